#include "relay/relay_plant.hpp"

#include <cmath>

#include "sensors/counts.hpp"

namespace sim {

bool relay_level_of_code(std::int32_t code, int *level)
{
    switch (code) {
    case static_cast<std::int32_t>(RLY_LVL_OFF): *level = 0; return true;
    case static_cast<std::int32_t>(RLY_LVL_WEAK_POS): *level = 1; return true;
    case static_cast<std::int32_t>(RLY_LVL_WEAK_NEG): *level = -1; return true;
    case static_cast<std::int32_t>(RLY_LVL_FULL_POS): *level = 2; return true;
    case static_cast<std::int32_t>(RLY_LVL_FULL_NEG): *level = -2; return true;
    default: *level = 0; return false;
    }
}

RelayPlant::RelayPlant(const Scenario &scn) { reset(scn); }

void RelayPlant::reset(const Scenario &scn)
{
    b_ = scn.mission_part<RelayScenario>().body;
    applied_ = b_.model;
    applied_.m_u_radps2 *= 1.0 + b_.scale_error;
    applied_.m_eps_radps2 *= 1.0 + b_.scale_error;
    period_us_ = scn.period_us;
    h_s_ = static_cast<double>(period_us_) * 1e-6;
    k_ = 0u;
    anchor_ = b_.state0;
    now_ = b_.state0;
    ticks_ = 0u;
    level_ = 0;
    pending_ = 0;
    noise_ = Rng(b_.seed, 0u);
    events_.clear();
    reason_.clear();
}

std::int64_t RelayPlant::utime_us() const
{
    return static_cast<std::int64_t>(k_) * static_cast<std::int64_t>(period_us_);
}

SensorFrame RelayPlant::sense()
{
    SensorFrame f;
    f.utime_us = utime_us();
    f.seq = k_;
    f.period_us = period_us_;
    f.n_ch = 1u;
    // One draw per period whether or not the noise is on, so the stream never shifts.
    const double n = noise_.gaussian();
    const double meas = now_.x() + b_.bias_rad + b_.noise_rad * n;
    f.cnt[0] = counts_from_si(meas, kRelayAngleLsbRad, kRelayAngleMaxCnt, &f.status[0]);
    return f;
}

void RelayPlant::set_level(int level)
{
    if (level != level_) {   // re-anchor at t_k: the closed form restarts from the exact state
        anchor_ = now_;
        ticks_ = 0u;
        level_ = level;
    }
}

void RelayPlant::apply(const ActuatorCmd &cmd)
{
    int lvl = 0;
    const std::int32_t code = (cmd.n_ch >= 1u) ? cmd.cnt[0] : static_cast<std::int32_t>(RLY_LVL_OFF);
    if (!relay_level_of_code(code, &lvl)) {   // never guess: an unknown code is no moment, and visible
        TruthEvent e;
        e.utime_us = utime_us();
        e.seq = cmd.seq;
        e.kind = "ACT_UNKNOWN";
        e.requested = static_cast<double>(code);
        e.applied = 0.0;
        events_.push_back(e);
    }
    if (b_.delay_ticks == 0u) {
        set_level(lvl);
    } else {
        set_level(pending_);
        pending_ = lvl;
    }
}

RunState RelayPlant::propagate()
{
    if (!reason_.empty()) {
        return RunState::Diverged;
    }
    ++ticks_;
    now_ = ref::propagate(applied_, anchor_, level_, static_cast<double>(ticks_) * h_s_);
    ++k_;
    return check();
}

RunState RelayPlant::check() const
{
    if (!std::isfinite(now_.x()) || std::fabs(now_.x()) > b_.x_max_rad) {
        reason_ = "DIVERGED: |x| above x_max_rad";
        return RunState::Diverged;
    }
    return RunState::Running;
}

std::vector<std::string> RelayPlant::truth_names() const
{
    return {"x_rad", "xbar_rad", "xbardot_radps", "xt1_rad", "xt2_rad", "xt3_rad", "xt4_rad",
            "pt1_rad", "pt2_rad", "pt3_rad", "pt4_rad", "level", "m_radps2"};
}

std::vector<double> RelayPlant::truth() const
{
    std::vector<double> t{now_.x(), now_.xbar_rad, now_.xbardot_radps};
    for (int i = 0; i < ref::kRelayMaxModes; ++i) {
        t.push_back(now_.q_rad[static_cast<std::size_t>(i)]);
    }
    for (int i = 0; i < ref::kRelayMaxModes; ++i) {
        const double w = applied_.omega_radps[static_cast<std::size_t>(i)];
        t.push_back((i < applied_.n_modes && w > 0.0) ? now_.qdot_radps[static_cast<std::size_t>(i)] / w : 0.0);
    }
    t.push_back(static_cast<double>(level_));
    t.push_back(ref::level_moment(applied_, level_));
    return t;
}

void RelayPlant::truth_message(std::array<double, 16> &state, std::array<double, 8> &extra) const
{
    state.fill(0.0);
    extra.fill(0.0);
    const std::vector<double> t = truth();
    for (std::size_t i = 0; i < t.size() && i < state.size(); ++i) {
        state[i] = t[i];
    }
    extra[0] = applied_.m_u_radps2;
    extra[1] = applied_.m_eps_radps2;
}

}  // namespace sim
