#include "impulse/imp_ref_solver.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "impulse/imp_ref_detail.hpp"

namespace ref {

using detail::kQ28;
using detail::sub_ax0;
using detail::sub_nax;
using detail::sub_row0;

namespace {

// Thrust factor and sign of burn b (0 first, 1 second) of local axis k under pattern pat.
double signed_alpha(const std::array<double, 6> &alpha, int sub, unsigned pat, int k, int b)
{
    const unsigned neg = (pat >> (2 * k + b)) & 1u;
    const int r = sub_ax0(sub) + k;
    const double a = alpha[static_cast<size_t>(2 * r) + neg];
    return neg ? -a : a;
}

// Gaussian elimination with partial pivoting, as fx_solve: returns false if a pivot is below
// pivot_min or the smallest/largest pivot ratio is below pivot_ratio (cause set).
bool pivoted_solve(Eigen::MatrixXd a, Eigen::VectorXd b, const ImpGuards &g, Eigen::VectorXd &x, unsigned &cause)
{
    const int n = static_cast<int>(a.rows());
    double pmin = 1e300, pmax = 0;
    for (int k = 0; k < n; ++k) {
        int p = k;
        for (int i = k + 1; i < n; ++i) {
            if (std::abs(a(i, k)) > std::abs(a(p, k))) { p = i; }
        }
        a.row(k).swap(a.row(p));
        std::swap(b(k), b(p));
        const double piv = a(k, k);
        if (!(std::abs(piv) >= g.pivot_min)) {
            cause = IMP_FAIL_SINGULAR;
            return false;
        }
        pmin = std::min(pmin, std::abs(piv));
        pmax = std::max(pmax, std::abs(piv));
        for (int i = k + 1; i < n; ++i) {
            const double l = a(i, k) / piv;
            a.row(i) -= l * a.row(k);
            b(i) -= l * b(k);
        }
    }
    if (pmin < g.pivot_ratio * pmax) {
        cause = IMP_FAIL_COND;
        return false;
    }
    x = Eigen::VectorXd::Zero(n);
    for (int i = n - 1; i >= 0; --i) {
        double s = b(i);
        for (int j = i + 1; j < n; ++j) { s -= a(i, j) * x(j); }
        x(i) = s / a(i, i);
    }
    return true;
}

}  // namespace

ImpGuards guards_from_table(const imp_params_t &p)
{
    ImpGuards g;
    g.max_iter = p.max_iter;
    g.r_tol = p.r_tol_lsb / kQ28;
    g.pivot_min = p.pivot_min_q26 / 67108864.0;   // q26
    g.pivot_ratio = std::ldexp(1.0, -static_cast<int>(p.pivot_ratio_sh));
    g.rho_warn = p.rho_warn_q28 / kQ28;
    g.rho_reject = p.rho_reject_q28 / kQ28;
    g.dv_tie = p.dv_tie_q28 / kQ28;
    g.tol_tau = 1.0 / 536870912.0;                // validity +-1 LSB of q29
    return g;
}

Eigen::Matrix4d phi_xy(double tau)
{
    const double s = std::sin(tau), c = std::cos(tau);
    Eigen::Matrix4d m;
    m << 1, 4 * s - 3 * tau, 6 * (tau - s), 2 * (1 - c),
         0, 4 * c - 3, 6 * (1 - c), 2 * s,
         0, -2 * (1 - c), 4 - 3 * c, s,
         0, -2 * s, 3 * s, c;
    return m;
}

Eigen::Matrix2d phi_z(double tau)
{
    Eigen::Matrix2d m;
    m << std::cos(tau), std::sin(tau), -std::sin(tau), std::cos(tau);
    return m;
}

Mat6 phi(double tau)
{
    Mat6 m = Mat6::Zero();
    m.topLeftCorner<4, 4>() = phi_xy(tau);
    m.bottomRightCorner<2, 2>() = phi_z(tau);
    return m;
}

Eigen::VectorXd psi(int axis, double sig)
{
    const double s = std::sin(sig), c = std::cos(sig);
    Eigen::VectorXd v(axis == 2 ? 2 : 4);
    if (axis == 0) {
        v << 4 * (1 - c) - 1.5 * sig * sig, 4 * s - 3 * sig, -2 * (sig - s), -2 * (1 - c);
    } else if (axis == 1) {
        v << 2 * (sig - s), 2 * (1 - c), 1 - c, s;
    } else {
        v << 1 - c, s;
    }
    return v;
}

Eigen::VectorXd phi_e(int axis, double sig)
{
    const double s = std::sin(sig), c = std::cos(sig);
    Eigen::VectorXd v(axis == 2 ? 2 : 4);
    if (axis == 0) {
        v << 4 * s - 3 * sig, 4 * c - 3, -2 * (1 - c), -2 * s;
    } else if (axis == 1) {
        v << 2 * (1 - c), 2 * s, s, c;
    } else {
        v << s, c;
    }
    return v;
}

ImpNd nondim(const ImpCase &c)
{
    ImpNd p;
    p.tauf = c.w * c.T;
    for (int i = 0; i < 6; ++i) {
        const double u = (i % 2 == 0) ? c.L() : c.V();
        p.x0(i) = c.x0(i) / u;
        p.xt(i) = c.xt(i) / u;
    }
    p.alpha = c.alpha;
    return p;
}

Eigen::VectorXd residual(const ImpNd &p, int sub, unsigned pat, const std::array<double, 2> &t1,
                         const std::array<double, 2> &t2)
{
    const int n = 2 * sub_nax(sub), r0 = sub_row0(sub);
    const Mat6 ph = phi(p.tauf);
    Eigen::VectorXd f = ph.block(r0, r0, n, n) * p.x0.segment(r0, n) - p.xt.segment(r0, n);
    for (int k = 0; k < sub_nax(sub); ++k) {
        const int r = sub_ax0(sub) + k;
        const double a1 = signed_alpha(p.alpha, sub, pat, k, 0), a2 = signed_alpha(p.alpha, sub, pat, k, 1);
        f += a1 * (psi(r, p.tauf) - psi(r, p.tauf - t1[static_cast<size_t>(k)])) +
             a2 * psi(r, p.tauf - t2[static_cast<size_t>(k)]);
    }
    return f;
}

Eigen::MatrixXd jacobian(const ImpNd &p, int sub, unsigned pat, const std::array<double, 2> &t1,
                         const std::array<double, 2> &t2)
{
    const int n = 2 * sub_nax(sub);
    Eigen::MatrixXd j(n, n);
    for (int k = 0; k < sub_nax(sub); ++k) {
        const int r = sub_ax0(sub) + k;
        j.col(2 * k) = signed_alpha(p.alpha, sub, pat, k, 0) * phi_e(r, p.tauf - t1[static_cast<size_t>(k)]);
        j.col(2 * k + 1) = -signed_alpha(p.alpha, sub, pat, k, 1) * phi_e(r, p.tauf - t2[static_cast<size_t>(k)]);
    }
    return j;
}

ImpAttempt attempt(const ImpNd &p, const ImpGuards &g, int sub, unsigned pat, std::array<double, 2> t1,
                   std::array<double, 2> t2, double gain)
{
    ImpAttempt a;
    const int nax = sub_nax(sub);
    for (int it = 0;; ++it) {
        const Eigen::VectorXd f = residual(p, sub, pat, t1, t2);
        a.hist.push_back(ImpIter{t1, t2, f});
        a.iters = it;
        a.fmax = f.cwiseAbs().maxCoeff();
        a.t1 = t1;
        a.t2 = t2;
        if (a.fmax <= g.r_tol) {
            a.cause = IMP_FAIL_NONE;
            for (int k = 0; k < nax; ++k) {
                const double u1 = t1[static_cast<size_t>(k)], u2 = t2[static_cast<size_t>(k)];
                if (u1 < -g.tol_tau || u2 - u1 < -g.tol_tau || u2 > p.tauf + g.tol_tau) {
                    a.cause = IMP_FAIL_ORDER;
                }
            }
            return a;
        }
        if (it >= g.max_iter) {
            a.cause = IMP_FAIL_ITER;
            return a;
        }
        Eigen::VectorXd d;
        unsigned cause = IMP_FAIL_NONE;
        if (!pivoted_solve(jacobian(p, sub, pat, t1, t2), f, g, d, cause)) {
            a.cause = cause;
            return a;
        }
        for (int k = 0; k < nax; ++k) {
            t1[static_cast<size_t>(k)] -= gain * d(2 * k);
            t2[static_cast<size_t>(k)] -= gain * d(2 * k + 1);
            for (double t : {t1[static_cast<size_t>(k)], t2[static_cast<size_t>(k)]}) {
                if (t <= -p.tauf || t >= 2 * p.tauf) { cause = IMP_FAIL_DIVERGE; }
            }
        }
        if (cause != IMP_FAIL_NONE) {
            a.cause = cause;
            a.iters = it + 1;
            a.t1 = t1;
            a.t2 = t2;
            return a;
        }
    }
}

namespace {

// Thruster of burn b of local axis k under the subsystem-local pattern pat.
unsigned pat_thruster(int sub, unsigned pat, int k, int b)
{
    return static_cast<unsigned>(2 * (sub_ax0(sub) + k)) + ((pat >> (2 * k + b)) & 1u);
}

bool pat_allowed(int sub, unsigned pat, unsigned thr_off)
{
    unsigned used = 0;
    for (int k = 0; k < sub_nax(sub); ++k) {
        for (int b = 0; b < 2; ++b) { used |= 1u << pat_thruster(sub, pat, k, b); }
    }
    return (used & thr_off) == 0u;
}

}  // namespace

ImpPlan solve_nd(const ImpNd &p, const ImpGuards &g, const ImpSolveOpt &o)
{
    ImpPlan pl;
    const std::array<double, 2> z1{{0, 0}}, z2{{p.tauf, p.tauf}};
    // impulsive solution: one Newton step from (0, tau_f), all polarities positive
    double rmax = 0;
    for (int sub = 0; sub < 2; ++sub) {
        Eigen::VectorXd d;
        unsigned cause = IMP_FAIL_NONE;
        if (!pivoted_solve(jacobian(p, sub, 0, z1, z2), residual(p, sub, 0, z1, z2), g, d, cause)) {
            pl.outcome = IMP_SOL_INFEASIBLE;
            return pl;
        }
        for (int k = 0; k < sub_nax(sub); ++k) {
            const int r = sub_ax0(sub) + k;
            const double a = p.alpha[static_cast<size_t>(2 * r)];
            pl.dv1[static_cast<size_t>(r)] = a * (-d(2 * k));
            pl.dv2[static_cast<size_t>(r)] = a * d(2 * k + 1);
            pl.rho[static_cast<size_t>(r)] =
                (std::abs(pl.dv1[static_cast<size_t>(r)]) + std::abs(pl.dv2[static_cast<size_t>(r)])) / p.tauf;
            rmax = std::max(rmax, pl.rho[static_cast<size_t>(r)]);
        }
    }
    if (!o.replan) {
        if (rmax > g.rho_reject) {
            pl.outcome = IMP_SOL_INFEASIBLE;
            return pl;
        }
        pl.marginal = rmax > g.rho_warn;
    }
    bool all = true;
    for (int sub = 0; sub < 2; ++sub) {
        const int nax = sub_nax(sub);
        const unsigned sh = sub == 0 ? 0u : 4u, pmask = sub == 0 ? 0xFu : 0x3u;
        unsigned rule = 0, tried = 0;
        for (int k = 0; k < nax; ++k) {
            const auto r = static_cast<size_t>(sub_ax0(sub) + k);
            rule |= (pl.dv1[r] < 0 ? 1u : 0u) << (2 * k);
            rule |= (pl.dv2[r] < 0 ? 1u : 0u) << (2 * k + 1);
        }
        auto dv_of = [&](const ImpAttempt &a, unsigned pat) {
            double s = 0;
            for (int k = 0; k < nax; ++k) {
                s += std::abs(signed_alpha(p.alpha, sub, pat, k, 0)) * a.t1[static_cast<size_t>(k)] +
                     std::abs(signed_alpha(p.alpha, sub, pat, k, 1)) * (p.tauf - a.t2[static_cast<size_t>(k)]);
            }
            return s;
        };
        bool found = false;
        ImpAttempt best;
        unsigned best_pat = 0, how = IMP_HOW_NONE;
        double best_dv = 0;
        auto one = [&](unsigned pat, std::array<double, 2> t1, std::array<double, 2> t2, unsigned h) {
            const ImpAttempt a = attempt(p, g, sub, pat, t1, t2);
            ++pl.attempts;
            if (a.cause != IMP_FAIL_NONE) {
                ++pl.n_fail[a.cause];
                return;
            }
            const double dv = dv_of(a, pat);
            if (h != IMP_HOW_SEARCH || !found || dv < best_dv - g.dv_tie) {
                found = true;
                best = a;
                best_pat = pat;
                best_dv = dv;
                how = h;
            }
        };
        if ((o.warm_mask >> sub) & 1u) {
            const unsigned wp = (o.warm_pattern >> sh) & pmask;
            tried |= 1u << wp;
            if (pat_allowed(sub, wp, o.thr_off)) {
                std::array<double, 2> w1{}, w2{};
                for (int k = 0; k < nax; ++k) {
                    w1[static_cast<size_t>(k)] = o.warm_t1[static_cast<size_t>(sub_ax0(sub) + k)];
                    w2[static_cast<size_t>(k)] = o.warm_t2[static_cast<size_t>(sub_ax0(sub) + k)];
                }
                one(wp, w1, w2, IMP_HOW_WARM);
            }
        }
        if (!found && !((tried >> rule) & 1u)) {
            tried |= 1u << rule;
            if (pat_allowed(sub, rule, o.thr_off)) { one(rule, z1, z2, IMP_HOW_RULE); }
        }
        if (!found) {
            const unsigned npat = sub == 0 ? 16u : 4u;
            for (unsigned pat = 0; pat < npat; ++pat) {
                if (((tried >> pat) & 1u) || !pat_allowed(sub, pat, o.thr_off)) { continue; }
                one(pat, z1, z2, IMP_HOW_SEARCH);
            }
        }
        pl.how[static_cast<size_t>(sub)] = how;
        if (!found) {
            all = false;
            continue;
        }
        pl.iters[static_cast<size_t>(sub)] = best.iters;
        pl.dv[static_cast<size_t>(sub)] = dv_of(best, best_pat);
        pl.pattern |= best_pat << sh;
        for (int k = 0; k < nax; ++k) {
            const auto r = static_cast<size_t>(sub_ax0(sub) + k);
            pl.t1[r] = std::max(0.0, best.t1[static_cast<size_t>(k)]);
            pl.t2[r] = std::max(pl.t1[r], std::min(p.tauf, best.t2[static_cast<size_t>(k)]));
        }
    }
    pl.outcome = all ? IMP_SOL_VALID : IMP_SOL_NO_SOLUTION;
    return pl;
}

ImpPlan solve(const ImpCase &c, const ImpGuards &g)
{
    return solve_nd(nondim(c), g, ImpSolveOpt());
}

}  // namespace ref
