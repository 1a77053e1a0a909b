/*
 * gv_digest.h — CRC-32 digests of golden-vector replays (spec 00 §6.4), the pattern of
 * tests/golden/fx_digest.c: every record is serialised word by word, little-endian (never as
 * raw struct bytes, whose padding is indeterminate), into fx_crc32. A replay prints
 *     digest <set> <records> <crc>
 * per set; tests/golden/digest.cmake saves the host's lines and makes each Cortex-M build
 * reproduce them bit for bit.
 *
 * Also the fingerprints of the flight tables the vectors were generated for: the generator
 * writes them into the vector headers, the replay recomputes them from the tables it links, so
 * a target build fed with a host build of another table revision fails with a clear message
 * instead of a bound violation. C99; the host generator includes it inside extern "C".
 */
#ifndef TESTS_GOLDEN_GV_DIGEST_H
#define TESTS_GOLDEN_GV_DIGEST_H

#include <stdint.h>
#include <stddef.h>
#include "fx.h"
#include "obs.h"
#include "imp.h"

typedef struct {
    uint32_t crc;
    uint32_t n;     /* records */
} gv_dg_t;

static inline void gv_dg_begin(gv_dg_t *d)
{
    d->crc = 0u;
    d->n = 0u;
}

static inline void gv_dg_u32(gv_dg_t *d, uint32_t v)
{
    uint8_t b[4];
    b[0] = (uint8_t)(v & 0xFFu);
    b[1] = (uint8_t)((v >> 8) & 0xFFu);
    b[2] = (uint8_t)((v >> 16) & 0xFFu);
    b[3] = (uint8_t)((v >> 24) & 0xFFu);
    d->crc = fx_crc32(d->crc, b, 4u);
}

static inline void gv_dg_i32(gv_dg_t *d, int32_t v) { gv_dg_u32(d, (uint32_t)v); }

static inline void gv_dg_i32n(gv_dg_t *d, const int32_t *v, uint32_t n)
{
    uint32_t i;
    for (i = 0u; i < n; i++) {
        gv_dg_i32(d, v[i]);
    }
}

/* A const record made only of 32-bit members (the gv_*_t layouts), as words. */
static inline void gv_dg_words(gv_dg_t *d, const void *rec, size_t bytes)
{
    const uint32_t *w = (const uint32_t *)rec;
    size_t i;
    for (i = 0u; i < (bytes / 4u); i++) {
        gv_dg_u32(d, w[i]);
    }
}

/* ------------------------------------------------------------------ table fingerprints */

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
    return d.crc;
}

static inline uint32_t gv_imp_table_fp(const imp_params_t *p)
{
    gv_dg_t d;
    gv_dg_begin(&d);
    gv_dg_u32(&d, ((uint32_t)p->max_iter << 8) | (uint32_t)p->pivot_ratio_sh);
    gv_dg_i32(&d, p->r_tol_lsb);
    gv_dg_i32(&d, p->pivot_min_q26);
    gv_dg_i32(&d, p->rho_warn_q28);
    gv_dg_i32(&d, p->rho_reject_q28);
    gv_dg_i32(&d, p->dv_tie_q28);
    gv_dg_i32(&d, p->tauf_min_q29);
    gv_dg_i32(&d, p->tauf_max_q29);
    gv_dg_i32n(&d, p->alpha_q30, IMP_NTHR);
    gv_dg_u32(&d, p->omega_nradps);
    gv_dg_u32(&d, p->a_nom_umps2);
    return d.crc;
}

#endif /* TESTS_GOLDEN_GV_DIGEST_H */
