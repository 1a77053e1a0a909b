// pd_ref.hpp — one HOLD channel in double precision (spec 40 §3, §4.2, §5, §8): the reference the
// fixed-point flight code (fsw/pd/pd.c) is proven against (golden G1 / G2 in tests/pd, and the
// reference backend of `sil run --fsw ref`). It reads the same table, dequantised, and the same
// counts; every rule of the flight channel (accept / refuse, hold, coast, frozen, the control period,
// the beta limit, the clamp) is written out again here from the spec, in double.
//
// One deliberate sharing with the flight code: the gains G_P = k0 k1 and G_D = k0 k2 / Ty are quantised
// to 2^-16 N m/rad, as the spec's formats fix them (§5 table: uq16), so the golden comparison measures the
// law's arithmetic and not the gain format (G_P's quantum times |y| <= 0.5 rad alone is 2^-17 N m, 2^11 q28
// LSB). The averaged modes use the exact mean.
//
// ADAPTIVE (§4.2, §4.4 A): the channel carries the estimator's double design ref::pd::FestRef
// (sim/pd/pd_fest_ref; the flight's pd_fest is proven against it by golden G3) built from
// make_fest_params(Channel) for the channel: the design the flight table's quantised block was made
// from (pd_analysis fest-params -> sim/pd/pd_fest_quant), not a dequantisation of that block. It is
// driven as fsw/pd/pd.c drives pd_fest (adaptive_start, adaptive_sample): per sample the sample or
// "invalid", the torque that acts over the coming sample, the k2 in use; at each period end the
// re-tune rule; pd_note_gap's swallowed samples as invalid ones with the held torque. Who may be
// ADAPTIVE is decided by the flight's own check of the table's block (pd_fest_check; yaw's two
// sections are refused there, so yaw is refused here too).
#ifndef SIM_PD_REF_HPP
#define SIM_PD_REF_HPP

#include <array>
#include <cstdint>
#include <memory>
#include <optional>

#include "pd/pd_fest_ref.hpp"

extern "C" {
#include "pd.h"
}

namespace ref {

// One channel's table, dequantised (SI units).
struct PdChannelTable {
    int law = PD_LAW_FAST, src = PD_SRC_FIXED, sched_law = PD_LAW_FAST;
    double Ty = 0.25;             // n_div period [s]
    int n_y = 16, n_bad_max = 4, n_hold = 1, n_frozen = 40;
    double y_lim = 0.5, dy_max = 0.015625, m_max = 2.0, m_frozen = 0.01;   // rad, rad, N m, N m
    double beta_warn = 0.5, beta_lim = 0.785398;                          // rad
    double f0 = 0.01, df = 0.005, f_ground = 0.05;                        // Hz
    double k0 = 2.0, k1 = 20.0, k2_nom = 150.0, k2_cold = 150.0, k2_min = 0.0, k2_max = 1000.0;
    std::array<double, PD_N_NODES> k2_node{};
    std::uint32_t revision = 0;
    // The table's estimator block is usable (pd_fest_check == 0) and Ty = 0.25 s: the flight's
    // condition for ADAPTIVE besides the schedule's law (pd_params_check, pd_set_source).
    bool fest_ok = false;
};
PdChannelTable dequantise(const pd_params_t &p);

// The schedule: linear in f between the nodes at the format's 16-bit fraction (pd_ref.cpp says why),
// clamped at the end nodes and to [k2_min, k2_max]; and the continuous interpolation for comparison.
double pd_sched_k2(const PdChannelTable &t, double f_hz);
double pd_sched_k2_continuous(const PdChannelTable &t, double f_hz);
// The gains as their formats hold them (2^-16 N m/rad): G_P and G_D for a k2 [s].
double pd_gain_p(const PdChannelTable &t);
double pd_gain_d(const PdChannelTable &t, double k2);

struct PdRefIn {
    std::int32_t y_cnt = 0;       // 2^-26 rad
    bool y_valid = false, y_sat = false;
    std::int32_t beta_cnt = 0;    // 2^-24 rad
    bool beta_valid = false;
};

struct PdRefOut {
    double m_nm = 0.0;
    std::uint32_t health = 0u;    // PD_H_* (bits 8..; no fx status in double)
};

class PdRefChannel {
public:
    // fest: the estimator's double design for this channel (make_fest_params), needed for ADAPTIVE.
    // Throws std::invalid_argument for a boot source ADAPTIVE the flight's pd_params_check vetoes
    // (PD_WHY_MODE: no usable estimator block, Ty != 0.25 s, schedule law != law) or without fest.
    explicit PdRefChannel(const PdChannelTable &t, std::shared_ptr<const pd::FestParams> fest = nullptr);
    void init();
    PdRefOut step(const PdRefIn &in);
    // n samples never reached the channel (as pd_note_gap): missing, invalid in their period.
    void note_gap(std::uint32_t n);
    // FIXED; GROUND when the schedule was made for the law in use; ADAPTIVE when, besides, the
    // channel has a usable estimator (as pd_set_source). Entering ADAPTIVE is a cold start.
    bool set_source(int src);
    bool adaptive_ok() const { return t_.sched_law == t_.law && t_.fest_ok && fest_p_ != nullptr; }
    int source() const { return src_; }
    void set_f_ground(double f_hz) { f_ground_ = f_hz; }
    void set_k2_fixed(double k2);
    double k2() const { return k2_; }
    // Counters of spec 40 §8 (as pd_ch_tlm_t).
    std::uint32_t miss = 0, stale = 0, range_rej = 0, rate_rej = 0, period_rej = 0, trq_sat = 0, beta_lim = 0;
    std::uint32_t health_sticky = 0;
    double y_last = 0.0, dy_last = 0.0;
    // The estimator's telemetry (as pd_ch_tlm_t fest_*): zero until the channel first runs ADAPTIVE,
    // then the last sample's; f_hat [Hz] published, word = state | confident << 2 | gate << 3 |
    // (fault reasons & 0xFF) << 8, P of the notch, rms(out)/rms(in), FAULTs since the start.
    double fest_f = 0.0, fest_p_a = 0.0, fest_att = 0.0;
    std::uint32_t fest_word = 0u, fest_resets = 0u;
    const pd::FestRef *fest() const { return fest_ ? &*fest_ : nullptr; }

private:
    double clamp_k2(double k2) const;
    bool period(bool ok, double y, std::uint32_t &h);
    void literal_update(std::uint32_t &h);
    double torque(double m, std::uint32_t &h);
    void adaptive_start();
    void adaptive_sample(bool ok, double y, double m);
    PdChannelTable t_;
    std::shared_ptr<const pd::FestParams> fest_p_;
    std::optional<pd::FestRef> fest_;
    double k2_adapt_ = 0.0, f_pub_prev_ = 0.0;
    int n_inv_fest_ = 0;
    int src_ = 0;
    double f_ground_ = 0.0, k2_fixed_ = 0.0, k2_ = -1.0, gp_ = 0.0, gd_ = 0.0;
    double y_prev_ = 0.0, m_last_ = 0.0, m_held_ = 0.0;
    bool have_prev_ = false;
    std::int32_t same_cnt_ = 0;
    std::uint32_t same_run_ = 0, miss_run_ = 0;
    int nu_ = 0, n_bad_ = 0, zero_run_ = 0;
    double sum_ = 0.0, fill_ = 0.0, xbar_ = 0.0, xbar_prev_ = 0.0;
    bool have_fill_ = false, have_xbar_ = false;
};

}  // namespace ref

#endif
