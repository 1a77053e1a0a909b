#include "respin/rsp_ref.hpp"

#include "respin/rsp_cmg_ref.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <stdexcept>

#include <Eigen/Dense>

namespace ref {

namespace {

double sgn(double x) { return x >= 0.0 ? 1.0 : -1.0; }   // spec 30 §3.1: Sgn 0 = +1

double clampd(double x, double lo, double hi) { return std::min(std::max(x, lo), hi); }

double norm3(const V3 &v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

}  // namespace

RespinTable dequantise(const rsp_params_t &p)
{
    // Every field is an integer times a power of two: ldexp is exact, so thresholds compare in
    // double exactly as the integers compare in the flight code (eps1 + h_eps included: both are
    // multiples of 2^-30 below 2, their sum is exact).
    RespinTable t;
    t.period_us = p.period_us;
    t.ts_s = static_cast<double>(p.period_us) * 1e-6;
    t.mode = p.mode;
    t.act_kind = p.act_kind;
    for (std::size_t i = 0; i < 3u; ++i) {
        t.j_kgm2[i] = std::ldexp(static_cast<double>(p.j_q19[i]), -19);
    }
    t.iw_kgm2 = std::ldexp(static_cast<double>(p.iw_q30), -30);
    t.eps1 = std::ldexp(static_cast<double>(p.eps1_q30), -30);
    t.eps2 = std::ldexp(static_cast<double>(p.eps2_q30), -30);
    t.heps = std::ldexp(static_cast<double>(p.heps_q30), -30);
    t.m_nm = std::ldexp(static_cast<double>(p.m_q24), -24);
    t.k_pnms = std::ldexp(static_cast<double>(p.k_q30), -30);
    t.mstar_nm = std::ldexp(static_cast<double>(p.mstar_q24), -24);
    t.mmax_nm = std::ldexp(static_cast<double>(p.mmax_q24), -24);
    t.hlim_nms = std::ldexp(static_cast<double>(p.hlim_q20), -20);
    t.inv_ts_hz = std::ldexp(static_cast<double>(p.inv_ts_q16), -16);
    t.gguard_nms = std::ldexp(static_cast<double>(p.gguard_q20), -20);
    t.gmin_nms = std::ldexp(static_cast<double>(p.gmin_q20), -20);
    t.n_g0 = p.n_g0;
    t.gyro_max_cnt = p.gyro_max_cnt;
    t.whl_max_cnt = p.whl_max_cnt;
    t.n_fault = p.n_fault;
    t.n_stale = p.n_stale;
    t.n_whl_est = p.n_whl_est;
    t.outlier_nms = std::ldexp(static_cast<double>(p.outlier_q20), -20);
    t.outlier_rel = std::ldexp(static_cast<double>(p.outlier_rel_q16), -16);
    t.drift = std::ldexp(static_cast<double>(p.drift_q30), -30);
    t.drift_sh = p.drift_sh;
    t.ealarm_j = std::ldexp(static_cast<double>(p.ealarm_q32), -32);
    t.done_xi = std::ldexp(static_cast<double>(p.done_xi_q30), -30);
    t.done_h_nms = std::ldexp(static_cast<double>(p.done_h_q20), -20);
    t.done_ticks = p.done_ticks;
    t.gfilt_alpha = std::ldexp(static_cast<double>(p.gfilt_alpha_q30), -30);
    t.hg_nms = std::ldexp(static_cast<double>(p.hg_q20), -20);
    t.sr_lambda = std::ldexp(static_cast<double>(p.lambda_q28), -28);
    t.umax_cnt = p.umax_cnt;
    t.ms_sing = std::ldexp(static_cast<double>(p.ms_sing_q28), -28);
    t.rotor_nom_cnt = p.rotor_nom_cnt;
    t.rotor_tol = std::ldexp(static_cast<double>(p.rotor_tol_q16), -16);
    return t;
}

// ------------------------------------------------------------------------------------------------
// Law

V3 rsp_distribute(const RespinTable &t, const V3 &mcmd_nm, const V3 &h_nms, std::array<bool, 3> *clip,
                  std::array<bool, 3> *hbound)
{
    V3 out{};
    for (std::size_t i = 0; i < 3u; ++i) {
        double m = mcmd_nm[i];
        (*clip)[i] = std::fabs(m) > t.mmax_nm;
        m = clampd(m, -t.mmax_nm, t.mmax_nm);
        // H after the hold is H - M Ts: keep it within +-h_lim. The flight multiplies by the
        // table's 1/Ts (no division), so the reference does too.
        const double lo = (h_nms[i] - t.hlim_nms) * t.inv_ts_hz;
        const double hi = (h_nms[i] + t.hlim_nms) * t.inv_ts_hz;
        const double mc = clampd(m, lo, hi);
        (*hbound)[i] = mc < m || mc > m;   // the clamp changed the command
        // Past h_lim (friction, quantisation) the clamp commands a moment back; the final clip
        // keeps that within the motor limit.
        out[i] = clampd(mc, -t.mmax_nm, t.mmax_nm);
    }
    return out;
}

RespinLawOut rsp_law_tick(const RespinTable &t, const RespinLawState &s, const V3 &g, const V3 &h_nms)
{
    RespinLawOut o;
    RespinLawState n = s;
    o.g = g;
    const double xa = std::sqrt(g[0] * g[0] + g[2] * g[2]);
    o.xi_abs = xa;

    // Region (§3.5 hysteresis; at the first tick the plain thresholds of §3.2). Guard: no FAR.
    std::uint32_t r = s.region;
    if (!s.started) {
        r = xa < t.eps1 ? RSP_RG_LIN : (xa <= t.eps2 ? RSP_RG_MID : RSP_RG_FAR);
        if (s.guard && r == RSP_RG_FAR) {
            r = RSP_RG_MID;
        }
        n.a_f = g[1] >= 0.0 ? 1 : -1;     // initial a_f = Sgn g_y(t0), both modes
        n.started = true;
    } else {
        const bool far_ok = !s.guard;
        switch (s.region) {
        case RSP_RG_LIN:
            if (far_ok && xa > t.eps2 + t.heps) {
                r = RSP_RG_FAR;
            } else if (xa > t.eps1 + t.heps) {
                r = RSP_RG_MID;
            }
            break;
        case RSP_RG_MID:
            if (far_ok && xa > t.eps2 + t.heps) {
                r = RSP_RG_FAR;
            } else if (xa < t.eps1 - t.heps) {
                r = RSP_RG_LIN;
            }
            break;
        default:   // FAR
            if (xa < t.eps1 - t.heps) {
                r = RSP_RG_LIN;
            } else if (xa < t.eps2 - t.heps) {
                r = RSP_RG_MID;
            }
            break;
        }
        o.switched = r != s.region;
    }
    n.region = r;

    // a_f: NEAREST re-selects the nearer of +-e_y while FAR (guard: while |xi| > eps2), keeping it
    // on a tie (C_phi = 0: Sgn 0 = +1); otherwise it is latched. PRINTED never re-selects.
    const bool free_af = r == RSP_RG_FAR || (s.guard && xa > t.eps2);
    if (t.mode == RSP_MODE_NEAREST && free_af && static_cast<double>(n.a_f) * g[1] < 0.0) {
        n.a_f = -n.a_f;
    }
    n.latched = !free_af;
    const double af = static_cast<double>(n.a_f);
    o.xi = {{-af * g[2], 0.0, af * g[0]}};
    o.cphi = af * g[1];
    if (r != RSP_RG_LIN && xa > 0.0) {   // hysteresis keeps |xi| >= eps1 - h_eps here
        o.e_xi = {{o.xi[0] / xa, 0.0, o.xi[2] / xa}};
    }

    // Law (§3.2), D = I, H_f = 0.
    for (std::size_t i = 0; i < 3u; ++i) {
        if (r == RSP_RG_LIN) {
            o.mcmd_nm[i] = -t.m_nm * (o.xi[i] - t.k_pnms * h_nms[i]);
        } else if (r == RSP_RG_MID) {
            o.mcmd_nm[i] = -t.m_nm * (o.e_xi[i] * sgn(o.cphi) - t.k_pnms * h_nms[i]);
        } else {
            o.mcmd_nm[i] = -t.mstar_nm * sgn(g[i]);
        }
    }
    o.mdel_nm = rsp_distribute(t, o.mcmd_nm, h_nms, &o.clip, &o.hbound);
    for (std::size_t i = 0; i < 3u; ++i) {
        o.whl_torque_nm[i] = -o.mdel_nm[i];
    }
    o.next = n;
    return o;
}

// ------------------------------------------------------------------------------------------------
// Module

void RespinRef::reset(const RespinTable &t)
{
    *this = RespinRef();
    t_ = t;
}

RespinRefOut RespinRef::step(const RespinRefIn &in)
{
    RespinRefOut o;
    const RespinTable &t = t_;

    // 1. Inputs. The gyro is all-or-nothing: any axis missing, SAT or at full scale -> invalid.
    V3 w{}, h{};
    bool gyro_ok = (in.valid & 0x7u) == 0x7u && (in.sat & 0x7u) == 0u;
    for (std::size_t i = 0; i < 3u; ++i) {
        const std::int64_t c = in.gyro_cnt[i];
        gyro_ok = gyro_ok && (c < t.gyro_max_cnt && -c < t.gyro_max_cnt);
        w[i] = static_cast<double>(in.gyro_cnt[i]) * kRspGyroLsbRadps;
    }
    bool whl_ok = true;
    const bool cmg = t.act_kind == RSP_ACT_GYRODINES;
    CmgGeom geom;
    if (cmg) {
        // Gyrodines: all four gimbal angles or an invalid tick; the rotors are health only (§8):
        // off nominal by more than rotor_tol for n_fault ticks in a row latches ROTOR_FAULT.
        whl_ok = (in.valid & 0x3C0u) == 0x3C0u;
        std::array<double, 4> beta{};
        bool off = false;
        for (std::size_t k = 0; k < 4u; ++k) {
            beta[k] = cmg_beta_rad(static_cast<std::uint32_t>(in.gimbal_cnt[k]));
            const double d = static_cast<double>(in.rotor_cnt[k]) - static_cast<double>(t.rotor_nom_cnt);
            if ((in.valid & (1u << (10u + k))) != 0u && std::fabs(d) > t.rotor_tol * static_cast<double>(t.rotor_nom_cnt)) {
                off = true;
            }
        }
        rotor_run_ = off ? rotor_run_ + 1u : 0u;
        rotor_fault_ = rotor_fault_ || rotor_run_ >= t.n_fault;
        geom = cmg_geom(beta, t.hg_nms);
        h = geom.h_nms;
    }
    for (std::size_t i = 0; i < 3u && !cmg; ++i) {
        const std::uint32_t bit = 1u << (3u + i);
        const std::int64_t c = in.whl_cnt[i];
        const bool ok = (in.valid & bit) != 0u && (in.sat & bit) == 0u && c <= t.whl_max_cnt && -c <= t.whl_max_cnt;
        if (ok) {
            h[i] = t.iw_kgm2 * (static_cast<double>(in.whl_cnt[i]) * kRspWhlLsbRadps);
            whl_miss_[i] = 0u;
            h_last_nms_[i] = h[i];
        } else if (whl_miss_[i] < t.n_whl_est) {
            // §8: a missing wheel speed for <= n_whl_est ticks is propagated from the last command.
            ++whl_miss_[i];
            h[i] = h_last_nms_[i] - mdel_last_nm_[i] * t.ts_s;
            h_last_nms_[i] = h[i];
            o.health |= RSP_H_WHL_EST;
        } else {
            whl_ok = false;
            h[i] = h_last_nms_[i];
        }
    }
    o.h_nms = h;
    if (!gyro_ok) {
        o.health |= RSP_H_GYRO_BAD;
    }
    if (!whl_ok) {
        o.health |= RSP_H_WHL_BAD;
    }

    V3 gv{};
    for (std::size_t i = 0; i < 3u; ++i) {
        gv[i] = t.j_kgm2[i] * w[i] + h[i];
    }
    const double gabs = norm3(gv);
    bool valid = gyro_ok && whl_ok;

    // 2. g0 (§3.6): the mean |G| over the first n_g0 valid ticks, zero command meanwhile.
    if (phase_ == RSP_PH_G0) {
        if (valid) {
            g0_sum_nms_ += gabs;
            ++n_acc_;
            if (n_acc_ >= t.n_g0) {
                g0_nms_ = g0_sum_nms_ / static_cast<double>(n_acc_);
                r0_pnms_ = 1.0 / g0_nms_;    // the only division by g0
                phase_ = g0_nms_ < t.gmin_nms ? RSP_PH_LOW : RSP_PH_RUN;
                law_.guard = g0_nms_ < t.gguard_nms;
            }
        }
        if (phase_ == RSP_PH_G0) {
            o.health |= RSP_H_G0_WAIT;
        }
        valid = false;   // no law this tick, whatever the inputs
    } else if (phase_ == RSP_PH_RUN && valid) {
        const double gate = std::max(t.outlier_rel * g0_nms_, t.outlier_nms);
        if (std::fabs(gabs - g0_nms_) > gate) {
            o.health |= RSP_H_OUTLIER;
            valid = false;
        }
    }
    if (phase_ == RSP_PH_LOW) {
        o.health |= RSP_H_LOW_MOMENTUM;
        valid = false;
    }
    if (law_.guard) {
        o.health |= RSP_H_GUARD;
    }
    o.phase = phase_;
    o.g0_nms = g0_nms_;
    o.valid = valid;

    if (valid) {
        // 2b. The optional G filter (§3.6): seeded from G_k after any invalid tick, as the flight.
        V3 gsrc = gv;
        if (t.gfilt_alpha > 0.0) {
            if (!have_ghat_) {
                ghat_nms_ = gv;
                have_ghat_ = true;
            } else {
                const V3 th{{w[0] * t.ts_s, w[1] * t.ts_s, w[2] * t.ts_s}};
                auto cross = [](const V3 &a, const V3 &b) {
                    return V3{{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}};
                };
                const V3 c1 = cross(th, ghat_nms_);
                const V3 c2 = cross(th, c1);
                for (std::size_t i = 0; i < 3u; ++i) {
                    const double gm = ghat_nms_[i] - c1[i] + 0.5 * c2[i];
                    ghat_nms_[i] = gm + t.gfilt_alpha * (gv[i] - gm);
                }
                const double c = 2.0 - norm3(ghat_nms_) * r0_pnms_;   // one Newton step to |G_hat| = g0
                for (std::size_t i = 0; i < 3u; ++i) {
                    ghat_nms_[i] *= c;
                }
            }
            gsrc = ghat_nms_;
        }
        // 3-6. The law.
        for (std::size_t i = 0; i < 3u; ++i) {
            o.g[i] = gsrc[i] * r0_pnms_;
        }
        o.rho = gabs * r0_pnms_ - 1.0;
        RespinLawOut lo = rsp_law_tick(t, law_, o.g, h);
        if (cmg) {
            // The whole M_cmd to the steering (§4): no per-axis clip, no momentum clamp.
            CmgTable ct;
            ct.hg_nms = t.hg_nms;
            ct.lambda = t.sr_lambda;
            ct.umax_cnt = t.umax_cnt;
            ct.umax_radps = static_cast<double>(t.umax_cnt) * kCmgRateLsbRadps;
            ct.ms_sing = t.ms_sing;
            const CmgSteer st = cmg_steer(ct, geom, lo.mcmd_nm);
            lo.mdel_nm = st.mdel_nm;
            lo.whl_torque_nm = {{0.0, 0.0, 0.0}};
            lo.clip = {{false, false, false}};
            lo.hbound = {{false, false, false}};
            o.gimbal_rate_cnt = st.rate_cnt;
            o.ms = st.ms;
            o.s_rate = st.s;
            if ((st.flags & RSP_CMG_F_SINGULAR) != 0u) {
                o.health |= RSP_H_SINGULAR;
            }
            if ((st.flags & RSP_CMG_F_RATE_LIMITED) != 0u) {
                o.health |= RSP_H_RATE_LIMITED;
            }
        }
        if (lo.switched) {
            ++n_switch_;
        }
        law_ = lo.next;
        o.xi_abs = lo.xi_abs;
        o.cphi = lo.cphi;
        o.e_xi = lo.e_xi;
        o.mcmd_nm = lo.mcmd_nm;
        o.mdel_nm = lo.mdel_nm;
        o.whl_torque_nm = lo.whl_torque_nm;
        for (std::size_t i = 0; i < 3u; ++i) {
            if (lo.clip[i]) {
                o.health |= RSP_H_CLIP;
            }
            if (lo.hbound[i]) {
                o.health |= RSP_H_HBOUND;
            }
        }

        // 7. Energy bookkeeping (§8) from measured quantities: trapezoid work between valid ticks.
        double tj = 0.0;
        for (std::size_t i = 0; i < 3u; ++i) {
            tj += 0.5 * (t.j_kgm2[i] * w[i]) * w[i];
        }
        if (!have_t0_) {
            t0_j_ = tj;
            w_j_ = 0.0;
            have_t0_ = true;
        } else if (have_prev_) {
            double dw = 0.0;
            for (std::size_t i = 0; i < 3u; ++i) {
                dw += 0.5 * (w[i] + omega_prev_radps_[i]) * (h[i] - h_prev_nms_[i]);
            }
            w_j_ -= dw;
        }
        omega_prev_radps_ = w;
        h_prev_nms_ = h;
        have_prev_ = true;
        o.t_j = tj;
        o.w_j = w_j_;
        o.re_j = tj - t0_j_ - w_j_;
        if (o.re_j > t.ealarm_j) {
            o.health |= RSP_H_ENERGY_ALARM;
        }

        // Done (§3.7): |xi| < done_xi, C_phi > 0, |H_i - H_f| < done_h, for done_ticks ticks.
        bool in_tol = lo.xi_abs < t.done_xi && lo.cphi > 0.0;
        for (std::size_t i = 0; i < 3u; ++i) {
            in_tol = in_tol && std::fabs(h[i]) < t.done_h_nms;
        }
        done_run_ = in_tol ? done_run_ + 1u : 0u;
    } else {
        ++n_invalid_;
        have_ghat_ = false;
        // Zero command; region, a_f and latch kept (§3.7 step 1).
        if (phase_ == RSP_PH_RUN) {
            o.g = {{gv[0] * r0_pnms_, gv[1] * r0_pnms_, gv[2] * r0_pnms_}};
        }
    }
    if (rotor_fault_) {
        // ROTOR_FAULT (§8): a momentum the steering does not know; command zero from then on.
        o.health |= RSP_H_ROTOR_FAULT;
        o.gimbal_rate_cnt = {{0, 0, 0, 0}};
        o.mdel_nm = {{0.0, 0.0, 0.0}};
        o.whl_torque_nm = {{0.0, 0.0, 0.0}};
    }
    mdel_last_nm_ = o.mdel_nm;
    o.region = law_.region;
    o.a_f = law_.a_f;
    o.latched = law_.latched;
    o.guard = law_.guard;
    o.done_run = done_run_;
    o.done = phase_ == RSP_PH_RUN && done_run_ >= t.done_ticks;
    if (o.done) {
        o.health |= RSP_H_DONE;
    }
    o.n_switch = n_switch_;
    return o;
}

std::int32_t torque_counts(double torque_nm)
{
    const double q = torque_nm / kRspTorqueLsbNm;
    if (!std::isfinite(q)) {
        return 0;
    }
    // Clamp before converting (an out-of-range double -> int conversion is UB); std::round rounds
    // half away from zero, as the flight code's single rounding does.
    return static_cast<std::int32_t>(std::round(clampd(q, -32768.0, 32767.0)));
}

// ------------------------------------------------------------------------------------------------
// Gyrostat

namespace {

// Integrator state: G (0..2), H (3..5), q (6..9), work (10), modal q (11..13), modal p (14..16),
// dissipated energy (17), gimbal angles beta (18..21). Modal slots of a rigid model stay zero, the
// gimbal slots of a wheel model keep their value (zero derivative); every slot is combined on its
// own, so the added slots leave the arithmetic of the others, and the wheel path, bit for bit as
// it was. With gyrodines the H slots carry H(beta), recomputed after every step.
constexpr std::size_t kNy = 22u;
constexpr std::size_t kYq = 11u, kYp = 14u, kYdiss = 17u, kYbeta = 18u;
constexpr double kPi = 3.14159265358979323846;
using Y = std::array<double, kNy>;
using A4 = std::array<double, 4>;

// The gyrodine cluster at gimbal angles beta (spec 30 §2): H and dH/dt for the held gimbal rates,
// both from the one geometry source cmg_geom (rsp_cmg_ref), which takes one h_g for the four
// rotors:  H = cmg_geom(beta, h_g).H + sum_p (k_p - 1) h_g u_p(beta_p),
//          dH/dt = h_g sum_p k_p a_p(beta_p) beta_dot_p      (a_p: column p of Ahat).
// The unit rotor direction u_p needs no second formula: a single-gimbal unit turns its rotor about
// the gimbal axis g_p, so a_p(beta) = g_p x u_p(beta) is u_p turned a quarter turn forward and
// u_p(beta) = a_p(beta - pi/2), column p of cmg_geom(beta - pi/2, 1).ahat (e.g. p = 1:
// a_1 = (0, -sin, cos), at beta - pi/2: (0, cos beta, sin beta) = u_1). That term is only formed
// when a rotor is off nominal, so a nominal cluster's H is cmg_geom's exactly.
struct Cluster {
    V3 h{{0.0, 0.0, 0.0}};
    V3 hdot{{0.0, 0.0, 0.0}};
};

Cluster cluster_at(const GyrostatModel &m, const double *beta, const A4 &rate)
{
    const A4 b{{beta[0], beta[1], beta[2], beta[3]}};
    const CmgGeom g = cmg_geom(b, m.hg_nms);
    Cluster c;
    c.h = g.h_nms;
    bool nominal = true;
    for (std::size_t p = 0; p < 4u; ++p) {
        nominal = nominal && !(m.rotor_scale[p] < 1.0 || m.rotor_scale[p] > 1.0);
    }
    if (!nominal) {
        const double q = 0.5 * kPi;
        const CmgGeom u = cmg_geom({{b[0] - q, b[1] - q, b[2] - q, b[3] - q}}, 1.0);
        for (std::size_t i = 0; i < 3u; ++i) {
            for (std::size_t p = 0; p < 4u; ++p) {
                c.h[i] += (m.rotor_scale[p] - 1.0) * m.hg_nms * u.ahat[i][p];
            }
        }
    }
    for (std::size_t i = 0; i < 3u; ++i) {
        double a = 0.0;
        for (std::size_t p = 0; p < 4u; ++p) {
            a += g.ahat[i][p] * (m.rotor_scale[p] * rate[p]);
        }
        c.hdot[i] = m.hg_nms * a;
    }
    return c;
}

// Per body axis: J - D D^T and the modes' momentum D p on it (one mode per axis at most).
struct AxisModal {
    V3 jeff{{0.0, 0.0, 0.0}};
};

AxisModal axis_modal(const GyrostatModel &m)
{
    AxisModal a;
    a.jeff = m.j_kgm2;
    for (std::size_t k = 0; k < m.n_modes; ++k) {
        a.jeff[m.modes[k].axis] -= m.modes[k].d_sqrtkgm * m.modes[k].d_sqrtkgm;
    }
    return a;
}

// omega = (J - D D^T)^-1 (G - H - D p): g, h, p point at three values each.
V3 body_rate(const GyrostatModel &m, const AxisModal &a, const double *g, const double *h, const double *p)
{
    V3 dp{{0.0, 0.0, 0.0}};
    for (std::size_t k = 0; k < m.n_modes; ++k) {
        dp[m.modes[k].axis] += m.modes[k].d_sqrtkgm * p[k];
    }
    if (m.n_modes == 0u) {   // the rigid expression, exactly as before the elastic variant existed
        return {{(g[0] - h[0]) / a.jeff[0], (g[1] - h[1]) / a.jeff[1], (g[2] - h[2]) / a.jeff[2]}};
    }
    return {{(g[0] - h[0] - dp[0]) / a.jeff[0], (g[1] - h[1] - dp[1]) / a.jeff[1], (g[2] - h[2] - dp[2]) / a.jeff[2]}};
}

V3 modal_rate(const GyrostatModel &m, const V3 &w, const double *p)
{
    V3 qd{{0.0, 0.0, 0.0}};
    for (std::size_t k = 0; k < m.n_modes; ++k) {
        qd[k] = p[k] - m.modes[k].d_sqrtkgm * w[m.modes[k].axis];
    }
    return qd;
}

struct Deriv {
    const GyrostatModel &m;
    AxisModal am;
    V3 tau;                                  // motor torque after the motor limit (ZOH)
    A4 rate;                                 // gyrodines: gimbal rates after the clip (ZOH)
    std::array<bool, 3> *cut;

    Y operator()(const Y &y) const
    {
        Y d{};
        if (m.cmg) {
            // H from beta at this evaluation; dH/dt = h_g Ahat(beta) diag(k) beta_dot; M = -dH/dt.
            const Cluster c = cluster_at(m, &y[kYbeta], rate);
            const V3 w = body_rate(m, am, &y[0], c.h.data(), &y[kYp]);
            for (std::size_t i = 0; i < 3u; ++i) {
                d[3u + i] = c.hdot[i];
            }
            for (std::size_t p = 0; p < 4u; ++p) {
                d[kYbeta + p] = rate[p];
            }
            body_terms(y, w, d);
            return d;
        }
        const V3 w = body_rate(m, am, &y[0], &y[3], &y[kYp]);
        for (std::size_t i = 0; i < 3u; ++i) {
            const double hi = y[3u + i];
            const double om = hi / m.iw_kgm2;
            // Bearing friction on the wheel; at Omega = 0 exactly no Coulomb term (no chatter at rest).
            const double fr = -(om > 0.0 ? m.coulomb_nm : (om < 0.0 ? -m.coulomb_nm : 0.0)) - m.viscous_nmps * om;
            double hd = tau[i] + fr;
            if (std::fabs(hi) >= m.h_max_nms && hd * hi > 0.0) {   // the hard limit: no torque outwards
                hd = 0.0;
                (*cut)[i] = true;
            }
            d[3u + i] = hd;
        }
        body_terms(y, w, d);
        return d;
    }

    // Everything but the actuator: G, q, the work of M = -dH/dt (d[3..5] set) and the modes.
    void body_terms(const Y &y, const V3 &w, Y &d) const
    {
        // dG/dt = -omega x G = G x omega
        d[0] = y[1] * w[2] - y[2] * w[1];
        d[1] = y[2] * w[0] - y[0] * w[2];
        d[2] = y[0] * w[1] - y[1] * w[0];
        // dq/dt = 1/2 q (x) (0, omega)
        const double qw = y[6], qx = y[7], qy = y[8], qz = y[9];
        d[6] = 0.5 * (-qx * w[0] - qy * w[1] - qz * w[2]);
        d[7] = 0.5 * (qw * w[0] + qy * w[2] - qz * w[1]);
        d[8] = 0.5 * (qw * w[1] + qz * w[0] - qx * w[2]);
        d[9] = 0.5 * (qw * w[2] + qx * w[1] - qy * w[0]);
        // d(work)/dt = omega^T M, M = -dH/dt (the internal moment on the body)
        d[10] = -(w[0] * d[3] + w[1] * d[4] + w[2] * d[5]);
        if (m.n_modes > 0u) {
            const V3 qd = modal_rate(m, w, &y[kYp]);
            for (std::size_t k = 0; k < m.n_modes; ++k) {
                const ElasticMode &e = m.modes[k];
                const double c = e.delta / kPi * e.omega_radps;   // (delta / pi) Omega
                d[kYq + k] = qd[k];
                d[kYp + k] = -c * qd[k] - e.omega_radps * e.omega_radps * y[kYq + k];
                d[kYdiss] += c * qd[k] * qd[k];
            }
        }
    }
};

Y axpy(const Y &y, const Y &k, double a)
{
    Y r{};
    for (std::size_t i = 0; i < kNy; ++i) {
        r[i] = y[i] + a * k[i];
    }
    return r;
}

// Elastic energy E - T = omega^T D qdot + 1/2 |qdot|^2 + 1/2 q^T Omega^2 q.
double elastic_energy_j(const GyrostatModel &m, const V3 &w, const V3 &qd, const V3 &q)
{
    double e = 0.0;
    for (std::size_t k = 0; k < m.n_modes; ++k) {
        const ElasticMode &md = m.modes[k];
        e += md.d_sqrtkgm * w[md.axis] * qd[k] + 0.5 * qd[k] * qd[k] +
             0.5 * md.omega_radps * md.omega_radps * q[k] * q[k];
    }
    return e;
}

}  // namespace

void gyrostat_set_modes(GyrostatModel &m, const std::string &set)
{
    // spec 30 §2, documented modal set: (axis, Omega rad/s, d kg^1/2 m); delta = 0.02 for all.
    struct Row { std::size_t axis; double omega, d; };
    const Row e1[3] = {{1u, 1.5, 30.0}, {0u, 4.0, 20.0}, {2u, 8.0, 5.0}};
    const Row e2[3] = {{1u, 0.8, 40.0}, {0u, 2.5, 25.0}, {2u, 6.0, 8.0}};
    const Row *rows = nullptr;
    if (set.empty() || set == "none") {
        m.n_modes = 0u;
        m.modes = {};
        return;
    }
    if (set == "E1") {
        rows = e1;
    } else if (set == "E2") {
        rows = e2;
    } else {
        throw std::invalid_argument("unknown modal set '" + set + "' (E1, E2 or none)");
    }
    m.n_modes = 3u;
    for (std::size_t k = 0; k < 3u; ++k) {
        m.modes[k] = ElasticMode{rows[k].axis, rows[k].omega, rows[k].d, 0.02};
    }
}

double gyrostat_fastest_mode_radps(const GyrostatModel &m)
{
    double w = 0.0;
    for (std::size_t k = 0; k < m.n_modes; ++k) {
        const ElasticMode &e = m.modes[k];
        w = std::max(w, e.omega_radps / std::sqrt(1.0 - e.d_sqrtkgm * e.d_sqrtkgm / m.j_kgm2[e.axis]));
    }
    return w;
}

GyrostatState gyrostat_initial(const GyrostatModel &m, const V3 &g_dir, double g0_nms)
{
    GyrostatState s;
    const double n = norm3(g_dir);
    for (std::size_t i = 0; i < 3u; ++i) {
        s.g_nms[i] = n > 0.0 ? g0_nms * g_dir[i] / n : 0.0;
        s.h_nms[i] = 0.0;
    }
    if (m.cmg) {
        s.beta_rad = m.beta0_rad;
        s.h_nms = gyrostat_cluster_h(m, s.beta_rad);
    }
    // Modes at rest (q = 0, qdot = 0): then G = J omega + H, omega = J^-1 (G - H) and p = D^T omega
    // (H = 0 for the wheels: G - 0 is G exactly).
    for (std::size_t k = 0; k < m.n_modes; ++k) {
        const std::size_t ax = m.modes[k].axis;
        s.p_m[k] = m.modes[k].d_sqrtkgm * (s.g_nms[ax] - s.h_nms[ax]) / m.j_kgm2[ax];
    }
    s.g0_nms = g0_nms;
    s.t0_j = gyrostat_energy_j(m, s);   // the elastic energy is zero at rest
    s.work_j = 0.0;
    s.diss_j = 0.0;
    return s;
}

V3 gyrostat_omega(const GyrostatModel &m, const GyrostatState &s)
{
    return body_rate(m, axis_modal(m), s.g_nms.data(), s.h_nms.data(), s.p_m.data());
}

V3 gyrostat_qdot(const GyrostatModel &m, const GyrostatState &s)
{
    return modal_rate(m, gyrostat_omega(m, s), s.p_m.data());
}

double gyrostat_energy_j(const GyrostatModel &m, const GyrostatState &s)
{
    const V3 w = gyrostat_omega(m, s);
    return 0.5 * (m.j_kgm2[0] * w[0] * w[0] + m.j_kgm2[1] * w[1] * w[1] + m.j_kgm2[2] * w[2] * w[2]);
}

double gyrostat_energy_check_j(const GyrostatModel &m, const GyrostatState &s)
{
    if (m.n_modes == 0u) {
        return s.t0_j + s.work_j;
    }
    const V3 w = gyrostat_omega(m, s);
    return s.t0_j + s.work_j - s.diss_j - elastic_energy_j(m, w, modal_rate(m, w, s.p_m.data()), s.q_m);
}

V3 gyrostat_g_inertial(const GyrostatState &s)
{
    const double qw = s.q_bi[0], qx = s.q_bi[1], qy = s.q_bi[2], qz = s.q_bi[3];
    const V3 &v = s.g_nms;
    // v_I = q v_B q*: the rotation matrix of q (Hamilton) applied to v.
    return {{(1.0 - 2.0 * (qy * qy + qz * qz)) * v[0] + 2.0 * (qx * qy - qw * qz) * v[1] + 2.0 * (qx * qz + qw * qy) * v[2],
             2.0 * (qx * qy + qw * qz) * v[0] + (1.0 - 2.0 * (qx * qx + qz * qz)) * v[1] + 2.0 * (qy * qz - qw * qx) * v[2],
             2.0 * (qx * qz - qw * qy) * v[0] + 2.0 * (qy * qz + qw * qx) * v[1] + (1.0 - 2.0 * (qx * qx + qy * qy)) * v[2]}};
}

V3 gyrostat_cluster_h(const GyrostatModel &m, const std::array<double, 4> &beta_rad)
{
    if (!m.cmg) {
        return {{0.0, 0.0, 0.0}};
    }
    return cluster_at(m, beta_rad.data(), {{0.0, 0.0, 0.0, 0.0}}).h;
}

void gyrostat_set_rotor_scale(GyrostatModel &m, GyrostatState &s, std::size_t p, double scale)
{
    if (!m.cmg || p >= 4u) {
        throw std::invalid_argument("gyrostat_set_rotor_scale: a cmg model and a rotor index 0..3");
    }
    const V3 wa = gyrostat_omega(m, s);
    const V3 ha = s.h_nms;
    m.rotor_scale[p] = scale;
    s.h_nms = gyrostat_cluster_h(m, s.beta_rad);
    const V3 wb = gyrostat_omega(m, s);
    // G, q, p unchanged: J_eff (omega_b - omega_a) = -dH, so dE = 1/2 (omega_b - omega_a)^T J_eff
    // (omega_a + omega_b) = -1/2 (omega_a + omega_b)^T dH exactly.
    double dw = 0.0;
    for (std::size_t i = 0; i < 3u; ++i) {
        dw += 0.5 * (wa[i] + wb[i]) * (s.h_nms[i] - ha[i]);
    }
    s.work_j -= dw;
}

namespace {

// n_sub RK4 steps of f over dt_s from s (the tick of either actuator).
void gyrostat_integrate(const GyrostatModel &m, GyrostatState &s, const Deriv &f, double dt_s, int n_sub, GyrostatTick &r)
{
    const int n = std::max(n_sub, 1);
    const double h = dt_s / static_cast<double>(n);
    Y y{};
    for (std::size_t i = 0; i < 3u; ++i) {
        y[i] = s.g_nms[i];
        y[3u + i] = s.h_nms[i];
    }
    for (std::size_t i = 0; i < 4u; ++i) {
        y[6u + i] = s.q_bi[i];
    }
    y[10] = s.work_j;
    for (std::size_t k = 0; k < 3u; ++k) {
        y[kYq + k] = s.q_m[k];
        y[kYp + k] = s.p_m[k];
    }
    y[kYdiss] = s.diss_j;
    for (std::size_t p = 0; p < 4u; ++p) {
        y[kYbeta + p] = s.beta_rad[p];
    }
    for (int step = 0; step < n; ++step) {
        const Y k1 = f(y);
        const Y k2 = f(axpy(y, k1, 0.5 * h));
        const Y k3 = f(axpy(y, k2, 0.5 * h));
        const Y k4 = f(axpy(y, k3, h));
        for (std::size_t i = 0; i < kNy; ++i) {
            y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
        if (m.cmg) {
            // H is a function of beta, not an integrated state: the slots take H(beta_end). The
            // work integral was integrated with the same H(beta(t)) at every stage.
            const V3 hb = cluster_at(m, &y[kYbeta], f.rate).h;
            for (std::size_t i = 0; i < 3u; ++i) {
                y[3u + i] = hb[i];
            }
        }
        // A step that crosses the hard limit overshoots it by at most M_max h; the wheel stops at the
        // limit instead. The removed momentum is an instantaneous exchange with the body, so its
        // work -omega . dH is booked (keeps T0 + work = T to first order in the overshoot).
        for (std::size_t i = 0; i < 3u && !m.cmg; ++i) {
            const double hi = y[3u + i];
            if (std::fabs(hi) > m.h_max_nms) {
                const double dh = std::copysign(m.h_max_nms, hi) - hi;
                const double wi = body_rate(m, f.am, &y[0], &y[3], &y[kYp])[i];
                y[10] -= wi * dh;
                y[3u + i] += dh;
                r.hlim_cut[i] = true;
            }
        }
        // |G| is invariant: re-project onto g0 (spec 30 §2). q back onto the unit sphere.
        const double gn = std::sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2]);
        if (gn > 0.0 && std::isfinite(gn)) {
            const double sc = s.g0_nms / gn;
            y[0] *= sc;
            y[1] *= sc;
            y[2] *= sc;
        }
        const double qn = std::sqrt(y[6] * y[6] + y[7] * y[7] + y[8] * y[8] + y[9] * y[9]);
        if (qn > 0.0 && std::isfinite(qn)) {
            for (std::size_t i = 6u; i < 10u; ++i) {
                y[i] /= qn;
            }
        }
    }
    for (std::size_t i = 0; i < 3u; ++i) {
        s.g_nms[i] = y[i];
        s.h_nms[i] = y[3u + i];
    }
    for (std::size_t i = 0; i < 4u; ++i) {
        s.q_bi[i] = y[6u + i];
    }
    s.work_j = y[10];
    for (std::size_t k = 0; k < 3u; ++k) {
        s.q_m[k] = y[kYq + k];
        s.p_m[k] = y[kYp + k];
    }
    s.diss_j = y[kYdiss];
    for (std::size_t p = 0; p < 4u; ++p) {
        s.beta_rad[p] = y[kYbeta + p];
    }
}

}  // namespace

GyrostatTick gyrostat_tick(const GyrostatModel &m, GyrostatState &s, const V3 &torque_cmd_nm, double dt_s, int n_sub)
{
    if (m.cmg) {   // a cluster with no rate command holds its gimbals
        return gyrostat_tick_cmg(m, s, {{0.0, 0.0, 0.0, 0.0}}, dt_s, n_sub);
    }
    GyrostatTick r;
    for (std::size_t i = 0; i < 3u; ++i) {
        const double c = torque_cmd_nm[i];
        r.motor_clip[i] = std::fabs(c) > m.torque_max_nm;
        r.torque_nm[i] = clampd(c, -m.torque_max_nm, m.torque_max_nm);
    }
    const Deriv f{m, axis_modal(m), r.torque_nm, {{0.0, 0.0, 0.0, 0.0}}, &r.hlim_cut};
    gyrostat_integrate(m, s, f, dt_s, n_sub, r);
    return r;
}

GyrostatTick gyrostat_tick_cmg(const GyrostatModel &m, GyrostatState &s, const std::array<double, 4> &rate_cmd_radps,
                               double dt_s, int n_sub)
{
    if (!m.cmg) {
        throw std::invalid_argument("gyrostat_tick_cmg: the model has no gyrodine cluster");
    }
    GyrostatTick r;
    for (std::size_t p = 0; p < 4u; ++p) {
        const double c = rate_cmd_radps[p];
        r.rate_clip[p] = std::fabs(c) > m.umax_radps;
        r.rate_radps[p] = std::isnan(c) ? 0.0 : clampd(c, -m.umax_radps, m.umax_radps);
    }
    const V3 h0 = s.h_nms;
    const Deriv f{m, axis_modal(m), {{0.0, 0.0, 0.0}}, r.rate_radps, &r.hlim_cut};
    gyrostat_integrate(m, s, f, dt_s, n_sub, r);
    // H(beta) is exact at both ends and beta is linear in t: -dH/dt is M's exact tick average.
    for (std::size_t i = 0; i < 3u; ++i) {
        r.moment_nm[i] = -(s.h_nms[i] - h0[i]) / dt_s;
    }
    return r;
}

// ------------------------------------------------------------------------------------------------
// Linearisation

LinResult linearise_lin(const V3 &j_kgm2, double g0_nms, double m_nm, double k_pnms, double xi_sign)
{
    // x = (G, H); dG/dt = G x omega, omega = J^-1 (G - H); dH/dt = -M = m [s xi - k H],
    // xi = g x e_y = -[e_y]x G / g0. At G = g0 e_y, H = 0, omega = (g0/J_y) e_y:
    //   dG' = -[omega]x dG + [G]x J^-1 (dG - dH)
    //   dH' = -(s m / g0) [e_y]x dG - m k dH
    using M3 = Eigen::Matrix3d;
    auto skew = [](const Eigen::Vector3d &a) {
        M3 s;
        s << 0.0, -a.z(), a.y(), a.z(), 0.0, -a.x(), -a.y(), a.x(), 0.0;
        return s;
    };
    const Eigen::Vector3d ey(0.0, 1.0, 0.0);
    const Eigen::Vector3d g = g0_nms * ey;
    const M3 ji = Eigen::Vector3d(1.0 / j_kgm2[0], 1.0 / j_kgm2[1], 1.0 / j_kgm2[2]).asDiagonal();
    const Eigen::Vector3d w = ji * g;
    Eigen::Matrix<double, 6, 6> a = Eigen::Matrix<double, 6, 6>::Zero();
    a.block<3, 3>(0, 0) = -skew(w) + skew(g) * ji;
    a.block<3, 3>(0, 3) = -skew(g) * ji;
    a.block<3, 3>(3, 0) = -(xi_sign * m_nm / g0_nms) * skew(ey);
    a.block<3, 3>(3, 3) = -(m_nm * k_pnms) * M3::Identity();

    LinResult r;
    for (Eigen::Index i = 0; i < 6; ++i) {
        for (Eigen::Index j = 0; j < 6; ++j) {
            r.a[static_cast<std::size_t>(i * 6 + j)] = a(i, j);
        }
    }
    // G_y's row and column are zero at this point (omega, G parallel to e_y): the |G| direction,
    // eigenvalue 0 (the family of equilibria c e_y). Drop it.
    const std::array<Eigen::Index, 5> keep{{0, 2, 3, 4, 5}};
    Eigen::Matrix<double, 5, 5> b;
    for (std::size_t i = 0; i < 5u; ++i) {
        for (std::size_t j = 0; j < 5u; ++j) {
            b(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = a(keep[i], keep[j]);
        }
    }
    const Eigen::EigenSolver<Eigen::Matrix<double, 5, 5>> es(b, false);
    bool any = false;
    for (Eigen::Index i = 0; i < 5; ++i) {
        const std::complex<double> e = es.eigenvalues()(i);
        r.eig_re.push_back(e.real());
        r.eig_im.push_back(e.imag());
        if (std::abs(e) > 1e-12 && (!any || e.real() > r.slowest_re)) {
            r.slowest_re = e.real();
            any = true;
        }
    }
    return r;
}

}  // namespace ref
