// PdPlant — the HOLD plant (spec 40 §2.6) behind the generic sim::Plant interface of the SIL nodes:
// three gyrodine channels (yaw, roll, pitch), each a body angle x_k, a gimbal angle beta_k and its
// elastic modes (yaw 2, roll 1, pitch 1), with the §2.4 parameters of ref::pd::Channel.
//   single (default): the three §2.2 channels, independent; each propagated by its own exact ZOH
//            (ref::pd::discretise), placed block-diagonally (ref::pd::discretise_single).
//   coupled: §2.1, the a Ib inertial cross terms between the channels, coupling sign +-1
//            (ref::pd::discretise_coupled: symmetric mass matrix, one block exponential).
// Ad, Bd are recomputed only when f_min changes (pd.f_steps, at a sample boundary; the state is
// continuous). The torque is held over [t_k, t_k + Ty) (one sample later with latency_samples: 1).
// The true plant may be scaled (pd.scale: I_i, Ix, H); the flight code does not know it.
//
// Sensor frame, always 6 channels:
//   0..2  attitude yaw / roll / pitch [2^-26 rad]: x_k + bias_k + sigma_k N(0,1) (+ an offset
//         window), rounded; +-2^25 counts (0.5 rad) saturate with SAT. One Gaussian draw per channel
//         per sample whether or not the noise is on, stream k of the sensor seed (Rng(seed, k)), so
//         a channel's noise never depends on another channel or on any sigma. A frozen window
//         repeats the channel's last count and status bit for bit.
//   3..5  gimbal encoder yaw / roll / pitch [2^-24 rad]: beta_k rounded, no noise; +-round(pi 2^24)
//         counts saturate with SAT.
// Actuator command, 3 channels: gimbal torque yaw / roll / pitch [2^-20 N m], clipped to +-M_max
// (ACT_CLIP event, channel k, logged on the sample a channel enters the clip); a command without
// its channel applies zero. Other events: F_STEP (channel -1, requested = old f, applied = new f
// [Hz]) and KICK (channel k, dx [rad]), on the sample they take effect: both act at the boundary
// t_k itself, so the frame of t_k already sees the kicked x, and [t_k, t_k+1) runs at the new f.
// Diverged: a non-finite state, |x_k| > 1 rad or |beta_k| > pi (the reason names which).
//
// Truth (truth(), 24 values; the first 16 are sim_truth_t.state, the last 8 .extra), at t_k:
//   state[0..2]   x yaw, roll, pitch [rad]
//   state[3..5]   beta yaw, roll, pitch [rad]
//   state[6..9]   q: yaw mode 1, yaw mode 2, roll, pitch [rad]
//   state[10..12] x' yaw, roll, pitch [rad/s]
//   state[13]     linear_validity: 1 while every |beta_k| <= 0.5 rad, else 0
//   state[14]     f_min in use over [t_k, t_k+1) [Hz]
//   state[15]     plant: 0 single, +1 / -1 coupled with that coupling sign
//   extra[0..2]   torque applied over the last period [t_k-1, t_k) yaw, roll, pitch [N m]
//   extra[3..5]   beta' yaw, roll, pitch [rad/s]
//   extra[6]      latency_samples;  extra[7] 0 (spare)
#ifndef SIM_PD_PLANT_HPP
#define SIM_PD_PLANT_HPP

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "pd/pd_coupled.hpp"
#include "pd/pd_section.hpp"
#include "plant/plant.hpp"
#include "sensors/rng.hpp"

namespace sim {

// The true plant's channels of a scenario: ref::pd yaw, roll, pitch with pd.scale applied.
std::array<ref::pd::Channel, 3> pd_channels(const PdSetup &b, double Ty);

class PdPlant final : public Plant {
public:
    // Indices into sim_truth_t.state / .extra (the layout above).
    static constexpr std::size_t kTruthX = 0u, kTruthBeta = 3u, kTruthQ = 6u, kTruthXdot = 10u, kTruthLinValid = 13u,
                                 kTruthFHz = 14u, kTruthPlant = 15u;
    static constexpr std::size_t kExtraTorque = 0u, kExtraBetadot = 3u, kExtraLatency = 6u;
    static constexpr std::size_t kTruthSize = 24u;

    explicit PdPlant(const Scenario &scn);
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

    // The state in the ref::pd::Layout order [x(3), beta(3), q(4), x'(3), beta'(3), q'(4)].
    const Eigen::VectorXd &state() const { return s_; }
    double f_hz() const { return f_hz_; }
    const ref::pd::DiscreteN &discrete() const { return d_; }
    const std::array<ref::pd::Channel, 3> &channels() const { return ch_; }
    const std::array<double, 3> &applied_nm() const { return applied_nm_; }

private:
    void recompute();
    void boundary_events();   // f steps and kicks due at t_k

    PdSetup b_;
    std::uint32_t period_us_ = 0u;
    std::uint32_t k_ = 0u;
    std::array<ref::pd::Channel, 3> ch_;
    ref::pd::Layout L_;
    ref::pd::DiscreteN d_;
    double f_hz_ = 0.0;
    Eigen::VectorXd s_, u_;
    std::array<double, 3> cmd_nm_{{0.0, 0.0, 0.0}};       // latest command received (clipped), held
    std::array<double, 3> delayed_nm_{{0.0, 0.0, 0.0}};   // latency 1: the command received one sample earlier
    std::array<double, 3> applied_nm_{{0.0, 0.0, 0.0}};   // applied over the last period
    std::array<bool, 3> clip_on_{{false, false, false}};
    std::size_t next_step_ = 0u, next_kick_ = 0u;
    std::array<Rng, 3> noise_;
    std::array<std::int32_t, 3> last_cnt_{{0, 0, 0}};
    std::array<std::uint8_t, 3> last_status_{{0u, 0u, 0u}};
    std::array<bool, 3> have_last_{{false, false, false}};
    std::vector<TruthEvent> events_;
    mutable std::string reason_;   // set by check(), which is logically const
};

}  // namespace sim

#endif
