/*
 * gv_obs.h — record layout of the observer's build-time golden vectors (spec 00 §6.4,
 * 10-observer §5) and the fingerprint of the table they were made for. The host generator
 * (tests/observer/gen/obs_golden_gen.cpp) writes const arrays of these records into the build
 * tree (never committed); the replay test (tests/observer/test_obs_golden_replay.c) includes the
 * generated header on the host and, through FSW_HOST_BUILD_DIR, on the target. The digest
 * machinery all modules share is tests/golden/gv_digest.h.
 *
 * Every member is a 32-bit integer, so the layout has no padding and the generator can emit
 * positional initialisers (it checks the size). Units are LSB of the named format; bounds are
 * integer thresholds for integer errors (|fixed - reference| <= bound), derived in the replay
 * test's comments and computed per record by the generator from the reference's own operands.
 * C99; the generator includes it inside extern "C".
 */
#ifndef TESTS_OBSERVER_GV_OBS_H
#define TESTS_OBSERVER_GV_OBS_H

#include <stdint.h>
#include "gv_digest.h"
#include "obs.h"

#define GV_P_UPPER 28u   /* upper triangle of the 7x7 scaled covariance, row-major */

/* Observer single-step vector (spec 10 §5): the quantised reference state before step n, the
   input counts of step n, the reference outputs of one step from exactly that state, and the
   per-step bounds. */
typedef struct {
    /* input */
    uint32_t seq;                 /* sample sequence number (the plant's step index) */
    int32_t  gyro_cnt[2];
    uint32_t init;                /* 1: initialised filter loaded; 0: the first complete sample
                                     (the flight code initialises from it, start_estimate) */
    /* quantised reference state before the step */
    int32_t  x_q29[6];
    int32_t  kappa_q28;
    int32_t  p_q30[GV_P_UPPER];   /* mirrored on load: the flight code keeps P exactly symmetric */
    int32_t  qres_q29[2];         /* command quantisation residual */
    int32_t  u_prev_q29[2];       /* command applied over the last period (counts << act shift) */
    uint32_t limited_run;         /* consecutive limited commands */
    /* reference outputs (rounded to the nearest LSB) */
    int32_t  cmd_cnt[2];
    int32_t  x1_q29[6];
    int32_t  kappa1_q28;
    int32_t  p1_q30[GV_P_UPPER];
    uint32_t health;              /* expected OBS_H_* bits and fx status (0) */
    uint32_t health_dc;           /* don't-care bits: a reference decision within the fixed-point
                                     error of its threshold (the generator reports how many) */
    /* bounds [d]: d = max |command difference| in counts (0 or 1; more fails the vector) */
    int32_t  bx[2][6];            /* x-hat, LSB q29 */
    int32_t  bk;                  /* kappa, LSB q28 */
    int32_t  bp[2];               /* every P_s entry, LSB q30 */
} gv_obs_t;

/* The fingerprint of the flight table the vectors were generated for: the generator writes it
   into the vector header, the replay recomputes it from the table it links, so a target build
   fed with a host build of another table revision fails with a clear message instead of a
   bound violation. */
static inline uint32_t gv_obs_table_fp(const obs_params_t *p)
{
    gv_dg_t d;
    uint32_t i;
    gv_dg_begin(&d);
    gv_dg_u32(&d, p->period_us);
    gv_dg_u32(&d, ((uint32_t)p->estimator << 24) | ((uint32_t)p->gyro_cnt_shift << 16) |
                      ((uint32_t)p->act_cnt_shift << 8) | (uint32_t)(uint8_t)p->sigma);
    gv_dg_i32(&d, p->gyro_max_cnt);
    gv_dg_i32(&d, p->act_max_cnt);
    gv_dg_i32(&d, p->bdot_max_q29);
    gv_dg_i32n(&d, p->phi0, OBS_NX * OBS_NX);
    gv_dg_i32n(&d, p->phik, OBS_NX * OBS_NX);
    gv_dg_i32n(&d, p->gam0, OBS_NX * OBS_NU);
    gv_dg_i32n(&d, p->gamk, OBS_NX * OBS_NU);
    gv_dg_i32n(&d, p->d, OBS_NU * OBS_NX);
    gv_dg_u32(&d, ((uint32_t)p->q_phi0 << 24) | ((uint32_t)p->q_phik << 16) | ((uint32_t)p->q_gam0 << 8) |
                      (uint32_t)p->q_gamk);
    gv_dg_u32(&d, (uint32_t)p->q_d);
    gv_dg_i32(&d, p->kappa0_q28);
    gv_dg_i32(&d, p->kappa_init_q28);
    gv_dg_i32(&d, p->kappa_lo_q28);
    gv_dg_i32(&d, p->kappa_hi_q28);
    for (i = 0u; i < OBS_NZ; i++) {
        gv_dg_i32(&d, (int32_t)p->ls[i]);
    }
    gv_dg_i32n(&d, p->p0_q30, OBS_NZ);
    gv_dg_i32n(&d, p->qd_q30, OBS_NZ);
    gv_dg_i32(&d, p->r_q30);
    gv_dg_i32(&d, p->p_floor_q30);
    gv_dg_i32(&d, p->p_ceil_q30);
    gv_dg_u32(&d, ((uint32_t)p->n_sat << 16) | (uint32_t)p->n_gap_max);
    gv_dg_i32(&d, p->d2_max_q16);
    gv_dg_u32(&d, (uint32_t)p->d2_reject);
    gv_dg_u32(&d, ((uint32_t)p->n_rej_safe << 16) | (uint32_t)p->rej_leak_inc);
    gv_dg_u32(&d, (uint32_t)p->rej_freeze_on);
    return d.crc;
}

#endif /* TESTS_OBSERVER_GV_OBS_H */
