// CW plant (sim/impulse/cw_plant): closed forms, thrusters, minimum on-time, faults, and the
// relative-navigation sensor (spec 50 §2, §9 frame pitfall). No LCM: the plant is driven
// directly. The closed loops with the module are in test_imp_loop.cpp.
#include "impulse/cw_plant.hpp"

#include <cmath>
#include <cstdio>

extern "C" {
#include "ut.h"
}

namespace {

using Vec6 = sim::CwPlant::Vec6;

Vec6 rk4_rhs(const Vec6 &x, double w, const Eigen::Vector3d &u)
{
    Vec6 d;
    d << x(1), 2 * w * x(3) + u(0), x(3), -2 * w * x(1) + 3 * w * w * x(2) + u(1), x(5), -w * w * x(4) + u(2);
    return d;
}

// §9: a chaser 1 km below the target (y0 = +1000 m, y towards the Earth) at rest drifts to +x.
UT_TEST(frame_lower_orbit_drifts_forward)
{
    sim::CwConfig cfg;
    Vec6 x0 = Vec6::Zero();
    x0(2) = 1000.0;
    sim::CwPlant pl(cfg, x0);
    for (int k = 0; k < 1000; ++k) { pl.step_mask(0u); }
    UT_CHECK(pl.x()(0) > 0.0);
    UT_CHECK(pl.x()(1) > 0.0);
    std::printf("frame: y0 = +1000 m at rest -> x(100 s) = %+.3f m, x' = %+.5f m/s\n", pl.x()(0), pl.x()(1));
}

// Closed form with sub-step windows against an RK4 integration (h = 1 ms) of the same firing.
UT_TEST(closed_form_matches_rk4)
{
    sim::CwConfig cfg;
    cfg.eps_c = 0.02;
    Vec6 x0;
    x0 << 5000, -1, 4000, -1, 4000, -1;
    sim::CwPlant pl(cfg, x0);
    Vec6 x = x0;
    const double w = cfg.w, a = cfg.a_nom * 1.02;
    for (int k = 0; k < 2000; ++k) {
        // +x on [20 ms, 70 ms) of every step, -y full steps for k < 500, +z on even steps
        std::array<std::uint32_t, 6> st{}, len{};
        std::uint8_t mask = 0x01u;
        st[0] = 20000;
        len[0] = 50000;
        if (k < 500) { mask |= 0x08u; len[3] = 100000; }
        if (k % 2 == 0) { mask |= 0x10u; len[4] = 100000; }
        pl.step(mask, st, len);
        for (int i = 0; i < 100; ++i) {
            const double ts = i * 1e-3 + 0.5e-3;
            Eigen::Vector3d u(ts >= 0.02 && ts < 0.07 ? a : 0.0, k < 500 ? -a : 0.0, k % 2 == 0 ? a : 0.0);
            const double h = 1e-3;
            const Vec6 k1 = rk4_rhs(x, w, u), k2 = rk4_rhs(x + 0.5 * h * k1, w, u), k3 = rk4_rhs(x + 0.5 * h * k2, w, u),
                       k4 = rk4_rhs(x + h * k3, w, u);
            x += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
        }
    }
    const double e = (pl.x() - x).cwiseAbs().maxCoeff();
    UT_CHECK(e <= 1e-6);
    UT_CHECK_EQ(pl.violations(), 0u);
    std::printf("closed form vs RK4 over 200 s with sub-step windows: %.3g\n", e);
}

UT_TEST(min_on_time_and_faults)
{
    sim::CwConfig cfg;
    sim::CwPlant a(cfg, Vec6::Zero());
    std::array<std::uint32_t, 6> st{}, len{};
    len[0] = 10000;   // 10 ms < t_min: dropped
    a.step(0x01u, st, len);
    UT_CHECK(a.dv_used()[0] <= 0.0);
    cfg.stretch = true;
    sim::CwPlant b(cfg, Vec6::Zero());
    b.step(0x01u, st, len);
    UT_CHECK(std::abs(b.dv_used()[0] - 0.04 * 0.02) <= 1e-12);
    len[0] = 100000;
    len[1] = 100000;
    b.step(0x03u, st, len);   // both x thrusters: violation logged
    UT_CHECK_EQ(b.violations(), 1u);
    cfg.stuck_on_j = 5;
    cfg.stuck_on_t = 0.0;
    sim::CwPlant c(cfg, Vec6::Zero());
    c.step_mask(0u);
    UT_CHECK(std::abs(c.dv_used()[5] - 0.004) <= 1e-12);
}

// Minimum on-time applies to whole burns: a window that continues a burn across the step
// boundary is never dropped, a short burn inside one step is (default) or stretched.
UT_TEST(min_on_time_applies_to_whole_burns)
{
    sim::CwConfig cfg;
    sim::CwPlant a(cfg, Vec6::Zero());
    std::array<std::uint32_t, 6> st{}, len{};
    st[2] = 95000;   // +y: last 5 ms of the step, continued by the first 10 ms of the next
    len[2] = 5000;
    a.step(0x04u, st, len);
    st[2] = 0;
    len[2] = 10000;
    a.step(0x04u, st, len);
    // 15 ms in total: executed (the burn was open at the step end), but shorter than t_min
    UT_CHECK(std::abs(a.dv_used()[2] - 0.04 * 0.015) <= 1e-12);
    UT_CHECK_EQ(a.short_burns(), 1u);
    // a burn of 30 ms split 10 + 20 across a boundary: executed, not short
    sim::CwPlant b(cfg, Vec6::Zero());
    st[2] = 90000;
    len[2] = 10000;
    b.step(0x04u, st, len);
    st[2] = 0;
    len[2] = 20000;
    b.step(0x04u, st, len);
    UT_CHECK(std::abs(b.dv_used()[2] - 0.04 * 0.03) <= 1e-12);
    UT_CHECK_EQ(b.short_burns(), 0u);
}

// A stuck valve is not a flight-code violation; two commanded windows on one axis are.
UT_TEST(violations_count_commanded_windows_only)
{
    sim::CwConfig cfg;
    cfg.stuck_on_j = 1;   // -x stuck on from t = 0
    cfg.stuck_on_t = 0.0;
    sim::CwPlant a(cfg, Vec6::Zero());
    a.step_mask(0x01u);   // +x commanded while -x is stuck on
    UT_CHECK_EQ(a.violations(), 0u);
    UT_CHECK(std::abs(a.dv_used()[1] - 0.004) <= 1e-12);
    std::array<std::uint32_t, 6> st{}, len{};
    len[0] = 30000;
    st[1] = 50000;
    len[1] = 30000;   // disjoint in time, but both in one step: a violation (spec 50 §5.2)
    a.step(0x03u, st, len);
    UT_CHECK_EQ(a.violations(), 1u);
}

// Navigation sensor (spec 50 §2.5): rate, step tag, hold, quantisation.
UT_TEST(nav_sampling_rate_tag_and_quantisation)
{
    sim::CwConfig cfg;
    Vec6 x0;
    x0 << 1234.5674, 0.123456, -1000.0005, -0.000015, 0.0, 2.0;
    sim::CwPlant pl(cfg, x0);
    UT_CHECK(pl.nav().valid);
    UT_CHECK_EQ(pl.nav().step, 0u);
    UT_CHECK_EQ(pl.nav().pos_mm[0], 1234567);     // 1234.5674 m -> 1234567 mm
    UT_CHECK_EQ(pl.nav().pos_mm[1], -1000001);    // -1000.0005 -> half away from zero
    UT_CHECK_EQ(pl.nav().vel_cnt[0], 12346);      // 0.123456 m/s in 10 um/s
    UT_CHECK_EQ(pl.nav().vel_cnt[1], -2);         // -0.000015 -> -1.5 counts -> -2
    for (int k = 1; k < 25; ++k) {
        pl.step_mask(0u);
        const std::uint32_t expect = static_cast<std::uint32_t>(k / 10 * 10);   // 1 Hz at 0.1 s
        UT_CHECK_EQ(pl.nav().step, expect);
    }
    std::array<std::int32_t, 3> p{}, v{};
    pl.nav_counts(p, v);
    UT_CHECK(p[0] != pl.nav().pos_mm[0]);          // held sample is 2.4 s old (moving target)
}

// Noise statistics of the nominal profile: sigma_p = 0.1 m, sigma_v = 1 mm/s. With 3 x 3000
// samples the sample standard deviation is within 3 % of sigma at > 4 sigma (its relative
// standard error is 1/sqrt(2 n) = 0.75 %); the mean is within 4 sigma / sqrt(n).
UT_TEST(nav_nominal_noise_statistics)
{
    sim::CwConfig cfg;
    cfg.nav.profile = sim::NavProfile::Nominal;
    cfg.nav.f_nav = 10.0;   // every step
    cfg.nav.seed = 7;
    sim::CwPlant pl(cfg, Vec6::Zero());
    double sp = 0, sv = 0, mp = 0, mv = 0;
    const int n = 3000;
    for (int k = 0; k < n; ++k) {
        for (int r = 0; r < 3; ++r) {
            const double ep = pl.nav().pos_mm[static_cast<size_t>(r)] * 1e-3, ev = pl.nav().vel_cnt[static_cast<size_t>(r)] * 1e-5;
            mp += ep;
            mv += ev;
            sp += ep * ep;
            sv += ev * ev;
        }
        pl.step_mask(0u);
    }
    const double m = 3.0 * n;
    std::printf("nominal nav: sigma_p %.4f m, sigma_v %.6f m/s, mean %.2e m, %.2e m/s\n", std::sqrt(sp / m),
                std::sqrt(sv / m), mp / m, mv / m);
    UT_CHECK(std::abs(std::sqrt(sp / m) - 0.1) <= 0.003);
    UT_CHECK(std::abs(std::sqrt(sv / m) - 1e-3) <= 3e-5);
    UT_CHECK(std::abs(mp / m) <= 4 * 0.1 / std::sqrt(m));
    UT_CHECK(std::abs(mv / m) <= 4 * 1e-3 / std::sqrt(m));
}

// Bias, range limit, scripted and random dropouts, outliers, determinism.
UT_TEST(nav_bias_range_dropouts_outliers_seeded)
{
    sim::CwConfig cfg;
    cfg.nav.bias_p = {{0.5, -0.25, 0.0}};
    cfg.nav.bias_v = {{0.0, 0.001, 0.0}};
    cfg.nav.dropouts = {{2.0, 4.0}};
    cfg.nav.outliers = {{5.0, {100.0, 1.0}}};
    Vec6 x0 = Vec6::Zero();
    sim::CwPlant pl(cfg, x0);
    UT_CHECK_EQ(pl.nav().pos_mm[0], 500);
    UT_CHECK_EQ(pl.nav().pos_mm[1], -250);
    UT_CHECK_EQ(pl.nav().vel_cnt[1], 100);
    int invalid = 0;
    bool outlier = false;
    for (int k = 1; k <= 80; ++k) {
        pl.step_mask(0u);
        if (k % 10 == 0) {
            const double t = k * 0.1;
            const bool in_gap = t >= 2.0 - 1e-9 && t < 4.0 - 1e-9;
            UT_CHECK(pl.nav().valid == !in_gap);
            invalid += pl.nav().valid ? 0 : 1;
            if (k == 50) { outlier = pl.nav().pos_mm[2] == 100000 && pl.nav().vel_cnt[2] == 100000; }
            if (k == 60) { UT_CHECK(std::abs(pl.nav().pos_mm[2]) < 10); }   // one sample only
        }
    }
    UT_CHECK_EQ(invalid, 2);
    UT_CHECK(outlier);
    // range limit: beyond it every sample is invalid
    sim::CwConfig rc;
    rc.nav.range_max = 100.0;
    x0(0) = 150.0;
    UT_CHECK(!sim::CwPlant(rc, x0).nav().valid);
    x0(0) = 50.0;
    UT_CHECK(sim::CwPlant(rc, x0).nav().valid);
    // random dropouts: fraction p = 0.3 over 2000 samples within 4 sigma (sigma = 1.0 %)
    sim::CwConfig dc;
    dc.nav.p_drop = 0.3;
    dc.nav.f_nav = 10.0;
    dc.nav.seed = 11;
    dc.nav.profile = sim::NavProfile::Degraded;
    sim::CwPlant a(dc, Vec6::Zero()), b(dc, Vec6::Zero());
    dc.nav.seed = 12;
    sim::CwPlant c(dc, Vec6::Zero());
    int drops = 0;
    bool same = true, differ = false;
    for (int k = 0; k < 2000; ++k) {
        drops += a.nav().valid ? 0 : 1;
        same = same && a.nav().pos_mm == b.nav().pos_mm && a.nav().valid == b.nav().valid;
        differ = differ || a.nav().pos_mm != c.nav().pos_mm;
        a.step_mask(0u);
        b.step_mask(0u);
        c.step_mask(0u);
    }
    std::printf("random dropouts: %d of 2000 (p = 0.3)\n", drops);
    UT_CHECK(std::abs(drops / 2000.0 - 0.3) <= 0.041);
    UT_CHECK(same);
    UT_CHECK(differ);
}
}  // namespace

int main(void)
{
    UT_CASES(cases) = {UT_CASE(frame_lower_orbit_drifts_forward), UT_CASE(closed_form_matches_rk4),
                       UT_CASE(min_on_time_and_faults), UT_CASE(min_on_time_applies_to_whole_burns),
                       UT_CASE(violations_count_commanded_windows_only),
                       UT_CASE(nav_sampling_rate_tag_and_quantisation), UT_CASE(nav_nominal_noise_statistics),
                       UT_CASE(nav_bias_range_dropouts_outliers_seeded)};
    return UT_RUN("imp_cw", cases);
}
