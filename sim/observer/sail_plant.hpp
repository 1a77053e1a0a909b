// Solar-sail platform plant (spec 10 §2.4): exact ZOH (or the RK4 cross-check), gimbal angles
// for truth, rate gyros and gimbal-rate actuators in counts, and the validity check.
#ifndef SIM_OBSERVER_SAIL_PLANT_HPP
#define SIM_OBSERVER_SAIL_PLANT_HPP

#include "observer/gimbal.hpp"
#include "observer/gyro.hpp"
#include "observer/observer_section.hpp"
#include "observer/sail_model.hpp"
#include "plant/plant.hpp"

namespace sim {

class SailPlant final : public Plant {
public:
    explicit SailPlant(const Scenario &scn);

    void reset(const Scenario &scn) override;
    SensorFrame sense() override;
    void apply(const ActuatorCmd &cmd) override;
    RunState propagate() override;
    RunState check() const override;
    std::uint32_t seq() const override { return seq_; }
    std::int64_t utime_us() const override;
    // [w_y_radps, w_z_radps, mu_y_rad, mudot_y_radps, mu_z_rad, mudot_z_radps, beta_y_rad,
    //  beta_z_rad, bdot_y_radps, bdot_z_radps] (the last two: rate applied over the last period)
    std::vector<double> truth() const override;
    std::vector<std::string> truth_names() const override;
    // state[0..7] = truth()[0..7] (w, mu, mudot, beta); extra = {k^2 true, bdot_y, bdot_z
    // applied, sigma, J factor}.
    void truth_message(std::array<double, 16> &state, std::array<double, 8> &extra) const override;
    const std::vector<TruthEvent> &events() const override { return events_; }
    std::string diverged_reason() const override { return diverged_reason_; }

    // Typed access for tests, the reference and the driver.
    const Scenario &scenario() const { return scn_; }
    const SailScenario &sail() const { return sail_; }
    const SailParams &params() const { return par_; }
    const SailZoh &zoh() const { return zoh_; }
    const Vec6 &x() const { return x_; }
    const Vec2 &beta_rad() const { return beta_rad_; }
    const Vec2 &bdot_applied_radps() const { return bdot_applied_radps_; }
    std::uint32_t ode_substeps() const { return ode_substeps_; }
    // Overwrite the state (tests). Does not touch the clock or the held command.
    void set_state(const Vec6 &x, const Vec2 &beta_rad);
    // Advance one period with an SI rate held over it, bypassing counts and the hardware clip
    // (tests and the double reference). Same propagator and check as propagate().
    RunState advance_radps(const Vec2 &u_radps);

private:
    void step_zoh(const Vec2 &u_radps);
    void step_ode(const Vec2 &u_radps);

    Scenario scn_;
    SailScenario sail_;    // the scenario's DETUMBLE part
    SailParams par_;
    SailZoh zoh_;
    RateGyro gyro_;
    GimbalActuators gimbal_;
    Vec6 x_ = Vec6::Zero();
    Vec2 beta_rad_ = Vec2::Zero();
    Vec2 bdot_applied_radps_ = Vec2::Zero();
    std::array<std::int32_t, 2> held_cnt_{};
    std::uint32_t held_seq_ = 0u;
    std::uint32_t seq_ = 0u;
    std::uint32_t ode_substeps_ = 1u;
    RunState state_ = RunState::Running;
    mutable std::string diverged_reason_;  // set by check(), which is logically const
    std::vector<TruthEvent> events_;
};

// Spectral radius of A_s (the fastest mode, ~51 rad/s); sets the automatic RK4 substep count.
double sail_max_abs_eig(const SailParams &p);

}  // namespace sim

#endif
