#include "pd/pd_plant.hpp"

#include <cmath>

#include "sensors/counts.hpp"

namespace sim {

PdPlant::PdPlant(const Scenario &scn) { reset(scn); }

void PdPlant::reset(const Scenario &scn)
{
    b_ = scn.mission_part<PdScenario>().body;
    period_us_ = scn.period_us;
    k_ = 0u;
    w_ = b_.w0_radps;
    tau_ = 0.0;
    noise_ = Rng(b_.gyro_seed, 0u);
    events_.clear();
    reason_.clear();
}

std::int64_t PdPlant::utime_us() const
{
    return static_cast<std::int64_t>(k_) * static_cast<std::int64_t>(period_us_);
}

SensorFrame PdPlant::sense()
{
    SensorFrame f;
    f.utime_us = utime_us();
    f.seq = k_;
    f.period_us = period_us_;
    f.n_ch = 1u;
    // One draw per period whether or not the noise is on, so the stream never shifts.
    const double n = noise_.gaussian();
    const double meas = w_ + b_.gyro_bias_radps + b_.gyro_noise_radps * n;
    f.cnt[0] = counts_from_si(meas, kPdRateLsbRadps, b_.gyro_max_cnt, &f.status[0]);
    return f;
}

void PdPlant::apply(const ActuatorCmd &cmd)
{
    // A command without its channel is applied as zero torque: the plant never guesses.
    const double req = (cmd.n_ch >= 1u) ? static_cast<double>(cmd.cnt[0]) * kPdTorqueLsbNm : 0.0;
    const bool clip = std::fabs(req) > b_.act_max_nm;
    tau_ = clip ? std::copysign(b_.act_max_nm, req) : req;
    if (clip) {   // clipped by the hardware: visible in truth only
        TruthEvent e;
        e.utime_us = utime_us();
        e.seq = cmd.seq;
        e.kind = "ACT_CLIP";
        e.requested = req;
        e.applied = tau_;
        events_.push_back(e);
    }
}

RunState PdPlant::propagate()
{
    if (!reason_.empty()) {
        return RunState::Diverged;
    }
    w_ += (static_cast<double>(period_us_) * 1e-6) * (tau_ + b_.torque_dist_nm) / b_.inertia_kgm2;
    ++k_;
    return check();
}

RunState PdPlant::check() const
{
    if (!std::isfinite(w_) || std::fabs(w_) > b_.w_max_radps) {
        reason_ = "DIVERGED: |omega| above w_max_radps";
        return RunState::Diverged;
    }
    return RunState::Running;
}

void PdPlant::truth_message(std::array<double, 16> &state, std::array<double, 8> &extra) const
{
    state.fill(0.0);
    extra.fill(0.0);
    state[0] = w_;
    state[1] = tau_;
    extra[0] = b_.inertia_kgm2;
    extra[1] = b_.torque_dist_nm;
}

}  // namespace sim
