#include "respin/rsp_ref_backend.hpp"

#include <cmath>

namespace host {

namespace {

std::uint32_t sat_u32(std::int32_t v) { return (v < 0) ? 0u : static_cast<std::uint32_t>(v); }

std::int32_t q_cnt(double v, double scale)
{
    const double s = std::round(v * scale);
    if (!(s > -2147483648.0)) { return INT32_MIN; }   // also NaN
    if (s > 2147483647.0) { return INT32_MAX; }
    return static_cast<std::int32_t>(s);
}

}  // namespace

RefRespinBackend::RefRespinBackend(const rsp_params_t &table)
    : p_(table), t_(ref::dequantise(table)), tlm_(new fsw_tlm_t())
{
    rsp_mis_t b{};
    b.p = table;
    b.have_p = true;
    rsp_mis_ranges(&b, rng_);   // the flight adapter's channel map
    (void)reset();
}

bool RefRespinBackend::reset()
{
    step_ = 0;
    law_.reset(t_);
    *tlm_ = fsw_tlm_t{};
    tlm_->mission = FSW_MISSION_RESPIN;
    return true;
}

void RefRespinBackend::host_counters(const bridge::Counters &c)
{
    missed_ = sat_u32(c.missed);
    rejected_ = sat_u32(bridge::rejected_total(c));
}

bool RefRespinBackend::step(const bridge::Frame &f, bridge::StepOutput &out)
{
    out = bridge::StepOutput{};
    ++step_;
    fsw_tlm_t &t = *tlm_;
    rsp_tlm_t &m = t.m.respin;
    ref::RespinRefIn in;
    in.valid = 0u;
    in.sat = 0u;
    for (std::uint32_t i = 0; i < RSP_N_SENS; ++i) {
        const std::int32_t c = (static_cast<int>(i) < f.n_counts) ? f.counts[i] : 0;
        const bool ok = static_cast<int>(i) < f.n_counts && (f.status[i] & bridge::kStatusStale) == 0 &&
                        c >= rng_[i].min && c <= rng_[i].max;
        if (ok) { in.valid |= 1u << i; }
        if ((f.status[i] & bridge::kStatusSat) != 0) { in.sat |= 1u << i; }
        if (i < 3u) {
            in.gyro_cnt[i] = c;
        } else if (i < 6u) {
            in.whl_cnt[i - 3u] = c;
        } else if (i < 10u) {
            in.gimbal_cnt[i - 6u] = c;
        } else {
            in.rotor_cnt[i - 10u] = c;
        }
    }
    const ref::RespinRefOut o = law_.step(in);
    // Telemetry from the double state, rounded to the flight's formats (rsp.h).
    m.phase = static_cast<std::uint8_t>(o.phase);
    m.region = static_cast<std::uint8_t>(o.region);
    m.latched = o.latched ? 1u : 0u;
    m.mode = static_cast<std::uint8_t>(p_.mode);
    m.a_f = o.a_f;
    m.flags = o.health;
    m.xi_abs_q30 = q_cnt(o.xi_abs, 0x1p30);
    m.cphi_q30 = q_cnt(o.cphi, 0x1p30);
    m.g0_q20 = q_cnt(o.g0_nms, 0x1p20);
    m.rho_q30 = q_cnt(o.rho, 0x1p30);
    for (std::size_t i = 0; i < 3; ++i) {
        m.g_q30[i] = q_cnt(o.g[i], 0x1p30);
        m.mcmd_q24[i] = q_cnt(o.mcmd_nm[i], 0x1p24);
        m.mdel_q24[i] = q_cnt(o.mdel_nm[i], 0x1p24);
        m.h_q20[i] = q_cnt(o.h_nms[i], 0x1p20);
    }
    m.t_q32 = static_cast<std::int64_t>(std::llround(o.t_j * 0x1p32));
    m.w_q32 = static_cast<std::int64_t>(std::llround(o.w_j * 0x1p32));
    m.re_q32 = static_cast<std::int64_t>(std::llround(o.re_j * 0x1p32));
    m.done_run = o.done_run;
    m.n_switch = o.n_switch;
    if (o.phase == RSP_PH_RUN && o.valid) {
        std::uint32_t *per[3] = {&m.n_lin, &m.n_mid, &m.n_far};
        ++*per[o.region < 3u ? o.region : 2u];
    }
    if (!o.valid) { ++m.n_gyro_bad; }
    m.health_sticky |= o.health;
    m.revision = p_.revision;
    t.utime_us = f.utime;
    t.seq = f.seq;
    t.step = step_;
    t.mode = FSW_MODE_RESPIN;
    t.host_missed = missed_;
    t.host_rejected = rejected_;
    out.n_counts = static_cast<std::int32_t>(RSP_N_ACT);
    for (std::size_t i = 0; i < 3; ++i) {
        const std::int32_t u = ref::torque_counts(o.whl_torque_nm[i]);
        t.act_cnt[i] = u;
        out.counts[i] = u;
    }
    for (std::size_t k = 0; k < 4; ++k) {
        t.act_cnt[3u + k] = o.gimbal_rate_cnt[k];
        out.counts[3u + k] = o.gimbal_rate_cnt[k];
        m.cmg_rate_cnt[k] = o.gimbal_rate_cnt[k];
    }
    m.cmg_ms_q28 = q_cnt(o.ms, 0x1p28);
    m.cmg_s_q16 = q_cnt(o.s_rate, 0x1p16);
    if ((o.health & RSP_H_SINGULAR) != 0u) { ++m.n_singular; }
    if ((o.health & RSP_H_RATE_LIMITED) != 0u) { ++m.n_rate_limited; }
    t.mod_health = o.health;
    out.fsw_mode = static_cast<std::int32_t>(FSW_MODE_RESPIN);
    out.tlm_layout_version = static_cast<std::int32_t>(RSP_TLM_LAYOUT);
    out.tlm_len = static_cast<std::int16_t>(fsw_tlm_encode(&t, out.tlm, static_cast<std::uint32_t>(bridge::kMaxTlm)));
    return true;
}

}  // namespace host
