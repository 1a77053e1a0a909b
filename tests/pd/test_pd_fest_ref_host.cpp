// The double reference of the on-board frequency estimator (sim/pd/pd_fest_ref, spec 40 §4.4 option
// A) flown in the adaptive pitch closed loop of §4.2 on the exact discrete plant (fly_adaptive:
// FAST law, cold start at k2_cold, re-tune at each period boundary, sigma_y = 2e-6 rad, x0 = 0.017
// rad, 1200 s), against a reduced set of the spec's requirements:
//   R3  |f^/f - 1| < 5 % at 300 s and < 10 % at 1200 s (0.01, 0.03, 0.07, 0.10 Hz, two seeds);
//   R5  no confident f^ > 1.1 f with the true modal coupling x0.8 and x1.25 (0.01, 0.07 Hz);
//   R4  once the truth is inside 5 sigma_y for good, f^ drifts <= 2 % per 600 s, and k2 is not
//       re-tuned once the estimator has frozen (HOLD);
//   A3-5 t* against the spec's §7 reference t*(k2 = 0) / t*(k2 = 150).
// The schedule is the committed tools/pd/schedule/pitch_fast.json. Every bound is the spec's.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "pd/pd_fest_ref.hpp"
#include "sim_test.hpp"

namespace {

using namespace ref::pd;

const K2Schedule &pitch_schedule()
{
    static const K2Schedule s = load_k2_schedule(std::string(PD_SCHEDULE_DIR) + "/pitch_fast.json");
    return s;
}

const FestParams &pitch_params()
{
    static const FestParams p = make_fest_params(Channel::pitch());
    return p;
}

AdaptiveRun fly(double f, unsigned seed, double coupling = 1.0)
{
    AdaptiveConfig c;
    Scales s;
    s.coupling = coupling;
    c.plant = scaled(Channel::pitch(), s);
    c.f_hz = f;
    c.seed = seed;
    return fly_adaptive(c, pitch_params(), pitch_schedule());
}

const double kNodes[] = {0.01, 0.03, 0.07, 0.10};

}  // namespace

// The table itself: the schedule was read, c(f, k2) is the spec's closed-loop shift (§2.2: +0.05 ...
// +5.1 % along the pitch schedule, -1.1 ... +6.5 % over k2 in [0, 475]), the injection is stable.
SIM_TEST(fest_table)
{
    const K2Schedule &s = pitch_schedule();
    EXPECT_EQ_INT(s.f_hz.size(), 19);
    EXPECT_NEAR(s.k2_cold, 475.0, 1e-9);
    const FestRef est(pitch_params());
    double cmin = 10.0, cmax = 0.0;
    for (std::size_t i = 0; i < s.f_hz.size(); ++i) {
        const double c = est.c_of(s.f_hz[i], s.k2[i]);
        cmin = std::min(cmin, c);
        cmax = std::max(cmax, c);
    }
    std::printf("  c(f, k2s(f)) in [%.4f, %.4f] along the schedule (spec: 1.0005 ... 1.051)\n", cmin, cmax);
    EXPECT_TRUE(cmin >= 0.999 && cmax <= 1.06);
    EXPECT_NEAR(pitch_params().m_ch, 1.13, 1e-12);
}

// R3 (reduced) and A3-5 at the same runs.
SIM_TEST(r3_a35_pitch)
{
    struct Ref {
        double t0, t150;  // spec §7: t*(k2 = 0) / t*(k2 = 150)
    };
    const Ref refs[] = {{1988.0, 1990.0}, {340.0, 384.0}, {130.0, 84.0}, {95.0, 68.0}};
    for (std::size_t i = 0; i < 4; ++i) {
        const double f = kNodes[i], best = std::min(refs[i].t0, refs[i].t150);
        for (unsigned seed = 0; seed < 2; ++seed) {
            const AdaptiveRun r = fly(f, seed);
            const double e300 = r.f_at(300.0) / f - 1.0, e1200 = r.f_at(1200.0) / f - 1.0;
            std::printf("  f=%.2f seed %u: f^(300) %+.4f%s f^(1200) %+.4f%s t* %.2f (best constant %.0f) resets %d\n",
                        f, seed, e300, r.conf_at(300.0) != 0 ? " c" : "  ", e1200,
                        r.conf_at(1200.0) != 0 ? " c" : "  ", r.t_star_s, best, r.resets);
            EXPECT_LE(std::fabs(e300), 0.05);
            EXPECT_LE(std::fabs(e1200), 0.10);
            EXPECT_TRUE(r.t_star_s >= 0.0);
            if (f <= 0.03 + 1e-9) {
                EXPECT_LE(r.t_star_s, 0.55 * best);
            }
            if (f < 0.05) {
                EXPECT_TRUE(r.t_star_s < best);
            } else {
                EXPECT_LE(r.t_star_s, 1.3 * best + 10.0);
            }
        }
    }
}

// R5 on the coupling part of A3-9.
SIM_TEST(r5_coupling)
{
    for (double coupling : {0.8, 1.25}) {
        for (double f : {0.01, 0.07}) {
            for (unsigned seed = 0; seed < 2; ++seed) {
                const AdaptiveRun r = fly(f, seed, coupling);
                double worst = 0.0;
                for (std::size_t i = 0; i < r.f_hat_hz.size(); ++i) {
                    if (r.confident[i] != 0) {
                        worst = std::max(worst, r.f_hat_hz[i] / f);
                    }
                }
                std::printf("  coupling x%.2f f=%.2f seed %u: max confident f^/f %.4f, f^(300)/f %.4f\n", coupling, f,
                            seed, worst, r.f_at(300.0) / f);
                EXPECT_LE(worst, 1.1);
            }
        }
    }
}

// R4: after the truth has stayed inside 5 sigma_y (the response is in the noise), f^ drifts <= 2 %
// per 600 s, the estimator freezes (HOLD) and no re-tune follows it. Until the gate's 20-s RMS has
// seen the line fade, TRACK may still trim k2 (by <= 3 % here). 2400-s runs, so that 0.03 Hz
// reaches the noise with 600 s to spare; at 0.01 Hz the elastic ripple outlasts them.
SIM_TEST(r4_quiescence)
{
    for (double f : {0.03, 0.07, 0.10}) {
        for (unsigned seed = 0; seed < 2; ++seed) {
            AdaptiveConfig c;
            c.plant = Channel::pitch();
            c.f_hz = f;
            c.seed = seed;
            c.horizon_s = 2400.0;
            const AdaptiveRun r = fly_adaptive(c, pitch_params(), pitch_schedule());
            std::size_t kq = r.x_rad.size();
            while (kq > 0 && std::fabs(r.x_rad[kq - 1]) < 5.0 * 2e-6) {
                --kq;
            }
            const double t_q = static_cast<double>(kq) * 0.25;
            const double f_q = r.f_at(t_q), k2_q = r.k2_at(t_q);
            double drift = 0.0, dk2 = 0.0;
            int retune_in_hold = 0;
            bool held = false;
            for (std::size_t i = 1; i < r.f_hat_hz.size(); ++i) {
                if (r.t_period_s[i] <= t_q) {
                    continue;
                }
                drift = std::max(drift, std::fabs(r.f_hat_hz[i] / f_q - 1.0));
                dk2 = std::max(dk2, std::fabs(r.k2[i] / k2_q - 1.0));
                held = held || r.state[i] == static_cast<int>(FestState::Hold);
                if (held && std::fabs(r.k2[i] - r.k2[i - 1]) > 1e-9) {
                    ++retune_in_hold;
                }
            }
            const double per600 = drift * 600.0 / std::max(600.0, 2400.0 - t_q);
            std::printf("  f=%.2f seed %u: in the noise from %.0f s, drift %.4f per 600 s, k2 moved %.4f, HOLD %s, "
                        "re-tunes in HOLD %d\n",
                        f, seed, t_q, per600, dk2, held ? "yes" : "no", retune_in_hold);
            EXPECT_LE(t_q, 1800.0);
            EXPECT_LE(per600, 0.02);
            EXPECT_LE(dk2, 0.03);
            EXPECT_TRUE(held);
            EXPECT_EQ_INT(retune_in_hold, 0);
        }
    }
}

// Yaw (two sections, the lower-tone rule; double design only, not yet ported): R3 for its lowest tone
// and R5 at the nodes that failed before the 2026-12-06 changes (0.020 Hz at 300 s, 5.5 %; 0.010 Hz,
// 18.6 % with the corner fix alone: fsw/pd/README.md "The estimator in double") and at 0.07 Hz.
SIM_TEST(r3_r5_yaw_lowest_tone)
{
    static const K2Schedule ys = load_k2_schedule(std::string(PD_SCHEDULE_DIR) + "/yaw_fast.json");
    static const FestParams yp = make_fest_params(Channel::yaw());
    for (double f : {0.010, 0.020, 0.035, 0.07}) {
        for (unsigned seed = 0; seed < 2; ++seed) {
            AdaptiveConfig c;
            c.plant = Channel::yaw();
            c.f_hz = f;
            c.seed = seed;
            const AdaptiveRun r = fly_adaptive(c, yp, ys);
            const double e300 = r.f_at(300.0) / f - 1.0, e1200 = r.f_at(1200.0) / f - 1.0;
            double worst = 0.0;
            for (std::size_t i = 0; i < r.f_hat_hz.size(); ++i) {
                if (r.confident[i] != 0) {
                    worst = std::max(worst, r.f_hat_hz[i] / f);
                }
            }
            std::printf("  yaw f=%.3f seed %u: f^(300) %+.4f f^(1200) %+.4f, max confident f^/f %.4f, resets %d\n", f,
                        seed, e300, e1200, worst, r.resets);
            EXPECT_LE(std::fabs(e300), 0.05);
            EXPECT_LE(std::fabs(e1200), 0.10);
            EXPECT_LE(worst, 1.1);
        }
    }
}

int main()
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(fest_table), cmocka_unit_test(r3_a35_pitch),
                                       cmocka_unit_test(r5_coupling), cmocka_unit_test(r4_quiescence),
                                       cmocka_unit_test(r3_r5_yaw_lowest_tone)};
    return cmocka_run_group_tests_name("pd_fest_ref_host", tests, nullptr, nullptr);
}
