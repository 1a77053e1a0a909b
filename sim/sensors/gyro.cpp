#include "sensors/gyro.hpp"

#include <cmath>

namespace sim {

// Stream ids for Rng: the bias draw and the white noise never share samples.
constexpr std::uint64_t kStreamGyroBias = 1u;
constexpr std::uint64_t kStreamGyroNoise = 2u;

std::int32_t counts_from_si(double v_si, double lsb_si, std::int32_t max_cnt, std::uint8_t *status)
{
    const double q = v_si / lsb_si;
    if (!std::isfinite(q)) {
        *status = static_cast<std::uint8_t>(kStatusSat | kStatusNonFinite);
        return 0;
    }
    const double full = static_cast<double>(max_cnt);
    std::int32_t c = 0;
    if (q >= full) {
        c = max_cnt;
    } else if (q <= -full) {
        c = -max_cnt;
    } else {
        // |q| < max_cnt <= 2^31 - 1, so the rounded value fits in int32.
        c = static_cast<std::int32_t>(std::round(q));
    }
    *status = (c == max_cnt || c == -max_cnt) ? kStatusSat : std::uint8_t{0u};
    return c;
}

RateGyro::RateGyro(const GyroConfig &cfg) { reset(cfg); }

void RateGyro::reset(const GyroConfig &cfg)
{
    cfg_ = cfg;
    Rng bias_rng(cfg.seed, kStreamGyroBias);
    for (std::size_t i = 0; i < 2u; ++i) {
        // Always draw, so the drawn bias depends only on the seed and not on bias_sigma.
        const double n = bias_rng.gaussian();
        bias_radps_[i] = cfg.bias_radps[i] + cfg.bias_sigma_radps * n;
    }
    noise_rng_ = Rng(cfg.seed, kStreamGyroNoise);
}

void RateGyro::sample(const std::array<double, 2> &w_radps, std::array<std::int32_t, 2> *cnt,
                      std::array<std::uint8_t, 2> *status)
{
    const bool noisy = cfg_.noise_radps > 0.0;
    for (std::size_t i = 0; i < 2u; ++i) {
        double v = w_radps[i] + bias_radps_[i];
        if (noisy) {
            v += cfg_.noise_radps * noise_rng_.gaussian();
        }
        (*cnt)[i] = counts_from_si(v, cfg_.lsb_radps(), cfg_.max_cnt, &(*status)[i]);
    }
}

}  // namespace sim
