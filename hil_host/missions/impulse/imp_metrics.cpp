#include "impulse/imp_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "gnc/actuator_cmd_v2_t.hpp"
#include "gnc/sim_truth_t.hpp"

namespace host {

namespace {
const char *const kSummaryFields[] = {
    "imp_mode", "imp_plans", "imp_plans_failed", "imp_plans_late", "imp_plans_skipped", "imp_plans_kept", "imp_cmd_rej",
    "imp_rej_reason", "imp_nav_rej", "imp_cal_rej", "imp_iters_xy", "imp_iters_z", "imp_how_xy", "imp_how_z",
    "imp_pattern", "imp_fres_xy", "imp_fres_z", "imp_stuck_j"};
}  // namespace

ImpMetrics::ImpMetrics(const sim::Scenario &s)
{
    const iface::Mission &m = iface_mission("RENDEZVOUS");
    for (const sim::ScnCommand &c : s.commands) {
        if (c.name == "IMP_START" && tf_step < 0) {
            t0_step = c.args[0];
            tf_step = c.args[1];
        }
    }
    const TlmLayout &l = tlm_layout(m);
    ix_.health = l.at("imp_health");
    ix_.mode = l.at("imp_mode");
    ix_.iters_xy = l.at("imp_iters_xy");
    ix_.iters_z = l.at("imp_iters_z");
    const char *ax[3] = {"x", "y", "z"};
    for (int a = 0; a < 3; ++a) {
        ix_.t1[a] = l.at(std::string("imp_t1_") + ax[a]);
        ix_.t2[a] = l.at(std::string("imp_t2_") + ax[a]);
        ix_.on2[a] = l.at(std::string("imp_on2_step_") + ax[a]);
    }
    // Every named health bit but the mode field; every scheduler mode (a mode whose name is also
    // a flag's gets the suffix _MODE).
    for (std::size_t i = 0; i < m.n_health; ++i) {
        if (std::string(m.health[i].name) != "MODE") {
            flags_.emplace_back(m.health[i].name, m.health[i].value);
        }
    }
    for (std::size_t e = 0; e < m.n_enums; ++e) {
        if (std::string(m.enums[e].name) != "mode") {
            continue;
        }
        for (std::size_t k = 0; k < m.enums[e].n; ++k) {
            std::string n = m.enums[e].values[k].name;
            for (const auto &f : flags_) {
                n = (f.first == n) ? n + "_MODE" : n;
            }
            modes_.resize(std::max<std::size_t>(modes_.size(), m.enums[e].values[k].value + 1u));
            modes_[m.enums[e].values[k].value] = n;
        }
    }
}

// Truth of the CW plant (sim/impulse/cw_sil_plant.hpp): state[0..5] x, x', y, y', z, z';
// state[6..11] delta-v per thruster; state[12] interlock violations.
void ImpMetrics::on_truth(const gnc::sim_truth_t &t)
{
    if (t.seq == tf_step) {
        at_tf = true;
        miss_r_m = std::sqrt(t.state[0] * t.state[0] + t.state[2] * t.state[2] + t.state[4] * t.state[4]);
        miss_v_mps = std::sqrt(t.state[1] * t.state[1] + t.state[3] * t.state[3] + t.state[5] * t.state[5]);
        for (int a = 0; a < 3; ++a) { miss_xyz_m[a] = t.state[2 * a]; }
    }
    dv_used_mps = 0.0;
    for (int j = 0; j < 6; ++j) {
        dv_thr_mps[j] = t.state[6 + j];
        dv_used_mps += t.state[6 + j];
    }
    violations = t.state[12];
    omega_radps = t.extra[0];
    a_nom_mps2 = t.extra[1];
    t_last_s = static_cast<double>(t.utime) * 1e-6;
    ++truth_n;
}

void ImpMetrics::on_cmd(const gnc::actuator_cmd_v2_t &c)
{
    if (c.n_counts > static_cast<std::int16_t>(IMP_ACT_MASK) && c.counts[IMP_ACT_MASK] != 0) {
        ++thr_on_steps;
        if (t_first.count("ABORTED") != 0u) { ++on_after_abort; }
    }
}

void ImpMetrics::on_tlm(const std::vector<std::int64_t> &v, double ts)
{
    const auto h = static_cast<std::uint32_t>(v[ix_.health]);
    imp_health_sticky |= h;
    for (const auto &f : flags_) {
        if ((h & f.second) != 0u && t_first.count(f.first) == 0u) {
            t_first[f.first] = ts;
        }
    }
    max_iters_xy = std::max(max_iters_xy, static_cast<std::uint32_t>(v[ix_.iters_xy]));
    max_iters_z = std::max(max_iters_z, static_cast<std::uint32_t>(v[ix_.iters_z]));
    const auto mode = static_cast<std::uint32_t>(v[ix_.mode]);
    // The START plan's delta-v: a_nom * sum over the axes of (T1 + T - T2), from the first
    // telemetry that shows the committed plan (ARMED), T = t_f - t0.
    if (mode == IMP_MODE_ARMED && plan_dv_mps < 0.0 && omega_radps > 0.0 && t0_step >= 0) {
        const double dt = (truth_n > 1) ? (t_last_s / static_cast<double>(truth_n - 1)) : 0.0;
        const double T = static_cast<double>(tf_step - t0_step) * dt;
        double s = 0.0;
        for (int a = 0; a < 3; ++a) {
            const double t1 = static_cast<double>(v[ix_.t1[a]]) / 536870912.0 / omega_radps;   // q29
            const double t2 = static_cast<double>(v[ix_.t2[a]]) / 536870912.0 / omega_radps;
            s += t1 + T - t2;
            const std::int64_t k2 = v[ix_.on2[a]];
            if (burn2_step < 0 || k2 < burn2_step) { burn2_step = k2; }
        }
        plan_dv_mps = a_nom_mps2 * s;
    }
    if (mode < modes_.size() && mode < 32u) {
        imp_modes_seen |= 1u << mode;
        if (t_first.count(modes_[mode]) == 0u) { t_first[modes_[mode]] = ts; }
    }
    imp_mode_final = mode;
    last_ = v;
}

void ImpMetrics::summary(Summary &s) const
{
    const iface::Mission &m = iface_mission("RENDEZVOUS");
    s.add("miss_r_m", miss_r_m, "%.4f");
    s.add("miss_v_mps", miss_v_mps, "%.6f");
    s.add("dv_used_mps", dv_used_mps, "%.4f");
    s.add("plan_dv_mps", plan_dv_mps, "%.4f");
    s.add_int("first_burn2_step", burn2_step);
    s.add_int("max_iters_xy", max_iters_xy);
    s.add_int("max_iters_z", max_iters_z);
    s.add("interlock_violations", violations, "%.0f");
    s.add_int("t_f_step", tf_step);
    s.add_int("thruster_on_steps", static_cast<std::int64_t>(thr_on_steps));
    if (!last_.empty()) {
        const TlmLayout &l = tlm_layout(m);
        for (const char *k : kSummaryFields) {
            s.add_int(std::string("fsw_") + k, last_[l.at(k)]);
        }
    }
    s.add_hex("imp_health_sticky", imp_health_sticky);
    s.add_str("imp_health_sticky_names", bits_str(imp_health_sticky, m.health, m.n_health));
    for (const auto &kv : t_first) {
        s.add("t_first_" + kv.first, kv.second, "%.1f");
    }
}

}  // namespace host
