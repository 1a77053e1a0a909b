#include "impulse/imp_ref_backend.hpp"

namespace host {

namespace {

std::uint32_t sat_u32(std::int32_t v) { return (v < 0) ? 0u : static_cast<std::uint32_t>(v); }

}  // namespace

RefImpBackend::RefImpBackend(const imp_params_t &table) : p_(table), chan_(new imp_mis_t()), tlm_(new fsw_tlm_t())
{
    chan_->p = p_;
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

void RefImpBackend::host_counters(const bridge::Counters &c)
{
    missed_ = sat_u32(c.missed);
    rejected_ = sat_u32(bridge::rejected_total(c));
}

bool RefImpBackend::command(const bridge::FswCommand &c)
{
    // The executive's rule: this mission's namespace and a known local id.
    const std::uint32_t id = static_cast<std::uint32_t>(c.cmd);
    const std::uint32_t local = id & FSW_TC_LOCAL_MASK;
    if (c.cmd < 0 || (id & ~FSW_TC_LOCAL_MASK) != FSW_TC_ID(FSW_MISSION_RENDEZVOUS, 0u) || local < 1u ||
        local > IMP_CMD_MAX) {
        return false;
    }
    tc_ = local;
    for (std::size_t i = 0; i < FSW_TC_ARGS; ++i) { tc_arg_[i] = c.args[i]; }
    return true;
}

bool RefImpBackend::step(const bridge::Frame &f, bridge::StepOutput &out)
{
    out = bridge::StepOutput{};
    ++step_;
    fsw_range_t rng[FSW_IN_MAX] = {};
    imp_mis_ranges(chan_.get(), rng);
    imp_in_t in{};
    in.step = static_cast<std::uint32_t>(static_cast<std::uint64_t>(f.seq) & 0xFFFFFFFFu);
    bool ok = f.n_counts >= static_cast<std::int16_t>(IMP_N_SENS);
    for (std::size_t i = 0; ok && i < IMP_N_SENS; ++i) {
        ok = (f.status[i] & bridge::kStatusStale) == 0 && f.counts[i] >= rng[i].min && f.counts[i] <= rng[i].max;
    }
    in.nav_valid = ok ? 1u : 0u;
    for (std::size_t r = 0; ok && r < IMP_NAX; ++r) {
        in.nav_pos_mm[r] = f.counts[r];
        in.nav_vel_cnt[r] = f.counts[IMP_NAX + r];
    }
    in.nav_step = ok ? static_cast<std::uint32_t>(f.counts[IMP_CH_NAV_STEP]) : 0u;
    in.avail_mask = IMP_THR_ALL;
    in.cmd = static_cast<std::uint8_t>(tc_);
    in.cmd_t0_step = (tc_arg_[0] < 0) ? 0u : static_cast<std::uint32_t>(tc_arg_[0]);
    in.cmd_tf_step = (tc_arg_[1] < 0) ? 0u : static_cast<std::uint32_t>(tc_arg_[1]);
    for (std::size_t r = 0; r < IMP_NAX; ++r) {
        in.cmd_tgt_pos_mm[r] = tc_arg_[2u + r];
        in.cmd_tgt_vel_cnt[r] = tc_arg_[5u + r];
    }
    if (tc_ != 0u) { ++tlm_->n_tc; }
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
    for (std::size_t j = 0; j < IMP_NTHR; ++j) {
        t.act_cnt[j] = static_cast<std::int32_t>(o.on_start_cnt[j]);
        t.act_cnt[IMP_NTHR + j] = static_cast<std::int32_t>(o.on_len_cnt[j]);
    }
    t.act_cnt[IMP_ACT_MASK] = static_cast<std::int32_t>(o.on_mask);
    t.mod_health = o.health;
    t.m.rendezvous = o.tlm;
    out.n_counts = static_cast<std::int16_t>(IMP_N_ACT);
    for (std::size_t i = 0; i < IMP_N_ACT; ++i) { out.counts[i] = t.act_cnt[i]; }
    out.fsw_mode = static_cast<std::int32_t>(FSW_MODE_RENDEZVOUS);
    out.fsw_health = t.health;
    out.tlm_layout_version = static_cast<std::int32_t>(IMP_TLM_LAYOUT);
    out.tlm_len = static_cast<std::int16_t>(fsw_tlm_encode(&t, out.tlm, static_cast<std::uint32_t>(bridge::kMaxTlm)));
    return true;
}

}  // namespace host
