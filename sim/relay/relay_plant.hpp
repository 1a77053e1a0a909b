// RelayPlant — the RELAY plant behind the generic sim::Plant interface (spec 20 §2): a rigid axis
// and up to four undamped modes, propagated in closed form by the lock-step driver (driver 3 of
// §2.2): every frame is computed from the anchor state at the last actuator change with elapsed
// time = (integer ticks) h, never from accumulated float time or chained steps.
//
// Sensor frame, 1 channel:     0 angle x = xbar + sum x~_i [2^-24 rad], noise and bias, +-2^23 (SAT).
// Actuator command, 1 channel: 0 level code RLY_LVL_*; an unknown code applies 0 and is an event
//                              (ACT_UNKNOWN); a missed command holds the last level (the SIL core).
// Truth: x, xbar, xbar', x~_i, x~_i'/omega_i (i < 4), applied level and moment.
#ifndef SIM_RLY_PLANT_HPP
#define SIM_RLY_PLANT_HPP

#include "plant/plant.hpp"
#include "relay/relay_section.hpp"
#include "sensors/rng.hpp"

namespace sim {

class RelayPlant final : public Plant {
public:
    explicit RelayPlant(const Scenario &scn);
    void reset(const Scenario &scn) override;
    SensorFrame sense() override;
    void apply(const ActuatorCmd &cmd) override;
    RunState propagate() override;
    RunState check() const override;
    std::uint32_t seq() const override { return k_; }
    std::int64_t utime_us() const override;
    std::vector<double> truth() const override;
    std::vector<std::string> truth_names() const override;
    const std::vector<TruthEvent> &events() const override { return events_; }
    std::string diverged_reason() const override { return reason_; }
    void truth_message(std::array<double, 16> &state, std::array<double, 8> &extra) const override;

    const ref::RelayState &state() const { return now_; }
    int level() const { return level_; }

private:
    void set_level(int level);

    RelaySetup b_;
    ref::RelayModel applied_;          // the model with the actuator's scale error
    std::uint32_t period_us_ = 0u;
    double h_s_ = 0.0;
    std::uint32_t k_ = 0u;
    ref::RelayState anchor_;           // state at the last level change
    std::uint64_t ticks_ = 0u;         // ticks since the anchor
    ref::RelayState now_;
    int level_ = 0;                    // applied level (-2..2)
    int pending_ = 0;                  // delay_ticks = 1: the level applied next tick
    Rng noise_;
    std::vector<TruthEvent> events_;
    mutable std::string reason_;       // set by check(), which is logically const
};

// Level code RLY_LVL_* -> signed level (-2 FULL_NEG .. +2 FULL_POS); false for an unknown code.
bool relay_level_of_code(std::int32_t code, int *level);

}  // namespace sim

#endif
