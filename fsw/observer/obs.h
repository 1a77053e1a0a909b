/*
 * obs.h — adaptive observer step for the solar-sail platform (spec 10-observer §4).
 *
 * Each period: read two rate-gyro counts, estimate x = [w_y, w_z, mu_y, mudot_y, mu_z, mudot_z]
 * and kappa = K/K_ref (K_ref = 0.01 s^-2) with an extended Kalman filter on the exact-ZOH model
 * Phi(kappa) = Phi0 + (kappa - kappa0) Phi_k, Gamma(kappa) likewise, and command the two gimbal
 * rates u = -D x_hat, limited as a vector. Fixed point throughout; no state outside the
 * caller-owned structs.
 *
 * Formats: x_hat q29 (rad/s and rad), kappa q28, u q29 rad/s, covariance of the scaled state
 * z_s = S^-1 [x; kappa] in q30, S = diag(2^OBS_LS_i) with power-of-two scales (table).
 */
#ifndef FSW_OBS_H
#define FSW_OBS_H

#include <stdint.h>
#include <stdbool.h>
#include "fx.h"
#include "obs_ids.h"

#define OBS_NX   6u           /* plant state */
#define OBS_NZ   7u           /* EKF state: x and kappa */
#define OBS_NU   2u           /* gimbal rates */
#define OBS_NY   2u           /* rate gyros */

#define OBS_X_Q      29u      /* x_hat: rad/s, rad */
#define OBS_KAPPA_Q  28u      /* kappa = K / 0.01 s^-2 */
#define OBS_U_Q      29u      /* gimbal-rate command, rad/s */
#define OBS_P_Q      30u      /* scaled covariance */
#define OBS_F_Q      28u      /* scaled transition matrix, gains */
#define OBS_D2_Q     16u      /* normalised innovation squared (telemetry) */

/* Estimator selection (table). */
#define OBS_EST_EKF      0u
#define OBS_EST_CONST_W  2u   /* the paper's constant-gain structure (paper-mode S0-3 only) */

/* Health bits (OBS_H_*, spec 10-observer §7) and params_check reasons (OBS_WHY_*): obs_ids.h,
   generated from obs_iface.py. */

typedef struct {
    uint32_t period_us;             /* control period; the executive's period */
    uint8_t  estimator;             /* OBS_EST_* */
    int8_t   sigma;                 /* +1 M-phys, -1 M-paper (informational, logged) */
    /* sensor and actuator */
    uint8_t  gyro_cnt_shift;        /* counts -> q29: x << shift (2^-20 rad/s counts: 9) */
    uint8_t  act_cnt_shift;         /* q29 -> counts: rnd(x >> shift) (2^-20 rad/s counts: 9) */
    int32_t  gyro_max_cnt;          /* |count| >= this is invalid (full scale) */
    int32_t  act_max_cnt;           /* actuator count range, +-act_max_cnt */
    int32_t  bdot_max_q29;          /* vector limit on |u|inf, rad/s */
    int32_t  bdot_hw_q29;           /* hardware limit, rad/s (params_check only) */
    /* model and gains, row-major, each with its own Q (>= 16 fraction bits) */
    int32_t  phi0[OBS_NX * OBS_NX];
    int32_t  phik[OBS_NX * OBS_NX];   /* K_ref * dPhi/dk^2 */
    int32_t  gam0[OBS_NX * OBS_NU];
    int32_t  gamk[OBS_NX * OBS_NU];
    int32_t  d[OBS_NU * OBS_NX];      /* u = -D x */
    int32_t  w[OBS_NZ * OBS_NY];      /* CONST_W gains (7x2), unused by the EKF */
    uint8_t  q_phi0;
    uint8_t  q_phik;
    uint8_t  q_gam0;
    uint8_t  q_gamk;
    uint8_t  q_d;
    uint8_t  q_w;
    /* stiffness */
    int32_t  kappa0_q28;
    int32_t  kappa_init_q28;
    int32_t  kappa_lo_q28;
    int32_t  kappa_hi_q28;
    /* EKF, in the scaled coordinates z_s = S^-1 z: S_i = 2^ls[i] */
    int8_t   ls[OBS_NZ];              /* log2 of the scales, e.g. -13 -13 -10 -10 -10 -10 -1 */
    int32_t  p0_q30[OBS_NZ];          /* initial covariance (diagonal) */
    int32_t  qd_q30[OBS_NZ];          /* process noise (diagonal), >= 4 LSB */
    int32_t  r_q30;                   /* gyro noise variance / S_w^2 */
    int32_t  p_floor_q30;
    int32_t  p_ceil_q30;
    /* fault handling */
    uint16_t n_lost;
    uint16_t n_good;
    uint16_t n_sat;
    uint16_t n_gap_max;
    int32_t  d2_max_q16;              /* gamma^2 of the innovation gate (d^2 = e_s^2 / S, per channel) */
    uint8_t  d2_reject;               /* 1: skip an update whose d^2 > d2_max (the gate); 0: monitor */
    uint16_t n_rej_safe;              /* consecutive rejections of a channel that declare it invalid */
    uint16_t rej_leak_inc;            /* leaky rejection level: + this per step with a rejection, -1 without */
    uint16_t rej_freeze_on;           /* kappa adaptation frozen from this level until it leaks back to 0 */
    uint32_t revision;                /* table revision, echoed in telemetry */
} obs_params_t;

typedef struct {
    uint32_t seq;
    int32_t  gyro_cnt[OBS_NY];
    uint8_t  stale;                   /* bit0 y, bit1 z: executive's stale marks */
    uint8_t  sat;                     /* bit0 y, bit1 z: plant's full-scale status */
} obs_in_t;

typedef struct {
    int32_t  x_q29[OBS_NX];
    int32_t  kappa_q28;
    int32_t  u_q29[OBS_NU];
    int32_t  e_q29[OBS_NY];           /* innovations of this step (0 when skipped) */
    int32_t  d2_q16[OBS_NY];
    int32_t  pkk_q30;                 /* scaled kappa variance */
    uint32_t health_sticky;
    uint32_t n_skip;
    uint32_t n_gap;
    uint32_t n_lost;
    uint32_t n_reinit;
    uint32_t n_clamp_lo;
    uint32_t n_clamp_hi;
    uint32_t n_limited;
    uint32_t n_innov;
    uint32_t n_cov_clip;
    uint32_t revision;
} obs_tlm_t;

typedef struct {
    int32_t   bdot_cmd_cnt[OBS_NU];   /* gimbal-rate commands in actuator counts, limited */
    uint32_t  health;                 /* bits 0-7: fx status of this step; 8-19: OBS_H_* */
    obs_tlm_t tlm;
} obs_out_t;

typedef struct {
    /* estimate */
    int32_t  x_q29[OBS_NX];
    int32_t  kappa_q28;
    int32_t  p_q30[OBS_NZ * OBS_NZ];  /* symmetric, kept exactly symmetric */
    int32_t  u_prev_q29[OBS_NU];      /* command applied over the last period */
    int32_t  qres_q29[OBS_NU];        /* command quantisation residual carried to the next step */
    /* sequencing and fault state */
    uint32_t last_seq;
    bool     have_seq;
    bool     initialized;
    bool     lost;
    uint32_t invalid_run;             /* steps without any valid axis (saturating) */
    uint32_t good_run;                /* valid steps since MEAS_LOST (saturating) */
    uint32_t limited_run;             /* consecutive limited commands (saturating) */
    uint32_t rej_run[OBS_NY];         /* consecutive gate rejections per channel (saturating) */
    uint32_t rej_level;               /* leaky rejection level, <= rej_freeze_on + rej_leak_inc */
    bool     kappa_frozen;            /* kappa adaptation frozen by the rejection level */
    bool     rej_safe;                /* latched: a channel persistently rejected; zero command */
    /* scratch (caller-owned so no function needs a large stack frame) */
    int32_t  f_q28[OBS_NX * OBS_NX];  /* F_s's x block (its kappa row is e_kappa^T, never stored) */
    int64_t  fk_q28[OBS_NX];          /* F_s's kappa column (regressor), q28 in int64: up to |64| */
    int32_t  t_q30[OBS_NZ * OBS_NZ];
    int32_t  phi_q[OBS_NX * OBS_NX];  /* Phi(kappa) in q_phi0 */
    int32_t  gam_q[OBS_NX * OBS_NU];  /* Gamma(kappa) in q_gam0 */
    obs_tlm_t tlm;                    /* counters and sticky health live here */
} obs_state_t;

fsw_rc_t obs_params_check(const obs_params_t *p, uint32_t *why);
/* Bit c set: channel c has failed the innovation gate n_rej_safe times in a row. */
uint32_t obs_rej_persist_mask(const obs_state_t *s, const obs_params_t *p);
fsw_rc_t obs_init(obs_state_t *s, const obs_params_t *p, obs_out_t *out);
void     obs_step(obs_state_t *s, const obs_params_t *p, const obs_in_t *in, obs_out_t *out);

#endif /* FSW_OBS_H */
