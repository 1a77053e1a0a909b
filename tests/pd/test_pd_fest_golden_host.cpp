// G3: the fixed-point estimator fsw/pd/pd_fest against its double design sim/pd/pd_fest_ref
// (FestRef), both fed the same sample stream of the adaptive closed loop of fly_adaptive (FAST law,
// cold start at k2_cold, re-tune at each period boundary, sigma_y = 2e-6 rad, x0 = 0.017 rad). The
// loop's k2 follows the reference's decisions, so the two estimators see identical (y, M, k2); y and
// M are quantised to the flight formats (q30 rad, q28 N m) and the reference gets the quantised
// values, so any difference is the port's arithmetic.
//
// Tolerances, derived:
//  - cinv table lookup: each node is rounded once (0.5 LSB q30), the bilinear interpolation adds
//    three roundings of 0.5 LSB, and the floored q28 grid fractions lose < 2^-28 of a cell, i.e.
//    < 0.45 x 2^30 / 2^28 = 1.8 LSB at the steepest cell the check allows (1 / c in [0.8, 1.25]):
//    <= 4 LSB.
//  - f_hat while both are confident: the published estimate moves in steps of >= 0.5 % (the
//    hysteresis), so two estimators whose raw estimates differ by less than that can publish values
//    up to one hysteresis step apart; the raw estimate itself may differ by the port's rounding of
//    the notch coefficient a (q29, <= 1e-9 relative per Td) amplified by the RLS over its memory
//    (~33 Td), far below 0.1 %. Bound: 0.5 % (one hysteresis step) + 0.1 % = 0.6 %, a fifth of the
//    spec's R3 budget at 300 s (5 %) at the most; measured figures are printed.
//  - state: the confidence tests are thresholds on the same quantities, so a borderline crossing
//    may fall one period apart; the states must agree on >= 95 % of the periods.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "pd/pd_fest_quant.hpp"
#include "pd/pd_fest_ref.hpp"
#include "sim_test.hpp"

namespace {

using namespace ref::pd;

const K2Schedule &schedule(const std::string &ch)
{
    static const K2Schedule p = load_k2_schedule(std::string(PD_SCHEDULE_DIR) + "/pitch_fast.json");
    static const K2Schedule r = load_k2_schedule(std::string(PD_SCHEDULE_DIR) + "/roll_fast.json");
    static const K2Schedule y = load_k2_schedule(std::string(PD_SCHEDULE_DIR) + "/yaw_fast.json");
    return ch == "roll" ? r : (ch == "yaw" ? y : p);
}

struct Cmp {
    int periods = 0, both_conf = 0, state_agree = 0, fx_conf = 0, ref_conf = 0;
    double max_rel = 0.0;           // |f_fx / f_ref - 1| while both confident
    double f300_ref = 0.0, f300_fx = 0.0, f1200_ref = 0.0, f1200_fx = 0.0;
    unsigned fx_resets = 0u, ref_resets = 0u;
    fx_status_t st = 0u;
};

// kick_s > 0: x += 0.017 rad there (A3-9's kick: a RESID fault and a re-acquisition); drop > 0: every
// drop-th sample is invalid (the §8 gap path: the predictor coasts, no differencing across it).
Cmp compare(const Channel &ch, double f_hz, unsigned seed, double kick_s = -1.0, long drop = 0)
{
    const FestParams fp = make_fest_params(ch);
    const pd_fest_params_t q = quantise_fest(fp);
    EXPECT_EQ_INT(pd_fest_check(&q), 0);
    const K2Schedule &sched = schedule(ch.name);
    const Discrete d = discretise(ch, f_hz);
    Eigen::VectorXd s = Eigen::VectorXd::Zero(d.Ad.rows()), sn(d.Ad.rows());
    s(0) = ch.x0;
    const long N = std::lround(1200.0 / ch.Ty);
    const long n_kick = kick_s > 0.0 ? std::lround(kick_s / ch.Ty) : -1;
    FestRef ref(fp);
    pd_fest_t fx{};
    pd_fest_init(&fx);
    double k2 = sched.k2_cold, y_prev = 0.0, f_prev = fp.f0_hz;
    bool first = true;
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> noise(0.0, 2e-6);
    const double GP = ch.k0 * ch.k1;
    Cmp c;
    for (long n = 0; n < N; ++n) {
        if (n == n_kick) {
            s(0) += 0.017;
        }
        const bool valid = drop <= 0 || (n % drop) != drop - 1;
        const double y = std::ldexp(std::nearbyint(std::ldexp(s(0) + noise(rng), 30)), -30);
        if (first) {
            y_prev = y;
            first = false;
        }
        const double GD = ch.k0 * k2 / ch.Ty;
        const double Mc = std::clamp(-(GP * y + GD * (y - y_prev)), -2.0, 2.0);
        const double M = std::ldexp(std::nearbyint(std::ldexp(Mc, 28)), -28);
        y_prev = y;
        const FestOut o = ref.step(valid, y, M, k2);
        pd_fest_step(&fx, &q, static_cast<uint32_t>(ch.n_y), valid, static_cast<int32_t>(std::ldexp(y, 30)),
                     static_cast<int32_t>(std::ldexp(M, 28)), static_cast<uint32_t>(std::lround(std::ldexp(k2, 22))));
        EXPECT_TRUE(o.period_end == fx.period_end);
        if (o.period_end) {
            const double t = static_cast<double>(n + 1) * ch.Ty;
            const double f_fx = std::ldexp(static_cast<double>(fx.f_hat_q32), -32);
            ++c.periods;
            c.state_agree += static_cast<int>(o.state) == static_cast<int>(fx.state) ? 1 : 0;
            c.fx_conf += fx.confident ? 1 : 0;
            c.ref_conf += o.confident ? 1 : 0;
            if (o.confident && fx.confident) {
                ++c.both_conf;
                c.max_rel = std::max(c.max_rel, std::fabs(f_fx / o.f_hat_hz - 1.0));
            }
            if (t <= 300.0 + 1e-9) {  // the period ending at or before 300 s
                c.f300_ref = o.f_hat_hz;
                c.f300_fx = f_fx;
            }
            c.f1200_ref = o.f_hat_hz;
            c.f1200_fx = f_fx;
            // the reference's re-tune decision (spec §4.2) drives the loop
            if (o.state == FestState::Fault) {
                k2 = sched.k2_cold;
            } else if (o.confident && std::fabs(o.f_hat_hz / f_prev - 1.0) < 0.02) {
                k2 = sched.at(o.f_hat_hz);
            }
            f_prev = o.f_hat_hz;
        }
        sn.noalias() = d.Ad * s + d.Bd * M;
        s.swap(sn);
    }
    c.fx_resets = fx.resets;
    c.ref_resets = static_cast<unsigned>(ref.out().resets);
    c.st = fx.st_sticky;
    std::printf("  %-5s f %.3f Hz seed %u%s%s: periods %d, states agree %.1f %%, confident ref %d fx %d both %d, "
                "max |f_fx/f_ref - 1| %.4f %%, f^(300) %.5f / %.5f, f^(1200) %.5f / %.5f Hz, resets %u / %u, "
                "fx status 0x%x\n",
                ch.name.c_str(), f_hz, seed, kick_s > 0.0 ? ", kick" : "", drop > 0 ? ", gaps" : "", c.periods, 100.0 * c.state_agree / std::max(c.periods, 1), c.ref_conf,
                c.fx_conf, c.both_conf, 100.0 * c.max_rel, c.f300_ref, c.f300_fx, c.f1200_ref, c.f1200_fx,
                c.ref_resets, c.fx_resets, static_cast<unsigned>(c.st));
    return c;
}

}  // namespace

// The 1 / c lookup of the flight table against the reference's (the same bilinear rule on 1 / c).
SIM_TEST(cinv_lookup)
{
    const FestParams fp = make_fest_params(Channel::pitch());
    const pd_fest_params_t q = quantise_fest(fp);
    const FestRef est(fp);
    double worst = 0.0;
    for (double f = 0.0; f <= 0.14; f += 0.00137) {
        for (double k2 = 0.0; k2 <= 1020.0; k2 += 37.0) {
            const uint32_t got = pd_fest_cinv(&q, static_cast<uint32_t>(std::lround(std::ldexp(f, 32))),
                                              static_cast<uint32_t>(std::lround(std::ldexp(k2, 22))));
            const double want = std::ldexp(est.cinv_of(f, k2), 30);
            worst = std::max(worst, std::fabs(static_cast<double>(got) - want));
        }
    }
    std::printf("  cinv: max |fixed - double| %.2f LSB q30 (bound 4)\n", worst);
    EXPECT_TRUE(worst <= 4.0);
}

// The table block: usable, and the check refuses what the port does not cover.
SIM_TEST(check_refuses)
{
    pd_fest_params_t q = quantise_fest(make_fest_params(Channel::pitch()));
    EXPECT_EQ_INT(pd_fest_check(&q), 0);
    q.n_sec = 2u;  // yaw's cascade: usable
    EXPECT_EQ_INT(pd_fest_check(&q), 0);
    q.n_sec = 3u;
    EXPECT_EQ_INT(pd_fest_check(&q), 1);
    q.n_sec = 0u;
    EXPECT_EQ_INT(pd_fest_check(&q), 1);
    q = quantise_fest(make_fest_params(Channel::pitch()));
    q.cinv_q30[3][4] = 0u;
    EXPECT_EQ_INT(pd_fest_check(&q), 9);
    q = quantise_fest(make_fest_params(Channel::pitch()));
    q.ad_sh[2] = 63u;
    EXPECT_EQ_INT(pd_fest_check(&q), 8);
    q = quantise_fest(make_fest_params(Channel::pitch()));
    q.sigma_y_q40 = 0u;
    EXPECT_EQ_INT(pd_fest_check(&q), 7);
}

// G3 on pitch at the four A3-5 nodes, and roll at one.
SIM_TEST(g3_pitch_roll)
{
    struct Case {
        Channel ch;
        double f;
    };
    const Case cases[] = {{Channel::pitch(), 0.01}, {Channel::pitch(), 0.03}, {Channel::pitch(), 0.07},
                          {Channel::pitch(), 0.10}, {Channel::roll(), 0.03}};
    for (const Case &k : cases) {
        const Cmp c = compare(k.ch, k.f, 0u);
        EXPECT_TRUE(c.periods == 300);
        EXPECT_TRUE(c.state_agree >= (95 * c.periods) / 100);
        EXPECT_TRUE(c.both_conf > 0);
        EXPECT_TRUE(c.max_rel <= 0.006);
        EXPECT_TRUE(std::fabs(c.f1200_fx / c.f1200_ref - 1.0) <= 0.001);
        EXPECT_TRUE(c.fx_resets == c.ref_resets);
        EXPECT_EQ_INT(static_cast<int>(c.st), 0);
    }
}

// The fault and gap paths: a kick (RESID fault, one period in FAULT, re-acquisition from f0 with the
// predictor kept) and 1 sample in 20 invalid, both against the reference; pitch, and yaw, whose reset
// also clears the cascade and the line logic (pair memory, envelope ring).
SIM_TEST(g3_fault_gaps)
{
    struct Case {
        Channel ch;
        double f_kick, f_gaps;
        unsigned kick_resets;  // the reference's FAULT count after the kick: pitch 1 (the RESID), yaw 4
    };
    for (const Case &c : {Case{Channel::pitch(), 0.03, 0.07, 1u}, Case{Channel::yaw(), 0.03, 0.05, 4u}}) {
        const Cmp k = compare(c.ch, c.f_kick, 1u, 600.0);
        EXPECT_EQ_INT(k.ref_resets, c.kick_resets);
        EXPECT_TRUE(k.fx_resets == k.ref_resets);
        EXPECT_TRUE(k.state_agree >= (95 * k.periods) / 100);
        EXPECT_TRUE(k.max_rel <= 0.006);
        const Cmp g = compare(c.ch, c.f_gaps, 2u, -1.0, 20);
        EXPECT_TRUE(g.both_conf > 0);
        EXPECT_TRUE(g.state_agree >= (95 * g.periods) / 100);
        EXPECT_TRUE(g.max_rel <= 0.006);
        EXPECT_EQ_INT(static_cast<int>(k.st | g.st), 0);
    }
}

// G3 on yaw (two sections and the line logic) across its range: the lowest grid node, where the
// pair decides, the pair-to-single hand-over region and the single-line proofs above it.
SIM_TEST(g3_yaw)
{
    const double fs[] = {0.01, 0.02, 0.03, 0.05, 0.10};
    for (double f : fs) {
        const Cmp c = compare(Channel::yaw(), f, 0u);
        EXPECT_TRUE(c.periods == 300);
        EXPECT_TRUE(c.state_agree >= (95 * c.periods) / 100);
        EXPECT_TRUE(c.max_rel <= 0.006);
        EXPECT_TRUE(std::fabs(c.f1200_fx / c.f1200_ref - 1.0) <= 0.001);
        EXPECT_TRUE(c.fx_resets == c.ref_resets);
        EXPECT_EQ_INT(static_cast<int>(c.st), 0);
    }
}

int main()
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(cinv_lookup), cmocka_unit_test(check_refuses),
                                       cmocka_unit_test(g3_pitch_roll), cmocka_unit_test(g3_yaw),
                                       cmocka_unit_test(g3_fault_gaps)};
    return cmocka_run_group_tests_name("pd_fest_golden_host", tests, nullptr, nullptr);
}
