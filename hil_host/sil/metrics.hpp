// metrics.hpp — acceptance metrics of a detumbling run, computed live from the LCM stream
// (spec 10-observer §6): truth from GNC_TRUTH, commands from GNC_CMD, estimates and counters
// from GNC_TLM. Used by `sil run` for its summary and by the SIL tests; tools/sil/report.py
// computes the same figures from a log for the plots.
#ifndef HIL_SIL_METRICS_HPP
#define HIL_SIL_METRICS_HPP

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <lcm/lcm.h>

namespace sil {

struct Metrics {
    double h_s = 0.0;
    double t_last_s = 0.0;       // time of the last truth sample
    double t_s = 0.0;            // last time |w| >= 0.01 deg/s, plus h (|w| = hypot(w_y, w_z))
    double t_s_plus = 0.0;       // ... or max(|mu_y|, |mu_z|) >= 0.01 deg
    double peak_w_degs = 0.0;    // per component
    double peak_mu_deg = 0.0;
    double peak_bdot_degs = 0.0; // commanded, per component
    double w_final_degs = 0.0;   // |w| at the last sample
    double max_w_tail_degs = 0.0;   // max |w| over the last tail_s seconds
    double max_mu_tail_deg = 0.0;
    double k_hat_final = 0.0;    // K-hat (s^-2) from the last telemetry
    double k_true = 0.0;
    double t_persist_s = -1.0;   // first CMD_LIMIT_PERSIST in the observer health, -1 = never
    double t_first_fx_s = -1.0;  // first fx status bit (unexpected saturation), -1 = never
    std::uint32_t first_fx_bits = 0;
    std::uint64_t truth_n = 0, cmd_n = 0, tlm_n = 0, ack_n = 0;
    std::int32_t last_ack_result = -1, last_ack_reason = 0;
    std::uint32_t obs_health_sticky = 0;
    std::map<std::string, std::int64_t> tlm;      // last decoded fsw_tlm_t fields (raw)
    std::map<std::string, std::int64_t> bridge;   // last bridge counters of fsw_tlm_frame_t
    std::uint64_t tlm_bad = 0;                    // frames whose tlm failed to decode
    // Rendezvous (plant cw, spec 50 §7): truth at t_f, delta-v, thruster activity, event times.
    bool rdv = false;
    std::int64_t tf_step = -1;                    // from the scenario's IMP_START
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
    std::int64_t t0_step = -1;
    double plan_dv_mps = -1.0;                    // the START plan's delta-v (first ARMED telemetry)
    std::int64_t burn2_step = -1;                 // earliest second-burn start of the START plan
    std::uint64_t on_after_abort = 0;             // commands with a thruster on after ABORTED was reported
    std::uint32_t max_iters_xy = 0, max_iters_z = 0;
};

class MetricsTap {
public:
    // tail_from_s: samples at t >= tail_from_s feed the "tail" maxima (e.g. duration - 20).
    MetricsTap(lcm_t *lcm, double tail_from_s);
    // Rendezvous metrics: the terminal miss at step tf_step (the plant's k of t_f).
    void set_rendezvous(std::int64_t t0_step, std::int64_t tf_step);
    ~MetricsTap();
    MetricsTap(const MetricsTap &) = delete;
    MetricsTap &operator=(const MetricsTap &) = delete;
    // The metrics so far; tlm is filled here from the last decoded telemetry (decoding every
    // message into a name map cost 85 % of a rendezvous SIL run, so the tap keeps raw values).
    const Metrics &m() const;
    std::string summary() const;   // key = value lines

private:
    static void on_truth(const lcm_recv_buf_t *rb, const char *ch, void *user);
    static void on_cmd(const lcm_recv_buf_t *rb, const char *ch, void *user);
    static void on_tlm(const lcm_recv_buf_t *rb, const char *ch, void *user);
    static void on_ack(const lcm_recv_buf_t *rb, const char *ch, void *user);
    lcm_t *lcm_;
    double tail_from_s_;
    std::vector<std::int64_t> last_;     // raw values of the last telemetry, in layout order
    const void *last_layout_ = nullptr;  // the layout they belong to
    lcm_subscription_t *subs_[4] = {nullptr, nullptr, nullptr, nullptr};
    mutable Metrics m_{};
};

// Decodes an encoded fsw_tlm_t (FSW_TLM_LAYOUT_VERSION) into name -> raw value, names as in
// fsw/app/fsw_tlm_formats.json. false on a wrong length.
bool decode_fsw_tlm(const std::uint8_t *buf, std::size_t len, std::map<std::string, std::int64_t> &out);

}  // namespace sil

#endif  // HIL_SIL_METRICS_HPP
