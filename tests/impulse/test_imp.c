/*
 * test_imp.c — unit tests of the impulse scheduler (spec 50-impulse), host (CMocka) and
 * Cortex-M3 target (QEMU). Integer-only: expected values are the spec's numbers (§3.4, A4-2)
 * converted to the solver's formats with w = 1.131367e-3 rad/s, a_nom = 0.04 m/s^2 (conversions
 * in comments), never outputs of the fixed-point code itself.
 *
 * Tolerances: the spec prints times to 1 ms (+-0.5 ms of rounding), and the fixed point may
 * differ from double by <= 0.25 ms (G4, measured 0.016 ms on this case by test_imp_golden_host):
 * 0.75 ms < 1 ms = 607 LSB of q29 (1 ms * w * 2^29). Delta-v: the spec prints 4-5 digits;
 * 1e-4 m/s = 759 LSB of q28 (1e-4 / (a_nom / w) * 2^28), 0.01 m/s = 75 925 LSB.
 */
#include "imp.h"
#include "imp_tables.h"
#include "ut.h"

#define MS1_Q29      607        /* 1 ms as q29 rad */
#define S10MS_Q29    6074       /* 10 ms */
#define DV1E4_Q28    759        /* 1e-4 m/s as q28 velocity units */
#define DV1E2_Q28    75925      /* 0.01 m/s */
#define T_EX_STEPS   10550u     /* 1055 s at 0.1 s */

static imp_ws_t g_ws;
static imp_solution_t g_sol;
static imp_state_t g_s;
static imp_state_t g_s2;

static int64_t iabs64(int64_t v)
{
    return (v < 0) ? -v : v;
}

/* The paper's example (spec 50 §3.4) as counts: position 1 mm, velocity 10 um/s. */
static const int32_t EX_POS_MM[3] = {5000000, 4000000, 4000000};
static const int32_t EX_VEL_CNT[3] = {-100000, -100000, -100000};

static uint32_t grid_us(const imp_params_t *p)
{
    return (p->subtick_us != 0u) ? p->subtick_us : p->period_us;
}

static void zero_bytes(void *v, uint32_t n)
{
    uint8_t *b = (uint8_t *)v;
    uint32_t i;
    for (i = 0u; i < n; i++) {
        b[i] = 0u;
    }
}

static void example_problem(imp_problem_t *pr, const imp_params_t *p, int32_t sign)
{
    uint32_t r;
    fx_status_t st = 0u;
    zero_bytes(pr, (uint32_t)sizeof(*pr));
    for (r = 0u; r < IMP_NAX; r++) {
        pr->x0_q28[2u * r] = fx_from_count(sign * EX_POS_MM[r], p->k_pos_m, p->k_pos_sh, 0, &st);
        pr->x0_q28[(2u * r) + 1u] = fx_from_count(sign * EX_VEL_CNT[r], p->k_vel_m, p->k_vel_sh, 0, &st);
        pr->xt_q28[2u * r] = 0;
        pr->xt_q28[(2u * r) + 1u] = 0;
    }
    for (r = 0u; r < IMP_NTHR; r++) {
        pr->alpha_q30[r] = p->alpha_q30[r];
    }
    pr->tauf_q29 = fx_rshift_sat((int64_t)T_EX_STEPS * (int64_t)p->k_gtau_m * (int64_t)(p->period_us / grid_us(p)),
                                 p->k_gtau_sh, &st);
    pr->warm_mask = 0u;
    pr->replan = 0u;
    UT_CHECK_EQ(st, 0u);
}

UT_TEST(default_table_passes_its_checks)
{
    uint32_t why = 0xFFFFFFFFu;
    UT_EQ(imp_params_check(&IMP_TBL_DEFAULT, &why), FSW_OK);
    UT_UEQ(why, 0u);
    why = 0xFFFFFFFFu;
    UT_EQ(imp_params_check(&IMP_TBL_1S, &why), FSW_OK);
    UT_UEQ(why, 0u);
    why = 0xFFFFFFFFu;
    UT_EQ(imp_params_check(&IMP_TBL_SUB1MS, &why), FSW_OK);
    UT_UEQ(why, 0u);
}

/* One field changed from a valid table must be refused with exactly the expected reason. */
static void refuse(const imp_params_t *p, uint32_t why_expected, fsw_rc_t rc_expected)
{
    uint32_t why = 0u;
    UT_CHECK_EQ(imp_params_check(p, &why), rc_expected);
    UT_CHECK_UEQ(why, why_expected);
}

UT_TEST(bad_tables_are_refused_with_a_reason)
{
    imp_params_t p = IMP_TBL_DEFAULT;
    p.max_iter = 0u;
    refuse(&p, IMP_WHY_ITER, FSW_ERR_RANGE);
    p = IMP_TBL_DEFAULT;
    p.plan_lead = 23u;    /* < ceil(240 / 10) = 24 (spec 50 §4.7) */
    refuse(&p, IMP_WHY_LEAD, FSW_ERR_INVARIANT);
    p = IMP_TBL_DEFAULT;
    p.plan_iter_per_step = 3u;   /* the rounding (IMP_ROUND_UNITS) never fits a step */
    refuse(&p, IMP_WHY_ITER, FSW_ERR_RANGE);
    p = IMP_TBL_DEFAULT;
    p.replan_gain_q30 = 1073741824;   /* 1.0: no re-plan could ever be applied */
    refuse(&p, IMP_WHY_ITER, FSW_ERR_RANGE);
    p = IMP_TBL_DEFAULT;
    p.rho_warn_q28 = p.rho_reject_q28 + 1;
    refuse(&p, IMP_WHY_RHO, FSW_ERR_RANGE);
    p = IMP_TBL_DEFAULT;
    p.alpha_q30[3] = 1395864371;   /* 1.3 */
    refuse(&p, IMP_WHY_ALPHA, FSW_ERR_RANGE);
    p = IMP_TBL_DEFAULT;
    p.k_tick_m += 300;             /* k_tau * k_tick no longer 1 within 2^-28 */
    refuse(&p, IMP_WHY_SCALE, FSW_ERR_INVARIANT);
    p = IMP_TBL_DEFAULT;
    p.k_pos_m += 2000;             /* 1.7e-6 relative: k_pos / k_vel no longer 100 w (2^-20) */
    refuse(&p, IMP_WHY_SCALE, FSW_ERR_INVARIANT);
    p = IMP_TBL_DEFAULT;
    p.omega_nradps = 1131400u;     /* 2.9e-5 relative off k_tau */
    refuse(&p, IMP_WHY_SCALE, FSW_ERR_INVARIANT);
    p = IMP_TBL_DEFAULT;
    p.tauf_max_q29 = 1342177280;   /* 2.5 rad */
    refuse(&p, IMP_WHY_TAU, FSW_ERR_RANGE);
    p = IMP_TBL_DEFAULT;
    p.subtick_us = 3000u;          /* does not divide the period */
    refuse(&p, IMP_WHY_GRID, FSW_ERR_INVARIANT);
    p = IMP_TBL_SUB1MS;
    p.k_gtau_m = IMP_TBL_DEFAULT.k_gtau_m;   /* grid constants of the step, not of 1 ms */
    p.k_gtick_m = IMP_TBL_DEFAULT.k_gtick_m;
    refuse(&p, IMP_WHY_GRID, FSW_ERR_INVARIANT);
    p = IMP_TBL_DEFAULT;
    p.cal_gate_q30 = 0;
    refuse(&p, IMP_WHY_CAL, FSW_ERR_RANGE);
    p = IMP_TBL_DEFAULT;
    p.u_cal_q30 = p.u_uncal_q30 + 1;
    refuse(&p, IMP_WHY_CAL, FSW_ERR_RANGE);
    p = IMP_TBL_DEFAULT;
    p.cal_pool = 2u;
    refuse(&p, IMP_WHY_CAL, FSW_ERR_RANGE);
    p = IMP_TBL_DEFAULT;
    p.fd_window = 0u;
    refuse(&p, IMP_WHY_FD, FSW_ERR_RANGE);
    p = IMP_TBL_DEFAULT;
    p.fd_frac_q30 = 1073741824;    /* 1.0 */
    refuse(&p, IMP_WHY_FD, FSW_ERR_RANGE);
    p = IMP_TBL_DEFAULT;
    p.fd_window = 601u;            /* 60.1 s: beyond the monitor's formats */
    refuse(&p, IMP_WHY_FD, FSW_ERR_RANGE);
    p = IMP_TBL_DEFAULT;
    p.nav_gate_vel_q28 = 0;
    refuse(&p, IMP_WHY_NAV, FSW_ERR_RANGE);
    p = IMP_TBL_DEFAULT;
    p.t_min_us = 100001u;
    refuse(&p, IMP_WHY_PERIOD, FSW_ERR_RANGE);
}

UT_TEST(init_gives_safe_outputs)
{
    imp_out_t out;
    uint32_t j;
    out.on_mask = 0x3Fu;
    for (j = 0u; j < IMP_NTHR; j++) {
        out.on_len_cnt[j] = 7u;
    }
    UT_EQ(imp_init(&g_s, &IMP_TBL_DEFAULT, &out), FSW_OK);
    UT_UEQ(out.on_mask, 0u);
    for (j = 0u; j < IMP_NTHR; j++) {
        UT_UEQ(out.on_len_cnt[j], 0u);
    }
    UT_UEQ((out.health & IMP_H_MODE) >> IMP_H_MODE_SH, IMP_MODE_IDLE);
}

UT_TEST(trig_kernels_are_symmetric_and_exact_at_zero)
{
    imp_trig_t t;
    imp_trig_t tn;
    fx_status_t st = 0u;
    int32_t sig;
    imp_trig(0, &t, &st);
    UT_EQ(t.s_q30, 0);
    UT_EQ(t.c_q30, 1073741824);
    UT_EQ(t.omc_q30, 0);
    UT_EQ(t.tms_q30, 0);
    for (sig = 1; sig < 1073741824; sig += 9999991) {
        imp_trig(sig, &t, &st);
        imp_trig(-sig, &tn, &st);
        UT_CHECK_EQ(tn.s_q30, -t.s_q30);
        UT_CHECK_EQ(tn.c_q30, t.c_q30);
        UT_CHECK_EQ(tn.omc_q30, t.omc_q30);
        UT_CHECK_EQ(tn.tms_q30, -t.tms_q30);
        UT_CHECK_EQ((int64_t)t.c_q30 + (int64_t)t.omc_q30, 1073741824);
        UT_CHECK(t.tms_q30 >= 0);
    }
    UT_UEQ(st, 0u);
    /* Phi(0) e_r = e_r and Psi(0) = 0 exactly. */
    {
        int32_t v[4];
        imp_trig(0, &t, &st);
        imp_phie(0u, 0, &t, v, &st);
        UT_EQ(v[0], 0);
        UT_EQ(v[1], 268435456);
        UT_EQ(v[2], 0);
        UT_EQ(v[3], 0);
        imp_psi(1u, 0, &t, v, &st);
        UT_EQ(v[0], 0);
        UT_EQ(v[1], 0);
        UT_EQ(v[2], 0);
        UT_EQ(v[3], 0);
    }
}

/* A4-2, fixed point: polarities, iterations, times, delta-v against the spec's numbers. */
UT_TEST(paper_example_matches_the_spec)
{
    imp_problem_t pr;
    const int32_t t1[3] = {21617296, 208148017, 18041544};     /* 35.590, 342.688, 29.703 s */
    const int32_t t2[3] = {509798888, 609960645, 564137930};   /* 839.316, 1004.219, 928.778 s */
    uint32_t r;
    example_problem(&pr, &IMP_TBL_DEFAULT, 1);
    imp_solve(&g_ws, &IMP_TBL_DEFAULT, &pr, &g_sol);
    UT_EQ(g_sol.outcome, IMP_SOL_VALID);
    UT_EQ(g_sol.pattern, 0x1Cu);                 /* x (+,+), y (-,-), z (-,+) */
    UT_EQ(g_sol.how[IMP_SUB_XY], IMP_HOW_RULE);
    UT_EQ(g_sol.how[IMP_SUB_Z], IMP_HOW_RULE);
    UT_CHECK_LE(g_sol.iters[IMP_SUB_XY], 5);     /* convergence declared by iteration 5 */
    UT_CHECK_LE(4, g_sol.iters[IMP_SUB_XY]);
    UT_CHECK_LE(g_sol.iters[IMP_SUB_Z], 5);
    UT_CHECK_LE(g_sol.fres_lsb[IMP_SUB_XY], IMP_TBL_DEFAULT.r_tol_lsb);
    UT_CHECK_LE(g_sol.fres_lsb[IMP_SUB_Z], IMP_TBL_DEFAULT.r_tol_lsb);
    UT_UEQ(g_sol.st_ok, 0u);
    UT_EQ(g_sol.marginal, 0u);
    for (r = 0u; r < IMP_NAX; r++) {
        UT_CHECK_LE(iabs64((int64_t)g_sol.t1_q29[r] - t1[r]), MS1_Q29);
        UT_CHECK_LE(iabs64((int64_t)g_sol.t2_q29[r] - t2[r]), MS1_Q29);
    }
    /* x invariant: signed x impulse 10.0509 m/s, T2x - T1x = 803.727 s. */
    UT_CHECK_LE(iabs64((int64_t)g_sol.dv1_q28[0] + g_sol.dv2_q28[0] - 76311211), DV1E4_Q28);
    UT_CHECK_LE(iabs64((int64_t)g_sol.t2_q29[0] - g_sol.t1_q29[0] - 488182199), S10MS_Q29);
    /* total delta-v 32.027 m/s */
    UT_CHECK_LE(iabs64((int64_t)g_sol.dv_q28[0] + g_sol.dv_q28[1] - 243164210), DV1E2_Q28);
}

/* Round half away from zero is odd-symmetric: the mirrored problem gives the mirrored
   polarities and bit-identical times. */
UT_TEST(mirrored_problem_gives_mirrored_plan)
{
    imp_problem_t pr;
    imp_solution_t a;
    uint32_t r;
    example_problem(&pr, &IMP_TBL_DEFAULT, 1);
    imp_solve(&g_ws, &IMP_TBL_DEFAULT, &pr, &a);
    example_problem(&pr, &IMP_TBL_DEFAULT, -1);
    imp_solve(&g_ws, &IMP_TBL_DEFAULT, &pr, &g_sol);
    UT_EQ(g_sol.outcome, IMP_SOL_VALID);
    UT_UEQ(g_sol.pattern, a.pattern ^ 0x3Fu);
    for (r = 0u; r < IMP_NAX; r++) {
        UT_CHECK_EQ(g_sol.t1_q29[r], a.t1_q29[r]);
        UT_CHECK_EQ(g_sol.t2_q29[r], a.t2_q29[r]);
        UT_CHECK_EQ(g_sol.dv1_q28[r], -a.dv1_q28[r]);
    }
}

/* §8 infeasible target: rho_max > rho_reject, nothing attempted. */
UT_TEST(infeasible_state_is_refused_without_attempts)
{
    imp_problem_t pr;
    uint32_t r;
    example_problem(&pr, &IMP_TBL_DEFAULT, 1);
    for (r = 0u; r < IMP_NAX; r++) {   /* (20 km, 5 m/s) on every axis (A4-7) */
        pr.x0_q28[2u * r] = 171797523;      /* 20000 m / 31250.21 m * 2^28 */
        pr.x0_q28[(2u * r) + 1u] = 37962377; /* 5 m/s / 35.3555 m/s * 2^28 */
    }
    imp_solve(&g_ws, &IMP_TBL_DEFAULT, &pr, &g_sol);
    UT_EQ(g_sol.outcome, IMP_SOL_INFEASIBLE);
    UT_EQ(g_sol.attempts[0], 0);
    UT_EQ(g_sol.attempts[1], 0);
    UT_CHECK(g_sol.rho_q28[0] > IMP_TBL_DEFAULT.rho_reject_q28);
}

/* §3.2 singularity: equal switching times (no coast) give two equal columns. */
UT_TEST(zero_coast_is_singular)
{
    imp_problem_t pr;
    uint32_t iters = 0u;
    uint32_t fres = 0u;
    fx_status_t st = 0u;
    int32_t t1[2];
    int32_t t2[2];
    example_problem(&pr, &IMP_TBL_DEFAULT, 1);
    t1[0] = pr.tauf_q29 / 2;
    t2[0] = t1[0];
    UT_EQ(imp_attempt(&g_ws, &IMP_TBL_DEFAULT, &pr, IMP_SUB_Z, 0u, t1, t2, &iters, &fres, &st), IMP_FAIL_SINGULAR);
    UT_CHECK((st & FX_ST_SINGULAR) != 0u);
    UT_EQ(iters, 0);
    t1[0] = 0;   /* x-y: coast vanishes on y only */
    t1[1] = pr.tauf_q29 / 3;
    t2[0] = pr.tauf_q29;
    t2[1] = t1[1];
    st = 0u;
    UT_EQ(imp_attempt(&g_ws, &IMP_TBL_DEFAULT, &pr, IMP_SUB_XY, 0xCu, t1, t2, &iters, &fres, &st), IMP_FAIL_SINGULAR);
}

/* §3.6 iteration limit: with max_iter = 2 no pattern converges; every attempt is counted. */
UT_TEST(iteration_limit_gives_no_solution)
{
    imp_params_t p = IMP_TBL_DEFAULT;
    imp_problem_t pr;
    p.max_iter = 2u;
    example_problem(&pr, &p, 1);
    imp_solve(&g_ws, &p, &pr, &g_sol);
    UT_EQ(g_sol.outcome, IMP_SOL_NO_SOLUTION);
    UT_EQ(g_sol.sub_outcome[IMP_SUB_XY], IMP_SOL_NO_SOLUTION);
    UT_EQ(g_sol.attempts[IMP_SUB_XY], 16);       /* rule + 15 others */
    UT_CHECK(g_sol.n_fail[IMP_FAIL_ITER] >= 1u);
    UT_EQ(g_sol.how[IMP_SUB_XY], IMP_HOW_NONE);
}

/* Warm start with the converged solution converges at once and is reported as warm. */
UT_TEST(warm_start_is_tried_first)
{
    imp_problem_t pr;
    uint32_t r;
    example_problem(&pr, &IMP_TBL_DEFAULT, 1);
    imp_solve(&g_ws, &IMP_TBL_DEFAULT, &pr, &g_sol);
    pr.warm_mask = 3u;
    pr.warm_pattern = g_sol.pattern;
    for (r = 0u; r < IMP_NAX; r++) {
        pr.warm_t1_q29[r] = g_sol.t1_q29[r];
        pr.warm_t2_q29[r] = g_sol.t2_q29[r];
    }
    imp_solve(&g_ws, &IMP_TBL_DEFAULT, &pr, &g_sol);
    UT_EQ(g_sol.outcome, IMP_SOL_VALID);
    UT_EQ(g_sol.how[IMP_SUB_XY], IMP_HOW_WARM);
    UT_EQ(g_sol.how[IMP_SUB_Z], IMP_HOW_WARM);
    UT_CHECK_LE(g_sol.iters[IMP_SUB_XY], 1);
}

/* §5.3 best rounding: never worse than nearest, steps are floor or ceil of the times. */
UT_TEST(best_rounding_is_no_worse_than_nearest)
{
    static imp_round_t rd;
    imp_problem_t pr;
    fx_status_t st = 0u;
    uint32_t r;
    example_problem(&pr, &IMP_TBL_DEFAULT, 1);
    imp_solve(&g_ws, &IMP_TBL_DEFAULT, &pr, &g_sol);
    UT_EQ(g_sol.outcome, IMP_SOL_VALID);
    imp_round_best(&g_ws, &IMP_TBL_DEFAULT, &pr, &g_sol, T_EX_STEPS, &rd, &st);
    UT_UEQ(st, 0u);
    UT_CHECK(rd.cost_q56 <= rd.cost_nearest_q56);
    for (r = 0u; r < IMP_NAX; r++) {
        /* n = T * k_tick within one step: |n * k_tau - T| <= 1 step (60 741 LSB of q29) */
        int64_t t1 = ((int64_t)rd.n1[r] * IMP_TBL_DEFAULT.k_tau_m) / ((int64_t)1 << IMP_TBL_DEFAULT.k_tau_sh);
        int64_t t2 = ((int64_t)rd.n2[r] * IMP_TBL_DEFAULT.k_tau_m) / ((int64_t)1 << IMP_TBL_DEFAULT.k_tau_sh);
        UT_CHECK_LE(iabs64(t1 - g_sol.t1_q29[r]), 60741);
        UT_CHECK_LE(iabs64(t2 - g_sol.t2_q29[r]), 60741);
        UT_CHECK(rd.n1[r] <= rd.n2[r]);
        UT_CHECK(rd.n2[r] <= T_EX_STEPS);
    }
    /* Predicted miss at a 0.1 s tick: spec 50 §5.3 evidence 0.60 m; well below 1 m = 8590 LSB. */
    for (r = 0u; r < IMP_NAX; r++) {
        UT_CHECK_LE(iabs64(rd.miss_q28[2u * r]), 8590);
    }
}

/* The resumable job (spec 50 §4.7) gives, bit for bit, the plan of imp_solve, whatever the
   budget per call; no call uses more than its budget, and the job ends within
   IMP_JOB_UNITS(max_iter) units. */
static void same_solution(const imp_solution_t *a, const imp_solution_t *b)
{
    uint32_t i;
    UT_CHECK_EQ(a->outcome, b->outcome);
    UT_CHECK_EQ(a->pattern, b->pattern);
    UT_CHECK_EQ(a->marginal, b->marginal);
    UT_CHECK_EQ(a->iters_total, b->iters_total);
    UT_CHECK_UEQ(a->st_ok, b->st_ok);
    UT_CHECK_UEQ(a->st_fail, b->st_fail);
    for (i = 0u; i < IMP_NSUB; i++) {
        UT_CHECK_EQ(a->how[i], b->how[i]);
        UT_CHECK_EQ(a->iters[i], b->iters[i]);
        UT_CHECK_EQ(a->attempts[i], b->attempts[i]);
        UT_CHECK_EQ(a->fres_lsb[i], b->fres_lsb[i]);
        UT_CHECK_EQ(a->dv_q28[i], b->dv_q28[i]);
        UT_CHECK_EQ(a->last_fail[i], b->last_fail[i]);
    }
    for (i = 0u; i < IMP_FAIL_N; i++) {
        UT_CHECK_EQ(a->n_fail[i], b->n_fail[i]);
    }
    for (i = 0u; i < IMP_NAX; i++) {
        UT_CHECK_EQ(a->t1_q29[i], b->t1_q29[i]);
        UT_CHECK_EQ(a->t2_q29[i], b->t2_q29[i]);
        UT_CHECK_EQ(a->dv1_q28[i], b->dv1_q28[i]);
        UT_CHECK_EQ(a->rho_q28[i], b->rho_q28[i]);
    }
}

static uint32_t run_in_slices(const imp_params_t *p, const imp_problem_t *pr, uint32_t budget)
{
    uint32_t calls = 0u;
    uint32_t n;
    imp_solve_begin(&g_ws, &g_sol);
    for (n = 0u; (n < 400u) && !imp_solve_done(&g_ws); n++) {
        uint32_t used = imp_solve_run(&g_ws, p, pr, &g_sol, budget);
        UT_CHECK_LE(used, budget);
        calls++;
    }
    UT_CHECK(imp_solve_done(&g_ws));
    UT_CHECK_LE(g_ws.job.units, IMP_JOB_UNITS(p->max_iter));
    return calls;
}

UT_TEST(resumable_job_is_bit_identical_to_one_shot)
{
    static imp_solution_t one;
    imp_problem_t pr;
    imp_params_t p2 = IMP_TBL_DEFAULT;
    uint32_t r;
    uint32_t b;
    static const uint32_t budgets[3] = {1u, 3u, 10u};
    p2.max_iter = 2u;
    for (b = 0u; b < 3u; b++) {
        example_problem(&pr, &IMP_TBL_DEFAULT, 1);
        imp_solve(&g_ws, &IMP_TBL_DEFAULT, &pr, &one);
        (void)run_in_slices(&IMP_TBL_DEFAULT, &pr, budgets[b]);
        same_solution(&g_sol, &one);
        /* a re-plan with a warm start (the converged times shifted by nothing) */
        pr.warm_mask = 3u;
        pr.replan = 1u;
        pr.warm_pattern = one.pattern;
        for (r = 0u; r < IMP_NAX; r++) {
            pr.warm_t1_q29[r] = one.t1_q29[r];
            pr.warm_t2_q29[r] = one.t2_q29[r];
        }
        imp_solve(&g_ws, &IMP_TBL_DEFAULT, &pr, &one);
        (void)run_in_slices(&IMP_TBL_DEFAULT, &pr, budgets[b]);
        same_solution(&g_sol, &one);
        /* every pattern fails: the worst kind of plan (16 + 4 attempts) */
        example_problem(&pr, &p2, 1);
        imp_solve(&g_ws, &p2, &pr, &one);
        UT_CHECK_EQ(run_in_slices(&p2, &pr, budgets[b]) >= (60u / budgets[b]), 1);
        same_solution(&g_sol, &one);
        UT_CHECK_EQ(one.outcome, IMP_SOL_NO_SOLUTION);
    }
}

/* Patterns that use an avoided thruster are never tried (stuck-off re-plan, spec 50 §8). The
   example's x invariant needs +10.05 m/s, which -x cannot give: no solution without +x. */
UT_TEST(avoided_thrusters_are_never_used)
{
    imp_problem_t pr;
    example_problem(&pr, &IMP_TBL_DEFAULT, 1);
    pr.thr_off = 0x01u;                      /* +x */
    imp_solve(&g_ws, &IMP_TBL_DEFAULT, &pr, &g_sol);
    UT_EQ(g_sol.outcome, IMP_SOL_NO_SOLUTION);
    UT_EQ(g_sol.sub_outcome[IMP_SUB_XY], IMP_SOL_NO_SOLUTION);
    UT_CHECK_LE(g_sol.attempts[IMP_SUB_XY], 4);   /* only s1x = s2x = -: 4 of 16 patterns */
    UT_EQ(g_sol.sub_outcome[IMP_SUB_Z], IMP_SOL_VALID);
    example_problem(&pr, &IMP_TBL_DEFAULT, 1);
    pr.thr_off = 0x20u;                      /* -z: the z rule (-, +) is not allowed */
    imp_solve(&g_ws, &IMP_TBL_DEFAULT, &pr, &g_sol);
    UT_CHECK_LE(g_sol.attempts[IMP_SUB_Z], 1);    /* only (+, +) */
    UT_CHECK(((uint32_t)g_sol.pattern & 0x30u) == 0u);
}

/* Sub-tick grid (1 ms) and the minimum impulse bit (spec 50 §5.3): burns are 0 or >= t_min
   (20 grid units), a same-thruster coast inside one step is merged, an opposite-thruster coast
   inside one step is widened to the next step boundary. The solution's times are set by hand
   (the rounding scores any schedule; only its rules are checked here). */
#define G1MS_PER_S   1000u
static int32_t tau_of_ms(uint32_t ms_x10)   /* tau q29 of ms_x10 tenths of a millisecond */
{
    fx_status_t st = 0u;
    return fx_rshift_sat((int64_t)ms_x10 * (int64_t)IMP_TBL_SUB1MS.k_gtau_m, IMP_TBL_SUB1MS.k_gtau_sh + 0u, &st) / 10;
}

UT_TEST(subtick_rounding_meets_minimum_impulse_and_coast_rules)
{
    static imp_round_t rd;
    imp_problem_t pr;
    fx_status_t st = 0u;
    const uint32_t ntot = 1055u * G1MS_PER_S;
    example_problem(&pr, &IMP_TBL_SUB1MS, 1);
    imp_solve(&g_ws, &IMP_TBL_SUB1MS, &pr, &g_sol);
    UT_EQ(g_sol.outcome, IMP_SOL_VALID);
    /* x: first burn 15.4 ms (< t_min), second burn ends at t_f as solved */
    g_sol.t1_q29[0] = tau_of_ms(154u);
    /* y (-, -): a coast of 38.3 ms inside one step: same thruster -> merged */
    g_sol.t1_q29[1] = tau_of_ms(3000123u);      /* 300.0123 s */
    g_sol.t2_q29[1] = tau_of_ms(3000506u);      /* 300.0506 s */
    /* z (-, +): a coast of 30.1 ms inside one step: opposite thrusters -> widened */
    g_sol.t1_q29[2] = tau_of_ms(500101u);       /* 50.0101 s */
    g_sol.t2_q29[2] = tau_of_ms(500402u);       /* 50.0402 s */
    imp_round_best(&g_ws, &IMP_TBL_SUB1MS, &pr, &g_sol, ntot, &rd, &st);
    UT_UEQ(st, 0u);
    UT_CHECK((rd.n1[0] == 0u) || (rd.n1[0] >= 20u));
    UT_CHECK_LE(rd.n1[0], 20);
    UT_CHECK_EQ(rd.n1[1], rd.n2[1]);                         /* merged */
    UT_CHECK((rd.n1[1] == 300012u) || (rd.n1[1] == 300013u));
    UT_CHECK_EQ(rd.fixed[IMP_SUB_XY] & 2u, 2u);
    UT_CHECK_EQ(rd.n2[2] % 100u, 0u);                        /* on a step boundary ... */
    UT_CHECK(((rd.n1[2] - 1u) / 100u) < (rd.n2[2] / 100u));  /* ... after the step of the first end */
    UT_CHECK_EQ(rd.n2[2], 50100u);
    UT_CHECK_EQ(rd.fixed[IMP_SUB_Z], 1u);
    /* second burn of x shorter than t_min: 0 or 20 grid units */
    g_sol.t1_q29[1] = tau_of_ms(3000000u);
    g_sol.t2_q29[1] = tau_of_ms(6000000u);
    g_sol.t2_q29[0] = fx_sub_sat(pr.tauf_q29, tau_of_ms(127u), &st);   /* 12.7 ms before t_f */
    imp_round_best(&g_ws, &IMP_TBL_SUB1MS, &pr, &g_sol, ntot, &rd, &st);
    UT_CHECK((rd.n2[0] == ntot) || (rd.n2[0] == (ntot - 20u)));
    UT_CHECK_EQ(rd.fixed[IMP_SUB_XY], 0u);
}

static imp_in_t start_cmd(uint32_t k, uint32_t t0, uint32_t tf)
{
    imp_in_t in;
    uint32_t r;
    zero_bytes(&in, (uint32_t)sizeof(in));
    in.step = k;
    in.cmd = IMP_CMD_START;
    in.cmd_t0_step = t0;
    in.cmd_tf_step = tf;
    in.nav_valid = 1u;
    in.nav_step = k;
    in.avail_mask = 0x3Fu;
    for (r = 0u; r < IMP_NAX; r++) {
        in.nav_pos_mm[r] = EX_POS_MM[r];
        in.nav_vel_cnt[r] = EX_VEL_CNT[r];
    }
    return in;
}

static uint32_t mode_of(const imp_out_t *out)
{
    return (out->health & IMP_H_MODE) >> IMP_H_MODE_SH;
}

/* Steps with no command from k0 to k1 (inclusive); returns the first step in `mode` (0: never). */
static uint32_t run_until(imp_state_t *s, const imp_params_t *p, imp_in_t *in, imp_out_t *out, uint32_t k0,
                          uint32_t k1, uint32_t mode)
{
    uint32_t k;
    uint32_t first = 0u;
    in->cmd = IMP_CMD_NONE;
    for (k = k0; k <= k1; k++) {
        in->step = k;
        imp_step(s, p, in, out);
        if ((first == 0u) && (mode_of(out) == mode)) {
            first = k;
        }
    }
    return first;
}

UT_TEST(start_is_refused_out_of_range)
{
    imp_out_t out;
    imp_in_t in;
    (void)imp_init(&g_s, &IMP_TBL_DEFAULT, &out);
    in = start_cmd(0u, 100u, 100u + 22097u);      /* tau_f = 2.5 rad (A4-7) */
    imp_step(&g_s, &IMP_TBL_DEFAULT, &in, &out);
    UT_UEQ(mode_of(&out), IMP_MODE_IDLE);
    UT_CHECK((out.health & IMP_H_CMD_REJ) != 0u);
    UT_EQ(out.tlm.rej_reason, IMP_REJ_TAU);
    in = start_cmd(1u, 10u, 10u + T_EX_STEPS);    /* t0 < now + plan_lead */
    imp_step(&g_s, &IMP_TBL_DEFAULT, &in, &out);
    UT_UEQ(mode_of(&out), IMP_MODE_IDLE);
    UT_EQ(out.tlm.rej_reason, IMP_REJ_TIME);
    (void)imp_init(&g_s, &IMP_TBL_DEFAULT, &out);
    in = start_cmd(2u, 100u, 100u + T_EX_STEPS);  /* no valid nav ever received: NO_NAV */
    in.nav_valid = 0u;
    imp_step(&g_s, &IMP_TBL_DEFAULT, &in, &out);
    UT_UEQ(mode_of(&out), IMP_MODE_IDLE);
    UT_EQ(out.tlm.rej_reason, IMP_REJ_NO_NAV);
    in = start_cmd(3u, 100u, 100u + T_EX_STEPS);  /* a valid sample, but 51 steps > nav_timeout old */
    in.cmd = IMP_CMD_NONE;
    in.step = 3u;
    in.nav_step = 3u;
    imp_step(&g_s, &IMP_TBL_DEFAULT, &in, &out);
    in = start_cmd(54u, 200u, 200u + T_EX_STEPS);
    in.nav_step = 3u;
    imp_step(&g_s, &IMP_TBL_DEFAULT, &in, &out);
    UT_UEQ(mode_of(&out), IMP_MODE_IDLE);
    UT_EQ(out.tlm.rej_reason, IMP_REJ_NO_NAV);
    in = start_cmd(53u, 200u, 200u + T_EX_STEPS);  /* 50 steps old: accepted */
    in.nav_step = 3u;
    imp_step(&g_s, &IMP_TBL_DEFAULT, &in, &out);
    UT_UEQ(mode_of(&out), IMP_MODE_PLANNING);
    UT_EQ(out.tlm.cmd_rej, 2);                     /* since the second init */
    UT_UEQ(out.on_mask, 0u);
    in = start_cmd(54u, 200u, 200u + T_EX_STEPS);  /* START while planning: refused (MODE) */
    imp_step(&g_s, &IMP_TBL_DEFAULT, &in, &out);
    UT_EQ(out.tlm.rej_reason, IMP_REJ_MODE);
    UT_EQ(out.tlm.cmd_rej, 3);
}

UT_TEST(infeasible_start_never_fires)
{
    imp_out_t out;
    imp_in_t in;
    uint32_t k;
    uint32_t r;
    (void)imp_init(&g_s, &IMP_TBL_DEFAULT, &out);
    in = start_cmd(0u, 100u, 100u + T_EX_STEPS);
    for (r = 0u; r < IMP_NAX; r++) {   /* (20 km, 5 m/s) on every axis (A4-7) */
        in.nav_pos_mm[r] = 20000000;
        in.nav_vel_cnt[r] = 500000;
    }
    imp_step(&g_s, &IMP_TBL_DEFAULT, &in, &out);
    /* infeasibility is known after the impulsive step: 3 work units, within the START step */
    UT_UEQ(mode_of(&out), IMP_MODE_INFEASIBLE);
    UT_CHECK((out.health & IMP_H_INFEASIBLE) != 0u);
    UT_CHECK(out.tlm.rho_q28[0] > IMP_TBL_DEFAULT.rho_reject_q28);
    in.cmd = IMP_CMD_NONE;
    for (k = 1u; k < (200u + T_EX_STEPS); k += 7u) {
        in.step = k;
        imp_step(&g_s, &IMP_TBL_DEFAULT, &in, &out);
        UT_CHECK_EQ(out.on_mask, 0u);
    }
    UT_UEQ(out.health & FX_ST_MASK, 0u);
}

UT_TEST(no_solution_start_never_fires)
{
    imp_params_t p = IMP_TBL_DEFAULT;
    imp_out_t out;
    imp_in_t in;
    uint32_t k;
    uint32_t kn;
    p.max_iter = 2u;
    (void)imp_init(&g_s, &p, &out);
    in = start_cmd(0u, 100u, 100u + T_EX_STEPS);
    imp_step(&g_s, &p, &in, &out);
    UT_UEQ(mode_of(&out), IMP_MODE_PLANNING);
    /* 3 + 16 x 3 + 4 x 3 = 63 work units at 10 per step: NO_SOLUTION in step 6 */
    kn = run_until(&g_s, &p, &in, &out, 1u, 20u, IMP_MODE_NO_SOLUTION);
    UT_EQ(kn, 6u);
    UT_CHECK((out.health & IMP_H_NO_SOLUTION) != 0u);
    UT_EQ(out.tlm.plans_failed, 1);
    UT_EQ(out.tlm.plan_units, 63);
    UT_CHECK(out.tlm.n_fail[IMP_FAIL_ITER] >= 1u);
    in.cmd = IMP_CMD_NONE;
    for (k = 21u; k < (200u + T_EX_STEPS); k += 7u) {
        in.step = k;
        imp_step(&g_s, &p, &in, &out);
        UT_CHECK_EQ(out.on_mask, 0u);
    }
}

/* Open-loop timeline of the example: PLANNING for a few steps (at most plan_iter_per_step work
   units each), ARMED, FIRING at t0, one thruster per axis, burn lengths = plan, DONE at t_f. */
UT_TEST(timeline_fires_the_plan)
{
    imp_out_t out;
    imp_in_t in;
    uint32_t k;
    uint32_t on_cnt[IMP_NTHR] = {0u, 0u, 0u, 0u, 0u, 0u};
    uint32_t j;
    uint32_t armed = 0u;
    const uint32_t t0 = 100u;
    const uint32_t tf = t0 + T_EX_STEPS;
    (void)imp_init(&g_s, &IMP_TBL_DEFAULT, &out);
    in = start_cmd(0u, t0, tf);
    imp_step(&g_s, &IMP_TBL_DEFAULT, &in, &out);
    UT_UEQ(mode_of(&out), IMP_MODE_PLANNING);
    UT_EQ(out.tlm.job_active, 1u);
    in.cmd = IMP_CMD_NONE;
    for (k = 1u; k < (tf + 10u); k++) {
        in.step = k;
        imp_step(&g_s, &IMP_TBL_DEFAULT, &in, &out);
        if ((armed == 0u) && (mode_of(&out) == IMP_MODE_ARMED)) {
            armed = k;
            UT_CHECK_EQ(out.tlm.pattern, 0x1Cu);
            UT_CHECK_LE(out.tlm.plan_steps, IMP_TBL_DEFAULT.plan_lead);
            UT_CHECK_LE(out.tlm.plan_units, (uint32_t)IMP_TBL_DEFAULT.plan_iter_per_step * out.tlm.plan_steps);
            UT_CHECK_LE(out.tlm.fres_lsb[0], IMP_TBL_DEFAULT.r_tol_lsb);
            UT_CHECK_LE(out.tlm.fres_lsb[1], IMP_TBL_DEFAULT.r_tol_lsb);
        }
        for (j = 0u; j < IMP_NTHR; j++) {
            if ((((uint32_t)out.on_mask >> j) & 1u) != 0u) {
                on_cnt[j]++;
                UT_CHECK_EQ(out.on_start_cnt[j], 0u);
                UT_CHECK_EQ(out.on_len_cnt[j], IMP_TBL_DEFAULT.period_us);
            }
        }
        UT_CHECK((out.on_mask & 0x03u) != 0x03u);
        UT_CHECK((out.on_mask & 0x0Cu) != 0x0Cu);
        UT_CHECK((out.on_mask & 0x30u) != 0x30u);
        UT_CHECK((out.health & (IMP_H_INTERLOCK | FX_ST_MASK)) == 0u);
        if (k < t0) {
            UT_CHECK_EQ(out.on_mask, 0u);
        }
        if (k >= tf) {
            UT_CHECK_EQ(out.on_mask, 0u);
            UT_CHECK_EQ(mode_of(&out), IMP_MODE_DONE);
        }
    }
    UT_CHECK((armed >= 1u) && (armed < t0));   /* 17 work units: 2 steps at 10 per step */
    /* x: + then +, one thruster: on1 - t0 + tf - on2 steps; y: - and -; z: - first, + second. */
    UT_EQ(on_cnt[1], 0);
    UT_EQ(on_cnt[2], 0);
    UT_EQ(on_cnt[0], (out.tlm.on1_step[0] - t0) + (tf - out.tlm.on2_step[0]));
    UT_EQ(on_cnt[3], (out.tlm.on1_step[1] - t0) + (tf - out.tlm.on2_step[1]));
    UT_EQ(on_cnt[5], out.tlm.on1_step[2] - t0);
    UT_EQ(on_cnt[4], tf - out.tlm.on2_step[2]);
    /* commanded delta-v telemetry: on-time at the nominal level, q28 = n * k_gtau / 2 (q29 -> q28),
       within the two roundings */
    UT_CHECK_LE(iabs64((int64_t)out.tlm.dv_cmd_q28[0] -
                       (((int64_t)on_cnt[0] * IMP_TBL_DEFAULT.k_gtau_m) >> (IMP_TBL_DEFAULT.k_gtau_sh + 1u))), 1);
    UT_CHECK_EQ(out.tlm.dv_used_q28[0], out.tlm.dv_cmd_q28[0]);   /* alpha = 1 */
    /* The plan is for the state drifted 10 s from the nav sample: x burns ~ 2 x 100+ s. */
    UT_CHECK(on_cnt[0] > 2000u);
}

/* EXPECTED_MISS (spec 50 §5.5): dR = u alpha d^2 / 2 per axis from the second-burn length d of
   the timeline in force. Calibration off: the prediction is final from the first plan, u =
   u_uncal; the example's x burn (~215.7 s) predicts ~27.9 m > 10 m, so the flag is raised as soon
   as the plan exists. Calibration on: a calibration epoch is still due before the second burns,
   so u = u_cal (~4.65 m) and no flag. Both checked against the formula in int64 from the
   telemetry's switching steps. */
static void expected_miss_case(const imp_params_t *p, int32_t u_q30, bool flag)
{
    imp_out_t out;
    imp_in_t in;
    uint32_t r;
    const uint32_t t0 = 100u;
    const uint32_t tf = t0 + T_EX_STEPS;
    UT_EQ(imp_init(&g_s, p, &out), FSW_OK);
    in = start_cmd(0u, t0, tf);
    imp_step(&g_s, p, &in, &out);
    (void)run_until(&g_s, p, &in, &out, 1u, 20u, IMP_MODE_ARMED);
    UT_UEQ(mode_of(&out), IMP_MODE_ARMED);
    UT_CHECK_EQ((out.health & IMP_H_EXPECTED_MISS) != 0u, flag);
    for (r = 0u; r < IMP_NAX; r++) {
        /* d as tau q29 from the table's grid constant; u in q30; each product truncated here
           and rounded in the module: within 2 LSB plus 1e-6 relative */
        int64_t d = ((int64_t)(tf - out.tlm.on2_step[r]) * p->k_gtau_m) >> p->k_gtau_sh;
        int64_t dv = ((d * u_q30) >> 30) / 2;                             /* q29 -> q28 */
        int64_t dr = ((dv * d) >> 29) / 2;                                /* u d^2 / 2 */
        UT_CHECK_LE(iabs64((int64_t)out.tlm.exp_dv_q28[r] - dv), 2 + (dv / 1000000));
        UT_CHECK_LE(iabs64((int64_t)out.tlm.exp_dr_q28[r] - dr), 2 + (dr / 1000000));
    }
    /* x: 27.9 m = 239 710 LSB of q28 (27.9 / 31250.21 * 2^28) at u = 0.03, the spec's printed
       figure, scaled by u / 0.03; the drifted state and the grid move it by < 1 m here */
    UT_CHECK_LE(iabs64((int64_t)out.tlm.exp_dr_q28[0] - ((239710 * (int64_t)u_q30) / 32212255)), 8590);
    UT_CHECK_EQ(out.tlm.exp_dr_q28[0] > p->miss_flag_q28, flag);
}

UT_TEST(expected_miss_is_predicted_from_the_final_burns)
{
    imp_params_t off = IMP_TBL_DEFAULT;
    off.cal_enable = 0u;
    expected_miss_case(&off, off.u_uncal_q30, true);
    expected_miss_case(&IMP_TBL_DEFAULT, IMP_TBL_DEFAULT.u_cal_q30, false);
}

/* §5.4 / §8: while the latest accepted sample is older than nav_timeout, NAV_STALE is raised
   (ARMED, FIRING, FINAL); re-plan epochs are skipped (counted once each) and retried at the next
   fresh sample; the timeline completes open loop; FINAL once t_a would reach a second burn. */
UT_TEST(stale_nav_skips_replans_then_final)
{
    imp_out_t out;
    imp_in_t in;
    uint32_t k;
    uint32_t saw_final = 0u;
    uint32_t k_miss = 0u;
    const uint32_t t0 = 100u;
    const uint32_t tf = t0 + T_EX_STEPS;
    (void)imp_init(&g_s, &IMP_TBL_DEFAULT, &out);
    in = start_cmd(0u, t0, tf);          /* nav tagged at step 0 and never refreshed */
    imp_step(&g_s, &IMP_TBL_DEFAULT, &in, &out);
    in.cmd = IMP_CMD_NONE;
    for (k = 1u; k <= tf; k++) {
        in.step = k;
        imp_step(&g_s, &IMP_TBL_DEFAULT, &in, &out);
        if (k < tf) {
            UT_CHECK_EQ((out.health & IMP_H_NAV_STALE) != 0u, k > IMP_TBL_DEFAULT.nav_timeout);
        }
        if (mode_of(&out) == IMP_MODE_FINAL) {
            saw_final = 1u;
        }
        if ((k_miss == 0u) && ((out.health & IMP_H_EXPECTED_MISS) != 0u)) {
            k_miss = k;
        }
        UT_CHECK((out.health & FX_ST_MASK) == 0u);
    }
    /* no window was ever accepted: once the last epoch before the second burns has passed the
       prediction is final (u_uncal, x ~27.9 m), raised before the first second burn (x) starts */
    UT_CHECK(k_miss >= (t0 + (8u * IMP_TBL_DEFAULT.replan_period)));
    UT_CHECK(k_miss < out.tlm.on2_step[0]);
    /* epochs t0 + i N while t_a = t_p + 50 < the earliest second burn (x, ~t0 + 8385): 8 */
    UT_CHECK_EQ(out.tlm.plans_skipped, 8);
    UT_CHECK_EQ(out.tlm.plans, 1);                     /* only the START plan */
    UT_EQ(saw_final, 1u);
    UT_UEQ(mode_of(&out), IMP_MODE_DONE);
    UT_EQ(out.tlm.nav_age, tf);
}

/* A plan unfinished at its application epoch is late (spec 50 §5.4): START -> NO_SOLUTION (never
   fires); a re-plan -> the timeline in force stays. Tables that allow it are refused by
   imp_params_check (checked first); the module still behaves. */
UT_TEST(late_plans_keep_the_old_timeline)
{
    imp_params_t p = IMP_TBL_DEFAULT;
    imp_out_t out;
    imp_in_t in;
    uint32_t why = 0u;
    uint32_t k;
    uint32_t fired = 0u;
    p.plan_iter_per_step = 4u;
    p.plan_lead = 2u;
    p.cal_enable = 0u;          /* the constant nav samples below carry no thrust information */
    UT_EQ(imp_params_check(&p, &why), FSW_ERR_INVARIANT);
    UT_UEQ(why, IMP_WHY_LEAD);
    p.nav_gate_pos_q28 = INT32_MAX;   /* ... and must pass the gate (a saturating limit: none) */
    p.nav_gate_vel_q28 = INT32_MAX;
    /* START with t0 2 steps ahead: the example plan needs 17 units = 5 steps */
    (void)imp_init(&g_s, &p, &out);
    in = start_cmd(0u, 2u, 2u + T_EX_STEPS);
    imp_step(&g_s, &p, &in, &out);
    (void)run_until(&g_s, &p, &in, &out, 1u, 100u, IMP_MODE_NO_SOLUTION);
    UT_UEQ(mode_of(&out), IMP_MODE_NO_SOLUTION);
    UT_EQ(out.tlm.plans_late, 1);
    UT_EQ(out.tlm.plans_failed, 0);
    /* START with t0 far enough; every re-plan (>= 11 units = 3 steps) is late at t_p + 2 */
    (void)imp_init(&g_s, &p, &out);
    in = start_cmd(0u, 100u, 100u + T_EX_STEPS);
    imp_step(&g_s, &p, &in, &out);
    in.cmd = IMP_CMD_NONE;
    for (k = 1u; k <= (110u + T_EX_STEPS); k++) {
        in.step = k;
        if (((k - 100u) % 1000u) == 0u) {
            in.nav_step = k;   /* fresh at the epochs t0 + i N only: 100 s apart the monitor pauses */
        }
        imp_step(&g_s, &p, &in, &out);
        fired += (out.on_mask != 0u) ? 1u : 0u;
    }
    UT_UEQ(mode_of(&out), IMP_MODE_DONE);
    UT_CHECK(out.tlm.plans_late >= 1u);
    UT_EQ(out.tlm.plans, 1u + out.tlm.plans_late + out.tlm.plans_failed);
    UT_CHECK(fired > 2000u);    /* the START timeline flew */
}

/* Nav outlier gate (spec 50 §8): a sample off by far more than the gate plus the model allowance
   is discarded (nav_rej) and the previous one stays; consistent samples are accepted. */
/* Samples of the coasting example (ARMED: no thrust) at step k: -1 m/s on every axis; the CW
   coupling (2 w y' = 2.3 mm/s^2) moves them by < 2 cm over the 4 s used here. */
static void drifted_sample(imp_in_t *in, uint32_t k)
{
    uint32_t r;
    in->step = k;
    in->nav_step = k;
    for (r = 0u; r < IMP_NAX; r++) {
        in->nav_pos_mm[r] = EX_POS_MM[r] - (int32_t)(k * 100u);   /* 100 mm per step */
        in->nav_vel_cnt[r] = EX_VEL_CNT[r];
    }
}

UT_TEST(nav_outliers_are_rejected)
{
    imp_out_t out;
    imp_in_t in;
    (void)imp_init(&g_s, &IMP_TBL_DEFAULT, &out);
    in = start_cmd(0u, 100u, 100u + T_EX_STEPS);
    imp_step(&g_s, &IMP_TBL_DEFAULT, &in, &out);
    (void)run_until(&g_s, &IMP_TBL_DEFAULT, &in, &out, 1u, 9u, IMP_MODE_ARMED);
    drifted_sample(&in, 10u);
    imp_step(&g_s, &IMP_TBL_DEFAULT, &in, &out);
    UT_EQ(out.tlm.nav_rej, 0);
    UT_EQ(out.tlm.nav_age, 0);
    drifted_sample(&in, 20u);
    in.nav_pos_mm[1] += 100000;  /* +100 m on y */
    imp_step(&g_s, &IMP_TBL_DEFAULT, &in, &out);
    UT_EQ(out.tlm.nav_rej, 1);
    UT_EQ(out.tlm.nav_age, 10);
    drifted_sample(&in, 30u);
    in.nav_vel_cnt[2] += 30000;  /* +0.3 m/s on z' (gate 25 mm/s + 1.5 a_nom x 2 s since the last
                                    accepted sample = 0.145 m/s) */
    imp_step(&g_s, &IMP_TBL_DEFAULT, &in, &out);
    UT_EQ(out.tlm.nav_rej, 2);
    drifted_sample(&in, 40u);    /* consistent again: accepted */
    imp_step(&g_s, &IMP_TBL_DEFAULT, &in, &out);
    UT_EQ(out.tlm.nav_rej, 2);
    UT_EQ(out.tlm.nav_age, 0);
    UT_UEQ(out.health & FX_ST_MASK, 0u);
}

/* The interlock and the availability mask are the last gate (spec 50 §5.6): a timeline that asks
   for both thrusters of an axis in one step (forced here) gives neither, and INTERLOCK. */
UT_TEST(interlock_and_availability_are_the_last_gate)
{
    imp_out_t out;
    imp_in_t in;
    const uint32_t t0 = 100u;
    (void)imp_init(&g_s, &IMP_TBL_DEFAULT, &out);
    in = start_cmd(0u, t0, t0 + T_EX_STEPS);
    imp_step(&g_s, &IMP_TBL_DEFAULT, &in, &out);
    (void)run_until(&g_s, &IMP_TBL_DEFAULT, &in, &out, 1u, t0 + 2u, IMP_MODE_FIRING);
    UT_UEQ(mode_of(&out), IMP_MODE_FIRING);
    UT_UEQ(out.on_mask & 0x01u, 0x01u);     /* +x fires ... */
    in.avail_mask = 0x3Eu;                  /* ... until the executive withdraws it */
    (void)run_until(&g_s, &IMP_TBL_DEFAULT, &in, &out, t0 + 3u, t0 + 5u, IMP_MODE_FIRING);
    UT_UEQ(out.on_mask & 0x01u, 0u);
    UT_CHECK((out.on_mask & 0x08u) != 0u);   /* -y fires */
    UT_UEQ(out.health & IMP_H_INTERLOCK, 0u);
    g_s.act.thr2[1] = 2u;       /* y: second burn on +y ... */
    g_s.act.n2_g[1] = 0u;       /* ... from t_a: with -y's first burn in the same steps */
    in.step = t0 + 6u;
    imp_step(&g_s, &IMP_TBL_DEFAULT, &in, &out);
    UT_UEQ(out.on_mask & 0x0Cu, 0u);
    UT_CHECK((out.health & IMP_H_INTERLOCK) != 0u);
    UT_CHECK((out.tlm.health_sticky & IMP_H_INTERLOCK) != 0u);
}

UT_TEST(abort_turns_everything_off)
{
    imp_out_t out;
    imp_in_t in;
    uint32_t k;
    (void)imp_init(&g_s, &IMP_TBL_DEFAULT, &out);
    in = start_cmd(0u, 100u, 100u + T_EX_STEPS);
    imp_step(&g_s, &IMP_TBL_DEFAULT, &in, &out);
    in.cmd = IMP_CMD_NONE;
    for (k = 1u; k <= 150u; k++) {
        in.step = k;
        imp_step(&g_s, &IMP_TBL_DEFAULT, &in, &out);
    }
    UT_CHECK(out.on_mask != 0u);
    in.step = 151u;
    in.cmd = IMP_CMD_ABORT;
    imp_step(&g_s, &IMP_TBL_DEFAULT, &in, &out);
    UT_UEQ(out.on_mask, 0u);
    UT_UEQ(mode_of(&out), IMP_MODE_ABORTED);
    in.cmd = IMP_CMD_NONE;
    for (k = 152u; k <= 400u; k++) {
        in.step = k;
        imp_step(&g_s, &IMP_TBL_DEFAULT, &in, &out);
        UT_CHECK_EQ(out.on_mask, 0u);
    }
    in.step = 401u;
    in.cmd = IMP_CMD_CLEAR_FAULTS;
    imp_step(&g_s, &IMP_TBL_DEFAULT, &in, &out);
    UT_UEQ(mode_of(&out), IMP_MODE_IDLE);
    UT_UEQ(out.tlm.health_sticky & ~IMP_H_MODE, 0u);
}

UT_TEST(deterministic)
{
    imp_out_t o1;
    imp_out_t o2;
    imp_in_t in;
    uint32_t k;
    uint32_t j;
    (void)imp_init(&g_s, &IMP_TBL_DEFAULT, &o1);
    (void)imp_init(&g_s2, &IMP_TBL_DEFAULT, &o2);
    in = start_cmd(0u, 100u, 100u + T_EX_STEPS);
    for (k = 0u; k < 3000u; k++) {
        in.step = k;
        in.nav_step = k - (k % 10u);
        imp_step(&g_s, &IMP_TBL_DEFAULT, &in, &o1);
        imp_step(&g_s2, &IMP_TBL_DEFAULT, &in, &o2);
        in.cmd = IMP_CMD_NONE;
        UT_CHECK_UEQ(o1.on_mask, o2.on_mask);
        UT_CHECK_UEQ(o1.health, o2.health);
        for (j = 0u; j < IMP_NTHR; j++) {
            UT_CHECK_UEQ(o1.on_start_cnt[j], o2.on_start_cnt[j]);
            UT_CHECK_UEQ(o1.on_len_cnt[j], o2.on_len_cnt[j]);
        }
    }
    UT_CHECK_EQ(o1.tlm.t1_q29[0], o2.tlm.t1_q29[0]);
    UT_CHECK_EQ(o1.tlm.plans, o2.tlm.plans);
}

/* Sub-tick windows (spec 50 §5.2, §5.6): with the 1 ms grid every window lies inside its step,
   at most one per thruster, a burn that spans steps gives contiguous windows (a window ending
   at the step end continues at 0 in the next step), and no window of a burn is shorter than
   t_min unless the burn continues across a step boundary. */
UT_TEST(subtick_windows_are_contiguous_and_executable)
{
    const imp_params_t *p = &IMP_TBL_SUB1MS;
    imp_out_t out;
    imp_in_t in;
    uint32_t k;
    uint32_t j;
    uint32_t open[IMP_NTHR] = {0u, 0u, 0u, 0u, 0u, 0u};
    uint32_t len[IMP_NTHR] = {0u, 0u, 0u, 0u, 0u, 0u};
    uint32_t partial = 0u;
    const uint32_t t0 = 100u;
    const uint32_t tf = t0 + T_EX_STEPS;
    (void)imp_init(&g_s, p, &out);
    in = start_cmd(0u, t0, tf);
    imp_step(&g_s, p, &in, &out);
    in.cmd = IMP_CMD_NONE;
    for (k = 1u; k <= tf; k++) {
        in.step = k;
        imp_step(&g_s, p, &in, &out);
        UT_CHECK((out.health & (IMP_H_INTERLOCK | FX_ST_MASK)) == 0u);
        for (j = 0u; j < IMP_NTHR; j++) {
            bool on = (((uint32_t)out.on_mask >> j) & 1u) != 0u;
            uint32_t a = out.on_start_cnt[j];
            uint32_t b = a + out.on_len_cnt[j];
            if (on) {
                UT_CHECK((out.on_len_cnt[j] > 0u) && (b <= p->period_us));
                UT_CHECK_EQ(a % p->subtick_us, 0u);
                UT_CHECK((open[j] == 0u) || (a == 0u));          /* contiguous */
                partial += ((a != 0u) || (b != p->period_us)) ? 1u : 0u;
                len[j] = ((open[j] != 0u) ? len[j] : 0u) + out.on_len_cnt[j];
                open[j] = (b == p->period_us) ? 1u : 0u;
                if (open[j] == 0u) {
                    UT_CHECK(len[j] >= p->t_min_us);              /* the whole burn */
                }
            } else {
                UT_CHECK((open[j] == 0u) || (len[j] >= p->t_min_us));
                open[j] = 0u;
            }
        }
    }
    UT_CHECK(partial >= 3u);    /* the sub-tick grid is used (not only whole steps) */
    UT_UEQ(mode_of(&out), IMP_MODE_DONE);
}

int main(void)
{
    UT_CASES(cases) = {
        UT_CASE(default_table_passes_its_checks), UT_CASE(bad_tables_are_refused_with_a_reason),
        UT_CASE(init_gives_safe_outputs), UT_CASE(trig_kernels_are_symmetric_and_exact_at_zero),
        UT_CASE(paper_example_matches_the_spec), UT_CASE(mirrored_problem_gives_mirrored_plan),
        UT_CASE(infeasible_state_is_refused_without_attempts), UT_CASE(zero_coast_is_singular),
        UT_CASE(iteration_limit_gives_no_solution), UT_CASE(warm_start_is_tried_first),
        UT_CASE(best_rounding_is_no_worse_than_nearest), UT_CASE(resumable_job_is_bit_identical_to_one_shot),
        UT_CASE(avoided_thrusters_are_never_used), UT_CASE(subtick_rounding_meets_minimum_impulse_and_coast_rules),
        UT_CASE(start_is_refused_out_of_range), UT_CASE(infeasible_start_never_fires),
        UT_CASE(no_solution_start_never_fires), UT_CASE(timeline_fires_the_plan),
        UT_CASE(expected_miss_is_predicted_from_the_final_burns), UT_CASE(stale_nav_skips_replans_then_final),
        UT_CASE(late_plans_keep_the_old_timeline), UT_CASE(nav_outliers_are_rejected),
        UT_CASE(interlock_and_availability_are_the_last_gate), UT_CASE(abort_turns_everything_off),
        UT_CASE(deterministic), UT_CASE(subtick_windows_are_contiguous_and_executable),
    };
    return UT_RUN("imp", cases);
}
