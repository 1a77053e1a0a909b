// pd_fest_ref — see pd_fest_ref.hpp (spec 40 §4.2-§4.4 option A, §8 estimator divergence).
#include "pd/pd_fest_ref.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <stdexcept>

#include <Eigen/Eigenvalues>

namespace ref::pd {

namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;

double clampd(double v, double lo, double hi) { return std::min(std::max(v, lo), hi); }

std::size_t uz(int i) { return static_cast<std::size_t>(i); }

}  // namespace

const char *fest_state_name(FestState s)
{
    switch (s) {
    case FestState::Acquire:
        return "ACQUIRE";
    case FestState::Track:
        return "TRACK";
    case FestState::Hold:
        return "HOLD";
    case FestState::Fault:
        return "FAULT";
    }
    return "?";
}

// ---- table synthesis (host) ------------------------------------------------------------------------
FestParams make_fest_params(const Channel &ch, const FestOptions &opt)
{
    FestParams p;
    p.channel = ch.name;
    p.Ty_s = ch.Ty;
    p.n_y = ch.n_y;
    p.Td_s = kFestDecim * ch.Ty;
    p.n_sections = ch.modes.size() >= 2 ? 2 : 1;
    // kappa schedule: pitch and roll keep the 0.93 of §4.4 (a narrower notch only slows them);
    // yaw narrows the notch at low f so that section 1's skirt leaves mode 1 to section 2.
    p.beta_kappa = p.n_sections == 2 ? 0.16 : 0.0;
    p.kappa_max_hi = p.n_sections == 2 ? 0.98 : p.kappa_max;
    // high-pass corner: 0.25 x the line for pitch and roll (0.4 slows the descent from the prior at
    // 0.03 Hz, whose re-tune then comes too late for A3-5: t* 193 s against 0.55 x 340 s); yaw keeps
    // 0.4, which its section 2 needs against the rigid residual at 0.01-0.02 Hz.
    p.alpha_hp = p.n_sections == 2 ? 0.4 : 0.25;
    // yaw: the high-pass corner follows section 1 / (mode-2 / mode-1 ratio), 1 / 1.74 (step 1c of
    // step_td: a corner that follows section 2 moves with its wander and phase-modulates the line).
    if (p.n_sections == 2) {
        double r_lo = 1e300, r_hi = 0.0;
        for (const Mode &m : ch.modes) {
            r_lo = std::min(r_lo, m.ratio);
            r_hi = std::max(r_hi, m.ratio);
        }
        p.hp_ref_scale = r_lo / r_hi;
    }
    // high-pass frequency floor: above the lowest line for pitch and roll (roll's slow closed-loop
    // pole at 0.01 Hz otherwise drags the notch to the clamp), at the range edge for yaw, whose
    // section 2 must still reach mode 1 at 0.0100 Hz.
    p.f_hp_min_hz = p.n_sections == 2 ? 0.0095 : 0.011;
    // Rigid-response regressors for pitch and yaw (pitch: A3-9's Ix, H errors; yaw: they remove the
    // rigid loop's slow residual that otherwise pulls section 2 off mode 1 at 0.01 Hz, f_hat(300 s)
    // 20 % -> 4 %). Not for roll: its modal inertia is 56 % of Ix, its loop at 0.01-0.02 Hz does not
    // settle (§3.4) and theta absorbs that slow dynamics (f_hat(300 s) at 0.01 Hz 20 % off with them,
    // 3 % without).
    p.n_reg = ch.name == "roll" ? 0 : 2;
    p.sigma_y_rad = opt.sigma_y_rad;
    p.sigma_floor_rad = 0.5 * opt.sigma_y_rad;
    p.w_inj_radps = opt.w_inj_radps;
    if (ch.modes.empty()) {
        throw std::invalid_argument("make_fest_params: the channel has no elastic mode");
    }
    std::size_t i1 = 0;  // the lowest mode: the one the estimator reports
    for (std::size_t i = 1; i < ch.modes.size(); ++i) {
        if (ch.modes[i].ratio < ch.modes[i1].ratio) {
            i1 = i;
        }
    }
    p.m_ch = ch.modes[i1].ratio;

    // 1. Rigid predictor: [x, beta, x', beta'] of the channel without modes, exact ZOH at Ty.
    const Discrete dr = discretise(ch.rigid(), 0.0);
    const Eigen::Matrix4d A = dr.Ad;
    for (int i = 0; i < kFestNx; ++i) {
        p.Bd_r[i] = dr.Bd(i);
        for (int j = 0; j < kFestNx; ++j) {
            p.Ad_r[i][j] = A(i, j);
        }
    }
    // Output injection by Ackermann (observer form): keep the two gimbal poles, move the two z = 1
    // poles (attitude integrator, momentum invariant) to exp(-w_inj Ty) (double).
    Eigen::EigenSolver<Eigen::Matrix4d> es(A, false);
    std::vector<std::complex<double>> z(4);
    for (int i = 0; i < 4; ++i) {
        z[uz(i)] = es.eigenvalues()(i);
    }
    std::sort(z.begin(), z.end(), [](const std::complex<double> &a, const std::complex<double> &b) {
        return std::abs(a - 1.0) > std::abs(b - 1.0);
    });  // the two nearest 1 last
    const double zs = std::exp(-opt.w_inj_radps * ch.Ty);
    z[2] = zs;
    z[3] = zs;
    std::vector<std::complex<double>> poly{1.0};  // coefficients, highest power first
    for (const std::complex<double> &r : z) {
        std::vector<std::complex<double>> np(poly.size() + 1, 0.0);
        for (std::size_t k = 0; k < poly.size(); ++k) {
            np[k] += poly[k];
            np[k + 1] -= r * poly[k];
        }
        poly = np;
    }
    Eigen::Matrix4d phi = Eigen::Matrix4d::Zero(), Apow[5];  // phi(A) = sum_k poly[4-k] A^k
    Apow[0].setIdentity();
    for (int k = 1; k <= 4; ++k) {
        Apow[k] = Apow[k - 1] * A;
    }
    for (int k = 0; k <= 4; ++k) {
        phi += poly[uz(4 - k)].real() * Apow[k];
    }
    Eigen::Matrix4d O;
    for (int k = 0; k < 4; ++k) {
        O.row(k) = Apow[k].row(0);  // C A^k with C = [1 0 0 0]
    }
    const Eigen::Vector4d L = phi * O.fullPivLu().solve(Eigen::Vector4d(0.0, 0.0, 0.0, 1.0));
    Eigen::Matrix4d Acl = A;
    Acl.col(0) -= L;
    Eigen::EigenSolver<Eigen::Matrix4d> ecl(Acl, false);
    for (int i = 0; i < 4; ++i) {
        if (!(std::abs(ecl.eigenvalues()(i)) < 1.0)) {
            throw std::runtime_error("make_fest_params: output injection not stabilising");
        }
    }
    for (int i = 0; i < kFestNx; ++i) {
        p.L_r[i] = L(i);
    }
    // Rigid-response regressors: d(Ad, Bd)/d(ln Ix) and d/d(ln H), central differences.
    for (int r = 0; r < kFestNr; ++r) {
        const double h = 0.01;
        Channel cp = ch.rigid(), cm = ch.rigid();
        (r == 0 ? cp.Ix : cp.H) *= 1.0 + h;
        (r == 0 ? cm.Ix : cm.H) *= 1.0 - h;
        const Discrete dp = discretise(cp, 0.0), dm = discretise(cm, 0.0);
        for (int i = 0; i < kFestNx; ++i) {
            p.dB_r[r][i] = (dp.Bd(i) - dm.Bd(i)) / (2.0 * h);
            for (int j = 0; j < kFestNx; ++j) {
                p.dA_r[r][i][j] = (dp.Ad(i, j) - dm.Ad(i, j)) / (2.0 * h);
            }
        }
    }

    // Anti-alias: 2nd-order Butterworth low-pass at f_aa, bilinear with pre-warping, at Ty.
    p.f_aa_hz = opt.f_aa_hz;
    if (p.f_aa_hz > 0.0) {
        const double K = std::tan(kTwoPi * p.f_aa_hz * ch.Ty / 2.0), q = std::sqrt(2.0);
        const double n = 1.0 / (1.0 + q * K + K * K);
        p.aa_b[0] = K * K * n;
        p.aa_b[1] = 2.0 * p.aa_b[0];
        p.aa_b[2] = p.aa_b[0];
        p.aa_a[0] = 2.0 * (K * K - 1.0) * n;
        p.aa_a[1] = (1.0 - q * K + K * K) * n;
    }
    // c(f, k2): the closed-loop elastic pole of the lowest mode over its partial frequency (§2.2).
    for (int fi = 0; fi < kFestCF; ++fi) {
        const double f = p.c_f0_hz + p.c_df_hz * fi;
        const Discrete d = discretise(ch, f);
        const double om1 = p.m_ch * kTwoPi * f;
        for (int kj = 0; kj < kFestCK; ++kj) {
            const double k2 = p.c_k20 + p.c_dk2 * kj;
            double c = 1.0;
            try {
                const Spectrum sp = spectrum(d, ch, Law::Fast, k2);
                double best = std::numeric_limits<double>::infinity();
                for (const std::complex<double> &s : sp.s_elastic) {
                    if (std::fabs(s.imag() - om1) < best) {
                        best = std::fabs(s.imag() - om1);
                        c = s.imag() / om1;
                    }
                }
            } catch (const std::exception &) {
                c = 1.0;
            }
            p.c[fi][kj] = clampd(c, 0.8, 1.25);
        }
    }
    return p;
}

// ---- the estimator ---------------------------------------------------------------------------------
FestRef::FestRef(const FestParams &p) : p_(p)
{
    ms_d3_ = 1.0;  // sigma_hat starts at the table sigma_y
    reset(false);
}

double FestRef::a_of_fobs(double f_obs_hz) const { return -2.0 * std::cos(kTwoPi * f_obs_hz * p_.Td_s); }

double FestRef::fobs_of_a(double a) const
{
    // port: w Td = 2 asin(sqrt(2 + a) / 2), isqrt of the int64 (2 + a) and an odd polynomial.
    const double v = clampd(2.0 + a, 0.0, 4.0);
    return 2.0 * std::asin(0.5 * std::sqrt(v)) / (kTwoPi * p_.Td_s);
}

void FestRef::reset_anf()
{
    d1_ = d2_ = 0.0;
    q1_ = q2_ = 0.0;
    two_ = false;
    slow_ok_ = false;
    n_single_ = 0;
    n_excite_ = 0;
    f_lo_ver_hz_ = 0.0;
    env_i_ = 0;
    for (double &v : env_) {
        v = 0.0;
    }
    aa_x_[0] = aa_x_[1] = aa_y_[0] = aa_y_[1] = 0.0;
    hp_x1_ = hp_h1_ = hp_h2_ = 0.0;
    for (int r = 0; r < kFestNr; ++r) {
        for (double &v : w_[r]) {
            v = 0.0;
        }
        phi_sum_[r] = phi_d_[r] = theta_[r] = r1_[r] = r2_[r] = 0.0;
        for (int c = 0; c < kFestNr; ++c) {
            Pth_[r][c] = r == c ? p_.P_th0 : 0.0;
        }
    }
    for (int i = 0; i < kFestMaxSections; ++i) {
        // section 2 of yaw starts at the expected mode-2 tone (x 1.74 / m_ch of section 1's prior)
        // yaw: section 2 starts below section 1, where mode 1 sits when section 1 holds mode 2
        const double f_obs0 = p_.f0_hz * p_.m_ch / (i == 0 ? 1.0 : 1.74);
        a_[i] = a_of_fobs(f_obs0);
        P_[i] = p_.P0;
        kappa_[i] = p_.kappa0;
        s1_[i] = s2_[i] = 0.0;
        ms_s_[i] = 0.0;
        ms_in_[i] = ms_out_[i] = 0.0;
    }
}

void FestRef::reset(bool keep_predictor)
{
    if (!keep_predictor) {
        pred_init_ = false;
        for (double &v : xh_) {
            v = 0.0;
        }
    }
    for (double &v : e_prev_) {
        v = 0.0;
    }
    n_run_ = 0;
    blk_sum_ = 0.0;
    blk_n_ = blk_valid_ = 0;
    e_d_ = 0.0;
    ms_e_ = 0.0;
    ms_n_ = 0.0;
    gate_ = false;
    reset_anf();
    f_hat_hz_ = f_prev_hz_ = f_pub_hz_ = p_.f0_hz;
    n_stable_ = n_clamp_ = n_att_bad_ = 0;
    e_fault_ = false;
    held_conf_ = false;
    state_ = FestState::Acquire;
    const int resets = out_.resets;
    const unsigned fault = out_.fault;
    out_ = FestOut{};
    out_.resets = resets;
    out_.fault = fault;
    out_.f_hat_hz = f_hat_hz_;
    // k_in_period_ is the law's phase and is not reset.
}

double FestRef::c_of(double f_hz, double k2) const { return 1.0 / cinv_of(f_hz, k2); }

double FestRef::cinv_of(double f_hz, double k2) const
{
    // 1 / c is what the flight table carries (multiplies only on board), so it is 1 / c that is
    // interpolated, here as there.
    const double u = clampd((f_hz - p_.c_f0_hz) / p_.c_df_hz, 0.0, kFestCF - 1.0);
    const double v = clampd((k2 - p_.c_k20) / p_.c_dk2, 0.0, kFestCK - 1.0);
    const int i = std::min(static_cast<int>(u), kFestCF - 2), j = std::min(static_cast<int>(v), kFestCK - 2);
    const double fu = u - i, fv = v - j;
    const double c00 = 1.0 / p_.c[i][j], c01 = 1.0 / p_.c[i][j + 1];
    const double c10 = 1.0 / p_.c[i + 1][j], c11 = 1.0 / p_.c[i + 1][j + 1];
    const double c0 = c00 + (c01 - c00) * fv;
    const double c1 = c10 + (c11 - c10) * fv;
    return c0 + (c1 - c0) * fu;
}

FestOut FestRef::step(bool y_valid, double y_rad, double M_applied_nm, double k2_in_use)
{
    out_.period_end = false;
    double e = 0.0;
    double phi_k[kFestNr] = {};  // C w_k: the residual's sensitivity, aligned with e_k
    if (!pred_init_ && y_valid) {
        xh_[0] = y_rad;  // started at x^ = y: the rigid transient is predicted from here on
        xh_[1] = xh_[2] = xh_[3] = 0.0;
        pred_init_ = true;
    }
    if (pred_init_) {
        if (y_valid) {
            e = y_rad - xh_[0];
            if (std::fabs(e) > p_.e_fault_rad) {
                // §8 divergence (FAULT at the period end). Re-anchor the attitude at once (an
                // unmodelled jump, such as A3-9's 0.017-rad kick) so that the predictor is consistent
                // when the estimator re-acquires; nothing of this sample enters the filters.
                e_fault_ = true;
                xh_[0] = y_rad;
                e = 0.0;
            }
        }
        for (int r = 0; r < p_.n_reg; ++r) {
            phi_k[r] = w_[r][0];
        }
        // Sensitivities first (they use xh_k): w <- (Ad - L C) w + dA xh + dB M.
        for (int r = 0; r < p_.n_reg; ++r) {
            double wn[kFestNx];
            const double w0 = w_[r][0];
            for (int i = 0; i < kFestNx; ++i) {
                double acc = p_.dB_r[r][i] * M_applied_nm - (y_valid ? p_.L_r[i] * w0 : 0.0);
                for (int j = 0; j < kFestNx; ++j) {
                    acc += p_.Ad_r[i][j] * w_[r][j] + p_.dA_r[r][i][j] * xh_[j];
                }
                wn[i] = acc;
            }
            for (int i = 0; i < kFestNx; ++i) {
                w_[r][i] = wn[i];
            }
        }
        // The predictor always propagates with the applied torque (§8: also across gaps).
        double xn[kFestNx];
        for (int i = 0; i < kFestNx; ++i) {
            double acc = p_.Bd_r[i] * M_applied_nm + p_.L_r[i] * e;  // e = 0 when invalid
            for (int j = 0; j < kFestNx; ++j) {
                acc += p_.Ad_r[i][j] * xh_[j];
            }
            xn[i] = acc;
        }
        for (int i = 0; i < kFestNx; ++i) {
            xh_[i] = xn[i];
        }
    }
    if (y_valid && pred_init_) {
        if (n_run_ >= 3) {
            // third difference: 20 sigma^2 for white noise; normalised by the table sigma_y
            // Each term is clipped at noise_clip x the current estimate, so that a step or spike in
            // y (a 0.017-rad kick gives D^3 = 8500 sigma) cannot inflate sigma_hat, and with it the
            // gate thresholds, for hundreds of seconds.
            const double d3 = (e - 3.0 * e_prev_[0] + 3.0 * e_prev_[1] - e_prev_[2]) / p_.sigma_y_rad;
            const double v = std::min(d3 * d3 / 20.0, p_.noise_clip * ms_d3_);
            ms_d3_ = p_.lambda_noise * ms_d3_ + (1.0 - p_.lambda_noise) * v;
        }
        e_prev_[2] = e_prev_[1];
        e_prev_[1] = e_prev_[0];
        e_prev_[0] = e;
        n_run_ = std::min(n_run_ + 1, 3);
        // 3. anti-alias low-pass ahead of the block mean (the block mean alone passes roll's
        //    0.87-Hz gimbal-body mode at 16 %, aliased to 0.13 Hz, next to the elastic tone)
        const double lp = p_.aa_b[0] * e + p_.aa_b[1] * aa_x_[0] + p_.aa_b[2] * aa_x_[1] - p_.aa_a[0] * aa_y_[0] -
                          p_.aa_a[1] * aa_y_[1];
        aa_x_[1] = aa_x_[0];
        aa_x_[0] = e;
        aa_y_[1] = aa_y_[0];
        aa_y_[0] = lp;
        blk_sum_ += p_.f_aa_hz > 0.0 ? lp : e;
        for (int r = 0; r < p_.n_reg; ++r) {
            phi_sum_[r] += phi_k[r];
        }
        ++blk_valid_;
    } else {
        n_run_ = 0;  // never difference across a gap
    }
    out_.e_rad = e;
    if (++blk_n_ == kFestDecim) {
        step_td(k2_in_use);
        blk_n_ = 0;
        blk_valid_ = 0;
        blk_sum_ = 0.0;
        for (double &v : phi_sum_) {
            v = 0.0;
        }
    }
    if (++k_in_period_ == p_.n_y) {
        k_in_period_ = 0;
        step_period();
        out_.period_end = true;
    }
    return out_;
}

void FestRef::step_td(double k2)
{
    const bool have = blk_valid_ > 0;
    if (have) {
        const double inv_n = 1.0 / blk_valid_;  // port: x {1, 1/2, 1/3, 1/4} table
        e_d_ = blk_sum_ * inv_n;
        for (int r = 0; r < p_.n_reg; ++r) {
            phi_d_[r] = phi_sum_[r] * inv_n;
        }
    }
    // 1b. the residual less the fitted rigid-model error
    double v_d = e_d_;
    for (int r = 0; r < p_.n_reg; ++r) {
        v_d -= theta_[r] * phi_d_[r];
    }
    // 1c. high-pass scheduled on the tone: two DC blockers (1 - z^-1)/(1 - rho z^-1),
    //     rho = 1 - alpha_hp w_obs Td. Removes the rigid loop's slow pole (0.035 rad/s at k2 = 475)
    //     that a rigid-model error leaves in the residual and that drags the notch to 0 Hz; the gain
    //     at the line is ~1 at any f (alpha 0.25: 1.03; 0.4: 1.12), and an LTI filter does not move
    //     a line's frequency.
    //     The corner never follows the estimate below the design range (f_hp_min_hz): below it the
    //     high-pass would pass more of the slow residual, which pulls the notch lower still (roll at
    //     0.01 Hz, whose closed-loop slow pole sits next to the line, ran into the lower clamp).
    //     Yaw: the corner follows section 1 (the dominant, steady line) scaled by the model's mode-1 /
    //     mode-2 ratio, not section 2. A moving corner is not harmless: the high-pass phase at the
    //     line, 2 atan(f_c / f), changes with it, and its rate is a frequency error of the line
    //     (df = dphi/dt / 2 pi) that every section then tracks. Section 2 wanders whenever there is no
    //     second line to hold (in the noise after mode 2 has decayed, and between the beats of mode 2
    //     at low f): with min(f_obs1, f_obs2) the corner swung 0.0064 -> 0.0108 Hz in 24 s at 0.035 Hz,
    //     which is -0.24 rad at the line, a 4.5 % frequency offset while it lasts, and section 1's
    //     estimate of the persistent mode 1 (zeta ~0.002) walked +-1.6 % after the response had
    //     decayed (R4 3.3 % per 600 s, a re-tune every few periods); it also fed back into section 2
    //     through the double notch (R3 at 0.02 Hz, 5.5 % at 300 s). Section 1 / ratio sits at mode 1
    //     when section 1 holds mode 2 (low f), and at ~0.57 f1 (0.23 x the line, as pitch's 0.25)
    //     when section 1 holds mode 1 alone (high f).
    //     At 0.010 Hz both sections still wander with the 135-s beat of modes 1 and 2; what keeps
    //     f_hat right there is section 2's co-motion, third pass and pair_att (step 6/7).
    const double f_hp = std::max(
        p_.n_sections == 2 ? fobs_of_a(a_[0]) * p_.hp_ref_scale : f_rep_obs_hz_, p_.f_hp_min_hz);
    const double rho = 1.0 - p_.alpha_hp * kTwoPi * f_hp * p_.Td_s;
    const double h1 = v_d - hp_x1_ + rho * hp_h1_;
    const double h2 = h1 - hp_h1_ + rho * hp_h2_;
    hp_x1_ = v_d;
    hp_h1_ = h1;
    hp_h2_ = h2;
    v_d = p_.alpha_hp > 0.0 ? h2 : v_d;
    // 2./4. noise reference and the hysteretic gate
    const double sigma_hat = p_.sigma_y_rad * std::sqrt(ms_d3_);
    const double sigma_ref = std::max(sigma_hat, p_.sigma_floor_rad);
    sigma_ref_ = sigma_ref;
    const double en = v_d / p_.sigma_y_rad;
    ms_e_ = p_.lambda_rms * ms_e_ + (1.0 - p_.lambda_rms) * en * en;
    const double r_e = p_.sigma_y_rad * std::sqrt(ms_e_);
    if (!gate_ && r_e >= p_.gate_on * sigma_ref) {
        gate_ = true;
        gate_rose_ = true;
    } else if (gate_ && r_e < p_.gate_off * sigma_ref) {
        gate_ = false;
    }
    // 5. normalise by a slow running RMS (fast attack, slow release): a normaliser that ripples at
    //    2 f_obs modulates the tone and puts a 3 f_obs line beside it, which biases the notch at
    //    low f (seen as +-2.5 % at 0.01 Hz with a 20-s RMS). One guarded reciprocal per Td.
    //    The release spans ~2 cycles of the current tone (lambda = 1 - k_norm f_obs Td, one multiply),
    //    short enough at high f to compress the start-up transient of the residual.
    const double lam_rel = clampd(1.0 - p_.k_norm * f_rep_obs_hz_ * p_.Td_s, p_.lambda_norm_lo, p_.lambda_norm);
    const double lam_n = (en * en > ms_n_) ? p_.lambda_norm_att : lam_rel;
    ms_n_ = lam_n * ms_n_ + (1.0 - lam_n) * en * en;
    const double r_n = p_.sigma_y_rad * std::sqrt(ms_n_);
    const double g_e = 1.0 / std::max(r_n, sigma_ref);
    const double u = clampd(v_d * g_e, -p_.u_max, p_.u_max);
    const bool adapt = have && gate_ && (state_ == FestState::Acquire || state_ == FestState::Track);

    // 6. notch section(s), cascaded
    const double a_lo = a_of_fobs(p_.fobs_lo_hz), a_hi = a_of_fobs(p_.fobs_hi_hz);
    // 1b. the regressors through section 1's notch (its a, kappa before this update)
    double psi[kFestNr] = {};
    for (int r = 0; r < p_.n_reg; ++r) {
        const double k = kappa_[0], a = a_[0];
        const double r0 = phi_d_[r] * g_e - k * a * r1_[r] - k * k * r2_[r];
        psi[r] = r0 + a * r1_[r] + r2_[r];
        r2_[r] = r1_[r];
        r1_[r] = r0;
    }
    double in = u;
    for (int i = 0; i < p_.n_sections; ++i) {
        const double k = kappa_[i], a = a_[i];
        const double s0 = in - k * a * s1_[i] - k * k * s2_[i];
        const double eps = s0 + a * s1_[i] + s2_[i];
        ms_s_[i] = p_.lambda_s * ms_s_[i] + (1.0 - p_.lambda_s) * s0 * s0;
        const double g_s = 1.0 / std::max(std::sqrt(ms_s_[i]), 1e-3);
        const double phi = s1_[i] * g_s, et = eps * g_s;
        if (adapt && i == 0 && p_.n_reg > 0) {
            // theta: RLS on eps = eps0 - theta' psi (normalised by g_s like eps), forgetting lambda_th
            double ps[kFestNr], Pps[kFestNr], den = p_.lambda_th;
            for (int r = 0; r < p_.n_reg; ++r) {
                ps[r] = psi[r] * g_s;
            }
            for (int r = 0; r < p_.n_reg; ++r) {
                Pps[r] = 0.0;
                for (int c = 0; c < p_.n_reg; ++c) {
                    Pps[r] += Pth_[r][c] * ps[c];
                }
                den += ps[r] * Pps[r];
            }
            const double inv_den = 1.0 / den;  // den >= lambda_th
            double tr = 0.0;
            for (int r = 0; r < p_.n_reg; ++r) {
                theta_[r] = clampd(theta_[r] + Pps[r] * inv_den * et, -p_.theta_max, p_.theta_max);
                for (int c = 0; c < p_.n_reg; ++c) {
                    Pth_[r][c] = (Pth_[r][c] - Pps[r] * Pps[c] * inv_den) / p_.lambda_th;
                }
                tr += Pth_[r][r];
            }
            if (tr > p_.P_th_max) {  // bound the wind-up while the regressors are quiet
                const double sc = p_.P_th_max / tr;  // tr > P_th_max > 0
                for (int r = 0; r < p_.n_reg; ++r) {
                    for (int c = 0; c < p_.n_reg; ++c) {
                        Pth_[r][c] *= sc;
                    }
                }
            }
        }
        if (adapt) {
            P_[i] = clampd(P_[i] / (p_.lambda + phi * phi * P_[i]), p_.P_min, p_.P_max);
            // Section 2 searches only [f1 / sec2_hi, f1 / sec2_lo] below section 1: at low f mode 2
            // dominates and section 1's leakage of it (5-10 %) is as strong as mode 1 (~12 %),
            // so an unconstrained section 2 locks onto the leak (seen at 0.01 Hz, ratio 1.1-1.2).
            // Its measured ratio must still fall inside the narrower [ratio_lo, ratio_hi].
            if (i == 1 && out_.f_obs_hz[0] > 0.0) {
                // yaw: section 2 moves with section 1 (same ratio) while its own notch is still
                // annealing. Section 1 descends from the prior for ~100 s; section 2, adapting on its
                // own, reached the pair window only by sliding through it while both notches were
                // wide, and at 0.010 Hz f_hat took a value 18 % high there and held it to ~350 s.
                // Started at section 1's prior / 1.74 and carried along, section 2 arrives next to
                // mode 1 when section 1 lands on mode 2 (0.010 Hz: f_hat(300 s) -1.7 % instead of
                // +18.6 %). Port: f_obs of both sections exist already; one cos (as for the window
                // clamps below) and the guarded reciprocal of f1_old (>= fobs_lo_hz).
                const double k_tgt2 = clampd(1.0 - p_.beta_kappa * kTwoPi * out_.f_obs_hz[1] * p_.Td_s,
                                             p_.kappa_max, p_.kappa_max_hi);
                if (kappa_[1] < k_tgt2 - p_.sec2_comove_dk) {
                    const double f1_new = fobs_of_a(a_[0]);  // section 1 adapted above (i == 0)
                    a_[1] = a_of_fobs(out_.f_obs_hz[1] * f1_new / out_.f_obs_hz[0]);
                }
            }
            const double lo_i = i == 0 ? a_lo : a_of_fobs(out_.f_obs_hz[0] / p_.sec2_hi);
            const double hi_i = i == 0 ? a_hi : a_of_fobs(out_.f_obs_hz[0] / p_.sec2_lo);
            a_[i] = clampd(a_[i] - P_[i] * phi * et, lo_i, hi_i);
            // kappa schedule: anneal (factor rho_kappa per Td) towards a pole radius that keeps the
            // notch width a fixed fraction of its frequency, 1 - kappa = beta_kappa w Td, within
            // [kappa_max, kappa_max_hi]: at low f a 0.93 notch is as wide as the tone's frequency and
            // its skirt hides yaw's mode 1 from section 2 (|H| = 0.56 at 0.01 Hz, 0.93 with 0.98).
            const double w_td = kTwoPi * out_.f_obs_hz[i] * p_.Td_s;
            const double k_tgt = clampd(1.0 - p_.beta_kappa * w_td, p_.kappa_max, p_.kappa_max_hi);
            kappa_[i] = k_tgt - (k_tgt - kappa_[i]) * p_.rho_kappa;
        }
        ms_in_[i] = p_.lambda_att * ms_in_[i] + (1.0 - p_.lambda_att) * in * in;
        ms_out_[i] = p_.lambda_att * ms_out_[i] + (1.0 - p_.lambda_att) * eps * eps;
        s2_[i] = s1_[i];
        s1_[i] = s0;
        in = eps;
        if (i == 0 && p_.n_sections == 2) {
            // yaw: section 2 sees section 1's line notched twice (the same biquad again), so that
            // the 5-15 % leak of a decaying, drifting mode 2 drops to ~1 % and no longer outweighs
            // mode 1 (~12 % of mode 2).
            const double t0 = eps - k * a * d1_ - k * k * d2_;
            in = t0 + a * d1_ + d2_;
            d2_ = d1_;
            d1_ = t0;
            // ... and a third pass, wider (kappa_pass3 0.97 against section 1's 0.98 at low f):
            // section 1 swings +-2.5-4 % about mode 2 with the 135-s beat of modes 1 and 2 at
            // 0.010 Hz, outside the double 0.98 notch, and that leak (as strong as mode 1 before
            // ~300 s) pulled section 2 to the top of its window. Needs pair_att (step 7): with the
            // deeper suppression, section 2 at 0.015 Hz, once mode 2 has died (~1000 s), pairs with
            // section 1 sliding down between the lines (f_hat -21 % at 1200 s without it).
            const double kq = p_.kappa_pass3;
            const double q0 = in - kq * a * q1_ - kq * kq * q2_;
            in = q0 + a * q1_ + q2_;
            q2_ = q1_;
            q1_ = q0;
        }
    }

    // 7. frequency (frozen outside ACQUIRE / TRACK)
    for (int i = 0; i < p_.n_sections; ++i) {
        out_.f_obs_hz[i] = fobs_of_a(a_[i]);
    }
    double f_rep = out_.f_obs_hz[0];
    out_.tone_ratio = 0.0;
    if (p_.n_sections == 2) {
        // Two tones when section 1 leaves a real line for section 2 (>= two_att1 of its input rms)
        // and section 2 notches most of what it gets (<= two_att2).
        two_ = ms_out_[0] >= p_.two_att1 * p_.two_att1 * ms_in_[0] &&
               ms_out_[1] <= p_.two_att2 * p_.two_att2 * ms_in_[1];
        const double lo = std::min(out_.f_obs_hz[0], out_.f_obs_hz[1]);
        const double hi = std::max(out_.f_obs_hz[0], out_.f_obs_hz[1]);
        out_.tone_ratio = two_ ? hi / lo : 0.0;  // lo >= fobs_lo_hz > 0 (port: the window test is
                                                  // 1.5 lo <= hi <= 2 lo, no division; the ratio is telemetry)
        f_rep = two_ ? lo : out_.f_obs_hz[0];    // single: section 1 holds the dominant line
    }
    f_rep_obs_hz_ = f_rep;
    // yaw: f_hat follows only a line known to be mode 1 (the lower of a pair in the ratio window,
    // or a proven single line); otherwise it holds, so a lost mode-1 line never turns into a jump
    // to mode 2.
    bool line_ok = true;
    if (p_.n_sections == 2) {
        const bool r_ok = out_.tone_ratio >= p_.ratio_lo && out_.tone_ratio <= p_.ratio_hi;
        // the pair is judged only once both notches have narrowed (their early power ratios mean nothing)
        // ... and only while the cascade removes most of the residual (both lines real): a section 1
        // sliding between lines (mode 2 decayed) notches little, and its ratio to section 2 means
        // nothing then.
        const bool casc_ok = ms_out_[1] <= p_.pair_att * p_.pair_att * ms_in_[0];
        line_ok = two_ ? (r_ok && kappa_[1] >= p_.kappa_conf && casc_ok) : single_proof(f_rep);
    }
    f_moved_ = f_moved_ || (adapt && line_ok);
    if (adapt && line_ok) {
        const double f_raw = f_rep / p_.m_ch;
        const double f1 = f_raw * cinv_of(f_raw, k2);
        f_hat_hz_ = clampd(f_raw * cinv_of(f1, k2), p_.f_lo_hz, p_.f_hi_hz);
    }
    out_.gate_open = gate_;
    out_.rms_e_rad = r_e;
    for (int r = 0; r < kFestNr; ++r) {
        out_.theta[r] = theta_[r];
    }
    out_.sigma_hat_rad = sigma_hat;
}

// yaw: a single line is mode 1 if (a) it is too low to be mode 2 of any f >= 0.0095 Hz, (b) it
// continues the lower line of a verified pair, or (c) it decays like mode 1 (slow_ok_, per period).
bool FestRef::single_proof(double f_obs_hz) const
{
    // and only a real line: section 1 removes all but single_att of its input (a notch sliding
    // between two lines passes through the window of rule (a) without holding anything)
    const bool line = ms_out_[0] <= p_.single_att * p_.single_att * ms_in_[0];
    const bool low = f_obs_hz <= p_.single_tone_max_hz;
    const bool cont = f_lo_ver_hz_ > 0.0 && std::fabs(f_obs_hz - f_lo_ver_hz_) <= p_.ver_tol * f_lo_ver_hz_;
    return line && (low || cont || slow_ok_);
}

void FestRef::enter_hold(bool held_conf)
{
    state_ = FestState::Hold;
    held_conf_ = held_conf;
    gate_rose_ = false;
    r_hold_rad_ = std::max(out_.rms_e_rad, p_.sigma_floor_rad);
}

void FestRef::step_period()
{
    const double f = f_hat_hz_;
    const double df = std::fabs(f / f_prev_hz_ - 1.0);  // f_prev >= f_lo_hz > 0
    const bool moved = f_moved_;  // a held f_hat is not evidence of convergence
    f_moved_ = false;
    n_stable_ = (df < p_.stab_conf && moved) ? std::min(n_stable_ + 1, 1000) : 0;
    const bool on_clamp = f <= p_.f_lo_hz * (1.0 + 1e-9) || f >= p_.f_hi_hz * (1.0 - 1e-9);
    const bool active = state_ == FestState::Acquire || state_ == FestState::Track;
    n_excite_ = gate_ ? std::min(n_excite_ + 1, 10000) : 0;
    n_clamp_ = (active && gate_ && on_clamp && moved) ? n_clamp_ + 1 : 0;  // held values do not count
    const int last = p_.n_sections - 1;
    const double att = std::sqrt(ms_out_[last] / std::max(ms_in_[0], 1e-12));
    // §8 "notch output power >= input power": judged once the notch is narrow (kappa >= kappa_conf);
    // a wide start-up notch has a broadband gain above 1 and would trip on any non-tonal residual.
    n_att_bad_ = (active && gate_ && kappa_[0] >= p_.kappa_conf && att >= 1.0) ? n_att_bad_ + 1 : 0;
    bool tone_ok = true;
    // yaw: envelope history for the single-tone decay proof (ring of n_env periods)
    env_[env_i_] = out_.rms_e_rad;
    env_i_ = (env_i_ + 1) % kFestEnv;
    double r_old = 0.0;  // the envelope's peak over the window (a growing start-up envelope must not pass)
    for (int i = 0; i < kFestEnv; ++i) {
        r_old = std::max(r_old, env_[i]);
    }
    if (p_.n_sections == 2) {
        if (two_) {
            tone_ok = out_.tone_ratio >= p_.ratio_lo && out_.tone_ratio <= p_.ratio_hi;
            n_single_ = 0;
            slow_ok_ = false;
        } else {
            n_single_ = std::min(n_single_ + 1, 1000);
            // (c) decay proof, judged once per period: it needs kFestEnv single-line periods, the
            // gate open >= n_proof periods (the loop no longer pumps the lines; the rigid loop's slow
            // pole at k2_cold is ~0.023 1/s) and a line >= f_proof_min_hz, where mode 2 (if it were)
            // would be damped >= 0.025 against mode 1's <= 0.0045 (below it the envelopes beat and
            // mode 2's zeta, 0.011 at 0.01 Hz, is too close to the threshold).
            const double w = kTwoPi * f_rep_obs_hz_;
            const double x = p_.zeta_single * w * kFestEnv * p_.n_y * p_.Ty_s;
            slow_ok_ = n_single_ >= kFestEnv && n_excite_ >= p_.n_proof && f_rep_obs_hz_ >= p_.f_proof_min_hz &&
                       r_old > 0.0 && r_old <= out_.rms_e_rad * (1.0 + x + 0.5 * x * x);
            tone_ok = single_proof(f_rep_obs_hz_);
        }
    }
    const int rep = 0;
    const bool conf_ok = gate_ && kappa_[rep] >= p_.kappa_conf && P_[rep] <= p_.P_conf && att <= p_.att_conf &&
                         n_stable_ >= p_.n_stab && n_stable_ * p_.n_y * p_.Ty_s * f_rep_obs_hz_ >= p_.cyc_conf &&
                         !on_clamp && tone_ok;
    const bool fading = att > p_.att_lose;  // the tone no longer dominates the residual
    const bool keep = !on_clamp && tone_ok;
    bool finite = std::isfinite(f) && std::isfinite(ms_e_);
    for (int i = 0; i < kFestMaxSections; ++i) {
        finite = finite && std::isfinite(a_[i]) && std::isfinite(s1_[i]) && std::isfinite(P_[i]);
    }
    for (double v : xh_) {
        finite = finite && std::isfinite(v);
    }
    finite_ok_ = finite;
    unsigned fault = 0u;
    if (static_cast<double>(n_clamp_) * p_.n_y * p_.Ty_s > p_.clamp_fault_s) {
        fault |= kFestFaultClamp;
    }
    if (state_ == FestState::Track && df > p_.jump_fault) {
        fault |= kFestFaultJump;
    }
    if (n_att_bad_ >= p_.n_atten_fault) {
        fault |= kFestFaultAtten;
    }
    if (e_fault_) {
        fault |= kFestFaultResid;
    }
    if (!finite) {
        fault |= kFestFaultNumeric;
    }

    if (state_ == FestState::Fault) {
        // one period in FAULT (k2_cold applied by the law), then ACQUIRE at f0. The predictor is
        // kept (its beta, x' follow the applied torque, which an attitude jump does not change)
        // unless its state is not finite, or a second RESID FAULT since the last TRACK says its rates
        // are wrong: RESID zeroes the residual, so the output injection could never correct them
        // (found by feeding the port garbage, tests/pd/test_pd_fest.c: FAULT every other period, forever).
        const bool keep_pred = finite_ok_ && resid_run_ < 2;
        resid_run_ = keep_pred ? resid_run_ : 0;
        reset(keep_pred);
    } else if (fault != 0u) {
        state_ = FestState::Fault;
        out_.fault = fault;
        ++out_.resets;
        resid_run_ = (fault & kFestFaultResid) != 0u ? std::min(resid_run_ + 1, 1000) : 0;
    } else {
        switch (state_) {
        case FestState::Acquire:
            if (!gate_) {
                enter_hold(false);
            } else if (conf_ok) {
                state_ = FestState::Track;
                resid_run_ = 0;
            }
            break;
        case FestState::Track: {
            // A fading line: HOLD keeps the estimate made while it lasted. Yaw only: if the residual
            // is still strong, another line has taken over (mode 2 decayed, mode 1 remains): re-acquire.
            const bool other_line = p_.n_sections == 2 && out_.rms_e_rad >= p_.gate_on * sigma_ref_;
            if (!gate_ || (fading && !other_line)) {
                enter_hold(true);
            } else if (fading || !keep) {
                state_ = FestState::Acquire;
                n_stable_ = 0;
            }
            break;
        }
        case FestState::Hold:
            // leave only on fresh excitation: the gate reopened, or the residual grew x rise_hold
            if (gate_rose_ || out_.rms_e_rad >= p_.rise_hold * r_hold_rad_) {
                state_ = FestState::Acquire;  // a kept; confidence is earned again
                held_conf_ = false;
                n_stable_ = 0;
            }
            break;
        case FestState::Fault:
            break;
        }
    }
    if (p_.n_sections == 2 && two_ && state_ == FestState::Track) {
        f_lo_ver_hz_ = f_rep_obs_hz_;  // the lower line of a verified pair
    }
    f_prev_hz_ = f_hat_hz_;
    out_.state = state_;
    // HOLD is not confident: f_hat is frozen and still reported, k2 stays where it is (the re-tune
    // rule acts only on a confident estimate), but nothing vouches for a frozen value once the plant
    // may have changed unobserved (A3-9's frequency step: 0.05 -> 0.02 Hz with no excitation).
    out_.confident = state_ == FestState::Track;
    out_.hold_valid = state_ == FestState::Hold && held_conf_;
    // Published f_hat with a +-pub_hyst hysteresis: the scheduled k2 moves only when the estimate
    // does (R4: no stream of sub-percent re-tunes from the estimator's jitter on a fading line).
    if (std::fabs(f_hat_hz_ - f_pub_hz_) >= p_.pub_hyst * f_pub_hz_ || state_ != FestState::Track) {
        f_pub_hz_ = f_hat_hz_;
    }
    out_.f_hat_hz = f_pub_hz_;
    out_.P_a = P_[rep];
    out_.att = att;
    out_.kappa = kappa_[rep];
}

// ---- evaluation ------------------------------------------------------------------------------------
double K2Schedule::at(double f) const
{
    if (f_hz.empty()) {
        return k2_cold;
    }
    if (f <= f_hz.front()) {
        return k2.front();
    }
    if (f >= f_hz.back()) {
        return k2.back();
    }
    std::size_t i = 0;
    while (i + 2 < f_hz.size() && f > f_hz[i + 1]) {
        ++i;
    }
    const double w = (f - f_hz[i]) / (f_hz[i + 1] - f_hz[i]);
    return k2[i] + (k2[i + 1] - k2[i]) * w;
}

K2Schedule load_k2_schedule(const std::string &path)
{
    std::ifstream in(path);
    if (!in) {
        throw std::runtime_error("cannot read schedule " + path);
    }
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string t = ss.str();
    auto number_after = [&](std::size_t pos) { return std::strtod(t.c_str() + t.find(':', pos) + 1, nullptr); };
    K2Schedule sc;
    const std::size_t kc = t.find("\"k2_cold\"");
    std::size_t p = t.find("\"nodes\"");
    if (kc == std::string::npos || p == std::string::npos) {
        throw std::runtime_error("schedule " + path + ": no k2_cold or nodes");
    }
    sc.k2_cold = number_after(kc);
    while ((p = t.find("\"f\":", p)) != std::string::npos) {
        const std::size_t q = t.find("\"k2\":", p);  // not "k2opt"
        if (q == std::string::npos) {
            break;
        }
        sc.f_hz.push_back(number_after(p));
        sc.k2.push_back(number_after(q));
        p = q;
    }
    if (sc.f_hz.size() < 2) {
        throw std::runtime_error("schedule " + path + ": fewer than 2 nodes");
    }
    return sc;
}

namespace {
std::size_t period_index(const std::vector<double> &t, double t_s)
{
    std::size_t i = 0;
    while (i + 1 < t.size() && t[i + 1] <= t_s + 1e-9) {
        ++i;
    }
    return i;
}
}  // namespace

double AdaptiveRun::f_at(double t_s) const { return f_hat_hz.empty() ? -1.0 : f_hat_hz[period_index(t_period_s, t_s)]; }
int AdaptiveRun::conf_at(double t_s) const { return confident.empty() ? 0 : confident[period_index(t_period_s, t_s)]; }
double AdaptiveRun::k2_at(double t_s) const { return k2.empty() ? -1.0 : k2[period_index(t_period_s, t_s)]; }

AdaptiveRun fly_adaptive(const AdaptiveConfig &cfg, const FestParams &fp, const K2Schedule &sched)
{
    const Channel &ch = cfg.plant;
    const Discrete d1 = discretise(ch, cfg.f_hz);
    const bool stepf = cfg.f2_hz > 0.0;
    const Discrete d2 = stepf ? discretise(ch, cfg.f2_hz) : d1;
    const Eigen::Index ns = d1.Ad.rows();
    Eigen::VectorXd s = Eigen::VectorXd::Zero(ns), sn(ns);
    s(0) = ch.x0;
    const long N = std::lround(cfg.horizon_s / ch.Ty);
    const long n_step = stepf ? std::lround(cfg.t_step_s / ch.Ty) : -1;
    const long n_kick = stepf ? std::lround(cfg.t_kick_s / ch.Ty) : -1;
    const bool adaptive = cfg.fixed_k2 < 0.0;
    FestRef fest(fp);
    double k2 = adaptive ? (cfg.warm ? sched.at(cfg.f_hz) : sched.k2_cold) : cfg.fixed_k2;
    std::mt19937_64 rng(cfg.seed);
    std::normal_distribution<double> noise(0.0, cfg.sigma_y_rad);
    const double GP = ch.k0 * ch.k1;
    double y_prev = 0.0, M_delayed = 0.0, f_prev = fp.f0_hz;
    bool first = true;
    AdaptiveRun r;
    r.x_rad.reserve(static_cast<std::size_t>(N + 1));
    const Eigen::MatrixXd *Ad = &d1.Ad;
    const Eigen::VectorXd *Bd = &d1.Bd;
    for (long n = 0; n <= N; ++n) {
        if (n == n_step) {
            Ad = &d2.Ad;
            Bd = &d2.Bd;
        }
        if (n == n_kick) {
            s(0) += cfg.kick_rad;
        }
        const double x = s(0);
        r.x_rad.push_back(x);
        if (n == N) {
            break;
        }
        const double y = x + noise(rng);
        if (first) {
            y_prev = y;
            first = false;
        }
        const double GD = ch.k0 * k2 / ch.Ty;
        const double M = clampd(-(GP * y + GD * (y - y_prev)), -cfg.M_max_nm, cfg.M_max_nm);
        y_prev = y;
        const double M_app = cfg.latency != 0 ? M_delayed : M;
        M_delayed = M;
        if (adaptive) {
            const FestOut o = fest.step(true, y, M, k2);
            if (o.period_end) {
                // §4.2 re-tune at the period boundary (no invalid samples in these runs)
                const double k2_old = k2;
                if (o.state == FestState::Fault) {
                    k2 = sched.k2_cold;
                } else if (o.confident && std::fabs(o.f_hat_hz / f_prev - 1.0) < 0.02) {
                    k2 = sched.at(o.f_hat_hz);
                }
                if (std::fabs(k2 - k2_old) > 1e-9) {
                    ++r.n_retunes;
                }
                f_prev = o.f_hat_hz;
                r.t_period_s.push_back(static_cast<double>(n + 1) * ch.Ty);
                r.f_hat_hz.push_back(o.f_hat_hz);
                r.k2.push_back(k2);
                r.confident.push_back(o.confident ? 1 : 0);
                r.state.push_back(static_cast<int>(o.state));
                r.fest.push_back(o);
                r.resets = o.resets;
            }
        }
        sn.noalias() = (*Ad) * s + (*Bd) * M_app;
        s.swap(sn);
    }
    if (stepf) {
        const std::size_t nk = static_cast<std::size_t>(n_kick);
        r.t_star_s = settle_time(std::vector<double>(r.x_rad.begin(), r.x_rad.begin() + static_cast<long>(nk)),
                                 ch.Ty, ch.dx);
        r.t_star2_s = settle_time(std::vector<double>(r.x_rad.begin() + static_cast<long>(nk), r.x_rad.end()),
                                  ch.Ty, ch.dx);
    } else {
        r.t_star_s = settle_time(r.x_rad, ch.Ty, ch.dx);
    }
    return r;
}

}  // namespace ref::pd
