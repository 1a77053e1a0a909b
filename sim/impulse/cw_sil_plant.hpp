// CwSilPlant — the rendezvous plant (spec 50 §2) behind the generic sim::Plant interface of the
// SIL nodes: sim::CwPlant (closed-form CW, six thrusters, navigation sensor) plus the channel
// maps of the lock-step protocol.
//
// Sensor frame, 7 channels:  0..2 nav position x, y, z [1 mm]; 3..5 nav velocity [10 um/s];
//                            6 step index of the nav sample. All 7 marked invalid (published as
//                            STATUS_STALE) when the sample is not valid (dropout, range).
// Actuator command, 13 channels: 0..5 on_start_cnt, 6..11 on_len_cnt [1 us, within the step],
//                            12 on_mask (bit j = thruster j: +x, -x, +y, -y, +z, -z).
// Truth (sim_truth_t): state[0..5] = (x, x', y, y', z, z') [m, m/s] in the spec frame,
//                            state[6..11] = delta-v delivered per thruster [m/s],
//                            state[12] = interlock violations, state[13] = short burns;
//                            extra = {omega [rad/s], a_nom [m/s^2], eps_c}.
#ifndef SIM_IMPULSE_CW_SIL_PLANT_HPP
#define SIM_IMPULSE_CW_SIL_PLANT_HPP

#include <memory>

#include "impulse/cw_plant.hpp"
#include "plant/plant.hpp"

namespace sim {

constexpr std::uint32_t kCwSensorChannels = 7u;
constexpr std::uint32_t kCwActChannels = 13u;

struct CwSetup;

// Scenario (mission: rendezvous) -> CwPlant configuration.
CwConfig cw_config(const Scenario &scn);

class CwSilPlant final : public Plant {
public:
    explicit CwSilPlant(const Scenario &scn);
    void reset(const Scenario &scn) override;
    SensorFrame sense() override;
    void apply(const ActuatorCmd &cmd) override;
    RunState propagate() override;
    RunState check() const override;
    std::uint32_t seq() const override { return static_cast<std::uint32_t>(cw_->steps()); }
    std::int64_t utime_us() const override;
    std::vector<double> truth() const override;
    std::vector<std::string> truth_names() const override;
    const std::vector<TruthEvent> &events() const override { return events_; }
    std::string diverged_reason() const override { return reason_; }
    void truth_message(std::array<double, 16> &state, std::array<double, 8> &extra) const override;

    const CwPlant &cw() const { return *cw_; }

private:
    Scenario scn_;
    const CwSetup &setup() const;   // the scenario's RENDEZVOUS plant set-up
    std::unique_ptr<CwPlant> cw_;
    std::uint8_t mask_ = 0u;                 // the command held (zero before the first one)
    std::array<std::uint32_t, 6> start_{}, len_{};
    std::vector<TruthEvent> events_;
    mutable std::string reason_;         // set by check(), which is logically const
};

}  // namespace sim

#endif
