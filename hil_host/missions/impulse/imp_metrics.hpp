// imp_metrics.hpp — acceptance metrics of a rendezvous run (spec 50 §7), computed live from the
// LCM stream: the terminal miss at t_f and the delta-v from the CW plant's truth, thruster
// activity from the commands, the scheduler's modes, flags and plans from the RENDEZVOUS
// telemetry. t0 and t_f come from the scenario's first IMP_START.
#ifndef HIL_MISSIONS_IMP_METRICS_HPP
#define HIL_MISSIONS_IMP_METRICS_HPP

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "mission_host.hpp"

namespace host {

class ImpMetrics final : public MissionMetrics {
public:
    explicit ImpMetrics(const sim::Scenario &s);
    void on_truth(const gnc::sim_truth_t &t) override;
    void on_cmd(const gnc::actuator_cmd_v2_t &c) override;
    void on_tlm(const std::vector<std::int64_t> &v, double t_s) override;
    void summary(Summary &s) const override;

    std::int64_t t0_step = -1, tf_step = -1;      // from the scenario's IMP_START
    bool at_tf = false;                           // a truth sample at t_f was seen
    double miss_r_m = -1.0, miss_v_mps = -1.0;    // |dR|, |dV| at t_f (target at the origin)
    double miss_xyz_m[3] = {0, 0, 0};
    double dv_used_mps = 0.0;                     // sum over the thrusters (truth)
    double dv_thr_mps[6] = {0, 0, 0, 0, 0, 0};
    double violations = 0.0;                      // interlock violations seen by the plant
    std::uint64_t thr_on_steps = 0;               // commands with any thruster on
    std::uint32_t imp_health_sticky = 0;
    std::uint32_t imp_mode_final = 0;
    std::uint32_t imp_modes_seen = 0;             // bit m: IMP_MODE m seen
    std::map<std::string, double> t_first;        // first time of an impulse health flag / mode
    double omega_radps = 0.0, a_nom_mps2 = 0.0;   // from the plant's truth
    double plan_dv_mps = -1.0;                    // the START plan's delta-v (first ARMED telemetry)
    std::int64_t burn2_step = -1;                 // earliest second-burn start of the START plan
    std::uint64_t on_after_abort = 0;             // commands with a thruster on after ABORTED was reported
    std::uint32_t max_iters_xy = 0, max_iters_z = 0;
    std::uint64_t truth_n = 0;
    double t_last_s = 0.0;

private:
    struct Idx {
        std::size_t health, mode, iters_xy, iters_z, t1[3], t2[3], on2[3];
    } ix_{};
    std::vector<std::pair<std::string, std::uint32_t>> flags_;   // health bits tracked by t_first
    std::vector<std::string> modes_;                              // t_first key of each IMP_MODE
    std::vector<std::int64_t> last_;
};

}  // namespace host

#endif  // HIL_MISSIONS_IMP_METRICS_HPP
