// obs_metrics.hpp — acceptance metrics of a detumbling run (spec 10-observer §6), computed live
// from the LCM stream: truth from GNC_TRUTH, commands from GNC_CMD, estimates and counters from
// the DETUMBLE telemetry. `sil run` writes them into summary.txt / summary.json; the SIL tests
// assert on them; tools/observer/report.py plots the log and prints these numbers.
#ifndef HIL_MISSIONS_OBS_METRICS_HPP
#define HIL_MISSIONS_OBS_METRICS_HPP

#include <cstdint>
#include <vector>

#include "mission_host.hpp"

namespace host {

class ObsMetrics final : public MissionMetrics {
public:
    explicit ObsMetrics(const sim::Scenario &s);
    void on_truth(const gnc::sim_truth_t &t) override;
    void on_cmd(const gnc::actuator_cmd_v2_t &c) override;
    void on_tlm(const std::vector<std::int64_t> &v, double t_s) override;
    void summary(Summary &s) const override;

    double h_s = 0.0;
    double t_last_s = 0.0;       // time of the last truth sample
    double t_s = 0.0;            // last time |w| >= 0.01 deg/s, plus h (|w| = hypot(w_y, w_z))
    double t_s_plus = 0.0;       // ... or max(|mu_y|, |mu_z|) >= 0.01 deg
    double peak_w_degs = 0.0;    // per component
    double peak_mu_deg = 0.0;
    double peak_bdot_degs = 0.0; // commanded, per component
    double w_final_degs = 0.0;   // |w| at the last sample
    double max_w_tail_degs = 0.0;   // max |w| over the last 20 s
    double max_mu_tail_deg = 0.0;
    double k_hat_final = 0.0;    // K-hat (s^-2) from the last telemetry
    double k_true = 0.0;
    double t_persist_s = -1.0;   // first CMD_LIMIT_PERSIST in the observer health, -1 = never
    std::uint32_t obs_health_sticky = 0;
    std::uint64_t truth_n = 0;

private:
    double tail_from_s_;
    std::size_t i_health_, i_kappa_;
    std::vector<std::int64_t> last_;
};

}  // namespace host

#endif  // HIL_MISSIONS_OBS_METRICS_HPP
