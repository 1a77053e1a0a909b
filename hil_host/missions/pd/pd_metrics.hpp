// pd_metrics.hpp — acceptance metrics of a HOLD run, computed live from the LCM
// stream: the body rate from the plant's truth (GNC_TRUTH), the torque commands (GNC_CMD), the
// module's health and counters from the HOLD telemetry. `sil run` writes them into
// summary.txt / summary.json; tools/pd/report.py derives the same figures from the log
// (CTest sil_pd_report_agrees proves they agree).
#ifndef HIL_MISSIONS_PD_METRICS_HPP
#define HIL_MISSIONS_PD_METRICS_HPP

#include <cstdint>
#include <vector>

#include "mission_host.hpp"

namespace host {

class PdMetrics final : public MissionMetrics {
public:
    explicit PdMetrics(const sim::Scenario &s);
    void on_truth(const gnc::sim_truth_t &t) override;
    void on_cmd(const gnc::actuator_cmd_v2_t &c) override;
    void on_tlm(const std::vector<std::int64_t> &v, double t_s) override;
    void summary(Summary &s) const override;

    static constexpr double kSettleRadps = 1e-3;   // settled: |omega| below this from t_settle on
    double h_s = 0.0;              // truth spacing
    double t_last_s = 0.0;
    double t_settle_s = 0.0;       // last time |omega| >= kSettleRadps, plus h (0: never above)
    double rate_final_radps = 0.0; // |omega| at the last truth sample
    double peak_torque_nm = 0.0;   // largest commanded |torque|
    std::uint32_t health_or = 0;   // OR of the module's health over the run
    double t_persist_s = -1.0;     // first CMD_LIMIT_PERSIST, -1 = never
    std::uint64_t truth_n = 0;

private:
    std::size_t i_health_;
    std::vector<std::int64_t> last_;
};

}  // namespace host

#endif
