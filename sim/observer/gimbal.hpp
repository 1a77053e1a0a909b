// Gimbal-rate actuators (spec 10 §2.4): int32 counts, LSB 2^-20 rad/s, hardware clip 0.35 rad/s
// per axis (each clip is a truth event), applied over [t_k, t_k + h) with no latency.
#ifndef SIM_OBSERVER_GIMBAL_HPP
#define SIM_OBSERVER_GIMBAL_HPP

#include <array>
#include <cstdint>
#include <vector>

#include "observer/observer_section.hpp"
#include "plant/plant.hpp"

namespace sim {

class GimbalActuators {
public:
    explicit GimbalActuators(const GimbalConfig &cfg = GimbalConfig()) : cfg_(cfg) {}
    void reset(const GimbalConfig &cfg) { cfg_ = cfg; }
    // Counts -> applied rate (rad/s), clipped per axis; clips are appended to events.
    // Counts are integers, so this direction needs no NaN check: cnt * 2^-n is exact.
    std::array<double, 2> apply(const std::array<std::int32_t, 2> &cnt, std::uint32_t seq, std::int64_t utime_us,
                                std::vector<TruthEvent> *events) const;
    // Helper for drivers and tests that start from SI rates: rad/s -> counts, with the NaN/Inf and
    // int32-range checks before conversion (status as counts_from_si, full scale INT32_MAX).
    std::int32_t counts(double rate_radps, std::uint8_t *status) const;
    const GimbalConfig &config() const { return cfg_; }

private:
    GimbalConfig cfg_;
};

}  // namespace sim

#endif
