#include "pd/pd_metrics.hpp"

#include <cmath>
#include <string>

#include "pd/pd_plant.hpp"
#include "pd/pd_section.hpp"
#include "gnc/actuator_cmd_v2_t.hpp"
#include "gnc/sim_truth_t.hpp"

namespace host {

namespace {
const char *const kCh[] = {"yaw", "roll", "pitch"};
const char *const kCounters[] = {"miss", "stale", "range_rej", "rate_rej", "period_rej", "trq_sat", "beta_lim"};
constexpr double kTrqLsb = 1.0 / 1048576.0;   // actuator count, 2^-20 N m
}  // namespace

PdMetrics::PdMetrics(const sim::Scenario &s)
{
    const TlmLayout &l = tlm_layout(iface_mission("HOLD"));
    for (std::size_t k = 0; k < 3; ++k) {
        const std::string c = std::string("pd_") + kCh[k];
        i_health_[k] = l.at(c + "_health");
        i_k2_[k] = l.at(c + "_k2");
        i_dy_[k] = l.at(c + "_dy");
        i_ff_[k] = l.at(c + "_fest_f");
        i_fw_[k] = l.at(c + "_fest");
        i_fr_[k] = l.at(c + "_fest_resets");
    }
    ty_s = s.h_s();
    const sim::PdSetup &b = s.mission_part<sim::PdScenario>().body;
    f0_hz_ = b.f_hz;
    for (const sim::PdFStep &st : b.f_steps) { f_steps_.emplace_back(st.t_s, st.f_hz); }
}

double PdMetrics::f_true_at(double t_s) const
{
    double f = f0_hz_;
    for (const auto &st : f_steps_) {
        if (st.first <= t_s) { f = st.second; }
    }
    return f;
}

double PdMetrics::fest_max_confident_ratio(std::size_t k) const
{
    double r = 0.0;
    for (std::size_t i = 0; i < fest_f[k].size(); ++i) {
        if ((fest_word[k][i] & 4u) != 0u) { r = std::fmax(r, fest_f[k][i] / f_true_at(t_tlm[i])); }
    }
    return r;
}

void PdMetrics::on_truth(const gnc::sim_truth_t &tr)
{
    const double ts = static_cast<double>(tr.utime) * 1e-6;
    t.push_back(ts);
    for (std::size_t k = 0; k < 3; ++k) {
        const double xk = tr.state[sim::PdPlant::kTruthX + k];
        x[k].push_back(xk);
        peak_beta[k] = std::fmax(peak_beta[k], std::fabs(tr.state[sim::PdPlant::kTruthBeta + k]));
        if (ts >= kLateS) { peak_x_late[k] = std::fmax(peak_x_late[k], std::fabs(xk)); }
    }
    if (tr.state[sim::PdPlant::kTruthLinValid] < 0.5) { lin_invalid = true; }
}

void PdMetrics::on_cmd(const gnc::actuator_cmd_v2_t &c)
{
    for (std::size_t k = 0; k < 3 && static_cast<std::int32_t>(k) < c.n_counts; ++k) {
        peak_m[k] = std::fmax(peak_m[k], std::fabs(c.counts[k] * kTrqLsb));
    }
}

void PdMetrics::on_tlm(const std::vector<std::int64_t> &v, double t_s)
{
    t_tlm.push_back(t_s);
    for (std::size_t k = 0; k < 3; ++k) {
        fest_f[k].push_back(std::ldexp(static_cast<double>(v[i_ff_[k]]), -32));
        fest_word[k].push_back(static_cast<std::uint32_t>(v[i_fw_[k]]));
        fest_resets[k] = static_cast<std::uint32_t>(v[i_fr_[k]]);
        health_or[k] |= static_cast<std::uint32_t>(v[i_health_[k]]);
        const auto k2 = static_cast<std::uint32_t>(v[i_k2_[k]]);
        if (have_tlm_ && k2 != k2_last_[k]) { ++k2_changes[k]; }
        k2_last_[k] = k2;
        k2_final[k] = std::ldexp(static_cast<double>(k2), -22);
        k2_series[k].push_back(k2_final[k]);
        peak_rate[k] = std::fmax(peak_rate[k], std::fabs(std::ldexp(static_cast<double>(v[i_dy_[k]]), -30)) / ty_s);
    }
    have_tlm_ = true;
    last_ = v;
}

double PdMetrics::fest_f_at(std::size_t k, double t_s) const
{
    double f = -1.0;
    for (std::size_t i = 0; i < t_tlm.size() && t_tlm[i] <= t_s + 1e-6; ++i) { f = fest_f[k][i]; }
    return f;
}

double PdMetrics::fest_max_confident(std::size_t k) const
{
    double f = 0.0;
    for (std::size_t i = 0; i < fest_f[k].size(); ++i) {
        if ((fest_word[k][i] & 4u) != 0u) { f = std::fmax(f, fest_f[k][i]); }
    }
    return f;
}

double PdMetrics::t_settle(std::size_t k) const
{
    const std::vector<double> &xs = x[k];
    if (xs.empty()) { return -1.0; }
    if (!(std::fabs(xs.back()) < kBandRad)) { return -1.0; }
    for (std::size_t i = xs.size(); i-- > 0;) {
        if (!(std::fabs(xs[i]) < kBandRad)) { return t[i + 1]; }
    }
    return 0.0;
}

void PdMetrics::summary(Summary &s) const
{
    const iface::Mission &m = iface_mission("HOLD");
    const TlmLayout &l = tlm_layout(m);
    for (std::size_t k = 0; k < 3; ++k) {
        const std::string c = kCh[k];
        s.add("t_settle_" + c + "_s", t_settle(k), "%.2f");
        s.add("peak_m_" + c + "_nm", peak_m[k], "%.6f");
        s.add("peak_rate_" + c + "_radps", peak_rate[k], "%.6g");
        s.add("peak_beta_" + c + "_rad", peak_beta[k], "%.6g");
        s.add("peak_x_late_" + c + "_rad", peak_x_late[k], "%.6g");
        s.add("k2_final_" + c + "_s", k2_final[k], "%.4f");
        // the estimator (spec 40 R3, R5): f_hat at 300 s and 1 200 s, its error against the plant's
        // f_min then, the largest confident f_hat / f, the FAULT count (f_hat is 0 unless ADAPTIVE)
        for (const double ts : {300.0, 1200.0}) {
            const double fh = fest_f_at(k, ts);
            const std::string at = std::to_string(static_cast<int>(ts));
            s.add("fest_f" + at + "_" + c + "_hz", fh, "%.7g");
            s.add("fest_err" + at + "_" + c, std::fabs(fh / f_true_at(ts) - 1.0), "%.6g");
        }
        s.add("fest_conf_ratio_max_" + c, fest_max_confident_ratio(k), "%.6g");
        s.add_int("fest_resets_" + c, fest_resets[k]);
        s.add_int("k2_changes_" + c, k2_changes[k]);
        s.add_hex("pd_" + c + "_health_or", health_or[k]);
        s.add_str("pd_" + c + "_health_or_names", bits_str(health_or[k], m.health, m.n_health));
        if (!last_.empty()) {
            for (const char *n : kCounters) {
                const std::string key = "pd_" + c + "_" + n;
                s.add_int("fsw_" + key, last_[l.at(key)]);
            }
        }
    }
    s.add_int("linear_invalid", lin_invalid ? 1 : 0);
}

}  // namespace host
