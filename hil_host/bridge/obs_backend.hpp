// obs_backend.hpp — in-process SIL backend around the observer (fsw/observer/obs.h).
//
// Until the executive's fsw_step() exists, the flight software in the loop is obs_step() with a
// parameter table (default OBS_TBL_50HZ_PHYS). Channel map: counts[0] = gyro y, counts[1] =
// gyro z (OBS_NY = 2); status STALE -> obs_in_t.stale bit, status SAT -> obs_in_t.sat bit;
// seq -> obs_in_t.seq modulo 2^32 (the observer's own sequencing handles gaps and repeats).
// Command: counts[0..1] = bdot_cmd_cnt, fsw_mode = 0 (no executive), fsw_health = obs health.
// Telemetry: kObsTlmLayoutVersion, little-endian via fsw_codec.h (see obs_backend.cpp).
#ifndef HIL_BRIDGE_OBS_BACKEND_HPP
#define HIL_BRIDGE_OBS_BACKEND_HPP

#include <cstdint>

#include "backend.hpp"
#include "frame_validator.hpp"

extern "C" {
#include "obs.h"
}

namespace bridge {

constexpr std::int32_t kObsTlmLayoutVersion = 0x0B50001;   // interim obs-only layout, v1

class InProcessObsBackend final : public Backend {
public:
    explicit InProcessObsBackend(const obs_params_t *params = nullptr);   // null: OBS_TBL_50HZ_PHYS
    bool reset() override;
    bool step(const Frame &f, StepOutput &out) override;
    const char *name() const override { return "sil-obs"; }

    std::uint32_t steps() const { return steps_; }
    const obs_out_t &last_out() const { return out_; }

    // Sensor-limits table derived from the parameter table: 2 channels,
    // |count| < gyro_max_cnt (the observer treats |count| >= gyro_max_cnt as invalid).
    static SensorLimits sensor_limits(const obs_params_t *params = nullptr);

private:
    const obs_params_t *p_;
    obs_state_t s_{};
    obs_out_t out_{};
    bool ok_ = false;
    std::uint32_t steps_ = 0;
};

}  // namespace bridge

#endif  // HIL_BRIDGE_OBS_BACKEND_HPP
