#include "impulse/imp_ref_checks.hpp"

#include <unsupported/Eigen/MatrixFunctions>

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "impulse/imp_ref_detail.hpp"

namespace ref {

using detail::sub_nax;

namespace {

double adaptive_simpson(const std::function<double(double)> &f, double a, double b, double fa, double fm,
                        double fb, double whole, double tol, int depth)
{
    const double m = 0.5 * (a + b), lm = 0.5 * (a + m), rm = 0.5 * (m + b);
    const double flm = f(lm), frm = f(rm);
    const double left = (m - a) / 6 * (fa + 4 * flm + fm), right = (b - m) / 6 * (fm + 4 * frm + fb);
    if (depth <= 0 || std::abs(left + right - whole) <= 15 * tol) {
        return left + right + (left + right - whole) / 15;
    }
    return adaptive_simpson(f, a, m, fa, flm, fm, left, tol / 2, depth - 1) +
           adaptive_simpson(f, m, b, fm, frm, fb, right, tol / 2, depth - 1);
}

}  // namespace

Vec6 terminal_error(const ImpCase &c, const std::array<double, 3> &t1, const std::array<double, 3> &t2,
                    unsigned pattern)
{
    const ImpNd p = nondim(c);
    Vec6 e;
    const std::array<double, 2> a1{{t1[0], t1[1]}}, a2{{t2[0], t2[1]}};
    const std::array<double, 2> b1{{t1[2], 0}}, b2{{t2[2], 0}};
    e.head<4>() = residual(p, 0, pattern & 0xFu, a1, a2);
    e.tail<2>() = residual(p, 1, (pattern >> 4) & 3u, b1, b2);
    for (int i = 0; i < 6; ++i) { e(i) *= (i % 2 == 0) ? c.L() : c.V(); }
    return e;
}

Vec6 terminal_error_rk(const ImpCase &c, const std::array<double, 3> &t1, const std::array<double, 3> &t2,
                       unsigned pattern, double h_s)
{
    const double w = c.w;
    auto accel = [&](double t) {
        Eigen::Vector3d u = Eigen::Vector3d::Zero();
        for (int r = 0; r < 3; ++r) {
            const double s1 = ((pattern >> (2 * r)) & 1u) ? -1.0 : 1.0, s2 = ((pattern >> (2 * r + 1)) & 1u) ? -1.0 : 1.0;
            const double a1 = c.alpha[static_cast<size_t>(2 * r) + (s1 < 0 ? 1 : 0)] * c.a_nom;
            const double a2 = c.alpha[static_cast<size_t>(2 * r) + (s2 < 0 ? 1 : 0)] * c.a_nom;
            if (t < t1[static_cast<size_t>(r)] / w) { u(r) = s1 * a1; }
            else if (t >= t2[static_cast<size_t>(r)] / w) { u(r) = s2 * a2; }
        }
        return u;
    };
    auto rhs = [&](const Vec6 &x, const Eigen::Vector3d &u) {
        Vec6 d;
        d << x(1), 2 * w * x(3) + u(0), x(3), -2 * w * x(1) + 3 * w * w * x(2) + u(1), x(5), -w * w * x(4) + u(2);
        return d;
    };
    std::vector<double> knots{0.0, c.T};
    for (int r = 0; r < 3; ++r) {
        knots.push_back(t1[static_cast<size_t>(r)] / w);
        knots.push_back(t2[static_cast<size_t>(r)] / w);
    }
    std::sort(knots.begin(), knots.end());
    Vec6 x = c.x0;
    for (size_t i = 0; i + 1 < knots.size(); ++i) {
        const double ta = std::max(0.0, knots[i]), tb = std::min(c.T, knots[i + 1]);
        if (tb <= ta) { continue; }
        const Eigen::Vector3d u = accel(0.5 * (ta + tb));
        const int n = std::max(1, static_cast<int>(std::ceil((tb - ta) / h_s)));
        const double h = (tb - ta) / n;
        for (int k = 0; k < n; ++k) {
            const Vec6 k1 = rhs(x, u), k2 = rhs(x + 0.5 * h * k1, u), k3 = rhs(x + 0.5 * h * k2, u),
                       k4 = rhs(x + h * k3, u);
            x += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
        }
    }
    return x - c.xt;
}

ImpRound round_best(const ImpCase &c, const ImpPlan &pl, double h_s, double t_w)
{
    ImpRound rd;
    const double dtau = c.w * h_s;
    const long n_total = std::lround(c.T / h_s);
    const double wv = c.w * t_w;
    std::array<long, 6> nf{};
    unsigned near_all = 0;
    for (int r = 0; r < 3; ++r) {
        for (int b = 0; b < 2; ++b) {
            const double t = (b == 0 ? pl.t1 : pl.t2)[static_cast<size_t>(r)] / dtau;
            const long f = std::min(n_total, static_cast<long>(std::floor(t)));
            nf[static_cast<size_t>(2 * r + b)] = f;
            near_all |= (t - static_cast<double>(f) >= 0.5 ? 1u : 0u) << (2 * r + b);
        }
    }
    auto steps = [&](unsigned ch_all, std::array<double, 3> &t1, std::array<double, 3> &t2, bool &ok) {
        ok = true;
        for (int r = 0; r < 3; ++r) {
            const long n1 = nf[static_cast<size_t>(2 * r)] + ((ch_all >> (2 * r)) & 1u);
            const long n2 = nf[static_cast<size_t>(2 * r + 1)] + ((ch_all >> (2 * r + 1)) & 1u);
            if (n1 > n2 || n2 > n_total) { ok = false; }
            t1[static_cast<size_t>(r)] = static_cast<double>(n1) * dtau;
            t2[static_cast<size_t>(r)] = static_cast<double>(n2) * dtau;
        }
    };
    for (int sub = 0; sub < 2; ++sub) {
        const unsigned nch = sub == 0 ? 16u : 4u, sh = sub == 0 ? 0u : 4u;
        const int r0 = sub == 0 ? 0 : 4, nr = sub == 0 ? 4 : 2;
        double best = 1e300;
        unsigned bi = 0;
        for (unsigned ch = 0; ch < nch; ++ch) {
            std::array<double, 3> t1{}, t2{};
            bool ok = true;
            steps(ch << sh, t1, t2, ok);
            double cost = 1e300;
            if (ok) {
                const Vec6 e = terminal_error(c, t1, t2, pl.pattern);
                cost = 0;
                for (int i = r0; i < r0 + nr; ++i) {
                    const double v = (i % 2 == 0) ? e(i) / c.L() : wv * e(i) / c.V();
                    cost += v * v;
                }
            }
            rd.cost[static_cast<size_t>(sub)][ch] = cost;
            if (cost < best) {
                best = cost;
                bi = ch;
            }
        }
        rd.choice[static_cast<size_t>(sub)] = bi;
        rd.nearest[static_cast<size_t>(sub)] = (near_all >> sh) & (nch - 1u);
    }
    const unsigned ch_all = rd.choice[0] | (rd.choice[1] << 4);
    std::array<double, 3> t1{}, t2{};
    bool ok = true;
    steps(ch_all, t1, t2, ok);
    rd.miss = terminal_error(c, t1, t2, pl.pattern);
    for (int r = 0; r < 3; ++r) {
        rd.n1[static_cast<size_t>(r)] = std::lround(t1[static_cast<size_t>(r)] / dtau);
        rd.n2[static_cast<size_t>(r)] = std::lround(t2[static_cast<size_t>(r)] / dtau);
    }
    steps(near_all, t1, t2, ok);
    rd.miss_nearest = terminal_error(c, t1, t2, pl.pattern);
    return rd;
}

Mat6 phi_expm(double tau)
{
    Mat6 a = Mat6::Zero();
    a(0, 1) = 1; a(1, 3) = 2;
    a(2, 3) = 1; a(3, 1) = -2; a(3, 2) = 3;
    a(4, 5) = 1; a(5, 4) = -1;
    return (a * tau).exp();
}

Eigen::VectorXd psi_quad(int axis, double sig, double tol)
{
    const int rows = axis == 2 ? 2 : 4;
    Eigen::VectorXd v(rows);
    for (int i = 0; i < rows; ++i) {
        std::function<double(double)> f = [&](double u) { return phi_e(axis, u)(i); };
        const double fa = f(0), fb = f(sig), fm = f(0.5 * sig);
        v(i) = adaptive_simpson(f, 0, sig, fa, fm, fb, sig / 6 * (fa + 4 * fm + fb), tol, 40);
    }
    return v;
}

Eigen::MatrixXd jacobian_fd(const ImpNd &p, int sub, unsigned pat, const std::array<double, 2> &t1,
                            const std::array<double, 2> &t2, double h)
{
    const int n = 2 * sub_nax(sub);
    Eigen::MatrixXd j(n, n);
    for (int col = 0; col < n; ++col) {
        std::array<double, 2> a1 = t1, a2 = t2, b1 = t1, b2 = t2;
        auto &ta = (col % 2 == 0) ? a1 : a2;
        auto &tb = (col % 2 == 0) ? b1 : b2;
        ta[static_cast<size_t>(col / 2)] += h;
        tb[static_cast<size_t>(col / 2)] -= h;
        j.col(col) = (residual(p, sub, pat, a1, a2) - residual(p, sub, pat, b1, b2)) / (2 * h);
    }
    return j;
}

}  // namespace ref
