/*
 * The RESPIN law (fsw/respin/rsp.c, spec 30 §3, §4, §8) on hand-derived cases. Host and target.
 *
 * Every expected number below is worked out from the spec's equations in the comment next to
 * it, never read back from the code. The conversions used throughout (rsp.h):
 *   H_i  = round(w_i * I_w / 2^20)            I_w = 10737418 (q30): H(w) = round(10.23999977 w)
 *   Jw_i = round(J_i * (c_i * 64) / 2^27)     J = {2900, 3600, 670} * 2^19: Jw = 725 c_x, 900 c_y,
 *                                             round(167.5 c_z)
 *   G = Jw + H (q20), |G| = floor sqrt(sum G_i^2), g = round(G 2^30 / g0) (fx_recip, exact rounding).
 * Most cases freeze g0 = 2^30 (1024 N m s): gyro y 1193042 counts -> 900 * 1193042 = 1073737800,
 * wheel y 393 counts -> H(393) = round(4024.33) = 4024, sum 2^30 exactly. Then G 2^30 / g0 = G and
 * g_q30 = G_q20 bit for bit, so |xi| = |g_x| whenever G_z = 0.
 * Law shortcuts: m / 2^26 = 25165824 / 2^26 = 0.375, so M = round(-0.375 inner); the momentum
 * bound is lo/hi = (H -+ h_lim) * 655360 / 2^12 = 160 (H -+ h_lim) exactly; an output count is
 * round(-M / 128); M* = M_max = 2516582 -> 2516582 / 128 = 19660.8 -> 19661 counts.
 */
#include "rsp.h"
#include "ut.h"

static rsp_state_t g_s;

#define C_Y1   1193042     /* gyro y counts: Jw_y = 1073737800 */
#define W_Y1   393         /* wheel y counts: H_y = 4024; G_y = 2^30 with C_Y1 */
#define Q30    1073741824
#define M_STAR 2516582
#define OUT_MAX 19661
#define HLIM   5221908
#define ENC_Q  131072      /* pi/4 in encoder counts (2^20 per turn) */
#define ROTOR_NOM 153600   /* 600 rad/s in 2^-8 rad/s */
#define C_Z02  838861      /* gyro z counts of 0.2 rad/s: G_z = 670 * 0.2 = 134 N m s (> g_guard 60) */

/* The default table of the brief (spec 30 §3.4, §8), built here rather than taken from
   rsp_tables.h. */
static rsp_params_t params(void)
{
    rsp_params_t p;
    p.period_us = 100000u;
    p.mode = RSP_MODE_NEAREST;
    p.act_kind = RSP_ACT_WHEELS;
    p.j_q19[0] = 2900 * 524288;
    p.j_q19[1] = 3600 * 524288;
    p.j_q19[2] = 670 * 524288;
    p.iw_q30 = 10737418;
    p.eps1_q30 = 107374182;
    p.eps2_q30 = 536870912;
    p.heps_q30 = 10737418;
    p.m_q24 = 25165824;
    p.k_q30 = 75161928;
    p.mstar_q24 = 2516582;
    p.mmax_q24 = 2516582;
    p.hlim_q20 = 5221908;
    p.inv_ts_q16 = 655360;
    p.gguard_q20 = 18161766;
    p.gmin_q20 = 2097152;
    p.n_g0 = 50u;
    p.gyro_max_cnt = 4194304;
    p.whl_max_cnt = 614400;
    p.n_fault = 50u;
    p.n_stale = 20u;
    p.n_whl_est = 10u;
    p.outlier_q20 = 524288;
    p.outlier_rel_q16 = 3277u;
    p.drift_q30 = 21474836;
    p.drift_sh = 10u;
    p.ealarm_q32 = INT64_C(2147483648);
    p.done_xi_q30 = 10737418;
    p.done_h_q20 = 52429;
    p.done_ticks = 3000u;
    p.gfilt_alpha_q30 = 0;          /* G filter off */
    p.hg_q20 = 7864320;             /* 7.5 N m s */
    p.lambda_q28 = 13421773;        /* 0.05 */
    p.umax_cnt = 11437;             /* 0.1745 rad/s in 2^-16 rad/s */
    p.ms_sing_q28 = 13421773;       /* 0.05 */
    p.rotor_nom_cnt = 153600;       /* 600 rad/s in 2^-8 rad/s */
    p.rotor_tol_q16 = 655u;         /* 0.01 */
    p.revision = 7u;
    return p;
}

static rsp_in_t input(int32_t cx, int32_t cy, int32_t cz, int32_t wx, int32_t wy, int32_t wz)
{
    rsp_in_t in;
    in.omega_BN_B_cnt[0] = cx;
    in.omega_BN_B_cnt[1] = cy;
    in.omega_BN_B_cnt[2] = cz;
    in.whl_speed_cnt[0] = wx;
    in.whl_speed_cnt[1] = wy;
    in.whl_speed_cnt[2] = wz;
    /* the gyrodine channels (ignored with wheels): the null configuration (pi/4, pi/4, -pi/4, -pi/4)
       = 2^17, 2^17, 7 2^17, 7 2^17 encoder counts, H = 0; rotors at 600 rad/s */
    in.gimbal_enc_cnt[0] = ENC_Q;
    in.gimbal_enc_cnt[1] = ENC_Q;
    in.gimbal_enc_cnt[2] = 7 * ENC_Q;
    in.gimbal_enc_cnt[3] = 7 * ENC_Q;
    in.rotor_cnt[0] = ROTOR_NOM;
    in.rotor_cnt[1] = ROTOR_NOM;
    in.rotor_cnt[2] = ROTOR_NOM;
    in.rotor_cnt[3] = ROTOR_NOM;
    in.valid = 0x3FFFu;
    in.sat = 0u;
    return in;
}

static rsp_out_t step_in(const rsp_params_t *p, const rsp_in_t *in)
{
    rsp_out_t out;
    rsp_step(&g_s, p, in, &out);
    return out;
}

static rsp_out_t step6(const rsp_params_t *p, int32_t cx, int32_t cy, int32_t cz, int32_t wx, int32_t wy,
                       int32_t wz)
{
    rsp_in_t in = input(cx, cy, cz, wx, wy, wz);
    return step_in(p, &in);
}

static bool cmd_zero(const rsp_out_t *o)
{
    return (o->whl_torque_cnt[0] == 0) && (o->whl_torque_cnt[1] == 0) && (o->whl_torque_cnt[2] == 0);
}

static void check_cmd(const rsp_out_t *o, int32_t x, int32_t y, int32_t z)
{
    UT_CHECK_EQ(o->whl_torque_cnt[0], x);
    UT_CHECK_EQ(o->whl_torque_cnt[1], y);
    UT_CHECK_EQ(o->whl_torque_cnt[2], z);
}

/* rsp_init, then n_g0 ticks of the gyro/wheel pair (c, w) on one axis with the sign alternating
   every tick: |G| is the same each tick and no gyro word repeats (so nothing is stale). Every
   averaging tick commands zero and reports G0_WAIT. The last tick is the negative one. */
static void prime(const rsp_params_t *p, uint32_t axis, int32_t c, int32_t w)
{
    uint32_t k;
    rsp_init(&g_s, p);
    for (k = 0u; k < p->n_g0; k++) {
        int32_t sg = ((k % 2u) == 0u) ? 1 : -1;
        rsp_in_t in = input(0, 0, 0, 0, 0, 0);
        rsp_out_t o;
        in.omega_BN_B_cnt[axis] = sg * c;
        in.whl_speed_cnt[axis] = sg * w;
        o = step_in(p, &in);
        UT_CHECK(cmd_zero(&o));
        UT_CHECK((o.health & RSP_H_G0_WAIT) != 0u);
    }
}

/* |xi| is the exact floor root of g_x^2 + g_z^2 (Q2.60): checked by its defining inequality. */
static void check_floor_root(int32_t r, int32_t gx, int32_t gz)
{
    uint64_t s = (uint64_t)((int64_t)gx * gx) + (uint64_t)((int64_t)gz * gz);
    uint64_t rr = (uint64_t)r;
    UT_CHECK(rr * rr <= s);
    UT_CHECK((rr + 1u) * (rr + 1u) > s);
}

/* ------------------------------------------------------------------ table check */

static void expect_why(const rsp_params_t *p, uint32_t why_want)
{
    uint32_t why = 0u;
    UT_CHECK_UEQ(rsp_params_check(p, &why), FSW_ERR_RANGE);
    UT_CHECK_UEQ(why, why_want);
}

UT_TEST(params_check_names_each_bad_field)
{
    const rsp_params_t d = params();
    rsp_params_t p = d;
    uint32_t why = 0xFFu;
    UT_UEQ(rsp_params_check(&p, &why), FSW_OK);
    UT_UEQ(why, 0u);
    UT_UEQ(rsp_params_check(NULL, &why), FSW_ERR_ARG);
    p.period_us = 0u; expect_why(&p, RSP_WHY_PERIOD); p = d;
    p.mode = 2u; expect_why(&p, RSP_WHY_MODE); p = d;
    p.act_kind = 2u; expect_why(&p, RSP_WHY_MODE); p = d;
    p.act_kind = RSP_ACT_GYRODINES; UT_UEQ(rsp_params_check(&p, &why), FSW_OK); p = d;
    p.j_q19[2] = 0; expect_why(&p, RSP_WHY_INERTIA); p = d;
    p.j_q19[0] = p.j_q19[1]; expect_why(&p, RSP_WHY_INERTIA); p = d;   /* J_y strictly largest */
    p.heps_q30 = 0; expect_why(&p, RSP_WHY_THRESH); p = d;
    p.eps1_q30 = 2 * p.heps_q30; expect_why(&p, RSP_WHY_THRESH | RSP_WHY_GAIN); p = d;  /* m eps1 off too */
    p.eps2_q30 = p.eps1_q30 + 2 * p.heps_q30; expect_why(&p, RSP_WHY_THRESH); p = d;
    p.eps2_q30 = Q30 - p.heps_q30; expect_why(&p, RSP_WHY_THRESH); p = d;  /* eps2 + heps = 2^30 */
    p.eps2_q30 = Q30 - p.heps_q30 - 1; UT_UEQ(rsp_params_check(&p, &why), FSW_OK); p = d;
    p.m_q24 = 0; expect_why(&p, RSP_WHY_GAIN); p = d;
    p.k_q30 = 0; expect_why(&p, RSP_WHY_GAIN); p = d;
    p.mstar_q24 = 0; expect_why(&p, RSP_WHY_GAIN); p = d;
    p.mmax_q24 = 0; expect_why(&p, RSP_WHY_GAIN); p = d;
    /* 1 % of M_max = 25165.82, so round(m eps1 / 2^30) may reach 2516582 + 25165 = 2541747:
       m = 25417474 -> 25417474 * 107374182 / 2^30 = 2541747.4 -> 2541747 passes,
       m = 25417476 -> 2541747.6 -> 2541748 fails */
    p.m_q24 = 25417474; UT_UEQ(rsp_params_check(&p, &why), FSW_OK); p = d;
    p.m_q24 = 25417476; expect_why(&p, RSP_WHY_GAIN); p = d;
    p.iw_q30 = 0; expect_why(&p, RSP_WHY_WHEEL); p = d;
    p.hlim_q20 = 0; expect_why(&p, RSP_WHY_WHEEL); p = d;
    /* 2^16 * 10^6 / 100000 = 655360 exactly: +-1 accepted, +-2 refused */
    p.inv_ts_q16 = 655361; UT_UEQ(rsp_params_check(&p, &why), FSW_OK); p = d;
    p.inv_ts_q16 = 655358; expect_why(&p, RSP_WHY_WHEEL); p = d;
    p.period_us = 500000u; expect_why(&p, RSP_WHY_WHEEL); p = d;   /* 0.5 s wants 131072 */
    p.gmin_q20 = 0; expect_why(&p, RSP_WHY_GUARDS); p = d;
    p.gmin_q20 = p.gguard_q20 + 1; expect_why(&p, RSP_WHY_GUARDS); p = d;
    p.n_g0 = 0u; expect_why(&p, RSP_WHY_GUARDS); p = d;
    p.n_g0 = RSP_G0_TICKS_MAX + 1u; expect_why(&p, RSP_WHY_GUARDS); p = d;
    p.n_g0 = RSP_G0_TICKS_MAX; UT_UEQ(rsp_params_check(&p, &why), FSW_OK); p = d;
    p.gyro_max_cnt = 0; expect_why(&p, RSP_WHY_SENSOR); p = d;
    p.gyro_max_cnt = 4194305; expect_why(&p, RSP_WHY_SENSOR); p = d;   /* 2^22 + 1: << 6 could overflow */
    p.whl_max_cnt = 0; expect_why(&p, RSP_WHY_SENSOR); p = d;
    p.n_fault = 0u; expect_why(&p, RSP_WHY_SENSOR); p = d;
    p.n_stale = 0u; expect_why(&p, RSP_WHY_SENSOR); p = d;
    p.n_whl_est = 0u; expect_why(&p, RSP_WHY_SENSOR); p = d;
    p.outlier_q20 = 0; expect_why(&p, RSP_WHY_HEALTH); p = d;
    p.outlier_rel_q16 = 0u; expect_why(&p, RSP_WHY_HEALTH); p = d;
    p.drift_q30 = 0; expect_why(&p, RSP_WHY_HEALTH); p = d;
    p.drift_sh = 0u; expect_why(&p, RSP_WHY_HEALTH); p = d;
    p.drift_sh = 21u; expect_why(&p, RSP_WHY_HEALTH); p = d;
    p.drift_sh = 20u; UT_UEQ(rsp_params_check(&p, &why), FSW_OK); p = d;
    p.ealarm_q32 = 0; expect_why(&p, RSP_WHY_HEALTH); p = d;
    p.done_xi_q30 = 0; expect_why(&p, RSP_WHY_HEALTH); p = d;
    p.done_h_q20 = 0; expect_why(&p, RSP_WHY_HEALTH); p = d;
    p.done_ticks = 0u; expect_why(&p, RSP_WHY_HEALTH); p = d;
    p.gfilt_alpha_q30 = -1; expect_why(&p, RSP_WHY_FILTER); p = d;
    p.gfilt_alpha_q30 = 536870913; expect_why(&p, RSP_WHY_FILTER); p = d;   /* 0.5 + 1 LSB */
    p.gfilt_alpha_q30 = 536870912; UT_UEQ(rsp_params_check(&p, &why), FSW_OK); p = d;
    p.hg_q20 = 0; expect_why(&p, RSP_WHY_CMG); p = d;
    p.lambda_q28 = 0; expect_why(&p, RSP_WHY_CMG); p = d;
    p.lambda_q28 = 268435457; expect_why(&p, RSP_WHY_CMG); p = d;   /* lambda0 > 1 */
    p.umax_cnt = 32768; expect_why(&p, RSP_WHY_CMG); p = d;         /* beyond the int16 command */
    p.ms_sing_q28 = 0; expect_why(&p, RSP_WHY_CMG); p = d;
    p.rotor_nom_cnt = 0; expect_why(&p, RSP_WHY_CMG); p = d;
    p.rotor_tol_q16 = 0u; expect_why(&p, RSP_WHY_CMG); p = d;
    p.period_us = 0u;
    p.n_stale = 0u;
    expect_why(&p, RSP_WHY_PERIOD | RSP_WHY_SENSOR);   /* every failing group is named */
}

/* Checks beyond the note of rsp_iface.py, for the module's own arithmetic: g_min > 2^19 = 0.5 N m s
   (below it the momentum LSB over g0 exceeds 2^-19 of g) and M_max must fit the int16 command
   (32767 * 128). */
UT_TEST(params_check_refuses_unrepresentable_limits)
{
    const rsp_params_t d = params();
    rsp_params_t p = d;
    uint32_t why = 0u;
    p.gmin_q20 = 524288; expect_why(&p, RSP_WHY_GUARDS); p = d;
    p.gmin_q20 = 524289; UT_UEQ(rsp_params_check(&p, &why), FSW_OK); p = d;
    /* M_max = 4194176 = 32767 * 128 with m = M_max / eps1 = 4194176 * 2^30 / 107374182 -> 41941760 */
    p.mmax_q24 = 4194176; p.mstar_q24 = 4194176; p.m_q24 = 41941760;
    UT_UEQ(rsp_params_check(&p, &why), FSW_OK);
    p.mmax_q24 = 4194177; expect_why(&p, RSP_WHY_GAIN);
}

/* ------------------------------------------------------------------ g0, low momentum */

UT_TEST(g0_is_the_rounded_mean_of_valid_ticks)
{
    const rsp_params_t p = params();
    rsp_in_t bad = input(0, C_Y1, 0, 0, W_Y1, 0);
    rsp_out_t o;
    uint32_t k;
    rsp_init(&g_s, &p);
    UT_UEQ(g_s.phase, RSP_PH_G0);
    UT_EQ(g_s.a_f, 1);
    /* 25 ticks of |G| = 2^30, then 25 of |G| = 2^30 + 1: gyro y 1193041 -> 1073736900,
       wheel y 481 -> H = round(4925.44) = 4925, sum 1073741825. Mean 2^30 + 0.5 -> 2^30 + 1.
       A gyro-invalid tick in the middle is not averaged. */
    bad.valid = 0x3Eu;
    for (k = 0u; k < 50u; k++) {
        int32_t sg = ((k % 2u) == 0u) ? 1 : -1;
        if (k == 20u) {
            o = step_in(&p, &bad);
            UT_UEQ(o.health, RSP_H_GYRO_BAD | RSP_H_G0_WAIT);
            UT_TRUE(cmd_zero(&o));
        }
        if (k < 25u) {
            o = step6(&p, 0, sg * C_Y1, 0, 0, sg * W_Y1, 0);
        } else {
            o = step6(&p, 0, sg * 1193041, 0, 0, sg * 481, 0);
        }
        UT_TRUE(cmd_zero(&o));
        UT_UEQ(o.health, RSP_H_G0_WAIT);
        UT_EQ(g_s.tlm.g0_q20, (k < 49u) ? 0 : Q30 + 1);
    }
    UT_UEQ(g_s.phase, RSP_PH_RUN);
    UT_UEQ(g_s.tlm.phase, RSP_PH_RUN);
    UT_EQ(g_s.r0.d, Q30 + 1);   /* g = round(G 2^30 / g0) from here on */
    UT_UEQ(g_s.tlm.n_gyro_bad, 1u);
    /* the first tick after: the law runs; G = (0, 2^30, 0), g_y = 2^30 * 2^20 / 2^20 = 2^30: LIN */
    o = step6(&p, 0, C_Y1, 0, 0, W_Y1, 0);
    UT_UEQ(o.health & RSP_H_G0_WAIT, 0u);
    UT_UEQ(g_s.tlm.region, RSP_RG_LIN);
}

UT_TEST(low_momentum_commands_zero_for_good)
{
    const rsp_params_t p = params();
    rsp_out_t o;
    uint32_t k;
    /* gyro y 2000 counts: G_y = 900 * 2000 = 1800000 (1.72 N m s) < g_min = 2097152 */
    prime(&p, 1u, 2000, 0);
    UT_UEQ(g_s.phase, RSP_PH_LOW);
    UT_EQ(g_s.tlm.g0_q20, 1800000);
    UT_UEQ(g_s.tlm.flags, RSP_H_G0_WAIT | RSP_H_LOW_MOMENTUM);   /* the freezing tick */
    for (k = 0u; k < 5u; k++) {
        /* even a large momentum now changes nothing */
        o = step6(&p, 800000, (int32_t)k, 0, 1000, 0, 0);
        UT_TRUE(cmd_zero(&o));
        UT_UEQ(o.health, RSP_H_LOW_MOMENTUM);
    }
    UT_UEQ(g_s.phase, RSP_PH_LOW);
}

/* ------------------------------------------------------------------ target, regions */

/* g = e_z exactly (spec 30 §9): C_phi = 0 and Sgn 0 = +1 gives a_f = +1. g0 is frozen on the z
   axis: gyro z 1602599 -> round(167.5 * 1602599) = round(268435332.5) = 268435333 (half away),
   wheel z 12 -> H = round(122.88) = 123, G_z = 268435456 = 2^28 = g0, so
   g_z = 2^28 * 2^30 / 2^28 = 2^30. |xi| = 2^30 > eps2: FAR, and M_i = -M* Sgn(g_i) = -M* on every
   axis (g_x = g_y = 0 count as +), so every wheel is told +19661. */
UT_TEST(g_along_z_ties_to_a_f_plus)
{
    const rsp_params_t p = params();
    rsp_out_t o;
    prime(&p, 2u, 1602599, 12);
    UT_EQ(g_s.tlm.g0_q20, 268435456);
    UT_EQ(g_s.r0.d, 268435456);
    o = step6(&p, 0, 0, 1602599, 0, 0, 12);
    UT_EQ(g_s.tlm.g_q30[0], 0);
    UT_EQ(g_s.tlm.g_q30[1], 0);
    UT_EQ(g_s.tlm.g_q30[2], Q30);
    UT_EQ(g_s.tlm.cphi_q30, 0);
    UT_EQ(g_s.tlm.xi_abs_q30, Q30);
    UT_EQ(g_s.a_f, 1);
    UT_EQ(g_s.tlm.a_f, 1);
    UT_UEQ(g_s.region, RSP_RG_FAR);
    UT_UEQ(g_s.tlm.latched, 0u);   /* NEAREST re-selects in FAR; the tie keeps a_f */
    UT_EQ(g_s.tlm.mcmd_q24[0], -M_STAR);
    UT_EQ(g_s.tlm.mcmd_q24[1], -M_STAR);
    UT_EQ(g_s.tlm.mcmd_q24[2], -M_STAR);
    check_cmd(&o, OUT_MAX, OUT_MAX, OUT_MAX);
    UT_UEQ(o.health, 0u);
    /* rho = |G| / g0 - 1 = 2^28 * 2^30 / 2^28 - 2^30 = 0 */
    UT_EQ(g_s.tlm.rho_q30, 0);
}

/* Mixed signs: gyro (-888614, 596523, 3846239) -> Jw = (725 * -888614, 900 * 596523,
   round(167.5 * 3846239)) = (-644245150, 536870700, 644245032.5 -> 644245033) = g (g0 = 2^30).
   |xi| ~ 0.85 > eps2: FAR, M = -M* (Sgn g) = (+M*, -M*, -M*), commands (-19661, +19661, +19661). */
UT_TEST(far_law_signs)
{
    const rsp_params_t p = params();
    rsp_out_t o;
    prime(&p, 1u, C_Y1, W_Y1);
    o = step6(&p, -888614, 596523, 3846239, 0, 0, 0);
    UT_EQ(g_s.tlm.g_q30[0], -644245150);
    UT_EQ(g_s.tlm.g_q30[1], 536870700);
    UT_EQ(g_s.tlm.g_q30[2], 644245033);
    check_floor_root(g_s.tlm.xi_abs_q30, -644245150, 644245033);
    UT_UEQ(g_s.region, RSP_RG_FAR);
    UT_EQ(g_s.tlm.mcmd_q24[0], M_STAR);
    UT_EQ(g_s.tlm.mcmd_q24[1], -M_STAR);
    UT_EQ(g_s.tlm.mcmd_q24[2], -M_STAR);
    check_cmd(&o, -OUT_MAX, OUT_MAX, OUT_MAX);
    UT_UEQ(o.health, 0u);
}

/* Gyro x / wheel x pairs giving G_x (= g_x = |xi| with G_z = 0 and g0 = 2^30) at the switching
   levels: eps1 = 107374182, heps = 10737418, eps2 = 536870912. */
#define XI_E1M1   148104, -119    /* 725 * 148104 = 107375400, H(-119) = round(-1218.56) = -1219: eps1 - 1 */
#define XI_E1     148114, -827    /* 107382650 + round(-8468.48) = 107374182: eps1 */
#define XI_UP1    162932, -1377   /* 118125700 + round(-14100.48) = 118111600: eps1 + heps */
#define XI_UP1P1  162911, 110     /* 118110475 + round(1126.40) = 118111601: eps1 + heps + 1 */
#define XI_DN1    133296, -277    /* 96639600 + round(-2836.48) = 96636764: eps1 - heps */
#define XI_DN1M1  133291, 77      /* 96635975 + round(788.48) = 96636763: eps1 - heps - 1 */
#define XI_E2     740548, -2577   /* 536897300 + round(-26388.48) = 536870912: eps2 */
#define XI_E2P1   740512, -28     /* 536871200 + round(-286.72) = 536870913: eps2 + 1 */
#define XI_UP2    755366, -3127   /* 547640350 + round(-32020.48) = 547608330: eps2 + heps */
#define XI_UP2P1  755320, 130     /* 547607000 + round(1331.20) = 547608331: eps2 + heps + 1 */
#define XI_DN2    725730, -2027   /* 526154250 + round(-20756.48) = 526133494: eps2 - heps */
#define XI_DN2M1  725700, 97      /* 526132500 + round(993.28) = 526133493: eps2 - heps - 1 */
/* g_y for |xi| near 0.5: gyro y 1033200 -> 929880000 (0.866), so |G| stays within the 5 % gate */
#define C_Y866 1033200

typedef struct {
    int32_t cx, wx, cy, wy;
    int32_t xi;
    uint32_t region;
} hyst_row_t;

UT_TEST(first_region_follows_the_plain_thresholds)
{
    static const hyst_row_t rows[4] = {
        {XI_E1M1, C_Y1, W_Y1, 107374181, RSP_RG_LIN},
        {XI_E1, C_Y1, W_Y1, 107374182, RSP_RG_MID},      /* eps1 <= |xi| */
        {XI_E2, C_Y866, 0, 536870912, RSP_RG_MID},       /* |xi| <= eps2 */
        {XI_E2P1, C_Y866, 0, 536870913, RSP_RG_FAR},
    };
    const rsp_params_t p = params();
    uint32_t i;
    for (i = 0u; i < 4u; i++) {
        prime(&p, 1u, C_Y1, W_Y1);
        (void)step6(&p, rows[i].cx, rows[i].cy, 0, rows[i].wx, rows[i].wy, 0);
        UT_EQ(g_s.tlm.xi_abs_q30, rows[i].xi);
        UT_UEQ(g_s.tlm.region, rows[i].region);
        UT_UEQ(g_s.tlm.n_switch, 0u);
    }
}

/* Each boundary crossed both ways (spec 30 §3.5): LIN->MID at > eps1 + heps, MID->LIN at
   < eps1 - heps, LIN/MID->FAR at > eps2 + heps, FAR->MID at < eps2 - heps, FAR->LIN at
   < eps1 - heps; sitting exactly on a level changes nothing. */
UT_TEST(region_hysteresis_both_ways)
{
    static const hyst_row_t rows[14] = {
        {XI_E1M1, C_Y1, W_Y1, 107374181, RSP_RG_LIN},     /* first tick: plain threshold */
        {XI_UP1, C_Y1, W_Y1, 118111600, RSP_RG_LIN},      /* = eps1 + heps: stays */
        {XI_UP1P1, C_Y1, W_Y1, 118111601, RSP_RG_MID},    /* switch 1 */
        {XI_E1, C_Y1, W_Y1, 107374182, RSP_RG_MID},
        {XI_DN1, C_Y1, W_Y1, 96636764, RSP_RG_MID},       /* = eps1 - heps: stays */
        {XI_DN1M1, C_Y1, W_Y1, 96636763, RSP_RG_LIN},     /* switch 2 */
        {XI_UP2, C_Y866, 0, 547608330, RSP_RG_MID},       /* LIN: > eps1 + heps, not > eps2 + heps: 3 */
        {XI_UP2P1, C_Y866, 0, 547608331, RSP_RG_FAR},     /* 4 */
        {XI_DN2, C_Y866, 0, 526133494, RSP_RG_FAR},       /* = eps2 - heps: stays */
        {XI_DN2M1, C_Y866, 0, 526133493, RSP_RG_MID},     /* 5 */
        {XI_UP2P1, C_Y866, 0, 547608331, RSP_RG_FAR},     /* 6 */
        {XI_DN1M1, C_Y1, W_Y1, 96636763, RSP_RG_LIN},     /* FAR -> LIN directly: 7 */
        {XI_UP2P1, C_Y866, 0, 547608331, RSP_RG_FAR},     /* LIN -> FAR directly: 8 */
        {XI_DN1, C_Y1, W_Y1, 96636764, RSP_RG_MID},       /* FAR: not < eps1 - heps, < eps2 - heps: 9 */
    };
    const rsp_params_t p = params();
    uint32_t i;
    prime(&p, 1u, C_Y1, W_Y1);
    for (i = 0u; i < 14u; i++) {
        rsp_out_t o = step6(&p, rows[i].cx, rows[i].cy, 0, rows[i].wx, rows[i].wy, 0);
        UT_EQ(g_s.tlm.g_q30[2], 0);
        UT_EQ(g_s.tlm.xi_abs_q30, rows[i].xi);
        UT_UEQ(g_s.tlm.region, rows[i].region);
        UT_UEQ(o.health & (RSP_H_OUTLIER | RSP_H_OVERFLOW | RSP_H_GUARD), 0u);
        UT_EQ(g_s.a_f, 1);
    }
    UT_UEQ(g_s.tlm.n_switch, 9u);
    UT_UEQ(g_s.tlm.n_lin, 4u);
    UT_UEQ(g_s.tlm.n_mid, 6u);
    UT_UEQ(g_s.tlm.n_far, 4u);
}

/* g ~ (0.8, +-0.6, 0) and (0.3, +-0.95, 0): gyro x 1184819 -> 725 * 1184819 = 858993775,
   x 444307 -> 322122575; gyro y 715828 -> 644245200, 1133394 -> 1020054600 (g0 = 2^30, g = G). */
#define C_X08 1184819
#define C_X03 444307
#define C_Y06 715828
#define C_Y095 1133394

UT_TEST(nearest_flips_in_far_and_latches_outside)
{
    const rsp_params_t p = params();
    rsp_out_t o;
    prime(&p, 1u, C_Y1, W_Y1);
    /* FAR, g_y > 0: a_f = +1 from the first tick, re-selecting (not latched) */
    o = step6(&p, C_X08, C_Y06, 0, 0, 0, 0);
    UT_UEQ(g_s.region, RSP_RG_FAR);
    UT_EQ(g_s.a_f, 1);
    UT_UEQ(g_s.tlm.latched, 0u);
    check_cmd(&o, OUT_MAX, OUT_MAX, OUT_MAX);
    /* FAR, g_y < 0: C_phi = -644245200 < 0 -> a_f = -1, C_phi recomputed +644245200;
       the far law ignores f: M = (-M*, +M*, -M*) */
    o = step6(&p, C_X08, -C_Y06, 0, 0, 0, 0);
    UT_EQ(g_s.a_f, -1);
    UT_EQ(g_s.tlm.cphi_q30, 644245200);
    UT_UEQ(g_s.tlm.latched, 0u);
    check_cmd(&o, OUT_MAX, -OUT_MAX, OUT_MAX);
    /* |xi| = 322122575 < eps2 - heps: MID, latched with a_f = -1 */
    o = step6(&p, C_X03, -C_Y095, 0, 0, 0, 0);
    UT_UEQ(g_s.region, RSP_RG_MID);
    UT_EQ(g_s.a_f, -1);
    UT_UEQ(g_s.tlm.latched, 1u);
    /* MID: xi = a_f (-g_z, 0, g_x) = (0, 0, -322122575), e_xi = (0, 0, -2^30), Sgn C_phi = +1:
       M_z = -m (-1) = +1.5 N m = 25165824 -> clipped to +M_max: command -19661 */
    UT_EQ(g_s.tlm.mcmd_q24[2], 25165824);
    check_cmd(&o, 0, 0, -OUT_MAX);
    UT_UEQ(o.health, RSP_H_CLIP);
    /* g_y back to +: C_phi = -1020054600 < 0 but MID is latched: a_f stays, Sgn C_phi = -1 flips
       the MID term: M_z = -m (-1)(-1) = -1.5 N m -> -M_max, command +19661 */
    o = step6(&p, C_X03, C_Y095, 0, 0, 0, 0);
    UT_EQ(g_s.a_f, -1);
    UT_EQ(g_s.tlm.cphi_q30, -1020054600);
    UT_EQ(g_s.tlm.mcmd_q24[2], -25165824);
    check_cmd(&o, 0, 0, OUT_MAX);
    /* re-entering FAR releases the latch: C_phi = -644245200 -> a_f = +1 */
    (void)step6(&p, C_X08, C_Y06, 0, 0, 0, 0);
    UT_UEQ(g_s.region, RSP_RG_FAR);
    UT_EQ(g_s.a_f, 1);
    UT_UEQ(g_s.tlm.latched, 0u);
    UT_UEQ(g_s.tlm.n_switch, 2u);
}

UT_TEST(printed_never_flips)
{
    rsp_params_t p = params();
    rsp_out_t o;
    p.mode = RSP_MODE_PRINTED;
    prime(&p, 1u, C_Y1, W_Y1);
    (void)step6(&p, C_X08, C_Y06, 0, 0, 0, 0);
    UT_EQ(g_s.a_f, 1);
    UT_UEQ(g_s.tlm.mode, RSP_MODE_PRINTED);
    (void)step6(&p, C_X08, -C_Y06, 0, 0, 0, 0);
    UT_EQ(g_s.a_f, 1);
    UT_EQ(g_s.tlm.cphi_q30, -644245200);
    /* MID near -f: C_phi < 0, e_xi = (0, 0, +1), Sgn C_phi = -1: M_z = -m (+1)(-1) = +1.5 N m,
       the law attracts g to -f (the defect of spec 30 §3.5) */
    o = step6(&p, C_X03, -C_Y095, 0, 0, 0, 0);
    UT_EQ(g_s.a_f, 1);
    UT_EQ(g_s.tlm.mcmd_q24[2], 25165824);
    check_cmd(&o, 0, 0, -OUT_MAX);
    UT_UEQ(g_s.tlm.latched, 1u);
    (void)step6(&p, C_X08, -C_Y06, 0, 0, 0, 0);
    UT_UEQ(g_s.region, RSP_RG_FAR);
    UT_EQ(g_s.a_f, 1);
    UT_UEQ(g_s.tlm.latched, 0u);   /* the latch shows the region band; a_f is fixed anyway */
}

/* Guard: g0 = 16 N m s = 2^24 < g_guard = 17.32 N m s (gyro y 18642 -> 16777800, wheel y -57 ->
   H = round(-583.68) = -584, sum 2^24). g = G 2^30 / 2^24 = 64 G. Gyro x 18513 -> G_x = 13421925,
   g_x = 859003200 (0.80); gyro y 11185 -> 10066500, g_y = 644256000 (0.60). */
UT_TEST(guard_never_enters_far)
{
    const rsp_params_t p = params();
    rsp_out_t o;
    prime(&p, 1u, 18642, -57);
    UT_EQ(g_s.tlm.g0_q20, 16777216);
    UT_EQ(g_s.r0.d, 16777216);
    UT_UEQ(g_s.tlm.flags, RSP_H_G0_WAIT | RSP_H_GUARD);
    o = step6(&p, 18513, 11185, 0, 0, 0, 0);
    UT_EQ(g_s.tlm.g_q30[0], 859003200);
    UT_EQ(g_s.tlm.xi_abs_q30, 859003200);
    UT_UEQ(g_s.region, RSP_RG_MID);        /* FAR by the plain thresholds, MID under the guard */
    UT_UEQ(o.health, RSP_H_GUARD | RSP_H_CLIP);
    /* MID, e_xi = (0, 0, 1), C_phi > 0: M_z = -1.5 N m -> -M_max */
    check_cmd(&o, 0, 0, OUT_MAX);
    /* |xi| > eps2 under the guard: a_f still re-selected (C_phi < 0 -> a_f = -1) */
    o = step6(&p, 18513, -11185, 0, 0, 0, 0);
    UT_UEQ(g_s.region, RSP_RG_MID);
    UT_EQ(g_s.a_f, -1);
    UT_UEQ(g_s.tlm.latched, 0u);
    /* |xi| = 0.95 (gyro x 21984 -> 15938400, g_x = 1020057600): still MID */
    (void)step6(&p, 21984, -5592, 0, 0, 0, 0);
    UT_UEQ(g_s.region, RSP_RG_MID);
    /* |xi| = 0.30 < eps2: MID, latched, a_f kept */
    (void)step6(&p, 6942, -17709, 0, 0, 0, 0);
    UT_UEQ(g_s.region, RSP_RG_MID);
    UT_UEQ(g_s.tlm.latched, 1u);
    UT_EQ(g_s.a_f, -1);
    UT_UEQ(g_s.tlm.n_far, 0u);
    UT_UEQ(g_s.tlm.n_mid, 4u);
}

/* ------------------------------------------------------------------ law values */

/* LIN: gyro (44000, C_Y1, -100000), wheels (20000, W_Y1, -10000):
   H = (round(204799.996), 4024, round(-102399.998)) = (204800, 4024, -102400)
   Jw = (725 * 44000, 1073737800, 167.5 * -100000) = (31900000, 1073737800, -16750000)
   g = G = (32104800, 2^30, -16852400); |xi| = 36259089 (0.034): LIN; a_f = +1
   xi = (-g_z, 0, g_x) = (16852400, 0, 32104800); k = 75161928 (q30)
   inner_x = round((16852400 2^20 - 75161928 * 204800) / 2^24) = round(135771.20) = 135771
   inner_y = round(-75161928 * 4024 / 2^24) = round(-18027.92) = -18028
   inner_z = round((32104800 2^20 + 75161928 * 102400) / 2^24) = round(2006550 + 458752.00) = 2465302
   M = round(-0.375 inner) = (round(-50914.125), round(6760.5), round(-924488.25))
     = (-50914, 6761, -924488), inside M_max and the bound
   commands round(-M / 128) = (round(397.77), round(-52.82), round(7222.56)) = (398, -53, 7223) */
UT_TEST(lin_law_value)
{
    const rsp_params_t p = params();
    rsp_out_t o;
    prime(&p, 1u, C_Y1, W_Y1);
    o = step6(&p, 44000, C_Y1, -100000, 20000, W_Y1, -10000);
    UT_EQ(g_s.tlm.h_q20[0], 204800);
    UT_EQ(g_s.tlm.h_q20[2], -102400);
    UT_EQ(g_s.tlm.g_q30[0], 32104800);
    UT_EQ(g_s.tlm.g_q30[1], Q30);
    UT_EQ(g_s.tlm.g_q30[2], -16852400);
    check_floor_root(g_s.tlm.xi_abs_q30, 32104800, -16852400);
    UT_UEQ(g_s.region, RSP_RG_LIN);
    UT_EQ(g_s.tlm.mcmd_q24[0], -50914);
    UT_EQ(g_s.tlm.mcmd_q24[1], 6761);
    UT_EQ(g_s.tlm.mcmd_q24[2], -924488);
    UT_EQ(g_s.tlm.mdel_q24[0], -50914);
    check_cmd(&o, 398, -53, 7223);
    UT_UEQ(o.health, 0u);
}

/* MID: after a LIN tick at g = e_y, gyro (220707, 1181699, -514710), wheels (102400, -51200, 30720):
   H = (round(1048575.98), round(-524287.99), round(314572.79)) = (2^20, -2^19, 314573)
   Jw = (160012575, 1063529100, round(-86213925)) -> g = G = (161061151, 1063004812, -85899352)
   |xi| = 182536004 (0.17 > eps1 + heps): MID; a_f = +1, C_phi > 0
   e_xi_x = round(85899352 2^30 / 182536004) = 505290600, e_xi_z = round(161061151 2^30 / 182536004)
   = 947419086 (Q1.30)
   inner_x = (505290600 - 75161928) / 16 = 26883042 exactly (H_x = 1 N m s)
   inner_y = round(75161928 / 32) = round(2348810.25) = 2348810
   M = (round(-10081140.75), round(-880803.75), ...) = (-10081141, -880804, ...): x and z clip to
   -M_max (commands +19661), y passes: round(880804 / 128) = round(6881.28) = 6881 */
UT_TEST(mid_law_value)
{
    const rsp_params_t p = params();
    rsp_out_t o;
    int64_t lhs;
    prime(&p, 1u, C_Y1, W_Y1);
    (void)step6(&p, 0, C_Y1, 0, 0, W_Y1, 0);
    UT_UEQ(g_s.region, RSP_RG_LIN);
    /* the jump from the LIN tick is not a motion: r_E sees energy from nowhere (ENERGY_ALARM) */
    o = step6(&p, 220707, 1181699, -514710, 102400, -51200, 30720);
    UT_EQ(g_s.tlm.h_q20[0], 1048576);
    UT_EQ(g_s.tlm.h_q20[1], -524288);
    UT_EQ(g_s.tlm.h_q20[2], 314573);
    UT_EQ(g_s.tlm.g_q30[0], 161061151);
    UT_EQ(g_s.tlm.g_q30[2], -85899352);
    UT_EQ(g_s.tlm.xi_abs_q30, 182536004);
    check_floor_root(182536004, 161061151, -85899352);
    /* e_xi_x = 505290600 is the rounded quotient: |85899352 2^30 - 505290600 * 182536004| <= 182536004 / 2 */
    lhs = (int64_t)85899352 * 1073741824 - (int64_t)505290600 * 182536004;
    UT_LE((lhs < 0) ? -lhs : lhs, 91268002);
    UT_UEQ(g_s.region, RSP_RG_MID);
    UT_EQ(g_s.tlm.mcmd_q24[0], -10081141);
    UT_EQ(g_s.tlm.mcmd_q24[1], -880804);
    UT_EQ(g_s.tlm.mdel_q24[0], -M_STAR);
    UT_EQ(g_s.tlm.mdel_q24[1], -880804);
    check_cmd(&o, OUT_MAX, 6881, OUT_MAX);
    UT_UEQ(o.health & ~RSP_H_ENERGY_ALARM, RSP_H_CLIP);
    UT_UEQ(g_s.tlm.n_switch, 1u);
}

/* ------------------------------------------------------------------ distribution */

/* FAR, g_y = 0.6 (gyro y 715828), g_x = +-0.8 with the wheel x momentum inside G_x.
   Wheel x 509952 -> H = round(5221908.0) = 5221908 = h_lim; 522240 -> round(5347737.4) = 5347737
   (h_lim + 0.12 N m s); 478515 -> 4899993 (4.67 N m s). Bounds lo/hi = 160 (H -+ h_lim).
   The ticks jump between unrelated states, so the energy residual is not looked at here. */
UT_TEST(wheel_clip_and_momentum_bound)
{
    const rsp_params_t p = params();
    rsp_out_t o;
    prime(&p, 1u, C_Y1, W_Y1);
    /* H_x = h_lim, g_x > 0: M_x = -M* would raise H_x; lo = 0 -> M_x = 0 (HBOUND), command 0 */
    o = step6(&p, 1177616, C_Y06, 0, 509952, 0, 0);
    UT_EQ(g_s.tlm.h_q20[0], HLIM);
    UT_UEQ(g_s.region, RSP_RG_FAR);
    UT_EQ(g_s.tlm.mcmd_q24[0], -M_STAR);
    UT_EQ(g_s.tlm.mdel_q24[0], 0);
    check_cmd(&o, 0, OUT_MAX, OUT_MAX);
    UT_UEQ(o.health & ~RSP_H_ENERGY_ALARM, RSP_H_HBOUND);
    /* H_x beyond: lo = 160 * 125829 = 20132640 (1.2 N m) -> M_x pushed up to lo, then the final
       clip to +M_max: the command points back (M > 0 lowers H), count -19661. CLIP reports the
       law's own excess only (M_x = -M* was not clipped). */
    o = step6(&p, 1177442, C_Y06, 0, 522240, 0, 0);
    UT_EQ(g_s.tlm.h_q20[0], 5347737);
    UT_EQ(g_s.tlm.mdel_q24[0], M_STAR);
    check_cmd(&o, -OUT_MAX, OUT_MAX, OUT_MAX);
    UT_UEQ(o.health & ~RSP_H_ENERGY_ALARM, RSP_H_HBOUND);
    /* mirror: H_x = -5347737, g_x < 0, M_x = +M*; hi = -20132640 -> -M_max, count +19661 */
    o = step6(&p, -1177442, C_Y06, 0, -522240, 0, 0);
    UT_EQ(g_s.tlm.mcmd_q24[0], M_STAR);
    UT_EQ(g_s.tlm.mdel_q24[0], -M_STAR);
    check_cmd(&o, OUT_MAX, OUT_MAX, OUT_MAX);
    UT_UEQ(o.health & ~RSP_H_ENERGY_ALARM, RSP_H_HBOUND);
    /* the law beyond M_max and the bound together: MID at g ~ (0.3, 0.95, 0) (gyro z 31927 ->
       round(5347772.5) = 5347773 cancels H_z = -5347737 up to 36 LSB), e_xi ~ (0, 0, 1),
       M_z = -m (e_z - k H_z) = -1.5 (1 + 0.07 * 5.1) = -2.04 N m -> CLIP to -M_max; wheel z at
       -(h_lim + 0.12): hi = -20132640 pulls it to -1.2 N m (HBOUND), the final clip gives -M_max:
       count +19661 */
    o = step6(&p, C_X03, C_Y095, 31927, 0, 0, -522240);
    UT_UEQ(g_s.region, RSP_RG_MID);
    UT_EQ(g_s.tlm.mdel_q24[2], -M_STAR);
    UT_UEQ(o.health & ~RSP_H_ENERGY_ALARM, RSP_H_HBOUND | RSP_H_CLIP);
    /* inside the bound (lo = 160 * -321915 = -51506400): the command passes */
    o = step6(&p, 1178060, C_Y06, 0, 478515, 0, 0);
    UT_EQ(g_s.tlm.mdel_q24[0], -M_STAR);
    check_cmd(&o, OUT_MAX, OUT_MAX, OUT_MAX);
    UT_UEQ(o.health & ~RSP_H_ENERGY_ALARM, 0u);
    /* at h_lim but the command lowers |H| (g_x < 0: M_x = +M* <= hi): passes */
    o = step6(&p, -1192021, C_Y06, 0, 509952, 0, 0);
    UT_EQ(g_s.tlm.mdel_q24[0], M_STAR);
    check_cmd(&o, -OUT_MAX, OUT_MAX, OUT_MAX);
    UT_UEQ(o.health & ~RSP_H_ENERGY_ALARM, 0u);
    UT_UEQ(g_s.tlm.n_hbound, 4u);
    UT_UEQ(g_s.tlm.n_clip, 1u);
}

/* ------------------------------------------------------------------ invalid inputs */

/* After the two NEAREST ticks (FAR, a_f = -1, not latched), each bad sample gives zero command,
   its cause and counter, and leaves region, a_f and latch alone. */
static void far_flipped(const rsp_params_t *p)
{
    prime(p, 1u, C_Y1, W_Y1);
    (void)step6(p, C_X08, C_Y06, 0, 0, 0, 0);
    (void)step6(p, C_X08, -C_Y06, 0, 0, 0, 0);
}

static void check_kept(void)
{
    UT_CHECK_UEQ(g_s.region, RSP_RG_FAR);
    UT_CHECK_EQ(g_s.a_f, -1);
    UT_CHECK(!g_s.latched);
    UT_CHECK_EQ(g_s.tlm.mcmd_q24[0], 0);
    UT_CHECK_EQ(g_s.tlm.mdel_q24[0], 0);
}

UT_TEST(bad_gyro_is_an_invalid_tick)
{
    const rsp_params_t p = params();
    rsp_in_t in;
    rsp_out_t o;
    far_flipped(&p);
    in = input(C_X08 + 1, -C_Y06, 0, 0, 0, 0);
    in.sat = 2u;                                   /* gyro y at full scale */
    o = step_in(&p, &in);
    UT_TRUE(cmd_zero(&o));
    UT_UEQ(o.health, RSP_H_GYRO_BAD);
    check_kept();
    in = input(C_X08 + 2, -C_Y06, 4194304, 0, 0, 0);   /* |count| = gyro_max_cnt */
    o = step_in(&p, &in);
    UT_UEQ(o.health, RSP_H_GYRO_BAD);
    in = input(C_X08 + 3, -C_Y06, -4194303, 0, 0, 0);  /* one below: accepted (then an outlier) */
    o = step_in(&p, &in);
    UT_UEQ(o.health & RSP_H_GYRO_BAD, 0u);
    in = input(C_X08 + 4, -C_Y06, 0, 0, 0, 0);
    in.valid = 0x3Bu;                              /* gyro z missing */
    o = step_in(&p, &in);
    UT_UEQ(o.health, RSP_H_GYRO_BAD);
    UT_TRUE(cmd_zero(&o));
    check_kept();
    UT_UEQ(g_s.tlm.n_gyro_bad, 3u);
    UT_UEQ(g_s.bad_run, 4u);
    /* a valid tick resumes the law and resets the run */
    o = step6(&p, C_X08, -C_Y06, 0, 0, 0, 0);
    check_cmd(&o, OUT_MAX, -OUT_MAX, OUT_MAX);
    UT_UEQ(g_s.bad_run, 0u);
}

/* |G| out of the gate max(0.05 g0, 0.5 N m s) = max(round(2^30 * 3277 / 2^16), 524288) = 53690368:
   g ~ (0.8, 0.66): |G| ~ 1.037 g0 passes; (0.8, 0.75): 1.097 g0 is an outlier. */
UT_TEST(outlier_is_an_invalid_tick)
{
    const rsp_params_t p = params();
    rsp_out_t o;
    far_flipped(&p);
    o = step6(&p, C_X08, -787411, 0, 0, 0, 0);     /* 900 * 787411 = 708669900 (0.66) */
    UT_UEQ(o.health & RSP_H_OUTLIER, 0u);
    o = step6(&p, C_X08, -894785, 0, 0, 0, 0);     /* 805306500 (0.75): |G| = 1.0735e9 * 1.0966 */
    UT_UEQ(o.health, RSP_H_OUTLIER);
    UT_TRUE(cmd_zero(&o));
    check_kept();
    UT_UEQ(g_s.tlm.n_outlier, 1u);
}

UT_TEST(gyro_stale_after_n_stale_repeats)
{
    const rsp_params_t p = params();
    rsp_out_t o;
    uint32_t k;
    far_flipped(&p);
    /* the word (C_X08, -C_Y06, 0) was last tick's: repeats 1..19 are still valid (wheel x
       dithers so that no wheel word is frozen under torque) */
    for (k = 1u; k < 20u; k++) {
        int32_t d = (int32_t)(k % 2u);
        o = step6(&p, C_X08, -C_Y06, 0, d, d, d);
        UT_UEQ(o.health & RSP_H_GYRO_STALE, 0u);
    }
    UT_UEQ(o.health & (RSP_H_WHL_BAD | RSP_H_GYRO_BAD), 0u);
    o = step6(&p, C_X08, -C_Y06, 0, 0, 0, 0);       /* 20th repeat */
    UT_UEQ(o.health, RSP_H_GYRO_STALE);
    UT_TRUE(cmd_zero(&o));
    check_kept();
    o = step6(&p, C_X08, -C_Y06, 0, 1, 0, 0);       /* still frozen */
    UT_UEQ(o.health, RSP_H_GYRO_STALE);
    UT_UEQ(g_s.tlm.n_gyro_stale, 2u);
    o = step6(&p, C_X08 + 1, -C_Y06, 0, 0, 0, 0);   /* moves again */
    UT_UEQ(o.health & RSP_H_GYRO_STALE, 0u);
    UT_TRUE(!cmd_zero(&o));
}

/* Wheel x missing in FAR (M_del_x = -M* each tick): H_x := H_x,last - M_del Ts, with
   M* Ts = 2516582 * 100000 / (16 * 10^6) = 15728.64 -> 15729 (2^-20 N m s) per tick. Ten ticks
   are propagated (WHL_EST, valid), the eleventh is WHL_BAD. The gyro x word dithers by one count. */
UT_TEST(wheel_missing_is_propagated_then_bad)
{
    const rsp_params_t p = params();
    rsp_in_t in;
    rsp_out_t o;
    uint32_t k;
    far_flipped(&p);
    (void)step6(&p, C_X08, -C_Y06, 0, 1000, 0, 0);   /* H_x = round(10239.9998) = 10240, M_x = -M* */
    UT_EQ(g_s.tlm.h_q20[0], 10240);
    UT_EQ(g_s.tlm.mdel_q24[0], -M_STAR);
    for (k = 1u; k <= 10u; k++) {
        in = input(C_X08 + (int32_t)(k % 2u), -C_Y06, 0, 0, 0, 0);
        in.valid = 0x37u;
        o = step_in(&p, &in);
        UT_UEQ(o.health, RSP_H_WHL_EST);
        UT_EQ(g_s.tlm.h_q20[0], 10240 + (int32_t)k * 15729);
        check_cmd(&o, OUT_MAX, -OUT_MAX, OUT_MAX);
    }
    UT_UEQ(g_s.tlm.n_whl_est, 10u);
    in = input(C_X08 + 1, -C_Y06, 0, 0, 0, 0);
    in.valid = 0x37u;
    o = step_in(&p, &in);
    UT_UEQ(o.health, RSP_H_WHL_BAD);
    UT_TRUE(cmd_zero(&o));
    check_kept();
    UT_UEQ(g_s.tlm.n_whl_bad, 1u);
    o = step6(&p, C_X08, -C_Y06, 0, 2000, 0, 0);       /* back: measured again */
    UT_UEQ(o.health, 0u);
    UT_EQ(g_s.tlm.h_q20[0], 20480);                    /* round(20479.9996) */
}

/* A wheel word frozen while |M_del| > 0.01 N m: the n_stale-th repeat under torque is WHL_BAD, and
   it stays bad while frozen (zero torque holds the run, it does not clear it). */
UT_TEST(wheel_stale_under_torque)
{
    const rsp_params_t p = params();
    rsp_out_t o;
    uint32_t k;
    far_flipped(&p);   /* its two FAR ticks had wheels (0, 0, 0) and M = -+M*: repeats 1 */
    for (k = 2u; k < 20u; k++) {
        o = step6(&p, C_X08 + (int32_t)(k % 2u), -C_Y06, 0, 0, 0, 0);
        UT_UEQ(o.health, 0u);
    }
    o = step6(&p, C_X08, -C_Y06, 0, 0, 0, 0);
    UT_UEQ(o.health, RSP_H_WHL_BAD);
    UT_TRUE(cmd_zero(&o));
    o = step6(&p, C_X08 + 1, -C_Y06, 0, 0, 0, 0);
    UT_UEQ(o.health, RSP_H_WHL_BAD);
    UT_UEQ(g_s.tlm.n_whl_bad, 2u);
    check_kept();
}

/* WHEEL_FAULT (spec 30 §8): the far law at g = e_z commands M = -M* on every axis, so each wheel
   should gain 0.015 N m s per tick; the wheel words only dither by one count (9.8e-6 N m s, so the
   frozen-word test stays quiet), i.e. the wheels deliver |M| <= 1e-4 N m against 0.15 commanded:
   0.15 > 0.03 N m. From the second law tick (the first with a previous sample) the miss counts;
   10 s = 10 * 655360 / 2^16 = 100 ticks later the fault latches: command zero from that tick on,
   FSW_H_MODULE through the adapter, until rsp_init. */
UT_TEST(wheel_not_following_latches_wheel_fault)
{
    const rsp_params_t p = params();
    rsp_out_t o;
    uint32_t k;
    prime(&p, 2u, 1602599, 12);
    for (k = 1u; k <= 101u; k++) {
        int32_t d = (int32_t)(k & 1u);
        o = step6(&p, d, 0, 1602599, d, d, 12 + d);
        if (k <= 100u) {
            check_cmd(&o, OUT_MAX, OUT_MAX, OUT_MAX);
            UT_UEQ(o.health & RSP_H_WHEEL_FAULT, 0u);
        }
    }
    UT_TRUE(cmd_zero(&o));
    UT_UEQ(o.health & RSP_H_WHEEL_FAULT, RSP_H_WHEEL_FAULT);
    UT_UEQ(g_s.follow_run[0], 100u);
    o = step6(&p, 0, 0, 1602599, 0, 0, 12);
    UT_TRUE(cmd_zero(&o));
    UT_UEQ(o.health & RSP_H_WHEEL_FAULT, RSP_H_WHEEL_FAULT);
    rsp_init(&g_s, &p);
    UT_TRUE(!g_s.wheel_fault);
}

UT_TEST(input_fault_latches_after_n_fault)
{
    const rsp_params_t p = params();
    rsp_in_t in = input(C_X08, -C_Y06, 0, 0, 0, 0);
    rsp_out_t o;
    uint32_t k;
    far_flipped(&p);
    in.valid = 0x3Eu;
    for (k = 1u; k < 50u; k++) {
        o = step_in(&p, &in);
        UT_UEQ(o.health, RSP_H_GYRO_BAD);
    }
    o = step_in(&p, &in);                                  /* 50th in a row */
    UT_UEQ(o.health, RSP_H_GYRO_BAD | RSP_H_INPUT_FAULT);
    check_kept();
    o = step6(&p, C_X08 + 1, -C_Y06, 0, 0, 0, 0);          /* valid again: the law runs, still latched */
    UT_UEQ(o.health, RSP_H_INPUT_FAULT);
    check_cmd(&o, OUT_MAX, -OUT_MAX, OUT_MAX);
    UT_UEQ(g_s.bad_run, 0u);
    UT_UEQ(g_s.tlm.n_gyro_bad, 50u);
    rsp_init(&g_s, &p);
    UT_TRUE(!g_s.input_fault);
}

/* An fx status zeroes the step's command: gyro y 4194303 (just below full scale) makes
   J_y omega_y = 900 * 4194303 = 3774872700 > 2^31 - 1, which saturates (SAT_HI). */
UT_TEST(fx_status_zeroes_the_command)
{
    const rsp_params_t p = params();
    rsp_out_t o;
    far_flipped(&p);
    o = step6(&p, C_X08, 4194303, 0, 0, 0, 0);
    UT_TRUE(cmd_zero(&o));
    UT_UEQ(o.health, RSP_H_OVERFLOW | RSP_H_OUTLIER | FX_ST_SAT_HI);
    UT_UEQ(g_s.tlm.n_overflow, 1u);
    UT_UEQ(g_s.tlm.health_sticky & (RSP_H_OVERFLOW | FX_ST_SAT_HI), RSP_H_OVERFLOW | FX_ST_SAT_HI);
}

/* ------------------------------------------------------------------ energy */

/* omega = (0, C_Y1, 0) held, the wheel y ramping 1000 counts a tick (H_y 4024, 14264, 24504,
   34744: +10240 each, a constant wheel command). omega_y = 1193042 * 64 = 76354688 (q28).
   T = 1/2 Jw_y omega_y = 1073737800 * 76354688 / 2^17 = 625495259955.2 -> 625495259955 (145.6 J),
   constant, so T0 = T. Each tick W -= (2 omega_y) dH / 2^17 = 152709376 * 10240 / 2^17 = 11930420
   exactly, r_E = -W = 11930420 k. A gap (one gyro-invalid tick) is not integrated across: the next
   valid tick keeps r_E and re-bases W = T - T0 - r_E. Then a wheel jump of 200000 counts
   (H_y 55224 -> 2103224, dH = 2048000) adds 152709376 * 2048000 / 2^17 = 2386084000 to r_E:
   2421875260 > e_alarm = 2^31 -> ENERGY_ALARM. */
UT_TEST(energy_bookkeeping)
{
    const rsp_params_t p = params();
    rsp_in_t gap = input(0, C_Y1, 0, 0, 4393, 0);
    rsp_out_t o;
    int32_t k;
    prime(&p, 1u, C_Y1, W_Y1);
    for (k = 0; k < 4; k++) {
        o = step6(&p, 0, C_Y1, 0, 0, W_Y1 + (1000 * k), 0);
        UT_EQ(g_s.tlm.h_q20[1], 4024 + (10240 * k));
        UT_EQ(g_s.tlm.t_q32, INT64_C(625495259955));
        UT_EQ(g_s.tlm.w_q32, -(int64_t)11930420 * k);
        UT_EQ(g_s.tlm.re_q32, (int64_t)11930420 * k);
        UT_UEQ(o.health & RSP_H_ENERGY_ALARM, 0u);
    }
    UT_EQ(g_s.t0_q32, INT64_C(625495259955));
    gap.valid = 0x3Du;
    o = step_in(&p, &gap);
    UT_UEQ(o.health, RSP_H_GYRO_BAD);
    o = step6(&p, 0, C_Y1, 0, 0, 5393, 0);
    UT_EQ(g_s.tlm.re_q32, 35791260);
    UT_EQ(g_s.tlm.w_q32, -35791260);
    UT_UEQ(o.health & RSP_H_ENERGY_ALARM, 0u);
    o = step6(&p, 0, C_Y1, 0, 0, 205393, 0);
    UT_EQ(g_s.tlm.h_q20[1], 2103224);
    UT_EQ(g_s.tlm.w_q32, -INT64_C(2421875260));
    UT_EQ(g_s.tlm.re_q32, INT64_C(2421875260));
    UT_UEQ(o.health & RSP_H_ENERGY_ALARM, RSP_H_ENERGY_ALARM);
}

/* ------------------------------------------------------------------ determinism */

static uint64_t mix(uint64_t h, int64_t v)
{
    return (h ^ (uint64_t)v) * UINT64_C(0x100000001B3);
}

/* A seeded random walk of G around |G| = 2^30 with dropouts, wheel gaps and outliers. */
static uint64_t replay(const rsp_params_t *p)
{
    uint64_t rng = 12345u;
    uint64_t h = UINT64_C(0xCBF29CE484222325);
    int32_t cx = 0;
    int32_t cz = 0;
    int32_t wx = 0;
    uint32_t k;
    prime(p, 1u, C_Y1, W_Y1);
    for (k = 0u; k < 600u; k++) {
        uint64_t r = ut_rng_next(&rng);
        rsp_in_t in;
        rsp_out_t o;
        int64_t gx;
        int64_t gz;
        int64_t rest;
        cx += (int32_t)(r % 80001u) - 40000;
        cz += (int32_t)((r >> 16) % 120001u) - 60000;
        wx += (int32_t)((r >> 32) % 2001u) - 1000;
        cx = (cx > 1400000) ? 1400000 : ((cx < -1400000) ? -1400000 : cx);
        cz = (cz > 4000000) ? 4000000 : ((cz < -4000000) ? -4000000 : cz);
        gx = (int64_t)cx * 725;
        gz = ((int64_t)cz * 335) / 2;
        rest = ((int64_t)1 << 60) - (gx * gx) - (gz * gz);
        /* wheels y and z dither by a count so that their words are never frozen under torque */
        in = input(cx, (rest > 0) ? (int32_t)(fx_isqrt64((uint64_t)rest) / 900u) : 1000, cz, wx,
                   (int32_t)((r >> 40) % 3u) - 1, (int32_t)((r >> 44) % 3u) - 1);
        if ((r >> 48) % 50u == 0u) {
            in.valid = 0x3Eu;
        }
        if ((r >> 54) % 40u == 0u) {
            in.valid &= ~0x08u;
        }
        o = step_in(p, &in);
        h = mix(h, o.whl_torque_cnt[0]);
        h = mix(h, o.whl_torque_cnt[1]);
        h = mix(h, o.whl_torque_cnt[2]);
        h = mix(h, (int64_t)o.health);
        h = mix(h, g_s.tlm.xi_abs_q30);
        h = mix(h, g_s.tlm.re_q32);
        h = mix(h, g_s.tlm.rho_lp_q30);
        h = mix(h, g_s.a_f);
    }
    return h;
}

UT_TEST(deterministic_replay)
{
    const rsp_params_t p = params();
    uint64_t h1 = replay(&p);
    rsp_tlm_t t1 = g_s.tlm;
    uint64_t h2 = replay(&p);
    UT_UEQ(h1, h2);
    UT_UEQ(t1.n_switch, g_s.tlm.n_switch);
    UT_UEQ(t1.health_sticky, g_s.tlm.health_sticky);
    UT_EQ(t1.w_q32, g_s.tlm.w_q32);
    /* the walk visited every region and the invalid paths */
    UT_TRUE(g_s.tlm.n_lin > 0u);
    UT_TRUE(g_s.tlm.n_mid > 0u);
    UT_TRUE(g_s.tlm.n_far > 0u);
    UT_TRUE(g_s.tlm.n_gyro_bad > 0u);
    UT_TRUE(g_s.tlm.n_whl_est > 0u);
    UT_UEQ(g_s.tlm.revision, 7u);
}

/* The optional G filter (spec 30 §3.6), from the prime's last state G = (0, -2^30, 0) (g0 = 2^30 q20 =
   1024 N m s, so g_q30 equals G_hat_q20 exactly and every expected value below is an integer formula):
   1. the first RUN tick seeds G_hat = G_k: g is the raw direction;
   2. a wheel-x step of H_x = 512 000 counts * I_w = 5 242 880 q20 (5 N m s): theta = omega Ts is
      parallel to G_hat (rate about y only), so theta x G_hat = 0 and G_hat^- = G_hat; the blend moves
      G_hat_x by alpha H_x = round(5 242 880 * 53 687 091 / 2^30) = 262 144; the Newton rescale
      c = 2 - |G_hat| / g0 lowers G_hat_y by 2^30 (262 144 / 2^30)^2 / 2 = 32 LSB (and G_hat_x by
      262 144 * 3e-8 < 0.01 LSB): g = (262 144, -(2^30 - 32), 0), +-1 LSB for the two roundings;
   3. an invalid tick drops the estimate: the next valid tick is seeded from G_k again, g_x = H_x / g0.
   With the filter off the same step gives the raw g_x = 5 242 880 at once. */
UT_TEST(g_filter_blends_and_reseeds)
{
    rsp_params_t p = params();
    const int32_t hx = 5242880;
    rsp_in_t in;
    p.gfilt_alpha_q30 = 53687091;   /* 0.05 */
    prime(&p, 1u, C_Y1, W_Y1);
    (void)step6(&p, 0, -C_Y1, 0, 0, -W_Y1, 0);
    UT_EQ(g_s.tlm.g_q30[0], 0);
    UT_EQ(g_s.tlm.g_q30[1], -Q30);
    (void)step6(&p, 0, -C_Y1, 0, 512000, -W_Y1, 0);
    UT_TRUE((g_s.tlm.g_q30[0] >= (262144 - 1)) && (g_s.tlm.g_q30[0] <= (262144 + 1)));
    UT_TRUE((g_s.tlm.g_q30[1] >= (-Q30 + 32 - 1)) && (g_s.tlm.g_q30[1] <= (-Q30 + 32 + 1)));
    UT_EQ(g_s.tlm.g_q30[2], 0);
    in = input(0, -C_Y1, 0, 512000, -W_Y1, 0);
    in.valid = 0x3Eu;   /* gyro x missing: invalid tick */
    (void)step_in(&p, &in);
    (void)step6(&p, 1, -C_Y1, 0, 512000, -W_Y1, 0);   /* gyro x 1 count: J_x omega_x = 2900 2^-22 = 725 q20 */
    UT_EQ(g_s.tlm.g_q30[0], hx + 725);
    p.gfilt_alpha_q30 = 0;
    prime(&p, 1u, C_Y1, W_Y1);
    (void)step6(&p, 0, -C_Y1, 0, 0, -W_Y1, 0);
    (void)step6(&p, 0, -C_Y1, 0, 512000, -W_Y1, 0);
    UT_EQ(g_s.tlm.g_q30[0], hx);
}

/* The G filter's propagation (spec 30 §3.6) with the rate across G: after the prime, gyro x = 4096
   counts (omega_x = 2^-10 rad/s, J_x omega_x = 2 969 600 q20 exactly) on top of G_y = -2^30 q20, two
   identical ticks: the first seeds G_hat = G_k, the second propagates by theta = omega Ts (theta_x =
   9.77e-5, theta_y = -0.02844 rad) and blends back towards G_k. Expected values from the spec's
   formulas in exact rational arithmetic (tools: Python fractions; not from this code):
   G_hat^- = G_hat - theta x G_hat + 1/2 theta x (theta x G_hat); G_hat = G_hat^- + alpha (G_k - G_hat^-);
   times c = 2 - |G_hat| / g0 (g0 = 2^30 q20):  g = (2 969 864.1, -1 073 737 716.6, 19 369.8) LSB.
   Tolerance 3 LSB: theta rounded to Q1.30 (1/2 LSB times |G| = 2^30 q20: 1/2 LSB of q20), the two cross
   products and the half (1/2 each), the blend and the rescale (1/2 each) - g = G_hat exactly here. */
UT_TEST(g_filter_propagates_with_the_body_rate)
{
    rsp_params_t p = params();
    p.gfilt_alpha_q30 = 53687091;   /* 0.05 */
    prime(&p, 1u, C_Y1, W_Y1);
    (void)step6(&p, 4096, -C_Y1, 0, 0, -W_Y1, 0);
    UT_EQ(g_s.tlm.g_q30[0], 2969600);   /* seeded: the raw direction */
    (void)step6(&p, 4096, -C_Y1, 0, 0, -W_Y1, 0);
    UT_TRUE((g_s.tlm.g_q30[0] >= (2969864 - 3)) && (g_s.tlm.g_q30[0] <= (2969864 + 3)));
    UT_TRUE((g_s.tlm.g_q30[1] >= (-1073737717 - 3)) && (g_s.tlm.g_q30[1] <= (-1073737717 + 3)));
    UT_TRUE((g_s.tlm.g_q30[2] >= (19370 - 3)) && (g_s.tlm.g_q30[2] <= (19370 + 3)));
}

/* Gyrodines (spec 30 §4): the first law tick with g = +e_z (FAR; C_phi = 0 -> a_f = +1) commands
   M = -M* Sgn(g) = (-1, -1, -1) N m (Sgn 0 = +1). At the null configuration Ahat Ahat^T = diag(1, 1, 2),
   so y = (Hdot_c / h_g) / (diag(1, 1, 2) + lambda0) = (1/7.5) (1/1.05, 1/1.05, 1/2.05) and
   beta_dot = Ahat^T y = sqrt(1/2) (y_z - y_y, y_y + y_z, y_x + y_z, y_z - y_x)
   = (-0.043801, 0.135782, 0.135782, -0.043801) rad/s (below u_max: no scaling)
   -> counts (x 2^16) -2 870.5 -> -2 871, 8 898.7 -> 8 899 (+-1: the solve's LSBs sit far below a
   count, but the .5 of -2 870.5 is within 0.02 counts of the boundary); the delivered moment of those
   counts, -h_g Ahat cnt 2^-16 = (-0.952451, -0.952451, -0.975595) N m = (-15 979 482, -15 979 482,
   -16 367 768) 2^-24 N m, +-64 LSB (one count of slack on a gimbal moves it by 7.5 * 0.707 * 2^-16 N m
   = 1 357 LSB: the bound applies when the counts match). No wheel torque. */
UT_TEST(gyrodines_far_law_is_steered)
{
    rsp_params_t p = params();
    rsp_out_t o;
    p.act_kind = RSP_ACT_GYRODINES;
    p.mstar_q24 = 16777216;   /* M* = 1 N m */
    p.gguard_q20 = 62914560;  /* 60 N m s */
    prime(&p, 2u, C_Z02, 0);
    o = step6(&p, 0, 0, C_Z02, 0, 0, 0);
    UT_UEQ(g_s.tlm.region, RSP_RG_FAR);
    UT_EQ(g_s.tlm.a_f, 1);
    UT_EQ(g_s.tlm.mcmd_q24[0], -16777216);
    UT_EQ(g_s.tlm.mcmd_q24[2], -16777216);
    check_cmd(&o, 0, 0, 0);
    UT_TRUE((o.gimbal_rate_cnt[0] >= -2872) && (o.gimbal_rate_cnt[0] <= -2870));
    UT_EQ(o.gimbal_rate_cnt[1], 8899);
    UT_EQ(o.gimbal_rate_cnt[2], 8899);
    UT_TRUE((o.gimbal_rate_cnt[3] >= -2872) && (o.gimbal_rate_cnt[3] <= -2870));
    if ((o.gimbal_rate_cnt[0] == -2871) && (o.gimbal_rate_cnt[3] == -2871)) {
        UT_TRUE((g_s.tlm.mdel_q24[0] >= (-15979482 - 64)) && (g_s.tlm.mdel_q24[0] <= (-15979482 + 64)));
        UT_TRUE((g_s.tlm.mdel_q24[1] >= (-15979482 - 64)) && (g_s.tlm.mdel_q24[1] <= (-15979482 + 64)));
        UT_TRUE((g_s.tlm.mdel_q24[2] >= (-16367768 - 64)) && (g_s.tlm.mdel_q24[2] <= (-16367768 + 64)));
    }
    UT_EQ(g_s.tlm.cmg_rate_cnt[1], 8899);
    UT_TRUE((o.health & (RSP_H_SINGULAR | RSP_H_RATE_LIMITED | RSP_H_OVERFLOW)) == 0u);
    /* m_s = sqrt 2 at the null configuration: 379 625 062 Q3.28, within the sin/cos LSBs */
    UT_TRUE((g_s.tlm.cmg_ms_q28 >= (379625062 - 64)) && (g_s.tlm.cmg_ms_q28 <= (379625062 + 64)));
}

/* Gyrodines, faults (spec 30 §8): a missing gimbal angle makes the tick invalid (WHL_BAD, zero
   rates: no propagation of H); a rotor 2 % below nominal (beyond rotor_tol 1 %) for n_fault ticks
   latches ROTOR_FAULT and the rates are zero from then on; 0.9 % below does not. */
UT_TEST(gyrodine_faults)
{
    rsp_params_t p = params();
    rsp_out_t o;
    rsp_in_t in;
    uint32_t k;
    p.act_kind = RSP_ACT_GYRODINES;
    p.mstar_q24 = 16777216;
    p.gguard_q20 = 62914560;
    prime(&p, 2u, C_Z02, 0);
    in = input(0, 0, C_Z02, 0, 0, 0);
    in.valid &= ~(1u << 8u);   /* gimbal 3 missing */
    o = step_in(&p, &in);
    UT_TRUE((o.health & RSP_H_WHL_BAD) != 0u);
    UT_EQ(o.gimbal_rate_cnt[1], 0);
    for (k = 0u; k < p.n_fault + 5u; k++) {
        int32_t cz = ((k % 2u) == 0u) ? -C_Z02 : C_Z02;
        in = input(0, 0, cz, 0, 0, 0);
        in.rotor_cnt[2] = ROTOR_NOM - 1382;   /* -0.9 %: within rotor_tol */
        o = step_in(&p, &in);
    }
    UT_TRUE((o.health & RSP_H_ROTOR_FAULT) == 0u);
    UT_TRUE(o.gimbal_rate_cnt[1] != 0);
    for (k = 0u; k < p.n_fault; k++) {
        int32_t cz = ((k % 2u) == 0u) ? -C_Z02 : C_Z02;
        in = input(0, 0, cz, 0, 0, 0);
        in.rotor_cnt[2] = ROTOR_NOM - 3072;   /* -2 % */
        o = step_in(&p, &in);
        if ((k + 1u) < p.n_fault) {
            UT_CHECK((o.health & RSP_H_ROTOR_FAULT) == 0u);
        }
    }
    UT_TRUE((o.health & RSP_H_ROTOR_FAULT) != 0u);
    UT_EQ(o.gimbal_rate_cnt[0], 0);
    UT_EQ(o.gimbal_rate_cnt[1], 0);
    UT_EQ(g_s.tlm.mdel_q24[2], 0);
    in = input(0, 0, C_Z02, 0, 0, 0);   /* the rotor back at nominal: still latched */
    o = step_in(&p, &in);
    UT_TRUE((o.health & RSP_H_ROTOR_FAULT) != 0u);
    UT_EQ(o.gimbal_rate_cnt[1], 0);
}

/* Reporting checks of spec 30 §8 (the command is not changed by them).
   HBOUND_STUCK: with the default k the LIN law always pulls a wheel near its bound inwards (m k |H| >
   m |xi| once |H| > 1.43 N m s), so the test takes k = 1 LSB: then M_x = -m xi_x. From the prime's
   g = -e_y (a_f = -1), gyro z 320 520 counts (G_z = 51.2 N m s: xi_x = g_z = 0.05, LIN) and wheel x at
   509 440 counts (4.975 N m s, inside h_lim = 4.98): the law asks M_x = -0.075 N m, the clamp allows
   >= (4.975 - 4.98) / Ts = -0.05: HBOUND every tick, HBOUND_STUCK from the 6 000th (600 s at 10 Hz). */
UT_TEST(hbound_stuck_after_600_s_in_lin)
{
    rsp_params_t p = params();
    uint32_t k;
    rsp_out_t o;
    p.k_q30 = 1;
    prime(&p, 1u, C_Y1, W_Y1);
    for (k = 0u; k < 6000u; k++) {
        o = step6(&p, (int32_t)(k & 1u), -C_Y1, 320520, 509440 + (int32_t)(k & 1u), -W_Y1, 0);
        UT_CHECK((o.health & RSP_H_HBOUND) != 0u);
        if (k < 5999u) {
            UT_CHECK((o.health & RSP_H_HBOUND_STUCK) == 0u);
        }
    }
    UT_UEQ(g_s.tlm.region, RSP_RG_LIN);
    UT_TRUE((o.health & RSP_H_HBOUND_STUCK) != 0u);
}

/* ENERGY_LOW: T >= |J omega|^2 / (2 J_y) >= (g0 - |H|)^2 / (2 J_y) for any true state. From the prime's
   G_y = -1024 N m s (g0 = 1024, |H| = 0.0038): a gyro y word 0.999 of nominal (1 191 849 counts: T =
   145.34 J against the floor 145.64 - 0.5) passes; 0.96 of nominal (1 145 320 counts: |G| = 983 N m s,
   inside the 5 % outlier gate; T = 134.2 J) raises ENERGY_LOW: a -4 % gyro scale error. */
UT_TEST(energy_floor_flags_a_low_t)
{
    rsp_params_t p = params();
    rsp_out_t o;
    prime(&p, 1u, C_Y1, W_Y1);
    o = step6(&p, 0, -1191849, 0, 0, -W_Y1, 0);
    UT_TRUE((o.health & (RSP_H_ENERGY_LOW | RSP_H_OUTLIER)) == 0u);
    o = step6(&p, 0, -1145320, 0, 0, -W_Y1, 0);
    UT_TRUE((o.health & RSP_H_OUTLIER) == 0u);
    UT_TRUE((o.health & RSP_H_ENERGY_LOW) != 0u);
}

/* FAR_T_RISE: g = -e_z (FAR) with |omega_z| growing by one gyro count per tick: T = J_z omega_z^2 / 2
   rises, and the first complete 100 s window (1 000 FAR ticks at 10 Hz) reports its change (about
   +2 J_z omega dOmega = 670 * 0.2 * 1000 * 2^-22 = +0.032 J) and FAR_T_RISE; the same with |omega_z|
   shrinking reports a negative change and no bit. Wheel words dither by one count (not stale). */
UT_TEST(far_t_slope_is_reported)
{
    rsp_params_t p = params();
    rsp_out_t o;
    uint32_t k;
    int32_t dir;
    for (dir = 1; dir >= -1; dir -= 2) {
        prime(&p, 2u, C_Z02, 0);
        for (k = 1u; k <= 1001u; k++) {
            int32_t d = (int32_t)(k & 1u);
            o = step6(&p, 0, 0, -C_Z02 - (dir * (int32_t)k), d, d, d);
            if (k < 1001u) {
                UT_CHECK((o.health & RSP_H_FAR_T_RISE) == 0u);
                UT_CHECK(g_s.tlm.t_far_d100_q32 == 0);
            }
        }
        UT_UEQ(g_s.tlm.region, RSP_RG_FAR);
        if (dir > 0) {
            /* 0.032 J = 1.37e8 in 2^-32 J; within 10 % (the wheel dither and the rounding of T) */
            UT_TRUE((g_s.tlm.t_far_d100_q32 > INT64_C(123000000)) && (g_s.tlm.t_far_d100_q32 < INT64_C(151000000)));
            UT_TRUE((o.health & RSP_H_FAR_T_RISE) != 0u);
        } else {
            UT_TRUE(g_s.tlm.t_far_d100_q32 < INT64_C(-123000000));
            UT_TRUE((o.health & RSP_H_FAR_T_RISE) == 0u);
        }
    }
}

int main(void)
{
    UT_CASES(cases) = {
        UT_CASE(params_check_names_each_bad_field),
        UT_CASE(params_check_refuses_unrepresentable_limits),
        UT_CASE(g0_is_the_rounded_mean_of_valid_ticks),
        UT_CASE(low_momentum_commands_zero_for_good),
        UT_CASE(g_along_z_ties_to_a_f_plus),
        UT_CASE(far_law_signs),
        UT_CASE(first_region_follows_the_plain_thresholds),
        UT_CASE(region_hysteresis_both_ways),
        UT_CASE(nearest_flips_in_far_and_latches_outside),
        UT_CASE(printed_never_flips),
        UT_CASE(guard_never_enters_far),
        UT_CASE(lin_law_value),
        UT_CASE(mid_law_value),
        UT_CASE(wheel_clip_and_momentum_bound),
        UT_CASE(bad_gyro_is_an_invalid_tick),
        UT_CASE(outlier_is_an_invalid_tick),
        UT_CASE(gyro_stale_after_n_stale_repeats),
        UT_CASE(wheel_missing_is_propagated_then_bad),
        UT_CASE(wheel_stale_under_torque),
        UT_CASE(wheel_not_following_latches_wheel_fault),
        UT_CASE(input_fault_latches_after_n_fault),
        UT_CASE(fx_status_zeroes_the_command),
        UT_CASE(energy_bookkeeping),
        UT_CASE(deterministic_replay),
        UT_CASE(g_filter_blends_and_reseeds),
        UT_CASE(g_filter_propagates_with_the_body_rate),
        UT_CASE(gyrodines_far_law_is_steered),
        UT_CASE(gyrodine_faults),
        UT_CASE(hbound_stuck_after_600_s_in_lin),
        UT_CASE(energy_floor_flags_a_low_t),
        UT_CASE(far_t_slope_is_reported),
    };
    return UT_RUN("rsp", cases);
}
