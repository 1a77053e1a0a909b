#include "impulse/imp_ref_fsw.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "impulse/imp_ref_detail.hpp"

namespace ref {

using detail::kQ28;
using detail::kQ29;
using detail::kQ30;

namespace {

constexpr unsigned kJobReplan = 2, kJobStuck = 3;   // re-plan kinds (as imp.c)
constexpr unsigned kEvOff = 0x100u, kEvOn = 0x200u;

int axis_rows(int r) { return r == 2 ? 2 : 4; }
int axis_row0(int r) { return r == 2 ? 4 : 0; }
unsigned burn_thr(unsigned pattern, int r, int b) { return static_cast<unsigned>(2 * r) + ((pattern >> (2 * r + b)) & 1u); }
Eigen::Vector3d vel(const Vec6 &v) { return Eigen::Vector3d(v(1), v(3), v(5)); }

// Gaussian elimination with partial pivoting for the calibration normal equations (as the
// flight code: singular when a pivot is below 2^-12 of the largest diagonal).
bool small_solve(Eigen::MatrixXd a, Eigen::VectorXd b, Eigen::VectorXd &x)
{
    const int n = static_cast<int>(a.rows());
    const double dmax = a.diagonal().cwiseAbs().maxCoeff();
    for (int k = 0; k < n; ++k) {
        int p = k;
        for (int i = k + 1; i < n; ++i) {
            if (std::abs(a(i, k)) > std::abs(a(p, k))) { p = i; }
        }
        a.row(k).swap(a.row(p));
        std::swap(b(k), b(p));
        if (!(std::abs(a(k, k)) >= dmax / 4096.0) || !(dmax > 0)) { return false; }
        for (int i = k + 1; i < n; ++i) {
            const double l = a(i, k) / a(k, k);
            a.row(i) -= l * a.row(k);
            b(i) -= l * b(k);
        }
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

ImpFsw::ImpFsw(const imp_params_t &p) : p_(p)
{
    w_ = p.omega_nradps * 1e-9;
    G_ = p.subtick_us ? p.period_us / p.subtick_us : 1u;
    us_ = p.subtick_us ? p.subtick_us : p.period_us;
    dg_ = w_ * us_ * 1e-6;
    wv_ = p.w_v_q28 / kQ28;
    nmin_ = (p.t_min_us + us_ - 1) / us_;
    g_ = guards_from_table(p);
    init();
}

void ImpFsw::init()
{
    mode_ = IMP_MODE_IDLE;
    t0_ = tf_ = next_tp_ = 0;
    retry_ = marginal_ = false;
    latched_ = 0;
    stuck_off_ = 0;
    stuck_j_ = 0xFF;
    act_ = pend_ = Tl();
    nav_ = cal_ref_ = fd_x0_ = Nav();
    log_.clear();
    lost_g_ = 0;
    seen_ = false;
    seen_step_ = 0;
    cal_reset();
    cnt_off_.fill(0);
    cnt_on_.fill(0);
    on_tot_.fill(0);
    exp_dr_.fill(0);
    exp_dv_.fill(0);
    plans_ = failed_ = skipped_ = cmd_rej_ = nav_rej_ = cal_rej_ = kept_ = 0;
    rej_reason_ = pattern_ = 0;
    health_sticky_ = 0;
}

Vec6 ImpFsw::convert(const std::int32_t *pos, const std::int32_t *vel_c) const
{
    const double a = p_.a_nom_umps2 * 1e-6, L = a / (w_ * w_), V = a / w_;
    Vec6 x;
    for (int r = 0; r < 3; ++r) {
        x(2 * r) = pos[r] * 1e-3 / L;
        x(2 * r + 1) = vel_c[r] * 1e-5 / V;
    }
    return x;
}

bool ImpFsw::fresh(std::uint32_t k) const
{
    return nav_.valid && nav_.step <= k && k - nav_.step <= p_.nav_timeout && covers(nav_.step);
}

bool ImpFsw::active(unsigned m)
{
    return m == IMP_MODE_PLANNING || m == IMP_MODE_ARMED || m == IMP_MODE_FIRING || m == IMP_MODE_FINAL;
}

bool ImpFsw::terminal(unsigned m)
{
    return m == IMP_MODE_IDLE || m == IMP_MODE_DONE || m == IMP_MODE_INFEASIBLE || m == IMP_MODE_NO_SOLUTION ||
           m == IMP_MODE_ABORTED || m == IMP_MODE_FAULT;
}

void ImpFsw::burn_response(Win &w, unsigned j, std::uint64_t bs, std::uint64_t be, std::uint64_t k1g,
                           std::uint64_t k2g, std::uint64_t teg) const
{
    const std::uint64_t a = std::max(bs, k1g), b = std::min(be, k2g);
    if (a < b && b <= teg) {
        const int r = static_cast<int>(j / 2);
        const Eigen::VectorXd d = psi(r, tau_g(teg - a)) - psi(r, tau_g(teg - b));
        const double sgn = (j & 1u) ? -1.0 : 1.0;
        w.r[j].segment(axis_row0(r), axis_rows(r)) += sgn * d;
        w.on[j] += b - a;
    }
}

void ImpFsw::log_response(Win &w, std::uint64_t k1g, std::uint64_t k2g, std::uint64_t teg) const
{
    for (const Seg &s : log_) { burn_response(w, s.thr, s.s, s.e, k1g, k2g, teg); }
}

void ImpFsw::tl_response(Win &w, const Tl &tl, std::uint64_t k1g, std::uint64_t k2g, std::uint64_t teg) const
{
    if (!tl.valid) { return; }
    const std::uint64_t a0 = static_cast<std::uint64_t>(tl.ta) * G_;
    for (int r = 0; r < 3; ++r) {
        const auto ru = static_cast<size_t>(r);
        burn_response(w, tl.thr1[ru], a0, a0 + tl.n1[ru], k1g, k2g, teg);
        burn_response(w, tl.thr2[ru], a0 + tl.n2[ru], a0 + tl.ntot, k1g, k2g, teg);
    }
}

Vec6 ImpFsw::predict(const Win &w, const Vec6 &x1, std::uint64_t dgu) const
{
    Vec6 x = phi(tau_g(dgu)) * x1;
    for (size_t j = 0; j < 6; ++j) { x += alpha_[j] * w.r[j]; }
    return x;
}

ImpFsw::Win ImpFsw::window(const Nav &a, const Nav &b) const
{
    Win w;
    for (auto &r : w.r) { r.setZero(); }
    const std::uint64_t k1g = static_cast<std::uint64_t>(a.step) * G_, k2g = static_cast<std::uint64_t>(b.step) * G_;
    log_response(w, k1g, k2g, k2g);
    w.xp = predict(w, a.x, k2g - k1g);
    w.m = b.x - w.xp;
    return w;
}

Vec6 ImpFsw::propagate(const Nav &nv, std::uint32_t now, std::uint32_t ta, bool use_tl) const
{
    Win w;
    for (auto &r : w.r) { r.setZero(); }
    const std::uint64_t k1g = static_cast<std::uint64_t>(nv.step) * G_, nowg = static_cast<std::uint64_t>(now) * G_,
                        teg = static_cast<std::uint64_t>(ta) * G_;
    log_response(w, k1g, nowg, teg);
    if (use_tl) { tl_response(w, act_, nowg, teg, teg); }
    return predict(w, nv.x, teg - k1g);
}

bool ImpFsw::gate_ok(const Nav &c) const
{
    if (!(nav_.valid && covers(nav_.step))) { return true; }
    const double dtau = tau_g(static_cast<std::uint64_t>(c.step - nav_.step) * G_);
    const double acc = p_.nav_gate_acc_q28 / kQ28;
    const double lp = p_.nav_gate_pos_q28 / kQ28 + 0.5 * acc * dtau * dtau, lv = p_.nav_gate_vel_q28 / kQ28 + acc * dtau;
    const Win w = window(nav_, c);
    for (int r = 0; r < 3; ++r) {
        if (std::abs(w.m(2 * r)) > lp || std::abs(w.m(2 * r + 1)) > lv) { return false; }
    }
    return true;
}

unsigned ImpFsw::fd_evaluate(const Win &w, std::uint32_t span)
{
    const double frac = p_.fd_frac_q30 / kQ30;
    const std::uint64_t half = static_cast<std::uint64_t>(p_.fd_window) * G_ / 2;
    const double sig = tau_g(static_cast<std::uint64_t>(span) * G_);
    const Eigen::Vector3d m = vel(w.m);
    for (unsigned j = 0; j < 6; ++j) {
        bool eo = false, en = false;
        if (w.on[j] >= half) {
            const Eigen::Vector3d g = vel(w.r[j]);
            const double gg = g.dot(g);
            if (gg > 0) { eo = g.dot(m) + alpha_[j] * gg < frac * alpha_[j] * gg; }
        } else if (w.on[j] == 0) {
            const int r = static_cast<int>(j / 2);
            const Eigen::VectorXd v = psi(r, sig);
            Eigen::Vector3d gf = (r == 2) ? Eigen::Vector3d(0, 0, v(1)) : Eigen::Vector3d(v(1), v(3), 0);
            if (j & 1u) { gf = -gf; }
            const double ff = gf.dot(gf);
            const double ft = std::max(0.0, -alpha_[j ^ 1u] * vel(w.r[j ^ 1u]).dot(gf));
            if (ff > 0 && ft <= 0.75 * ff) { en = gf.dot(m) > ft + frac * (ff - ft); }
        }
        cnt_off_[j] = eo ? cnt_off_[j] + 1 : 0;
        cnt_on_[j] = en ? cnt_on_[j] + 1 : 0;
    }
    for (unsigned j = 0; j < 6; ++j) {
        if (cnt_on_[j] >= p_.fd_persist) { return kEvOn | j; }
    }
    for (unsigned j = 0; j < 6; ++j) {
        if (cnt_off_[j] >= p_.fd_persist && !((stuck_off_ >> j) & 1u)) { return kEvOff | j; }
    }
    return 0;
}

unsigned ImpFsw::fd_step()
{
    unsigned ev = 0;
    const std::uint32_t span = nav_.step - fd_x0_.step;
    if (!fd_x0_.valid || !covers(fd_x0_.step) || nav_.step < fd_x0_.step || span > 2 * p_.fd_window) {
        fd_x0_ = nav_;
    } else if (span >= p_.fd_window) {
        ev = fd_evaluate(window(fd_x0_, nav_), span);
        fd_x0_ = nav_;
    }
    return ev;
}

void ImpFsw::log_prune()
{
    std::uint64_t ref = static_cast<std::uint64_t>(nav_.step) * G_;
    if (fd_x0_.valid) { ref = std::min(ref, static_cast<std::uint64_t>(fd_x0_.step) * G_); }
    if (cal_ref_.valid) { ref = std::min(ref, static_cast<std::uint64_t>(cal_ref_.step) * G_); }
    std::vector<Seg> keep;
    for (const Seg &s : log_) {
        if (s.e > ref) { keep.push_back(s); }
    }
    log_ = keep;
}

void ImpFsw::log_add(unsigned j, std::uint64_t a, std::uint64_t b, std::uint64_t step_g)
{
    for (auto it = log_.rbegin(); it != log_.rend(); ++it) {
        if (it->thr == j) {
            if (it->e == a) {
                it->e = b;
                return;
            }
            break;
        }
    }
    if (log_.size() >= IMP_LOG_CAP) {
        log_.clear();
        lost_g_ = step_g;
    }
    log_.push_back(Seg{j, a, b});
}

unsigned ImpFsw::nav_intake(const imp_in_t &in)
{
    unsigned ev = 0;
    const bool fresh_tag = !seen_ || in.nav_step > seen_step_;
    if (in.nav_valid && in.nav_step <= in.step && fresh_tag && (!nav_.valid || in.nav_step > nav_.step)) {
        seen_ = true;
        seen_step_ = in.nav_step;
        Nav c;
        c.step = in.nav_step;
        c.valid = true;
        c.x = convert(in.nav_pos_mm, in.nav_vel_cnt);
        bool ok = c.x.cwiseAbs().maxCoeff() < 8.0;
        if (ok && active(mode_)) { ok = gate_ok(c); }
        if (!ok) {
            ++nav_rej_;
        } else {
            nav_ = c;
            if (active(mode_)) { ev = fd_step(); }
            log_prune();
        }
    }
    return ev;
}

void ImpFsw::cal_reset()
{
    sum_w_.fill(0);
    sum_wa_.fill(0);
    n_acc_.fill(0);
    for (size_t j = 0; j < 6; ++j) { alpha_[j] = p_.alpha_q30[j] / kQ30; }
    cal_ref_.valid = false;
}

bool ImpFsw::cal_done(unsigned j) const
{
    bool any = false;
    for (unsigned n : n_acc_) { any = any || n != 0; }
    return p_.cal_enable && (n_acc_[j] != 0 || (p_.cal_pool && any));
}

// Returns true when the window was discarded by cal_gate (THRUST_LEVEL).
bool ImpFsw::cal_epoch()
{
    if (!(cal_ref_.valid && covers(cal_ref_.step) && nav_.step > cal_ref_.step)) { return false; }
    const Win w = window(cal_ref_, nav_);
    std::vector<unsigned> unk;
    for (unsigned r = 0; r < 3; ++r) {
        unsigned j = 2 * r;
        if (w.on[j + 1] > w.on[j]) { j = j + 1; }
        if (w.on[j] > 0 && tau_g(w.on[j]) >= p_.dv_cal_min_q28 / kQ28) { unk.push_back(j); }
    }
    if (unk.empty()) { return false; }
    const int n = static_cast<int>(unk.size());
    Eigen::MatrixXd a(n, n);
    Eigen::VectorXd b(n), x;
    const Eigen::Vector3d m = vel(w.m);
    for (int u = 0; u < n; ++u) {
        for (int v = 0; v < n; ++v) { a(u, v) = vel(w.r[unk[static_cast<size_t>(u)]]).dot(vel(w.r[unk[static_cast<size_t>(v)]])); }
        b(u) = vel(w.r[unk[static_cast<size_t>(u)]]).dot(m);
    }
    if (!small_solve(a, b, x)) { return false; }
    bool out = false;
    std::vector<double> ah(static_cast<size_t>(n));
    for (int u = 0; u < n; ++u) {
        ah[static_cast<size_t>(u)] = alpha_[unk[static_cast<size_t>(u)]] + x(u);
        out = out || std::abs(ah[static_cast<size_t>(u)] - 1.0) > p_.cal_gate_q30 / kQ30;
    }
    if (out) {
        ++cal_rej_;
        return true;
    }
    for (int u = 0; u < n; ++u) {
        const unsigned j = unk[static_cast<size_t>(u)];
        const double wt = vel(w.r[j]).squaredNorm();
        sum_w_[j] += wt;
        sum_wa_[j] += wt * ah[static_cast<size_t>(u)];
        ++n_acc_[j];
    }
    double sw = 0, swa = 0;
    for (size_t j = 0; j < 6; ++j) {
        sw += sum_w_[j];
        swa += sum_wa_[j];
    }
    for (size_t j = 0; j < 6; ++j) {
        if (n_acc_[j] != 0 && sum_w_[j] > 0) {
            alpha_[j] = sum_wa_[j] / sum_w_[j];
        } else if (p_.cal_pool && sw > 0) {
            alpha_[j] = swa / sw;
        } else {
            alpha_[j] = p_.alpha_q30[j] / kQ30;
        }
    }
    return false;
}

bool ImpFsw::final_at(std::uint32_t ta) const
{
    std::uint64_t e2 = static_cast<std::uint64_t>(tf_) * G_;
    for (int r = 0; r < 3; ++r) {
        e2 = std::min(e2, static_cast<std::uint64_t>(act_.ta) * G_ + act_.n2[static_cast<size_t>(r)]);
    }
    return static_cast<std::uint64_t>(ta) * G_ >= e2 || static_cast<std::uint64_t>(ta) + p_.t_stop > tf_;
}

void ImpFsw::round_plan(const ImpNd &p, const ImpPlan &pl, std::uint32_t n_total, std::array<std::uint32_t, 3> &n1,
                        std::array<std::uint32_t, 3> &n2, Vec6 &miss) const
{
    const std::uint32_t nm = std::min(nmin_, n_total);
    // candidates per switch (r, b) after the minimum-impulse rule
    std::array<std::array<std::uint32_t, 2>, 6> cand{};
    for (int r = 0; r < 3; ++r) {
        for (int b = 0; b < 2; ++b) {
            const double t = (b == 0 ? pl.t1 : pl.t2)[static_cast<size_t>(r)] / dg_;
            const std::uint32_t nf = static_cast<std::uint32_t>(std::min<double>(n_total, std::floor(t)));
            for (std::uint32_t c = 0; c < 2; ++c) {
                std::uint32_t v = c == 0 ? nf : std::min(nf + 1, n_total);
                if (b == 0 && v > 0 && v < nm) { v = c ? nm : 0; }
                if (b == 1 && n_total - v > 0 && n_total - v < nm) { v = c ? n_total : n_total - nm; }
                cand[static_cast<size_t>(2 * r + b)][c] = v;
            }
        }
    }
    for (int sub = 0; sub < 2; ++sub) {
        const int nax = sub == 0 ? 2 : 1, ax0 = sub == 0 ? 0 : 2, r0 = sub == 0 ? 0 : 4, nr = sub == 0 ? 4 : 2;
        const unsigned nch = 1u << (2 * nax), lpat = sub == 0 ? (pl.pattern & 0xFu) : ((pl.pattern >> 4) & 3u);
        double best = std::numeric_limits<double>::infinity();
        std::array<std::uint32_t, 2> b1{}, b2{};
        Eigen::VectorXd bf = Eigen::VectorXd::Zero(nr);
        for (unsigned ch = 0; ch < nch; ++ch) {
            std::array<std::uint32_t, 2> v1{}, v2{};
            bool ok = true;
            for (int k = 0; k < nax; ++k) {
                const int r = ax0 + k;
                std::uint32_t a1 = cand[static_cast<size_t>(2 * r)][(ch >> (2 * k)) & 1u];
                std::uint32_t a2 = cand[static_cast<size_t>(2 * r + 1)][(ch >> (2 * k + 1)) & 1u];
                if (a1 > a2 || a2 > n_total) { ok = false; }
                if (ok && a1 > 0 && a2 < n_total) {
                    const bool share = (a1 - 1) / G_ == a2 / G_;
                    const bool same = burn_thr(pl.pattern, r, 0) == burn_thr(pl.pattern, r, 1);
                    if (same && a2 > a1 && (a2 - a1 < nmin_ || share)) {
                        a2 = a1;
                    } else if (!same && share) {
                        std::uint32_t wd = (a1 + G_ - 1) / G_ * G_;
                        if (wd >= n_total || n_total - wd < nmin_) { wd = n_total; }
                        a2 = wd;
                    }
                }
                v1[static_cast<size_t>(k)] = a1;
                v2[static_cast<size_t>(k)] = a2;
            }
            if (!ok) { continue; }
            std::array<double, 2> t1{}, t2{};
            for (int k = 0; k < nax; ++k) {
                t1[static_cast<size_t>(k)] = tau_g(v1[static_cast<size_t>(k)]);
                t2[static_cast<size_t>(k)] = tau_g(v2[static_cast<size_t>(k)]);
            }
            const Eigen::VectorXd f = residual(p, sub, lpat, t1, t2);
            double cost = 0;
            for (int i = 0; i < nr; ++i) {
                const double e = (i % 2 == 0) ? f(i) : wv_ * f(i);
                cost += e * e;
            }
            if (cost < best) {
                best = cost;
                b1 = v1;
                b2 = v2;
                bf = f;
            }
        }
        for (int k = 0; k < nax; ++k) {
            n1[static_cast<size_t>(ax0 + k)] = b1[static_cast<size_t>(k)];
            n2[static_cast<size_t>(ax0 + k)] = b2[static_cast<size_t>(k)];
        }
        miss.segment(r0, nr) = bf;
    }
}

bool ImpFsw::plan(const ImpNd &nd, const ImpSolveOpt &o, std::uint32_t ta, Tl &tl)
{
    ++plans_;
    const ImpPlan pl = solve_nd(nd, g_, o);
    if (pl.outcome != IMP_SOL_VALID) {
        ++failed_;
        if (!o.replan) { mode_ = pl.outcome == IMP_SOL_INFEASIBLE ? IMP_MODE_INFEASIBLE : IMP_MODE_NO_SOLUTION; }
        return false;
    }
    if (!o.replan) { marginal_ = pl.marginal; }
    tl.ta = ta;
    tl.ntot = (tf_ - ta) * G_;
    round_plan(nd, pl, tl.ntot, tl.n1, tl.n2, miss_);
    tl.pattern = pl.pattern;
    pattern_ = pl.pattern;
    for (int r = 0; r < 3; ++r) {
        const auto ru = static_cast<size_t>(r);
        tl.thr1[ru] = burn_thr(pl.pattern, r, 0);
        tl.thr2[ru] = burn_thr(pl.pattern, r, 1);
        tl.t1[ru] = pl.t1[ru];
        tl.t2[ru] = pl.t2[ru];
    }
    tl.valid = true;
    return true;
}

void ImpFsw::start_replan(const imp_in_t &in, unsigned kind, std::uint32_t ta)
{
    ImpNd nd;
    nd.x0 = propagate(nav_, in.step, ta, true);
    nd.xt = Vec6::Zero();
    nd.tauf = tau_g(static_cast<std::uint64_t>(tf_ - ta) * G_);
    nd.alpha = alpha_;
    ImpSolveOpt o;
    o.replan = true;
    o.warm_mask = 3;
    o.warm_pattern = act_.pattern;
    o.thr_off = (~(static_cast<unsigned>(in.avail_mask) & ~stuck_off_)) & 0x3Fu;
    const double shift = tau_g(static_cast<std::uint64_t>(ta - act_.ta) * G_);
    for (size_t r = 0; r < 3; ++r) {
        o.warm_t1[r] = std::max(0.0, act_.t1[r] - shift);
        o.warm_t2[r] = act_.t2[r] - shift;
    }
    // predicted cost of keeping the timeline in force (the rounding's metric)
    auto cost = [&](const Vec6 &e) {
        double c = 0;
        for (int i = 0; i < 6; ++i) {
            const double v = (i % 2 == 0) ? e(i) : wv_ * e(i);
            c += v * v;
        }
        return c;
    };
    double keep = std::numeric_limits<double>::infinity();
    if (kind == kJobReplan) {
        Win w;
        for (auto &r : w.r) { r.setZero(); }
        const std::uint64_t tag = static_cast<std::uint64_t>(ta) * G_, teg = static_cast<std::uint64_t>(tf_) * G_;
        tl_response(w, act_, tag, teg, teg);
        keep = cost(predict(w, nd.x0, teg - tag) - nd.xt);
    }
    Tl tl;
    if (plan(nd, o, ta, tl)) {
        if (cost(miss_) > (1.0 - p_.replan_gain_q30 / kQ30) * keep) {
            ++kept_;
        } else {
            pend_ = tl;
        }
    } else if (kind == kJobStuck) {
        mode_ = IMP_MODE_ABORTED;
    }
}

unsigned ImpFsw::start(const imp_in_t &in)
{
    if (in.step > UINT32_MAX - p_.plan_lead || in.cmd_tf_step <= in.cmd_t0_step || in.cmd_t0_step < in.step + p_.plan_lead) {
        return IMP_REJ_TIME;
    }
    const double tauf = tau_g(static_cast<std::uint64_t>(in.cmd_tf_step - in.cmd_t0_step) * G_);
    if (tauf < p_.tauf_min_q29 / kQ29 || tauf > p_.tauf_max_q29 / kQ29) { return IMP_REJ_TAU; }
    if (!fresh(in.step) || nav_.step > in.cmd_t0_step) { return IMP_REJ_NO_NAV; }
    const Vec6 xt = convert(in.cmd_tgt_pos_mm, in.cmd_tgt_vel_cnt);
    if (xt.cwiseAbs().maxCoeff() >= 8.0) { return IMP_REJ_TARGET; }
    t0_ = in.cmd_t0_step;
    tf_ = in.cmd_tf_step;
    act_.valid = pend_.valid = false;
    retry_ = marginal_ = false;
    cal_reset();
    ImpNd nd;
    nd.x0 = propagate(nav_, in.step, t0_, false);
    cal_ref_ = nav_;
    fd_x0_ = nav_;
    cnt_off_.fill(0);
    cnt_on_.fill(0);
    on_tot_.fill(0);
    nd.xt = xt;
    nd.tauf = tauf;
    nd.alpha = alpha_;
    ImpSolveOpt o;
    o.thr_off = (~(static_cast<unsigned>(in.avail_mask) & ~stuck_off_)) & 0x3Fu;
    mode_ = IMP_MODE_PLANNING;
    Tl tl;
    if (plan(nd, o, t0_, tl)) {
        act_ = tl;
        next_tp_ = t0_ + p_.replan_period;
        mode_ = IMP_MODE_ARMED;
    }
    return IMP_REJ_NONE;
}

unsigned ImpFsw::command(const imp_in_t &in)
{
    unsigned why = IMP_REJ_NONE;
    if (in.cmd == IMP_CMD_ABORT) {
        mode_ = IMP_MODE_ABORTED;
        pend_.valid = false;
    } else if (in.cmd == IMP_CMD_CLEAR_FAULTS) {
        if (terminal(mode_)) {
            mode_ = IMP_MODE_IDLE;
            latched_ = 0;
            stuck_off_ = 0;
            stuck_j_ = 0xFF;
            health_sticky_ = 0;
            cnt_off_.fill(0);
            cnt_on_.fill(0);
        }
    } else if (in.cmd == IMP_CMD_START && terminal(mode_)) {
        why = start(in);
    } else if (in.cmd != IMP_CMD_NONE) {
        why = IMP_REJ_MODE;
    }
    if (why != IMP_REJ_NONE) {
        ++cmd_rej_;
        rej_reason_ = why;
        return IMP_H_CMD_REJ;
    }
    return 0;
}

void ImpFsw::fd_react(const imp_in_t &in, unsigned ev)
{
    const unsigned j = ev & 0xFFu, kind = ev & 0xF00u;
    if (kind == 0 || j >= 6 || !active(mode_)) { return; }
    stuck_j_ = j;
    if (kind == kEvOn) {
        latched_ |= 1u << (IMP_H_STUCK_ON_SH + j / 2);
        mode_ = IMP_MODE_ABORTED;
        pend_.valid = false;
        return;
    }
    const std::uint32_t ta = in.step + p_.plan_lead;
    latched_ |= 1u << (IMP_H_STUCK_OFF_SH + j / 2);
    stuck_off_ |= 1u << j;
    pend_.valid = false;
    if (mode_ == IMP_MODE_FIRING && !final_at(ta) && fresh(in.step)) {
        start_replan(in, kJobStuck, ta);
    } else {
        mode_ = IMP_MODE_ABORTED;
    }
}

void ImpFsw::epoch(const imp_in_t &in, bool regular)
{
    const std::uint32_t ta = in.step + p_.plan_lead;
    if (final_at(ta)) {
        mode_ = IMP_MODE_FINAL;
        retry_ = false;
    } else if (pend_.valid) {
        ++skipped_;
    } else if (!fresh(in.step)) {
        if (regular) { ++skipped_; }
        retry_ = true;
        cal_ref_.valid = false;
    } else {
        retry_ = false;
        if (regular && p_.cal_enable && cal_epoch()) { latched_ |= IMP_H_THRUST_LEVEL; }
        cal_ref_ = nav_;
        start_replan(in, kJobReplan, ta);
    }
}

void ImpFsw::progress(const imp_in_t &in)
{
    if (mode_ == IMP_MODE_ARMED && in.step >= t0_) { mode_ = IMP_MODE_FIRING; }
    if (mode_ == IMP_MODE_FIRING) {
        if (p_.replan_period != 0 && in.step >= next_tp_) {
            next_tp_ += p_.replan_period;
            if (next_tp_ <= in.step) { next_tp_ = in.step + p_.replan_period; }
            epoch(in, true);
        } else if (retry_ && fresh(in.step)) {
            epoch(in, false);
        }
    }
    if (pend_.valid && in.step >= pend_.ta) {
        act_ = pend_;
        pend_.valid = false;
    }
    if ((mode_ == IMP_MODE_FIRING || mode_ == IMP_MODE_FINAL) && in.step >= tf_) {
        mode_ = IMP_MODE_DONE;
        pend_.valid = false;
    }
}

unsigned ImpFsw::fire(std::uint32_t k, unsigned avail, imp_out_t &out)
{
    const std::uint64_t k0 = static_cast<std::uint64_t>(k) * G_, k1 = k0 + G_, a0 = static_cast<std::uint64_t>(act_.ta) * G_;
    std::array<std::uint32_t, 6> lo{}, hi{};
    unsigned h = 0, mask = 0;
    auto clip = [&](std::uint64_t bs, std::uint64_t be, unsigned j) {
        const std::uint64_t a = std::max(bs, k0), b = std::min(be, k1);
        if (a >= b) { return; }
        const auto la = static_cast<std::uint32_t>(a - k0), lb = static_cast<std::uint32_t>(b - k0);
        if (hi[j] == lo[j]) {
            lo[j] = la;
            hi[j] = lb;
        } else if (la == hi[j]) {
            hi[j] = lb;
        } else if (lb == lo[j]) {
            lo[j] = la;
        } else {
            h |= IMP_H_INTERLOCK;
        }
    };
    if (act_.valid) {
        for (size_t r = 0; r < 3; ++r) {
            clip(a0, a0 + act_.n1[r], act_.thr1[r]);
            clip(a0 + act_.n2[r], a0 + act_.ntot, act_.thr2[r]);
        }
    }
    for (unsigned j = 0; j < 6; ++j) {
        if (hi[j] > lo[j]) { mask |= 1u << j; }
    }
    for (unsigned r = 0; r < 3; ++r) {
        if (((mask >> (2 * r)) & 3u) == 3u) {
            mask &= ~(3u << (2 * r));
            h |= IMP_H_INTERLOCK;
        }
    }
    mask &= avail;
    for (unsigned j = 0; j < 6; ++j) {
        if ((mask >> j) & 1u) {
            out.on_start_cnt[j] = lo[j] * us_;
            out.on_len_cnt[j] = (hi[j] - lo[j]) * us_;
            on_tot_[j] += hi[j] - lo[j];
            log_add(j, k0 + lo[j], k0 + hi[j], k0);
        }
    }
    out.on_mask = static_cast<std::uint8_t>(mask);
    return h;
}

unsigned ImpFsw::health(const imp_in_t &in, imp_out_t &out)
{
    unsigned h = (mode_ << IMP_H_MODE_SH) & IMP_H_MODE;
    if (mode_ == IMP_MODE_INFEASIBLE) { h |= IMP_H_INFEASIBLE; }
    if (mode_ == IMP_MODE_NO_SOLUTION) { h |= IMP_H_NO_SOLUTION; }
    if (marginal_ && mode_ != IMP_MODE_IDLE) { h |= IMP_H_MARGINAL; }
    if (active(mode_) && !fresh(in.step)) { h |= IMP_H_NAV_STALE; }
    exp_dr_.fill(0);
    exp_dv_.fill(0);
    if ((mode_ == IMP_MODE_ARMED || mode_ == IMP_MODE_FIRING || mode_ == IMP_MODE_FINAL) && act_.valid) {
        // u_cal while a calibration epoch is still due before the second burns (fsw imp_tl.c)
        const bool ahead = p_.cal_enable != 0 && p_.replan_period != 0 && mode_ != IMP_MODE_FINAL &&
                           !final_at(next_tp_ + p_.plan_lead);
        for (size_t r = 0; r < 3; ++r) {
            if (act_.n2[r] >= act_.ntot) { continue; }
            const unsigned j = act_.thr2[r];
            const double d = tau_g(act_.ntot - act_.n2[r]);
            const double u = ((ahead || cal_done(j)) ? p_.u_cal_q30 : p_.u_uncal_q30) / kQ30;
            exp_dv_[r] = u * alpha_[j] * d;
            exp_dr_[r] = 0.5 * exp_dv_[r] * d;
            if (exp_dr_[r] > p_.miss_flag_q28 / kQ28) { h |= IMP_H_EXPECTED_MISS; }
        }
    }
    (void)out;
    return h | latched_;
}

void ImpFsw::step(const imp_in_t &in, imp_out_t &out)
{
    out.on_mask = 0;
    for (size_t j = 0; j < 6; ++j) {
        out.on_start_cnt[j] = 0;
        out.on_len_cnt[j] = 0;
    }
    const unsigned ev = nav_intake(in);
    unsigned h = command(in);
    fd_react(in, ev);
    progress(in);
    const unsigned avail = static_cast<unsigned>(in.avail_mask) & ~stuck_off_ & 0x3Fu;
    if (mode_ == IMP_MODE_FIRING || mode_ == IMP_MODE_FINAL) { h |= fire(in.step, avail, out); }
    h |= health(in, out);
    health_sticky_ |= h;
    out.health = h;
    imp_tlm_t &t = out.tlm;
    t = imp_tlm_t{};
    t.plans = plans_;
    t.plans_failed = failed_;
    t.plans_skipped = skipped_;
    t.cmd_rej = cmd_rej_;
    t.nav_rej = nav_rej_;
    t.cal_rej = cal_rej_;
    t.plans_kept = kept_;
    t.mode = static_cast<std::uint8_t>(mode_);
    t.rej_reason = static_cast<std::uint8_t>(rej_reason_);
    t.pattern = static_cast<std::uint8_t>(pattern_);
    t.stuck_j = static_cast<std::uint8_t>(stuck_j_);
    t.stuck_off_mask = static_cast<std::uint8_t>(stuck_off_);
    for (size_t j = 0; j < 6; ++j) {
        t.alpha_q30[j] = static_cast<std::int32_t>(std::lround(alpha_[j] * kQ30));
        t.cal_windows[j] = static_cast<std::uint16_t>(n_acc_[j]);
        t.dv_cmd_q28[j] = static_cast<std::int32_t>(std::lround(tau_g(on_tot_[j]) * kQ28));
        t.dv_used_q28[j] = static_cast<std::int32_t>(std::lround(tau_g(on_tot_[j]) * alpha_[j] * kQ28));
        t.miss_q28[j] = static_cast<std::int32_t>(std::lround(miss_(static_cast<int>(j)) * kQ28));
    }
    for (size_t r = 0; r < 3; ++r) {
        t.exp_dr_q28[r] = static_cast<std::int32_t>(std::lround(exp_dr_[r] * kQ28));
        t.exp_dv_q28[r] = static_cast<std::int32_t>(std::lround(exp_dv_[r] * kQ28));
        t.on1_step[r] = act_.ta + act_.n1[r] / G_;
        t.on2_step[r] = act_.ta + act_.n2[r] / G_;
    }
    t.nav_age = nav_.valid ? in.step - nav_.step : UINT32_MAX;
    t.health_sticky = health_sticky_;
    t.revision = p_.revision;
}

}  // namespace ref
