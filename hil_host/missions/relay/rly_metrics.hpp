// rly_metrics.hpp — acceptance metrics of a RELAY run (spec 20 §7), computed live from the LCM
// stream: the plant's truth (GNC_TRUTH: x, the modes' x~_i and x~_i'/omega_i, the applied level)
// and the RELAY telemetry (state, envelope a_i, k_t, pulse lengths, window packets, counters).
// `sil run` writes them into summary.txt / summary.json; tools/relay/report.py derives the same
// figures from the log (CTest sil_rly_report_agrees proves they agree).
#ifndef HIL_MISSIONS_RLY_METRICS_HPP
#define HIL_MISSIONS_RLY_METRICS_HPP

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "mission_host.hpp"

namespace host {

class RelayMetrics final : public MissionMetrics {
public:
    explicit RelayMetrics(const sim::Scenario &s);
    void on_truth(const gnc::sim_truth_t &t) override;
    void on_cmd(const gnc::actuator_cmd_v2_t &c) override;
    void on_tlm(const std::vector<std::int64_t> &v, double t_s) override;
    void summary(Summary &s) const override;

    static constexpr double kLateFromS = 2000.0;   // ā over [2000 s, end] (spec 20 §7)
    double x_peak_rad = 0.0;            // max |x| (truth)
    std::uint64_t level_changes = 0;    // applied level changes (truth)
    double abar_true_late = 0.0;        // mean true envelope sum sqrt(x~^2 + p~^2) over the late part
    double abar_fsw_late = 0.0;         // mean flight a over the late part
    double env_err_max_lsb = 0.0;       // max |a_i,fx - a_i,true| in 2^-40 rad, ticks with both
    std::uint64_t env_pairs = 0;        // ticks compared
    double tau_main_min_s = 0.0, tau_main_max_s = 0.0, tau_brake_min_s = 0.0, tau_brake_max_s = 0.0;
    std::uint64_t pulses = 0;
    double t_first_freeze_s = -1.0;     // first FREEZE_* window event
    double kt_final = 0.0;
    std::uint32_t health_or = 0;
    // Envelope period (spec 20 §7 S2: 44 +- 2 s): the first autocorrelation peak of the flight a
    // sampled at 20 Hz, past its first dip, refined by a parabola; -1 if there is none.
    // Samples from t >= min(kLateFromS, t_end / 2), so a 300-s suite run measures it too.
    static constexpr std::int64_t kEnvSampleUs = 50000;   // 20 Hz
    static constexpr std::size_t kEnvMaxLag = 2400;       // 120 s
    double env_period_s() const;

private:
    double h_s_;
    std::int64_t truth_us_ = -1;
    std::array<double, 4> a_true_{};
    double abar_from_s_;                           // RelaySetup::abar_from_s (< 0: not reported)
    double sum_from_ = 0.0;
    std::uint64_t n_from_ = 0;
    double sum_true_ = 0.0, sum_fsw_ = 0.0;
    std::uint64_t n_true_ = 0, n_fsw_ = 0;
    int last_level_ = 0;
    std::uint64_t truth_n_ = 0;
    std::int64_t last_tau1_ = -1, last_st_ = -1;
    std::size_t i_health_, i_st_, i_tau1_, i_tau2_, i_kt_, i_a_, i_ai_, i_win_event_, i_windows_;
    std::int64_t last_windows_ = 0;
    std::vector<std::int64_t> last_;
    std::vector<std::pair<double, double>> a20_;   // (t [s], flight a [rad]) at 20 Hz
};

}  // namespace host

#endif
