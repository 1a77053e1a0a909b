#include "pd/pd_ref_backend.hpp"

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

}  // namespace

RefPdBackend::RefPdBackend(const pd_params_t &table)
    : p_(table), t_(ref::dequantise(table)), tlm_(new fsw_tlm_t())
{
    pd_mis_t b{};
    b.p = table;
    b.have_p = true;
    pd_mis_ranges(&b, &rng_);   // the flight adapter's channel map
    (void)reset();
}

bool RefPdBackend::reset()
{
    step_ = 0;
    limited_run_ = 0;
    *tlm_ = fsw_tlm_t{};
    tlm_->mission = FSW_MISSION_HOLD;
    return true;
}

void RefPdBackend::host_counters(const bridge::Counters &c)
{
    missed_ = sat_u32(c.missed);
    rejected_ = sat_u32(bridge::rejected_total(c));
}

bool RefPdBackend::step(const bridge::Frame &f, bridge::StepOutput &out)
{
    out = bridge::StepOutput{};
    ++step_;
    fsw_tlm_t &t = *tlm_;
    pd_tlm_t &m = t.m.hold;
    const bool valid = f.n_counts >= 1 && (f.status[0] & (bridge::kStatusStale | bridge::kStatusSat)) == 0 &&
                       f.counts[0] >= rng_.min && f.counts[0] <= rng_.max;
    std::uint32_t h = 0u;
    std::int32_t u = 0;
    if (valid) {
        const ref::PdOut o = ref::pd_law(t_, static_cast<double>(f.counts[0]) * sim::kPdRateLsbRadps);
        u = to_cnt(o.tau_nm, sim::kPdTorqueLsbNm);
        limited_run_ = o.limited ? limited_run_ + 1u : 0u;
        if (o.limited) { h |= PD_H_CMD_LIMITED; ++m.n_limited; }
        m.rate_cnt = f.counts[0];
    } else {
        h |= PD_H_MEAS_SKIP;
        ++m.n_skip;
        limited_run_ = 0u;
        m.rate_cnt = 0;
    }
    if (limited_run_ >= p_.n_sat) { h |= PD_H_CMD_LIMIT_PERSIST; }
    m.u_cnt = u;
    m.health_sticky |= h;
    m.revision = p_.revision;
    t.utime_us = f.utime;
    t.seq = f.seq;
    t.step = step_;
    t.mode = FSW_MODE_HOLD;
    t.host_missed = missed_;
    t.host_rejected = rejected_;
    t.act_cnt[0] = u;
    t.mod_health = h;
    out.n_counts = 1;
    out.counts[0] = u;
    out.fsw_mode = static_cast<std::int32_t>(FSW_MODE_HOLD);
    out.tlm_layout_version = static_cast<std::int32_t>(PD_TLM_LAYOUT);
    out.tlm_len = static_cast<std::int16_t>(fsw_tlm_encode(&t, out.tlm, static_cast<std::uint32_t>(bridge::kMaxTlm)));
    return true;
}

}  // namespace host
