#include "observer/sail_plant.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstring>
#include <sstream>

namespace sim {

namespace {
constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;
// Automatic RK4 substep: |lambda|max * h_sub <= 1e-3. RK4's phase error per substep is about
// (|lambda| h_sub)^5 / 120, so over 20 s at 51 rad/s (~1e6 substeps) the drift stays near 1e-11
// relative, two orders inside the 1e-9 ZOH/ODE agreement of spec 10 §2.4.
constexpr double kOdeMaxPhasePerSubstep = 1e-3;
}  // namespace

double sail_max_abs_eig(const SailParams &p)
{
    const Eigen::EigenSolver<Mat6> es(sail_a_s(p), false);
    return es.eigenvalues().cwiseAbs().maxCoeff();
}

SailPlant::SailPlant(const Scenario &scn) { reset(scn); }

void SailPlant::reset(const Scenario &scn)
{
    scn_ = scn;
    sail_ = scn.mission_part<SailScenario>();
    par_ = SailParams();
    par_.sigma = sail_.sigma;
    par_.k2_per_s2 = sail_.k2_true_per_s2;
    par_.j_factor = sail_.j_factor;
    // The exponential is computed once per scenario (spec 10 §2.4); every step is then two
    // small matrix products.
    zoh_ = sail_zoh(par_, scn.h_s());
    if (sail_.ode_substeps > 0u) {
        ode_substeps_ = sail_.ode_substeps;
    } else {
        const double n = std::ceil(sail_max_abs_eig(par_) * scn.h_s() / kOdeMaxPhasePerSubstep);
        ode_substeps_ = (n >= 1.0 && n < 1.0e6) ? static_cast<std::uint32_t>(n) : 1000000u;
    }
    gyro_.reset(sail_.gyro);
    gimbal_.reset(sail_.gimbal);
    x_ << sail_.w0_radps[0], sail_.w0_radps[1], sail_.mu0_rad[0], sail_.mudot0_radps[0], sail_.mu0_rad[1],
        sail_.mudot0_radps[1];
    beta_rad_.setZero();
    bdot_applied_radps_.setZero();
    held_cnt_ = {0, 0};
    held_seq_ = 0u;
    seq_ = 0u;
    events_.clear();
    diverged_reason_.clear();
    state_ = RunState::Running;
    state_ = check();
}

std::int64_t SailPlant::utime_us() const
{
    return static_cast<std::int64_t>(seq_) * static_cast<std::int64_t>(scn_.period_us);
}

SensorFrame SailPlant::sense()
{
    SensorFrame f;
    f.utime_us = utime_us();
    f.seq = seq_;
    f.period_us = scn_.period_us;
    f.n_ch = 2u;
    std::array<std::int32_t, 2> cnt{};
    std::array<std::uint8_t, 2> st{};
    gyro_.sample({x_(kWy), x_(kWz)}, &cnt, &st);
    if (sail_.gyro.glitch_s >= 0.0 && sail_.gyro.glitch_channel < 2u &&
        seq_ == static_cast<std::uint32_t>(std::llround(sail_.gyro.glitch_s / scn_.h_s()))) {
        // The flip acts on the count the sensor outputs (after its own range logic), so the
        // sample stays in range and carries no status: only the flight code's own checks see it.
        const std::uint32_t u = static_cast<std::uint32_t>(cnt[sail_.gyro.glitch_channel]) ^ (1u << sail_.gyro.glitch_bit);
        std::int32_t v = 0;
        std::memcpy(&v, &u, sizeof v);
        cnt[sail_.gyro.glitch_channel] = v;
    }
    for (std::size_t i = 0; i < 2u; ++i) {
        f.cnt[i] = cnt[i];
        f.status[i] = st[i];
    }
    return f;
}

void SailPlant::apply(const ActuatorCmd &cmd)
{
    // Channels beyond the two gimbal axes are ignored; a short command leaves the others at zero.
    held_cnt_[0] = cmd.n_ch > 0u ? cmd.cnt[0] : 0;
    held_cnt_[1] = cmd.n_ch > 1u ? cmd.cnt[1] : 0;
    held_seq_ = cmd.seq;
}

RunState SailPlant::propagate()
{
    if (state_ != RunState::Running) {
        return state_;
    }
    const std::array<double, 2> u = gimbal_.apply(held_cnt_, seq_, utime_us(), &events_);
    return advance_radps(Vec2(u[0], u[1]));
}

RunState SailPlant::advance_radps(const Vec2 &u_radps)
{
    if (state_ != RunState::Running) {
        return state_;
    }
    if (sail_.propagator == Propagator::Ode) {
        step_ode(u_radps);
    } else {
        step_zoh(u_radps);
    }
    // beta_dot = u is constant over the period, so this update is exact in both propagators.
    beta_rad_ += scn_.h_s() * u_radps;
    bdot_applied_radps_ = u_radps;
    ++seq_;
    state_ = check();
    if (state_ == RunState::Running && seq_ >= scn_.n_steps()) {
        state_ = RunState::Done;
    }
    return state_;
}

void SailPlant::step_zoh(const Vec2 &u_radps)
{
    const Vec6 xn = zoh_.phi * x_ + zoh_.gamma * u_radps;
    x_ = xn;
}

void SailPlant::step_ode(const Vec2 &u_radps)
{
    // Classic RK4 on the written-out equations (sail_deriv), not on A_s, so this path checks
    // the matrix assembly as well as the exponential.
    const double hs = scn_.h_s() / static_cast<double>(ode_substeps_);
    const double u[2] = {u_radps(0), u_radps(1)};
    double x[6];
    for (int i = 0; i < 6; ++i) {
        x[i] = x_(i);
    }
    double k1[6], k2[6], k3[6], k4[6], t[6];
    for (std::uint32_t n = 0; n < ode_substeps_; ++n) {
        sail_deriv(par_, x, u, k1);
        for (int i = 0; i < 6; ++i) t[i] = x[i] + 0.5 * hs * k1[i];
        sail_deriv(par_, t, u, k2);
        for (int i = 0; i < 6; ++i) t[i] = x[i] + 0.5 * hs * k2[i];
        sail_deriv(par_, t, u, k3);
        for (int i = 0; i < 6; ++i) t[i] = x[i] + hs * k3[i];
        sail_deriv(par_, t, u, k4);
        for (int i = 0; i < 6; ++i) {
            x[i] += hs / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
    }
    for (int i = 0; i < 6; ++i) {
        x_(i) = x[i];
    }
}

RunState SailPlant::check() const
{
    if (state_ == RunState::Diverged) {
        return state_;
    }
    auto diverge = [this](const std::string &why) {
        std::ostringstream os;
        os << "DIVERGED at t = " << static_cast<double>(utime_us()) * 1e-6 << " s (k = " << seq_ << "): " << why;
        diverged_reason_ = os.str();
        return RunState::Diverged;
    };
    if (!x_.allFinite() || !beta_rad_.allFinite()) {
        return diverge("non-finite state");
    }
    const double mu_abs[2] = {std::fabs(x_(kMuY)), std::fabs(x_(kMuZ))};
    const double w_abs[2] = {std::fabs(x_(kWy)), std::fabs(x_(kWz))};
    for (int i = 0; i < 2; ++i) {
        if (mu_abs[i] > sail_.mu_max_rad) {
            std::ostringstream os;
            os << "|mu_" << (i == 0 ? 'y' : 'z') << "| = " << mu_abs[i] * kRadToDeg << " deg > "
               << sail_.mu_max_rad * kRadToDeg << " deg";
            return diverge(os.str());
        }
        if (w_abs[i] > sail_.w_max_radps) {
            std::ostringstream os;
            os << "|w_" << (i == 0 ? 'y' : 'z') << "| = " << w_abs[i] * kRadToDeg << " deg/s > "
               << sail_.w_max_radps * kRadToDeg << " deg/s";
            return diverge(os.str());
        }
    }
    return state_ == RunState::Done ? RunState::Done : RunState::Running;
}

void SailPlant::set_state(const Vec6 &x, const Vec2 &beta_rad)
{
    x_ = x;
    beta_rad_ = beta_rad;
    state_ = RunState::Running;
    diverged_reason_.clear();
    state_ = check();
}

void SailPlant::truth_message(std::array<double, 16> &state, std::array<double, 8> &extra) const
{
    const std::vector<double> t = truth();   // w, mu.. (6), beta (2), bdot applied (2)
    state.fill(0.0);
    extra.fill(0.0);
    for (std::size_t i = 0; i < 8u && i < t.size(); ++i) {
        state[i] = t[i];
    }
    extra[0] = sail_.k2_true_per_s2;
    extra[1] = t.size() > 8u ? t[8] : 0.0;
    extra[2] = t.size() > 9u ? t[9] : 0.0;
    extra[3] = static_cast<double>(sail_.sigma);
    extra[4] = sail_.j_factor;
}

std::vector<double> SailPlant::truth() const
{
    return {x_(0), x_(1), x_(2), x_(3), x_(4), x_(5), beta_rad_(0), beta_rad_(1),
            bdot_applied_radps_(0), bdot_applied_radps_(1)};
}

std::vector<std::string> SailPlant::truth_names() const
{
    return {"w_y_radps", "w_z_radps", "mu_y_rad", "mudot_y_radps", "mu_z_rad", "mudot_z_radps",
            "beta_y_rad", "beta_z_rad", "bdot_y_radps", "bdot_z_radps"};
}

}  // namespace sim
