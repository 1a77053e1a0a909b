// pd_metrics.hpp — acceptance metrics of a HOLD run (spec 40 §2.6, §7), computed live from the LCM
// stream: the attitude, gimbal angles and f_min from the plant's truth (GNC_TRUTH), the torque commands
// (GNC_CMD), the channels' health, k2 and counters from the HOLD telemetry. `sil run` writes them into
// summary.txt / summary.json; tools/pd/report.py derives the same figures from the log (CTest
// sil_pd_report_agrees proves they agree). The truth attitude series is kept (tests compare two runs).
#ifndef HIL_MISSIONS_PD_METRICS_HPP
#define HIL_MISSIONS_PD_METRICS_HPP

#include <array>
#include <cstdint>
#include <utility>
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

    static constexpr double kBandRad = 5e-5;          // spec 40 §2.4 settling band
    static constexpr double kLateS = 600.0;            // A3-8: |x| after this time
    // Settling time of channel k on the truth at the sample instants (§2.6): the first sample after
    // the last one with |x| >= band; -1 if the final sample violates it; 0 if none does.
    double t_settle(std::size_t k) const;

    std::array<std::vector<double>, 3> x;             // truth attitude at t_k [rad]
    std::vector<double> t;                            // t_k [s]
    std::array<double, 3> peak_beta{}, peak_m{}, peak_rate{}, peak_x_late{};   // rad, N m, rad/s, rad
    std::array<double, 3> k2_final{};                 // s
    std::array<std::uint32_t, 3> k2_changes{}, health_or{};
    bool lin_invalid = false;                         // any sample with |beta| > 0.5 rad
    // The estimator's telemetry per frame (the summary keeps f_hat at 300 / 1 200 s): published f_hat [Hz] (0
    // while the channel is not ADAPTIVE), the fest word (state bits 0..1, confident bit 2), FAULT count.
    std::vector<double> t_tlm;                        // frame time [s]
    std::array<std::vector<double>, 3> fest_f;
    std::array<std::vector<std::uint32_t>, 3> fest_word;
    std::array<std::uint32_t, 3> fest_resets{};
    std::array<std::vector<double>, 3> k2_series;     // k2 in use per frame [s]
    // f_hat of the last frame at or before t_s (-1 if none); the largest confident f_hat (0 if none)
    double fest_f_at(std::size_t k, double t_s) const;
    double fest_max_confident(std::size_t k) const;
    // The plant's f_min at t_s (the scenario's f_hz and f_steps) and the largest confident f_hat / f
    // over the run (R5; 0 if never confident).
    double f_true_at(double t_s) const;
    double fest_max_confident_ratio(std::size_t k) const;
    double ty_s = 0.25;

private:
    std::array<std::size_t, 3> i_health_{}, i_k2_{}, i_dy_{}, i_ff_{}, i_fw_{}, i_fr_{};
    std::array<std::uint32_t, 3> k2_last_{};
    double f0_hz_ = 0.0;
    std::vector<std::pair<double, double>> f_steps_;   // (t_s, f_hz)
    bool have_tlm_ = false;
    std::vector<std::int64_t> last_;
};

}  // namespace host

#endif
