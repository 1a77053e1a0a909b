// pd_fest_ref — the on-board elastic-frequency estimator of spec 40 §4.4 option A, in double
// precision, written as the fixed sequence of scalar operations that fsw/pd's `pd_fest` will port to
// int32 / int64 (R1): O(1) per sample, every loop bound a compile-time constant, one guarded
// reciprocal per normalisation, no division by a signal that can approach 0. The design ranges
// and proposed fixed-point formats of the state are in the table in FestRef.
//
// Per sample (Ty = 0.25 s); inputs: y valid?, y [rad], the applied torque command M [N m], k2 in use.
//  1. Rigid predictor with slow output injection (§4.4 A.1; "late drift" and "Ix error" gaps):
//       e_k = y_k - xh_k[0];  xh_{k+1} = Ad_r xh_k + Bd_r M_k + L_r e_k   (no injection if y invalid)
//     xh = [x, beta, x', beta'] of Channel::rigid() (exact ZOH). L_r moves the predictor's two z = 1
//     poles (attitude integrator, momentum invariant) to a double pole at s = -w_inj (0.02 rad/s);
//     the gimbal poles stay. A rigid-model error then leaves a transient, never a DC offset or ramp
//     (the open-loop predictor's offset is what drags a notch to 0 Hz after the excitation dies).
//     |e| > e_fault (1e-3 rad) is a §8 divergence; the attitude is re-anchored at once (xh[0] = y).
//  1b. Rigid-response regressors (pitch, yaw): w_r = d xh / d ln(Ix), d ln(H), propagated with the
//     predictor; theta fitted so that it minimises the notch output (the line is notched out of the
//     regressors too, so theta cannot eat it); the residual used below is e - theta' C w.
//  2. Noise reference sigma_hat: E[(D^3 e)^2] = 20 sigma^2 for white noise (a line below 0.2 Hz leaks
//     < 1 %); each term clipped at 9x the running value (kicks, spikes).
//  3. Anti-alias 2nd-order low-pass (0.35 Hz), then the block mean of 4 (Td = 1 s, fixed phase;
//     invalid samples left out, an all-invalid block repeats the last mean and freezes adaptation).
//  Per Td:
//  1c. Two DC blockers (1 - z^-1)/(1 - rho z^-1), rho = 1 - alpha_hp w_line Td: the rigid loop's slow
//     pole (0.035 rad/s at k2 = 475) is what a rigid-model error leaves; the corner follows the line
//     (yaw: section 1's line / 1.74, never section 2's, whose wander would phase-modulate the lines).
//  4. Gate, hysteretic and noise-referenced: r_e = running RMS (20 s) of the residual; opens at
//     r_e >= 8 sigma_ref, closes at r_e < 4 sigma_ref, sigma_ref = max(sigma_hat, sigma_y / 2).
//  5. u = e_d / max(r_n, sigma_ref), r_n a slow RMS (5-s attack, ~2-cycle release; a faster one
//     modulates the line at 2 f and biases the notch at 0.01 Hz); one guarded reciprocal; |u| <= 16.
//  6. Notch section(s) H(z) = (1 + a z^-1 + z^-2) / (1 + k a z^-1 + k^2 z^-2), k = kappa:
//       s_n = in_n - k a s_{n-1} - k^2 s_{n-2};  eps_n = s_n + a s_{n-1} + s_{n-2}   (a priori)
//     phi = s_{n-1} / r_s, error eps / r_s (r_s the running RMS of s: one guarded reciprocal);
//     scalar RLS, forgetting lambda = 0.97:  P <- P / (lambda + phi^2 P) (denominator >= lambda);
//     a <- a - P phi eps; a, P clamped. kappa: 0.6 -> target by (target - kappa) *= 0.97 per
//     adapting Td; target 0.93 (pitch, roll), 1 - 0.16 w Td in [0.93, 0.98] (yaw).
//     Yaw: two sections in cascade; section 2 sees section 1's line notched twice (kappa) and once
//     more (kappa 0.97), searches [f1 / 2.2, f1 / 1.3], and keeps its ratio to section 1 while its
//     kappa anneals; the reported line is the lower of a pair whose ratio is in [1.5, 2.0] while the
//     cascade removes all but 0.3 (rms) of the residual,
//     or a single line proven to be mode 1 (below 0.0155 Hz; continuing a verified pair's lower
//     line; or decaying like mode 1, zeta < 0.007 over 64 s, >= 200 s after excitation, >= 0.04 Hz).
//  7. f_obs = acos(-a/2) / (2 pi Td) (port: 2 asin(sqrt(2 + a)/2), isqrt + odd polynomial);
//     f_raw = f_obs / m_ch; f_hat = f_raw / c(f, k2), c bilinear in the tool's closed-loop table,
//     evaluated twice (f1 = f_raw / c(f_raw, k2), f_hat = f_raw / c(f1, k2)); clamped [0.008, 0.12].
//  Per control period (16 samples, the law's period phase): state machine, confidence, §8 checks;
//  the published f_hat moves in TRACK only by >= 0.5 % (no stream of sub-percent re-tunes).
//
// State machine. ACQUIRE: adapting, not confident. -> TRACK (confident) when the gate is open, kappa
// >= 0.75, P <= 0.1, notch rms(out)/rms(in) <= 0.6, f_hat stable to 1 % per period for >= 3 periods
// and >= 1 cycle of the line, off the clamps, and (yaw) the line is mode 1. TRACK -> HOLD when the
// gate closes or the line fades (rms ratio > 0.7); -> ACQUIRE if the line rule fails (yaw: if
// another strong line took over). HOLD freezes a, P_a, kappa, theta and f_hat (filters keep running),
// is not confident, and leaves to ACQUIRE only on fresh excitation (the gate reopens or r_e doubles).
// FAULT (§8: f_hat on a clamp > 60 s with the gate open; a confident jump > 20 % in a period; notch
// output power >= input for 8 periods once kappa >= 0.75; |e| > 1e-3 rad; a non-finite state) lasts
// one period (the law applies k2_cold), then ACQUIRE at the prior f0 = 0.05 Hz, predictor kept.
#ifndef SIM_PD_PD_FEST_REF_HPP
#define SIM_PD_PD_FEST_REF_HPP

#include <cstdint>
#include <string>
#include <vector>

#include "pd/pd_coupled.hpp"
#include "pd/pd_model.hpp"

namespace ref::pd {

constexpr int kFestNx = 4;          // rigid predictor states
constexpr int kFestDecim = 4;       // samples per Td
constexpr int kFestMaxSections = 2; // yaw: 2
constexpr int kFestEnv = 16;        // yaw: envelope history (periods) for the single-tone proof
constexpr int kFestNr = 2;          // rigid-response regressors: relative Ix, relative H
constexpr int kFestCF = 13;         // c table: f = 0.005 .. 0.125 Hz step 0.01
constexpr int kFestCK = 11;         // c table: k2 = 0 .. 1000 step 100 (the flight table's grid: 143
                                    // words a channel fit the 4 KiB table image; fsw/pd/pd_fest.h)

enum class FestState : int { Acquire = 0, Track = 1, Hold = 2, Fault = 3 };
const char *fest_state_name(FestState s);

// Fault reasons (bit mask, telemetry).
enum : unsigned {
    kFestFaultClamp = 1u,    // f_hat on a clamp > clamp_fault_s with the gate open
    kFestFaultJump = 2u,     // confident jump > jump_fault in one period
    kFestFaultAtten = 4u,    // notch output power >= input power for n_atten_fault periods
    kFestFaultResid = 8u,    // |e| > e_fault_rad
    kFestFaultNumeric = 16u  // non-finite state (the fixed-point port: any fx status bit)
};

// Everything the flight table needs. Units in the names; [design range] -> proposed Q format in
// FestRef's state table.
struct FestParams {
    std::string channel;
    double Ty_s = 0.25;
    int n_y = 16;                   // samples per control period
    double Td_s = 1.0;              // kFestDecim Ty
    int n_sections = 1;             // 2 for yaw
    double m_ch = 1.13;             // Omega_1 / Omega_min of the channel's lowest mode

    // 1. rigid predictor (x [rad], beta [rad], x' [rad/s], beta' [rad/s])
    double Ad_r[kFestNx][kFestNx] = {};
    double Bd_r[kFestNx] = {};      // [rad / (N m)] per row unit
    double L_r[kFestNx] = {};       // output injection
    double w_inj_radps = 0.02;      // its double pole [rad/s]
    // 1b. rigid-response regressors (the "Ix error" gap): sensitivity of the predictor's x to a
    //     relative error of Ix and of H, w_{k+1} = (Ad_r - L_r C) w_k + dA_r xh_k + dB_r M_k
    //     (central differences of the exact ZOH, +-1 %). Their theta is fitted to minimise the notch
    //     output power, so the tone (notched out of the regressors too) cannot pull it.
    int n_reg = 0;                  // 2 for pitch and yaw, 0 for roll (make_fest_params)
    double dA_r[kFestNr][kFestNx][kFestNx] = {};
    double dB_r[kFestNr][kFestNx] = {};
    double lambda_th = 0.995;       // per Td
    double P_th0 = 0.01, P_th_max = 10.0;         // initial P; trace bound (no wind-up while unexcited)
    double theta_max = 0.3;         // |theta_j| (relative parameter error)

    // 1c. high-pass on the decimated residual (per channel in make_fest_params)
    double alpha_hp = 0.4;          // corner / line frequency: 0.25 pitch and roll, 0.4 yaw ...
    double f_hp_min_hz = 0.0095;    // ... with the line frequency floored here: 0.011 / 0.0095 Hz
    double hp_ref_scale = 1.0;      // yaw: the line is section 1's f_obs x this (mode-1 / mode-2 ratio,
                                    // 1 / 1.74), not the lower of the two sections: section 2 wanders
                                    // when it holds no line, and a moving corner shifts the line's
                                    // frequency (step 1c). Not in the flight table (yaw is not ported):
                                    // a port carries it as a compile-time constant or one uq30 word.

    // 3. anti-alias low-pass (full rate) ahead of the block mean
    double f_aa_hz = 0.35;
    double aa_b[3] = {1.0, 0.0, 0.0}, aa_a[2] = {0.0, 0.0};

    // 2. noise reference
    double sigma_y_rad = 2e-6;      // table prior (initial sigma_hat)
    double sigma_floor_rad = 1e-6;  // sigma_ref >= this
    double lambda_noise = 0.999;    // per sample (tau 250 s)
    double noise_clip = 9.0;        // each (D^3 e)^2 / 20 term <= this x the running estimate

    // 4. gate
    double lambda_rms = 0.95;       // per Td, residual RMS for the gate (tau 20 s)
    double lambda_norm = 0.995;     // per Td, normaliser of u: release 1 - k_norm f_obs Td within
    double lambda_norm_lo = 0.95;   //   [lambda_norm_lo, lambda_norm] ...
    double k_norm = 0.45;
    double lambda_norm_att = 0.8;   // ... and attack (tau 5 s)
    double gate_on = 8.0;           // x sigma_ref (the decimated noise is sigma / 2)
    double gate_off = 4.0;
    double u_max = 16.0;            // |u| clamp (normalised units)

    // 6. notch / RLS
    double lambda = 0.97;
    double kappa0 = 0.6, kappa_max = 0.93, rho_kappa = 0.97;
    double kappa_max_hi = 0.98, beta_kappa = 0.0;   // kappa target 1 - beta w Td in [kappa_max, hi]
                                                    // (pitch, roll: 0.93 fixed; yaw: beta 0.16, hi 0.98)
    double P0 = 1.0, P_min = 1e-4, P_max = 1.0;
    double lambda_s = 0.97;         // running RMS of s
    double fobs_lo_hz = 0.005, fobs_hi_hz = 0.30;  // section clamps on the observed tone

    // 7. frequency output
    double f0_hz = 0.05;            // prior
    double pub_hyst = 0.005;        // published f_hat moves in TRACK only by >= 0.5 %
    double f_lo_hz = 0.008, f_hi_hz = 0.12;       // output clamps
    double c_f0_hz = 0.005, c_df_hz = 0.01, c_k20 = 0.0, c_dk2 = 100.0;
    double c[kFestCF][kFestCK] = {};  // observed / partial frequency of mode 1, closed loop

    // confidence (per period)
    double lambda_att = 0.9;        // per Td, notch in/out power for the attenuation figure
    double kappa_conf = 0.75;       // kappa must have annealed to this (~24 adapting Td)
    double P_conf = 0.1;
    double att_conf = 0.6;          // rms(out)/rms(in) of the notch (yaw: of the cascade)
    double att_lose = 0.7;          // TRACK -> HOLD (fading tone) above this
    double rise_hold = 2.0;         // HOLD -> ACQUIRE when r_e grows by this (or the gate reopens)
    double stab_conf = 0.01;        // |f_j / f_{j-1} - 1| per period
    int n_stab = 3;                 // consecutive stable periods, at least, and
    double cyc_conf = 1.0;          // ... spanning this many cycles of the reported tone (n T0 f_obs >= it:
                                    //   the RLS memory, 33 Td, is shorter than a 0.01-Hz cycle, and a
                                    //   half-cycle stall must not pass as convergence)
    double ratio_lo = 1.5, ratio_hi = 2.0;        // yaw tone ratio window
    double sec2_lo = 1.3, sec2_hi = 2.2;          // yaw: section 2's search window below section 1
    double sec2_comove_dk = 0.02;   // yaw: section 2 keeps its ratio to section 1 while its kappa is
                                    //   more than this below its target (~the first 100 adapting Td)
    double kappa_pass3 = 0.97;      // yaw: pole radius of the third pass of section 1's notch ahead of
                                    //   section 2 (wider than section 1's 0.98 at low f)
    double pair_att = 0.3;          // yaw: f_hat follows a pair only while the cascade leaves <= this
                                    //   (rms) of its input
    double two_att1 = 0.02;         // yaw: two lines when section 1 leaves >= this (rms ratio) ...
    double two_att2 = 0.5;          // ... and section 2 removes all but <= this of its input
    double single_tone_max_hz = 0.0155;           // yaw single line below this: mode 1 (mode 2 of f >= 0.0095 Hz
                                                  // is >= 0.0165 Hz; 6 % margin for the notch wander)
    double single_att = 0.3;        // yaw: a single line is one that section 1 notches to <= this (rms)
    double ver_tol = 0.04;          // ... or within this of the last verified lower line
    double zeta_single = 0.007;     // ... or decaying slower than this damping ratio over kFestEnv periods,
    int n_proof = 50;               //     judged no earlier than this many periods after the gate opened,
    double f_proof_min_hz = 0.04;   //     for lines at or above this

    // §8 divergence
    double clamp_fault_s = 60.0;
    double jump_fault = 0.20;
    int n_atten_fault = 8;
    double e_fault_rad = 1e-3;
};

struct FestOptions {
    double sigma_y_rad = 2e-6;
    double w_inj_radps = 0.02;
    double f_aa_hz = 0.35;
};
// The table for channel ch (its nominal model): predictor from ch.rigid() + discretise, L_r by pole
// placement, c(f, k2) from the closed-loop elastic pole of ch (FAST law) at each grid point.
FestParams make_fest_params(const Channel &ch, const FestOptions &opt = {});

struct FestOut {
    double f_hat_hz = 0.05;
    bool confident = false;         // TRACK only
    bool hold_valid = false;        // HOLD entered from TRACK (the frozen f_hat was confident)
    FestState state = FestState::Acquire;
    bool period_end = false;        // this sample closed a control period
    bool gate_open = false;
    double P_a = 0.0;               // RLS P of the reporting section
    double rms_e_rad = 0.0;         // running RMS of the decimated residual
    double sigma_hat_rad = 0.0;
    double att = 1.0;               // notch rms(out)/rms(in), reporting section
    double tone_ratio = 0.0;        // yaw: f_obs(hi) / f_obs(lo); 0 otherwise
    double f_obs_hz[kFestMaxSections] = {0.0, 0.0};
    double kappa = 0.0;
    double e_rad = 0.0;             // this sample's residual
    double theta[kFestNr] = {0.0, 0.0};  // fitted relative Ix, H errors of the rigid model
    unsigned fault = 0u;            // reasons of the last FAULT
    int resets = 0;
};

class FestRef {
public:
    explicit FestRef(const FestParams &p);
    // ACQUIRE at f0; the predictor is re-initialised on the next valid sample unless kept
    void reset(bool keep_predictor = false);
    FestOut step(bool y_valid, double y_rad, double M_applied_nm, double k2_in_use);
    const FestOut &out() const { return out_; }
    const FestParams &params() const { return p_; }
    // The law's control-period phase (0 .. n_y - 1): an estimator started mid-period (a channel entering
    // ADAPTIVE by telecommand) closes its periods with the law's, as the flight's adaptive_start sets
    // pd_fest_t.k_in_period = nu (fsw/pd/pd.c). reset() leaves the phase alone.
    void set_period_phase(int k) { k_in_period_ = (k >= 0 && k < p_.n_y) ? k : 0; }
    double c_of(double f_hz, double k2) const;  // 1 / cinv_of
    double cinv_of(double f_hz, double k2) const;  // 1 / c bilinear on the grid (as flight), clamped to it

private:
    void step_td(double k2);
    void step_period();
    void enter_hold(bool held_conf);
    bool single_proof(double f_obs_hz) const;
    double a_of_fobs(double f_obs_hz) const;
    double fobs_of_a(double a) const;
    void reset_anf();

    FestParams p_;
    FestOut out_;
    // ---- state: design range [measured, nominal runs of all channels] -> proposed format (R1) -----
    // Formats are int32 unless int64 is named; qN = N fractional bits; 6 bits of headroom over the
    // design range as R1 asks. Matrices of the table (Ad_r, Bd_r, L_r, dA_r, dB_r): int32 mantissa
    // + per-row exponent (spec §5); c table uq30; scalars of the table in the state's format.
    // predictor and regressors (per sample)
    bool pred_init_ = false;
    double xh_[kFestNx] = {};       // x +-0.5 (y range) [-4e-4, 0.017], beta +-pi/4 [+-0.28], x' +-0.01
                                    // [+-2e-3], beta' +-1 [+-0.8] rad, rad/s -> int64, LSB 2^-40
    double w_[kFestNr][kFestNx] = {};  // per unit relative error: x +-0.01 [+-5e-3], beta +-0.5 [+-0.29],
                                       // x' +-0.002 [+-1.2e-3], beta' +-0.5 [+-0.11] -> int64, LSB 2^-40
    double phi_sum_[kFestNr] = {};  // <= 4 C w: +-0.04 -> int64 q34
    double phi_d_[kFestNr] = {};    // block means, +-0.01 -> q34 (+-0.125)
    double theta_[kFestNr] = {};    // clamp +-0.3 [-0.04, 0.06] -> q30
    double Pth_[kFestNr][kFestNr] = {};  // trace <= 10 [diag 2e-5 .. 3.2] -> uq27 (symmetric: 3 words)
    double r1_[kFestNr] = {}, r2_[kFestNr] = {};  // regressor notch prefilter, +-2^11 [+-3.4e3 incl. A3-9]
                                                  // -> q16 (the regressors enter normalised by g_e)
    double aa_x_[2] = {}, aa_y_[2] = {};  // anti-alias states, as e -> q34
    double e_prev_[3] = {};         // e_{k-1..k-3}: +-1e-3 rad (|e| > 1e-3 is a FAULT) [+-8.4e-4] -> q34
                                    // (+-0.125 rad: 7 bits headroom; LSB 6e-11 = sigma_y / 3.4e4)
    int n_run_ = 0;                 // consecutive valid samples (sat 3)
    double ms_d3_ = 0.0;            // sigma_hat^2 / sigma_y^2: [0.25, 2^10] [0.92, 1.6] -> uq16
    // decimation
    double blk_sum_ = 0.0;          // <= 4 residuals: +-4e-3 rad -> int64 q34
    int blk_n_ = 0, blk_valid_ = 0; // 0..4
    double e_d_ = 0.0;              // block mean, as e -> q34
    int k_in_period_ = 0;           // 0..n_y-1 (the law's phase)
    // per Td: high-pass, gate, normalisation
    double hp_x1_ = 0.0, hp_h1_ = 0.0, hp_h2_ = 0.0;  // as e [+-6e-4] -> q34
    double ms_e_ = 0.0;             // r_e^2 / sigma_y^2: [0, 2.5e5] (|e| <= 1e-3) [7.2e4] -> int64 uq24
    double ms_n_ = 0.0;             // normaliser, as ms_e_ [7.6e4] -> int64 uq24
    bool gate_ = false;
    double sigma_ref_ = 2e-6;       // [1e-6, 6.4e-5] rad -> uq40 in uint32 (LSB 9e-13 rad)
    // notch sections
    double a_[kFestMaxSections] = {};      // (-2, 2), clamps [a(0.005 Hz), a(0.3 Hz)] = [-1.998, 0.618] -> q29
    double P_[kFestMaxSections] = {};      // [P_min, P_max] = [1e-4, 1] [9e-3, 1] -> uq31 (P_min: 17 bits)
    double kappa_[kFestMaxSections] = {};  // [0.6, 0.98] -> uq31 (kappa^2 formed per Td)
    double s1_[kFestMaxSections] = {}, s2_[kFestMaxSections] = {};  // normalised: bound +-2^11 (u <= 16,
                                    // resonance gain ~ 1/((1 - kappa) 2 sin w)) [+-235] -> q16 (+-32768)
    double ms_s_[kFestMaxSections] = {};   // s^2: [0, 2^22] [3.0e4] -> uq10 in uint32 (sqrt: isqrt)
    double ms_in_[kFestMaxSections] = {}, ms_out_[kFestMaxSections] = {};  // [0, 2^5] [9.7] -> uq26
    double d1_ = 0.0, d2_ = 0.0;    // yaw: second pass of section 1's notch, as s1_ [+-133] -> q16
    double q1_ = 0.0, q2_ = 0.0;    // yaw: third pass (kappa_pass3), as s1_ -> q16
    // yaw line logic
    bool two_ = false;              // two lines seen
    bool slow_ok_ = false;          // the single line passed the decay proof (last period)
    int n_single_ = 0;              // periods in single-line mode (sat 1000)
    int n_excite_ = 0;              // periods since the gate opened (sat 10000)
    double f_lo_ver_hz_ = 0.0;      // last verified lower line (observed) -> uq32
    double env_[kFestEnv] = {};     // r_e at the last kFestEnv period ends, [0, 1e-3] rad -> uq40
    int env_i_ = 0;
    // frequency and period logic
    bool f_moved_ = false;          // f_hat was updated during this period
    double f_hat_hz_ = 0.05;        // [0.008, 0.12] -> uq32 (LSB 2.3e-10 Hz)
    double f_prev_hz_ = 0.05;       // as f_hat
    double f_pub_hz_ = 0.05;        // published f_hat (hysteresis), as f_hat
    double f_rep_obs_hz_ = 0.05;    // observed frequency of the reported line, [0.005, 0.3] -> uq32
    int n_stable_ = 0, n_clamp_ = 0, n_att_bad_ = 0;  // counters, saturating int16
    bool finite_ok_ = true;
    bool e_fault_ = false, held_conf_ = false, gate_rose_ = false;
    double r_hold_rad_ = 0.0;       // r_e at HOLD entry, as env_
    int resid_run_ = 0;             // RESID FAULTs since the last TRACK (2: the predictor restarts)
    FestState state_ = FestState::Acquire;
};

// ---- evaluation: the adaptive closed loop on the exact discrete plant (spec §4.2, A3-5, A3-9) ---
struct K2Schedule {
    std::vector<double> f_hz, k2;   // nodes (ascending f)
    double k2_cold = 475.0;
    double at(double f_hz) const;   // linear in f, clamped at the end nodes
};
// The committed schedule tools/pd/schedule/<channel>_fast.json (pd_analysis synth --json): its
// "k2_cold" and its nodes' "f" and "k2". A reader for that one layout; throws on failure.
K2Schedule load_k2_schedule(const std::string &path);

struct AdaptiveConfig {
    Channel plant;                  // the true channel (scaled(); the estimator's model is not)
    double f_hz = 0.05;
    double horizon_s = 1200.0;
    double sigma_y_rad = 2e-6;
    std::uint64_t seed = 0;
    int latency = 0;                // 1: the command acts one sample later
    double M_max_nm = 2.0;
    double fixed_k2 = -1.0;         // >= 0: constant gain, no estimator in the loop (reference runs)
    bool warm = false;              // GROUND start: k2 = sched(f) instead of k2_cold
    // frequency step: plant f -> f2_hz at t_step_s (state kept), x += kick_rad at t_kick_s
    double f2_hz = -1.0, t_step_s = 1200.0, t_kick_s = 1300.0, kick_rad = 0.017;
};

struct AdaptiveRun {
    std::vector<double> x_rad;      // truth x at every sample
    std::vector<double> t_period_s, f_hat_hz, k2;   // per control period (after its re-tune decision)
    std::vector<int> confident, state;
    std::vector<FestOut> fest;      // the estimator's outputs at each period end
    int n_retunes = 0;              // k2 changes after the first
    int resets = 0;
    double t_star_s = -1.0;         // settle_time over the whole run (or up to t_kick_s for a step run)
    double t_star2_s = -1.0;        // step run: from t_kick_s
    double f_at(double t_s) const;  // f_hat of the period ending at or before t
    int conf_at(double t_s) const;
    double k2_at(double t_s) const;
};
AdaptiveRun fly_adaptive(const AdaptiveConfig &cfg, const FestParams &fp, const K2Schedule &sched);

}  // namespace ref::pd

#endif
