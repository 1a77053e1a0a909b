/*
 * gv.h — record layouts of the build-time golden vectors (spec 00 §6.4, 10-observer §5,
 * 50-impulse §6). The host generator (tests/golden/gen/golden_gen.cpp) writes const arrays of
 * these records into the build tree (never committed); the replay tests
 * (tests/observer/test_obs_golden_replay.c, tests/impulse/test_imp_golden_replay.c) include the
 * generated headers on the host and, through FSW_HOST_BUILD_DIR, on the target.
 *
 * Every member is a 32-bit integer, so the layout has no padding and the generator can emit
 * positional initialisers (it checks the sizes). Units are LSB of the named format; bounds are
 * integer thresholds for integer errors (|fixed - reference| <= bound), derived in the replay
 * tests' comments and computed per record by the generator from the reference's own operands.
 */
#ifndef TESTS_GOLDEN_GV_H
#define TESTS_GOLDEN_GV_H

#include <stdint.h>

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

#endif /* TESTS_GOLDEN_GV_H */
