#include "pd/pd_metrics.hpp"

#include <cmath>

#include "pd/pd_section.hpp"
#include "gnc/actuator_cmd_v2_t.hpp"
#include "gnc/sim_truth_t.hpp"

namespace host {

namespace {
const char *const kCounters[] = {"pd_n_skip", "pd_n_limited", "pd_revision"};
}  // namespace

PdMetrics::PdMetrics(const sim::Scenario &)
{
    i_health_ = tlm_layout(iface_mission("HOLD")).at("pd_health");
}

void PdMetrics::on_truth(const gnc::sim_truth_t &t)
{
    const double ts = static_cast<double>(t.utime) * 1e-6;
    if (truth_n == 1) {
        h_s = ts - t_last_s;
    }
    const double w = std::fabs(t.state[0]);
    if (w >= kSettleRadps) {
        t_settle_s = ts + ((truth_n >= 1) ? h_s : 0.0);
    }
    rate_final_radps = w;
    t_last_s = ts;
    ++truth_n;
}

void PdMetrics::on_cmd(const gnc::actuator_cmd_v2_t &c)
{
    if (c.n_counts >= 1) {
        peak_torque_nm = std::fmax(peak_torque_nm, std::fabs(c.counts[0] * sim::kPdTorqueLsbNm));
    }
}

void PdMetrics::on_tlm(const std::vector<std::int64_t> &v, double t_s)
{
    const auto h = static_cast<std::uint32_t>(v[i_health_]);
    health_or |= h;
    if (t_persist_s < 0.0 && (h & PD_H_CMD_LIMIT_PERSIST) != 0u) {
        t_persist_s = t_s;
    }
    last_ = v;
}

void PdMetrics::summary(Summary &s) const
{
    const iface::Mission &m = iface_mission("HOLD");
    s.add("t_settle_s", t_settle_s, "%.2f");
    s.add("rate_final_radps", rate_final_radps, "%.3g");
    s.add("peak_torque_nm", peak_torque_nm, "%.6f");
    s.add("t_cmd_limit_persist_s", t_persist_s, "%.2f");
    if (!last_.empty()) {
        const TlmLayout &l = tlm_layout(m);
        for (const char *k : kCounters) {
            s.add_int(std::string("fsw_") + k, last_[l.at(k)]);
        }
    }
    s.add_hex("pd_health_sticky", health_or);
    s.add_str("pd_health_sticky_names", bits_str(health_or, m.health, m.n_health));
}

}  // namespace host
