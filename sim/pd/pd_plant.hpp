// PdPlant — the HOLD plant behind the generic sim::Plant interface of the SIL nodes:
// a rigid body about one axis, J omega' = tau + tau_dist, with the command held over the period
// (zero-order hold, propagated exactly: omega_{k+1} = omega_k + h (tau + tau_dist) / J).
//
// Sensor frame, 1 channel:   0 rate gyro [2^-20 rad/s] (noise, bias, full-scale clip with SAT).
// Actuator command, 1 channel: 0 torque [2^-16 N m], clipped to the hardware limit (ACT_CLIP).
// Truth (sim_truth_t): state[0] = omega [rad/s], state[1] = applied torque [N m];
//                      extra = {J [kg m^2], tau_dist [N m]}.
#ifndef SIM_PD_PLANT_HPP
#define SIM_PD_PLANT_HPP

#include "pd/pd_section.hpp"
#include "plant/plant.hpp"
#include "sensors/rng.hpp"

namespace sim {

class PdPlant final : public Plant {
public:
    explicit PdPlant(const Scenario &scn);
    void reset(const Scenario &scn) override;
    SensorFrame sense() override;
    void apply(const ActuatorCmd &cmd) override;
    RunState propagate() override;
    RunState check() const override;
    std::uint32_t seq() const override { return k_; }
    std::int64_t utime_us() const override;
    std::vector<double> truth() const override { return {w_, tau_}; }
    std::vector<std::string> truth_names() const override { return {"omega_BN_B_x_radps", "tau_B_x_nm"}; }
    const std::vector<TruthEvent> &events() const override { return events_; }
    std::string diverged_reason() const override { return reason_; }
    void truth_message(std::array<double, 16> &state, std::array<double, 8> &extra) const override;

    double omega() const { return w_; }

private:
    PdSetup b_;
    std::uint32_t period_us_ = 0u;
    std::uint32_t k_ = 0u;
    double w_ = 0.0, tau_ = 0.0;
    Rng noise_;
    std::vector<TruthEvent> events_;
    mutable std::string reason_;   // set by check(), which is logically const
};

}  // namespace sim

#endif
