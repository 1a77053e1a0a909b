/*
 * The HOLD law (fsw/pd/pd.c; spec 40 §3, §4.2, §5, §8) against numbers derived by hand in the
 * comments, never values printed by the code under test. Host and target.
 *
 * Units used throughout (pd.h, spec 40 §5): y in counts of 2^-26 rad enters as q30 = 16 counts;
 * G_P, G_D in uq16; acc = G_P y + G_D dy at LSB 2^-46; M = -rnd(acc / 2^18) in q28; the actuator
 * count is rnd(M / 2^8) (LSB 2^-20 N m). rnd is half away from zero (spec 00 §1.3), written out
 * below independently of fsw/fx.
 *
 * Default-table gains (PD_TBL_DEFAULT, tools/pd/design.py), Ty = 0.25 s so 1/Ty = 4 exactly:
 *   yaw   k0 2, k1 20, k2_nom 745 s: G_P = 40 N m/rad   -> 40 2^16,  G_D = 2 745 4 = 5960 -> 5960 2^16
 *   roll  k0 2, k1 15, k2_nom 135 s: G_P = 30           -> 30 2^16,  G_D = 2 135 4 = 1080 -> 1080 2^16
 *   pitch k0 2, k1 20, k2_nom 475 s: G_P = 40           -> 40 2^16,  G_D = 2 475 4 = 3800 -> 3800 2^16
 * With integer gains M is exact: M = -(G_P 2^16 16 y + G_D 2^16 16 dy) / 2^18 = -4 (G_P y + G_D dy)
 * for y, dy in counts, so pitch gives M = -160 y - 15200 dy (q28), with no rounding at all.
 */
#include "pd_mission.h"
#include "pd_tables.h"
#include "ut.h"

#define CH_YAW   0u
#define CH_ROLL  1u
#define CH_PITCH 2u

#define Q16(v)   ((int64_t)(v) * 65536)
#define K_Q22(s) ((uint32_t)(s) * 4194304u)          /* an integer k in s -> uq22 */

#define GP40_Q16    Q16(40)      /* yaw, pitch: k0 k1 = 2 20 */
#define GP30_Q16    Q16(30)      /* roll: 2 15 */
#define GD_PITCH_Q16 Q16(3800)   /* 2 475 / 0.25 */
#define GD_YAW_Q16   Q16(5960)   /* 2 745 / 0.25 */
#define GD_ROLL_Q16  Q16(1080)   /* 2 135 / 0.25 */

#define M_MAX_Q28   536870912    /* 2 N m = 2^29 q28 */
#define BETA_WARN   8388608      /* 0.5 rad = 2^23 q24 */
#define BETA_LIM    13176795     /* pi/4 2^24 = 13 176 794.6 -> 13 176 795 */
#define F_003_Q32   128849019u   /* 0.03 2^32 = 128 849 018.88 -> 128 849 019 */

/* Large objects in static storage (the target runner's stack is small). Test-only state. */
static pd_state_t g_s;
static pd_state_t g_s2;
static pd_params_t g_p;
static pd_params_t g_p2;

/* ------------------------------------------------------------------ independent arithmetic */

/* round(v / 2^n), n >= 1, half away from zero: add half to the magnitude, floor, restore the sign. */
static int64_t rnd_shr(int64_t v, uint32_t n)
{
    const uint64_t mag = (v < 0) ? ((uint64_t)0 - (uint64_t)v) : (uint64_t)v;
    const uint64_t q = (mag + ((uint64_t)1 << (n - 1u))) >> n;
    return (v < 0) ? -(int64_t)q : (int64_t)q;
}

static int64_t clamp_m(int64_t m)
{
    return (m > M_MAX_Q28) ? M_MAX_Q28 : ((m < -M_MAX_Q28) ? -M_MAX_Q28 : m);
}

/* FAST / FAST_AVGP: M = -rnd((G_P x + G_D dy) / 2^18), unclamped; x and dy in q30. */
static int64_t m_raw(int64_t gp_q16, int64_t gd_q16, int64_t x_q30, int64_t dy_q30)
{
    return -rnd_shr((gp_q16 * x_q30) + (gd_q16 * dy_q30), 18u);
}

/* The same from counts (q30 = 16 counts), clamped to +-M_max. */
static int32_t m_fast(int64_t gp_q16, int64_t gd_q16, int32_t y_cnt, int32_t dy_cnt)
{
    return (int32_t)clamp_m(m_raw(gp_q16, gd_q16, 16 * (int64_t)y_cnt, 16 * (int64_t)dy_cnt));
}

static int32_t cnt_of(int32_t m_q28)
{
    return (int32_t)rnd_shr((int64_t)m_q28, 8u);
}

/* ------------------------------------------------------------------ harness */

static pd_out_t step_in(pd_state_t *s, const pd_params_t *p, const pd_in_t *in)
{
    pd_out_t o;
    pd_step(s, p, in, &o);
    return o;
}

static pd_in_t in_of(int32_t y, bool valid)
{
    pd_in_t in;
    in.y_cnt = y;
    in.y_valid = valid;
    in.y_sat = false;
    in.beta_cnt = 0;
    in.beta_valid = false;
    return in;
}

static pd_out_t step(pd_state_t *s, const pd_params_t *p, int32_t y, bool valid)
{
    const pd_in_t in = in_of(y, valid);
    return step_in(s, p, &in);
}

static pd_out_t step_beta(pd_state_t *s, const pd_params_t *p, int32_t y, int32_t beta, bool beta_valid)
{
    pd_in_t in = in_of(y, true);
    in.beta_cnt = beta;
    in.beta_valid = beta_valid;
    return step_in(s, p, &in);
}

/* why of pd_params_check, and its return code consistent with it (OK iff why == 0). */
static uint32_t why_of(const pd_params_t *p)
{
    uint32_t why = 0xA5A5A5A5u;
    const fsw_rc_t rc = pd_params_check(p, &why);
    UT_CHECK_UEQ(rc, (why == 0u) ? FSW_OK : FSW_ERR_RANGE);
    return why;
}

static void params(uint32_t k, pd_params_t *p)
{
    pd_params_of(&PD_TBL_DEFAULT, k, p);
}

/* Fixed LCG (Numerical Recipes constants), the same on host and target. */
static uint32_t lcg(uint32_t *s)
{
    *s = (*s * 1664525u) + 1013904223u;
    return *s;
}

/* ------------------------------------------------------------------ 1. pd_params_check */

UT_TEST(params_check_passes_the_three_default_channels)
{
    uint32_t k;
    for (k = 0u; k < PD_N_CH; k++) {
        params(k, &g_p);
        UT_CHECK_UEQ(why_of(&g_p), 0u);
        /* the literal and averaged-P tables fly FIXED, so their FAST schedule is allowed */
        pd_params_of(&PD_TBL_LITERAL, k, &g_p);
        UT_CHECK_UEQ(why_of(&g_p), 0u);
        pd_params_of(&PD_TBL_AVGP, k, &g_p);
        UT_CHECK_UEQ(why_of(&g_p), 0u);
    }
    params(CH_PITCH, &g_p);
    UT_UEQ(pd_params_check(&g_p, NULL), FSW_OK);
}

UT_TEST(params_check_null_is_an_argument_error)
{
    uint32_t why = 0xFFu;
    UT_UEQ(pd_params_check(NULL, &why), FSW_ERR_ARG);
    UT_UEQ(why, 0u);
    UT_UEQ(pd_params_check(NULL, NULL), FSW_ERR_ARG);
}

/* 1/Ty in uq22 at Ty = 0.25 s: 2^22 10^6 / 250 000 = 4 2^22 = 16 777 216; 1 LSB off is accepted,
   2 LSB refused. At n_div = 2, Ty = 0.5 s: 2 2^22 = 8 388 608. */
UT_TEST(params_check_period_inv_ty_to_one_lsb)
{
    params(CH_PITCH, &g_p);
    UT_UEQ(g_p.c.inv_ty_q22, 16777216u);
    g_p.c.inv_ty_q22 = 16777217u;
    UT_UEQ(why_of(&g_p), 0u);
    g_p.c.inv_ty_q22 = 16777215u;
    UT_UEQ(why_of(&g_p), 0u);
    g_p.c.inv_ty_q22 = 16777218u;
    UT_UEQ(why_of(&g_p), PD_WHY_PERIOD);
    g_p.c.inv_ty_q22 = 16777214u;
    UT_UEQ(why_of(&g_p), PD_WHY_PERIOD);
    params(CH_PITCH, &g_p);
    g_p.c.period_us = 0u;
    UT_UEQ(why_of(&g_p), PD_WHY_PERIOD);
    params(CH_PITCH, &g_p);
    g_p.c.n_div = 0u;
    UT_UEQ(why_of(&g_p), PD_WHY_PERIOD);
    params(CH_PITCH, &g_p);
    g_p.c.n_div = 2u;                  /* 1/Ty still that of 0.25 s */
    UT_UEQ(why_of(&g_p), PD_WHY_PERIOD);
    g_p.c.inv_ty_q22 = 8388609u;
    UT_UEQ(why_of(&g_p), 0u);
    g_p.c.inv_ty_q22 = 8388610u;
    UT_UEQ(why_of(&g_p), PD_WHY_PERIOD);
}

UT_TEST(params_check_n_y_power_of_two_and_n_bad_max)
{
    params(CH_PITCH, &g_p);
    g_p.c.n_y = 12u;
    UT_UEQ(why_of(&g_p), PD_WHY_NY);
    g_p.c.n_y = 128u;
    UT_UEQ(why_of(&g_p), PD_WHY_NY);
    g_p.c.n_y = 64u;
    UT_UEQ(why_of(&g_p), 0u);
    g_p.c.n_y = 16u;
    g_p.c.n_bad_max = 16u;             /* n_bad_max >= n_y */
    UT_UEQ(why_of(&g_p), PD_WHY_NY);
    g_p.c.n_bad_max = 15u;
    UT_UEQ(why_of(&g_p), 0u);
    g_p.c.n_y = 4u;
    g_p.c.n_bad_max = 4u;
    UT_UEQ(why_of(&g_p), PD_WHY_NY);
}

/* ADAPTIVE needs a usable estimator block (one section, or yaw's two) and Ty = 0.25 s; a schedule
   made for another law may fly only FIXED. */
UT_TEST(params_check_mode_source_and_schedule_law)
{
    params(CH_PITCH, &g_p);
    g_p.c.src = (uint8_t)PD_SRC_ADAPTIVE;
    UT_UEQ(why_of(&g_p), 0u);
    g_p.g.fest.n_sec = 3u;
    UT_UEQ(why_of(&g_p), PD_WHY_MODE);
    params(CH_YAW, &g_p);
    g_p.c.src = (uint8_t)PD_SRC_ADAPTIVE;
    UT_UEQ(why_of(&g_p), 0u);
    g_p.g.fest.n_sec = 0u;
    UT_UEQ(why_of(&g_p), PD_WHY_MODE);
    params(CH_PITCH, &g_p);
    g_p.c.src = (uint8_t)PD_SRC_GROUND;
    UT_UEQ(why_of(&g_p), 0u);
    g_p.c.sched_law = (uint8_t)PD_LAW_LITERAL;   /* law FAST */
    UT_UEQ(why_of(&g_p), PD_WHY_MODE);
    g_p.c.src = (uint8_t)PD_SRC_FIXED;
    UT_UEQ(why_of(&g_p), 0u);
    params(CH_PITCH, &g_p);
    g_p.c.law = 3u;
    UT_UEQ(why_of(&g_p) & PD_WHY_MODE, PD_WHY_MODE);
}

/* k2 order min <= nom <= max, min <= cold <= max; k < 1024 s; G_P = k0 k1 < 2^10 (k1 = 512 s gives
   2 512 = 1024 exactly: refused; 511 gives 1022). */
UT_TEST(params_check_gain_order_and_g_p_bound)
{
    params(CH_PITCH, &g_p);
    g_p.g.k2_min_q22 = g_p.g.k2_nom_q22 + 1u;
    UT_UEQ(why_of(&g_p), PD_WHY_GAIN);
    params(CH_PITCH, &g_p);
    g_p.g.k2_nom_q22 = g_p.g.k2_max_q22 + 1u;
    UT_UEQ(why_of(&g_p), PD_WHY_GAIN);
    params(CH_PITCH, &g_p);
    g_p.g.k2_cold_q22 = g_p.g.k2_max_q22 + 1u;
    UT_UEQ(why_of(&g_p), PD_WHY_GAIN);
    params(CH_PITCH, &g_p);
    g_p.g.k2_max_q22 = PD_K_MAX_Q22 + 1u;         /* 1023 2^22 + 1 */
    UT_UEQ(why_of(&g_p), PD_WHY_GAIN);
    params(CH_PITCH, &g_p);
    g_p.g.k0_q22 = PD_K_MAX_Q22 + 1u;
    UT_UEQ(why_of(&g_p), PD_WHY_GAIN);
    params(CH_PITCH, &g_p);
    g_p.g.k1_q22 = K_Q22(512);
    UT_UEQ(why_of(&g_p), PD_WHY_GAIN);
    g_p.g.k1_q22 = K_Q22(511);
    UT_UEQ(why_of(&g_p), 0u);
}

/* G_D = k0 k2_max / Ty < 2^16. At period 25 000 us (1/Ty = 40 exactly: 40 2^22 = 167 772 160 uq22):
   pitch k2_max 1000 s -> 2 1000 40 = 80 000 (refused), 820 s -> 65 600 (refused), 819 s -> 65 520
   (accepted); yaw's 815 s -> 65 200 (accepted). */
UT_TEST(params_check_g_d_bound_through_k2_max_at_a_short_ty)
{
    params(CH_PITCH, &g_p);
    g_p.c.period_us = 25000u;
    g_p.c.inv_ty_q22 = 167772160u;
    UT_UEQ(why_of(&g_p), PD_WHY_GAIN);
    g_p.g.k2_max_q22 = K_Q22(820);
    UT_UEQ(why_of(&g_p), PD_WHY_GAIN);
    g_p.g.k2_max_q22 = K_Q22(819);
    UT_UEQ(why_of(&g_p), 0u);
    params(CH_YAW, &g_p);
    g_p.c.period_us = 25000u;
    g_p.c.inv_ty_q22 = 167772160u;
    UT_UEQ(why_of(&g_p), 0u);
}

UT_TEST(params_check_schedule_nodes)
{
    params(CH_PITCH, &g_p);
    g_p.g.k2_node_q22[5] = g_p.g.k2_node_q22[4] + 1u;   /* increasing in f */
    UT_UEQ(why_of(&g_p), PD_WHY_SCHED);
    params(CH_PITCH, &g_p);
    g_p.g.k2_node_q22[0] = g_p.g.k2_max_q22 + 1u;       /* above k2_max (the order still holds) */
    UT_UEQ(why_of(&g_p), PD_WHY_SCHED);
    params(CH_PITCH, &g_p);
    g_p.c.df_inv_q16 = 0u;
    UT_UEQ(why_of(&g_p), PD_WHY_SCHED);
}

/* y_lim <= 0.5 rad = 2^29 q30, dy_max <= 2^-6 rad = 2^24 q30, M_max <= 4 N m = 2^30 q28;
   beta_lim >= beta_warn; n_frozen >= 2. */
UT_TEST(params_check_limits_and_fault_thresholds)
{
    params(CH_PITCH, &g_p);
    UT_EQ(g_p.c.y_lim_q30, 536870912);
    g_p.c.y_lim_q30 = 536870913;
    UT_UEQ(why_of(&g_p), PD_WHY_LIMIT);
    params(CH_PITCH, &g_p);
    g_p.c.dy_max_q30 = 16777217;
    UT_UEQ(why_of(&g_p), PD_WHY_LIMIT);
    params(CH_PITCH, &g_p);
    g_p.c.m_max_q28 = 1073741825;
    UT_UEQ(why_of(&g_p), PD_WHY_LIMIT);
    g_p.c.m_max_q28 = 0;
    UT_UEQ(why_of(&g_p), PD_WHY_LIMIT);
    params(CH_PITCH, &g_p);
    g_p.c.ch_mask = 8u;
    UT_UEQ(why_of(&g_p), PD_WHY_LIMIT);
    params(CH_PITCH, &g_p);
    g_p.c.beta_lim_q24 = g_p.c.beta_warn_q24;
    UT_UEQ(why_of(&g_p), 0u);
    g_p.c.beta_lim_q24 = g_p.c.beta_warn_q24 - 1;
    UT_UEQ(why_of(&g_p), PD_WHY_FAULT);
    params(CH_PITCH, &g_p);
    g_p.c.n_frozen = 1u;
    UT_UEQ(why_of(&g_p), PD_WHY_FAULT);
}

/* ------------------------------------------------------------------ 2. FAST arithmetic */

UT_TEST(gains_are_the_hand_products)
{
    params(CH_PITCH, &g_p);
    pd_init(&g_s, &g_p);
    UT_EQ(g_s.g_p_q16, GP40_Q16);                /* 2 621 440 */
    UT_EQ(g_s.g_d_q16, GD_PITCH_Q16);            /* 249 036 800 */
    UT_UEQ(g_s.k2_q22, K_Q22(475));              /* 1 992 294 400 */
    UT_UEQ(g_s.tlm.k2_q22, K_Q22(475));
    params(CH_ROLL, &g_p);
    pd_init(&g_s, &g_p);
    UT_EQ(g_s.g_p_q16, GP30_Q16);
    UT_EQ(g_s.g_d_q16, GD_ROLL_Q16);
    params(CH_YAW, &g_p);
    pd_init(&g_s, &g_p);
    UT_EQ(g_s.g_p_q16, GP40_Q16);
    UT_EQ(g_s.g_d_q16, GD_YAW_Q16);
}

/* Pitch. y0 = 100 000 counts = 1 600 000 q30: acc = 40 2^16 1 600 000 = 4 194 304 000 000 (2^-46),
   M = -acc / 2^18 = -16 000 000 q28 (-0.0596 N m) exactly, no derivative; m_cnt = -62 500.
   Ramp y_k = 100 000 + 300 k: dy = 300 counts, M_k = -4 (40 y_k + 3800 300) = -(160 y_k + 4 560 000);
   k = 1: -20 608 000, m_cnt -80 500. */
UT_TEST(fast_first_sample_has_no_kick_then_a_ramp_is_exact)
{
    pd_out_t o;
    int32_t k;
    params(CH_PITCH, &g_p);
    pd_init(&g_s, &g_p);
    o = step(&g_s, &g_p, 100000, true);
    UT_EQ(o.m_q28, -16000000);
    UT_EQ(o.m_cnt, -62500);
    UT_EQ(g_s.tlm.dy_q30, 0);
    UT_EQ(g_s.tlm.y_q30, 1600000);
    /* FAST (0) FIXED (0), k2 = k2_nom = k2_cold: FALLBACK_GAIN and nothing else */
    UT_UEQ(o.health, PD_H_FALLBACK_GAIN);
    o = step(&g_s, &g_p, 100300, true);
    UT_EQ(o.m_q28, -20608000);
    UT_EQ(o.m_cnt, -80500);
    UT_EQ(g_s.tlm.dy_q30, 4800);
    for (k = 2; k <= 20; k++) {
        const int32_t y = 100000 + (300 * k);
        o = step(&g_s, &g_p, y, true);
        UT_CHECK_EQ(o.m_q28, -((160 * y) + 4560000));
        UT_CHECK_EQ(o.m_q28, m_fast(GP40_Q16, GD_PITCH_Q16, y, 300));
        UT_CHECK_EQ(o.m_cnt, cnt_of(o.m_q28));
        UT_CHECK_UEQ(o.health, PD_H_FALLBACK_GAIN);
    }
    UT_EQ(g_s.tlm.m_q28, o.m_q28);
    UT_UEQ(g_s.tlm.trq_sat_cnt, 0u);
}

/* A gain with a fraction makes the rounding visible: k2 = 475 + 2^-19 s (uq22 1 992 294 408) gives
   G_D = 2 (475 + 2^-19) 4 = 3800 + 2^-16 -> uq16 3800 2^16 + 1 = 249 036 801 exactly.
   (a) y0 = 4 counts: M = -160 4 = -640 q28 exactly, m_cnt = rnd(-2.5) = -3 (away from zero).
   (b) then y1 = 8196 (dy = 8192 counts = 2^17 q30): acc / 2^18 = 160 8196 + (3800 2^16 + 1) 2^17 / 2^18
       = 1 311 360 + 124 518 400 + 0.5 -> rnd = 125 829 761, M = -125 829 761, m_cnt = rnd(-491 522.504)
       = -491 523. The mirrored inputs give +640 / +3 and +125 829 761 / +491 523. */
UT_TEST(fast_rounds_half_away_from_zero_and_is_odd)
{
    pd_out_t a;
    pd_out_t b;
    params(CH_PITCH, &g_p);
    g_p.g.k2_nom_q22 = K_Q22(475) + 8u;
    UT_UEQ(why_of(&g_p), 0u);
    pd_init(&g_s, &g_p);
    pd_init(&g_s2, &g_p);
    UT_EQ(g_s.g_d_q16, 249036801);
    a = step(&g_s, &g_p, 4, true);
    b = step(&g_s2, &g_p, -4, true);
    UT_EQ(a.m_q28, -640);
    UT_EQ(a.m_cnt, -3);
    UT_EQ(b.m_q28, 640);
    UT_EQ(b.m_cnt, 3);
    a = step(&g_s, &g_p, 8196, true);
    b = step(&g_s2, &g_p, -8196, true);
    UT_EQ(a.m_q28, -125829761);
    UT_EQ(a.m_cnt, -491523);
    UT_EQ(b.m_q28, 125829761);
    UT_EQ(b.m_cnt, 491523);
    UT_UEQ(a.health, 0u);        /* k2 no longer k2_cold: no FALLBACK_GAIN */
    UT_UEQ(b.health, 0u);
}

/* 3000 samples of a bounded random walk (|y| <= 2^22 counts = 0.0625 rad, steps within
   +-2^16 counts = 2^-10 rad, inside dy_max) on instance A and the mirror -y on instance B, with the
   fractional G_D above. Every torque equals the model M = sat(-rnd((G_P y + G_D dy) / 2^18)), B's is
   exactly -A's, TRQ_SAT is raised exactly when the unclamped |M| > M_max (|G_P y| reaches
   40 0.0625 = 2.5 N m and |G_D dy| 3800 2^-10 = 3.7 N m, so the clamp is exercised: about 44 % of the
   samples), and no fx status bit appears. (Missing samples have their own tests below.) */
UT_TEST(fast_mirrored_inputs_give_mirrored_torques)
{
    uint32_t seed = 12345u;
    int32_t y = 0;
    int32_t y_prev = 0;
    uint32_t n_sat = 0u;
    uint32_t k;
    params(CH_PITCH, &g_p);
    g_p.g.k2_nom_q22 = K_Q22(475) + 8u;
    pd_init(&g_s, &g_p);
    pd_init(&g_s2, &g_p);
    for (k = 0u; k < 3000u; k++) {
        const int32_t d = (int32_t)((lcg(&seed) >> 15) & 0x1FFFFu) - 65536;
        pd_out_t a;
        pd_out_t b;
        int64_t raw;
        y = ((y + d > 4194304) || (y + d < -4194304)) ? (y - d) : (y + d);
        a = step(&g_s, &g_p, y, true);
        b = step(&g_s2, &g_p, -y, true);
        raw = m_raw(GP40_Q16, 249036801, 16 * (int64_t)y, (k == 0u) ? 0 : (16 * ((int64_t)y - (int64_t)y_prev)));
        if ((raw > M_MAX_Q28) || (raw < -M_MAX_Q28)) {
            n_sat++;
            UT_CHECK((a.health & PD_H_TRQ_SAT) != 0u);
        } else {
            UT_CHECK((a.health & PD_H_TRQ_SAT) == 0u);
        }
        y_prev = y;
        UT_CHECK_EQ(a.m_q28, clamp_m(raw));
        UT_CHECK_EQ(b.m_q28, -a.m_q28);
        UT_CHECK_EQ(a.m_cnt, cnt_of(a.m_q28));
        UT_CHECK_EQ(b.m_cnt, -a.m_cnt);
        UT_CHECK_UEQ(a.health, b.health);
        UT_CHECK_UEQ(a.health & FX_ST_MASK, 0u);
        if (ut_fail_count() != 0u) {
            break;
        }
    }
    UT_TRUE(n_sat > 1000u);
    UT_TRUE(n_sat < 2000u);
    UT_UEQ(g_s.tlm.trq_sat_cnt, n_sat);
    UT_UEQ(g_s2.tlm.trq_sat_cnt, n_sat);
}

/* Pitch M = -160 y: y = 3 355 443 counts gives -536 870 880 > -2^29 = -536 870 912 (no clamp);
   3 355 444 gives -536 871 040, clamped to -2^29, TRQ_SAT, m_cnt = -2^21 = -2 097 152. */
UT_TEST(torque_clamp_at_m_max_is_the_designated_saturation)
{
    pd_out_t o;
    params(CH_PITCH, &g_p);
    pd_init(&g_s, &g_p);
    o = step(&g_s, &g_p, 3355443, true);
    UT_EQ(o.m_q28, -536870880);
    UT_UEQ(o.health & PD_H_TRQ_SAT, 0u);
    pd_init(&g_s, &g_p);
    o = step(&g_s, &g_p, 3355444, true);
    UT_EQ(o.m_q28, -M_MAX_Q28);
    UT_EQ(o.m_cnt, -2097152);
    UT_UEQ(o.health, PD_H_TRQ_SAT | PD_H_FALLBACK_GAIN);
    UT_UEQ(g_s.tlm.trq_sat_cnt, 1u);
    pd_init(&g_s, &g_p);
    o = step(&g_s, &g_p, -3355444, true);
    UT_EQ(o.m_q28, M_MAX_Q28);
    UT_EQ(o.m_cnt, 2097152);
    /* the largest accepted |y| (0.5 rad = 2^25 counts) and the largest |dy| (2^20 counts): the
       widest accumulator, still no fx status */
    o = step(&g_s, &g_p, -3355444 - 1048576, true);
    UT_EQ(o.m_q28, M_MAX_Q28);
    UT_UEQ(o.health & FX_ST_MASK, 0u);
    pd_init(&g_s, &g_p);
    o = step(&g_s, &g_p, 33554432 - 1048576, true);
    o = step(&g_s, &g_p, 33554432, true);
    UT_EQ(o.m_q28, -M_MAX_Q28);
    UT_UEQ(o.health & FX_ST_MASK, 0u);
    UT_UEQ(g_s.tlm.trq_sat_cnt, 2u);
    UT_UEQ(g_s.tlm.health_sticky & PD_H_TRQ_SAT, PD_H_TRQ_SAT);
}

/* ------------------------------------------------------------------ 3. schedule */

/* f_i = 0.010 + 0.005 i Hz in uq32, rounded: ((10 + 5 i) 2^32 + 500) / 1000. */
static uint32_t f_node(uint32_t i)
{
    return (uint32_t)((((uint64_t)(10u + (5u * i)) << 32) + 500u) / 1000u);
}

/* halfway: 0.0125 + 0.005 i Hz: ((125 + 50 i) 2^32 + 5000) / 10000. */
static uint32_t f_mid(uint32_t i)
{
    return (uint32_t)((((uint64_t)(125u + (50u * i)) << 32) + 5000u) / 10000u);
}

/* A commanded node f_i is within 2^-33 Hz of the node, i.e. within 2^-33 200 = 2.3e-8 of a node
   spacing. The 16-bit fraction phi of spec 40 §5 item 6, rounded (spec 00 §1.3), is then 0 (or
   65 536, the next index), so the interpolation returns the node itself; 1 LSB is left for the
   product's rounding. Checked for all 19 nodes of the three channels. */
UT_TEST(sched_returns_each_node_within_1_lsb)
{
    uint32_t k;
    uint32_t i;
    UT_UEQ(f_node(0u), 42949673u);          /* 0.01 2^32 = 42 949 672.96 */
    UT_UEQ(f_node(4u), F_003_Q32);
    for (k = 0u; k < PD_N_CH; k++) {
        params(k, &g_p);
        for (i = 0u; i < PD_N_NODES; i++) {
            const int64_t d = (int64_t)pd_sched_k2(&g_p, f_node(i)) - (int64_t)g_p.g.k2_node_q22[i];
            if ((d > 1) || (d < -1)) {
                /* first value: 100 channel + node; second: the error in uq22 LSB */
                ut_record_fail(__FILE__, __LINE__, "sched(f_node) - node > 1 LSB (ch*100+i, err)",
                               (int64_t)((100u * k) + i), d);
            }
        }
    }
}

/* Halfway between nodes i and i+1 (f rounded to uq32, again 2.3e-8 of a spacing off) the rounded
   phi is 32 768 and k2 = k2_i + rnd((k2_i+1 - k2_i) / 2): within 0.5 LSB of the mean, so
   |2 k2 - (k2_i + k2_i+1)| <= 1 (checked as <= 2, i.e. 1 LSB). */
UT_TEST(sched_returns_the_mean_halfway_within_1_lsb)
{
    uint32_t k;
    uint32_t i;
    for (k = 0u; k < PD_N_CH; k++) {
        params(k, &g_p);
        for (i = 0u; (i + 1u) < PD_N_NODES; i++) {
            const int64_t two_k2 = 2 * (int64_t)pd_sched_k2(&g_p, f_mid(i));
            const int64_t d = two_k2 - ((int64_t)g_p.g.k2_node_q22[i] + (int64_t)g_p.g.k2_node_q22[i + 1u]);
            if ((d > 2) || (d < -2)) {
                ut_record_fail(__FILE__, __LINE__, "2 sched(f_mid) - (n_i + n_i+1) > 2 (ch*100+i, err)",
                               (int64_t)((100u * k) + i), d);
            }
        }
    }
}

/* Below f0 -> node 0; above the last node -> node 18; then [k2_min, k2_max]. */
UT_TEST(sched_clamps_at_the_end_nodes_and_to_the_k2_limits)
{
    params(CH_PITCH, &g_p);
    UT_UEQ(pd_sched_k2(&g_p, 0u), K_Q22(475));
    UT_UEQ(pd_sched_k2(&g_p, f_node(0u) - 1u), K_Q22(475));
    UT_UEQ(pd_sched_k2(&g_p, f_node(18u)), K_Q22(75));
    UT_UEQ(pd_sched_k2(&g_p, 858993459u), K_Q22(75));      /* 0.2 Hz */
    UT_UEQ(pd_sched_k2(&g_p, 0xFFFFFFFFu), K_Q22(75));     /* ~1 Hz */
    g_p.g.k2_min_q22 = K_Q22(200);
    UT_UEQ(pd_sched_k2(&g_p, f_node(18u)), K_Q22(200));
    UT_UEQ(pd_sched_k2(&g_p, f_node(0u)), K_Q22(475));
    params(CH_PITCH, &g_p);
    g_p.g.k2_max_q22 = K_Q22(300);
    UT_UEQ(pd_sched_k2(&g_p, f_node(0u)), K_Q22(300));
    UT_UEQ(pd_sched_k2(&g_p, 0u), K_Q22(300));
    UT_UEQ(pd_sched_k2(&g_p, f_node(18u)), K_Q22(75));
    params(CH_ROLL, &g_p);
    UT_UEQ(pd_sched_k2(&g_p, f_node(18u)), 0u);             /* roll's high-f nodes are 0 */
}

/* GROUND at 0.03 Hz = node 4: pitch 385 s (G_D = 2 385 4 = 3080). The change shows at the next
   step with a one-step RETUNE pulse and the source bits; FIXED via pd_set_k2_fixed; FALLBACK_GAIN
   exactly while k2 == k2_cold (475 s). */
UT_TEST(gain_source_changes_take_effect_at_the_next_step)
{
    pd_out_t o;
    params(CH_PITCH, &g_p);
    pd_init(&g_s, &g_p);
    o = step(&g_s, &g_p, 1000, true);
    UT_UEQ(o.health, PD_H_FALLBACK_GAIN);
    pd_set_f_ground(&g_s, F_003_Q32);
    UT_TRUE(pd_set_source(&g_s, &g_p, (uint8_t)PD_SRC_GROUND));
    o = step(&g_s, &g_p, 1000, true);
    UT_UEQ(o.health, PD_H_RETUNE | (PD_SRC_GROUND << PD_H_SRC_SH));
    UT_UEQ(g_s.tlm.k2_q22, K_Q22(385));
    UT_EQ(g_s.g_d_q16, Q16(3080));
    UT_EQ(o.m_q28, -160000);                      /* dy = 0: -160 1000 */
    o = step(&g_s, &g_p, 1100, true);             /* M = -4 (40 1100 + 3080 100) = -1 408 000 */
    UT_EQ(o.m_q28, -1408000);
    UT_UEQ(o.health, PD_SRC_GROUND << PD_H_SRC_SH);
    {
        pd_params_t q = g_p;
        q.g.fest.n_sec = 3u;   /* no usable estimator block */
        UT_TRUE(!pd_set_source(&g_s, &q, (uint8_t)PD_SRC_ADAPTIVE));   /* refused, nothing changes */
    }
    o = step(&g_s, &g_p, 1100, true);
    UT_UEQ(o.health, PD_SRC_GROUND << PD_H_SRC_SH);
    pd_set_k2_fixed(&g_s, &g_p, K_Q22(300));
    UT_TRUE(pd_set_source(&g_s, &g_p, (uint8_t)PD_SRC_FIXED));
    o = step(&g_s, &g_p, 1100, true);
    UT_UEQ(o.health, PD_H_RETUNE);
    UT_UEQ(g_s.tlm.k2_q22, K_Q22(300));
    pd_set_k2_fixed(&g_s, &g_p, K_Q22(475));
    o = step(&g_s, &g_p, 1100, true);
    UT_UEQ(o.health, PD_H_RETUNE | PD_H_FALLBACK_GAIN);
    o = step(&g_s, &g_p, 1100, true);
    UT_UEQ(o.health, PD_H_FALLBACK_GAIN);
    /* roll: a fixed k2 above k2_max (150 s) is clamped to it */
    params(CH_ROLL, &g_p);
    pd_init(&g_s, &g_p);
    pd_set_k2_fixed(&g_s, &g_p, K_Q22(160));
    o = step(&g_s, &g_p, 1000, true);
    UT_UEQ(g_s.tlm.k2_q22, K_Q22(150));
    UT_UEQ(o.health, PD_H_RETUNE);
}

/* Spec 40 §5 item 4: G_D from uq22 products with one rounding. Off the exact Ty (n_div = 2,
   Ty = 0.5 s, 1/Ty = 2 -> uq22 2^23) with k2 = 475 + 2^-12 s (uq22 1 992 295 424):
   G_D = 2 (475 + 2^-12) 2 = 1900 + 2^-10 N m s/rad -> uq16 1900 2^16 + 64 = 124 518 464, exactly
   (k0 k2 / Ty 2^16 = 2^23 1 992 295 424 2^23 / 2^50 = 1 992 295 424 / 16, no remainder).
   Through the law: y0 = 0, y1 = 2^14 counts (dy = 2^18 q30): M = -(G_P 2^18 + G_D 2^18) / 2^18
   = -(2 621 440 + 124 518 464) = -127 139 904 q28 exactly. */
UT_TEST(gain_d_off_the_exact_ty_has_one_rounding)
{
    pd_out_t o;
    params(CH_PITCH, &g_p);
    g_p.c.n_div = 2u;
    g_p.c.inv_ty_q22 = 8388608u;
    g_p.g.k2_nom_q22 = K_Q22(475) + 1024u;
    UT_UEQ(why_of(&g_p), 0u);
    pd_init(&g_s, &g_p);
    o = step(&g_s, &g_p, 0, true);
    UT_EQ(o.m_q28, 0);
    o = step(&g_s, &g_p, 16384, true);
    UT_CHECK_EQ(g_s.g_d_q16, 124518464);
    UT_EQ(o.m_q28, -127139904);
}

/* ------------------------------------------------------------------ 4. spec 40 §8 rows */

/* Pitch, M = -160 y - 15 200 dy. Missing sample: STALE, miss_cnt, M held for n_hold = 1 sample,
   then 0 with COAST; on return the difference restarts (dy = 0, M = -160 y). */
UT_TEST(missing_sample_holds_one_sample_then_coasts)
{
    pd_out_t o;
    params(CH_PITCH, &g_p);
    pd_init(&g_s, &g_p);
    o = step(&g_s, &g_p, 1000, true);
    UT_EQ(o.m_q28, -160000);
    o = step(&g_s, &g_p, 1010, true);            /* -(161 600 + 152 000) */
    UT_EQ(o.m_q28, -313600);
    o = step(&g_s, &g_p, 1020, false);
    UT_EQ(o.m_q28, -313600);
    UT_UEQ(o.health, PD_H_STALE | PD_H_FALLBACK_GAIN);
    UT_UEQ(g_s.tlm.miss_cnt, 1u);
    o = step(&g_s, &g_p, 1030, false);
    UT_EQ(o.m_q28, 0);
    UT_EQ(o.m_cnt, 0);
    UT_UEQ(o.health, PD_H_STALE | PD_H_COAST | PD_H_FALLBACK_GAIN);
    UT_UEQ(g_s.tlm.miss_cnt, 2u);
    o = step(&g_s, &g_p, 1040, true);            /* no kick: -160 1040 */
    UT_EQ(o.m_q28, -166400);
    UT_EQ(g_s.tlm.dy_q30, 0);
    UT_UEQ(o.health, PD_H_FALLBACK_GAIN);
    o = step(&g_s, &g_p, 1050, true);            /* -(168 000 + 152 000) */
    UT_EQ(o.m_q28, -320000);
    UT_UEQ(g_s.tlm.range_rej + g_s.tlm.rate_rej + g_s.tlm.stale_cnt, 0u);
}

/* A3-10 / spec 40 §3.2 as this module takes it (fsw/pd/README.md, decision 9): after 4 or 16 dropped
   samples the first valid sample carries no derivative: M = -rnd(G_P y / 2^18) = -160 y exactly. After a
   single dropped sample (its torque was held over it) the difference is taken across it: dy spans two
   samples of the 500-count ramp, M = -(160 y + 15 200 1000). */
UT_TEST(no_derivative_kick_after_4_16_dropped_samples_and_across_one)
{
    static const uint32_t gaps[3] = {1u, 4u, 16u};
    uint32_t g;
    params(CH_PITCH, &g_p);
    for (g = 0u; g < 3u; g++) {
        pd_out_t o = {0, 0, 0u};
        int32_t k;
        int32_t y;
        pd_init(&g_s, &g_p);
        for (k = 0; k < 20; k++) {
            o = step(&g_s, &g_p, 1000 + (500 * k), true);
        }
        UT_CHECK_EQ(o.m_q28, m_fast(GP40_Q16, GD_PITCH_Q16, 1000 + (500 * 19), 500));
        for (k = 20; k < (20 + (int32_t)gaps[g]); k++) {
            (void)step(&g_s, &g_p, 1000 + (500 * k), false);
        }
        y = 1000 + (500 * k);
        o = step(&g_s, &g_p, y, true);
        if (gaps[g] == 1u) {
            UT_CHECK_EQ(o.m_q28, -((160 * y) + (15200 * 1000)));
            UT_CHECK_EQ(g_s.tlm.dy_q30, 1000 * 16);
        } else {
            if (o.m_q28 != -(160 * y)) {
                /* first value: the gap; second: the torque (expected -160 y) */
                ut_record_fail(__FILE__, __LINE__, "M on the first valid sample after the gap != -160 y",
                               (int64_t)gaps[g], (int64_t)o.m_q28);
            }
            UT_CHECK_EQ(g_s.tlm.dy_q30, 0);
        }
        UT_CHECK_UEQ(g_s.tlm.miss_cnt, gaps[g]);
    }
}

/* Spec 40 §8 "bad control period": M = 0 for the next period applies to the averaged modes only;
   the FAST law keeps flying its P and D terms (a period with 5 of 16 samples missing is counted in
   period_rej). Pitch, y_k = 1000 + 37 k, samples 3..7 missing: at k = 15 (dy = 37 from k = 14)
   M = -(160 1555 + 15 200 37) = -(248 800 + 562 400) = -811 200, and on through the next period. */
UT_TEST(fast_law_is_not_zeroed_after_a_bad_period)
{
    pd_out_t o;
    int32_t k;
    params(CH_PITCH, &g_p);
    pd_init(&g_s, &g_p);
    for (k = 0; k < 15; k++) {
        (void)step(&g_s, &g_p, 1000 + (37 * k), (k < 3) || (k > 7));
    }
    o = step(&g_s, &g_p, 1000 + (37 * 15), true);
    UT_UEQ(g_s.tlm.period_rej, 1u);
    UT_EQ(o.m_q28, -811200);
    for (k = 16; k < 32; k++) {
        const int32_t y = 1000 + (37 * k);
        o = step(&g_s, &g_p, y, true);
        UT_CHECK_EQ(o.m_q28, -((160 * y) + 562400));
    }
}

/* |y| > 0.5 rad (2^25 counts) or the sensor's saturation bit: refused as missing (REJECT, STALE,
   range_rej, held then coasting), miss_cnt untouched; exactly 0.5 rad is accepted. */
UT_TEST(out_of_range_sample_is_rejected)
{
    pd_out_t o;
    pd_in_t in;
    params(CH_PITCH, &g_p);
    pd_init(&g_s, &g_p);
    o = step(&g_s, &g_p, 33554433, true);
    UT_EQ(o.m_q28, 0);
    UT_UEQ(o.health, PD_H_REJECT | PD_H_STALE | PD_H_FALLBACK_GAIN);
    UT_UEQ(g_s.tlm.range_rej, 1u);
    o = step(&g_s, &g_p, -33554433, true);
    UT_UEQ(o.health, PD_H_REJECT | PD_H_STALE | PD_H_COAST | PD_H_FALLBACK_GAIN);
    UT_UEQ(g_s.tlm.range_rej, 2u);
    in = in_of(100, true);
    in.y_sat = true;
    o = step_in(&g_s, &g_p, &in);
    UT_UEQ(o.health & PD_H_REJECT, PD_H_REJECT);
    UT_UEQ(g_s.tlm.range_rej, 3u);
    UT_UEQ(g_s.tlm.miss_cnt, 0u);
    o = step(&g_s, &g_p, 33554432, true);        /* 0.5 rad: 2^29 q30, M = -160 2^25 -> clamp */
    UT_EQ(g_s.tlm.y_q30, 536870912);
    UT_EQ(o.m_q28, -M_MAX_Q28);
    UT_UEQ(o.health, PD_H_TRQ_SAT | PD_H_FALLBACK_GAIN);
    UT_UEQ(g_s.tlm.range_rej, 3u);
}

/* |dy| > 2^-6 rad (2^20 counts, 2^24 q30): refused (REJECT, rate_rej), never clamped; the next
   valid sample restarts the difference. dy = 2^20 counts exactly is accepted. */
UT_TEST(implausible_rate_is_rejected_never_clamped)
{
    pd_out_t o;
    params(CH_PITCH, &g_p);
    pd_init(&g_s, &g_p);
    (void)step(&g_s, &g_p, 0, true);
    o = step(&g_s, &g_p, 1048576, true);
    UT_EQ(g_s.tlm.dy_q30, 16777216);
    UT_UEQ(o.health & PD_H_REJECT, 0u);
    UT_EQ(o.m_q28, -M_MAX_Q28);                   /* -4 (40 + 3800) 2^20: clamped */
    o = step(&g_s, &g_p, 2097153, true);          /* dy = 2^20 + 1 counts */
    UT_UEQ(o.health, PD_H_REJECT | PD_H_STALE | PD_H_FALLBACK_GAIN);
    UT_UEQ(g_s.tlm.rate_rej, 1u);
    UT_EQ(o.m_q28, -M_MAX_Q28);                   /* held (n_hold = 1) */
    UT_EQ(g_s.tlm.dy_q30, 0);                     /* no clamped dy flown */
    UT_EQ(g_s.tlm.y_q30, 16777216);               /* the last accepted y (2^20 counts) */
    o = step(&g_s, &g_p, 1048578, true);          /* restart: -160 (2^20 + 2) */
    UT_EQ(o.m_q28, -167772480);
    UT_EQ(g_s.tlm.dy_q30, 0);
    UT_UEQ(o.health, PD_H_FALLBACK_GAIN);
    o = step(&g_s, &g_p, 1, true);                /* dy = -(2^20 + 1) */
    UT_UEQ(o.health & PD_H_REJECT, PD_H_REJECT);
    UT_UEQ(g_s.tlm.rate_rej, 2u);
    UT_UEQ(g_s.tlm.range_rej + g_s.tlm.miss_cnt, 0u);
}

/* Frozen: bit-identical y for n_frozen = 40 samples while |M| >= 0.01 N m (m_frozen 2 684 355 q28).
   y = 65 536 counts: M = -160 65 536 = -10 485 760 (0.039 N m). The 40th is refused (FROZEN,
   stale_cnt), the torque held one sample then 0; still refused while the count repeats with M = 0;
   accepted again (no kick) when y changes. n_y = 64 with n_bad_max = 63 keeps the bad-period rule
   out of this test (21 refused samples inside one 64-sample period). */
UT_TEST(frozen_sensor_is_refused_until_the_count_changes)
{
    pd_out_t o;
    uint32_t k;
    params(CH_PITCH, &g_p);
    g_p.c.n_y = 64u;
    g_p.c.n_bad_max = 63u;
    UT_UEQ(why_of(&g_p), 0u);
    pd_init(&g_s, &g_p);
    for (k = 1u; k <= 39u; k++) {
        o = step(&g_s, &g_p, 65536, true);
        UT_CHECK_EQ(o.m_q28, -10485760);
        UT_CHECK_UEQ(o.health & PD_H_FROZEN, 0u);
    }
    o = step(&g_s, &g_p, 65536, true);            /* the 40th */
    UT_UEQ(o.health, PD_H_FROZEN | PD_H_STALE | PD_H_FALLBACK_GAIN);
    UT_EQ(o.m_q28, -10485760);
    UT_UEQ(g_s.tlm.stale_cnt, 1u);
    o = step(&g_s, &g_p, 65536, true);
    UT_UEQ(o.health, PD_H_FROZEN | PD_H_STALE | PD_H_COAST | PD_H_FALLBACK_GAIN);
    UT_EQ(o.m_q28, 0);
    for (k = 42u; k <= 60u; k++) {
        o = step(&g_s, &g_p, 65536, true);
        UT_CHECK_UEQ(o.health & PD_H_FROZEN, PD_H_FROZEN);
        UT_CHECK_EQ(o.m_q28, 0);
    }
    UT_UEQ(g_s.tlm.stale_cnt, 21u);
    UT_UEQ(g_s.tlm.miss_cnt, 0u);
    o = step(&g_s, &g_p, 65537, true);            /* -160 65 537 */
    UT_EQ(o.m_q28, -10485920);
    UT_UEQ(o.health, PD_H_FALLBACK_GAIN);
    UT_EQ(g_s.tlm.dy_q30, 0);
    UT_UEQ(g_s.tlm.stale_cnt, 21u);
}

/* Under |M| < m_frozen a resting body may repeat its count for ever. Boundary: 160 16 777 =
   2 684 320 < 2 684 355 (never frozen, 100 samples), 160 16 778 = 2 684 480 >= it (frozen on the
   40th). */
UT_TEST(identical_y_under_small_torque_is_never_frozen)
{
    pd_out_t o;
    uint32_t k;
    params(CH_PITCH, &g_p);
    UT_EQ(g_p.c.m_frozen_q28, 2684355);
    pd_init(&g_s, &g_p);
    for (k = 0u; k < 100u; k++) {
        o = step(&g_s, &g_p, 16777, true);
        UT_CHECK_EQ(o.m_q28, -2684320);
        UT_CHECK_UEQ(o.health, PD_H_FALLBACK_GAIN);
    }
    UT_UEQ(g_s.tlm.stale_cnt, 0u);
    pd_init(&g_s, &g_p);
    for (k = 1u; k <= 40u; k++) {
        o = step(&g_s, &g_p, -16778, true);
    }
    UT_UEQ(o.health & PD_H_FROZEN, PD_H_FROZEN);
    UT_UEQ(g_s.tlm.stale_cnt, 1u);
}

/* Gimbal: beta_warn = 0.5 rad = 2^23 q24 (flag above it), beta_lim = 13 176 795 (pi/4, at or above
   it the torque that drives |beta| further out is zeroed). Pitch y = 1000: M = -160 000 (< 0), so a
   negative beta is driven outward. */
UT_TEST(gimbal_warn_and_limit)
{
    pd_out_t o;
    params(CH_PITCH, &g_p);
    pd_init(&g_s, &g_p);
    o = step_beta(&g_s, &g_p, 1000, BETA_WARN, true);
    UT_EQ(o.m_q28, -160000);
    UT_UEQ(o.health, PD_H_FALLBACK_GAIN);
    o = step_beta(&g_s, &g_p, 1000, BETA_WARN + 1, true);
    UT_EQ(o.m_q28, -160000);
    UT_UEQ(o.health, PD_H_BETA_WARN | PD_H_FALLBACK_GAIN);
    o = step_beta(&g_s, &g_p, 1000, -(BETA_LIM - 1), true);
    UT_EQ(o.m_q28, -160000);
    UT_UEQ(o.health, PD_H_BETA_WARN | PD_H_FALLBACK_GAIN);
    o = step_beta(&g_s, &g_p, 1000, -BETA_LIM, true);      /* outward: zeroed */
    UT_EQ(o.m_q28, 0);
    UT_EQ(o.m_cnt, 0);
    UT_UEQ(o.health, PD_H_BETA_LIM | PD_H_BETA_WARN | PD_H_FALLBACK_GAIN);
    UT_UEQ(g_s.tlm.beta_lim_cnt, 1u);
    o = step_beta(&g_s, &g_p, 1000, BETA_LIM, true);       /* inward: passes */
    UT_EQ(o.m_q28, -160000);
    UT_UEQ(o.health, PD_H_BETA_LIM | PD_H_BETA_WARN | PD_H_FALLBACK_GAIN);
    UT_UEQ(g_s.tlm.beta_lim_cnt, 2u);
    o = step_beta(&g_s, &g_p, 1000, INT32_MIN, true);      /* the widest count: outward */
    UT_EQ(o.m_q28, 0);
    UT_UEQ(g_s.tlm.beta_lim_cnt, 3u);
    o = step_beta(&g_s, &g_p, 1000, -BETA_LIM - 1000, false);   /* encoder invalid: no checks */
    UT_EQ(o.m_q28, -160000);
    UT_UEQ(o.health, PD_H_FALLBACK_GAIN);
    UT_UEQ(g_s.tlm.beta_lim_cnt, 3u);
    /* mirrored: y = -1000 gives +160 000, zeroed at +beta_lim */
    pd_init(&g_s, &g_p);
    o = step_beta(&g_s, &g_p, -1000, BETA_LIM, true);
    UT_EQ(o.m_q28, 0);
    o = step_beta(&g_s, &g_p, -1000, -BETA_LIM, true);
    UT_EQ(o.m_q28, 160000);
}

/* ------------------------------------------------------------------ 5. averaged modes */

/* LITERAL as pd.h / pd.c document it: the period sum is kept exact (xsum, q30, the sum of n_y = 16
   samples) and each term is rounded once at q28:
     M = -( rnd(G_P xsum / 2^(18 + 4)) + rnd(G_D (xsum_j - xsum_j-1) / 2^(18 + 8)) ),
   i.e. G_P xbar + G_D (xbar_j - xbar_j-1) / 16 with xbar = xsum / 16. Spec 40 §5 item 5 rounds the
   mean to q30 first (xbar = rnd(xsum / 16)); with count inputs (q30 = 16 counts) xsum is a multiple
   of 16, so both readings give the same numbers in these tests. */
static int32_t m_literal(int64_t gp_q16, int64_t gd_q16, int64_t xsum_q30, int64_t xsum_prev_q30)
{
    return (int32_t)clamp_m(-(rnd_shr(gp_q16 * xsum_q30, 22u) + rnd_shr(gd_q16 * (xsum_q30 - xsum_prev_q30), 26u)));
}

/* Pitch, y_k = 1000 + 37 k. M = 0 for k = 0..14. k = 15: sum = 16 (16 1000 + 37 120) = 327 040,
   xbar_0 = 20 440 q30 (1277.5 counts), no difference on the first mean: M = -40 2^16 20 440 / 2^18
   = -204 400, held for k = 16..30. k = 31: xbar_1 = 16 1000 + 37 376 = 29 912, dx = 9472,
   M = -(40 29 912 + 3800 9472 / 16) / 4 = -(1 196 480 + 2 249 600) / 4 = -861 520. */
UT_TEST(literal_law_on_the_period_means)
{
    pd_out_t o;
    int32_t k;
    pd_params_of(&PD_TBL_LITERAL, CH_PITCH, &g_p);
    pd_init(&g_s, &g_p);
    for (k = 0; k < 15; k++) {
        o = step(&g_s, &g_p, 1000 + (37 * k), true);
        UT_CHECK_EQ(o.m_q28, 0);
        UT_CHECK_UEQ(o.health, (PD_LAW_LITERAL << PD_H_LAW_SH) | PD_H_FALLBACK_GAIN);
    }
    o = step(&g_s, &g_p, 1000 + (37 * 15), true);
    UT_EQ(o.m_q28, -204400);
    UT_EQ(o.m_q28, m_literal(GP40_Q16, GD_PITCH_Q16, 16 * 20440, 16 * 20440));
    UT_EQ(o.m_cnt, -798);                         /* -204 400 / 256 = -798.4 */
    for (k = 16; k < 31; k++) {
        o = step(&g_s, &g_p, 1000 + (37 * k), true);
        UT_CHECK_EQ(o.m_q28, -204400);
    }
    o = step(&g_s, &g_p, 1000 + (37 * 31), true);
    UT_EQ(o.m_q28, -861520);
    UT_EQ(o.m_q28, m_literal(GP40_Q16, GD_PITCH_Q16, 16 * 29912, 16 * 20440));
    for (k = 32; k < 47; k++) {
        o = step(&g_s, &g_p, 1000 + (37 * k), true);
        UT_CHECK_EQ(o.m_q28, -861520);
    }
    /* k = 47: xbar_2 = 16 1000 + 37 (32 + ... + 47) = 16 000 + 37 632 = 39 384 */
    o = step(&g_s, &g_p, 1000 + (37 * 47), true);
    UT_EQ(o.m_q28, m_literal(GP40_Q16, GD_PITCH_Q16, 16 * 39384, 16 * 29912));
    UT_UEQ(g_s.tlm.period_rej, 0u);
}

/* A period with 5 of its 16 samples invalid (k = 20..24): period_rej, PERIOD_BAD at its last
   sample (k = 31), M = 0 over the next period (k = 31..46); then the difference restarts on the
   first good mean (k = 47: xbar_2 = 39 384, no difference term). With 4 invalid (k = 20..23,
   filled with the last good y_19 = 1703) the period is good: sum = 29 912 - (1740 + 1777 + 1814 +
   1851 - 4 1703) = 29 912 - 370 = 29 542, dx = 29 542 - 20 440 = 9102. */
UT_TEST(literal_bad_period_zeroes_the_next_period)
{
    pd_out_t o;
    int32_t k;
    pd_params_of(&PD_TBL_LITERAL, CH_PITCH, &g_p);
    pd_init(&g_s, &g_p);
    for (k = 0; k < 31; k++) {
        (void)step(&g_s, &g_p, 1000 + (37 * k), (k < 20) || (k > 24));
    }
    o = step(&g_s, &g_p, 1000 + (37 * 31), true);
    UT_UEQ(g_s.tlm.period_rej, 1u);
    UT_UEQ(o.health & PD_H_PERIOD_BAD, PD_H_PERIOD_BAD);
    UT_EQ(o.m_q28, 0);
    for (k = 32; k < 47; k++) {
        o = step(&g_s, &g_p, 1000 + (37 * k), true);
        UT_CHECK_EQ(o.m_q28, 0);
    }
    o = step(&g_s, &g_p, 1000 + (37 * 47), true);
    UT_EQ(o.m_q28, m_literal(GP40_Q16, GD_PITCH_Q16, 16 * 39384, 16 * 39384));
    UT_EQ(o.m_q28, -393840);                       /* -10 39 384 */
    /* 4 invalid: a good period */
    pd_init(&g_s, &g_p);
    for (k = 0; k < 31; k++) {
        (void)step(&g_s, &g_p, 1000 + (37 * k), (k < 20) || (k > 23));
    }
    o = step(&g_s, &g_p, 1000 + (37 * 31), true);
    UT_UEQ(g_s.tlm.period_rej, 0u);
    UT_EQ(o.m_q28, m_literal(GP40_Q16, GD_PITCH_Q16, 16 * 29542, 16 * 20440));
    /* P = 40 29 542 / 4 = 295 420 exactly; D = 3800 9102 / 64 = 540 431.25 -> 540 431 */
    UT_EQ(o.m_q28, -835851);
}

/* FAST_AVGP, pitch, y_k = 1000 + 37 k: before the first period completes P uses y_k
   (k = 0: -160 000; k = 1..14: -(160 y_k + 562 400)); from k = 15 the mean of the last completed
   period (xbar_0 = 20 440 q30) with D per sample: -(40 20 440 + 3800 592) / 4 = -766 800 on
   k = 15..30; k = 31: xbar_1 = 29 912: -(1 196 480 + 2 249 600) / 4 = -861 520. */
UT_TEST(avgp_law_p_on_the_last_mean_d_per_sample)
{
    pd_out_t o;
    int32_t k;
    pd_params_of(&PD_TBL_AVGP, CH_PITCH, &g_p);
    pd_init(&g_s, &g_p);
    o = step(&g_s, &g_p, 1000, true);
    UT_EQ(o.m_q28, -160000);
    UT_UEQ(o.health, (PD_LAW_FAST_AVGP << PD_H_LAW_SH) | PD_H_FALLBACK_GAIN);
    for (k = 1; k < 15; k++) {
        const int32_t y = 1000 + (37 * k);
        o = step(&g_s, &g_p, y, true);
        UT_CHECK_EQ(o.m_q28, -((160 * y) + 562400));
    }
    for (k = 15; k < 31; k++) {
        o = step(&g_s, &g_p, 1000 + (37 * k), true);
        UT_CHECK_EQ(o.m_q28, -766800);
        UT_CHECK_EQ(o.m_q28, (int32_t)m_raw(GP40_Q16, GD_PITCH_Q16, 20440, 16 * 37));
    }
    o = step(&g_s, &g_p, 1000 + (37 * 31), true);
    UT_EQ(o.m_q28, -861520);
}

/* ------------------------------------------------------------------ 6. determinism */

static void same_tlm(const pd_ch_tlm_t *a, const pd_ch_tlm_t *b)
{
    UT_CHECK_EQ(a->y_q30, b->y_q30);
    UT_CHECK_EQ(a->dy_q30, b->dy_q30);
    UT_CHECK_EQ(a->m_q28, b->m_q28);
    UT_CHECK_UEQ(a->k2_q22, b->k2_q22);
    UT_CHECK_UEQ(a->health, b->health);
    UT_CHECK_UEQ(a->health_sticky, b->health_sticky);
    UT_CHECK_UEQ(a->miss_cnt, b->miss_cnt);
    UT_CHECK_UEQ(a->stale_cnt, b->stale_cnt);
    UT_CHECK_UEQ(a->range_rej, b->range_rej);
    UT_CHECK_UEQ(a->rate_rej, b->rate_rej);
    UT_CHECK_UEQ(a->period_rej, b->period_rej);
    UT_CHECK_UEQ(a->trq_sat_cnt, b->trq_sat_cnt);
    UT_CHECK_UEQ(a->beta_lim_cnt, b->beta_lim_cnt);
}

/* Two instances fed the same 2000 samples (random walk, missing and out-of-range samples, spikes,
   gimbal angles, gain source changes) give identical outputs and telemetry at every step. */
UT_TEST(two_instances_are_identical_over_2000_samples)
{
    uint32_t seed = 987654321u;
    int32_t y = 20000;
    uint32_t k;
    params(CH_PITCH, &g_p);
    g_p2 = g_p;
    pd_init(&g_s, &g_p);
    pd_init(&g_s2, &g_p2);
    for (k = 0u; k < 2000u; k++) {
        const uint32_t r = lcg(&seed);
        pd_in_t in;
        pd_out_t a;
        pd_out_t b;
        y += (int32_t)((r >> 20) & 0x7FFu) - 1024;
        in = in_of(y, (r & 0x1Fu) != 0u);
        if ((r & 0x3F00u) == 0x0100u) {
            in.y_cnt = y + 2000000;                  /* a spike: rate rejection */
        }
        if ((r & 0x3F00u) == 0x0200u) {
            in.y_sat = true;
        }
        in.beta_cnt = (int32_t)((lcg(&seed) >> 6) & 0x1FFFFFFu) - 16777216;
        in.beta_valid = (k & 1u) == 0u;
        if (k == 500u) {
            pd_set_f_ground(&g_s, F_003_Q32);
            pd_set_f_ground(&g_s2, F_003_Q32);
            (void)pd_set_source(&g_s, &g_p, (uint8_t)PD_SRC_GROUND);
            (void)pd_set_source(&g_s2, &g_p, (uint8_t)PD_SRC_GROUND);
        }
        if (k == 1200u) {
            pd_set_k2_fixed(&g_s, &g_p, K_Q22(300));
            pd_set_k2_fixed(&g_s2, &g_p2, K_Q22(300));
            (void)pd_set_source(&g_s, &g_p, (uint8_t)PD_SRC_FIXED);
            (void)pd_set_source(&g_s2, &g_p, (uint8_t)PD_SRC_FIXED);
        }
        a = step_in(&g_s, &g_p, &in);
        b = step_in(&g_s2, &g_p2, &in);
        UT_CHECK_EQ(a.m_q28, b.m_q28);
        UT_CHECK_EQ(a.m_cnt, b.m_cnt);
        UT_CHECK_UEQ(a.health, b.health);
        UT_CHECK_UEQ(a.health & FX_ST_MASK, 0u);
        same_tlm(&g_s.tlm, &g_s2.tlm);
        if (ut_fail_count() != 0u) {
            break;
        }
    }
    /* the sequence did exercise the fault rows */
    UT_TRUE(g_s.tlm.miss_cnt > 0u);
    UT_TRUE(g_s.tlm.rate_rej > 0u);
    UT_TRUE(g_s.tlm.range_rej > 0u);
    UT_TRUE(g_s.tlm.beta_lim_cnt > 0u);
    UT_UEQ(g_s.tlm.k2_q22, K_Q22(300));
}

int main(void)
{
    UT_CASES(cases) = {
        UT_CASE(params_check_passes_the_three_default_channels),
        UT_CASE(params_check_null_is_an_argument_error),
        UT_CASE(params_check_period_inv_ty_to_one_lsb),
        UT_CASE(params_check_n_y_power_of_two_and_n_bad_max),
        UT_CASE(params_check_mode_source_and_schedule_law),
        UT_CASE(params_check_gain_order_and_g_p_bound),
        UT_CASE(params_check_g_d_bound_through_k2_max_at_a_short_ty),
        UT_CASE(params_check_schedule_nodes),
        UT_CASE(params_check_limits_and_fault_thresholds),
        UT_CASE(gains_are_the_hand_products),
        UT_CASE(fast_first_sample_has_no_kick_then_a_ramp_is_exact),
        UT_CASE(fast_rounds_half_away_from_zero_and_is_odd),
        UT_CASE(fast_mirrored_inputs_give_mirrored_torques),
        UT_CASE(torque_clamp_at_m_max_is_the_designated_saturation),
        UT_CASE(sched_returns_each_node_within_1_lsb),
        UT_CASE(sched_returns_the_mean_halfway_within_1_lsb),
        UT_CASE(sched_clamps_at_the_end_nodes_and_to_the_k2_limits),
        UT_CASE(gain_source_changes_take_effect_at_the_next_step),
        UT_CASE(gain_d_off_the_exact_ty_has_one_rounding),
        UT_CASE(missing_sample_holds_one_sample_then_coasts),
        UT_CASE(no_derivative_kick_after_4_16_dropped_samples_and_across_one),
        UT_CASE(fast_law_is_not_zeroed_after_a_bad_period),
        UT_CASE(out_of_range_sample_is_rejected),
        UT_CASE(implausible_rate_is_rejected_never_clamped),
        UT_CASE(frozen_sensor_is_refused_until_the_count_changes),
        UT_CASE(identical_y_under_small_torque_is_never_frozen),
        UT_CASE(gimbal_warn_and_limit),
        UT_CASE(literal_law_on_the_period_means),
        UT_CASE(literal_bad_period_zeroes_the_next_period),
        UT_CASE(avgp_law_p_on_the_last_mean_d_per_sample),
        UT_CASE(two_instances_are_identical_over_2000_samples),
    };
    return UT_RUN("pd", cases);
}
