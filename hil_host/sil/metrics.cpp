#include "metrics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "channels.hpp"
#include "tlm_rdv_fields.hpp"
#include "gnc/actuator_cmd_t.hpp"
#include "gnc/fsw_tlm_frame_t.hpp"
#include "gnc/sim_truth_t.hpp"
#include "gnc/table_ack_t.hpp"

extern "C" {
#include "fsw_codec.h"
#include "fsw_exec.h"
}

namespace sil {

namespace {
constexpr double kDeg = 3.14159265358979323846 / 180.0;
constexpr double kActLsb = 1.0 / 1048576.0;   // gimbal command LSB 2^-20 rad/s (obs tables)

// Field names in wire order (fsw/app/fsw_tlm_formats.json); types: 'q' i64, 'u' u32, 'i' i32.
struct F { const char *name; char t; };
const F kTlm[] = {
    {"utime_us", 'q'}, {"seq", 'q'}, {"step", 'u'}, {"mode", 'u'}, {"health", 'u'}, {"health_sticky", 'u'},
    {"n_chan_rej", 'u'}, {"n_stale_steps", 'u'}, {"n_in_bad", 'u'}, {"n_tbl_acc", 'u'}, {"n_tbl_rej", 'u'},
    {"tbl_reason", 'u'}, {"tbl_revision", 'u'}, {"n_scrub_err", 'u'}, {"n_safe", 'u'}, {"n_mode_rej", 'u'},
    {"host_missed", 'u'}, {"host_rejected", 'u'}, {"act_cnt_y", 'i'}, {"act_cnt_z", 'i'}, {"obs_health", 'u'},
    {"obs_x_wy", 'i'}, {"obs_x_wz", 'i'}, {"obs_x_muy", 'i'}, {"obs_x_mudoty", 'i'}, {"obs_x_muz", 'i'},
    {"obs_x_mudotz", 'i'}, {"obs_kappa", 'i'}, {"obs_u_y", 'i'}, {"obs_u_z", 'i'}, {"obs_e_y", 'i'},
    {"obs_e_z", 'i'}, {"obs_d2_y", 'i'}, {"obs_d2_z", 'i'}, {"obs_pkk", 'i'}, {"obs_health_sticky", 'u'},
    {"obs_n_skip", 'u'}, {"obs_n_gap", 'u'}, {"obs_n_lost", 'u'}, {"obs_n_reinit", 'u'}, {"obs_n_clamp_lo", 'u'},
    {"obs_n_clamp_hi", 'u'}, {"obs_n_limited", 'u'}, {"obs_n_innov", 'u'}, {"obs_n_cov_clip", 'u'},
    {"obs_revision", 'u'},
};
}  // namespace

namespace {

// One telemetry layout as the tap reads it: names and wire types in order, and the index of a
// name (built once).
struct TlmLayout {
    std::vector<std::string> names;
    std::vector<char> types;                      // 'q' i64, 'u' u32, 'i' i32, 'h' u16, 'b' u8
    std::size_t bytes = 0;
    std::map<std::string, std::size_t> idx;
    std::size_t i_health = 0, i_obs_health = 0, i_obs_kappa = 0;   // read on every message
    std::size_t at(const char *n) const
    {
        const auto it = idx.find(n);
        return (it == idx.end()) ? names.size() : it->second;
    }
};

TlmLayout make_layout(const F *f, std::size_t n, std::size_t bytes)
{
    TlmLayout l;
    for (std::size_t i = 0; i < n; ++i) {
        l.names.emplace_back(f[i].name);
        l.types.push_back(f[i].t);
        l.idx[f[i].name] = i;
    }
    l.bytes = bytes;
    l.i_health = l.at("health");
    l.i_obs_health = l.at("obs_health");
    l.i_obs_kappa = l.at("obs_kappa");
    return l;
}

const TlmLayout &layout_v1()
{
    static const TlmLayout l = make_layout(kTlm, sizeof kTlm / sizeof kTlm[0], FSW_TLM_BYTES);
    return l;
}

const TlmLayout &layout_rdv()
{
    static const TlmLayout l = [] {
        TlmLayout r;
        for (const TlmField &f : kTlmRdv) {
            r.idx[f.name] = r.names.size();
            r.names.emplace_back(f.name);
            r.types.push_back(f.t);
        }
        r.bytes = kTlmRdvBytes;
        r.i_health = r.at("health");
        return r;
    }();
    return l;
}

// Raw values of one encoded fsw_tlm_t in its layout (chosen by length); nullptr when the
// length matches no layout or the bytes do not decode exactly.
const TlmLayout *decode_values(const std::uint8_t *buf, std::size_t len, std::vector<std::int64_t> &v)
{
    const TlmLayout *l = (len == kTlmRdvBytes) ? &layout_rdv() : ((len == FSW_TLM_BYTES) ? &layout_v1() : nullptr);
    if (l == nullptr) {
        return nullptr;
    }
    fsw_rd_t r;
    fsw_rd_init(&r, buf, static_cast<std::uint32_t>(len));
    v.resize(l->types.size());
    for (std::size_t i = 0; i < l->types.size(); ++i) {
        switch (l->types[i]) {
        case 'q': v[i] = fsw_rd_i64(&r); break;
        case 'u': v[i] = static_cast<std::int64_t>(fsw_rd_u32(&r)); break;
        case 'i': v[i] = fsw_rd_i32(&r); break;
        case 'h': v[i] = static_cast<std::int64_t>(fsw_rd_u16(&r)); break;
        default: v[i] = static_cast<std::int64_t>(fsw_rd_u8(&r)); break;
        }
    }
    return (!r.err && r.pos == len) ? l : nullptr;
}

}  // namespace

bool decode_fsw_tlm(const std::uint8_t *buf, std::size_t len, std::map<std::string, std::int64_t> &out)
{
    std::vector<std::int64_t> v;
    const TlmLayout *l = decode_values(buf, len, v);
    if (l == nullptr) {
        return false;
    }
    for (std::size_t i = 0; i < v.size(); ++i) {
        out[l->names[i]] = v[i];
    }
    return true;
}

MetricsTap::MetricsTap(lcm_t *lcm, double tail_from_s) : lcm_(lcm), tail_from_s_(tail_from_s)
{
    subs_[0] = lcm_subscribe(lcm_, kChTruth, &MetricsTap::on_truth, this);
    subs_[1] = lcm_subscribe(lcm_, kChCmd, &MetricsTap::on_cmd, this);
    subs_[2] = lcm_subscribe(lcm_, kChTlm, &MetricsTap::on_tlm, this);
    subs_[3] = lcm_subscribe(lcm_, kChTblAck, &MetricsTap::on_ack, this);
}

MetricsTap::~MetricsTap()
{
    for (auto *s : subs_) {
        if (s != nullptr) { lcm_unsubscribe(lcm_, s); }
    }
}

void MetricsTap::set_rendezvous(std::int64_t t0_step, std::int64_t tf_step)
{
    m_.rdv = true;
    m_.t0_step = t0_step;
    m_.tf_step = tf_step;
}

namespace {

// Truth of the CW plant (sim/impulse/cw_sil_plant.hpp): state[0..5] x, x', y, y', z, z';
// state[6..11] delta-v per thruster; state[12] interlock violations.
void rdv_truth(Metrics &m, const gnc::sim_truth_t &t)
{
    if (t.seq == m.tf_step) {
        m.at_tf = true;
        m.miss_r_m = std::sqrt(t.state[0] * t.state[0] + t.state[2] * t.state[2] + t.state[4] * t.state[4]);
        m.miss_v_mps = std::sqrt(t.state[1] * t.state[1] + t.state[3] * t.state[3] + t.state[5] * t.state[5]);
        for (int a = 0; a < 3; ++a) { m.miss_xyz_m[a] = t.state[2 * a]; }
    }
    m.dv_used_mps = 0.0;
    for (int j = 0; j < 6; ++j) {
        m.dv_thr_mps[j] = t.state[6 + j];
        m.dv_used_mps += t.state[6 + j];
    }
    m.violations = t.state[12];
    m.omega_radps = t.extra[0];
    m.a_nom_mps2 = t.extra[1];
}

const char *const kImpFlags[] = {"INFEASIBLE", "NO_SOLUTION", "MARGINAL", "NAV_STALE", "THRUST_LEVEL",
                                 "EXPECTED_MISS", "INTERLOCK"};   // IMP_H_* bits 12..18
const char *const kImpModes[] = {"IDLE", "PLANNING", "ARMED", "FIRING", "FINAL", "DONE",
                                 "INFEASIBLE_MODE", "NO_SOLUTION_MODE", "ABORTED", "FAULT"};

// Indices of the RENDEZVOUS fields the metrics read every step (looked up once).
struct RdvIdx {
    std::size_t health, mode, iters_xy, iters_z, t1[3], t2[3], on2[3];
};

const RdvIdx &rdv_idx()
{
    static const RdvIdx ix = [] {
        const TlmLayout &l = layout_rdv();
        RdvIdx r{};
        r.health = l.at("imp_health");
        r.mode = l.at("imp_mode");
        r.iters_xy = l.at("imp_iters_xy");
        r.iters_z = l.at("imp_iters_z");
        const char *ax[3] = {"x", "y", "z"};
        for (int a = 0; a < 3; ++a) {
            r.t1[a] = l.at((std::string("imp_t1_") + ax[a]).c_str());
            r.t2[a] = l.at((std::string("imp_t2_") + ax[a]).c_str());
            r.on2[a] = l.at((std::string("imp_on2_step_") + ax[a]).c_str());
        }
        return r;
    }();
    return ix;
}

void rdv_tlm(Metrics &m, const TlmLayout &, const std::vector<std::int64_t> &v, double ts)
{
    const RdvIdx &ix = rdv_idx();
    const auto h = static_cast<std::uint32_t>(v[ix.health]);
    m.imp_health_sticky |= h;
    for (std::uint32_t b = 0; b < 7u; ++b) {
        if ((h & (IMP_H_INFEASIBLE << b)) != 0u && m.t_first.count(kImpFlags[b]) == 0u) {
            m.t_first[kImpFlags[b]] = ts;
        }
    }
    if ((h & IMP_H_STUCK_OFF) != 0u && m.t_first.count("STUCK_OFF") == 0u) { m.t_first["STUCK_OFF"] = ts; }
    if ((h & IMP_H_STUCK_ON) != 0u && m.t_first.count("STUCK_ON") == 0u) { m.t_first["STUCK_ON"] = ts; }
    m.max_iters_xy = std::max(m.max_iters_xy, static_cast<std::uint32_t>(v[ix.iters_xy]));
    m.max_iters_z = std::max(m.max_iters_z, static_cast<std::uint32_t>(v[ix.iters_z]));
    const auto mode = static_cast<std::uint32_t>(v[ix.mode]);
    // The START plan's delta-v: a_nom * sum over the axes of (T1 + T - T2), from the first
    // telemetry that shows the committed plan (ARMED), T = t_f - t0.
    if (mode == IMP_MODE_ARMED && m.plan_dv_mps < 0.0 && m.omega_radps > 0.0 && m.t0_step >= 0) {
        const double dt = (m.truth_n > 1) ? (m.t_last_s / static_cast<double>(m.truth_n - 1)) : 0.0;
        const double T = static_cast<double>(m.tf_step - m.t0_step) * dt;
        double s = 0.0;
        for (int a = 0; a < 3; ++a) {
            const double t1 = static_cast<double>(v[ix.t1[a]]) / 536870912.0 / m.omega_radps;
            const double t2 = static_cast<double>(v[ix.t2[a]]) / 536870912.0 / m.omega_radps;
            s += t1 + T - t2;
            const std::int64_t k2 = v[ix.on2[a]];
            if (m.burn2_step < 0 || k2 < m.burn2_step) { m.burn2_step = k2; }
        }
        m.plan_dv_mps = m.a_nom_mps2 * s;
    }
    if (mode < 10u) {
        m.imp_modes_seen |= 1u << mode;
        if (m.t_first.count(kImpModes[mode]) == 0u) { m.t_first[kImpModes[mode]] = ts; }
    }
    m.imp_mode_final = mode;
}

}  // namespace

void MetricsTap::on_truth(const lcm_recv_buf_t *rb, const char *, void *user)
{
    auto *self = static_cast<MetricsTap *>(user);
    gnc::sim_truth_t t;
    if (t.decode(rb->data, 0, static_cast<int>(rb->data_size)) < 0) {
        return;
    }
    Metrics &m = self->m_;
    if (m.rdv) {
        rdv_truth(m, t);
        m.t_last_s = static_cast<double>(t.utime) * 1e-6;
        ++m.truth_n;
        return;
    }
    const double ts = static_cast<double>(t.utime) * 1e-6;
    if (m.truth_n == 1) {
        m.h_s = ts - m.t_last_s;
    }
    const double wy = t.state[0] / kDeg, wz = t.state[1] / kDeg;
    const double mu = std::fmax(std::fabs(t.state[2]), std::fabs(t.state[4])) / kDeg;
    const double wn = std::hypot(wy, wz);
    const double h = (m.truth_n >= 1) ? m.h_s : 0.0;
    if (wn >= 0.01) { m.t_s = ts + h; }
    if (wn >= 0.01 || mu >= 0.01) { m.t_s_plus = ts + h; }
    m.peak_w_degs = std::fmax(m.peak_w_degs, std::fmax(std::fabs(wy), std::fabs(wz)));
    m.peak_mu_deg = std::fmax(m.peak_mu_deg, mu);
    m.w_final_degs = wn;
    if (ts >= self->tail_from_s_) {
        m.max_w_tail_degs = std::fmax(m.max_w_tail_degs, wn);
        m.max_mu_tail_deg = std::fmax(m.max_mu_tail_deg, mu);
    }
    m.k_true = t.extra[0];
    m.t_last_s = ts;
    ++m.truth_n;
}

void MetricsTap::on_cmd(const lcm_recv_buf_t *rb, const char *, void *user)
{
    auto *self = static_cast<MetricsTap *>(user);
    gnc::actuator_cmd_t c;
    if (c.decode(rb->data, 0, static_cast<int>(rb->data_size)) < 0) {
        return;
    }
    if (self->m_.rdv) {
        if (c.n_counts > 12 && c.counts[12] != 0) {
            ++self->m_.thr_on_steps;
            if (self->m_.t_first.count("ABORTED") != 0u) { ++self->m_.on_after_abort; }
        }
    } else {
        for (int i = 0; i < 2 && i < c.n_counts; ++i) {
            self->m_.peak_bdot_degs = std::fmax(self->m_.peak_bdot_degs, std::fabs(c.counts[i] * kActLsb) / kDeg);
        }
    }
    ++self->m_.cmd_n;
}

void MetricsTap::on_tlm(const lcm_recv_buf_t *rb, const char *, void *user)
{
    auto *self = static_cast<MetricsTap *>(user);
    gnc::fsw_tlm_frame_t f;
    if (f.decode(rb->data, 0, static_cast<int>(rb->data_size)) < 0 || f.tlm_len < 0 || f.tlm_len > 512) {
        ++self->m_.tlm_bad;
        return;
    }
    Metrics &m = self->m_;
    const TlmLayout *l = decode_values(f.tlm, static_cast<std::size_t>(f.tlm_len), self->last_);
    if (l == nullptr) {
        ++m.tlm_bad;
        return;
    }
    self->last_layout_ = l;
    const std::vector<std::int64_t> &v = self->last_;
    const double ts = static_cast<double>(f.utime) * 1e-6;
    const auto health = static_cast<std::uint32_t>(v[l->i_health]);
    if (m.rdv) {
        rdv_tlm(m, *l, v, ts);
    } else {
        const auto oh = static_cast<std::uint32_t>(v[l->i_obs_health]);
        m.k_hat_final = 0.01 * static_cast<double>(v[l->i_obs_kappa]) / 268435456.0;
        m.obs_health_sticky |= oh;
        if (m.t_persist_s < 0.0 && (oh & OBS_H_CMD_LIMIT_PERSIST) != 0u) {
            m.t_persist_s = ts;
        }
    }
    if (m.t_first_fx_s < 0.0 && (health & 0xFFu) != 0u) {
        m.t_first_fx_s = ts;
        m.first_fx_bits = health & 0xFFu;
    }
    m.bridge = {{"dups", f.dups}, {"stale", f.stale}, {"gaps", f.gaps}, {"rejected", f.rejected},
                {"nonfinite_rej", f.nonfinite_rej}, {"range_rej", f.range_rej}, {"missed", f.missed},
                {"table_rej", f.table_rej}};
    ++m.tlm_n;
}

void MetricsTap::on_ack(const lcm_recv_buf_t *rb, const char *, void *user)
{
    auto *self = static_cast<MetricsTap *>(user);
    gnc::table_ack_t a;
    if (a.decode(rb->data, 0, static_cast<int>(rb->data_size)) < 0) {
        return;
    }
    self->m_.last_ack_result = a.result;
    self->m_.last_ack_reason = a.reason;
    ++self->m_.ack_n;
}

const Metrics &MetricsTap::m() const
{
    if (last_layout_ != nullptr) {
        const auto *l = static_cast<const TlmLayout *>(last_layout_);
        m_.tlm.clear();
        for (std::size_t i = 0; i < last_.size(); ++i) {
            m_.tlm[l->names[i]] = last_[i];
        }
    }
    return m_;
}

std::string MetricsTap::summary() const
{
    (void)m();
    std::ostringstream o;
    char b[160];
    auto line = [&](const char *k, double v, const char *fmt) {
        std::snprintf(b, sizeof b, fmt, v);
        o << k << " = " << b << "\n";
    };
    if (m_.rdv) {
        line("miss_r_m", m_.miss_r_m, "%.4f");
        line("miss_v_mps", m_.miss_v_mps, "%.6f");
        line("dv_used_mps", m_.dv_used_mps, "%.4f");
        line("plan_dv_mps", m_.plan_dv_mps, "%.4f");
        line("first_burn2_step", static_cast<double>(m_.burn2_step), "%.0f");
        line("max_iters_xy", m_.max_iters_xy, "%.0f");
        line("max_iters_z", m_.max_iters_z, "%.0f");
        line("interlock_violations", m_.violations, "%.0f");
        o << "t_f_step = " << m_.tf_step << "\nthruster_on_steps = " << m_.thr_on_steps << "\nsteps_truth = " << m_.truth_n
          << "\nsteps_tlm = " << m_.tlm_n << "\n";
        for (const auto &kv : m_.bridge) { o << "bridge_" << kv.first << " = " << kv.second << "\n"; }
        for (const char *k : {"mode", "n_chan_rej", "n_tc", "n_tc_rej", "n_safe", "host_missed", "imp_mode", "imp_plans",
                              "imp_plans_failed", "imp_plans_late", "imp_plans_skipped", "imp_plans_kept", "imp_cmd_rej",
                              "imp_rej_reason", "imp_nav_rej", "imp_cal_rej", "imp_iters_xy", "imp_iters_z",
                              "imp_how_xy", "imp_how_z", "imp_pattern", "imp_fres_xy", "imp_fres_z", "imp_stuck_j"}) {
            auto it = m_.tlm.find(k);
            o << "fsw_" << k << " = " << (it == m_.tlm.end() ? 0 : it->second) << "\n";
        }
        std::snprintf(b, sizeof b, "0x%08x", m_.imp_health_sticky);
        o << "imp_health_sticky = " << b << "\n";
        for (const auto &kv : m_.t_first) {
            std::snprintf(b, sizeof b, "%.1f", kv.second);
            o << "t_first_" << kv.first << " = " << b << "\n";
        }
        return o.str();
    }
    line("t_s_s", m_.t_s, "%.2f");
    line("t_s_plus_s", m_.t_s_plus, "%.2f");
    line("k_hat_final_per_s2", m_.k_hat_final, "%.6f");
    line("k_true_per_s2", m_.k_true, "%.6f");
    line("peak_bdot_degps", m_.peak_bdot_degs, "%.3f");
    line("peak_mu_deg", m_.peak_mu_deg, "%.4f");
    line("peak_w_degps", m_.peak_w_degs, "%.4f");
    line("w_final_degps", m_.w_final_degs, "%.3g");
    line("max_w_tail_degps", m_.max_w_tail_degs, "%.3g");
    line("max_mu_tail_deg", m_.max_mu_tail_deg, "%.3g");
    line("t_cmd_limit_persist_s", m_.t_persist_s, "%.2f");
    line("t_first_fx_status_s", m_.t_first_fx_s, "%.2f");
    line("first_fx_status_bits", static_cast<double>(m_.first_fx_bits), "%.0f");
    o << "steps_truth = " << m_.truth_n << "\nsteps_tlm = " << m_.tlm_n << "\n";
    for (const auto &kv : m_.bridge) { o << "bridge_" << kv.first << " = " << kv.second << "\n"; }
    for (const char *k : {"mode", "n_chan_rej", "n_stale_steps", "n_tbl_acc", "n_tbl_rej", "tbl_revision", "n_safe",
                          "host_missed", "obs_n_skip", "obs_n_gap", "obs_n_lost", "obs_n_reinit", "obs_n_limited",
                          "obs_n_clamp_lo", "obs_n_clamp_hi", "obs_n_innov", "obs_n_cov_clip"}) {
        auto it = m_.tlm.find(k);
        o << "fsw_" << k << " = " << (it == m_.tlm.end() ? 0 : it->second) << "\n";
    }
    auto hs = m_.tlm.find("health_sticky");
    std::snprintf(b, sizeof b, "0x%08llx", static_cast<unsigned long long>(hs == m_.tlm.end() ? 0 : hs->second));
    o << "fsw_health_sticky = " << b << "\n";
    std::snprintf(b, sizeof b, "0x%08x", m_.obs_health_sticky);
    o << "obs_health_sticky = " << b << "\n";
    return o.str();
}

}  // namespace sil
