/*
 * rsp.h — respin: the switching law of spec 30 (seed 002) that brings a tumbling satellite into a
 * steady spin about its major body axis y with the weak internal moments of three reaction wheels
 * or of a four-gyrodine cluster (table field act_kind).
 * Regions LIN / MID / FAR over |xi| = |g x f| with thresholds eps1, eps2 and hysteresis h_eps, the
 * target-latching NEAREST law (default) and the printed law PRINTED (kept to demonstrate its
 * defect, spec 30 §3.5), g0 averaged once, the low-momentum rule and the small-|G| guard (§3.6), the
 * per-axis wheel distribution with the momentum-bound clamp or the gyrodine steering (§4, rsp_cmg.h),
 * the optional G filter (§3.6), energy bookkeeping and the health checks of §8.
 *
 * Frames: B = principal body axes with the wheels locked (J diagonal, y the major axis).
 * Sign chain (spec 30 §9): M is the internal moment on the body, M = -dH/dt; the wheel motor
 * torque command is -M.
 *
 * Formats (spec 30 §5; counts are the channel units of rsp_iface.py):
 *   gyro        omega_BN_B_cnt[3]  2^-22 rad/s;  omega_BN_B_q28 = cnt << 6   (Q3.28)
 *   wheel speed whl_speed_cnt[3]  2^-10 rad/s;  h_whl_B_q20 = round(cnt * iw_q30 / 2^20)
 *   momentum    G, H, Jw, g0       int32, LSB 2^-20 N m s (suffix _q20)
 *   inertia     J_i                int32, LSB 2^-19 kg m^2 (j_q19)
 *   G filter (optional)            G_hat propagated by theta = omega Ts (Q1.30), blended with G,
 *                                  rescaled to g0 by one Newton step; g = G_hat / g0 when on
 *   g = G / g0                     through fx_recip (the reciprocal of g0 made once when g0
 *                                  freezes; each quotient correctly rounded, README "formats")
 *   g, xi, e_xi, C_phi, |xi|       Q1.30
 *   inner term xi - k (H - H_f)    Q5.26 (D = I)
 *   moments M                      int32, LSB 2^-24 N m (suffix _q24)
 *   wheel torque command           int16 counts, 2^-17 N m (= -M, rounded once)
 *   gimbal angle                   encoder counts of 2 pi / 2^20 rad; binary angle = cnt << 12
 *   rotor speed                    counts of 2^-8 rad/s (health only)
 *   gimbal rate command            int16 counts, 2^-16 rad/s (rsp_cmg_steer)
 *   energies T, W, r_E             int64, LSB 2^-32 J (suffix _q32)
 */
#ifndef FSW_RSP_H
#define FSW_RSP_H

#include <stdint.h>
#include <stdbool.h>
#include "fx.h"
#include "fx_rc.h"
#include "rsp_ids.h"
#include "rsp_cmg.h"

#define RSP_N_AX        3u
#define RSP_G0_TICKS_MAX 1024u     /* n_g0 upper bound (the sum of |G| stays in int64) */

typedef struct {
    uint32_t period_us;        /* Ts; 100 000 (0.1 s) or 500 000 (0.5 s) */
    uint32_t mode;             /* RSP_MODE_NEAREST (default) or RSP_MODE_PRINTED */
    uint32_t act_kind;         /* RSP_ACT_WHEELS or RSP_ACT_GYRODINES */
    int32_t  j_q19[3];         /* principal inertia J_x, J_y, J_z, LSB 2^-19 kg m^2; y the largest */
    int32_t  iw_q30;           /* wheel rotor inertia I_w, Q30 kg m^2 */
    int32_t  eps1_q30;         /* eps1 (0.1) */
    int32_t  eps2_q30;         /* eps2 (0.5) */
    int32_t  heps_q30;         /* hysteresis h_eps (0.01) */
    int32_t  m_q24;            /* law gain m = M_max / eps1 (1.5 N m), LSB 2^-24 N m */
    int32_t  k_q30;            /* k (0.07 1/(N m s)), Q30 */
    int32_t  mstar_q24;        /* far-law moment M* (0.15 N m wheels) */
    int32_t  mmax_q24;         /* wheel motor torque limit M_max (0.15 N m) */
    int32_t  hlim_q20;         /* momentum-bound clamp h_lim (4.98 N m s) */
    int32_t  inv_ts_q16;       /* 1/Ts in Q16.16 (10 s^-1) */
    int32_t  gguard_q20;       /* small-|G| guard g_guard (17.3 N m s = 2 H_cap) */
    int32_t  gmin_q20;         /* low-momentum limit g_min (2 N m s) */
    uint32_t n_g0;             /* valid ticks averaged for g0 (50), 1..RSP_G0_TICKS_MAX */
    int32_t  gyro_max_cnt;     /* |count| >= gyro_max_cnt is full scale (2^22) */
    int32_t  whl_max_cnt;      /* |count| >  whl_max_cnt is out of range (600 rad/s = 614 400) */
    uint32_t n_fault;          /* invalid ticks in a row before a cause latches (50) */
    uint32_t n_stale;          /* identical raw words in a row that count as stale (20) */
    uint32_t n_whl_est;        /* ticks a missing wheel speed may be propagated (10) */
    int32_t  outlier_q20;      /* absolute floor of the |G| outlier gate (0.5 N m s) */
    uint32_t outlier_rel_q16;  /* relative gate on ||G| - g0| (0.05 g0), Q16 */
    int32_t  drift_q30;        /* |rho_G| low-passed beyond this raises G_DRIFT (0.02) */
    uint32_t drift_sh;         /* rho_G low-pass: alpha = 2^-drift_sh per tick (100 s at 0.1 s: 10) */
    int64_t  ealarm_q32;       /* r_E above this raises ENERGY_ALARM (0.5 J) */
    int32_t  done_xi_q30;      /* done: |xi| < done_xi (0.01) ... */
    int32_t  done_h_q20;       /* ... and |H - H_f| < done_h (0.05 N m s) per axis ... */
    uint32_t done_ticks;       /* ... for done_ticks ticks (300 s) */
    int32_t  gfilt_alpha_q30;  /* G filter blend alpha per tick, Q30 (0.05); 0: filter off (spec 30 §3.6) */
    int32_t  hg_q20;           /* gyrodine rotor momentum h_g (7.5 N m s) */
    int32_t  lambda_q28;       /* singularity-robust damping lambda0, Q3.28 (0.05) */
    int32_t  umax_cnt;         /* gimbal-rate limit in command counts of 2^-16 rad/s (11 437 = 0.1745 rad/s) */
    int32_t  ms_sing_q28;      /* SINGULAR below this singularity measure m_s, Q3.28 (0.05) */
    int32_t  rotor_nom_cnt;    /* nominal rotor speed in counts of 2^-8 rad/s (600 rad/s) */
    uint32_t rotor_tol_q16;    /* ROTOR_FAULT beyond |Omega_r / Omega_nom - 1| (0.01), Q16 */
    uint32_t revision;         /* table revision (the image header's) */
} rsp_params_t;

/* The telemetry block (its wire layout: rsp_iface.py -> rsp_tlm.c). */
typedef struct {
    uint8_t  phase;            /* RSP_PH_* */
    uint8_t  region;           /* RSP_RG_* */
    uint8_t  latched;          /* 1 while a_f is latched (region left FAR) */
    uint8_t  mode;             /* RSP_MODE_* in force (telemetry shows the mode, spec 30 §3.5) */
    int32_t  a_f;              /* +1 / -1: f = a_f e_y */
    uint32_t flags;            /* RSP_H_* of the last step */
    int32_t  xi_abs_q30;       /* |xi| */
    int32_t  cphi_q30;         /* C_phi = a_f g_y */
    int32_t  g_q30[3];         /* g = G / g0 */
    int32_t  g0_q20;           /* frozen g0 (0 until frozen) */
    int32_t  rho_q30;          /* rho_G = |G| / g0 - 1 */
    int32_t  rho_lp_q30;       /* rho_G low-passed */
    int32_t  mcmd_q24[3];      /* law moment on the body, before distribution */
    int32_t  mdel_q24[3];      /* moment after distribution (what the wheels are told) */
    int32_t  h_q20[3];         /* wheel momentum used */
    int64_t  t_q32;            /* T = 1/2 (J omega) . omega */
    int64_t  w_q32;            /* work of the internal moment since t0 */
    int64_t  re_q32;           /* r_E = T - T0 - W */
    int64_t  t_far_d100_q32;   /* T change over the last complete 100 s window in FAR (spec 30 §8) */
    uint32_t done_run;         /* ticks in tolerance in a row */
    uint32_t n_switch;         /* region changes */
    uint32_t n_lin;            /* ticks per region (valid ticks after g0) */
    uint32_t n_mid;
    uint32_t n_far;
    uint32_t n_gyro_bad;       /* invalid ticks: gyro full scale / out of range */
    uint32_t n_gyro_stale;     /* invalid ticks: gyro raw word frozen n_stale ticks */
    uint32_t n_whl_bad;        /* invalid ticks: wheel speed missing beyond n_whl_est / out of range */
    uint32_t n_whl_est;        /* ticks with a propagated wheel momentum */
    uint32_t n_outlier;        /* invalid ticks: |G| outlier */
    uint32_t n_overflow;       /* ticks with an fx status (zero command) */
    uint32_t n_clip;           /* ticks with any axis clipped to M_max */
    uint32_t n_hbound;         /* ticks with any axis at the momentum bound */
    int32_t  cmg_rate_cnt[4];  /* gimbal rate command, 2^-16 rad/s (0 with wheels) */
    int32_t  cmg_ms_q28;       /* m_s of the last steered tick, Q3.28 */
    int32_t  cmg_s_q16;        /* rate scale s of the last steered tick, Q16.16 */
    uint32_t n_singular;       /* ticks with m_s < ms_sing */
    uint32_t n_rate_limited;   /* ticks with the gimbal rates scaled */
    uint32_t health_sticky;    /* OR of the health words since init */
    uint32_t revision;         /* table revision in use */
} rsp_tlm_t;

typedef struct {
    uint32_t phase;            /* RSP_PH_G0 until g0 froze, RSP_PH_LOW (low momentum) or RSP_PH_RUN */
    uint32_t region;           /* RSP_RG_* */
    int32_t  a_f;              /* +1 / -1 */
    bool     latched;
    uint32_t n_g0_acc;         /* valid ticks averaged so far */
    int64_t  g0_sum_q20;       /* sum of |G_k| over them */
    fx_recip_t r0;             /* reciprocal of g0 (fx_recip_init once g0 froze) */
    bool     have_prev;        /* omega_prev / h_prev hold the last valid tick */
    int32_t  omega_prev_q28[3];
    bool     have_ghat;        /* ghat holds the G filter's estimate (false: re-seed from G_k) */
    int32_t  ghat_q20[3];      /* G filter estimate (spec 30 §3.6), LSB 2^-20 N m s */
    int32_t  h_prev_q20[3];
    int32_t  h_last_q20[3];    /* last good wheel momentum per axis (propagation base) */
    int32_t  mdel_last_q24[3]; /* moment commanded last tick (wheel propagation, M_del check) */
    uint32_t whl_miss[3];      /* missing samples in a row per wheel */
    int32_t  gyro_last_cnt[3]; /* raw gyro words of the last tick (stale detection) */
    uint32_t gyro_same;        /* ticks in a row with all three raw words unchanged */
    int32_t  whl_last_cnt[3];
    uint32_t whl_same[3];      /* ticks in a row with the wheel word unchanged while |M_i| > 0.01 N m */
    uint32_t bad_run;          /* invalid ticks in a row (latches RSP_H_INPUT_FAULT at n_fault) */
    int64_t  t0_q32;           /* T at the first valid tick after g0 froze */
    bool     have_t0;
    bool     input_fault;      /* RSP_H_INPUT_FAULT latched (n_fault invalid ticks in a row) until rsp_init */
    uint32_t follow_run[3];    /* valid ticks in a row with wheel i off its command (spec 30 §8) */
    bool     wheel_fault;      /* RSP_H_WHEEL_FAULT latched until rsp_init: the command is zero */
    uint32_t rotor_run;        /* valid ticks in a row with a rotor speed off nominal */
    uint32_t hbound_lin_run;   /* valid LIN ticks in a row with HBOUND (HBOUND_STUCK at 600 s) */
    uint32_t far_win;          /* valid FAR ticks into the current 100 s window (0: none open) */
    int64_t  far_t0_q32;       /* T at the window's start */
    bool     rotor_fault;      /* RSP_H_ROTOR_FAULT latched until rsp_init: the command is zero */
    rsp_cmg_geom_t cmg_geom;   /* the cluster's H and Jacobian of this tick (kept off the stack) */
    rsp_cmg_out_t  cmg_out;    /* the steering's output of this tick */
    /* tlm also carries the law's running values that RESET_COUNTERS leaves alone and rsp.c reads
       back each tick: g0_q20, rho_lp_q30, w_q32, re_q32 (r_E carried over a gap), done_run. */
    rsp_tlm_t tlm;
} rsp_state_t;

typedef struct {
    int32_t  omega_BN_B_cnt[3];  /* gyro counts, 2^-22 rad/s */
    int32_t  whl_speed_cnt[3];   /* wheel speed counts, 2^-10 rad/s */
    int32_t  gimbal_enc_cnt[4];  /* gimbal angle counts, 2 pi / 2^20 rad, [0, 2^20) */
    int32_t  rotor_cnt[4];       /* rotor speed counts, 2^-8 rad/s */
    uint32_t valid;              /* bit 0..2 gyro x/y/z, 3..5 wheel x/y/z, 6..9 gimbal 1..4, 10..13 rotor 1..4 */
    uint32_t sat;                /* same bits: accepted with the plant's SAT (full scale) bit */
} rsp_in_t;

typedef struct {
    int16_t  whl_torque_cnt[3];  /* wheel motor torque command, 2^-17 N m (= -M_del); 0 with gyrodines */
    int16_t  gimbal_rate_cnt[4]; /* gimbal rate command, 2^-16 rad/s; 0 with wheels */
    uint32_t health;             /* bits 0..7 fx status of the step, 8.. RSP_H_* */
} rsp_out_t;

/* FSW_OK when p can fly; else FSW_ERR_ARG / FSW_ERR_RANGE and *why = RSP_WHY_* bits. */
fsw_rc_t rsp_params_check(const rsp_params_t *p, uint32_t *why);
void     rsp_init(rsp_state_t *s, const rsp_params_t *p);
void     rsp_step(rsp_state_t *s, const rsp_params_t *p, const rsp_in_t *in, rsp_out_t *out);

#endif /* FSW_RSP_H */
