#include "observer/obs_metrics.hpp"

#include <cmath>

#include "gnc/actuator_cmd_v2_t.hpp"
#include "gnc/sim_truth_t.hpp"

namespace host {

namespace {
constexpr double kDeg = 3.14159265358979323846 / 180.0;
constexpr double kActLsb = 1.0 / 1048576.0;   // gimbal command LSB 2^-20 rad/s (obs tables)
constexpr double kTailS = 20.0;               // the "tail" window of spec 10 §6
const char *const kCounters[] = {"obs_n_skip", "obs_n_gap", "obs_n_lost", "obs_n_reinit", "obs_n_limited",
                                 "obs_n_clamp_lo", "obs_n_clamp_hi", "obs_n_innov", "obs_n_cov_clip", "obs_revision"};
}  // namespace

ObsMetrics::ObsMetrics(const sim::Scenario &s) : tail_from_s_(s.duration_s - kTailS)
{
    const TlmLayout &l = tlm_layout(iface_mission("DETUMBLE"));
    i_health_ = l.at("obs_health");
    i_kappa_ = l.at("obs_kappa");
}

void ObsMetrics::on_truth(const gnc::sim_truth_t &t)
{
    const double ts = static_cast<double>(t.utime) * 1e-6;
    if (truth_n == 1) {
        h_s = ts - t_last_s;
    }
    const double wy = t.state[0] / kDeg, wz = t.state[1] / kDeg;
    const double mu = std::fmax(std::fabs(t.state[2]), std::fabs(t.state[4])) / kDeg;
    const double wn = std::hypot(wy, wz);
    const double h = (truth_n >= 1) ? h_s : 0.0;
    if (wn >= 0.01) { t_s = ts + h; }
    if (wn >= 0.01 || mu >= 0.01) { t_s_plus = ts + h; }
    peak_w_degs = std::fmax(peak_w_degs, std::fmax(std::fabs(wy), std::fabs(wz)));
    peak_mu_deg = std::fmax(peak_mu_deg, mu);
    w_final_degs = wn;
    if (ts >= tail_from_s_) {
        max_w_tail_degs = std::fmax(max_w_tail_degs, wn);
        max_mu_tail_deg = std::fmax(max_mu_tail_deg, mu);
    }
    k_true = t.extra[0];
    t_last_s = ts;
    ++truth_n;
}

void ObsMetrics::on_cmd(const gnc::actuator_cmd_v2_t &c)
{
    for (int i = 0; i < 2 && i < c.n_counts; ++i) {
        peak_bdot_degs = std::fmax(peak_bdot_degs, std::fabs(c.counts[i] * kActLsb) / kDeg);
    }
}

void ObsMetrics::on_tlm(const std::vector<std::int64_t> &v, double t_s_now)
{
    const auto oh = static_cast<std::uint32_t>(v[i_health_]);
    k_hat_final = 0.01 * static_cast<double>(v[i_kappa_]) / 268435456.0;   // kappa q28 = K / 0.01
    obs_health_sticky |= oh;
    if (t_persist_s < 0.0 && (oh & OBS_H_CMD_LIMIT_PERSIST) != 0u) {
        t_persist_s = t_s_now;
    }
    last_ = v;
}

void ObsMetrics::summary(Summary &s) const
{
    const iface::Mission &m = iface_mission("DETUMBLE");
    s.add("t_s_s", t_s, "%.2f");
    s.add("t_s_plus_s", t_s_plus, "%.2f");
    s.add("k_hat_final_per_s2", k_hat_final, "%.6f");
    s.add("k_true_per_s2", k_true, "%.6f");
    s.add("peak_bdot_degps", peak_bdot_degs, "%.3f");
    s.add("peak_mu_deg", peak_mu_deg, "%.4f");
    s.add("peak_w_degps", peak_w_degs, "%.4f");
    s.add("w_final_degps", w_final_degs, "%.3g");
    s.add("max_w_tail_degps", max_w_tail_degs, "%.3g");
    s.add("max_mu_tail_deg", max_mu_tail_deg, "%.3g");
    s.add("t_cmd_limit_persist_s", t_persist_s, "%.2f");
    if (!last_.empty()) {
        const TlmLayout &l = tlm_layout(m);
        for (const char *k : kCounters) {
            s.add_int(std::string("fsw_") + k, last_[l.at(k)]);
        }
    }
    s.add_hex("obs_health_sticky", obs_health_sticky);
    s.add_str("obs_health_sticky_names", bits_str(obs_health_sticky, m.health, m.n_health));
}

}  // namespace host
