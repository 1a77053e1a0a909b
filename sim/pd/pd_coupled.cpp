// pd_coupled — see pd_coupled.hpp (spec 40 §2.1, §2.2, §2.6).
#include "pd/pd_coupled.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace ref::pd {

namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;

std::size_t uz(int i) { return static_cast<std::size_t>(i); }

}  // namespace

Channel scaled(const Channel &ch, const Scales &s)
{
    Channel c = ch;
    c.Ix *= s.ix;
    c.H *= s.h;
    for (Mode &m : c.modes) {
        m.I *= s.coupling;
    }
    return c;
}

std::array<Channel, kChannels> three_channels(const Scales &s, double Ty)
{
    std::array<Channel, kChannels> ch{{scaled(Channel::yaw(), s), scaled(Channel::roll(), s), scaled(Channel::pitch(), s)}};
    for (Channel &c : ch) {
        c.Ty = Ty;
    }
    return ch;
}

Layout layout(const std::array<Channel, kChannels> &ch)
{
    Layout l;
    int off = 2 * kChannels;
    for (int k = 0; k < kChannels; ++k) {
        l.q_off[uz(k)] = off;
        l.n_q[uz(k)] = static_cast<int>(ch[uz(k)].modes.size());
        off += l.n_q[uz(k)];
    }
    l.n_dof = off;
    return l;
}

SecondOrder second_order(const std::array<Channel, kChannels> &ch, double f_hz, int sign, bool cross)
{
    if (sign != 1 && sign != -1) {
        throw std::invalid_argument("pd coupled plant: coupling sign must be +1 or -1");
    }
    const Layout L = layout(ch);
    const Eigen::Index nd = L.n_dof;
    SecondOrder so;
    so.Mm = Eigen::MatrixXd::Zero(nd, nd);
    so.C = Eigen::MatrixXd::Zero(nd, nd);
    so.K = Eigen::MatrixXd::Zero(nd, nd);
    so.F = Eigen::MatrixXd::Zero(nd, kChannels);
    so.omega.assign(uz(L.n_modes()), 0.0);
    // One gimbal inertia in the cross terms: the same Ib on both sides keeps Mm symmetric.
    const double Ib = ch[0].Ibeta;
    for (const Channel &c : ch) {
        if (std::fabs(c.Ibeta - Ib) > 0.0) {
            throw std::invalid_argument("pd coupled plant: the three gyrodines must share one Ibeta");
        }
    }
    const double a = std::sqrt(0.5);   // cos(pi/4) (§2.1 [C])
    const double aI = cross ? static_cast<double>(sign) * a * Ib : 0.0;   // body-gimbal cross term
    const double a2I = cross ? a * a * Ib : 0.0;                          // body-body term (sign-free)
    for (int k = 0; k < kChannels; ++k) {
        const Channel &c = ch[uz(k)];
        const int xk = Layout::x(k), bk = Layout::beta(k);
        // body k: (I_k + 2 a^2 Ib) x_k'' + a^2 Ib sum x_j'' + sigma a Ib sum beta_j'' + sum I_i q_i'' - H beta_k'
        so.Mm(xk, xk) = c.Ix + 2.0 * a2I;
        so.C(xk, bk) = -c.H;
        for (int j = 0; j < kChannels; ++j) {
            if (j == k) {
                continue;
            }
            so.Mm(xk, Layout::x(j)) = a2I;
            so.Mm(xk, Layout::beta(j)) = aI;
            // gimbal k: sigma a Ib sum_{j != k} x_j''
            so.Mm(bk, Layout::x(j)) = aI;
        }
        // gimbal k: Ib beta_k'' + kbd beta_k' + kbs beta_k + H x_k' = M_k
        so.Mm(bk, bk) = c.Ibeta;
        so.C(bk, bk) = c.kbd;
        so.K(bk, bk) = c.kbs;
        so.C(bk, xk) = c.H;
        so.F(bk, k) = 1.0;
        // mode i, scaled by I_i / r_i: I_i x_k'' + (I_i / r_i) q_i'' + (I_i / r_i) Omega_i^2 q_i = 0
        for (int i = 0; i < L.n_q[uz(k)]; ++i) {
            const Mode &m = c.modes[uz(i)];
            const int qi = L.q(k, i);
            const double om = m.ratio * kTwoPi * f_hz;   // as ref::pd::continuous
            const double mq = m.I / m.r;
            so.omega[uz(qi - 2 * kChannels)] = om;
            so.Mm(xk, qi) = m.I;
            so.Mm(qi, xk) = m.I;
            so.Mm(qi, qi) = mq;
            so.K(qi, qi) = mq * om * om;
        }
    }
    // Built symmetric entry by entry: any asymmetry is a construction error, so exact equality.
    if (!(so.Mm - so.Mm.transpose()).isZero(0.0)) {
        throw std::logic_error("pd plant: mass matrix not symmetric");
    }
    Eigen::LLT<Eigen::MatrixXd> llt(so.Mm);
    if (llt.info() != Eigen::Success) {
        throw std::invalid_argument("pd plant: mass matrix not positive definite (needs Ix - sum_i r_i I_i > 0 per "
                                    "channel: scale.coupling too large for scale.ix)");
    }
    return so;
}

StateSpace state_space(const SecondOrder &so)
{
    const Eigen::Index nd = so.Mm.rows();
    const Eigen::LLT<Eigen::MatrixXd> llt(so.Mm);
    StateSpace ss;
    ss.A = Eigen::MatrixXd::Zero(2 * nd, 2 * nd);
    ss.A.topRightCorner(nd, nd).setIdentity();
    ss.A.bottomLeftCorner(nd, nd) = -llt.solve(so.K);
    ss.A.bottomRightCorner(nd, nd) = -llt.solve(so.C);
    ss.B = Eigen::MatrixXd::Zero(2 * nd, so.F.cols());
    ss.B.bottomRows(nd) = llt.solve(so.F);
    return ss;
}

DiscreteN discretise_coupled(const std::array<Channel, kChannels> &ch, double f_hz, int sign, double Ty)
{
    const StateSpace ss = state_space(second_order(ch, f_hz, sign, true));
    return zoh(ss.A, ss.B, Ty);
}

DiscreteN discretise_single(const std::array<Channel, kChannels> &ch, double f_hz, double Ty)
{
    const Layout L = layout(ch);
    const Eigen::Index nd = L.n_dof;
    DiscreteN d;
    d.Ty = Ty;
    d.Ad = Eigen::MatrixXd::Zero(2 * nd, 2 * nd);
    d.Bd = Eigen::MatrixXd::Zero(2 * nd, kChannels);
    for (int k = 0; k < kChannels; ++k) {
        Channel c = ch[uz(k)];
        c.Ty = Ty;
        const Discrete dk = discretise(c, f_hz);
        // Channel state [x, beta, q_1..q_n, x', beta', q_1'..q_n'] -> the layout.
        const int ndk = 2 + L.n_q[uz(k)];
        auto g = [&](int l) {
            const int j = l % ndk, vel = (l >= ndk) ? static_cast<int>(nd) : 0;
            const int dof = (j == 0) ? Layout::x(k) : (j == 1) ? Layout::beta(k) : L.q(k, j - 2);
            return static_cast<Eigen::Index>(dof + vel);
        };
        for (int r = 0; r < 2 * ndk; ++r) {
            d.Bd(g(r), k) = dk.Bd(r);
            for (int s = 0; s < 2 * ndk; ++s) {
                d.Ad(g(r), g(s)) = dk.Ad(r, s);
            }
        }
    }
    return d;
}

}  // namespace ref::pd
