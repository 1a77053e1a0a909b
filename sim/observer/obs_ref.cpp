#include "observer/obs_ref.hpp"

#include <cmath>
#include <limits>

namespace ref {
namespace {

double dq(int32_t v, unsigned q) { return std::ldexp(static_cast<double>(v), -static_cast<int>(q)); }

// Round half away from zero, the flight code's rule (std::round does exactly that).
int32_t rnd_count(double v, int32_t lim)
{
    double c = std::round(v);
    if (c > lim) { c = lim; }
    if (c < -lim) { c = -lim; }
    return static_cast<int32_t>(c);
}

}  // namespace

ObsTable dequantise(const obs_params_t &p)
{
    ObsTable t;
    for (int i = 0; i < 6; ++i) {
        for (int j = 0; j < 6; ++j) {
            t.phi0(i, j) = dq(p.phi0[i * 6 + j], p.q_phi0);
            t.phik(i, j) = dq(p.phik[i * 6 + j], p.q_phik);
        }
        for (int j = 0; j < 2; ++j) {
            t.gam0(i, j) = dq(p.gam0[i * 2 + j], p.q_gam0);
            t.gamk(i, j) = dq(p.gamk[i * 2 + j], p.q_gamk);
            t.d(j, i) = dq(p.d[j * 6 + i], p.q_d);
        }
    }
    t.q.setZero();
    for (int i = 0; i < 7; ++i) {
        t.s(i) = std::ldexp(1.0, p.ls[i]);
        t.q(i, i) = dq(p.qd_q30[i], 30);
    }
    t.r = dq(p.r_q30, 30);
    t.p_floor = dq(p.p_floor_q30, 30);
    t.p_ceil = dq(p.p_ceil_q30, 30);
    t.kappa0 = dq(p.kappa0_q28, 28);
    t.kappa_lo = dq(p.kappa_lo_q28, 28);
    t.kappa_hi = dq(p.kappa_hi_q28, 28);
    t.bdot_max = dq(p.bdot_max_q29, 29);
    t.gyro_lsb = std::ldexp(1.0, static_cast<int>(p.gyro_cnt_shift) - 29);
    t.act_lsb = std::ldexp(1.0, static_cast<int>(p.act_cnt_shift) - 29);
    t.act_max_cnt = p.act_max_cnt;
    t.d2_max = dq(p.d2_max_q16, 16);
    t.d2_reject = p.d2_reject != 0u;
    t.n_rej_safe = p.n_rej_safe;
    t.rej_leak_inc = p.rej_leak_inc;
    t.rej_freeze_on = p.rej_freeze_on;
    return t;
}

ObsState from_fixed(const obs_state_t &s)
{
    ObsState st;
    for (int i = 0; i < 6; ++i) { st.x(i) = dq(s.x_q29[i], 29); }
    st.kappa = dq(s.kappa_q28, 28);
    for (int i = 0; i < 2; ++i) { st.qres(i) = dq(s.qres_q29[i], 29); }
    st.rej_run = {{s.rej_run[0], s.rej_run[1]}};
    st.rej_level = s.rej_level;
    st.kappa_frozen = s.kappa_frozen;
    st.rej_safe = s.rej_safe;
    for (int i = 0; i < 7; ++i) {
        for (int j = 0; j < 7; ++j) { st.p(i, j) = dq(s.p_q30[i * 7 + j], 30); }
    }
    return st;
}

ObsState initial_state(const obs_params_t &p, const std::array<int32_t, 2> &y_cnt)
{
    const double lsb = std::ldexp(1.0, static_cast<int>(p.gyro_cnt_shift) - 29);
    ObsState st;
    st.x.setZero();
    st.x(0) = y_cnt[0] * lsb;
    st.x(1) = y_cnt[1] * lsb;
    st.kappa = dq(p.kappa_init_q28, 28);
    st.p.setZero();
    for (int i = 0; i < 7; ++i) { st.p(i, i) = dq(p.p0_q30[i], 30); }
    st.qres.setZero();
    return st;
}

ObsStepOut obs_step_ref(const ObsTable &t, ObsState &st, const std::array<int32_t, 2> &y_cnt, bool per_axis_clip)
{
    ObsStepOut out{{0, 0}, false, 0u, {{0.0, 0.0}}, Eigen::Matrix<double, 7, 2>::Zero(),
                   Eigen::Matrix<double, 7, 7>::Zero(), Eigen::Matrix<double, 6, 2>::Zero(),
                   Eigen::Matrix<double, 7, 7>::Zero()};
    // Measurement update, one scalar channel at a time, in scaled coordinates.
    Eigen::Matrix<double, 7, 1> z;
    z << st.x, st.kappa;
    for (int c = 0; c < 2; ++c) {
        double e = y_cnt[static_cast<size_t>(c)] * t.gyro_lsb - z(c);
        double sn = st.p(c, c) + t.r;
        const double es = e / t.s(c);
        out.d2[static_cast<size_t>(c)] = (sn > 0.0) ? es * es / sn : std::numeric_limits<double>::infinity();
        if (sn <= 0.0) {
            // Not a covariance any more (obs.c update_channel): the sample cannot be weighed.
            if (t.d2_reject) {
                ++st.rej_run[static_cast<size_t>(c)];
                out.rejected |= 1u << c;
            }
            continue;
        }
        if (t.d2_reject && out.d2[static_cast<size_t>(c)] > t.d2_max) {
            // The gate: the sample is not used at all.
            ++st.rej_run[static_cast<size_t>(c)];
            out.rejected |= 1u << c;
            continue;
        }
        Eigen::Matrix<double, 7, 1> l = st.p.col(c) / sn;
        out.gain.col(c) = l;
        Eigen::Matrix<double, 1, 7> row = st.p.row(c);
        for (int j = 0; j < 6; ++j) { z(j) += l(j) * e * t.s(j) / t.s(c); }
        if (!st.kappa_frozen) { z(6) += l(6) * e * t.s(6) / t.s(c); }
        // Frozen kappa is the gain L_kappa = 0, whose Joseph form differs from this update only
        // in P_kk, which keeps its value.
        const double pkk = st.p(6, 6);
        st.p -= l * row;
        if (st.kappa_frozen) { st.p(6, 6) = pkk; }
        st.rej_run[static_cast<size_t>(c)] = 0u;
    }
    // Leaky rejection level: freeze kappa at rej_freeze_on, release at 0; latch the safe output
    // after n_rej_safe consecutive rejections of a channel.
    const uint32_t cap = t.rej_freeze_on + t.rej_leak_inc;
    if (out.rejected != 0u) {
        st.rej_level = std::min(st.rej_level + t.rej_leak_inc, cap);
    } else if (st.rej_level > 0u) {
        --st.rej_level;
    }
    if (st.rej_level >= t.rej_freeze_on) { st.kappa_frozen = true; }
    else if (st.rej_level == 0u) { st.kappa_frozen = false; }
    if (st.rej_run[0] >= t.n_rej_safe || st.rej_run[1] >= t.n_rej_safe) { st.rej_safe = true; }
    st.x = z.head<6>();
    st.kappa = std::min(std::max(z(6), t.kappa_lo), t.kappa_hi);
    for (int i = 0; i < 7; ++i) { st.p(i, i) = std::min(std::max(st.p(i, i), t.p_floor), t.p_ceil); }
    // Command: u = -D x, limited as a vector, quantised to counts; the model uses the counts.
    Eigen::Vector2d u = -t.d * st.x;
    if (st.rej_safe) {   // latched safe output: zero command, no quantisation residual kept
        u.setZero();
        st.qres.setZero();
    }
    double mag = u.cwiseAbs().maxCoeff();
    if (mag > t.bdot_max) {
        if (per_axis_clip) {
            u = u.cwiseMax(-t.bdot_max).cwiseMin(t.bdot_max);
        } else {
            u *= t.bdot_max / mag;
        }
        out.limited = true;
    }
    // Error-feedback quantisation (obs.c to_counts): the residual a count could not carry is
    // added to the next command; a clip at the actuator range clears it.
    for (size_t i = 0; i < 2; ++i) {
        const Eigen::Index ii = static_cast<Eigen::Index>(i);
        const double want = u(ii) + st.qres(ii);
        const double c = std::round(want / t.act_lsb);
        out.cmd_cnt[i] = rnd_count(want / t.act_lsb, t.act_max_cnt);
        u(ii) = out.cmd_cnt[i] * t.act_lsb;
        st.qres(ii) = (std::fabs(c) > t.act_max_cnt) ? 0.0 : want - u(ii);
    }
    // Time update on the first-order model, linearised at the updated estimate.
    double dk = st.kappa - t.kappa0;
    Eigen::Matrix<double, 6, 6> phi = t.phi0 + dk * t.phik;
    Eigen::Matrix<double, 6, 2> gam = t.gam0 + dk * t.gamk;
    Eigen::Matrix<double, 7, 7> f = Eigen::Matrix<double, 7, 7>::Zero();
    f.topLeftCorner<6, 6>() = phi;
    f.block<6, 1>(0, 6) = t.phik * st.x + t.gamk * u;
    f(6, 6) = 1.0;
    Eigen::Matrix<double, 7, 7> fs = t.s.asDiagonal().inverse() * f * t.s.asDiagonal();
    out.fs = fs;
    out.gam = gam;
    out.t = fs * st.p;
    st.p = fs * st.p * fs.transpose() + t.q;
    for (int i = 0; i < 7; ++i) { st.p(i, i) = std::min(std::max(st.p(i, i), t.p_floor), t.p_ceil); }
    st.x = phi * st.x + gam * u;
    return out;
}

}  // namespace ref
