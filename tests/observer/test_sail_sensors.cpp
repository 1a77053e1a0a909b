// Sensor model checks (spec 10 §2.4): quantisation, saturation and the SAT bit, conversions that
// never cast NaN/Inf/out-of-range doubles, noise statistics with derived bounds, and the
// library-independent RNG.
#include <algorithm>
#include <cstring>
#include <limits>
#include <vector>

#include "observer/gyro.hpp"
#include "observer/sail_plant.hpp"
#include "sensors/rng.hpp"
#include "sim_test.hpp"

namespace {
constexpr double kLsb = 1.0 / 1048576.0;  // 2^-20 rad/s
constexpr std::int32_t kMax = 1048575;    // 2^20 - 1
}  // namespace

SIM_TEST(test_quantisation_and_saturation)
{
    struct Case {
        double v_lsb;  // input in LSB
        std::int32_t cnt;
        std::uint8_t st;
    };
    const Case cases[] = {
        {0.0, 0, 0},        {0.49, 0, 0},         {0.5, 1, 0},          {-0.5, -1, 0},  // ties away from 0
        {1.5, 2, 0},        {-2.51, -3, 0},       {12345.4, 12345, 0},  {kMax - 1.0, kMax - 1, 0},
        {kMax - 0.4, kMax, sim::kStatusSat},      {kMax, kMax, sim::kStatusSat},
        {1048576.0, kMax, sim::kStatusSat},       {-1048576.0, -kMax, sim::kStatusSat},
        {1e300, kMax, sim::kStatusSat},           {-1e300, -kMax, sim::kStatusSat},
    };
    for (const Case &c : cases) {
        std::uint8_t st = 0xFFu;
        const std::int32_t n = sim::counts_from_si(c.v_lsb * kLsb, kLsb, kMax, &st);
        EXPECT_EQ_INT(n, c.cnt);
        EXPECT_EQ_INT(st, c.st);
    }
    // Non-finite input: never converted (UB), count 0 with SAT | NONFINITE.
    for (double v : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                     -std::numeric_limits<double>::infinity()}) {
        std::uint8_t st = 0u;
        EXPECT_EQ_INT(sim::counts_from_si(v, kLsb, kMax, &st), 0);
        EXPECT_EQ_INT(st, sim::kStatusSat | sim::kStatusNonFinite);
    }
    // Through RateGyro: 1 rad/s is beyond full scale (2^20 LSB > 2^20 - 1).
    sim::RateGyro g;
    std::array<std::int32_t, 2> cnt{};
    std::array<std::uint8_t, 2> st{};
    g.sample({1.0, -0.5}, &cnt, &st);
    EXPECT_EQ_INT(cnt[0], kMax);
    EXPECT_EQ_INT(st[0], sim::kStatusSat);
    EXPECT_EQ_INT(cnt[1], -524288);
    EXPECT_EQ_INT(st[1], 0);
}

// The plant samples truth at t_k: w0 = 1 deg/s = 0.0174533 rad/s = 18300.9 LSB -> 18301 counts.
SIM_TEST(test_gyro_in_plant)
{
    sim::SailPlant p(sim::sail_default_scenario());
    const sim::SensorFrame f = p.sense();
    EXPECT_EQ_INT(f.n_ch, 2);
    EXPECT_EQ_INT(f.cnt[0], 18301);
    EXPECT_EQ_INT(f.cnt[1], 18301);
    EXPECT_EQ_INT(f.status[0], 0);
    EXPECT_EQ_INT(f.status[1], 0);
}

// Noise statistics. Each output is (w + b + sigma*n)/LSB rounded; with sigma = 1e-5 = 10.5 LSB the
// rounding error is uniform and independent of the noise to within exp(-2 pi^2 (sigma/LSB)^2), so
// the sample error has mean b and variance s2 = sigma^2 + LSB^2/12. For N samples:
//   |mean - b| <= 5 sqrt(s2 / N)                (5 sigma of the sample mean)
//   |std / sqrt(s2) - 1| <= 5 / sqrt(2 N)       (5 sigma of the sample std, Gaussian)
//   |corr(y, z)|, |lag-1 autocorr| <= 5 / sqrt(N)
// The seed is fixed, so the test is deterministic; the bounds say the model is right, not lucky.
SIM_TEST(test_noise_statistics)
{
    sim::GyroConfig cfg;
    cfg.noise_radps = 1e-5;
    cfg.bias_radps = {2e-6, -3e-6};
    cfg.seed = 12345u;
    sim::RateGyro g(cfg);
    const std::array<double, 2> w = {0.01, -0.02};
    const int n = 200000;
    double sum[2] = {0, 0}, sum2[2] = {0, 0}, sxy = 0.0, lag = 0.0, prev = 0.0;
    std::vector<double> ey(static_cast<std::size_t>(n));
    for (int k = 0; k < n; ++k) {
        std::array<std::int32_t, 2> cnt{};
        std::array<std::uint8_t, 2> st{};
        g.sample(w, &cnt, &st);
        double e[2];
        for (int i = 0; i < 2; ++i) {
            e[i] = static_cast<double>(cnt[static_cast<std::size_t>(i)]) * kLsb - w[static_cast<std::size_t>(i)];
            sum[i] += e[i];
            sum2[i] += e[i] * e[i];
        }
        ey[static_cast<std::size_t>(k)] = e[0];
        sxy += (e[0] - cfg.bias_radps[0]) * (e[1] - cfg.bias_radps[1]);
        if (k > 0) {
            lag += (e[0] - cfg.bias_radps[0]) * (prev - cfg.bias_radps[0]);
        }
        prev = e[0];
    }
    const double nd = static_cast<double>(n);
    const double s2 = cfg.noise_radps * cfg.noise_radps + kLsb * kLsb / 12.0;
    for (int i = 0; i < 2; ++i) {
        const double mean = sum[i] / nd;
        const double var = sum2[i] / nd - mean * mean;
        const double ratio = std::sqrt(var / s2);
        std::printf("  axis %d: mean %.4e (bias %.1e, bound %.2e), std/expected %.5f (bound %.4f)\n", i, mean,
                    cfg.bias_radps[static_cast<std::size_t>(i)], 5.0 * std::sqrt(s2 / nd), ratio,
                    5.0 / std::sqrt(2.0 * nd));
        EXPECT_NEAR(mean, cfg.bias_radps[static_cast<std::size_t>(i)], 5.0 * std::sqrt(s2 / nd));
        EXPECT_NEAR(ratio, 1.0, 5.0 / std::sqrt(2.0 * nd));
    }
    const double corr = sxy / nd / s2;
    const double ac1 = lag / (nd - 1.0) / s2;
    std::printf("  corr(y, z) %.2e, lag-1 autocorr %.2e (bound %.2e)\n", corr, ac1, 5.0 / std::sqrt(nd));
    EXPECT_LE(std::fabs(corr), 5.0 / std::sqrt(nd));
    EXPECT_LE(std::fabs(ac1), 5.0 / std::sqrt(nd));
}

// Standard normal from the polar method: mean, variance, P(|z| < 1) and P(|z| < 2), each within
// 5 sigma of its sampling distribution; det_log within 2 ulp-scale of std::log.
SIM_TEST(test_gaussian_and_log)
{
    sim::Rng r(7u);
    const int n = 400000;
    double s = 0, s2 = 0, in1 = 0, in2 = 0;
    for (int k = 0; k < n; ++k) {
        const double z = r.gaussian();
        s += z;
        s2 += z * z;
        in1 += std::fabs(z) < 1.0 ? 1.0 : 0.0;
        in2 += std::fabs(z) < 2.0 ? 1.0 : 0.0;
    }
    const double nd = static_cast<double>(n);
    const double p1 = 0.682689492137086, p2 = 0.954499736103642;
    std::printf("  mean %.2e var %.5f P1 %.5f P2 %.5f\n", s / nd, s2 / nd, in1 / nd, in2 / nd);
    EXPECT_NEAR(s / nd, 0.0, 5.0 / std::sqrt(nd));
    EXPECT_NEAR(s2 / nd, 1.0, 5.0 * std::sqrt(2.0 / nd));  // Var(z^2) = 2
    EXPECT_NEAR(in1 / nd, p1, 5.0 * std::sqrt(p1 * (1.0 - p1) / nd));
    EXPECT_NEAR(in2 / nd, p2, 5.0 * std::sqrt(p2 * (1.0 - p2) / nd));
    double worst = 0.0;
    sim::Rng u(9u);
    for (int k = 0; k < 100000; ++k) {
        const double x = std::ldexp(u.uniform() + 0.5, static_cast<int>(u.next_u64() % 200u) - 100);
        const double ref = std::log(x);
        const double d = std::fabs(sim::det_log(x) - ref);
        worst = std::max(worst, d / std::max(std::fabs(ref), 1e-300));
    }
    std::printf("  det_log worst relative error %.2e\n", worst);
    EXPECT_LE(worst, 1e-15);
    EXPECT_TRUE(std::isnan(sim::det_log(0.0)));
    EXPECT_TRUE(std::isnan(sim::det_log(-1.0)));
    EXPECT_NEAR(sim::det_log(1.0), 0.0, 0.0);
}

// Pinned stream values: a port or a library change that alters the noise shows up here first.
SIM_TEST(test_rng_pinned)
{
    sim::Rng r(0u);
    const std::uint64_t a = r.next_u64();
    const std::uint64_t b = r.next_u64();
    sim::Rng q(1u, 2u);
    const double z = q.gaussian();
    std::uint64_t zb = 0u;
    std::memcpy(&zb, &z, sizeof zb);
    std::printf("  pinned: 0x%016llx 0x%016llx z 0x%016llx (%.17g)\n", static_cast<unsigned long long>(a),
                static_cast<unsigned long long>(b), static_cast<unsigned long long>(zb), z);
    EXPECT_TRUE(a == UINT64_C(0xfb5405f7bd79c540));
    EXPECT_TRUE(b == UINT64_C(0x780c98e26cea5883));
    EXPECT_TRUE(zb == UINT64_C(0xbfe43639aa7e46a1));
}

// The constant bias: fixed part plus a seeded draw (separate stream from the white noise).
SIM_TEST(test_bias_draw)
{
    sim::GyroConfig cfg;
    cfg.bias_radps = {1e-4, -1e-4};
    cfg.bias_sigma_radps = 1e-5;
    cfg.seed = 3u;
    const sim::RateGyro g1(cfg), g2(cfg);
    cfg.seed = 4u;
    const sim::RateGyro g3(cfg);
    EXPECT_TRUE(g1.bias_radps() == g2.bias_radps());
    EXPECT_TRUE(g1.bias_radps() != g3.bias_radps());
    EXPECT_NEAR(g1.bias_radps()[0], 1e-4, 6e-5);  // 6 sigma
    // Turning white noise on does not change the drawn bias.
    cfg.seed = 3u;
    cfg.noise_radps = 1e-5;
    const sim::RateGyro g4(cfg);
    EXPECT_TRUE(g4.bias_radps() == g1.bias_radps());
    // Without noise the bias shows as a constant count offset: 1e-4 rad/s = 104.9 LSB.
    sim::GyroConfig c0;
    c0.bias_radps = {1e-4, 0.0};
    sim::RateGyro g0(c0);
    std::array<std::int32_t, 2> cnt{};
    std::array<std::uint8_t, 2> st{};
    g0.sample({0.0, 0.0}, &cnt, &st);
    EXPECT_EQ_INT(cnt[0], 105);
    EXPECT_EQ_INT(cnt[1], 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_quantisation_and_saturation),
        cmocka_unit_test(test_gyro_in_plant),
        cmocka_unit_test(test_noise_statistics),
        cmocka_unit_test(test_gaussian_and_log),
        cmocka_unit_test(test_rng_pinned),
        cmocka_unit_test(test_bias_draw),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
