/*
 * Impulse solver golden replay (spec 50-impulse §6 G3 and a G4 subset; spec 00 §6.4): host and
 * target. The vectors are generated at build time from the double reference
 * (tests/impulse/gen/imp_golden_gen.cpp, sim/impulse/imp_ref_solver) and never committed: the problems
 * as the fixed-point solver sees them (q28 state and target, q29 tau_f, q30 alpha of
 * IMP_TBL_DEFAULT; the reference solved the same dequantised problem with the table's guards),
 * and the reference results. The fixed-point solver runs each problem; its outputs go into a
 * CRC-32 digest per set, which each Cortex-M build must reproduce bit for bit (digest.cmake).
 * The live comparison with more cases (500 + 200 + the w x tau_f grid, G1, G2, G5) stays in
 * test_imp_golden_host.cpp (host only).
 *
 * Sets:
 *  G3: the paper's example. Iterates k = 0..5 of the pure Newton attempts from (0, tau_f) with
 *    the rule's polarities (x-y 0xC, z 0x1): imp_attempt with max_iter = k leaves iterate k and
 *    its residual in the workspace. Then the full plan (imp_solve), checked as a G4 case.
 *  G4: imp_mc's seeded draws (seed 1): 64 of the nominal box (+-5 km / +-1 m/s) and 32 of the
 *    wide box (+-20 km / +-5 m/s, mostly INFEASIBLE or NO_SOLUTION).
 *
 * Tolerances (spec 50 §6, in LSB of q29 at the table's orbit rate, 1 LSB = 1.65 us; the
 * generator adds 0.5 LSB for the rounded reference time, the errors being integers):
 *  G3: every iterate's times within 1 ms (GV_IMP_TOL_1MS_Q29), the final iterate's within
 *    0.25 ms, and iterate k is reached after exactly k Newton steps on both sides. Residuals:
 *    both sides evaluate F at their own iterate, so dF = J dT + E_F to first order (dT <= 1e-6
 *    rad: the second-order term is far below 1 LSB): |dF_i| <= ||J||inf max|dT| / 2 (q29 -> q28)
 *    + E_F (16 LSB, the residual-evaluation allowance of test_imp_golden_host.cpp: 2x the
 *    measured 3-7 LSB floor) + 1 (rounded reference, margin). ||J||inf comes per iterate from
 *    the reference (ceil(256 x), jn_q8), so the check is 512 |dF| <= jn_q8 max|dT| + 512 * 17.
 *  G4 (and the G3 plan): the same outcome; for valid plans the same polarity pattern unless the
 *    two patterns are a dv tie (|sum dv_fx - sum dv_ref| <= 2 dv_tie, spec 50 §3.5: then only the
 *    outcome is compared); the same `how` per subsystem; iterations within +-1; |dT| <= 0.25 ms
 *    (GV_IMP_TOL_025MS_Q29) and within the derived bound of test_imp_golden_host.cpp: the fixed
 *    schedule satisfies |F_fx| <= fres, so |F(T_fx)| <= fres + E_F and
 *    |dT| <= ||J^-1||inf (fres + E_F) 2^-28 rad + 1 LSB q29 (validity clamp) + 0.5 (rounded
 *    reference): 256 |dT| <= jinv_q8 2 (fres + 16) + 384 in LSB q29; dv per subsystem
 *    sum_k alpha (T1 + tau_f - T2) differs by the alpha-weighted time differences plus the two
 *    roundings: 2^31 |ddv| <= sum_k alpha_max_q30 (|dT1| + |dT2|) + 2^31 (LSB q28); no fx status
 *    outside failed attempts (st_ok = 0).
 */
#include "imp.h"
#include "imp_tables.h"
#include "ut.h"
#include "gv_imp.h"
#include "gv_print.h"
#include "gv_imp_vectors.h"

#if defined(GV_MISSING)

UT_TEST(golden_vectors_present)
{
    ut_puts("golden vectors missing: " GV_MISSING "\n"
            "  build the host preset first (tools/test.sh does), or set FSW_HOST_BUILD_DIR\n");
    UT_CHECK(0);
}

int main(void)
{
    UT_CASES(cases) = {UT_CASE(golden_vectors_present)};
    return UT_RUN("imp_golden_replay", cases);
}

#else

#define E_F_LSB 16

static imp_ws_t s_ws;
static imp_solution_t s_sol;

static uint32_t uabs_diff(int32_t a, int32_t b)
{
    int64_t d = (int64_t)a - (int64_t)b;
    return (uint32_t)((d < 0) ? -d : d);
}

static void problem_of(const gv_imp_case_t *c, imp_problem_t *pr)
{
    uint32_t i;
    pr->tauf_q29 = c->tauf_q29;
    for (i = 0u; i < IMP_NX; i++) {
        pr->x0_q28[i] = c->x0_q28[i];
        pr->xt_q28[i] = c->xt_q28[i];
    }
    for (i = 0u; i < IMP_NTHR; i++) {
        pr->alpha_q30[i] = c->alpha_q30[i];
    }
    pr->warm_mask = 0u;
    pr->replan = 0u;
    pr->warm_pattern = 0u;
    pr->thr_off = 0u;
    for (i = 0u; i < IMP_NAX; i++) {
        pr->warm_t1_q29[i] = 0;
        pr->warm_t2_q29[i] = 0;
    }
}

static void put_us(uint32_t lsb)
{
    /* 1 LSB q29 = 2^-29 / w s = 1e18 / (w_nrad 2^29) ns (1646 ns at 400 km); printed to the us */
    uint64_t ns_per_lsb = UINT64_C(1000000000000000000) / ((uint64_t)IMP_TBL_DEFAULT.omega_nradps << 29);
    ut_put_u64(((uint64_t)lsb * ns_per_lsb) / 1000u);
    ut_puts(" us");
}

static void digest_solution(gv_dg_t *d, const imp_solution_t *s)
{
    uint32_t i;
    gv_dg_u32(d, ((uint32_t)s->outcome << 24) | ((uint32_t)s->pattern << 16) | ((uint32_t)s->marginal << 8));
    for (i = 0u; i < IMP_NSUB; i++) {
        gv_dg_u32(d, ((uint32_t)s->how[i] << 24) | ((uint32_t)s->iters[i] << 16) | ((uint32_t)s->sub_outcome[i] << 8) |
                         (uint32_t)s->last_fail[i]);
        gv_dg_u32(d, (uint32_t)s->attempts[i]);
    }
    for (i = 0u; i < IMP_FAIL_N; i++) {
        gv_dg_u32(d, (uint32_t)s->n_fail[i]);
    }
    gv_dg_u32(d, (uint32_t)s->iters_total);
    gv_dg_i32n(d, s->t1_q29, IMP_NAX);
    gv_dg_i32n(d, s->t2_q29, IMP_NAX);
    gv_dg_i32n(d, s->fres_lsb, IMP_NSUB);
    gv_dg_i32n(d, s->dv_q28, IMP_NSUB);
    gv_dg_i32n(d, s->dv1_q28, IMP_NAX);
    gv_dg_i32n(d, s->dv2_q28, IMP_NAX);
    gv_dg_i32n(d, s->rho_q28, IMP_NAX);
    gv_dg_u32(d, s->st_ok);
    gv_dg_u32(d, s->st_fail);
    d->n++;
}

typedef struct {
    uint32_t n, valid, same, ties, bad;
    uint32_t dt_max;       /* LSB q29 */
    uint32_t it_diff_max;
    uint32_t ddv_max;      /* LSB q28 */
} g4_stats_t;

static void say_case(const char *set, uint32_t idx, const char *what, int64_t a, int64_t b)
{
    ut_puts("  ");
    ut_puts(set);
    ut_puts("[");
    ut_put_u64(idx);
    ut_puts("]: ");
    ut_puts(what);
    ut_puts(" fixed ");
    ut_put_i64(a);
    ut_puts(" ref/bound ");
    ut_put_i64(b);
    ut_puts("\n");
}

/* Solve one problem and compare with the reference plan; returns 1 on a violation. */
static uint32_t solve_case(const char *set, uint32_t idx, const gv_imp_case_t *c, gv_dg_t *d, g4_stats_t *st)
{
    imp_problem_t pr;
    const imp_solution_t *s = &s_sol;
    uint32_t bad = 0u;
    uint32_t sub;
    uint32_t r;
    int32_t amax = 0;
    problem_of(c, &pr);
    imp_solve(&s_ws, &IMP_TBL_DEFAULT, &pr, &s_sol);
    digest_solution(d, s);
#if defined(GV_DUMP)
    /* -DGV_DUMP: the running digest after each record, to find the first differing one */
    say_case(set, idx, "running digest", (int64_t)d->crc, (int64_t)d->n);
#endif
    st->n++;
    if (s->st_ok != 0u) {
        say_case(set, idx, "fx status outside failed attempts", (int64_t)s->st_ok, 0);
        bad = 1u;
    }
    if ((uint32_t)s->outcome != c->outcome) {
        say_case(set, idx, "outcome", (int64_t)s->outcome, (int64_t)c->outcome);
        return 1u;
    }
    if (c->outcome != IMP_SOL_VALID) {
        return bad;
    }
    st->valid++;
    if ((uint32_t)s->pattern != c->pattern) {
        int32_t dvf = s->dv_q28[0] + s->dv_q28[1];
        int32_t dvr = c->dv_q28[0] + c->dv_q28[1];
        say_case(set, idx, "pattern (a dv tie is allowed)", (int64_t)s->pattern, (int64_t)c->pattern);
        if ((int64_t)uabs_diff(dvf, dvr) > 2 * (int64_t)IMP_TBL_DEFAULT.dv_tie_q28) {
            say_case(set, idx, "pattern differs beyond a dv tie: |ddv|", (int64_t)uabs_diff(dvf, dvr),
                     2 * (int64_t)IMP_TBL_DEFAULT.dv_tie_q28);
            bad = 1u;
        }
        st->ties++;
        return bad;
    }
    st->same++;
    for (r = 0u; r < IMP_NTHR; r++) {
        amax = (c->alpha_q30[r] > amax) ? c->alpha_q30[r] : amax;
    }
    for (sub = 0u; sub < IMP_NSUB; sub++) {
        uint32_t idiff = uabs_diff((int32_t)s->iters[sub], (int32_t)c->iters[sub]);
        uint32_t ax0 = (sub == IMP_SUB_XY) ? 0u : 2u;
        uint32_t nax = (sub == IMP_SUB_XY) ? 2u : 1u;
        int64_t dbound = ((int64_t)c->jinv_q8 * 2 * ((int64_t)s->fres_lsb[sub] + E_F_LSB)) + 384;
        int64_t dvsum = 0;
        uint32_t ddv = uabs_diff(s->dv_q28[sub], c->dv_q28[sub]);
        st->it_diff_max = (idiff > st->it_diff_max) ? idiff : st->it_diff_max;
        if (idiff > 1u) {
            say_case(set, idx, "iterations", (int64_t)s->iters[sub], (int64_t)c->iters[sub]);
            bad = 1u;
        }
        if ((uint32_t)s->how[sub] != c->how[sub]) {
            say_case(set, idx, "how", (int64_t)s->how[sub], (int64_t)c->how[sub]);
            bad = 1u;
        }
        for (r = ax0; r < (ax0 + nax); r++) {
            uint32_t d1 = uabs_diff(s->t1_q29[r], c->t1_q29[r]);
            uint32_t d2 = uabs_diff(s->t2_q29[r], c->t2_q29[r]);
            uint32_t dm = (d1 > d2) ? d1 : d2;
            st->dt_max = (dm > st->dt_max) ? dm : st->dt_max;
            if ((int64_t)dm > (int64_t)GV_IMP_TOL_025MS_Q29) {
                say_case(set, idx, "|dT| [LSB q29] > 0.25 ms", (int64_t)dm, GV_IMP_TOL_025MS_Q29);
                bad = 1u;
            }
            if (((int64_t)dm * 256) > dbound) {
                say_case(set, idx, "|dT| x 256 [LSB q29] > derived bound", (int64_t)dm * 256, dbound);
                bad = 1u;
            }
            dvsum += (int64_t)amax * ((int64_t)d1 + (int64_t)d2);
        }
        st->ddv_max = (ddv > st->ddv_max) ? ddv : st->ddv_max;
        if (((int64_t)ddv * INT64_C(2147483648)) > (dvsum + INT64_C(2147483648))) {
            say_case(set, idx, "dv [LSB q28]", (int64_t)s->dv_q28[sub], (int64_t)c->dv_q28[sub]);
            bad = 1u;
        }
    }
    return bad;
}

static void print_stats(const char *set, const g4_stats_t *st)
{
    ut_puts(set);
    ut_puts(": ");
    ut_put_u64(st->n);
    ut_puts(" problems, ");
    ut_put_u64(st->valid);
    ut_puts(" valid, same pattern ");
    ut_put_u64(st->same);
    ut_puts(", dv ties ");
    ut_put_u64(st->ties);
    ut_puts("; max |dT| ");
    ut_put_u64(st->dt_max);
    ut_puts(" LSB q29 (");
    put_us(st->dt_max);
    ut_puts("), max |d iterations| ");
    ut_put_u64(st->it_diff_max);
    ut_puts(", max |d dv| ");
    ut_put_u64(st->ddv_max);
    ut_puts(" LSB q28; violations ");
    ut_put_u64(st->bad);
    ut_puts("\n");
}

static void check_inputs(const char *name, const void *recs, uint32_t n, uint32_t rec_bytes, uint32_t crc)
{
    gv_dg_t d;
    uint32_t k;
    gv_dg_begin(&d);
    for (k = 0u; k < n; k++) {
        gv_dg_words(&d, (const uint8_t *)recs + ((size_t)k * rec_bytes), rec_bytes);
        d.n++;
    }
    UT_CHECK_UEQ(d.crc, crc);
    gv_dg_print(name, "", &d);
}

UT_TEST(golden_replay_g3_example)
{
    gv_dg_t d;
    g4_stats_t st = {0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u};
    imp_problem_t pr;
    uint32_t k;
    uint32_t dt_max = 0u;
    uint32_t df_max = 0u;
    uint32_t bad = 0u;
    UT_CHECK_UEQ(gv_imp_table_fp(&IMP_TBL_DEFAULT), GV_IMP_TABLE_FP);
    check_inputs("imp_g3_vectors", GV_IMP_G3, GV_IMP_G3_N, (uint32_t)sizeof(GV_IMP_G3[0]), GV_IMP_G3_CRC);
    problem_of(&GV_IMP_G3_CASE, &pr);
    gv_dg_begin(&d);
    for (k = 0u; k < GV_IMP_G3_N; k++) {
        const gv_imp_iter_t *v = &GV_IMP_G3[k];
        imp_params_t p = IMP_TBL_DEFAULT;
        const int32_t z1[2] = {0, 0};
        const int32_t z2[2] = {pr.tauf_q29, pr.tauf_q29};
        uint32_t iters = 0u;
        uint32_t fres = 0u;
        fx_status_t ast = 0u;
        uint32_t nax = (v->sub == IMP_SUB_XY) ? 2u : 1u;
        bool last = ((k + 1u) == GV_IMP_G3_N) || (GV_IMP_G3[k + 1u].sub != v->sub);
        uint32_t dmax = 0u;
        uint32_t res;
        uint32_t a;
        p.max_iter = (uint8_t)v->k;
        res = imp_attempt(&s_ws, &p, &pr, v->sub, v->pat, z1, z2, &iters, &fres, &ast);
        gv_dg_u32(&d, res);
        gv_dg_u32(&d, iters);
        gv_dg_u32(&d, fres);
        gv_dg_u32(&d, ast);
        gv_dg_i32n(&d, s_ws.t1_q29, nax);
        gv_dg_i32n(&d, s_ws.t2_q29, nax);
        gv_dg_i32n(&d, s_ws.f_q28, 2u * nax);
        d.n++;
#if defined(GV_DUMP)
        say_case("G3 iterate", k, "running digest", (int64_t)d.crc, (int64_t)d.n);
#endif
        UT_CHECK_EQ(ast, 0);
        UT_CHECK_EQ(iters, v->k);
        for (a = 0u; a < nax; a++) {
            uint32_t d1 = uabs_diff(s_ws.t1_q29[a], v->t1_q29[a]);
            uint32_t d2 = uabs_diff(s_ws.t2_q29[a], v->t2_q29[a]);
            dmax = (d1 > dmax) ? d1 : dmax;
            dmax = (d2 > dmax) ? d2 : dmax;
        }
        dt_max = (dmax > dt_max) ? dmax : dt_max;
        if ((int64_t)dmax > (int64_t)GV_IMP_TOL_1MS_Q29) {
            say_case("G3 iterate", k, "|dT| [LSB q29] > 1 ms", (int64_t)dmax, GV_IMP_TOL_1MS_Q29);
            bad = 1u;
        }
        if (last && ((int64_t)dmax > (int64_t)GV_IMP_TOL_025MS_Q29)) {
            say_case("G3 final iterate", k, "|dT| [LSB q29] > 0.25 ms", (int64_t)dmax, GV_IMP_TOL_025MS_Q29);
            bad = 1u;
        }
        for (a = 0u; a < (2u * nax); a++) {
            uint32_t df = uabs_diff(s_ws.f_q28[a], v->f_q28[a]);
            int64_t bound = ((int64_t)v->jn_q8 * (int64_t)dmax) + (512 * (E_F_LSB + 1));
            df_max = (df > df_max) ? df : df_max;
            if (((int64_t)df * 512) > bound) {
                say_case("G3 iterate", k, "|dF| x 512 [LSB q28] > bound", (int64_t)df * 512, bound);
                bad = 1u;
            }
        }
    }
    gv_dg_print("imp_g3_iterates", "", &d);
    gv_dg_begin(&d);
    bad += solve_case("G3 plan", 0u, &GV_IMP_G3_CASE, &d, &st);
    gv_dg_print("imp_g3_plan", "", &d);
    ut_puts("G3 example: ");
    ut_put_u64(GV_IMP_G3_N);
    ut_puts(" iterates, max |dT| ");
    ut_put_u64(dt_max);
    ut_puts(" LSB q29 (");
    put_us(dt_max);
    ut_puts("), max |dF| ");
    ut_put_u64(df_max);
    ut_puts(" LSB q28; plan max |dT| ");
    ut_put_u64(st.dt_max);
    ut_puts(" LSB q29 (");
    put_us(st.dt_max);
    ut_puts(")\n");
    UT_CHECK_EQ(GV_IMP_G3_CASE.outcome, IMP_SOL_VALID);
    UT_CHECK_EQ(st.same, 1);
    UT_CHECK_EQ(bad, 0);
}

UT_TEST(golden_replay_g4_monte_carlo)
{
    gv_dg_t d;
    g4_stats_t st = {0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u};
    uint32_t k;
    UT_CHECK_UEQ(gv_imp_table_fp(&IMP_TBL_DEFAULT), GV_IMP_TABLE_FP);
    check_inputs("imp_g4_vectors", GV_IMP_G4, GV_IMP_G4_N, (uint32_t)sizeof(GV_IMP_G4[0]), GV_IMP_G4_CRC);
    gv_dg_begin(&d);
    for (k = 0u; k < GV_IMP_G4_N; k++) {
        st.bad += solve_case("G4", k, &GV_IMP_G4[k], &d, &st);
    }
    gv_dg_print("imp_g4_plans", "", &d);
    print_stats("G4 subset", &st);
    UT_CHECK_EQ(st.bad, 0);
    UT_CHECK_EQ(st.n, GV_IMP_G4_N);
}

int main(void)
{
    UT_CASES(cases) = {UT_CASE(golden_replay_g3_example), UT_CASE(golden_replay_g4_monte_carlo)};
    return UT_RUN("imp_golden_replay", cases);
}

#endif /* GV_MISSING */
