/*
 * The fixed-point estimator fsw/pd/pd_fest fed bad data (host and target; under the asan-ubsan preset
 * it also proves the arithmetic free of undefined behaviour on these inputs). Its accuracy against the
 * double design is golden_pd_fest's (G3); here only what must hold for any input:
 *   - the published f_hat stays inside the output clamps [0.008, 0.12] Hz, the state in 0..3, the RLS P of
 *     the notch in [1e-4, 1] once a period has ended, the FAULT count never decreases (pitch's block, and
 *     yaw's with its two sections and line logic);
 *   - garbage (full-range attitudes and torques, random validity, random k2 up to 1023 s) raises FAULTs
 *     (counted, the reasons kept), never a stuck estimator: a quiet stream afterwards (y = 0, M = 0,
 *     all valid) leaves FAULT within two periods and raises no further FAULT;
 *   - the same inputs give the same outputs (two runs compared field by field).
 * Inputs from a fixed-seed xorshift32, no floating point.
 */
#include "pd_mission.h"
#include "pd_tables.h"
#include "ut.h"

#define N_GARBAGE   2048u     /* 128 control periods of 16 */
#define N_QUIET     256u      /* 16 periods */
#define F_LO_Q32    34359738u /* 0.008 Hz */
#define F_HI_Q32    515396076u/* 0.12 Hz */
#define P_MIN_Q30   107374u   /* 1e-4 */
#define P_MAX_Q30   1073741824u

static pd_fest_t g_a;
static pd_fest_t g_b;

static uint32_t rng(uint32_t *x)
{
    uint32_t v = *x;
    v ^= v << 13;
    v ^= v >> 17;
    v ^= v << 5;
    *x = v;
    return v;
}

/* One garbage sample: a full-range attitude (q30, +-2 rad), a full-range torque (q28, +-8 N m), valid
   3 times in 4, k2 anywhere in [0, 1023] s. */
static void garbage(pd_fest_t *s, const pd_fest_params_t *p, uint32_t *seed)
{
    const uint32_t r = rng(seed);
    const int32_t y = (int32_t)(rng(seed) & 0x7FFFFFFFu) - 1073741824;
    const int32_t m = (int32_t)(rng(seed) & 0x7FFFFFFFu) - 1073741824;
    const uint32_t k2 = rng(seed) % (1023u << 22);
    pd_fest_step(s, p, 16u, (r & 3u) != 0u, y, m, k2);
}

static void check_invariants(const pd_fest_t *s, uint32_t *resets_prev, uint32_t k)
{
    UT_TRUE(s->state <= 3u);
    UT_TRUE((s->f_hat_q32 >= F_LO_Q32) && (s->f_hat_q32 <= F_HI_Q32));
    if (k >= 16u) {
        UT_TRUE((s->p_a_q30 >= P_MIN_Q30) && (s->p_a_q30 <= P_MAX_Q30));
    }
    UT_TRUE(s->resets >= *resets_prev);
    *resets_prev = s->resets;
}

/* garbage, then a quiet stream, through one channel's block */
static void garbage_then_quiet_on(const pd_fest_params_t *p, uint32_t seed0)
{
    uint32_t seed = seed0;
    uint32_t resets = 0u;
    uint32_t k;
    uint32_t resets_after;
    uint32_t left_fault = 0u;
    UT_UEQ(pd_fest_check(p), 0u);
    pd_fest_init(&g_a);
    for (k = 0u; k < N_GARBAGE; k++) {
        garbage(&g_a, p, &seed);
        check_invariants(&g_a, &resets, k);
    }
    UT_TRUE(g_a.resets > 0u);                              /* garbage is noticed ... */
    UT_TRUE((g_a.fault & PD_FEST_F_RESID) != 0u);          /* ... as residuals beyond 1e-3 rad */
    resets_after = g_a.resets;
    for (k = 0u; k < N_QUIET; k++) {
        pd_fest_step(&g_a, p, 16u, true, 0, 0, 475u << 22);
        check_invariants(&g_a, &resets, N_GARBAGE + k);
        if ((k == 31u) && (g_a.state != (uint8_t)PD_FEST_FAULT)) {
            left_fault = 1u;                               /* out of FAULT within two periods */
        }
    }
    UT_UEQ(left_fault, 1u);
    UT_TRUE(g_a.resets <= (resets_after + 1u));            /* at most the FAULT pending at the switch */
    UT_TRUE(g_a.state != (uint8_t)PD_FEST_FAULT);
}

UT_TEST(garbage_then_quiet)
{
    garbage_then_quiet_on(&PD_TBL_DEFAULT.ch[2].fest, 0x2545F491u);   /* pitch: one section, regressors */
}

/* yaw: two sections, the passes, the pair / single-line logic and the envelope ring on garbage */
UT_TEST(garbage_then_quiet_yaw)
{
    garbage_then_quiet_on(&PD_TBL_DEFAULT.ch[0].fest, 0x9E3779B9u);
    UT_TRUE((g_a.sec[1].p_q30 >= P_MIN_Q30) && (g_a.sec[1].p_q30 <= P_MAX_Q30));
    UT_TRUE(g_a.env_i < PD_FEST_ENV);
}

static void same_inputs_on(const pd_fest_params_t *p)
{
    uint32_t sa = 12345u;
    uint32_t sb = 12345u;
    uint32_t k;
    uint32_t i;
    pd_fest_init(&g_a);
    pd_fest_init(&g_b);
    for (k = 0u; k < 512u; k++) {
        garbage(&g_a, p, &sa);
        garbage(&g_b, p, &sb);
    }
    UT_UEQ(g_a.f_hat_q32, g_b.f_hat_q32);
    UT_UEQ(g_a.state, g_b.state);
    UT_UEQ(g_a.resets, g_b.resets);
    UT_UEQ(g_a.fault, g_b.fault);
    for (i = 0u; i < PD_FEST_NSEC; i++) {
        UT_UEQ(g_a.sec[i].p_q30, g_b.sec[i].p_q30);
        UT_EQ(g_a.sec[i].a_q29, g_b.sec[i].a_q29);
        UT_UEQ(g_a.sec[i].kap_q30, g_b.sec[i].kap_q30);
    }
    UT_UEQ(g_a.f_lo_ver_q32, g_b.f_lo_ver_q32);
    UT_TRUE(g_a.ms_e_q32 == g_b.ms_e_q32);
    for (i = 0u; i < PD_FEST_NX; i++) {
        UT_TRUE(g_a.xh[i] == g_b.xh[i]);
    }
}

UT_TEST(same_inputs_same_outputs)
{
    same_inputs_on(&PD_TBL_DEFAULT.ch[1].fest);   /* roll: no regressors */
    same_inputs_on(&PD_TBL_DEFAULT.ch[0].fest);   /* yaw: two sections */
}

/* The check passes the three default blocks (yaw's with two sections) and refuses a corrupt one. */
UT_TEST(check_codes)
{
    static pd_fest_params_t q;
    UT_UEQ(pd_fest_check(&PD_TBL_DEFAULT.ch[0].fest), 0u);    /* yaw: n_sec 2 */
    UT_UEQ(pd_fest_check(&PD_TBL_DEFAULT.ch[1].fest), 0u);
    q = PD_TBL_DEFAULT.ch[0].fest;
    q.n_sec = 3u;
    UT_UEQ(pd_fest_check(&q), 1u);
    q = PD_TBL_DEFAULT.ch[2].fest;
    q.inv_m_q30 = 0u;
    UT_UEQ(pd_fest_check(&q), 3u);
    q = PD_TBL_DEFAULT.ch[2].fest;
    q.l_sh[1] = 200u;
    UT_UEQ(pd_fest_check(&q), 8u);
    q = PD_TBL_DEFAULT.ch[2].fest;
    q.cinv_q30[12][10] = 2000000000u;
    UT_UEQ(pd_fest_check(&q), 9u);
}

int main(void)
{
    UT_CASES(cases) = { UT_CASE(garbage_then_quiet), UT_CASE(garbage_then_quiet_yaw),
                          UT_CASE(same_inputs_same_outputs), UT_CASE(check_codes) };
    return UT_RUN("pd_fest", cases);
}
