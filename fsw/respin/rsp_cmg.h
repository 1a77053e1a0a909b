/*
 * rsp_cmg.h — respin: steering of the four-gyrodine cluster (2-SPE, two scissored pairs; spec 30
 * §2 "Gyrodine cluster", §4 "Gyrodines", §5 formats). Pure functions over caller-owned structs.
 *
 * Geometry (body frame = cluster frame; p = 1..4 is index 0..3, c_p = cos beta_p, s_p = sin beta_p):
 *   pair A, gimbal axes || x:  h1 = h_g ( c1 e_y + s1 e_z),  h2 = h_g (-c2 e_y + s2 e_z)
 *   pair B, gimbal axes || y:  h3 = h_g ( c3 e_x + s3 e_z),  h4 = h_g (-c4 e_x + s4 e_z)
 *   H = h_g (c3 - c4, c1 - c2, s1 + s2 + s3 + s4)
 *   Ahat = dH/dbeta / h_g, columns (0, -s1, c1), (0, s2, c2), (-s3, 0, c3), (s4, 0, c4)
 * Null configuration beta = (pi/4, pi/4, -pi/4, -pi/4): H = 0, Ahat Ahat^T = diag(1, 1, 2).
 *
 * Steering (singularity-robust inverse, spec 30 §4). Sign chain (§9): M_cmd is the internal moment on
 * the body, the cluster must follow Hdot_c = -M_cmd.
 *   y = (Ahat Ahat^T + lambda0 I)^-1 (Hdot_c / h_g)    LDL^T, pivots >= lambda0: no division near zero
 *   beta_dot = Ahat^T y                                  (rate_q28, before the rate scaling)
 *   s = max_p |beta_dot_p| / u_max; s > 1: beta_dot := beta_dot / s, RATE_LIMITED  (direction kept)
 *   rate_cnt = round(beta_dot 2^16), |rate_cnt| <= umax_cnt held in counts
 *   M_del = -h_g Ahat beta_dot_cmd, beta_dot_cmd = rate_cnt 2^-16 (what the cluster delivers)
 *   m_s = sqrt det(Ahat Ahat^T) = sqrt(sum of the four squared 3x3 minors of Ahat) (Cauchy-Binet),
 *   SINGULAR when m_s < ms_sing.
 *
 * Formats (spec 30 §5): Ahat, Ahat Ahat^T + lambda0 I and its LDL^T factors Q3.28 with exact int64
 * products; Hdot_c / h_g Q1.30; y Q5.26; beta_dot Q3.28; command int16 counts of 2^-16 rad/s;
 * momenta LSB 2^-20 N m s (_q20); moments LSB 2^-24 N m (_q24). Ranges and margins: rsp_cmg.c.
 *
 * fx status: every narrowing saturates through fx and ORs its bits into *st. A status raised inside
 * rsp_cmg_steer zeroes that call's command (rate_cnt and mdel_q24, spec 30 §5: "that step's command
 * is zero"); rate_q28, ms_q28 and s_q16 keep their (saturated) values for telemetry. A table the
 * steering cannot use (hg_q20 <= 0, lambda_q28 outside (0, 1.0], umax_cnt outside [1, 32767]) raises
 * FX_ST_ARG and zeroes every output.
 */
#ifndef FSW_RSP_CMG_H
#define FSW_RSP_CMG_H

#include <stdint.h>
#include <stdbool.h>
#include "fx.h"

#define RSP_CMG_N 4u
#define RSP_CMG_F_SINGULAR     0x1u
#define RSP_CMG_F_RATE_LIMITED 0x2u

typedef struct {
    int32_t hg_q20;       /* rotor momentum h_g, LSB 2^-20 N m s (7.5 N m s) */
    int32_t lambda_q28;   /* singularity-robust damping lambda0, Q3.28 (0.05) */
    int32_t umax_cnt;     /* gimbal-rate limit in command counts of 2^-16 rad/s (11437) */
    int32_t ms_sing_q28;  /* SINGULAR when m_s < this, Q3.28 (0.05) */
} rsp_cmg_params_t;

typedef struct {
    int32_t h_q20[3];         /* cluster momentum H = sum h_p, body frame, LSB 2^-20 N m s */
    int32_t ahat_q28[3][4];   /* normalised Jacobian dH/dbeta / h_g, Q3.28 (row = body axis) */
} rsp_cmg_geom_t;

typedef struct {
    int16_t rate_cnt[4];      /* gimbal rate command, 2^-16 rad/s, |.| <= umax_cnt */
    int32_t rate_q28[4];      /* beta_dot before the rate scaling, Q3.28 rad/s (telemetry, golden) */
    int32_t mdel_q24[3];      /* delivered moment -h_g Ahat beta_dot_cmd, LSB 2^-24 N m */
    int32_t ms_q28;           /* singularity measure m_s, Q3.28 */
    int32_t s_q16;            /* rate scale s = max|beta_dot| / u_max, Q16.16 (reported; saturates) */
    uint32_t flags;           /* RSP_CMG_F_* */
} rsp_cmg_out_t;

/* Gimbal angles as binary angles (2^32 = 2 pi; an encoder count of 2pi/2^20 is count << 12). */
void rsp_cmg_geom(const uint32_t beta_bam[4], int32_t hg_q20, rsp_cmg_geom_t *g, fx_status_t *st);
/* m_s by Cauchy-Binet, Q3.28 (>= 0; [0, 1.54] for a geometry made by rsp_cmg_geom). */
int32_t rsp_cmg_ms_q28(const rsp_cmg_geom_t *g, fx_status_t *st);
/* mcmd_q24: the law's moment on the body M_cmd (|M| <= 4.7 N m), LSB 2^-24 N m. Hdot_c = -M_cmd. */
void rsp_cmg_steer(const rsp_cmg_params_t *p, const rsp_cmg_geom_t *g, const int32_t mcmd_q24[3],
                   rsp_cmg_out_t *o, fx_status_t *st);

#endif /* FSW_RSP_CMG_H */
