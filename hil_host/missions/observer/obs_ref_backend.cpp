#include "observer/obs_ref_backend.hpp"

#include <cmath>

namespace host {

using bridge::Counters;
using bridge::Frame;
using bridge::StepOutput;

namespace {

std::int32_t to_q(double v, int q)
{
    const double s = std::round(std::ldexp(v, q));
    if (!(s > -2147483648.0)) { return INT32_MIN; }   // also NaN: the run is diverging
    if (s > 2147483647.0) { return INT32_MAX; }
    return static_cast<std::int32_t>(s);
}

std::uint32_t sat_u32(std::int32_t v) { return (v < 0) ? 0u : static_cast<std::uint32_t>(v); }

}  // namespace

RefObsBackend::RefObsBackend(const obs_params_t &table, bool per_axis_clip)
    : p_(table), t_(ref::dequantise(table)), per_axis_(per_axis_clip), tlm_(new fsw_tlm_t())
{
    (void)reset();
}

bool RefObsBackend::reset()
{
    init_ = false;
    step_ = 0;
    limited_run_ = 0;
    *tlm_ = fsw_tlm_t{};
    tlm_->mission = FSW_MISSION_DETUMBLE;
    return true;
}

void RefObsBackend::host_counters(const Counters &c)
{
    missed_ = sat_u32(c.missed);
    rejected_ = sat_u32(bridge::rejected_total(c));
}

bool RefObsBackend::step(const Frame &f, StepOutput &out)
{
    out = StepOutput{};
    ++step_;
    const std::array<std::int32_t, 2> y{{f.counts[0], f.counts[1]}};
    const bool valid = f.n_counts >= 2 && (f.status[0] & (bridge::kStatusStale | bridge::kStatusSat)) == 0 &&
                       (f.status[1] & (bridge::kStatusStale | bridge::kStatusSat)) == 0;
    fsw_tlm_t &t = *tlm_;
    std::uint32_t oh = 0u;
    std::array<std::int32_t, 2> cmd{{0, 0}};
    if (!init_ && valid) {
        st_ = ref::initial_state(p_, y);
        init_ = true;
    }
    if (init_ && valid) {
        const ref::ObsStepOut o = ref::obs_step_ref(t_, st_, y, per_axis_);
        cmd = o.cmd_cnt;
        limited_run_ = o.limited ? limited_run_ + 1u : 0u;
        if (o.limited) { oh |= OBS_H_CMD_LIMITED; ++t.m.detumble.n_limited; }
        if (limited_run_ >= p_.n_sat) { oh |= OBS_H_CMD_LIMIT_PERSIST; }
        if (st_.kappa <= t_.kappa_lo) { oh |= OBS_H_K_CLAMP_LO; ++t.m.detumble.n_clamp_lo; }
        if (st_.kappa >= t_.kappa_hi) { oh |= OBS_H_K_CLAMP_HI; ++t.m.detumble.n_clamp_hi; }
        for (int c = 0; c < 2; ++c) {
            if (o.d2[static_cast<std::size_t>(c)] > t_.d2_max) { oh |= OBS_H_INNOV_HIGH; ++t.m.detumble.n_innov; }
        }
        if (st_.kappa_frozen) { oh |= OBS_H_ADAPT_FROZEN; }
        if (st_.rej_safe) { oh |= OBS_H_INNOV_PERSIST | OBS_H_ADAPT_FROZEN; }
    } else {
        oh |= init_ ? OBS_H_MEAS_SKIP : OBS_H_NOT_INIT;   // held command is the plant's business
    }
    t.utime_us = f.utime;
    t.seq = f.seq;
    t.step = step_;
    t.mode = FSW_MODE_DETUMBLE;
    t.health = 0u;
    t.host_missed = missed_;
    t.host_rejected = rejected_;
    t.act_cnt[0] = cmd[0];
    t.act_cnt[1] = cmd[1];
    t.mod_health = oh;
    t.m.detumble.health_sticky |= oh;
    if (init_) {
        for (int i = 0; i < 6; ++i) { t.m.detumble.x_q29[i] = to_q(st_.x(i), 29); }
        t.m.detumble.kappa_q28 = to_q(st_.kappa, 28);
        t.m.detumble.pkk_q30 = to_q(st_.p(6, 6), 30);
    }
    t.m.detumble.u_q29[0] = to_q(cmd[0] * t_.act_lsb, 29);
    t.m.detumble.u_q29[1] = to_q(cmd[1] * t_.act_lsb, 29);
    t.m.detumble.revision = p_.revision;
    out.n_counts = 2;
    out.counts[0] = cmd[0];
    out.counts[1] = cmd[1];
    out.fsw_mode = static_cast<std::int32_t>(FSW_MODE_DETUMBLE);
    out.fsw_health = 0u;
    out.tlm_layout_version = static_cast<std::int32_t>(OBS_TLM_LAYOUT);
    out.tlm_len = static_cast<std::int16_t>(fsw_tlm_encode(&t, out.tlm, static_cast<std::uint32_t>(bridge::kMaxTlm)));
    return true;
}

}  // namespace host
