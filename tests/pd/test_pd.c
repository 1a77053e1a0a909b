/*
 * The HOLD law (fsw/pd/pd.c) on hand-derived cases: its table check names the
 * bad field; the command is -round(gain * rate / 2^16) with rounding half away from zero; the
 * limit is a designed saturation (CMD_LIMITED, no fx status), persistent after n_sat steps; a
 * step without a valid rate commands zero and is counted. Host and target.
 */
#include "pd_tables.h"
#include "ut.h"

static pd_state_t g_s;

static pd_out_t step(const pd_params_t *p, int32_t rate, bool valid)
{
    pd_in_t in;
    pd_out_t out;
    in.rate_cnt = rate;
    in.valid = valid;
    pd_step(&g_s, p, &in, &out);
    return out;
}

UT_TEST(params_check_names_the_bad_field)
{
    pd_params_t p = PD_TBL_DEFAULT;
    uint32_t why = 0xFFu;
    UT_UEQ(pd_params_check(&p, &why), FSW_OK);
    UT_UEQ(why, 0u);
    p.gain_q16 = 0;
    UT_UEQ(pd_params_check(&p, &why), FSW_ERR_RANGE);
    UT_UEQ(why, PD_WHY_GAIN);
    p = PD_TBL_DEFAULT;
    p.u_max_cnt = PD_U_MAX_CNT + 1;
    p.n_sat = 0u;
    UT_UEQ(pd_params_check(&p, &why), FSW_ERR_RANGE);
    UT_UEQ(why, PD_WHY_LIMIT | PD_WHY_FAULT);
    UT_UEQ(pd_params_check(NULL, &why), FSW_ERR_ARG);
}

/* Default table: gain_q16 = 2048 (K = 0.5 N m s), so u = -rate / 32 rounded half away from 0. */
UT_TEST(law_rounds_half_away_from_zero)
{
    const pd_params_t *p = &PD_TBL_DEFAULT;
    pd_out_t o;
    UT_EQ(p->gain_q16, 2048);
    pd_init(&g_s, p);
    o = step(p, 16384, true);          /* 2^-6 rad/s -> 2^-7 N m = 512 counts */
    UT_EQ(o.u_cnt, -512);
    UT_UEQ(o.health, 0u);
    o = step(p, 16, true);             /* -0.5 count: away from zero */
    UT_EQ(o.u_cnt, -1);
    o = step(p, -16, true);
    UT_EQ(o.u_cnt, 1);
    o = step(p, 15, true);             /* -0.46875 -> 0 */
    UT_EQ(o.u_cnt, 0);
    o = step(p, -104831, true);        /* 3275.97 -> 3276, below the 3277 limit */
    UT_EQ(o.u_cnt, 3276);
    UT_UEQ(o.health, 0u);
    UT_UEQ(g_s.tlm.n_limited, 0u);
    UT_EQ(g_s.tlm.rate_cnt, -104831);
}

UT_TEST(limit_is_a_designed_saturation)
{
    pd_params_t p = PD_TBL_DEFAULT;
    pd_out_t o;
    uint32_t k;
    p.n_sat = 3u;
    pd_init(&g_s, &p);
    o = step(&p, 200000, true);        /* -6250 counts wanted */
    UT_EQ(o.u_cnt, -p.u_max_cnt);
    UT_UEQ(o.health, PD_H_CMD_LIMITED);
    o = step(&p, INT32_MIN, true);     /* the widest product: clamped, still no fx status */
    UT_EQ(o.u_cnt, p.u_max_cnt);
    UT_UEQ(o.health & FX_ST_MASK, 0u);
    o = step(&p, INT32_MAX, true);     /* third limited step in a row: persistent */
    UT_EQ(o.u_cnt, -p.u_max_cnt);
    UT_UEQ(o.health, PD_H_CMD_LIMITED | PD_H_CMD_LIMIT_PERSIST);
    o = step(&p, 0, true);             /* in range again: the run restarts */
    UT_UEQ(o.health, 0u);
    for (k = 0u; k < 2u; k++) {
        o = step(&p, 300000, true);
        UT_CHECK_UEQ(o.health, PD_H_CMD_LIMITED);
    }
    UT_UEQ(g_s.tlm.n_limited, 5u);
    UT_UEQ(g_s.tlm.health_sticky, PD_H_CMD_LIMITED | PD_H_CMD_LIMIT_PERSIST);
}

UT_TEST(invalid_rate_commands_zero_and_is_counted)
{
    const pd_params_t *p = &PD_TBL_DEFAULT;
    pd_out_t o;
    pd_init(&g_s, p);
    o = step(p, 100000, true);
    UT_CHECK(o.u_cnt != 0);
    o = step(p, 100000, false);
    UT_EQ(o.u_cnt, 0);
    UT_UEQ(o.health, PD_H_MEAS_SKIP);
    UT_UEQ(g_s.tlm.n_skip, 1u);
    UT_EQ(g_s.tlm.rate_cnt, 0);
    UT_UEQ(g_s.tlm.revision, p->revision);
}

int main(void)
{
    UT_CASES(cases) = {
        UT_CASE(params_check_names_the_bad_field),
        UT_CASE(law_rounds_half_away_from_zero),
        UT_CASE(limit_is_a_designed_saturation),
        UT_CASE(invalid_rate_commands_zero_and_is_counted),
    };
    return UT_RUN("pd", cases);
}
