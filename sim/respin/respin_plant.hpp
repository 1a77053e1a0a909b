// RespinPlant — the RESPIN plant behind the generic sim::Plant interface of the SIL nodes (spec 30
// §2, rigid gyrostat with three reaction wheels or four gyrodines): dG/dt = -omega x G,
// omega = J^-1 (G - H), dH/dt = -M, the command (wheel motor torque or gimbal rate) held (ZOH) over
// the tick. Integrated by RK4 with h = Ts / n_sub (n_sub = 4: h = 0.025 s, omega h <= 0.011 rad at
// the 0.45 rad/s of a spin about z, so the RK4 error is far below every figure compared; the same
// step the elastic variant needs, Omega_max h <= 0.25); G re-projected onto |G| = g0 after every
// step (ref::gyrostat_tick / ref::gyrostat_tick_cmg).
//
// Elastic variant (respin.elastic: E1 | E2): the array modes of ref::GyrostatModel; the gyro sees
// the body rate, the flight's J omega + H misses D qdot. Either actuator.
//
// Gyrodines (respin.actuator: gyrodines): H = sum_p h_p(beta_p) of the 2-SPE cluster (spec 30 §2),
// ideal gimbal rate loop (the commanded rate clipped to +-u_max, held over the tick, beta
// integrated inside the RK4 step), no gimbal stops; beta(0) = beta0 (null configuration: H(0) = 0).
// Rotor fault (respin.cmg.rotor_fault): from t_s on rotor p has, and reads, scale x nominal
// (an instantaneous internal exchange: G kept, its work booked; ROTOR_FAULT event).
//
// Sensor frame, always 14 channels (the superset for both kinds; all status OK unless saturated):
//   0..2   rate gyro omega_BN_B x/y/z [2^-22 rad/s]: (1 + scale) omega + bias + white noise,
//          +-2^22 counts (SAT at full scale);
//   3..5   wheel speed x/y/z [2^-10 rad/s]: Omega = H / I_w, +-600 rad/s (SAT); 0 with gyrodines;
//   6..9   gimbal angle of gyrodine 1..4 [2 pi / 2^20 rad]: beta mod 2 pi rounded to the nearest
//          count, 2^20 wrapped to 0, so [0, 2^20) (gimbal_encoder_counts); with wheels the null
//          configuration's counts 131072, 131072, 917504, 917504 (a locked cluster);
//   10..13 rotor speed of gyrodine 1..4 [2^-8 rad/s]: k_p x rotor_speed_radps (600 rad/s nominal =
//          153 600 counts), 0 with wheels.
// Actuator command, 7 channels (a command without its channel is zero):
//   0..2   wheel motor torque [2^-17 N m] (= -M), read with wheels: saturated at the motor limit
//          (ACT_CLIP event when beyond it by more than one count), cut at the momentum limit where
//          it would increase |H_i| (WHL_HLIM event);
//   3..6   gimbal rate of gyrodine 1..4 [2^-16 rad/s], read with gyrodines: clipped to +-u_max
//          (GIMBAL_RATE_CLIP event, channel 3..6, when beyond it by more than one count: the
//          flight's limit 11 437 counts is 0.174515 rad/s, a quantisation above 0.1745, not a clip).
//   Events are logged on the tick a channel enters the condition.
// Truth (truth(), 24 values; the first 16 are sim_truth_t.state, the last 8 .extra):
//   state[0..2]  omega_BN_B [rad/s]     state[3..5]  H, wheels or cluster [N m s]    state[6..8] G body [N m s]
//   state[9..12] q_BI (w, x, y, z)      state[13]    T = 1/2 omega^T J omega [J]
//   state[14]    T0 + int omega^T M dt [J] (the energy check: equals T for a rigid body)
//   state[15]    |xi| = sqrt(G_x^2 + G_z^2) / |G| (truth, independent of a_f)
//   extra[0..2]  wheels: the applied wheel torque [N m] (= -M, after the motor limit and the
//                momentum cut) of the last tick; gyrodines: the delivered internal moment on the
//                body M = -(H_end - H_start) / Ts [N m], its exact average over the last tick
//                (a rotor-fault jump is not in it)
//   extra[3] g0 [N m s]
//   extra[4..6]  modal coordinates q_1..q_3 [kg^1/2 m] of the elastic variant (0 when rigid;
//                the inertial invariant G_I = R_IB G follows from state[6..12])
//   extra[7]     G_y / |G| (C_phi for f = +e_y)
#ifndef SIM_RSP_PLANT_HPP
#define SIM_RSP_PLANT_HPP

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "plant/plant.hpp"
#include "respin/respin_section.hpp"
#include "respin/rsp_ref.hpp"
#include "sensors/rng.hpp"

namespace sim {

class RespinPlant final : public Plant {
public:
    // Indices into sim_truth_t.state / .extra (the layout above).
    static constexpr std::size_t kTruthW = 0u, kTruthH = 3u, kTruthG = 6u, kTruthQ = 9u, kTruthT = 13u,
                                 kTruthEcheck = 14u, kTruthXi = 15u;
    static constexpr std::size_t kExtraTau = 0u, kExtraMoment = 0u, kExtraG0 = 3u, kExtraQm = 4u, kExtraGyRel = 7u;

    explicit RespinPlant(const Scenario &scn);
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

    const ref::GyrostatState &state() const { return s_; }
    const ref::GyrostatModel &model() const { return model_; }
    ref::V3 omega_radps() const { return ref::gyrostat_omega(model_, s_); }
    double energy_j() const { return ref::gyrostat_energy_j(model_, s_); }
    double energy_check_j() const { return ref::gyrostat_energy_check_j(model_, s_); }   // equals T exactly
    const ref::V3 &applied_torque_nm() const { return applied_nm_; }        // wheels
    const ref::V3 &delivered_moment_nm() const { return moment_nm_; }      // gyrodines: M averaged over the last tick
    const std::array<double, 4> &gimbal_rate_radps() const { return rate_applied_; }   // applied, last tick
    double max_gimbal_rate_radps() const { return max_rate_radps_; }       // max |applied gimbal rate| so far
    const std::array<double, 3> &gyro_bias_radps() const { return b_.gyro_bias_radps; }

private:
    void apply_cmg(const ActuatorCmd &cmd);
    void rotor_fault_due();

    RespinSetup b_;
    ref::GyrostatModel model_;
    std::uint32_t period_us_ = 0u;
    std::uint32_t k_ = 0u;
    ref::GyrostatState s_;
    ref::V3 cmd_nm_{{0.0, 0.0, 0.0}};         // held motor torque command
    ref::V3 applied_nm_{{0.0, 0.0, 0.0}};     // after the motor limit and the momentum cut (last tick)
    std::array<bool, 3> clip_on_{{false, false, false}}, cut_on_{{false, false, false}};
    std::array<double, 4> rate_cmd_{{0.0, 0.0, 0.0, 0.0}};       // held gimbal rate command (gyrodines)
    std::array<double, 4> rate_applied_{{0.0, 0.0, 0.0, 0.0}};   // after the u_max clip (last tick)
    std::array<bool, 4> rate_clip_on_{{false, false, false, false}};
    double max_rate_radps_ = 0.0;
    ref::V3 moment_nm_{{0.0, 0.0, 0.0}};      // gyrodines: M averaged over the last tick
    std::int64_t rotor_fault_us_ = -1;        // rotor fault time (-1: none); applied once
    bool rotor_fault_done_ = false;
    Rng noise_;
    std::vector<TruthEvent> events_;
    mutable std::string reason_;   // set by check(), which is logically const
};

// ------------------------------------------------------------------------------------------------
// The reference closed loop (spec 30 §6 (c)): this plant and ref::RespinRef in lock-step through
// the same counts the flight code sees (frame -> RespinRefIn; torque -> int16 counts), no fixed
// point. Truth figures of §7 ("converged": truth |xi| < 0.01 and C_phi > 0 for the reference's
// current f = a_f e_y) and the invariants of A5.

struct RespinLoopOptions {
    double sample_dt_s = 10.0;     // trajectory log spacing (0: no log)
    double conv_xi = 0.01;         // the "converged" |xi| (spec 30 §7)
    double tail_s = 2000.0;        // region switches are also counted over the last tail_s
};

struct RespinLoopSample {
    double t_s = 0.0, xi_abs = 0.0, cphi = 0.0, t_j = 0.0, h_abs_nms = 0.0;
    std::uint32_t region = 0u;
    std::int32_t a_f = 1;
};

struct RespinLoopRun {
    std::uint64_t ticks = 0u;
    bool diverged = false;
    std::string reason;
    double t_first_conv_s = -1.0;  // first time truth |xi| < conv_xi with C_phi > 0
    double t_settle_s = -1.0;      // start of the final stretch in that condition (-1: not at the end)
    double t_done_s = -1.0;        // first tick the reference raised DONE
    // At the end of the run (truth unless named ref_)
    double xi_end = 0.0, cphi_end = 0.0, t_end_j = 0.0, omega_err_end_radps = 0.0, h_end_nms = 0.0;
    std::int32_t a_f_end = 1;
    std::uint32_t region_end = 0u;
    // Invariants over the run (A5)
    double max_g_rel_err = 0.0;          // ||G| - g0| / g0
    double max_h_abs_nms = 0.0;          // max |H_i|
    double max_energy_err_j = 0.0;       // |T0 + int omega^T M dt - T|
    double max_abs_re_j = 0.0;           // reference |r_E|
    double max_gi_dev_rel = 0.0;         // |G_I(t) - G_I(0)| / g0 (attitude kinematics check)
    double max_torque_cmd_nm = 0.0;      // max |commanded wheel torque| (counts * LSB)
    double max_gimbal_rate_radps = 0.0;  // gyrodines: max |applied gimbal rate| (plant)
    std::uint32_t n_switch = 0u, n_switch_tail = 0u;
    double g0_ref_nms = 0.0;
    std::vector<RespinLoopSample> log;
};

// Flies scn (its respin: setup, duration and period) against the table p.
RespinLoopRun run_respin_reference(const Scenario &scn, const rsp_params_t &p, const RespinLoopOptions &opt = {});

// A sensor frame as the flight code's input: counts, a valid bit per channel unless the status is
// STALE / non-finite, the SAT bits.
ref::RespinRefIn respin_ref_input(const SensorFrame &f);

// A gimbal angle as its encoder reads it: beta mod 2 pi in counts of 2 pi / 2^20, rounded to the
// nearest count, 2^20 wrapped to 0: [0, 2^20). 0 for a non-finite angle.
std::int32_t gimbal_encoder_counts(double beta_rad);

}  // namespace sim

#endif
