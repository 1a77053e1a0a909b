// Two-axis rate gyro (spec 10 §2.4): int32 counts, LSB 2^-20 rad/s, range +-(2^20 - 1),
// SAT at full scale, white noise and constant bias from a seeded RNG.
#ifndef SIM_OBSERVER_GYRO_HPP
#define SIM_OBSERVER_GYRO_HPP

#include <array>
#include <cstdint>

#include "observer/observer_section.hpp"
#include "sensors/counts.hpp"
#include "sensors/rng.hpp"

namespace sim {

class RateGyro {
public:
    explicit RateGyro(const GyroConfig &cfg = GyroConfig());
    void reset(const GyroConfig &cfg);
    // One sample of (w_y, w_z); consumes two noise draws when noise is on.
    void sample(const std::array<double, 2> &w_radps, std::array<std::int32_t, 2> *cnt,
                std::array<std::uint8_t, 2> *status);
    const std::array<double, 2> &bias_radps() const { return bias_radps_; }

private:
    GyroConfig cfg_;
    std::array<double, 2> bias_radps_{};
    Rng noise_rng_;
};

}  // namespace sim

#endif
