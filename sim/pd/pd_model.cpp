// pd_model — see pd_model.hpp (spec 40 §2.2-§2.6, §3.1, §3.2, §4.1).
#include "pd/pd_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Eigenvalues>
#include <unsupported/Eigen/MatrixFunctions>

namespace ref::pd {

namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;

Eigen::VectorXcd poly_roots_monic3(double c2, double c1, double c0)  // s^3 + c2 s^2 + c1 s + c0
{
    Eigen::Matrix3d comp = Eigen::Matrix3d::Zero();
    comp(0, 0) = -c2;
    comp(0, 1) = -c1;
    comp(0, 2) = -c0;
    comp(1, 0) = 1.0;
    comp(2, 1) = 1.0;
    Eigen::EigenSolver<Eigen::Matrix3d> es(comp, false);
    return es.eigenvalues();
}

std::size_t idx(Eigen::Index i) { return static_cast<std::size_t>(i); }

}  // namespace

// ---- channels (§2.4) -------------------------------------------------------------------------------
Channel Channel::rigid() const
{
    Channel c = *this;
    c.modes.clear();
    return c;
}

Channel Channel::yaw()
{
    Channel c;
    c.name = "yaw";
    c.Ix = 48100.0;
    c.modes = {Mode{1630.0, 1.0, 1.00}, Mode{9941.0, 2.32, 1.74}};
    c.k0 = 2.0;
    c.k1 = 20.0;
    c.k2 = 150.0;
    return c;
}

Channel Channel::roll()
{
    Channel c;
    c.name = "roll";
    c.Ix = 7700.0;
    c.modes = {Mode{4285.0, 1.0, 1.04}};
    c.k0 = 2.0;
    c.k1 = 15.0;
    c.k2 = 130.0;
    c.k2_cap = 150.0;
    return c;
}

Channel Channel::pitch()
{
    Channel c;
    c.name = "pitch";
    c.Ix = 52600.0;
    c.modes = {Mode{6130.0, 1.0, 1.13}};
    c.k0 = 2.0;
    c.k1 = 20.0;
    c.k2 = 150.0;
    return c;
}

Channel Channel::by_name(const std::string &name)
{
    if (name == "yaw") {
        return yaw();
    }
    if (name == "roll") {
        return roll();
    }
    if (name == "pitch") {
        return pitch();
    }
    throw std::invalid_argument("unknown channel '" + name + "'");
}

// ---- plant (§2.2) ----------------------------------------------------------------------------------
Plant continuous(const Channel &ch, double f_hz)
{
    const Eigen::Index n = static_cast<Eigen::Index>(ch.modes.size());
    const Eigen::Index nd = n + 2;  // dof: x, beta, q_1..q_n
    Eigen::MatrixXd Mm = Eigen::MatrixXd::Zero(nd, nd), C = Eigen::MatrixXd::Zero(nd, nd),
                    K = Eigen::MatrixXd::Zero(nd, nd);
    Eigen::VectorXd F = Eigen::VectorXd::Zero(nd);
    Plant p;
    p.n_dof = static_cast<int>(nd);
    // body: Ix x'' + sum I_i q_i'' - H beta' = 0
    Mm(0, 0) = ch.Ix;
    C(0, 1) = -ch.H;
    // gimbal: Ibeta beta'' + kbd beta' + kbs beta + H x' = M
    Mm(1, 1) = ch.Ibeta;
    C(1, 1) = ch.kbd;
    K(1, 1) = ch.kbs;
    C(1, 0) = ch.H;
    F(1) = 1.0;
    for (Eigen::Index i = 0; i < n; ++i) {
        const Mode &m = ch.modes[idx(i)];
        const double om = m.ratio * kTwoPi * f_hz;
        p.omega.push_back(om);
        Mm(0, 2 + i) = m.I;
        // mode: r_i x'' + q_i'' + Omega_i^2 q_i = 0
        Mm(2 + i, 0) = m.r;
        Mm(2 + i, 2 + i) = 1.0;
        K(2 + i, 2 + i) = om * om;
    }
    const Eigen::MatrixXd Mi = Mm.inverse();
    p.A = Eigen::MatrixXd::Zero(2 * nd, 2 * nd);
    p.A.topRightCorner(nd, nd).setIdentity();
    p.A.bottomLeftCorner(nd, nd) = -Mi * K;
    p.A.bottomRightCorner(nd, nd) = -Mi * C;
    p.B = Eigen::VectorXd::Zero(2 * nd);
    p.B.tail(nd) = Mi * F;
    return p;
}

DiscreteN zoh(const Eigen::MatrixXd &A, const Eigen::MatrixXd &B, double Ty)
{
    const Eigen::Index ns = A.rows(), nu = B.cols();
    Eigen::MatrixXd blk = Eigen::MatrixXd::Zero(ns + nu, ns + nu);
    blk.topLeftCorner(ns, ns) = A * Ty;
    blk.topRightCorner(ns, nu) = B * Ty;
    const Eigen::MatrixXd E = blk.exp();
    DiscreteN d;
    d.Ad = E.topLeftCorner(ns, ns);
    d.Bd = E.topRightCorner(ns, nu);
    d.Ty = Ty;
    return d;
}

Discrete discretise(const Plant &p, double Ty)
{
    const DiscreteN z = zoh(p.A, p.B, Ty);
    Discrete d;
    d.Ad = z.Ad;
    d.Bd = z.Bd.col(0);
    d.omega = p.omega;
    d.Ty = Ty;
    return d;
}

Discrete discretise(const Channel &ch, double f_hz) { return discretise(continuous(ch, f_hz), ch.Ty); }

// ---- §2.3 rigid analysis ---------------------------------------------------------------------------
RigidAnalysis rigid_analysis(const Channel &ch, double k2)
{
    RigidAnalysis r;
    const double IxIb = ch.Ix * ch.Ibeta;
    r.a2 = ch.kbd / ch.Ibeta;
    r.a1 = ch.H * (ch.H + ch.k0 * k2) / IxIb + ch.kbs / ch.Ibeta;
    r.a0 = ch.H * ch.k0 * ch.k1 / IxIb;
    const Eigen::VectorXcd s = poly_roots_monic3(r.a2, r.a1, r.a0);
    std::vector<std::complex<double>> v(s.data(), s.data() + 3);
    std::sort(v.begin(), v.end(), [](const std::complex<double> &a, const std::complex<double> &b) {
        return std::fabs(a.real()) > std::fabs(b.real());
    });
    for (std::size_t i = 0; i < 3; ++i) {
        r.roots[i] = v[i];
    }
    r.min_abs_re = std::fabs(v[2].real());
    const double c = std::cbrt(r.a0);
    r.b2 = r.a2 / c;
    r.b1 = r.a1 / (c * c);
    // eta^3 - b2 eta^2 + b1 eta - 1 = 0: the roots are -p.
    const Eigen::VectorXcd e = poly_roots_monic3(-r.b2, r.b1, -1.0);
    double best = std::numeric_limits<double>::infinity();
    for (Eigen::Index i = 0; i < 3; ++i) {
        const std::complex<double> z = e(i);
        if (std::fabs(z.imag()) <= 1e-9 * std::max(1.0, std::abs(z)) && z.real() > 0.0 && z.real() < best) {
            best = z.real();
        }
    }
    r.eta_p = std::isfinite(best) ? best : std::numeric_limits<double>::quiet_NaN();
    r.eta = r.eta_p * c;
    r.t_p = 3.0 / r.eta;
    r.stab_lhs = ch.kbd * (ch.H + ch.k0 * k2);
    r.stab_rhs = ch.Ibeta * ch.k0 * ch.k1;
    r.stable = r.stab_lhs > r.stab_rhs && r.a2 * r.a1 > r.a0 && r.a2 > 0.0 && r.a0 > 0.0;
    r.dominance = std::fabs(v[1].real()) / r.min_abs_re;
    r.real_dominant = std::fabs(v[2].imag()) < 1e-12 * std::abs(v[2]) + 1e-15 && r.dominance >= 3.0;
    return r;
}

// ---- §3 sampled closed loops -----------------------------------------------------------------------
double loop_period(const Channel &ch, Law law) { return law == Law::Fast ? ch.Ty : ch.T0(); }

Eigen::MatrixXd closed_loop(const Discrete &d, const Channel &ch, Law law, double k2)
{
    const Eigen::Index ns = d.Ad.rows();
    if (law == Law::Fast) {
        // M_k = -(G_P y_k + G_D (y_k - y_{k-1})), y = x = s(0); z = [s; y_{k-1}]
        const double GP = ch.k0 * ch.k1, GD = ch.k0 * k2 / ch.Ty;
        Eigen::MatrixXd P = Eigen::MatrixXd::Zero(ns + 1, ns + 1);
        P.topLeftCorner(ns, ns) = d.Ad;
        P.col(0).head(ns) -= d.Bd * (GP + GD);
        P.block(0, ns, ns, 1) = d.Bd * GD;
        P(ns, 0) = 1.0;
        return P;
    }
    // LITERAL, z = [s; Mh; xbar_prev; S] through n_y samples, then the period update.
    const Eigen::Index nz = ns + 3, iM = ns, iX = ns + 1, iS = ns + 2;
    Eigen::MatrixXd prop = Eigen::MatrixXd::Identity(nz, nz), acc = Eigen::MatrixXd::Identity(nz, nz);
    prop.topLeftCorner(ns, ns) = d.Ad;
    prop.block(0, iM, ns, 1) = d.Bd;  // the plant advances one Ty under the held M
    acc(iS, 0) = 1.0;                  // S += y_k
    Eigen::MatrixXd upd = Eigen::MatrixXd::Identity(nz, nz);
    const double ny = static_cast<double>(ch.n_y), T0 = ch.T0();
    // xbar = S/n_y; M = -k0 (k1 xbar + k2 (xbar - xbar_prev)/T0); xbar_prev = xbar; S = 0
    upd.row(iM).setZero();
    upd(iM, iS) = -ch.k0 * (ch.k1 + k2 / T0) / ny;
    upd(iM, iX) = ch.k0 * k2 / T0;
    upd.row(iX).setZero();
    upd(iX, iS) = 1.0 / ny;
    upd.row(iS).setZero();
    // Samples nu = 0..n_y-1 at jT0 + nu Ty; the period completes with the last sample, whose frame
    // computes the new M; it acts from that sample on (lock-step, as FAST) for n_y samples.
    Eigen::MatrixXd L = Eigen::MatrixXd::Identity(nz, nz);
    for (int k = 0; k < ch.n_y - 1; ++k) {
        L = prop * acc * L;
    }
    L = prop * upd * acc * L;
    // S is 0 at every boundary: the lifted map on [s; Mh; xbar_prev].
    return L.topLeftCorner(ns + 2, ns + 2);
}

Spectrum spectrum(const Discrete &d, const Channel &ch, Law law, double k2)
{
    const Eigen::MatrixXd P = closed_loop(d, ch, law, k2);
    Eigen::EigenSolver<Eigen::MatrixXd> es(P, false);
    const Eigen::VectorXcd z = es.eigenvalues();
    const Eigen::Index nz = z.size();
    Eigen::Index i1 = 0;
    for (Eigen::Index i = 1; i < nz; ++i) {
        if (std::abs(z(i) - 1.0) < std::abs(z(i1) - 1.0)) {
            i1 = i;
        }
    }
    Spectrum sp;
    sp.z1_dist = std::abs(z(i1) - 1.0);
    if (!(sp.z1_dist < 1e-9)) {
        throw std::runtime_error("pd spectrum: no eigenvalue within 1e-9 of z = 1 (momentum invariant)");
    }
    const double T = loop_period(ch, law);
    std::vector<std::complex<double>> s;
    std::vector<bool> finite;
    for (Eigen::Index i = 0; i < nz; ++i) {
        if (i == i1) {
            continue;
        }
        sp.rho = std::max(sp.rho, std::abs(z(i)));
        const bool fin = std::abs(z(i)) > 1e-300;
        finite.push_back(fin);
        s.push_back(fin ? std::log(z(i)) / T : std::complex<double>(-std::numeric_limits<double>::infinity(), 0.0));
    }
    std::vector<bool> elastic(s.size(), false);
    std::vector<std::size_t> order(d.omega.size());
    for (std::size_t i = 0; i < order.size(); ++i) {
        order[i] = i;
    }
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return d.omega[a] > d.omega[b]; });
    for (std::size_t m : order) {
        const std::complex<double> target(0.0, d.omega[m]);
        std::size_t best = s.size();
        double bd = std::numeric_limits<double>::infinity();
        for (std::size_t i = 0; i < s.size(); ++i) {
            if (!finite[i] || elastic[i] || s[i].imag() < 0.0) {
                continue;
            }
            const double dd = std::abs(s[i] - target);
            if (dd < bd) {
                bd = dd;
                best = i;
            }
        }
        if (best == s.size()) {
            continue;
        }
        elastic[best] = true;
        sp.s_elastic.push_back(s[best]);
        // its conjugate
        std::size_t conj = s.size();
        double cd = std::numeric_limits<double>::infinity();
        for (std::size_t i = 0; i < s.size(); ++i) {
            if (i == best || !finite[i] || elastic[i]) {
                continue;
            }
            const double dd = std::abs(s[i] - std::conj(s[best]));
            if (dd < cd) {
                cd = dd;
                conj = i;
            }
        }
        if (conj != s.size() && s[best].imag() > 0.0) {
            elastic[conj] = true;
        }
    }
    sp.zeta = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < s.size(); ++i) {
        if (!finite[i] || elastic[i]) {
            continue;
        }
        const double mag = std::abs(s[i]);
        const double zeta = mag > 0.0 ? -s[i].real() / mag : 1.0;
        if (zeta < sp.zeta) {
            sp.zeta = zeta;
            sp.s_least = s[i];
        }
    }
    if (!std::isfinite(sp.zeta)) {
        sp.zeta = 1.0;
    }
    return sp;
}

// ---- §2.6 settling and simulation ------------------------------------------------------------------
double settle_time(const std::vector<double> &x, double Ty, double dx)
{
    if (x.empty()) {
        return -1.0;
    }
    std::size_t last = x.size();  // none
    for (std::size_t k = x.size(); k-- > 0;) {
        if (!(std::fabs(x[k]) < dx)) {  // NaN (a diverged run) violates the band
            last = k;
            break;
        }
    }
    if (last == x.size()) {
        return 0.0;
    }
    if (last + 1 == x.size()) {
        return -1.0;
    }
    return static_cast<double>(last + 1) * Ty;
}

namespace {

// The k2 columns advanced together. Calls on_sample(k, x_row) at every sample t_k = k Ty.
template <class OnSample>
void run_columns(const Discrete &d, const Channel &ch, Law law, const std::vector<double> &k2s, double horizon,
                 OnSample on_sample)
{
    const std::size_t ns = idx(d.Ad.rows()), K = k2s.size();
    const long nsteps = std::lround(horizon / ch.Ty);
    std::vector<double> Ad(ns * ns), Bd(ns);
    for (std::size_t i = 0; i < ns; ++i) {
        Bd[i] = d.Bd(static_cast<Eigen::Index>(i));
        for (std::size_t j = 0; j < ns; ++j) {
            Ad[i * ns + j] = d.Ad(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
        }
    }
    std::vector<double> s(ns * K, 0.0), sn(ns * K), M(K, 0.0), yp(K), xbp(K), S(K, 0.0), gd(K), c2(K);
    for (std::size_t k = 0; k < K; ++k) {
        s[k] = ch.x0;  // row 0 = x
        yp[k] = ch.x0;
        gd[k] = ch.k0 * k2s[k] / ch.Ty;
        c2[k] = ch.k0 * k2s[k] / ch.T0();
    }
    const double GP = ch.k0 * ch.k1, ny = static_cast<double>(ch.n_y);
    bool first_period = true;
    for (long n = 0; n <= nsteps; ++n) {
        const double *x = s.data();
        on_sample(n, x);
        if (n == nsteps) {
            break;
        }
        if (law == Law::Fast) {
            for (std::size_t k = 0; k < K; ++k) {
                M[k] = -(GP * x[k] + gd[k] * (x[k] - yp[k]));
                yp[k] = x[k];
            }
        } else {
            for (std::size_t k = 0; k < K; ++k) {
                S[k] += x[k];
            }
            if ((n + 1) % ch.n_y == 0) {  // the period's last sample: new M from this sample on
                for (std::size_t k = 0; k < K; ++k) {
                    const double xb = S[k] / ny;
                    if (first_period) {
                        xbp[k] = xb;
                    }
                    M[k] = -(GP * xb + c2[k] * (xb - xbp[k]));
                    xbp[k] = xb;
                    S[k] = 0.0;
                }
                first_period = false;
            }
        }
        for (std::size_t i = 0; i < ns; ++i) {
            double *out = &sn[i * K];
            const double b = Bd[i];
            for (std::size_t k = 0; k < K; ++k) {
                out[k] = b * M[k];
            }
            for (std::size_t j = 0; j < ns; ++j) {
                const double a = Ad[i * ns + j];
                const double *in = &s[j * K];
                for (std::size_t k = 0; k < K; ++k) {
                    out[k] += a * in[k];
                }
            }
        }
        s.swap(sn);
    }
}

}  // namespace

std::vector<double> simulate(const Discrete &d, const Channel &ch, Law law, double k2, double horizon)
{
    std::vector<double> out;
    run_columns(d, ch, law, std::vector<double>{k2}, horizon, [&](long, const double *x) { out.push_back(x[0]); });
    return out;
}

std::vector<double> settle_times(const Discrete &d, const Channel &ch, Law law, const std::vector<double> &k2s,
                                 double horizon)
{
    const std::size_t K = k2s.size();
    std::vector<long> last(K, -1);
    long nlast = 0;
    run_columns(d, ch, law, k2s, horizon, [&](long n, const double *x) {
        nlast = n;
        for (std::size_t k = 0; k < K; ++k) {
            if (!(std::fabs(x[k]) < ch.dx)) {  // NaN violates the band
                last[k] = n;
            }
        }
    });
    std::vector<double> t(K);
    for (std::size_t k = 0; k < K; ++k) {
        if (last[k] < 0) {
            t[k] = 0.0;
        } else if (last[k] == nlast) {
            t[k] = -1.0;
        } else {
            t[k] = static_cast<double>(last[k] + 1) * ch.Ty;
        }
    }
    return t;
}

// ---- §4.1 ------------------------------------------------------------------------------------------
std::vector<double> grid(double from, double step, double to)
{
    if (!(step > 0.0) || to < from) {
        throw std::invalid_argument("grid: need step > 0 and to >= from");
    }
    const long n = std::lround(std::floor((to - from) / step + 1e-9));
    std::vector<double> g;
    for (long i = 0; i <= n; ++i) {
        g.push_back(from + static_cast<double>(i) * step);
    }
    return g;
}

std::vector<double> f_nodes()
{
    std::vector<double> f;
    for (int i = 0; i <= 18; ++i) {
        f.push_back((10.0 + 5.0 * static_cast<double>(i)) / 1000.0);
    }
    return f;
}

double NodeResult::t_at(double k2v) const
{
    for (std::size_t i = 0; i < k2.size(); ++i) {
        if (std::fabs(k2[i] - k2v) < 1e-9) {
            return tstar[i];
        }
    }
    throw std::invalid_argument("t_at: k2 not on the grid");
}

namespace {

// kPlateauMargin: k2opt moved up (never down) until the window around it is free of a t* jump.
double plateau_k2(const NodeResult &r)
{
    if (r.k2opt < 0.0) {
        return r.k2opt;
    }
    const double band = r.tmin + std::max(5.0, 0.05 * r.tmin);
    for (std::size_t i = 0; i < r.k2.size(); ++i) {
        if (r.k2[i] < r.k2opt - 1e-9 || !r.admissible[i]) {
            continue;
        }
        bool flat = true;
        for (std::size_t j = 0; j < r.k2.size() && flat; ++j) {
            if (std::fabs(r.k2[j] - r.k2[i]) <= kPlateauMargin + 1e-9) {
                flat = r.tstar[j] >= 0.0 && r.tstar[j] <= band;
            }
        }
        if (flat) {
            return r.k2[i];
        }
    }
    return r.k2opt;
}

}  // namespace

NodeResult sweep_node(const Channel &ch, double f_hz, const std::vector<double> &k2grid, Law law, double horizon)
{
    NodeResult r;
    r.f = f_hz;
    r.k2 = k2grid;
    const Discrete d = discretise(ch, f_hz);
    r.tstar = settle_times(d, ch, law, k2grid, horizon);
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < k2grid.size(); ++i) {
        const Spectrum sp = spectrum(d, ch, law, k2grid[i]);
        r.rho.push_back(sp.rho);
        r.zeta.push_back(sp.zeta);
        const bool adm = sp.rho < 1.0 && sp.zeta >= kZetaMin && k2grid[i] <= ch.k2_cap;
        r.admissible.push_back(adm);
        if (adm && r.tstar[i] >= 0.0 && r.tstar[i] < best) {
            best = r.tstar[i];
            r.k2opt = k2grid[i];
        }
    }
    r.tmin = std::isfinite(best) ? best : -1.0;
    r.k2plat = plateau_k2(r);
    return r;
}

Schedule finish_schedule(std::vector<NodeResult> nodes)
{
    Schedule sc;
    sc.nodes = std::move(nodes);
    const std::size_t n = sc.nodes.size();
    sc.k2s.assign(n, 0.0);
    for (std::size_t i = n; i-- > 0;) {
        double v = sc.nodes[i].k2plat;
        if (v < 0.0) {  // nothing settles: the largest admissible k2 (documented choice)
            for (std::size_t j = 0; j < sc.nodes[i].k2.size(); ++j) {
                if (sc.nodes[i].admissible[j]) {
                    v = sc.nodes[i].k2[j];
                }
            }
        }
        sc.k2s[i] = (i + 1 < n) ? std::max(v, sc.k2s[i + 1]) : v;
    }
    if (n == 0) {
        return sc;
    }
    const std::vector<double> &g = sc.nodes[0].k2;
    for (std::size_t j = 0; j < g.size(); ++j) {
        if (g[j] > sc.k2s[0] + 1e-9) {
            break;
        }
        bool all = true;
        for (const NodeResult &nr : sc.nodes) {
            all = all && nr.admissible[j];
        }
        if (all) {
            sc.k2_cold = g[j];
        }
    }
    return sc;
}

double zeta_cap(const Channel &ch, const std::vector<double> &fs, const std::vector<double> &k2grid)
{
    std::vector<Discrete> ds;
    for (double f : fs) {
        ds.push_back(discretise(ch, f));
    }
    double cap = -1.0;
    for (double k2 : k2grid) {
        for (const Discrete &d : ds) {
            if (spectrum(d, ch, Law::Fast, k2).zeta < kZetaMin) {
                return cap;
            }
        }
        cap = k2;
    }
    return cap;
}

}  // namespace ref::pd
