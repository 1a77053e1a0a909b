#include "observer/gyro.hpp"

#include <cmath>

namespace sim {

// Stream ids for Rng: the bias draw and the white noise never share samples.
constexpr std::uint64_t kStreamGyroBias = 1u;
constexpr std::uint64_t kStreamGyroNoise = 2u;

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
