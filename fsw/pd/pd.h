/*
 * pd.h — one gyrodine PD channel of the HOLD mission (spec 40 §3, §4.2, §5, §8). One instance per
 * channel (yaw, roll, pitch), each over its own caller-owned params / state; the mission adapter
 * (pd_mission.c) runs the three behind its step divider. No globals, no floating point, every loop
 * bounded by a compile-time constant.
 *
 * Units on the interface (the channel units of pd_iface.py):
 *   y     attitude sample, counts of 2^-26 rad (range +-0.5 rad), carried internally in q30 rad
 *   beta  gimbal encoder, counts of 2^-24 rad (= q24 rad)
 *   M     gimbal torque, q28 N m inside, counts of 2^-20 N m on the actuator
 * Laws (PD_LAW_*, spec 40 §3):
 *   FAST       M_k = sat(-[G_P y_k + G_D (y_k - y_k-1)]),   G_P = k0 k1 (uq16), G_D = k0 k2 / Ty (uq16)
 *   FAST_AVGP  P on the mean of the last completed control period (n_y samples, held), D as FAST;
 *              before the first period completes the P term uses y_k
 *   LITERAL    at the last sample of control period j: M = -[G_P xbar_j + G_D (xbar_j - xbar_j-1) / n_y],
 *              held for the next n_y samples; M = 0 until the first period completes
 * The averaged modes keep the period sum exact (the mean is never rounded to q30: one q30 LSB of the
 * mean is 10 LSB of q28 at G_P = 40) and form each term by mul_shr (pd.c), one rounding per term.
 * Law arithmetic (§5): acc = G_P y + G_D dy in int64 at LSB 2^-46 (|acc| < 2^57 given |y| <= 0.5 rad,
 * |dy| <= 2^-6 rad, G_P < 2^10, G_D < 2^16, all guaranteed by pd_params_check); M = -rnd(acc / 2^18)
 * (half away from zero: mirrored inputs give exactly mirrored torques), clamped to +-M_max (TRQ_SAT, the
 * module's only designated saturation point).
 */
#ifndef FSW_PD_H
#define FSW_PD_H

#include <stdint.h>
#include <stdbool.h>
#include "fx.h"
#include "fx_rc.h"
#include "pd_ids.h"
#include "pd_fest.h"

#define PD_N_CH        3u           /* channels: yaw, roll, pitch (pd_iface.CHANNELS) */
#define PD_N_NODES     19u          /* schedule nodes: f = f0 + i df, 0.010 .. 0.100 Hz at 0.005 Hz */
#define PD_K_MAX_Q22   ((uint32_t)1023u << 22)   /* k0, k1, k2 < 1024 (uq22) */
#define PD_GP_MAX_Q16  ((uint32_t)1u << 26)      /* G_P < 2^10 N m/rad */
#define PD_GD_MAX_Q16  ((uint64_t)1u << 32)      /* G_D < 2^16 N m s/rad per sample */
#define PD_Y_MAX_Q30   ((int32_t)536870912)      /* 2^29: |y_lim| <= 0.5 rad, the accumulator headroom */
#define PD_DY_MAX_Q30  ((int32_t)16777216)       /* 2^24: |dy_max| <= 2^-6 rad, the accumulator headroom */
#define PD_M_MAX_Q28   ((int32_t)1073741824)     /* 2^30: M_max <= 4 N m, the actuator count fits 2^22 */
#define PD_ROLL_K2_CAP_Q22 ((uint32_t)150u << 22) /* spec 40 §3.4: roll's sampled gimbal-body mode */
#define PD_TY_EXACT_US 250000u                   /* Ty at which 1/Ty = 4 is folded in exactly; the estimator's Ty */
#define PD_GAP_DIFF_MAX 3u                        /* link gaps up to this many samples are differenced across */

/* What the three channels share (the common part of the mission table). */
typedef struct {
    uint32_t period_us;     /* executive step period */
    uint32_t inv_ty_q22;    /* 1 / Ty [1/s], Ty = n_div period_us; checked to 1 LSB */
    uint8_t  law;           /* PD_LAW_* */
    uint8_t  src;           /* PD_SRC_* at init (telecommand SET_SOURCE changes it in the state) */
    uint8_t  sched_law;     /* the law the schedule nodes were synthesised for */
    uint8_t  ch_mask;       /* bit k: channel k flies (else its torque is 0) */
    uint8_t  n_y;           /* samples per control period, a power of two in [2, 64] */
    uint8_t  n_bad_max;     /* a period with more invalid samples is rejected (4) */
    uint16_t n_div;         /* executive steps per sample (step divider), >= 1 */
    uint16_t n_hold;        /* missing samples for which the last torque is held (1), then 0 */
    uint16_t n_frozen;      /* bit-identical samples under torque before FROZEN (40) */
    int32_t  y_lim_q30;     /* |y| above it: refused (0.5 rad) */
    int32_t  dy_max_q30;    /* |dy| above it: refused (2^-6 rad) */
    int32_t  m_max_q28;     /* torque clamp (2 N m) */
    int32_t  m_frozen_q28;  /* the frozen test applies while |M| >= it (0.01 N m) */
    int32_t  beta_warn_q24; /* BETA_WARN above it (0.5 rad) */
    int32_t  beta_lim_q24;  /* BETA_LIM at or above it: outward torque zeroed (pi/4) */
    uint32_t f0_q32;        /* first schedule node [Hz], uq32 */
    uint32_t df_inv_q16;    /* 1 / node spacing [1/Hz], uq16 */
    uint32_t f_ground_q32;  /* GROUND: the commanded f_min at init [Hz] */
    uint32_t revision;      /* table revision (the image header's) */
} pd_common_t;

/* One channel's gains and schedule (uq22; k2 in s). */
typedef struct {
    uint32_t k0_q22;
    uint32_t k1_q22;
    uint32_t k2_nom_q22;    /* FIXED */
    uint32_t k2_cold_q22;   /* admissible at every node: the slow-first start and the fallback */
    uint32_t k2_min_q22;    /* every scheduled or commanded k2 is clamped to [k2_min, k2_max] */
    uint32_t k2_max_q22;    /* the channel's hard cap */
    uint32_t k2_node_q22[PD_N_NODES];   /* non-increasing in f */
    pd_fest_params_t fest;              /* the channel's estimator block (ADAPTIVE; pd_fest.h) */
} pd_gains_t;

/* The parameters of one channel instance. */
typedef struct {
    pd_common_t c;
    pd_gains_t  g;
} pd_params_t;

/* The mission table, decoded (pd_table.c). */
typedef struct {
    pd_common_t c;
    pd_gains_t  ch[PD_N_CH];
} pd_table_t;

/* One channel's telemetry (its wire layout: pd_iface.py -> pd_tlm.c). */
typedef struct {
    int32_t  y_q30;
    int32_t  dy_q30;
    int32_t  m_q28;
    uint32_t k2_q22;
    uint32_t health;
    uint32_t health_sticky;
    uint32_t miss_cnt;
    uint32_t stale_cnt;
    uint32_t range_rej;
    uint32_t rate_rej;
    uint32_t period_rej;
    uint32_t trq_sat_cnt;
    uint32_t beta_lim_cnt;
    uint32_t fest_f_q32;    /* estimator: published f_hat [Hz] (f0 while it has not run) */
    uint32_t fest_word;     /* estimator: state (bits 0..1), confident (2), gate (3), fault reasons (8..15) */
    uint32_t fest_p_a_q30;  /* estimator: RLS P of the notch */
    uint32_t fest_att_q16;  /* estimator: notch rms(out) / rms(in) */
    uint32_t fest_resets;   /* estimator: FAULTs since init */
} pd_ch_tlm_t;

typedef struct {
    pd_ch_tlm_t ch[PD_N_CH];
    uint32_t revision;
} pd_tlm_t;

typedef struct {
    /* gain in use and its source (telecommands change src, f_ground, k2_fixed) */
    uint8_t  src;
    uint32_t f_ground_q32;
    uint32_t k2_fixed_q22;
    uint32_t k2_q22;
    int64_t  g_p_q16;
    int64_t  g_d_q16;
    /* derivative and the missing-sample rule */
    int32_t  y_prev_q30;
    bool     have_prev;
    uint32_t miss_run;      /* consecutive samples without a usable y */
    int32_t  m_last_q28;    /* last commanded torque */
    /* frozen-sensor detector */
    int32_t  y_same_q30;
    uint32_t same_run;      /* samples bit-identical to y_same (1 = only itself) */
    /* control period */
    uint32_t nu;            /* samples of the current period so far */
    int64_t  sum_q30;       /* sum of its samples (invalid ones filled with the last good y) */
    uint32_t n_bad;
    int32_t  y_fill_q30;
    bool     have_fill;
    int64_t  xsum_q30;      /* sum of the last completed period (its mean is xsum / n_y, kept exact) */
    int64_t  xsum_prev_q30; /* and of the one before */
    bool     have_xbar;
    uint32_t zero_run;      /* averaged modes: samples left at M = 0 after a bad period */
    int32_t  m_held_q28;    /* LITERAL: the torque held over the period */
    /* ADAPTIVE: the estimator and the re-tune rule's memory */
    pd_fest_t fest;
    uint32_t k2_adapt_q22;   /* the k2 the re-tune rule chose (k2_cold at entry and after a FAULT) */
    uint32_t f_pub_prev_q32; /* the estimator's published f_hat at the previous period end */
    uint32_t n_inv_fest;     /* samples of the current control period the estimator saw invalid */
    pd_ch_tlm_t tlm;
} pd_state_t;

typedef struct {
    int32_t y_cnt;          /* attitude, 2^-26 rad */
    bool    y_valid;        /* accepted by the executive this step, seq advanced */
    bool    y_sat;          /* accepted with the sensor's saturation bit: out of range */
    int32_t beta_cnt;       /* gimbal encoder, 2^-24 rad */
    bool    beta_valid;
} pd_in_t;

typedef struct {
    int32_t  m_q28;
    int32_t  m_cnt;         /* the actuator count, 2^-20 N m */
    uint32_t health;        /* bits 0..7 fx status of the step, 8.. PD_H_* */
} pd_out_t;

/* FSW_OK when p can fly; else FSW_ERR_ARG / FSW_ERR_RANGE and *why = PD_WHY_* bits. The roll cap
   is the adapter's (it knows which channel is roll). */
fsw_rc_t pd_params_check(const pd_params_t *p, uint32_t *why);
void     pd_init(pd_state_t *s, const pd_params_t *p);
void     pd_step(pd_state_t *s, const pd_params_t *p, const pd_in_t *in, pd_out_t *out);

/* The scheduled k2 at f (uq32 Hz): linear in f between the nodes, clamped at the end nodes,
   then to [k2_min, k2_max] (spec 40 §5 item 6). */
uint32_t pd_sched_k2(const pd_params_t *p, uint32_t f_q32);

/* n samples never reached the module (the frame seq jumped by n + 1): each is counted missing and
   invalid in its control period; the derivative rule is that of missing samples (pd.c: one missing
   sample is differenced across, a longer gap restarts it). The adapter calls it before the step of
   the frame after the gap. */
void     pd_note_gap(pd_state_t *s, const pd_params_t *p, uint32_t n);

/* Telecommand effects, from the next sample on. */
/* FIXED; GROUND when the table's schedule was made for its law; ADAPTIVE when moreover Ty = 0.25 s and
   the channel's estimator block passes pd_fest_check (not yaw: pd_fest.h). Entering ADAPTIVE starts the
   estimator cold (k2_cold, the prior f0). false (nothing changes) otherwise. */
bool     pd_set_source(pd_state_t *s, const pd_params_t *p, uint8_t src);
void     pd_set_f_ground(pd_state_t *s, uint32_t f_q32);
void     pd_set_k2_fixed(pd_state_t *s, const pd_params_t *p, uint32_t k2_q22);   /* clamped */
void     pd_reset_counters(pd_state_t *s);

#endif /* FSW_PD_H */
