/*
 * Observer golden replay (spec 10-observer §5 single-step vectors, spec 00 §6.4): host and
 * target. The vectors are generated at build time from the double reference in closed loop
 * with the exact plant (tests/observer/gen/obs_golden_gen.cpp) and never committed: the three runs on
 * which spec 10 S0-8 requires the golden bounds, S0-5 nominal and S0-5 gyro noise seed 0 on
 * obs_50hz_paper, S0-7 nominal on obs_50hz_phys, and the S0-9 authority case (S0-5 nominal with
 * the command vector-limited at 1.2 deg/s), whose CMD_LIMITED / CMD_LIMIT_PERSIST vectors give
 * the flag comparison set bits; per run the first 200 steps (0-4 s: the initialising sample, P
 * collapsing from P0, the largest gains) and every 30th (S0-5, to 120 s) or 150th step (S0-7, to
 * 600 s) after them. Each vector holds the reference state before
 * step n quantised to the flight formats, the step's gyro counts, the reference outputs of one
 * step from exactly that state, and the bounds of that step. The fixed-point obs_step is loaded
 * with the state (white box: every field the step reads), run once and compared; the fixed-point
 * outputs of every vector go into a CRC-32 digest per set, which each Cortex-M build must
 * reproduce bit for bit (digest.cmake, FSW_HOST_BUILD_DIR). The live comparison over whole runs
 * stays in test_obs_golden_host.cpp (host only).
 *
 * Loaded state (obs.c): x_q29, kappa_q28, p_q30 (upper triangle mirrored: the flight code keeps P
 * exactly symmetric and reads both triangles), qres_q29 (error-feedback residual of to_counts),
 * u_prev_q29 (only a sequence gap reads it), limited_run (CMD_LIMIT_PERSIST), last_seq = seq - 1
 * with have_seq (so d = 1), initialized, lost = false, invalid_run = good_run = 0; the counters
 * and sticky health from obs_init. The first vector of a set is the initialising sample: the
 * state is obs_init's and the step runs start_estimate. The scratch (f_q28, t_q30, phi_q, gam_q)
 * is filled with a pattern; every 16th vector is run twice with different patterns and must give
 * identical outputs, proving the step never reads scratch before writing it.
 *
 * Bounds, derived from the operation chain as in test_obs_golden_host.cpp, evaluated by the
 * generator on each step's reference operands and stored as integers (errors are integers:
 * err <= b iff err <= floor(b)). LSB_x = 2^-29, LSB_k = 2^-28, LSB_P = 2^-30; channels c = 0, 1
 * are updated in sequence; amp_j = |L_j1| 2^(ls_j - ls_1) is how channel 1's gain scales an
 * innovation error of 1 LSB_x into state j; d = 0 or 1 is the largest command difference in
 * counts between the two implementations (more fails the vector).
 *  command: u = -D x from the same x rounds once to q29 (and the vector limit u bdot_max / |u|inf,
 *    if active, once more through the reciprocal) and once to counts with the same residual;
 *    the two can land on either side of a half count: |dcnt| <= 1. The state sees u only as
 *    counts, so the limit adds nothing to the other bounds beyond the d = 1 case.
 *  kappa: channel 0's innovation is exact on both sides (counts and the loaded state are
 *    exact), its correction rounds once (0.5 LSB_k); channel 1's innovation inherits channel 0's
 *    rounding of x_1 (<= 1 LSB_x with the gain's own rounding), which its gain turns into
 *    0.5 amp_6 LSB_k, plus its rounding (0.5). bk = 1 + 0.5 amp_6 + 1 (margin: clamp and
 *    rounding ties) + 0.5 (the stored reference value is rounded).
 *  x-hat: after the update dx_k <= 1 + amp_k. The prediction x+ = Phi(kappa) x + Gamma(kappa) u
 *    carries sum_k |Phi_jk| dx_k (this step's Phi(kappa), row by row), rounds once (0.5) and
 *    adds: the rounding of each Phi(kappa), Gamma(kappa) entry (0.5 LSB of q_phi0, q_gam0)
 *    times |x_k|, |u_k|; the kappa difference (<= bk LSB_k) through Phi_k x + Gamma_k u; for
 *    d = 1, sum_u |Gamma_ju| 2^act_shift (one count is 2^act_shift LSB_x); +1 margin; +0.5.
 *  P_s: each update rounds L (0.5 LSB of q28 = 2 LSB_P, times |P| <= 1.44) and each product
 *    (0.5); channel 1 also inherits channel 0's rounding (<= 1 + 2 * 1.44) through L_1 and the
 *    subtraction, scaled by ||L_1||inf: dP_upd <= (1 + 2.88)(1 + ||L_1||inf) + 1. The
 *    prediction rounds the F_s entries (2 LSB_P, twice, times ||P||), F P and (F P) F^T once each,
 *    and carries dP_upd through ||F_s||inf^2: ||F_s||^2 dP_upd + 2 * 2 * 1.44 ||F_s|| +
 *    0.5 ||F_s|| + 1.5. The regressor column f = Phi_k x + Gamma_k u of F_s is built from the
 *    post-update x (difference dx above): df_s,i = sum_j |Phi_k,ij| dx_j 2^(1 + ls_k - ls_i)
 *    LSB_P, and dP+ = dF P F^T + F P dF^T gives 2 max_i |df_s,i| ||P_s row 6||_1 ||F_s||. Beyond
 *    the live test: the kappa difference in the Phi block, 2 (bk 2^-28) ||Phi_k,s||inf ||P_s||inf
 *    ||F_s||inf; for d = 1, one count in the regressor, df_u,i = sum_u |Gamma_k,iu| 2^act_shift
 *    with the same scaling; +0.5 for the stored reference. Every P entry (upper triangle) is
 *    checked against the one bound.
 *  Flags: equal, bit for bit, to those the reference decides (CMD_LIMITED, CMD_LIMIT_PERSIST,
 *    K_CLAMP_*, COV_CLIP, INNOV_HIGH; all others and the fx status bits 0-7 zero), except a
 *    don't-care bit when the reference value lies within 1e-6 of its threshold.
 * Spec 10 §5 expects <= 4 LSB (x, kappa, u) and <= 8 LSB (P_s); the replay prints the measured
 * maxima next to the ratios to the per-step bounds.
 */
#include "obs.h"
#include "obs_tables.h"
#include "ut.h"
#include "gv_obs.h"
#include "gv_print.h"
#include "gv_obs_vectors.h"

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
    return UT_RUN("obs_golden_replay", cases);
}

#else

#define NZ OBS_NZ

typedef struct {
    uint32_t n;          /* vectors compared */
    uint32_t bad;        /* vectors outside a bound */
    uint32_t cnt1;       /* vectors with a one-count command difference */
    int32_t  ex, ex0;    /* largest x-hat error, LSB: all vectors / equal commands */
    int32_t  ek, ep;     /* largest kappa and P_s errors, LSB */
    uint32_t rx, rk, rp; /* largest error / bound, per mille */
    int32_t  ecnt;
} stats_t;

/* Vectors from this step on (after the dense first 4 s) are also summarised on their own. */
#define GV_LATE_SEQ 200u

static int32_t max_i32(int32_t a, int32_t b) { return (a > b) ? a : b; }
static uint32_t max_u32(uint32_t a, uint32_t b) { return (a > b) ? a : b; }

static void merge(stats_t *a, const stats_t *b)
{
    a->n += b->n;
    a->bad += b->bad;
    a->cnt1 += b->cnt1;
    a->ex = max_i32(a->ex, b->ex);
    a->ex0 = max_i32(a->ex0, b->ex0);
    a->ek = max_i32(a->ek, b->ek);
    a->ep = max_i32(a->ep, b->ep);
    a->rx = max_u32(a->rx, b->rx);
    a->rk = max_u32(a->rk, b->rk);
    a->rp = max_u32(a->rp, b->rp);
    a->ecnt = max_i32(a->ecnt, b->ecnt);
}

static obs_state_t s_state;
static obs_state_t s_twin;
static obs_out_t s_out;
static obs_out_t s_twin_out;

static uint32_t uabs_diff(int32_t a, int32_t b)
{
    int64_t d = (int64_t)a - (int64_t)b;
    return (uint32_t)((d < 0) ? -d : d);
}

static void fill_scratch(obs_state_t *s, uint32_t pattern)
{
    uint32_t i;
    for (i = 0u; i < (NZ * NZ); i++) {
        s->t_q30[i] = (int32_t)(pattern + i);
    }
    for (i = 0u; i < (OBS_NX * OBS_NX); i++) {
        s->f_q28[i] = (int32_t)(pattern ^ (i * 0x9E3779B9u));
        s->phi_q[i] = (int32_t)(~pattern ^ i);
    }
    for (i = 0u; i < OBS_NX; i++) {
        s->fk_q28[i] = (int64_t)(pattern ^ (i * 0x9E3779B9u)) * 3;
    }
    for (i = 0u; i < (OBS_NX * OBS_NU); i++) {
        s->gam_q[i] = (int32_t)(pattern - i);
    }
}

static void load(obs_state_t *s, obs_out_t *o, const obs_params_t *p, const gv_obs_t *v, uint32_t pattern)
{
    uint32_t i;
    uint32_t j;
    uint32_t m = 0u;
    (void)obs_init(s, p, o);
    fill_scratch(s, pattern);
    if (v->init != 0u) {
        for (i = 0u; i < OBS_NX; i++) {
            s->x_q29[i] = v->x_q29[i];
        }
        s->kappa_q28 = v->kappa_q28;
        for (i = 0u; i < NZ; i++) {
            for (j = i; j < NZ; j++) {
                s->p_q30[(i * NZ) + j] = v->p_q30[m];
                s->p_q30[(j * NZ) + i] = v->p_q30[m];
                m++;
            }
        }
        for (i = 0u; i < OBS_NU; i++) {
            s->qres_q29[i] = v->qres_q29[i];
            s->u_prev_q29[i] = v->u_prev_q29[i];
        }
        s->last_seq = v->seq - 1u;
        s->have_seq = true;
        s->initialized = true;
        s->lost = false;
        s->invalid_run = 0u;
        s->good_run = 0u;
        s->limited_run = v->limited_run;
    }
}

static void step(obs_state_t *s, obs_out_t *o, const obs_params_t *p, const gv_obs_t *v, uint32_t pattern)
{
    obs_in_t in;
    in.seq = v->seq;
    in.gyro_cnt[0] = v->gyro_cnt[0];
    in.gyro_cnt[1] = v->gyro_cnt[1];
    in.stale = 0u;
    in.sat = 0u;
    load(s, o, p, v, pattern);
    obs_step(s, p, &in, o);
}

/* Everything the step produced, word by word (also the twin-run comparison). */
static void digest_out(gv_dg_t *d, const obs_state_t *s, const obs_out_t *o)
{
    gv_dg_i32n(d, o->bdot_cmd_cnt, OBS_NU);
    gv_dg_u32(d, o->health);
    gv_dg_i32n(d, s->x_q29, OBS_NX);
    gv_dg_i32(d, s->kappa_q28);
    gv_dg_i32n(d, s->p_q30, NZ * NZ);
    gv_dg_i32n(d, s->qres_q29, OBS_NU);
    gv_dg_i32n(d, s->u_prev_q29, OBS_NU);
    gv_dg_i32n(d, o->tlm.u_q29, OBS_NU);
    gv_dg_i32n(d, o->tlm.e_q29, OBS_NY);
    gv_dg_i32n(d, o->tlm.d2_q16, OBS_NY);
    gv_dg_u32(d, o->tlm.health_sticky);
    gv_dg_u32(d, s->limited_run);
    d->n++;
}

static uint32_t per_mille(uint32_t err, int32_t bound)
{
    return (bound > 0) ? (uint32_t)(((uint64_t)err * 1000u) / (uint64_t)bound) : ((err == 0u) ? 0u : 1000000u);
}

static void put_milli(uint32_t v)
{
    uint32_t f = v % 1000u;
    ut_put_u64(v / 1000u);
    ut_puts(".");
    ut_puts((f < 100u) ? ((f < 10u) ? "00" : "0") : "");
    ut_put_u64(f);
}

static void track(uint32_t err, int32_t bound, int32_t *emax, uint32_t *rmax, uint32_t *bad)
{
    uint32_t r = per_mille(err, bound);
    if ((int64_t)err > (int64_t)*emax) {
        *emax = (int32_t)err;
    }
    if (r > *rmax) {
        *rmax = r;
    }
    if ((int64_t)err > (int64_t)bound) {
        *bad = 1u;
    }
}

static void report_bad(const char *set, uint32_t idx, const gv_obs_t *v, const char *what, uint32_t err, int32_t bound)
{
    ut_puts("  ");
    ut_puts(set);
    ut_puts(" vector ");
    ut_put_u64(idx);
    ut_puts(" (seq ");
    ut_put_u64(v->seq);
    ut_puts("): ");
    ut_puts(what);
    ut_puts(" error ");
    ut_put_u64(err);
    ut_puts(" > bound ");
    ut_put_i64(bound);
    ut_puts("\n");
}

/* Compare one vector; returns 1 when it is outside a bound (details printed for the first few). */
static uint32_t compare(const char *set, uint32_t idx, const gv_obs_t *v, const obs_state_t *s, const obs_out_t *o,
                        stats_t *st, bool verbose)
{
    uint32_t bad = 0u;
    uint32_t dcnt = 0u;
    uint32_t d;
    uint32_t i;
    uint32_t j;
    uint32_t m = 0u;
    uint32_t mask = ~v->health_dc;
    for (i = 0u; i < OBS_NU; i++) {
        uint32_t e = uabs_diff(o->bdot_cmd_cnt[i], v->cmd_cnt[i]);
        dcnt = (e > dcnt) ? e : dcnt;
    }
    if ((int64_t)dcnt > (int64_t)st->ecnt) {
        st->ecnt = (int32_t)dcnt;
    }
    if (dcnt > 1u) {
        bad = 1u;
        if (verbose) {
            report_bad(set, idx, v, "command [count]", dcnt, 1);
        }
    }
    st->cnt1 += (dcnt == 1u) ? 1u : 0u;
    d = (dcnt > 0u) ? 1u : 0u;
    for (i = 0u; i < OBS_NX; i++) {
        uint32_t b0 = 0u;
        uint32_t e = uabs_diff(s->x_q29[i], v->x1_q29[i]);
        track(e, v->bx[d][i], &st->ex, &st->rx, &b0);
        if ((d == 0u) && ((int64_t)e > (int64_t)st->ex0)) {
            st->ex0 = (int32_t)e;
        }
        if ((b0 != 0u) && verbose) {
            report_bad(set, idx, v, "x_hat [LSB q29]", e, v->bx[d][i]);
        }
        bad |= b0;
    }
    {
        uint32_t b0 = 0u;
        uint32_t e = uabs_diff(s->kappa_q28, v->kappa1_q28);
        track(e, v->bk, &st->ek, &st->rk, &b0);
        if ((b0 != 0u) && verbose) {
            report_bad(set, idx, v, "kappa [LSB q28]", e, v->bk);
        }
        bad |= b0;
    }
    for (i = 0u; i < NZ; i++) {
        for (j = i; j < NZ; j++) {
            uint32_t b0 = 0u;
            uint32_t e = uabs_diff(s->p_q30[(i * NZ) + j], v->p1_q30[m]);
            track(e, v->bp[d], &st->ep, &st->rp, &b0);
            if ((b0 != 0u) && verbose) {
                report_bad(set, idx, v, "P_s [LSB q30]", e, v->bp[d]);
            }
            bad |= b0;
            m++;
        }
    }
    if ((o->health & mask) != (v->health & mask)) {
        if (verbose) {
            ut_puts("  ");
            ut_puts(set);
            ut_puts(" vector ");
            ut_put_u64(idx);
            ut_puts(": health ");
            ut_put_u32hex(o->health);
            ut_puts(" expected ");
            ut_put_u32hex(v->health);
            ut_puts("\n");
        }
        bad = 1u;
    }
    return bad;
}

static void print_stats(const char *set, const char *part, const stats_t *st)
{
    ut_puts("obs ");
    ut_puts(set);
    ut_puts(part);
    ut_puts(": ");
    ut_put_u64(st->n);
    ut_puts(" vectors; max |fixed - ref|: x_hat ");
    ut_put_i64(st->ex0);
    ut_puts(" LSB q29 with equal commands, ");
    ut_put_i64(st->ex);
    ut_puts(" overall (");
    put_milli(st->rx);
    ut_puts(" of bound), kappa ");
    ut_put_i64(st->ek);
    ut_puts(" LSB q28 (");
    put_milli(st->rk);
    ut_puts("), P_s ");
    ut_put_i64(st->ep);
    ut_puts(" LSB q30 (");
    put_milli(st->rp);
    ut_puts("), command ");
    ut_put_i64(st->ecnt);
    ut_puts(" count (");
    ut_put_u64(st->cnt1);
    ut_puts(" vectors one count apart); outside bounds ");
    ut_put_u64(st->bad);
    ut_puts("\n");
}

static obs_params_t s_tab;

static void replay(const char *set, const char *dg_name, const obs_params_t *base, int32_t bdot_max_q29,
                   const gv_obs_t *vec, uint32_t n, uint32_t fp, uint32_t vec_crc)
{
    const obs_params_t *p = &s_tab;
    gv_dg_t din;
    gv_dg_t dout;
    stats_t st = {0u, 0u, 0u, 0, 0, 0, 0, 0u, 0u, 0u, 0};
    stats_t late = {0u, 0u, 0u, 0, 0, 0, 0, 0u, 0u, 0u, 0};
    uint32_t k;
    uint32_t twin_bad = 0u;
    /* The set's table: the boot table with its command limit (the S0-9 set overrides it, as the
       SIL boot table does); the vectors must belong to it, and be intact. */
    s_tab = *base;
    s_tab.bdot_max_q29 = bdot_max_q29;
    UT_CHECK_UEQ(gv_obs_table_fp(p), fp);
    gv_dg_begin(&din);
    gv_dg_begin(&dout);
    for (k = 0u; k < n; k++) {
        gv_dg_words(&din, &vec[k], sizeof vec[k]);
        din.n++;
    }
    UT_CHECK_UEQ(din.crc, vec_crc);
    for (k = 0u; k < n; k++) {
        const gv_obs_t *v = &vec[k];
        step(&s_state, &s_out, p, v, 0xA5A5A5A5u);
        if ((k % 16u) == 0u) {
            gv_dg_t a;
            gv_dg_t b;
            step(&s_twin, &s_twin_out, p, v, 0x3C3C0FF0u);
            gv_dg_begin(&a);
            gv_dg_begin(&b);
            digest_out(&a, &s_state, &s_out);
            digest_out(&b, &s_twin, &s_twin_out);
            twin_bad += (a.crc != b.crc) ? 1u : 0u;
        }
        digest_out(&dout, &s_state, &s_out);
        {
            stats_t one = {0u, 0u, 0u, 0, 0, 0, 0, 0u, 0u, 0u, 0};
            one.bad = compare(set, k, v, &s_state, &s_out, &one, st.bad < 5u);
            one.n = 1u;
            merge(&st, &one);
            if (v->seq >= GV_LATE_SEQ) {
                merge(&late, &one);
            }
#if defined(GV_DUMP)
            /* -DGV_DUMP: one line per vector (errors, bounds at d = 0, running output digest) */
            ut_puts("  vec ");
            ut_put_u64(k);
            ut_puts(" seq ");
            ut_put_u64(v->seq);
            ut_puts(" x ");
            ut_put_i64(one.ex);
            ut_puts(" k ");
            ut_put_i64(one.ek);
            ut_puts("/");
            ut_put_i64(v->bk);
            ut_puts(" P ");
            ut_put_i64(one.ep);
            ut_puts("/");
            ut_put_i64(v->bp[0]);
            ut_puts(" cnt ");
            ut_put_i64(one.ecnt);
            ut_puts(" digest ");
            ut_put_u32hex(dout.crc);
            ut_puts("\n");
#endif
        }
    }
    print_stats(set, "", &st);
    print_stats(set, ", from step 200 on", &late);
    gv_dg_print(dg_name, "_vectors", &din);
    gv_dg_print(dg_name, "", &dout);
    UT_CHECK_EQ(st.bad, 0);
    UT_CHECK_EQ(twin_bad, 0);
    UT_CHECK_EQ(st.n, n);
}

UT_TEST(golden_replay_s0_5_paper)
{
    replay("S0-5 M-paper", "obs_s0_5_paper", &OBS_TBL_50HZ_PAPER, GV_OBS_PAPER_BDOT_MAX_Q29, GV_OBS_PAPER,
           GV_OBS_PAPER_N, GV_OBS_PAPER_TABLE_FP, GV_OBS_PAPER_CRC);
}

UT_TEST(golden_replay_s0_5_noise)
{
    replay("S0-5 M-paper noise seed 0", "obs_s0_5_noise0", &OBS_TBL_50HZ_PAPER, GV_OBS_NOISE_BDOT_MAX_Q29,
           GV_OBS_NOISE, GV_OBS_NOISE_N, GV_OBS_NOISE_TABLE_FP, GV_OBS_NOISE_CRC);
}

UT_TEST(golden_replay_s0_7_phys)
{
    replay("S0-7 M-phys", "obs_s0_7_phys", &OBS_TBL_50HZ_PHYS, GV_OBS_PHYS_BDOT_MAX_Q29, GV_OBS_PHYS,
           GV_OBS_PHYS_N, GV_OBS_PHYS_TABLE_FP, GV_OBS_PHYS_CRC);
}

UT_TEST(golden_replay_s0_9_limited)
{
    replay("S0-9 M-paper limited 1.2 deg/s", "obs_s0_9_limit", &OBS_TBL_50HZ_PAPER, GV_OBS_LIMIT_BDOT_MAX_Q29,
           GV_OBS_LIMIT, GV_OBS_LIMIT_N, GV_OBS_LIMIT_TABLE_FP, GV_OBS_LIMIT_CRC);
}

int main(void)
{
    UT_CASES(cases) = {UT_CASE(golden_replay_s0_5_paper), UT_CASE(golden_replay_s0_5_noise),
                       UT_CASE(golden_replay_s0_7_phys), UT_CASE(golden_replay_s0_9_limited)};
    return UT_RUN("obs_golden_replay", cases);
}

#endif /* GV_MISSING */
