#include "pd/pd_ref_backend.hpp"

#include <algorithm>
#include <cmath>

namespace host {

namespace {

std::int32_t to_cnt(double v, double lsb)
{
    const double s = std::round(v / lsb);
    if (!(s > -2147483648.0)) { return INT32_MIN; }   // also NaN
    if (s > 2147483647.0) { return INT32_MAX; }
    return static_cast<std::int32_t>(s);
}

std::uint32_t sat_u32(std::int32_t v) { return (v < 0) ? 0u : static_cast<std::uint32_t>(v); }

std::uint32_t to_u32(double v, int q)
{
    const double s = std::round(std::ldexp(v, q));
    if (!(s > 0.0)) { return 0u; }   // also NaN
    return (s >= 4294967295.0) ? 0xFFFFFFFFu : static_cast<std::uint32_t>(s);
}

// The estimator's double design per channel (yaw, roll, pitch): make_fest_params on the channel's nominal
// model, the design the flight table's quantised fest block was made from (pd_analysis fest-params ->
// sim/pd/pd_fest_quant); the reference flies that design, not a dequantisation of the block. Whether a
// channel may use it is the flight's check of the table's block (PdChannelTable::fest_ok).
const std::shared_ptr<const ref::pd::FestParams> &fest_design(std::size_t k)
{
    static const std::array<std::shared_ptr<const ref::pd::FestParams>, PD_N_CH> d = [] {
        std::array<std::shared_ptr<const ref::pd::FestParams>, PD_N_CH> a;
        const char *const names[PD_N_CH] = {"yaw", "roll", "pitch"};
        for (std::size_t i = 0; i < PD_N_CH; ++i) {
            a[i] = std::make_shared<const ref::pd::FestParams>(
                ref::pd::make_fest_params(ref::pd::Channel::by_name(names[i])));
        }
        return a;
    }();
    return d[k];
}

}  // namespace

RefPdBackend::RefPdBackend(const pd_table_t &table) : t_(table), tlm_(new fsw_tlm_t()) { (void)reset(); }

bool RefPdBackend::reset()
{
    ch_.clear();
    *tlm_ = fsw_tlm_t{};
    tlm_->mission = FSW_MISSION_HOLD;
    for (std::uint32_t k = 0; k < PD_N_CH; ++k) {
        pd_params_t p{};
        pd_params_of(&t_, k, &p);
        ref::PdChannelTable ct = ref::dequantise(p);
        if ((t_.c.ch_mask & (1u << k)) == 0u) {
            // A channel that does not fly is never stepped, so its telemetry keeps what the flight's
            // pd_init left: the boot source's k2 (ADAPTIVE: k2_cold, GROUND: the schedule at f_ground,
            // FIXED: k2_nom), all else zero. It needs no gain source here (as pd_table_check: an
            // ADAPTIVE table flies pitch and roll with ch_mask 6).
            const double clamp_lo = ct.k2_min, clamp_hi = ct.k2_max;
            const double k2 = (ct.src == PD_SRC_ADAPTIVE) ? std::fmin(std::fmax(ct.k2_cold, clamp_lo), clamp_hi)
                              : (ct.src == PD_SRC_GROUND) ? ref::pd_sched_k2(ct, ct.f_ground)
                                                          : std::fmin(std::fmax(ct.k2_nom, clamp_lo), clamp_hi);
            tlm_->m.hold.ch[k].k2_q22 = static_cast<std::uint32_t>(std::llround(std::ldexp(k2, 22)));
            ct.src = PD_SRC_FIXED;
        }
        ch_.emplace_back(ct, fest_design(k));
    }
    act_.fill(0);
    step_ = health_ = 0u;
    seq0_ = -1;
    last_seq_ = -1;
    last_idx_ = -1;
    tc_ = 0u;
    return true;
}

void RefPdBackend::host_counters(const bridge::Counters &c)
{
    missed_ = sat_u32(c.missed);
    rejected_ = sat_u32(bridge::rejected_total(c));
}

bool RefPdBackend::command(const bridge::FswCommand &c)
{
    const std::uint32_t id = static_cast<std::uint32_t>(c.cmd);
    const std::uint32_t local = id & FSW_TC_LOCAL_MASK;
    if (c.cmd < 0 || (id & ~FSW_TC_LOCAL_MASK) != FSW_TC_ID(FSW_MISSION_HOLD, 0u) || local < 1u || local > PD_CMD_MAX) {
        return false;
    }
    tc_ = local;
    for (std::size_t i = 0; i < FSW_TC_ARGS; ++i) { tc_arg_[i] = c.args[i]; }
    return true;
}

bool RefPdBackend::step(const bridge::Frame &f, bridge::StepOutput &out)
{
    out = bridge::StepOutput{};
    ++step_;
    // the adapter's telecommands (pd_mission.c), in the same units
    for (std::size_t k = 0; k < PD_N_CH; ++k) {
        ref::PdRefChannel &c = ch_[k];
        if (tc_ == PD_CMD_RESET_COUNTERS) {
            c.miss = c.stale = c.range_rej = c.rate_rej = c.period_rej = c.trq_sat = c.beta_lim = 0u;
            c.health_sticky = 0u;
        } else if (tc_ == PD_CMD_SET_SOURCE && tc_arg_[0] >= 0 && tc_arg_[0] <= static_cast<std::int32_t>(PD_SRC_ADAPTIVE)) {
            (void)c.set_source(tc_arg_[0]);   // refused (yaw: ADAPTIVE): the source stays
        } else if (tc_ == PD_CMD_SET_F && tc_arg_[0] >= 0 && tc_arg_[0] < 500000) {
            // the flight's uq32 of the commanded 1e-6 Hz, dequantised
            const std::uint64_t f_uhz = static_cast<std::uint32_t>(tc_arg_[0]);
            const std::uint64_t f_q32 = (f_uhz * 4294967296ull + 500000ull) / 1000000ull;
            c.set_f_ground(std::ldexp(static_cast<double>(f_q32), -32));
            (void)c.set_source(PD_SRC_GROUND);
        } else if (tc_ == PD_CMD_SET_K2 && tc_arg_[k] >= 0 && tc_arg_[k] < 1023 * 256) {
            c.set_k2_fixed(static_cast<double>(tc_arg_[k]) / 256.0);
            (void)c.set_source(PD_SRC_FIXED);
        }
    }
    tc_ = 0u;
    fsw_tlm_t &t = *tlm_;
    pd_tlm_t &m = t.m.hold;
    const bool have = f.n_counts >= static_cast<std::int16_t>(PD_N_SENS);
    // the adapter's sample instants (pd_mission.c): every n_div-th frame by seq from the first, a seq
    // jump a gap of lost samples, a repeated seq stale
    if (seq0_ < 0) {
        seq0_ = f.seq;
        last_seq_ = f.seq - 1;
    }
    const std::int64_t nd = t_.c.n_div;
    const std::int64_t rel = f.seq - seq0_;
    if (rel >= 0 && rel % nd == 0) {
        const bool fresh = f.seq != last_seq_;
        const std::int64_t idx = rel / nd;
        const std::uint32_t gap =
            (last_idx_ >= 0 && idx > last_idx_) ? static_cast<std::uint32_t>(idx - last_idx_ - 1) : 0u;
        std::uint32_t h = 0u;
        for (std::size_t k = 0; k < PD_N_CH; ++k) {
            if ((t_.c.ch_mask & (1u << k)) == 0u) {
                act_[k] = 0;
                continue;
            }
            if (gap > 0u) { ch_[k].note_gap(gap); }
            const std::size_t kb = k + PD_N_CH;
            ref::PdRefIn in;
            in.y_cnt = have ? f.counts[k] : 0;
            in.y_valid = have && fresh && (f.status[k] & bridge::kStatusStale) == 0;
            in.y_sat = have && (f.status[k] & bridge::kStatusSat) != 0;
            in.beta_cnt = have ? f.counts[kb] : 0;
            in.beta_valid = have && fresh && (f.status[kb] & (bridge::kStatusStale | bridge::kStatusSat)) == 0;
            const ref::PdRefOut o = ch_[k].step(in);
            act_[k] = to_cnt(o.m_nm, std::ldexp(1.0, -20));
            h |= o.health;
            pd_ch_tlm_t &c = m.ch[k];
            const ref::PdRefChannel &r = ch_[k];
            c.y_q30 = to_cnt(r.y_last, std::ldexp(1.0, -30));
            c.dy_q30 = to_cnt(r.dy_last, std::ldexp(1.0, -30));
            c.m_q28 = to_cnt(o.m_nm, std::ldexp(1.0, -28));
            c.k2_q22 = static_cast<std::uint32_t>(std::llround(std::ldexp(r.k2(), 22)));
            c.health = o.health;
            c.health_sticky = r.health_sticky;
            c.miss_cnt = r.miss;
            c.stale_cnt = r.stale;
            c.range_rej = r.range_rej;
            c.rate_rej = r.rate_rej;
            c.period_rej = r.period_rej;
            c.trq_sat_cnt = r.trq_sat;
            c.beta_lim_cnt = r.beta_lim;
            c.fest_f_q32 = to_u32(r.fest_f, 32);
            c.fest_word = r.fest_word;
            c.fest_p_a_q30 = to_u32(r.fest_p_a, 30);
            c.fest_att_q16 = to_u32(r.fest_att, 16);
            c.fest_resets = r.fest_resets;
        }
        health_ = h;
        last_idx_ = std::max(idx, last_idx_);
    }
    if (rel >= 0) { last_seq_ = f.seq; }
    m.revision = t_.c.revision;
    t.utime_us = f.utime;
    t.seq = f.seq;
    t.step = step_;
    t.mode = FSW_MODE_HOLD;
    t.host_missed = missed_;
    t.host_rejected = rejected_;
    for (std::size_t k = 0; k < PD_N_CH; ++k) { t.act_cnt[k] = act_[k]; }
    t.mod_health = health_;
    out.n_counts = static_cast<std::int16_t>(PD_N_ACT);
    for (std::size_t k = 0; k < PD_N_CH; ++k) { out.counts[k] = act_[k]; }
    out.fsw_mode = static_cast<std::int32_t>(FSW_MODE_HOLD);
    out.tlm_layout_version = static_cast<std::int32_t>(PD_TLM_LAYOUT);
    out.tlm_len = static_cast<std::int16_t>(fsw_tlm_encode(&t, out.tlm, static_cast<std::uint32_t>(bridge::kMaxTlm)));
    return true;
}

}  // namespace host
