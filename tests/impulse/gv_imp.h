/*
 * gv_imp.h — record layouts of the impulse solver's build-time golden vectors (spec 00 §6.4,
 * 50-impulse §6) and the fingerprint of the table they were made for. The host generator
 * (tests/impulse/gen/imp_golden_gen.cpp) writes const arrays of these records into the build
 * tree (never committed); the replay test (tests/impulse/test_imp_golden_replay.c) includes the
 * generated header on the host and, through FSW_HOST_BUILD_DIR, on the target. The digest
 * machinery all modules share is tests/golden/gv_digest.h.
 *
 * Every member is a 32-bit integer, so the layouts have no padding and the generator can emit
 * positional initialisers (it checks the sizes). Units are LSB of the named format. C99; the
 * generator includes it inside extern "C".
 */
#ifndef TESTS_IMPULSE_GV_IMP_H
#define TESTS_IMPULSE_GV_IMP_H

#include <stdint.h>
#include "gv_digest.h"
#include "imp.h"

/* Impulse solver problem and the reference plan (spec 50 §6, G3 final / G4). */
typedef struct {
    int32_t  tauf_q29;
    int32_t  x0_q28[6];
    int32_t  xt_q28[6];
    int32_t  alpha_q30[6];
    /* reference plan (ref::solve on the dequantised problem) */
    uint32_t outcome;             /* IMP_SOL_* */
    uint32_t pattern;             /* 6-bit polarity pattern (valid plans) */
    uint32_t how[2];              /* IMP_HOW_* per subsystem */
    uint32_t iters[2];
    int32_t  t1_q29[3];
    int32_t  t2_q29[3];
    int32_t  dv_q28[2];           /* plan dv per subsystem */
    int32_t  jinv_q8;             /* ceil(256 ||J^-1||inf) at the reference solution (valid) */
} gv_imp_case_t;

/* G3: iterate k of one subsystem of the paper's example, pure Newton from (0, tau_f) with the
   rule's polarities (x-y 0xC, z 0x1), the flight guards. */
typedef struct {
    uint32_t sub;                 /* IMP_SUB_XY, IMP_SUB_Z */
    uint32_t pat;                 /* subsystem-local pattern */
    uint32_t k;                   /* iterate index 0..5 */
    int32_t  t1_q29[2];
    int32_t  t2_q29[2];
    int32_t  f_q28[4];            /* residual at the reference iterate (2 used for z) */
    int32_t  jn_q8;               /* ceil(256 ||J||inf) at the reference iterate */
} gv_imp_iter_t;

/* The fingerprint of the flight table the vectors were generated for: the generator writes it
   into the vector header, the replay recomputes it from the table it links, so a target build
   fed with a host build of another table revision fails with a clear message instead of a
   bound violation. */
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

#endif /* TESTS_IMPULSE_GV_IMP_H */
