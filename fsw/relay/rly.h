/*
 * rly.h — the relay-logic attitude law of a large flexible structure with its mode-envelope
 * estimator and k_t adaptation (spec 20-relay; seed 001). One axis, up to RLY_MAX_MODES undamped
 * elastic modes, a three-level actuator (0, +-m_eps, +-m_u) commanded as an enum.
 *
 * Per tick (rly_step, spec 20 §4.2 order of work):
 *   1. the envelope copy: per mode the anchored exact rotation of (q_i - c_i(l), p_i) by the 64-bit
 *      phase phi_i, a_i = sqrt(q_i^2 + p_i^2) (q40 rad), a = sum a_i;
 *   2. a added to the window sum; at a window boundary the window packet and the k_t adaptation
 *      (rly_adapt.c: PAPER or IMPROVED, spec §5);
 *   3. the law (§3.2 transition table, integer timers, Q0.16 k_t) on the q24 angle sample;
 *   4. re-anchoring of every mode when the commanded level changes (or on a re-initialisation);
 *   5. phi_i += dphi_i.
 * Formats: angle x q24 rad (2^-24 rad = one sensor count), envelope q40 rad (2^-40 rad), k_t
 * unsigned Q0.16, timers uint32 ticks, phases 64-bit BAM (one turn = 2^64).
 * No globals, no floating point, every loop bounded by RLY_MAX_MODES or a constant.
 */
#ifndef FSW_RLY_H
#define FSW_RLY_H

#include <stdint.h>
#include <stdbool.h>
#include "fx.h"
#include "fx_rc.h"
#include "rly_ids.h"

#define RLY_MAX_MODES      4u
#define RLY_X_FULL_Q24     ((int32_t)8388608)      /* 2^23 counts: the sensor's +-0.5 rad */
#define RLY_ANCHOR_MAX     ((int32_t)1073741824)   /* 2^30 LSB (9.8e-4 rad): anchors saturate here */
#define RLY_C_MAX          ((int32_t)536870912)    /* 2^29: |c_i| bound that keeps q_i in int32 */
#define RLY_WIN_MAX        2097152u                /* 2^21 ticks: window sums stay below 2^54 */
#define RLY_DPHI_HI_MAX    1073741823u             /* dphi < 2^62 (a quarter turn per tick) */
#define RLY_KT_HIST        7u                      /* k_t in force over the last 7 windows */
#define RLY_N_PROBE        3u                      /* IMPROVED probe points: k_t, k_t + dk, k_t - dk */

/* The parameter table (rly_table.c gives its wire layout and limits). */
typedef struct {
    uint32_t period_us;          /* tick period the constants were derived for */
    int32_t  x_max_q24;          /* |x| above it is refused (X_RANGE) */
    int32_t  eps_q24;            /* deadband half-width epsilon */
    int32_t  gamma_q24;          /* hysteresis gamma (epsilon - gamma in integers, spec §9) */
    uint32_t tau_max_ticks;      /* main-pulse timer saturation (TAU_SAT) */
    uint32_t win_ticks;          /* adaptation window N_w, ticks */
    uint32_t seed;               /* xorshift32 seed, nonzero */
    uint32_t env_alarm_q40;      /* ENV_HIGH when a window mean exceeds it */
    uint16_t lost_ticks;         /* invalid samples in a row before COAST */
    uint16_t tmin_windows;       /* T_min / T */
    uint16_t dk_q16;             /* Delta k_t */
    uint16_t kt0_q16;
    uint16_t kt_min_q16;
    uint16_t kt_max_q16;
    uint8_t  n_modes;            /* modes in the envelope copy, 0..RLY_MAX_MODES */
    uint8_t  adapt_mode;         /* RLY_ADAPT_OFF / PAPER / IMPROVED / IMPROVED_UP */
    uint8_t  delta0_num;         /* delta_0 = num / den */
    uint8_t  delta0_den;
    uint8_t  n_small;            /* small-change run that freezes (PAPER) or gates (IMPROVED) */
    uint8_t  n_ignore;           /* decrease run after which one increase is ignored */
    uint8_t  count_before_tmin;  /* 1: windows before T_min count toward the run */
    uint8_t  learn_after_tmin;   /* 1: the sign keeps being learned after T_min */
    uint8_t  gate_dk;            /* IMPROVED: stationarity gate |k_t,j - k_t,j-6| < gate_dk dk */
    uint8_t  probe_settle;       /* IMPROVED: windows each probe point settles before it is measured */
    uint8_t  cliff_num;          /* IMPROVED: cliff when den S_j > num S_j-1 */
    uint8_t  cliff_den;
    uint8_t  retreat_dk;         /* IMPROVED: retreat retreat_dk dk behind the previous k_t */
    uint8_t  unfreeze_num;       /* IMPROVED: un-freeze when den S_j > num S_ref ... */
    uint8_t  unfreeze_den;
    uint8_t  unfreeze_windows;   /* ... in this many consecutive windows */
    uint64_t dphi_bam64[RLY_MAX_MODES];   /* round(omega_i h / 2 pi 2^64) per tick */
    uint64_t f_q64[RLY_MAX_MODES];        /* omega_i / 2 pi in turns/s, Q0.64 (check of dphi) */
    int32_t  cu_q40[RLY_MAX_MODES];       /* C_u,i = k_i m_u / omega_i^2 */
    int32_t  ce_q40[RLY_MAX_MODES];       /* C_eps,i = k_i m_eps / omega_i^2 */
    int32_t  q0_q40[RLY_MAX_MODES];       /* initial mode state q_i = x~_i */
    int32_t  p0_q40[RLY_MAX_MODES];       /* p_i = x~_i' / omega_i */
    uint32_t revision;                    /* the image header's */
} rly_params_t;

/* The per-window packet (spec §8): the last window's decision, replayable from its fields. */
typedef struct {
    uint32_t j;                  /* window index (saturates at UINT32_MAX) */
    uint64_t s;                  /* S_j, 2^-40 rad tick */
    uint32_t abar_q40;           /* S_j / N_w, saturating */
    uint16_t kt_in_q16;          /* k_t in force during window j */
    uint16_t kt_next_q16;        /* k_t from the next brake on */
    uint8_t  phase;              /* RLY_PH_* after the decision */
    uint8_t  event;              /* RLY_EV_* */
    int32_t  sign;               /* sign of the step (-1, 0, +1) */
    uint8_t  n_small;
    uint32_t mag_q16;            /* magnitude drawn, [1, 65536] */
    uint32_t n_dec;
    uint64_t s_ref;              /* IMPROVED: reference sum after a freeze */
    uint32_t rng;                /* generator state after the decision */
    uint32_t n_invalid;          /* invalid samples in the window */
} rly_win_t;

/* The telemetry block (wire layout: rly_iface.py -> rly_tlm.c). */
typedef struct {
    uint8_t  st;                 /* RLY_ST_* */
    uint8_t  cmd;                /* RLY_LVL_* commanded this tick */
    int32_t  x_q24;              /* sample used (0 when invalid) */
    uint32_t a_q40;              /* envelope a, saturating */
    uint32_t ai_q40[RLY_MAX_MODES];
    uint16_t kt_q16;             /* k_t in force */
    uint32_t n;                  /* main-pulse timer */
    uint32_t nb;                 /* brake countdown */
    uint32_t tau1;               /* last main pulse, ticks */
    uint32_t tau2;               /* last brake, ticks */
    uint32_t n_r_main;           /* entries into R_MAIN */
    uint32_t n_l_main;           /* entries into L_MAIN */
    uint32_t n_x_invalid;        /* counters of the health bits (saturating) */
    uint32_t n_x_range;
    uint32_t n_lost;
    uint32_t n_tau_sat;
    uint32_t n_kt_clamped;
    uint32_t n_env_sat;
    uint32_t n_reinit;
    uint32_t n_env_high;
    uint32_t n_windows;          /* windows closed */
    uint32_t health_sticky;
    uint32_t seed;
    uint32_t revision;
    rly_win_t win;               /* last window packet */
    int64_t  win_s;              /* win.s and win.s_ref on the wire (< 2^54: exact as int64) */
    int64_t  win_s_ref;
} rly_tlm_t;

/* Adaptation state (rly_adapt.c). */
typedef struct {
    uint32_t rng;                /* xorshift32 state */
    uint64_t s_prev;             /* S_{j-1} (last valid window) */
    uint64_t s_ref;
    uint64_t s_probe[RLY_N_PROBE];
    uint16_t kt_probe[RLY_N_PROBE];
    uint16_t kt_hist[RLY_KT_HIST];   /* k_t in force over the last windows, [0] newest */
    uint32_t n_valid;            /* valid windows seen */
    uint32_t n_small;
    uint32_t n_dec;
    uint32_t frozen_age;         /* windows since a freeze */
    uint32_t unf_run;
    uint8_t  probe_i;            /* point being probed */
    uint8_t  probe_w;            /* windows spent on it */
    uint8_t  phase;              /* RLY_PH_* */
    int8_t   sign;               /* sign of the last step (+-1) */
    int8_t   d_last;             /* direction of the last applied step: k_t,j - k_t,j-1 or r */
} rly_adapt_t;

typedef struct {
    uint8_t  st;
    uint8_t  lvl;                /* level the anchors were taken at (RLY_LVL_*) */
    uint16_t kt_q16;
    uint32_t n;                  /* main-pulse timer */
    uint32_t nb;                 /* brake countdown */
    uint32_t lost_run;
    int32_t  u_q40[RLY_MAX_MODES];
    int32_t  v_q40[RLY_MAX_MODES];
    uint64_t phi[RLY_MAX_MODES];
    uint64_t s_win;              /* window sum */
    uint32_t w_n;                /* ticks into the window */
    uint32_t w_j;                /* window index */
    uint32_t w_invalid;          /* invalid samples in the window */
    bool     w_lost;             /* the sensor was lost during the window: skipped */
    rly_adapt_t ad;
    rly_tlm_t tlm;
} rly_state_t;

typedef struct {
    int32_t x_q24;
    bool    valid;               /* the executive accepted the sample */
    bool    reinit;              /* an observer re-initialises the copy (spec §4.4) */
    int32_t q_q40[RLY_MAX_MODES];
    int32_t p_q40[RLY_MAX_MODES];
} rly_in_t;

typedef struct {
    uint8_t  cmd;                /* RLY_LVL_* */
    uint32_t health;             /* bits 0..7 fx status of the step, 8.. RLY_H_* */
} rly_out_t;

/* FSW_OK when p can fly; else FSW_ERR_ARG / FSW_ERR_RANGE and *why = RLY_WHY_* bits. */
fsw_rc_t rly_params_check(const rly_params_t *p, uint32_t *why);
void     rly_init(rly_state_t *s, const rly_params_t *p);
void     rly_step(rly_state_t *s, const rly_params_t *p, const rly_in_t *in, rly_out_t *out);
/* A new table in flight (at a window boundary): the copy is re-anchored under the new constants
   at its current state, k_t is held inside the new limits; the law's state is kept. */
void     rly_retable(rly_state_t *s, const rly_params_t *p_old, const rly_params_t *p_new);

/* tau2 = clamp((kt_q16 tau1 + 2^15) >> 16, 1, tau1) in uint64 (spec §3.5); tau1 >= 1. */
uint32_t rly_tau2(uint16_t kt_q16, uint32_t tau1);
/* xorshift32 (x ^= x << 13; x ^= x >> 17; x ^= x << 5); the state must be nonzero. */
uint32_t rly_xorshift32(uint32_t *x);
/* round(f_q64 period_us / 10^6) exactly (the 96-bit product in 32-bit pieces); UINT64_MAX when
   the result reaches 2^62. */
uint64_t rly_dphi_of(uint64_t f_q64, uint32_t period_us);

#endif /* FSW_RLY_H */
