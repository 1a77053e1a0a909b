#include "respin/rsp_metrics.hpp"

#include <algorithm>
#include <cmath>

#include "respin/respin_plant.hpp"
#include "respin/respin_section.hpp"
#include "gnc/actuator_cmd_v2_t.hpp"
#include "gnc/sim_truth_t.hpp"

namespace host {

namespace {
const char *const kCounters[] = {"rsp_region", "rsp_mode", "rsp_n_switch", "rsp_n_lin", "rsp_n_mid", "rsp_n_far",
                                 "rsp_n_gyro_bad", "rsp_n_gyro_stale", "rsp_n_whl_bad", "rsp_n_whl_est",
                                 "rsp_n_outlier", "rsp_n_overflow", "rsp_n_clip", "rsp_n_hbound", "rsp_n_singular",
                                 "rsp_n_rate_limited", "rsp_revision"};
}  // namespace

RespinMetrics::RespinMetrics(const sim::Scenario &s)
    : j_y_kgm2_(sim::respin_setup(s).j_kgm2[1])
{
    const TlmLayout &l = tlm_layout(iface_mission("RESPIN"));
    i_health_ = l.at("rsp_health");
    i_af_ = l.at("rsp_a_f");
    i_re_ = l.at("rsp_r_e");
}

void RespinMetrics::on_truth(const gnc::sim_truth_t &t)
{
    using T = sim::RespinPlant;
    const double ts = static_cast<double>(t.utime) * 1e-6;
    const double w[3] = {t.state[T::kTruthW], t.state[T::kTruthW + 1], t.state[T::kTruthW + 2]};
    const double h[3] = {t.state[T::kTruthH], t.state[T::kTruthH + 1], t.state[T::kTruthH + 2]};
    const double g[3] = {t.state[T::kTruthG], t.state[T::kTruthG + 1], t.state[T::kTruthG + 2]};
    const double gn = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
    if (g0_true_ < 0.0) { g0_true_ = gn; }
    if (g0_true_ > 0.0) { g_rel_err_max = std::max(g_rel_err_max, std::fabs(gn - g0_true_) / g0_true_); }
    // Before the flight's first telemetry the target is the nearer of +-e_y (NEAREST's choice).
    const double af = (a_f_ != 0) ? static_cast<double>(a_f_) : ((g[1] >= 0.0) ? 1.0 : -1.0);
    const double xi = (gn > 0.0) ? std::sqrt(g[0] * g[0] + g[2] * g[2]) / gn : 1.0;
    const double cphi = (gn > 0.0) ? af * g[1] / gn : 0.0;
    const bool conv = xi < kXiDone && cphi > 0.0;
    if (conv && t_first_xi_s < 0.0) { t_first_xi_s = ts; }
    if (conv && !conv_run_) { t_settle_s = ts; }
    if (!conv) { t_settle_s = -1.0; }
    conv_run_ = conv;
    xi_final = xi;
    cphi_final = cphi;
    const double wf = gn / j_y_kgm2_;
    w_err_final_radps = std::sqrt(w[0] * w[0] + (w[1] - af * wf) * (w[1] - af * wf) + w[2] * w[2]);
    const double hn = std::sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
    h_final_nms = hn;
    h_peak_nms = std::max(h_peak_nms, hn);
    for (double hi : h) { h_axis_peak_nms = std::max(h_axis_peak_nms, std::fabs(hi)); }
    if (ts <= kEarlyS + 1e-9 && gn > 0.0) {
        early.push_back(Pt{ts, {g[0] / gn, g[1] / gn, g[2] / gn}, {h[0], h[1], h[2]}});
    }
    for (std::size_t k = 0; k < 3u; ++k) {
        q_peak_sqrtkgm[k] = std::max(q_peak_sqrtkgm[k], std::fabs(t.extra[T::kExtraQm + k]));
    }
    t_end_j = t.state[T::kTruthT];
    e_check_max_j = std::max(e_check_max_j, std::fabs(t.state[T::kTruthEcheck] - t.state[T::kTruthT]));
    t_last_s_ = ts;
    ++truth_n;
}

void RespinMetrics::on_cmd(const gnc::actuator_cmd_v2_t &c)
{
    for (int i = 0; i < c.n_counts && i < 3; ++i) {
        cmd_peak_nm = std::max(cmd_peak_nm, std::fabs(c.counts[i] * sim::kRespinTorqueLsbNm));
    }
    for (int i = 3; i < c.n_counts && i < 7; ++i) {
        gimbal_rate_peak_radps = std::max(gimbal_rate_peak_radps, std::fabs(c.counts[i] * 0x1p-16));
    }
}

void RespinMetrics::on_tlm(const std::vector<std::int64_t> &v, double t_s)
{
    const auto h = static_cast<std::uint32_t>(v[i_health_]);
    health_or |= h;
    if (t_done_s < 0.0 && (h & RSP_H_DONE) != 0u) { t_done_s = t_s; }
    if (v[i_af_] != 0) {
        a_f_ = v[i_af_];
        a_f_final = a_f_;
    }
    const double re = static_cast<double>(v[i_re_]) * 0x1p-32;
    re_abs_max_j = std::max(re_abs_max_j, std::fabs(re));
    re_min_j = std::min(re_min_j, re);
    re_max_j = std::max(re_max_j, re);
    last_ = v;
}

void RespinMetrics::summary(Summary &s) const
{
    const iface::Mission &m = iface_mission("RESPIN");
    s.add_int("converged", t_settle_s >= 0.0 ? 1 : 0);
    // A4 / A7 count convergence among runs with g0 >= g_min; below it the module commands zero.
    const bool low = (health_or & RSP_H_LOW_MOMENTUM) != 0u;
    s.add_int("low_momentum", low ? 1 : 0);
    s.add_int("converged_or_low", (t_settle_s >= 0.0 || low) ? 1 : 0);
    s.add("g0_true_nms", g0_true_, "%.4f");
    s.add("t_first_xi_s", t_first_xi_s, "%.1f");
    s.add("t_settle_s", t_settle_s, "%.1f");
    s.add("xi_final", xi_final, "%.3e");
    s.add("cphi_final", cphi_final, "%.6f");
    s.add_int("a_f_final", a_f_final);
    s.add("w_err_final_radps", w_err_final_radps, "%.3e");
    s.add("h_final_nms", h_final_nms, "%.3e");
    s.add("h_axis_peak_nms", h_axis_peak_nms, "%.6f");
    s.add("h_peak_nms", h_peak_nms, "%.4f");
    s.add("t_end_j", t_end_j, "%.5f");
    s.add("e_check_max_j", e_check_max_j, "%.3e");
    s.add("g_rel_err_max", g_rel_err_max, "%.3e");
    s.add("re_abs_max_j", re_abs_max_j, "%.4f");
    s.add("re_min_j", re_min_j, "%.4f");
    s.add("re_max_j", re_max_j, "%.4f");
    s.add("q1_peak_sqrtkgm", q_peak_sqrtkgm[0], "%.3e");
    s.add("q2_peak_sqrtkgm", q_peak_sqrtkgm[1], "%.3e");
    s.add("q3_peak_sqrtkgm", q_peak_sqrtkgm[2], "%.3e");
    s.add("t_done_s", t_done_s, "%.1f");
    s.add("cmd_peak_nm", cmd_peak_nm, "%.6f");
    s.add("gimbal_rate_peak_radps", gimbal_rate_peak_radps, "%.6f");
    if (!last_.empty()) {
        const TlmLayout &l = tlm_layout(m);
        for (const char *k : kCounters) {
            s.add_int(std::string("fsw_") + k, last_[l.at(k)]);
        }
    }
    s.add_hex("rsp_health_sticky", health_or);
    s.add_str("rsp_health_sticky_names", bits_str(health_or, m.health, m.n_health));
}

}  // namespace host
