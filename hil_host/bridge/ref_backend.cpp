#include "ref_backend.hpp"

#include <cmath>

namespace bridge {

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
    return true;
}

void RefObsBackend::host_counters(const Counters &c)
{
    missed_ = sat_u32(c.missed);
    rejected_ = sat_u32(rejected_total(c));
}

bool RefObsBackend::step(const Frame &f, StepOutput &out)
{
    out = StepOutput{};
    ++step_;
    const std::array<std::int32_t, 2> y{{f.counts[0], f.counts[1]}};
    const bool valid = f.n_counts >= 2 && (f.status[0] & (kStatusStale | kStatusSat)) == 0 &&
                       (f.status[1] & (kStatusStale | kStatusSat)) == 0;
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
        if (o.limited) { oh |= OBS_H_CMD_LIMITED; ++t.obs.n_limited; }
        if (limited_run_ >= p_.n_sat) { oh |= OBS_H_CMD_LIMIT_PERSIST; }
        if (st_.kappa <= t_.kappa_lo) { oh |= OBS_H_K_CLAMP_LO; ++t.obs.n_clamp_lo; }
        if (st_.kappa >= t_.kappa_hi) { oh |= OBS_H_K_CLAMP_HI; ++t.obs.n_clamp_hi; }
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
    t.obs_health = oh;
    t.obs.health_sticky |= oh;
    if (init_) {
        for (int i = 0; i < 6; ++i) { t.obs.x_q29[i] = to_q(st_.x(i), 29); }
        t.obs.kappa_q28 = to_q(st_.kappa, 28);
        t.obs.pkk_q30 = to_q(st_.p(6, 6), 30);
    }
    t.obs.u_q29[0] = to_q(cmd[0] * t_.act_lsb, 29);
    t.obs.u_q29[1] = to_q(cmd[1] * t_.act_lsb, 29);
    t.obs.revision = p_.revision;
    out.n_counts = 2;
    out.counts[0] = cmd[0];
    out.counts[1] = cmd[1];
    out.fsw_mode = static_cast<std::int32_t>(FSW_MODE_DETUMBLE);
    out.fsw_health = 0u;
    out.tlm_layout_version = static_cast<std::int32_t>(FSW_TLM_LAYOUT_VERSION);
    out.tlm_len = static_cast<std::int16_t>(fsw_tlm_encode(&t, out.tlm, static_cast<std::uint32_t>(kMaxTlm)));
    return true;
}

RefImpBackend::RefImpBackend(const imp_params_t &table) : p_(table), tlm_(new fsw_tlm_t())
{
    (void)reset();
}

bool RefImpBackend::reset()
{
    fsw_.reset(new ref::ImpFsw(p_));
    fsw_->init();
    *tlm_ = fsw_tlm_t{};
    tlm_->mission = FSW_MISSION_RENDEZVOUS;
    step_ = 0;
    tc_ = 0;
    return true;
}

void RefImpBackend::host_counters(const Counters &c)
{
    missed_ = sat_u32(c.missed);
    rejected_ = sat_u32(rejected_total(c));
}

bool RefImpBackend::command(const FswCommand &c)
{
    if (c.cmd != kCmdImpStart && c.cmd != kCmdImpAbort && c.cmd != kCmdImpClear) {
        return false;
    }
    tc_ = c.cmd;
    for (std::size_t i = 0; i < 8u; ++i) { tc_arg_[i] = c.args[i]; }
    return true;
}

bool RefImpBackend::step(const Frame &f, StepOutput &out)
{
    out = StepOutput{};
    ++step_;
    imp_in_t in{};
    in.step = static_cast<std::uint32_t>(static_cast<std::uint64_t>(f.seq) & 0xFFFFFFFFu);
    bool ok = f.n_counts >= static_cast<std::int16_t>(FSW_RDV_N_SENS);
    for (std::size_t i = 0; ok && i < FSW_RDV_N_SENS; ++i) {
        const std::int32_t hi = (i < 3u) ? FSW_NAV_POS_MAX_MM : ((i < 6u) ? FSW_NAV_VEL_MAX_CNT : INT32_MAX);
        const std::int32_t lo = (i < 6u) ? -hi : 0;
        ok = (f.status[i] & kStatusStale) == 0 && f.counts[i] >= lo && f.counts[i] <= hi;
    }
    in.nav_valid = ok ? 1u : 0u;
    for (std::size_t r = 0; ok && r < 3u; ++r) {
        in.nav_pos_mm[r] = f.counts[r];
        in.nav_vel_cnt[r] = f.counts[3u + r];
    }
    in.nav_step = ok ? static_cast<std::uint32_t>(f.counts[6]) : 0u;
    in.avail_mask = 0x3Fu;
    in.cmd = (tc_ == kCmdImpStart) ? IMP_CMD_START : (tc_ == kCmdImpAbort) ? IMP_CMD_ABORT
           : (tc_ == kCmdImpClear) ? IMP_CMD_CLEAR_FAULTS : IMP_CMD_NONE;
    in.cmd_t0_step = (tc_arg_[0] < 0) ? 0u : static_cast<std::uint32_t>(tc_arg_[0]);
    in.cmd_tf_step = (tc_arg_[1] < 0) ? 0u : static_cast<std::uint32_t>(tc_arg_[1]);
    for (std::size_t r = 0; r < 3u; ++r) {
        in.cmd_tgt_pos_mm[r] = tc_arg_[2u + r];
        in.cmd_tgt_vel_cnt[r] = tc_arg_[5u + r];
    }
    if (tc_ != 0) { ++tlm_->n_tc; }
    tc_ = 0;
    for (std::int32_t &a : tc_arg_) { a = 0; }
    imp_out_t o{};
    fsw_->step(in, o);

    fsw_tlm_t &t = *tlm_;
    t.utime_us = f.utime;
    t.seq = f.seq;
    t.step = step_;
    t.mode = FSW_MODE_RENDEZVOUS;
    t.health = ok ? 0u : FSW_H_STALE;
    t.health_sticky |= t.health;
    if (!ok) { ++t.n_chan_rej; }
    t.host_missed = missed_;
    t.host_rejected = rejected_;
    for (std::size_t j = 0; j < 6u; ++j) {
        t.act_cnt[j] = static_cast<std::int32_t>(o.on_start_cnt[j]);
        t.act_cnt[6u + j] = static_cast<std::int32_t>(o.on_len_cnt[j]);
    }
    t.act_cnt[FSW_RDV_ACT_MASK] = static_cast<std::int32_t>(o.on_mask);
    t.imp_health = o.health;
    t.imp = o.tlm;
    out.n_counts = static_cast<std::int16_t>(FSW_RDV_N_ACT);
    for (std::size_t i = 0; i < FSW_RDV_N_ACT; ++i) { out.counts[i] = t.act_cnt[i]; }
    out.fsw_mode = static_cast<std::int32_t>(FSW_MODE_RENDEZVOUS);
    out.fsw_health = t.health;
    out.tlm_layout_version = static_cast<std::int32_t>(FSW_TLM_RDV_LAYOUT_VERSION);
    out.tlm_len = static_cast<std::int16_t>(fsw_tlm_encode(&t, out.tlm, static_cast<std::uint32_t>(kMaxTlm)));
    return true;
}

}  // namespace bridge
