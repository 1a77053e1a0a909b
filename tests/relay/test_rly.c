/*
 * Unit tests of the relay module (spec 20): tau2 rounding, the generator, the phase increment,
 * the table check (F5, one case per rule), the §3.2 transition table on hand-made samples, the
 * faults F1, F2, F4, F6, the envelope copy's invariants, the windows, and the adaptation rules of
 * §5 on synthetic window sums (PAPER and IMPROVED). Every expected value is worked out from the
 * spec's rules in the comment next to it, never read back from the code. Host and target.
 */
#include "rly_int.h"
#include "rly_tables.h"
#include "ut.h"

/* Test-only state in static storage: the target runner has a small stack. */
static rly_state_t g_s;
static rly_params_t g_p;
static rly_out_t g_o;

static rly_in_t sample(int32_t x)
{
    rly_in_t in = {0};
    in.x_q24 = x;
    in.valid = true;
    return in;
}

static void run(int32_t x, uint32_t n)
{
    uint32_t i;
    rly_in_t in = sample(x);
    for (i = 0u; i < n; i++) {
        rly_step(&g_s, &g_p, &in, &g_o);
    }
}

static void invalid(uint32_t n)
{
    uint32_t i;
    rly_in_t in = sample(INT32_MAX);
    in.valid = false;
    for (i = 0u; i < n; i++) {
        rly_step(&g_s, &g_p, &in, &g_o);
    }
}

/* tau2 = clamp((kt tau1 + 2^15) >> 16, 1, tau1), spec §3.5. */
UT_TEST(tau2_rounds_half_up_and_clamps)
{
    UT_UEQ(rly_tau2(20316u, 3367u), 1044u);     /* 0.31 x 3367 = 1043.77 -> 68 397 972 + 32 768 >> 16 = 1044 */
    UT_UEQ(rly_tau2(32768u, 3u), 2u);           /* 1.5 exactly: half up */
    UT_UEQ(rly_tau2(32768u, 1u), 1u);           /* 0.5 -> 1 (and >= 1) */
    UT_UEQ(rly_tau2(1u, 1u), 1u);               /* rounds to 0, clamped to 1 */
    UT_UEQ(rly_tau2(65535u, 65535u), 65534u);   /* 65535^2 / 65536 = 65534.00002 */
    UT_UEQ(rly_tau2(65535u, 1u), 1u);           /* clamped to tau1 */
    UT_UEQ(rly_tau2(65535u, 0xFFFFFFFFu), 0xFFFEFFFFu);   /* (2^16 - 1)(2^32 - 1) / 2^16, no overflow */
}

/* Marsaglia's xorshift32 from x = 1: 1 ^ 1 << 13 = 8193; ^ >> 17 keeps it; ^ 8193 << 5 = 270369. */
UT_TEST(xorshift32_is_marsaglias)
{
    uint32_t x = 1u;
    UT_UEQ(rly_xorshift32(&x), 270369u);
    UT_UEQ(x, 270369u);
}

/* dphi from f: the table's own pair (design.py, exact decimals) and the spec's value (§9). */
UT_TEST(phase_increment_of_the_frequency)
{
    UT_UEQ(RLY_TBL_DEFAULT.dphi_bam64[0], 1291791821444081u);
    UT_UEQ(RLY_TBL_DEFAULT.dphi_bam64[1], 2216597329977911u);
    UT_LE(rly_dphi_of(RLY_TBL_DEFAULT.f_q64[0], 1000u) - RLY_TBL_DEFAULT.dphi_bam64[0] + 1u, 2u);
    UT_UEQ(rly_dphi_of(0xFFFFFFFFFFFFFFFFu, 1000000u), 0xFFFFFFFFFFFFFFFFu);   /* a whole turn: >= 2^62 */
    UT_UEQ(rly_dphi_of((uint64_t)1u << 60, 1000u), 1152921504606847u);   /* 2^60 / 1000 = ...846.976 */
}

static uint32_t why_of(const rly_params_t *p)
{
    uint32_t why = 0u;
    (void)rly_params_check(p, &why);
    return why;
}

UT_TEST(table_check_one_case_per_rule)
{
    rly_params_t p;
    uint32_t why = 0xFFu;
    UT_UEQ(rly_params_check(&RLY_TBL_DEFAULT, &why), FSW_OK);
    UT_UEQ(why, 0u);
    UT_UEQ(rly_params_check(&RLY_TBL_PAPER, &why), FSW_OK);
    UT_UEQ(rly_params_check(&RLY_TBL_IMPROVED, &why), FSW_OK);
    UT_UEQ(rly_params_check(NULL, &why), FSW_ERR_ARG);
    p = RLY_TBL_DEFAULT; p.gamma_q24 = p.eps_q24;                 UT_UEQ(why_of(&p), RLY_WHY_GEOM);
    p = RLY_TBL_DEFAULT; p.gamma_q24 = 1;                         UT_UEQ(why_of(&p), RLY_WHY_GEOM);
    p = RLY_TBL_DEFAULT; p.x_max_q24 = p.eps_q24 - 1;             UT_UEQ(why_of(&p), RLY_WHY_GEOM);
    p = RLY_TBL_DEFAULT; p.kt0_q16 = (uint16_t)(p.kt_max_q16 + 1u); UT_UEQ(why_of(&p), RLY_WHY_KT);
    p = RLY_TBL_DEFAULT; p.kt_min_q16 = (uint16_t)(p.kt0_q16 + 1u); UT_UEQ(why_of(&p), RLY_WHY_KT);
    p = RLY_TBL_DEFAULT; p.dk_q16 = (uint16_t)((26214u - 18350u) / 4u + 1u); UT_UEQ(why_of(&p), RLY_WHY_KT);
    p = RLY_TBL_DEFAULT; p.seed = 0u;                             UT_UEQ(why_of(&p), RLY_WHY_SEED);
    p = RLY_TBL_DEFAULT; p.win_ticks = RLY_WIN_MAX + 1u;          UT_UEQ(why_of(&p), RLY_WHY_WIN);
    p = RLY_TBL_DEFAULT; p.n_modes = 5u;                          UT_UEQ(why_of(&p), RLY_WHY_MODES);
    p = RLY_TBL_DEFAULT; p.cu_q40[1] = RLY_C_MAX + 1;             UT_UEQ(why_of(&p), RLY_WHY_MODES);
    p = RLY_TBL_DEFAULT; p.dphi_bam64[0] = (uint64_t)1u << 62;    UT_UEQ(why_of(&p), RLY_WHY_PHASE);
    p = RLY_TBL_DEFAULT; p.dphi_bam64[1] += 2u;                   UT_UEQ(why_of(&p), RLY_WHY_PHASE);
    p = RLY_TBL_DEFAULT; p.period_us = 2000u;                     UT_UEQ(why_of(&p), RLY_WHY_PHASE);  /* dphi of 1 ms */
    p = RLY_TBL_DEFAULT; p.delta0_num = 20u;                      UT_UEQ(why_of(&p), RLY_WHY_ADAPT);
    p = RLY_TBL_DEFAULT; p.cliff_num = 2u;                        UT_UEQ(why_of(&p), RLY_WHY_ADAPT);
    p = RLY_TBL_DEFAULT; p.adapt_mode = 4u;                       UT_UEQ(why_of(&p), RLY_WHY_ADAPT);
    p = RLY_TBL_DEFAULT; p.lost_ticks = 0u;                       UT_UEQ(why_of(&p), RLY_WHY_LOST);
}

/* A rigid-only table with no adaptation: the law alone. */
static void law_only(void)
{
    g_p = RLY_TBL_FIXED_031;
    g_p.n_modes = 0u;
    rly_init(&g_s, &g_p);
}

/* §3.2 on the right side: W_POS -> R_MAIN at x >= eps (8389), main until x <= eps - gamma (6711),
   brake tau2(0.31, tau1) ticks, then W_POS with its tests in the same tick. */
UT_TEST(right_cycle_follows_the_transition_table)
{
    law_only();
    run(8388, 5u);                                     /* inside the deadband */
    UT_UEQ(g_o.cmd, RLY_LVL_WEAK_POS);
    UT_UEQ(g_s.st, RLY_ST_W_POS);
    run(8389, 1u);                                     /* x = eps: enters R_MAIN, commands from this tick */
    UT_UEQ(g_s.st, RLY_ST_R_MAIN);
    UT_UEQ(g_o.cmd, RLY_LVL_FULL_NEG);
    UT_UEQ(g_s.n, 0u);
    UT_UEQ(g_s.tlm.n_r_main, 1u);
    run(6712, 99u);                                    /* above the edge: n counts to 99 */
    UT_UEQ(g_s.n, 99u);
    run(6711, 1u);                                     /* x = eps - gamma: tau1 = 100, tau2 = round(31.0) = 31 */
    UT_UEQ(g_s.st, RLY_ST_R_BRAKE);
    UT_UEQ(g_o.cmd, RLY_LVL_FULL_POS);
    UT_UEQ(g_s.tlm.tau1, 100u);
    UT_UEQ(g_s.tlm.tau2, 31u);                         /* (20316 x 100 + 32768) >> 16 = 31 */
    run(9000, 30u);                                    /* x unused while braking */
    UT_UEQ(g_s.st, RLY_ST_R_BRAKE);
    UT_UEQ(g_s.nb, 1u);
    run(9000, 1u);                                     /* brake ends; W_POS tests: x >= eps -> R_MAIN */
    UT_UEQ(g_s.st, RLY_ST_R_MAIN);
    UT_UEQ(g_s.tlm.n_r_main, 2u);
}

/* The mirror: L_MAIN until x >= -(eps - gamma), the brake ends in W_NEG (weak level negative). */
UT_TEST(left_cycle_ends_in_the_negative_weak_level)
{
    law_only();
    run(-8389, 1u);
    UT_UEQ(g_s.st, RLY_ST_L_MAIN);
    UT_UEQ(g_o.cmd, RLY_LVL_FULL_POS);
    run(-6712, 9u);
    run(-6711, 1u);                                    /* tau1 = 10, tau2 = round(3.1) = 3 */
    UT_UEQ(g_s.st, RLY_ST_L_BRAKE);
    UT_UEQ(g_o.cmd, RLY_LVL_FULL_NEG);
    UT_UEQ(g_s.tlm.tau2, 3u);
    run(0, 3u);
    UT_UEQ(g_s.st, RLY_ST_W_NEG);
    UT_UEQ(g_o.cmd, RLY_LVL_WEAK_NEG);
    UT_UEQ(g_s.tlm.n_l_main, 1u);
}

/* n saturates at tau_max_ticks (TAU_SAT counted); the pulse still ends on its x test. */
UT_TEST(main_timer_saturates_and_the_pulse_still_ends)
{
    law_only();
    g_p.tau_max_ticks = 50u;
    run(8389, 1u);
    run(8000, 60u);
    UT_UEQ(g_s.n, 50u);
    UT_UEQ(g_s.tlm.n_tau_sat, 10u);                    /* ticks 51..60 */
    UT_TRUE((g_s.tlm.health_sticky & RLY_H_TAU_SAT) != 0u);
    run(0, 1u);
    UT_UEQ(g_s.st, RLY_ST_R_BRAKE);
    UT_UEQ(g_s.tlm.tau1, 50u);
}

/* F1: 10 invalid samples (INT32_MAX, not valid) in R_MAIN: tests skipped, the timer runs on;
   the first valid sample below the edge ends the pulse with tau1 counting the invalid ticks. */
UT_TEST(f1_invalid_samples_skip_the_tests_only)
{
    law_only();
    run(8389, 1u);
    run(7000, 5u);
    invalid(10u);
    UT_UEQ(g_s.st, RLY_ST_R_MAIN);
    UT_UEQ(g_o.cmd, RLY_LVL_FULL_NEG);
    UT_UEQ(g_s.n, 15u);
    UT_UEQ(g_s.tlm.n_x_invalid, 10u);
    UT_TRUE((g_o.health & RLY_H_X_INVALID) != 0u);
    run(0, 1u);
    UT_UEQ(g_s.st, RLY_ST_R_BRAKE);
    UT_UEQ(g_s.tlm.tau1, 16u);
    /* |x| > x_max is refused the same way, and counted as X_RANGE too */
    g_p.x_max_q24 = 100000;
    run(100001, 1u);
    UT_UEQ(g_s.tlm.n_x_range, 1u);
    UT_UEQ(g_s.tlm.n_x_invalid, 11u);
}

/* F2: a 500 ms outage: COAST (OFF) from the 100th invalid sample, SENSOR_LOST, the window is
   skipped with k_t unchanged; the first valid sample restarts from W_POS. */
UT_TEST(f2_sensor_lost_coasts_and_skips_the_window)
{
    g_p = RLY_TBL_DEFAULT;
    g_p.n_modes = 0u;
    g_p.win_ticks = 1000u;
    rly_init(&g_s, &g_p);
    run(8389, 1u);
    invalid(99u);
    UT_UEQ(g_s.st, RLY_ST_R_MAIN);
    invalid(1u);                                       /* the 100th in a row */
    UT_UEQ(g_s.st, RLY_ST_COAST);
    UT_UEQ(g_o.cmd, RLY_LVL_OFF);
    UT_TRUE((g_o.health & RLY_H_SENSOR_LOST) != 0u);
    invalid(400u);
    UT_UEQ(g_s.tlm.n_lost, 1u);
    run(0, 1u);                                        /* back: W_POS, weak positive level */
    UT_UEQ(g_s.st, RLY_ST_W_POS);
    UT_UEQ(g_o.cmd, RLY_LVL_WEAK_POS);
    run(0, 497u);                                      /* 999 ticks so far; tick 1000 closes window 0 */
    UT_UEQ(g_s.tlm.n_windows, 0u);
    run(0, 1u);
    UT_UEQ(g_s.tlm.n_windows, 1u);
    UT_UEQ(g_s.tlm.win.event, RLY_EV_SKIPPED);
    UT_UEQ(g_s.tlm.win.n_invalid, 500u);
    UT_UEQ(g_s.kt_q16, RLY_TBL_DEFAULT.kt0_q16);
    UT_UEQ(g_s.ad.n_valid, 0u);
}

/* The copy under one level is an exact rotation: amplitude held within the sin/cos error
   (<= 2^-28 relative: < 1 LSB at 3e6 LSB) over 100 000 ticks; q1(0) = x~1(0) gives a1 = 3 023 657. */
UT_TEST(copy_rotates_without_drift_under_one_level)
{
    g_p = RLY_TBL_FIXED_031;
    g_p.ce_q40[0] = 0;   /* no static deflection under the weak level: a1 stays |q1(0)| */
    g_p.ce_q40[1] = 0;
    rly_init(&g_s, &g_p);
    run(0, 1u);
    UT_UEQ(g_s.tlm.ai_q40[0], 3023657u);
    UT_UEQ(g_s.tlm.ai_q40[1], 0u);
    run(0, 100000u);
    UT_LE(g_s.tlm.ai_q40[0], 3023658u);
    UT_LE(3023656u, g_s.tlm.ai_q40[0]);
    UT_UEQ(g_s.lvl, RLY_LVL_WEAK_POS);
    UT_UEQ(g_s.tlm.a_q40, g_s.tlm.ai_q40[0]);
}

/* A level change re-anchors at the current (q, p): at the switch to FULL_NEG the anchor is
   u = q - (-C_u) = C_u, v = 0; one tick later (theta = omega h = 4.4e-4 rad) the mode is at
   (q, p) = (-C_u (1 - cos theta), -C_u sin theta), so a1 = 2 C_u sin(theta / 2) = 2129.05 LSB
   (C_u,1 = 4 838 760): the copy moved continuously from a = 0. Tolerance: 1/2 LSB per rounding. */
UT_TEST(level_change_reanchors_continuously)
{
    uint32_t a_before;
    g_p = RLY_TBL_FIXED_031;
    g_p.ce_q40[0] = 0;
    g_p.ce_q40[1] = 0;
    g_p.q0_q40[0] = 0;
    rly_init(&g_s, &g_p);
    run(0, 10u);
    a_before = g_s.tlm.a_q40;
    UT_UEQ(a_before, 0u);
    run(8389, 1u);                                     /* FULL_NEG from this tick: anchors u = 0 + C_u */
    UT_UEQ(g_s.lvl, RLY_LVL_FULL_NEG);
    UT_EQ(g_s.u_q40[0], RLY_TBL_FIXED_031.cu_q40[0]);
    run(8389, 1u);
    UT_LE(g_s.tlm.ai_q40[0], 2130u);
    UT_LE(2128u, g_s.tlm.ai_q40[0]);
}

/* F6: a 1.5e-3 rad initial mode is beyond the anchors' 2^30 LSB: they saturate, ENV_SAT sticky and
   counted, and the copy keeps running (no UB: this test also runs under UBSan). */
UT_TEST(f6_anchor_saturation_is_sticky_and_safe)
{
    rly_in_t in = sample(0);
    g_p = RLY_TBL_FIXED_031;
    g_p.q0_q40[0] = RLY_ANCHOR_MAX;
    rly_init(&g_s, &g_p);
    in.reinit = true;
    in.q_q40[0] = 1649267442;                          /* 1.5e-3 rad x 2^40 */
    rly_step(&g_s, &g_p, &in, &g_o);
    UT_TRUE((g_o.health & RLY_H_ENV_SAT) != 0u);
    UT_TRUE((g_o.health & RLY_H_REINIT) != 0u);
    UT_EQ(g_s.u_q40[0], RLY_ANCHOR_MAX);
    run(0, 1000u);
    UT_TRUE((g_s.tlm.health_sticky & RLY_H_ENV_SAT) != 0u);
    UT_UEQ(g_s.tlm.n_env_sat, 1u);
    UT_UEQ(g_s.tlm.n_reinit, 1u);
    UT_LE(g_s.tlm.ai_q40[0], 1073741824u + 120969u + 2u);   /* |u| + C_eps,1 (weak level) */
}

/* Windows are counted ticks: S sums a per tick, abar = round(S / N_w), j increments. */
UT_TEST(window_sum_and_mean)
{
    g_p = RLY_TBL_FIXED_031;
    g_p.ce_q40[0] = 0;
    g_p.ce_q40[1] = 0;
    g_p.win_ticks = 100u;
    rly_init(&g_s, &g_p);
    run(0, 99u);
    UT_UEQ(g_s.tlm.n_windows, 0u);
    run(0, 1u);
    UT_TRUE((g_o.health & RLY_H_WIN_DONE) != 0u);
    UT_UEQ(g_s.tlm.win.j, 0u);
    UT_LE(g_s.tlm.win.s, 302365800u);                  /* 100 x 3 023 657 +- 1 LSB a tick */
    UT_LE(302365600u, g_s.tlm.win.s);
    UT_LE(g_s.tlm.win.abar_q40, 3023658u);
    UT_LE(3023656u, g_s.tlm.win.abar_q40);
    UT_UEQ(g_s.tlm.win.event, RLY_EV_NONE);            /* adaptation OFF still reports */
    run(0, 100u);
    UT_UEQ(g_s.tlm.win.j, 1u);
}

/* ---- adaptation on synthetic sums (rly_adapt_window directly) ---- */
static rly_adapt_t g_a;
static rly_win_t g_w;
static uint16_t g_kt;

static uint16_t win(uint64_t s, uint32_t j, uint32_t *h)
{
    g_w.s = s;
    g_w.j = j;
    g_w.kt_in_q16 = g_kt;
    g_kt = rly_adapt_window(&g_a, &g_p, true, &g_w, h);
    return g_kt;
}

/* First draw after warm-up from the seed (the generator alone, replayed here). */
static uint32_t draw_n(uint32_t seed, uint32_t n)
{
    uint32_t x = seed;
    uint32_t u = 0u;
    uint32_t i;
    for (i = 0u; i < (16u + n); i++) {
        u = rly_xorshift32(&x);
    }
    return u;
}

/* PAPER §5.1: j = 0 draws sign and magnitude; a decrease keeps the sign; an increase flips it;
   after n_ignore decreases one increase is ignored; the step is round(mag dk). */
UT_TEST(paper_learning_rules)
{
    uint32_t h = 0u;
    uint32_t u0 = draw_n(1u, 1u);
    int32_t s0 = ((u0 >> 31) != 0u) ? -1 : 1;
    uint32_t mag = ((u0 >> 15) & 0xFFFFu) + 1u;
    int32_t step = (int32_t)(((uint64_t)mag * 131u + 32768u) >> 16);
    uint32_t j;
    g_p = RLY_TBL_PAPER;
    rly_adapt_init(&g_a, &g_p);
    g_kt = g_p.kt0_q16;
    UT_EQ(win(1000000u, 0u, &h), 20316 + s0 * step);
    UT_EQ(g_w.sign, s0);
    UT_UEQ(g_w.mag_q16, mag);
    UT_UEQ(g_w.event, RLY_EV_STEP);
    /* four decreases keep the sign */
    for (j = 1u; j <= 4u; j++) {
        (void)win(1000000u - (j * 100000u), j, &h);
        UT_EQ(g_w.sign, s0);
    }
    UT_UEQ(g_a.n_dec, 4u);
    (void)win(900000u, 5u, &h);                        /* an increase after 4 decreases: ignored once */
    UT_EQ(g_w.sign, s0);
    UT_UEQ(g_a.n_dec, 0u);
    (void)win(950000u, 6u, &h);                        /* a second increase flips */
    UT_EQ(g_w.sign, -s0);
    UT_UEQ(g_w.rng, g_a.rng);
}

/* PAPER freeze: from j + 1 >= tmin (20) with n_small >= 6 the k_t freezes for good (no step). */
UT_TEST(paper_freezes_on_a_run_of_small_changes)
{
    uint32_t h = 0u;
    uint32_t j;
    uint16_t kt_frozen = 0u;
    g_p = RLY_TBL_PAPER;
    rly_adapt_init(&g_a, &g_p);
    g_kt = g_p.kt0_q16;
    for (j = 0u; j < 18u; j++) {                       /* 1 % changes: all small (delta0 = 5 %) */
        (void)win(1000000u + ((j & 1u) * 10000u), j, &h);
        UT_UEQ(g_w.event, RLY_EV_STEP);
    }
    (void)win(1000000u, 18u, &h);                      /* j + 1 = 19 < 20: still a step */
    UT_UEQ(g_w.event, RLY_EV_STEP);
    kt_frozen = win(1010000u, 19u, &h);                /* j + 1 = 20, n_small = 19 >= 6 */
    UT_UEQ(g_w.event, RLY_EV_FREEZE_SETTLED);
    UT_UEQ(kt_frozen, g_w.kt_in_q16);
    UT_UEQ(g_w.phase, RLY_PH_FROZEN);
    (void)win(5000000u, 20u, &h);                      /* PAPER never un-freezes */
    UT_UEQ(g_kt, kt_frozen);
    UT_UEQ(g_w.phase, RLY_PH_FROZEN);
}

/* IMPROVED cliff (§5.6): 2 S_j > 3 S_j-1 after T_min freezes at k_t,j-1 - d 2 dk. */
UT_TEST(improved_retreats_from_a_cliff)
{
    uint32_t h = 0u;
    uint32_t j;
    uint16_t kt_prev;
    int32_t d;
    g_p = RLY_TBL_DEFAULT;
    rly_adapt_init(&g_a, &g_p);
    g_kt = g_p.kt0_q16;
    for (j = 0u; j < 20u; j++) {                       /* alternating +-10 %: never small, never a cliff */
        (void)win(((j & 1u) != 0u) ? 1100000u : 1000000u, j, &h);
    }
    kt_prev = g_a.kt_hist[0];                          /* k_t in force during window 19 */
    d = g_a.d_last;                                    /* direction of the step that ends window 19 */
    (void)win(1000000u * 2u, 20u, &h);                 /* 2 x 2.0 > 3 x 1.0 or 1.1: cliff */
    UT_UEQ(g_w.event, RLY_EV_FREEZE_CLIFF);
    UT_EQ(g_kt, (int32_t)kt_prev - (d * 2 * 131));
    UT_UEQ(g_w.phase, RLY_PH_FROZEN);
}

/* IMPROVED settled: n_small >= 6 and k_t within 2 dk of 6 windows ago -> PROBE k, k + dk, k - dk,
   2 windows each; freeze at the lowest measured S (ties: earlier). Then the un-freeze net. */
UT_TEST(improved_probes_then_freezes_at_the_best_point)
{
    uint32_t h = 0u;
    uint32_t j;
    uint16_t k0;
    g_p = RLY_TBL_DEFAULT;
    g_p.dk_q16 = 1u;                                   /* tiny steps: k_t stays within the gate */
    rly_adapt_init(&g_a, &g_p);
    g_kt = g_p.kt0_q16;
    for (j = 0u; j < 19u; j++) {
        (void)win(1000000u, j, &h);                    /* flat: every change small */
    }
    k0 = win(1000000u, 19u, &h);                       /* j + 1 = 20: settled -> probe */
    UT_UEQ(g_w.event, RLY_EV_PROBE_START);
    UT_UEQ(k0, g_w.kt_in_q16);
    UT_UEQ(win(999999u, 20u, &h), k0);                 /* point 0 settles */
    UT_UEQ(win(1000000u, 21u, &h), (uint16_t)(k0 + 1u));   /* point 0 measured: S = 1 000 000 */
    UT_UEQ(win(1000000u, 22u, &h), (uint16_t)(k0 + 1u));   /* point 1 settles */
    UT_UEQ(win(900000u, 23u, &h), (uint16_t)(k0 - 1u));    /* point 1 measured: 900 000 */
    UT_UEQ(win(800000u, 24u, &h), (uint16_t)(k0 - 1u));    /* point 2 settles (not measured) */
    UT_UEQ(win(950000u, 25u, &h), (uint16_t)(k0 + 1u));    /* point 2 measured 950 000: best is point 1 */
    UT_UEQ(g_w.event, RLY_EV_FREEZE_SETTLED);
    (void)win(900000u, 26u, &h);                       /* 1st window after the freeze */
    (void)win(900000u, 27u, &h);                       /* 2nd: S_ref = 900 000 */
    UT_UEQ(g_a.s_ref, 900000u);
    (void)win(1400000u, 28u, &h);                      /* 2 x 1.4 > 3 x 0.9: 1 */
    (void)win(1400000u, 29u, &h);                      /* 2 */
    UT_UEQ(g_w.phase, RLY_PH_FROZEN);
    (void)win(1400000u, 30u, &h);                      /* 3 in a row: un-freeze with a fresh draw */
    UT_UEQ(g_w.event, RLY_EV_UNFREEZE);
    UT_UEQ(g_w.phase, RLY_PH_SEARCH);
}

/* F4: kt0 = kt_max with dk = 0.05 (3277): never outside the limits, KT_CLAMPED raised. */
UT_TEST(f4_kt_stays_within_its_limits)
{
    uint32_t h = 0u;
    uint32_t j;
    g_p = RLY_TBL_PAPER;
    g_p.kt0_q16 = g_p.kt_max_q16;
    g_p.dk_q16 = 1966u;                                /* the largest legal: (26214 - 18350) / 4 */
    rly_adapt_init(&g_a, &g_p);
    g_kt = g_p.kt0_q16;
    for (j = 0u; j < 200u; j++) {
        (void)win(((j * 7919u) % 13u + 1u) * 1000000u, j, &h);
        UT_LE(g_kt, 26214);
        UT_LE(18350, g_kt);
    }
    UT_TRUE((h & RLY_H_KT_CLAMPED) != 0u);
}

int main(void)
{
    UT_CASES(cases) = {
        UT_CASE(tau2_rounds_half_up_and_clamps),
        UT_CASE(xorshift32_is_marsaglias),
        UT_CASE(phase_increment_of_the_frequency),
        UT_CASE(table_check_one_case_per_rule),
        UT_CASE(right_cycle_follows_the_transition_table),
        UT_CASE(left_cycle_ends_in_the_negative_weak_level),
        UT_CASE(main_timer_saturates_and_the_pulse_still_ends),
        UT_CASE(f1_invalid_samples_skip_the_tests_only),
        UT_CASE(f2_sensor_lost_coasts_and_skips_the_window),
        UT_CASE(copy_rotates_without_drift_under_one_level),
        UT_CASE(level_change_reanchors_continuously),
        UT_CASE(f6_anchor_saturation_is_sticky_and_safe),
        UT_CASE(window_sum_and_mean),
        UT_CASE(paper_learning_rules),
        UT_CASE(paper_freezes_on_a_run_of_small_changes),
        UT_CASE(improved_retreats_from_a_cliff),
        UT_CASE(improved_probes_then_freezes_at_the_best_point),
        UT_CASE(f4_kt_stays_within_its_limits),
    };
    return UT_RUN("rly", cases);
}
