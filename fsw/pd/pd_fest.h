/*
 * pd_fest.h — the on-board elastic-frequency estimator of spec 40 §4.3-§4.4 (option A) in fixed
 * point: a port of the double design sim/pd/pd_fest_ref (which documents every step and every
 * tuning decision; this file repeats only what the port changes). One instance per channel, owned
 * by the channel's pd_state_t; O(1) per sample, every loop bounded by a compile-time constant, no
 * floating point, int32 storage and int64 accumulation (R1).
 *
 * Formats (the reference's state table in pd_fest_ref.hpp proposes them; the port's choices):
 *   xh, w, phi    int64, LSB 2^-40 rad (rad/s): x +-0.5, beta +-pi/4, rates +-1 use <= 2^41
 *   e, AA, blocks int64 2^-40 rad; |e| <= 1e-3 rad (= 1.1e9 LSB) or the sample is a RESID fault
 *   ratios to sigma_y (en, r_e, sigma_hat, sigma_ref)   q16;  their squares (ms_e, ms_n, ms_d3) q32
 *   normalised notch signals (u, s, eps, r, psi)        int64 q24;  their squares (ms_s/in/out) q32
 *   theta q30 (clamped +-0.3);  P_th q27 (trace <= 10);  a q29 (-2, 2);  P, kappa q30
 *   f  uq32 Hz (f_obs, f_hat, f_pub: LSB 2.3e-10 Hz);  cinv = 1 / c(f, k2)  uq30
 * Wide products and quotients go through fx_mul64_shr / fx_div64_shl (fsw/fx): no other code forms
 * a product that could exceed 64 bits.
 * Matrices of the table: int32 mantissa m and a shift sh per coefficient row; a product is
 * round(x m / 2^sh) of the int64 x, so the tool folds both Q formats into sh.
 *
 * One notch section for pitch and roll; two in cascade for yaw (n_sec = 2), with the reference's
 * line logic: section 2 searching below section 1 and co-moving with it while it anneals, the
 * second and third passes of section 1's notch ahead of section 2, the pair window 1.5 <= hi / lo
 * <= 2 tested without a division, and the single-line proofs (low line, continuation of a verified
 * pair, decay over PD_FEST_ENV periods). The estimator requires Ty = 0.25 s (Td = 1 s: f in uq32 is
 * the BAM of the notch angle per Td) and the compile-time tuning constants of pd_fest.c, which are
 * the reference's FestParams defaults; yaw's mode-2 / mode-1 ratio (1.74) is one of them
 * (tests/pd/test_pd_fest_golden_host checks the port against the reference, G3, on all channels).
 */
#ifndef FSW_PD_FEST_H
#define FSW_PD_FEST_H

#include <stdint.h>
#include <stdbool.h>
#include "fx.h"

#define PD_FEST_NX      4u      /* rigid predictor states: x, beta, x', beta' */
#define PD_FEST_NR      2u      /* rigid-response regressors: relative Ix, relative H */
#define PD_FEST_NSEC    2u      /* notch sections: 1 (pitch, roll), 2 (yaw) */
#define PD_FEST_ENV     16u     /* yaw: residual envelope history (periods) for the decay proof */
#define PD_FEST_DECIM   4u      /* samples per Td */
#define PD_FEST_CF      13u     /* c grid: f = 0.005 .. 0.125 Hz, step 0.01 */
#define PD_FEST_CK      11u     /* c grid: k2 = 0 .. 1000 s, step 100 */

/* Estimator states (health bits 12..13, pd_ids.h PD_H_FEST): 0 is "no estimator" there, so the
   health field carries state + 1. */
#define PD_FEST_ACQUIRE 0u
#define PD_FEST_TRACK   1u
#define PD_FEST_HOLD    2u
#define PD_FEST_FAULT   3u

/* Fault reasons (bit mask) */
#define PD_FEST_F_CLAMP   1u    /* f_hat on a clamp > 60 s with the gate open */
#define PD_FEST_F_JUMP    2u    /* confident jump > 20 % in a period */
#define PD_FEST_F_ATTEN   4u    /* notch output power >= input power for 8 periods */
#define PD_FEST_F_RESID   8u    /* |e| > 1e-3 rad */
#define PD_FEST_F_NUMERIC 16u   /* an fx status bit in the estimator's arithmetic */

/* One channel's estimator constants (the pd table's fest block; tools/pd makes them from the
   channel's nominal model with sim/pd make_fest_params, quantised by sim/pd/pd_fest_quant). */
typedef struct {
    uint8_t  n_sec;             /* notch sections: 1, or 2 (yaw) */
    uint8_t  n_reg;             /* rigid-response regressors, 0 or 2 */
    uint32_t inv_m_q30;         /* 1 / m_ch: the channel's lowest mode over f_min */
    uint32_t alpha_hp_q30;      /* high-pass corner over the line frequency */
    uint32_t f_hp_min_q32;      /* the high-pass line frequency floor [Hz] */
    uint32_t beta_kappa_q30;    /* kappa target 1 - beta w Td ... */
    uint32_t kappa_hi_q30;      /* ... within [0.93, kappa_hi] */
    uint32_t sigma_y_q40;       /* attitude noise prior [rad]; the floor of sigma_ref is half of it */
    int32_t  ad_m[PD_FEST_NX][PD_FEST_NX];  /* Ad_r: xh (2^-40) -> 2^-40 */
    uint8_t  ad_sh[PD_FEST_NX];
    int32_t  bd_m[PD_FEST_NX];  /* Bd_r: M (q28 N m) -> 2^-40 */
    uint8_t  bd_sh[PD_FEST_NX];
    int32_t  l_m[PD_FEST_NX];   /* L_r: e, w (2^-40) -> 2^-40 */
    uint8_t  l_sh[PD_FEST_NX];
    int32_t  dad_m[PD_FEST_NR][PD_FEST_NX][PD_FEST_NX];  /* dA_r: xh -> w (2^-40) */
    uint8_t  dad_sh[PD_FEST_NR][PD_FEST_NX];
    int32_t  dbd_m[PD_FEST_NR][PD_FEST_NX];              /* dB_r: M -> w */
    uint8_t  dbd_sh[PD_FEST_NR][PD_FEST_NX];
    int32_t  aa_b_q29[3];       /* anti-alias low-pass (0.35 Hz, full rate) */
    int32_t  aa_a_q29[2];
    uint32_t cinv_q30[PD_FEST_CF][PD_FEST_CK];  /* 1 / c(f, k2) of the lowest mode, closed loop */
} pd_fest_params_t;

/* one notch section's state (per Td) */
typedef struct {
    int64_t  s1_q24;
    int64_t  s2_q24;
    int64_t  ms_s_q32;
    int64_t  ms_in_q32;
    int64_t  ms_out_q32;
    int32_t  a_q29;
    uint32_t p_q30;
    uint32_t kap_q30;
    uint32_t f_obs_q32;         /* its line [Hz] at the last Td */
} pd_fest_sec_t;

typedef struct {
    /* outputs of the last period end (what the law and the telemetry read) */
    uint32_t f_hat_q32;         /* published estimate [Hz] */
    uint32_t p_a_q30;           /* RLS P of the notch */
    uint32_t att_q16;           /* notch rms(out) / rms(in) */
    uint32_t r_e_q16;           /* running RMS of the decimated residual / sigma_y */
    uint32_t sig_hat_q16;       /* noise estimate / sigma_y */
    uint32_t kappa_q30;
    uint32_t fault;             /* PD_FEST_F_* of the last FAULT */
    uint32_t resets;            /* FAULTs since init (saturating) */
    fx_status_t st_sticky;      /* fx status bits seen since init */
    /* predictor and regressors (per sample) */
    int64_t  xh[PD_FEST_NX];
    int64_t  w[PD_FEST_NR][PD_FEST_NX];
    int64_t  phi_sum[PD_FEST_NR];
    int64_t  phi_d[PD_FEST_NR];
    int32_t  theta_q30[PD_FEST_NR];
    int32_t  pth_q27[PD_FEST_NR][PD_FEST_NR];
    int64_t  r1_q24[PD_FEST_NR];
    int64_t  r2_q24[PD_FEST_NR];
    int64_t  aa_x[2];
    int64_t  aa_y[2];
    int64_t  e_prev[3];
    uint32_t n_run;
    int64_t  ms_d3_q32;         /* sigma_hat^2 / sigma_y^2 */
    int64_t  blk_sum;
    uint32_t blk_n;
    uint32_t blk_valid;
    int64_t  e_d;
    uint32_t k_in_period;       /* the law's period phase (never reset) */
    /* per Td */
    int64_t  hp_x1;
    int64_t  hp_h1;
    int64_t  hp_h2;
    int64_t  ms_e_q32;
    int64_t  ms_n_q32;
    uint32_t sig_ref_q16;
    pd_fest_sec_t sec[PD_FEST_NSEC];
    int64_t  d1_q24;            /* yaw: second pass of section 1's notch */
    int64_t  d2_q24;
    int64_t  q1_q24;            /* yaw: third pass (kappa 0.97) */
    int64_t  q2_q24;
    /* yaw line logic (per period) */
    uint32_t f_lo_ver_q32;      /* the lower line of the last verified pair (0: none) */
    uint32_t env_q16[PD_FEST_ENV];  /* r_e / sigma_y at the last PD_FEST_ENV period ends */
    uint32_t env_i;
    uint32_t n_single;          /* periods in single-line mode (saturating) */
    uint32_t n_excite;          /* periods since the gate opened (saturating) */
    /* frequency and period logic */
    uint32_t f_raw_q32;         /* f_hat before publication (the reference's f_hat_) */
    uint32_t f_prev_q32;
    uint32_t f_rep_q32;         /* observed frequency of the reported line */
    uint32_t n_stable;
    uint32_t n_clamp;
    uint32_t n_att_bad;
    fx_status_t st_period;      /* fx status bits since the last period end (NUMERIC) */
    uint32_t r_hold_q16;        /* r_e / sigma_y at HOLD entry */
    uint32_t resid_run;         /* RESID FAULTs since the last TRACK (2: the predictor restarts) */
    /* flags and the state (last: no padding between the wide fields) */
    uint8_t  state;             /* PD_FEST_* */
    bool     confident;         /* TRACK */
    bool     hold_valid;        /* HOLD entered from TRACK */
    bool     gate;
    bool     period_end;        /* this sample closed a control period */
    bool     pred_init;
    bool     a_set;             /* a_q29 started from the prior since the last reset */
    bool     f_moved;
    bool     e_fault;
    bool     held_conf;
    bool     gate_rose;
    bool     two;               /* yaw: two lines seen (last Td) */
    bool     slow_ok;           /* yaw: the single line passed the decay proof (last period) */
} pd_fest_t;

/* FSW_OK-style check of the constants the loader's limits cannot see: 0 when usable, else a
   non-zero code (the table check reports it as PD_WHY_FEST). */
uint32_t pd_fest_check(const pd_fest_params_t *p);
void     pd_fest_init(pd_fest_t *s);
/* One sample: y (q30 rad) and its validity, the torque applied over the coming sample (q28 N m),
   the k2 in use (uq22 s). Sets s->period_end at the last sample of a control period of n_y. */
void     pd_fest_step(pd_fest_t *s, const pd_fest_params_t *p, uint32_t n_y, bool y_valid, int32_t y_q30,
                      int32_t m_q28, uint32_t k2_q22);
/* 1 / c(f, k2) in uq30, bilinear on the grid, clamped at its edges. */
uint32_t pd_fest_cinv(const pd_fest_params_t *p, uint32_t f_q32, uint32_t k2_q22);

#endif /* FSW_PD_FEST_H */
