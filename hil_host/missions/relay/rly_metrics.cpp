#include "relay/rly_metrics.hpp"

#include <algorithm>
#include <cmath>

#include "relay/relay_section.hpp"
#include "gnc/actuator_cmd_v2_t.hpp"
#include "gnc/sim_truth_t.hpp"

namespace host {

namespace {
const char *const kCounters[] = {"rly_n_r_main", "rly_n_l_main", "rly_n_x_invalid", "rly_n_x_range", "rly_n_lost",
                                 "rly_n_tau_sat", "rly_n_kt_clamped", "rly_n_env_sat", "rly_n_reinit",
                                 "rly_n_env_high", "rly_n_windows", "rly_revision", "rly_seed"};
constexpr double kQ40 = 1099511627776.0;   // 2^40
}  // namespace

RelayMetrics::RelayMetrics(const sim::Scenario &s)
    : h_s_(static_cast<double>(s.period_us) * 1e-6),
      abar_from_s_(s.mission_part<sim::RelayScenario>().body.abar_from_s)
{
    const TlmLayout &l = tlm_layout(iface_mission("RELAY"));
    i_health_ = l.at("rly_health");
    i_st_ = l.at("rly_st");
    i_tau1_ = l.at("rly_tau1");
    i_tau2_ = l.at("rly_tau2");
    i_kt_ = l.at("rly_kt");
    i_a_ = l.at("rly_a");
    i_ai_ = l.at("rly_a_0");
    i_win_event_ = l.at("rly_win_event");
    i_windows_ = l.at("rly_n_windows");
}

void RelayMetrics::on_truth(const gnc::sim_truth_t &t)
{
    const double ts = static_cast<double>(t.utime) * 1e-6;
    x_peak_rad = std::fmax(x_peak_rad, std::fabs(t.state[0]));
    double sum = 0.0;
    for (std::size_t i = 0; i < 4u; ++i) {   // truth: x~_i at state[3 + i], x~_i'/omega_i at state[7 + i]
        const double q = t.state[3 + i], p = t.state[7 + i];
        a_true_[i] = std::sqrt(q * q + p * p);   // not hypot: the Python report must reproduce it bit for bit
        sum += a_true_[i];
    }
    const auto level = static_cast<int>(std::lround(t.state[11]));   // an integer level carried as a double
    if (truth_n_ > 0 && level != last_level_) {
        ++level_changes;
    }
    last_level_ = level;
    if (ts >= kLateFromS) {
        sum_true_ += sum;
        ++n_true_;
    }
    if (abar_from_s_ >= 0.0 && ts >= abar_from_s_) {
        sum_from_ += sum;
        ++n_from_;
    }
    truth_us_ = t.utime;
    ++truth_n_;
}

void RelayMetrics::on_cmd(const gnc::actuator_cmd_v2_t &) {}

void RelayMetrics::on_tlm(const std::vector<std::int64_t> &v, double t_s)
{
    health_or |= static_cast<std::uint32_t>(v[i_health_]);
    const std::int64_t us = std::llround(t_s * 1e6);
    if (us == truth_us_) {   // the copy at t_k against the plant at t_k (truth is published first)
        for (std::size_t i = 0; i < 4u; ++i) {   // unmodelled modes: 0 in both
            const double fx = static_cast<double>(v[i_ai_ + i]);
            const double err = std::fabs(fx - a_true_[i] * kQ40);
            env_err_max_lsb = std::fmax(env_err_max_lsb, err);
        }
        ++env_pairs;
    }
    if (us % kEnvSampleUs == 0) {
        a20_.emplace_back(t_s, static_cast<double>(v[i_a_]) / kQ40);
    }
    if (t_s >= kLateFromS) {
        sum_fsw_ += static_cast<double>(v[i_a_]) / kQ40;
        ++n_fsw_;
    }
    const std::int64_t st = v[i_st_];
    const bool brake = st == static_cast<std::int64_t>(RLY_ST_R_BRAKE) || st == static_cast<std::int64_t>(RLY_ST_L_BRAKE);
    const bool was_main = last_st_ == static_cast<std::int64_t>(RLY_ST_R_MAIN) ||
                          last_st_ == static_cast<std::int64_t>(RLY_ST_L_MAIN);
    if (brake && was_main) {   // a main pulse just ended: its length and its brake's
        const double t1 = static_cast<double>(v[i_tau1_]) * h_s_;
        const double t2 = static_cast<double>(v[i_tau2_]) * h_s_;
        tau_main_min_s = (pulses == 0) ? t1 : std::fmin(tau_main_min_s, t1);
        tau_main_max_s = (pulses == 0) ? t1 : std::fmax(tau_main_max_s, t1);
        tau_brake_min_s = (pulses == 0) ? t2 : std::fmin(tau_brake_min_s, t2);
        tau_brake_max_s = (pulses == 0) ? t2 : std::fmax(tau_brake_max_s, t2);
        ++pulses;
    }
    last_st_ = st;
    if (v[i_windows_] != last_windows_) {
        const std::int64_t ev = v[i_win_event_];
        if (t_first_freeze_s < 0.0 && (ev == static_cast<std::int64_t>(RLY_EV_FREEZE_SETTLED) ||
                                       ev == static_cast<std::int64_t>(RLY_EV_FREEZE_CLIFF))) {
            t_first_freeze_s = t_s;
        }
        last_windows_ = v[i_windows_];
    }
    kt_final = static_cast<double>(v[i_kt_]) / 65536.0;
    last_ = v;
}

double RelayMetrics::env_period_s() const
{
    if (a20_.empty()) {
        return -1.0;
    }
    const double t0 = std::fmin(kLateFromS, 0.5 * a20_.back().first);
    std::vector<double> x;
    for (const auto &e : a20_) {
        if (e.first >= t0) {
            x.push_back(e.second);
        }
    }
    double mean = 0.0;
    for (const double a : x) {
        mean += a;
    }
    mean /= static_cast<double>(x.empty() ? 1u : x.size());
    for (double &a : x) {
        a -= mean;
    }
    const std::size_t n = x.size();
    const std::size_t lmax = std::min(kEnvMaxLag, n / 2);
    std::vector<double> r(lmax + 1, 0.0);
    for (std::size_t l = 1; l <= lmax; ++l) {   // mean of the products, as tools/relay/report.py
        double acc = 0.0;
        for (std::size_t i = 0; i + l < n; ++i) {
            acc += x[i] * x[i + l];
        }
        r[l] = acc / static_cast<double>(n - l);
    }
    // The first local minimum, then the first local maximum after it: the envelope also drifts
    // slowly (r stays positive through the first period on a 2000-s run), so a zero crossing is no
    // reliable marker.
    std::size_t l = 2;
    while (l < lmax && !(r[l] <= r[l - 1] && r[l] < r[l + 1])) {
        ++l;
    }
    while (l < lmax && !(r[l] >= r[l - 1] && r[l] > r[l + 1])) {
        ++l;
    }
    const std::size_t best = (l < lmax) ? l : 0u;
    if (best == 0) {
        return -1.0;
    }
    const double den = r[best - 1] - 2.0 * r[best] + r[best + 1];
    const double d = (den < 0.0) ? 0.5 * (r[best - 1] - r[best + 1]) / den : 0.0;
    return (static_cast<double>(best) + d) * static_cast<double>(kEnvSampleUs) * 1e-6;
}

void RelayMetrics::summary(Summary &s) const
{
    const iface::Mission &m = iface_mission("RELAY");
    s.add("x_peak_rad", x_peak_rad, "%.6g");
    s.add_int("level_changes", static_cast<std::int64_t>(level_changes));
    s.add("abar_true_late_rad", n_true_ ? sum_true_ / static_cast<double>(n_true_) : 0.0, "%.6g");
    s.add("abar_fsw_late_rad", n_fsw_ ? sum_fsw_ / static_cast<double>(n_fsw_) : 0.0, "%.6g");
    if (abar_from_s_ >= 0.0) {
        s.add("abar_from_s", abar_from_s_, "%.1f");
        s.add("abar_true_from_rad", n_from_ ? sum_from_ / static_cast<double>(n_from_) : 0.0, "%.6g");
    }
    s.add("env_err_max_lsb", env_err_max_lsb, "%.3f");
    s.add_int("env_pairs", static_cast<std::int64_t>(env_pairs));
    s.add_int("main_pulses", static_cast<std::int64_t>(pulses));
    s.add("tau_main_min_s", tau_main_min_s, "%.3f");
    s.add("tau_main_max_s", tau_main_max_s, "%.3f");
    s.add("tau_brake_min_s", tau_brake_min_s, "%.3f");
    s.add("tau_brake_max_s", tau_brake_max_s, "%.3f");
    s.add("t_first_freeze_s", t_first_freeze_s, "%.1f");
    s.add("kt_final", kt_final, "%.6f");
    s.add("env_period_s", env_period_s(), "%.3f");
    if (!last_.empty()) {
        const TlmLayout &l = tlm_layout(m);
        for (const char *k : kCounters) {
            s.add_int(std::string("fsw_") + k, last_[l.at(k)]);
        }
    }
    s.add_hex("rly_health_sticky", health_or);
    s.add_str("rly_health_sticky_names", bits_str(health_or, m.health, m.n_health));
}

}  // namespace host
