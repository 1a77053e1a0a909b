// Golden comparison of the fixed-point switching-time solver (fsw/impulse) against the Eigen
// double reference (sim/impulse/imp_ref_solver, imp_ref_checks), spec 50-impulse §6 (G1-G4) and §7 (A4-1..A4-3).
// Every expected value comes from the double reference or from the spec's text, never from the
// fixed-point code. Both sides get the same (dequantised) inputs: the reference solves the
// problem the fixed-point code sees, so only arithmetic differs.
//
// Tolerances (LSB reasoning):
//  G1 trig: fx_sincos is within 4 LSB of q30 at sigma/2 (platform contract). sin = 2 s_h c_h and
//    1 - cos = 2 s_h^2 double that error and add 0.5 LSB of rounding: |err| <= 2*(4 + 4) + 0.5 =
//    16.5 LSB q30 ~ 4 LSB q28, the spec's G1 bound. The BAM of sigma/2 is rounded to 2^-32 turn
//    (0.73e-9 rad, < 1 LSB q30 after the factor 2). Checked at 4 LSB of q28 = 16 LSB of q30.
//  G2 model: every Phi / Psi / Phi e_r entry is an integer combination (coefficients <= 6) of the
//    trig values, formed exactly in q30 and rounded once to q28: <= 6 * 16 LSB q30 / 4 + 0.5 =
//    24.5 LSB q28 in the worst algebraic case, but the large coefficients multiply tms (series or
//    sigma - sin, whose error is that of sin alone, 8.5 LSB q30) and omc: 6 * 8.5 / 4 + 0.5 = 13.
//    The spec sets 8 LSB (G2); we check the spec's 8 LSB and report the maximum.
//  Residual evaluation: F sums <= 7 products of a q28 entry (error e_m <= 8 LSB) and a factor of
//    magnitude <= 1.2 (alpha) or <= 0.64 (state), plus one final rounding: measured floor 3-7 LSB
//    (spec §4.6); we allow E_F = 16 LSB (2x the worst measured floor).
//  Times: the fixed-point schedule satisfies |F_fx(T_fx)| <= r_tol = 32 LSB, so the double
//    residual there is |F(T_fx)| <= fres + E_F and T_fx - T_ref = J^-1 F(T_fx) to first order:
//    |dT| <= ||J^-1||inf (fres + E_F) 2^-28 rad (+ 1 LSB q29 of the validity clamp). With the
//    example's ||J^-1||inf ~ 10, that is <= 10 * 48 * 3.7e-9 = 1.8e-6 rad = 1.6 ms in the worst
//    case; quadratic convergence normally lands far below r_tol (fres ~ 3 LSB), giving ~0.1 ms.
//    We check both the per-case derived bound and the spec's G4 0.25 ms (G3: 1 ms per iterate).
//  True miss: the double closed form evaluated at the fixed-point times; spec: <= 1 cm, 1e-4 m/s.
#include "impulse/imp_ref_checks.hpp"
#include "impulse/imp_ref_solver.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

extern "C" {
#include "imp.h"
#include "imp_tables.h"
#include "ut.h"
}

namespace {

constexpr double Q28 = 268435456.0;
constexpr double Q29 = 536870912.0;
constexpr double Q30 = 1073741824.0;
constexpr double E_F_LSB = 16.0;   // residual evaluation error allowance, q28 LSB (see above)

int32_t q(double v, double s) { return static_cast<int32_t>(std::lround(v * s)); }

struct Fixed {
    imp_problem_t pr{};
    ref::ImpCase c;   // the dequantised case seen by the fixed-point code
};

// Quantise an SI case for the fixed-point solver, and dequantise it back for the reference.
Fixed quantise(const ref::ImpCase &in)
{
    Fixed f;
    f.c = in;
    f.pr.tauf_q29 = q(in.w * in.T, Q29);
    f.c.T = f.pr.tauf_q29 / Q29 / in.w;
    for (int i = 0; i < 6; ++i) {
        const double u = (i % 2 == 0) ? in.L() : in.V();
        f.pr.x0_q28[i] = q(in.x0(i) / u, Q28);
        f.pr.xt_q28[i] = q(in.xt(i) / u, Q28);
        f.c.x0(i) = f.pr.x0_q28[i] / Q28 * u;
        f.c.xt(i) = f.pr.xt_q28[i] / Q28 * u;
        f.pr.alpha_q30[i] = q(in.alpha[static_cast<size_t>(i)], Q30);
        f.c.alpha[static_cast<size_t>(i)] = f.pr.alpha_q30[i] / Q30;
    }
    return f;
}

ref::ImpCase example()
{
    ref::ImpCase c;
    c.x0 << 5000, -1, 4000, -1, 4000, -1;
    return c;
}

// ||J^-1||inf of the reference Jacobian at the reference solution, per subsystem (max).
double jinv_norm(const ref::ImpCase &c, const ref::ImpPlan &pl)
{
    const ref::ImpNd p = ref::nondim(c);
    const std::array<double, 2> a1{{pl.t1[0], pl.t1[1]}}, a2{{pl.t2[0], pl.t2[1]}};
    const std::array<double, 2> b1{{pl.t1[2], 0}}, b2{{pl.t2[2], 0}};
    const double nxy = ref::jacobian(p, 0, pl.pattern & 0xFu, a1, a2).inverse().cwiseAbs().rowwise().sum().maxCoeff();
    const double nz = ref::jacobian(p, 1, (pl.pattern >> 4) & 3u, b1, b2).inverse().cwiseAbs().rowwise().sum().maxCoeff();
    return std::max(nxy, nz);
}

struct Stats {
    int n = 0, valid_ref = 0, rule_ref = 0, agree = 0, solved = 0;
    double dt_max_ms = 0, miss_r_max = 0, miss_v_max = 0;
    int it_max_fx = 0, it_max_ref = 0, it_diff_max = 0;
};

// Compare one case; returns false (and records failures) on disagreement.
void compare_case(const ref::ImpCase &in, Stats &s, bool strict_times, int max_it, const char *tag, int idx)
{
    static imp_ws_t ws;
    static imp_solution_t sol;
    Fixed f = quantise(in);
    const ref::ImpPlan pl = ref::solve(f.c);
    imp_solve(&ws, &IMP_TBL_DEFAULT, &f.pr, &sol);
    ++s.n;
    UT_CHECK_EQ(sol.st_ok, 0u);   // no fx status outside failed attempts (A4-3, A4-6)
    UT_CHECK_EQ(sol.outcome, pl.outcome);
    if (pl.outcome == IMP_SOL_VALID) {
        ++s.valid_ref;
        s.rule_ref += (pl.how[0] == IMP_HOW_RULE && pl.how[1] == IMP_HOW_RULE) ? 1 : 0;
    }
    if (sol.outcome != IMP_SOL_VALID || pl.outcome != IMP_SOL_VALID) {
        if (sol.outcome != pl.outcome) {
            std::printf("  %s[%d]: outcome fixed %u ref %u\n", tag, idx, sol.outcome, pl.outcome);
        }
        return;
    }
    ++s.solved;
    // Polarities: identical unless the two candidate patterns are a dv tie (spec 50 §3.5).
    if (sol.pattern != pl.pattern) {
        std::printf("  %s[%d]: pattern fixed 0x%02x ref 0x%02x (dv fixed %.6f ref %.6f)\n", tag, idx, sol.pattern,
                    pl.pattern, (sol.dv_q28[0] + sol.dv_q28[1]) / Q28, pl.dv[0] + pl.dv[1]);
        UT_CHECK(std::abs((sol.dv_q28[0] + sol.dv_q28[1]) / Q28 - (pl.dv[0] + pl.dv[1])) <= 2 * 2.828418e-5);
        return;
    }
    ++s.agree;
    const double jn = jinv_norm(f.c, pl);
    for (int sub = 0; sub < 2; ++sub) {
        const int ifx = sol.iters[sub], irf = pl.iters[static_cast<size_t>(sub)];
        UT_CHECK_LE(std::abs(ifx - irf), 1);
        UT_CHECK_LE(ifx, max_it);
        s.it_max_fx = std::max(s.it_max_fx, ifx);
        s.it_max_ref = std::max(s.it_max_ref, irf);
        s.it_diff_max = std::max(s.it_diff_max, std::abs(ifx - irf));
    }
    std::array<double, 3> t1{}, t2{};
    for (int r = 0; r < 3; ++r) {
        t1[static_cast<size_t>(r)] = sol.t1_q29[r] / Q29;
        t2[static_cast<size_t>(r)] = sol.t2_q29[r] / Q29;
        const int sub = r < 2 ? 0 : 1;
        const double bound_rad = jn * (sol.fres_lsb[sub] + E_F_LSB) / Q28 + 1.0 / Q29;
        for (double d : {t1[static_cast<size_t>(r)] - pl.t1[static_cast<size_t>(r)],
                         t2[static_cast<size_t>(r)] - pl.t2[static_cast<size_t>(r)]}) {
            UT_CHECK(std::abs(d) <= bound_rad);
            if (strict_times) {
                UT_CHECK(std::abs(d) / f.c.w <= 0.25e-3);
            }
            s.dt_max_ms = std::max(s.dt_max_ms, std::abs(d) / f.c.w * 1e3);
        }
    }
    const ref::Vec6 e = ref::terminal_error(f.c, t1, t2, sol.pattern);
    const double mr = std::sqrt(e(0) * e(0) + e(2) * e(2) + e(4) * e(4));
    const double mv = std::sqrt(e(1) * e(1) + e(3) * e(3) + e(5) * e(5));
    UT_CHECK(mr <= 0.01);
    UT_CHECK(mv <= 1e-4);
    s.miss_r_max = std::max(s.miss_r_max, mr);
    s.miss_v_max = std::max(s.miss_v_max, mv);
}

void print_stats(const char *tag, const Stats &s)
{
    std::printf("%s: %d cases, ref valid %d (rule alone %d), fixed solved %d, same pattern %d; "
                "max |dT| %.4f ms; iterations fx max %d, ref max %d, max |diff| %d; true miss max %.3g m, %.3g m/s\n",
                tag, s.n, s.valid_ref, s.rule_ref, s.solved, s.agree, s.dt_max_ms, s.it_max_fx, s.it_max_ref,
                s.it_diff_max, s.miss_r_max, s.miss_v_max);
}

}  // namespace

// A4-1 / G1 / G2: reference model checks and fixed-point kernels against double.
UT_TEST(golden_model_kernels)
{
    double e_trig = 0, e_mod = 0, e_phi_expm = 0, e_psi_q = 0, e_jfd = 0;
    for (int i = 0; i <= 4096; ++i) {
        const double sig_req = 2.2 * i / 4096.0;
        const int32_t sq = q(sig_req, Q29);
        const double sig = sq / Q29;
        imp_trig_t t;
        fx_status_t st = 0u;
        imp_trig(sq, &t, &st);
        UT_CHECK_EQ(st, 0u);
        const double ds = std::abs(t.s_q30 - std::sin(sig) * Q30), dc = std::abs(t.c_q30 - std::cos(sig) * Q30);
        const double domc = std::abs(t.omc_q30 - (1 - std::cos(sig)) * Q30);
        const double dtms = std::abs(t.tms_q30 - (sig - std::sin(sig)) * Q30);
        const double m = std::max({ds, dc, domc, dtms}) / 4.0;   // in q28 LSB
        UT_CHECK(m <= 4.0);
        e_trig = std::max(e_trig, m);
        // odd / even symmetry, exact
        imp_trig_t tn;
        imp_trig(-sq, &tn, &st);
        UT_CHECK_EQ(tn.s_q30, -t.s_q30);
        UT_CHECK_EQ(tn.c_q30, t.c_q30);
        UT_CHECK_EQ(tn.tms_q30, -t.tms_q30);
        if (sig <= 2.0 && (i % 8) == 0) {   // G2: 512 angles up to tau_f max
            for (int r = 0; r < 3; ++r) {
                int32_t v[4];
                imp_psi(static_cast<uint32_t>(r), sq, &t, v, &st);
                const Eigen::VectorXd pr = ref::psi(r, sig);
                for (int k = 0; k < pr.size(); ++k) { e_mod = std::max(e_mod, std::abs(v[k] - pr(k) * Q28)); }
                imp_phie(static_cast<uint32_t>(r), sq, &t, v, &st);
                const Eigen::VectorXd pe = ref::phi_e(r, sig);
                for (int k = 0; k < pe.size(); ++k) { e_mod = std::max(e_mod, std::abs(v[k] - pe(k) * Q28)); }
            }
            const ref::Mat6 ph = ref::phi(sig);
            // Phi entries: Phi(sigma) e_j for unit vectors (1.0 in q28), read back exactly in q56.
            for (int jj = 0; jj < 6; ++jj) {
                int32_t e[6] = {0, 0, 0, 0, 0, 0};
                int64_t col[6];
                e[jj] = 268435456;
                imp_phi_apply(sq, &t, e, col, &st);
                for (int k = 0; k < 6; ++k) {
                    e_mod = std::max(e_mod, std::abs(std::ldexp(static_cast<double>(col[k]), -28) - ph(k, jj) * Q28));
                }
            }
            // Phi(sigma) X for a state in the +-20 km / +-5 m/s box (|X| <= 0.64), G2.
            int32_t x[6];
            ref::Vec6 xd;
            for (int k = 0; k < 6; ++k) {
                x[k] = q(0.64 * std::sin(1.7 * i + 2.3 * k), Q28);
                xd(k) = x[k] / Q28;
            }
            int64_t y[6];
            imp_phi_apply(sq, &t, x, y, &st);
            const ref::Vec6 yd = ph * xd;
            for (int k = 0; k < 6; ++k) { e_mod = std::max(e_mod, std::abs(std::ldexp(static_cast<double>(y[k]), -28) - yd(k) * Q28)); }
            UT_CHECK_EQ(st, 0u);
        }
    }
    UT_CHECK(e_mod <= 8.0);
    // A4-1 reference checks: Phi vs expm, Psi vs quadrature, J vs finite differences.
    const ref::ImpCase ex = example();
    for (int i = 1; i <= 20; ++i) {
        const double tau = ex.w * ex.T * i / 20.0;
        const ref::Mat6 a = ref::phi(tau), b = ref::phi_expm(tau);
        e_phi_expm = std::max(e_phi_expm, (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff());
        for (int r = 0; r < 3; ++r) {
            const Eigen::VectorXd p1 = ref::psi(r, tau), p2 = ref::psi_quad(r, tau);
            e_psi_q = std::max(e_psi_q, (p1 - p2).cwiseAbs().maxCoeff() / p2.cwiseAbs().maxCoeff());
        }
    }
    const ref::ImpNd nd = ref::nondim(ex);
    const std::array<double, 2> t1{{0.03, 0.3}}, t2{{0.74, 0.89}};
    for (unsigned pat : {0x0u, 0xCu, 0x5u}) {
        const Eigen::MatrixXd ja = ref::jacobian(nd, 0, pat, t1, t2), jf = ref::jacobian_fd(nd, 0, pat, t1, t2);
        e_jfd = std::max(e_jfd, (ja - jf).cwiseAbs().maxCoeff() / ja.cwiseAbs().maxCoeff());
    }
    UT_CHECK(e_phi_expm <= 1e-9);
    UT_CHECK(e_psi_q <= 1e-8);
    UT_CHECK(e_jfd <= 1e-6);
    std::printf("G1 trig max %.2f LSB q28 (<= 4); G2 model max %.2f LSB q28 (<= 8); A4-1 Phi vs expm %.2e, "
                "Psi vs quad %.2e, J vs FD %.2e\n", e_trig, e_mod, e_phi_expm, e_psi_q, e_jfd);
}

// A4-2 / G3: the paper's example, reference and fixed point, iterate by iterate.
UT_TEST(golden_paper_example)
{
    static imp_ws_t ws;
    static imp_solution_t sol;
    const Fixed f = quantise(example());
    const ref::ImpCase &c = f.c;
    const ref::ImpNd nd = ref::nondim(c);
    const ref::ImpPlan pl = ref::solve(c);
    const double w = c.w;
    // Reference against the spec's numbers (§3.4, A4-2).
    UT_EQ(pl.outcome, IMP_SOL_VALID);
    UT_EQ(pl.pattern, 0x1Cu);   // x (+,+), y (-,-), z (-,+)
    const double exp_t1[3] = {35.590, 342.688, 29.703}, exp_t2[3] = {839.316, 1004.219, 928.778};
    for (int r = 0; r < 3; ++r) {
        UT_CHECK(std::abs(pl.t1[static_cast<size_t>(r)] / w - exp_t1[r]) <= 0.01);
        UT_CHECK(std::abs(pl.t2[static_cast<size_t>(r)] / w - exp_t2[r]) <= 0.01);
    }
    const double V = c.V();
    UT_CHECK(std::abs((pl.dv[0] + pl.dv[1]) * V - 32.027) <= 0.01);
    UT_CHECK(std::abs((pl.dv1[0] + pl.dv2[0]) * V - 10.0509) <= 1e-4);
    UT_CHECK(std::abs((pl.t2[0] - pl.t1[0]) / w - 803.727) <= 0.01);
    // Iterates: |dR| <= 0.01 m after 4, <= 1e-6 m after 5; iterate 1 = impulsive solution.
    const ref::ImpAttempt axy = ref::attempt(nd, ref::ImpGuards(), 0, 0xCu, {{0, 0}}, {{nd.tauf, nd.tauf}});
    const ref::ImpAttempt az = ref::attempt(nd, ref::ImpGuards(), 1, 0x1u, {{0, 0}}, {{nd.tauf, nd.tauf}});
    UT_TRUE(axy.hist.size() >= 6u);
    const double it1[6] = {92.137, 895.864, 236.070, 960.444, 19.822, 933.308};
    UT_CHECK(std::abs(axy.hist[1].t1[0] / w - it1[0]) <= 0.01);
    UT_CHECK(std::abs(axy.hist[1].t2[0] / w - it1[1]) <= 0.01);
    UT_CHECK(std::abs(axy.hist[1].t1[1] / w - it1[2]) <= 0.01);
    UT_CHECK(std::abs(axy.hist[1].t2[1] / w - it1[3]) <= 0.01);
    UT_CHECK(std::abs(az.hist[1].t1[0] / w - it1[4]) <= 0.01);
    UT_CHECK(std::abs(az.hist[1].t2[0] / w - it1[5]) <= 0.01);
    // Pure Newton, no stopping rule (r_tol = 0), 5 iterations on both subsystems.
    ref::ImpGuards g0;
    g0.r_tol = 0;
    g0.max_iter = 5;
    const ref::ImpAttempt pxy = ref::attempt(nd, g0, 0, 0xCu, {{0, 0}}, {{nd.tauf, nd.tauf}});
    const ref::ImpAttempt pz = ref::attempt(nd, g0, 1, 0x1u, {{0, 0}}, {{nd.tauf, nd.tauf}});
    UT_TRUE(pxy.hist.size() == 6u && pz.hist.size() == 6u);
    double miss45[2] = {0, 0};
    for (size_t k = 4; k <= 5; ++k) {
        const ref::Vec6 e = ref::terminal_error(c, {{pxy.hist[k].t1[0], pxy.hist[k].t1[1], pz.hist[k].t1[0]}},
                                                {{pxy.hist[k].t2[0], pxy.hist[k].t2[1], pz.hist[k].t2[0]}}, 0x1Cu);
        miss45[k - 4] = std::sqrt(e(0) * e(0) + e(2) * e(2) + e(4) * e(4));
    }
    UT_CHECK(miss45[0] <= 0.01);
    UT_CHECK(miss45[1] <= 1e-6);
    // RK4 integration of the reference schedule against the closed form (piecewise Phi/Psi):
    // the same schedule, two independent propagations (spec 50 §2.2: agree to ~1e-10 m).
    const ref::Vec6 erk = ref::terminal_error_rk(c, pl.t1, pl.t2, pl.pattern) -
                          ref::terminal_error(c, pl.t1, pl.t2, pl.pattern);
    UT_CHECK(erk.cwiseAbs().maxCoeff() <= 1e-6);
    std::printf("reference: |dR| after 4 / 5 pure Newton iterations %.3g / %.3g m; RK4 vs closed form %.3g\n",
                miss45[0], miss45[1], erk.cwiseAbs().maxCoeff());
    // Fixed point, iterate by iterate (G3): max_iter = k stops with iterate k in the workspace.
    double g3_max_ms = 0;
    for (uint32_t k = 0; k <= 5; ++k) {
        imp_params_t p = IMP_TBL_DEFAULT;
        p.max_iter = static_cast<uint8_t>(k == 0 ? 1 : k);
        uint32_t iters = 0, fres = 0;
        fx_status_t st = 0;
        const int32_t z1[2] = {0, 0}, z2[2] = {f.pr.tauf_q29, f.pr.tauf_q29};
        if (k == 0) {
            // iterate 0 is the start itself
            continue;
        }
        (void)imp_attempt(&ws, &p, &f.pr, IMP_SUB_XY, 0xCu, z1, z2, &iters, &fres, &st);
        UT_CHECK_EQ(st, 0u);
        const ref::ImpIter &h = axy.hist[std::min<size_t>(k, axy.hist.size() - 1)];
        for (int a = 0; a < 2; ++a) {
            const double d1 = std::abs(ws.t1_q29[a] / Q29 - h.t1[static_cast<size_t>(a)]) / w * 1e3;
            const double d2 = std::abs(ws.t2_q29[a] / Q29 - h.t2[static_cast<size_t>(a)]) / w * 1e3;
            UT_CHECK(d1 <= 1.0);
            UT_CHECK(d2 <= 1.0);
            g3_max_ms = std::max({g3_max_ms, d1, d2});
        }
        if (k == 5) {
            // The fixed-point residual at its own final iterate against the double residual there.
            const std::array<double, 2> u1{{ws.t1_q29[0] / Q29, ws.t1_q29[1] / Q29}};
            const std::array<double, 2> u2{{ws.t2_q29[0] / Q29, ws.t2_q29[1] / Q29}};
            const Eigen::VectorXd fd = ref::residual(nd, 0, 0xCu, u1, u2);
            for (int i = 0; i < 4; ++i) { UT_CHECK(std::abs(ws.f_q28[i] - fd(i) * Q28) <= E_F_LSB); }
        }
    }
    // Fixed point, full plan.
    imp_solve(&ws, &IMP_TBL_DEFAULT, &f.pr, &sol);
    UT_EQ(sol.outcome, IMP_SOL_VALID);
    UT_EQ(sol.pattern, 0x1Cu);
    UT_CHECK_EQ(sol.how[0], IMP_HOW_RULE);
    UT_CHECK_EQ(sol.how[1], IMP_HOW_RULE);
    UT_CHECK_LE(sol.iters[0], 5);
    UT_CHECK_LE(sol.iters[1], 5);
    UT_CHECK_EQ(sol.st_ok, 0u);
    std::array<double, 3> t1{}, t2{};
    double dmax = 0;
    for (int r = 0; r < 3; ++r) {
        t1[static_cast<size_t>(r)] = sol.t1_q29[r] / Q29;
        t2[static_cast<size_t>(r)] = sol.t2_q29[r] / Q29;
        dmax = std::max({dmax, std::abs(t1[static_cast<size_t>(r)] - pl.t1[static_cast<size_t>(r)]) / w,
                         std::abs(t2[static_cast<size_t>(r)] - pl.t2[static_cast<size_t>(r)]) / w});
    }
    UT_CHECK(dmax <= 0.25e-3);   // G3 final (and A4-2's 1 ms)
    const ref::Vec6 e = ref::terminal_error(c, t1, t2, sol.pattern);
    const double mr = std::sqrt(e(0) * e(0) + e(2) * e(2) + e(4) * e(4));
    const double mv = std::sqrt(e(1) * e(1) + e(3) * e(3) + e(5) * e(5));
    UT_CHECK(mr <= 0.01);
    UT_CHECK(mv <= 1e-4);
    std::printf("paper example: ref iters xy %d z %d; fixed iters xy %u z %u, final |F| %d / %d LSB; "
                "G3 max iterate diff %.4f ms; final max |dT| %.4f ms; true miss %.3g m, %.3g m/s; dv %.4f m/s\n",
                pl.iters[0], pl.iters[1], sol.iters[0], sol.iters[1], sol.fres_lsb[0], sol.fres_lsb[1], g3_max_ms,
                dmax * 1e3, mr, mv, (sol.dv_q28[0] + sol.dv_q28[1]) / Q28 * V);
    for (int r = 0; r < 3; ++r) {
        std::printf("  axis %d: fixed T1 %.4f s T2 %.4f s | ref T1 %.4f s T2 %.4f s\n", r, t1[static_cast<size_t>(r)] / w,
                    t2[static_cast<size_t>(r)] / w, pl.t1[static_cast<size_t>(r)] / w, pl.t2[static_cast<size_t>(r)] / w);
    }
}

// A4-3 / G4: seeded Monte Carlo, nominal box (500) and wide box (200), plus other w and tau_f.
UT_TEST(golden_monte_carlo)
{
    std::mt19937_64 rng(20131010u);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    auto draw = [&](double rp, double rv) {
        ref::ImpCase c;
        for (int i = 0; i < 6; ++i) { c.x0(i) = u(rng) * ((i % 2 == 0) ? rp : rv); }
        return c;
    };
    Stats nom;
    for (int i = 0; i < 500; ++i) { compare_case(draw(5000, 1), nom, true, 6, "nominal", i); }
    print_stats("G4 nominal +-5 km / +-1 m/s", nom);
    UT_CHECK_EQ(nom.valid_ref, nom.n);                          // rule plus search solves 100 %
    UT_CHECK(nom.rule_ref >= 78 * nom.n / 100 && nom.rule_ref <= 85 * nom.n / 100);
    UT_CHECK_LE(nom.it_max_fx, 6);
    Stats wide;
    int low_rho_unsolved = 0;
    for (int i = 0; i < 200; ++i) {
        const ref::ImpCase c = draw(20000, 5);
        compare_case(c, wide, true, IMP_ITER_CAP, "wide", i);
        const ref::ImpPlan pl = ref::solve(quantise(c).c);
        const double rmax = std::max({pl.rho[0], pl.rho[1], pl.rho[2]});
        if (rmax < 0.38 && pl.outcome != IMP_SOL_VALID) { ++low_rho_unsolved; }
    }
    print_stats("G4 wide +-20 km / +-5 m/s", wide);
    UT_CHECK(wide.valid_ref >= 5 * wide.n / 100 && wide.valid_ref <= 15 * wide.n / 100);
    UT_CHECK_EQ(low_rho_unsolved, 0);
    // Other orbit rates and horizons (spec 50 §4.6): w x tau_f grid, +-5 km / +-1 m/s.
    Stats grid;
    for (double w : {8.3e-4, 1.131367e-3, 1.2e-3}) {
        for (double tau : {1.2, 2.0}) {
            for (int i = 0; i < 40; ++i) {
                ref::ImpCase c = draw(5000, 1);
                c.w = w;
                c.T = tau / w;
                compare_case(c, grid, true, 7, "grid", i);
            }
        }
    }
    print_stats("G4 grid w in {8.3e-4, 1.131e-3, 1.2e-3} x tau_f in {1.2, 2.0}", grid);
}

// G5: best rounding onto 1 s and 0.1 s ticks. The fixed-point choice must be optimal within 1 %
// when scored in double (candidates can differ only when a switching time lies within the
// solvers' 0.25 ms of a grid point), and its predicted miss must match the double terminal error
// of the same steps: the prediction sums exactly precomputed q58 terms and rounds once, so it
// carries the residual-evaluation error E_F (measured floor 3-7 LSB of q28 = 0.35-0.8 mm);
// spec G5 bounds it by 1 mm (positions) and we bound velocities by 16 LSB (2.1 um/s at 400 km).
UT_TEST(golden_rounding)
{
    static imp_ws_t ws;
    static imp_solution_t sol;
    static imp_round_t rd;
    std::mt19937_64 rng(55u);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    // grids: 1 s and 0.1 s ticks (whole steps), 1 ms sub-ticks of a 0.1 s tick (spec 50 G5)
    for (double h : {1.0, 0.1, 0.001}) {
        const imp_params_t p = h > 0.5 ? IMP_TBL_1S : (h > 0.05 ? IMP_TBL_DEFAULT : IMP_TBL_SUB1MS);
        const double w = 1.131367e-3;
        uint32_t why = 0;
        UT_EQ(imp_params_check(&p, &why), FSW_OK);
        double miss_pred_max = 0, miss_predv_max = 0, worst_ratio = 1;
        int n_same = 0, n = 0;
        for (int i = 0; i < 101; ++i) {
            ref::ImpCase in = example();
            if (i > 0) {
                for (int k = 0; k < 6; ++k) { in.x0(k) = u(rng) * ((k % 2 == 0) ? 5000 : 1); }
            }
            const uint32_t n_total = static_cast<uint32_t>(std::lround(in.T / h));
            Fixed f = quantise(in);
            fx_status_t st = 0;
            f.pr.tauf_q29 = fx_rshift_sat(static_cast<int64_t>(n_total) * p.k_gtau_m, p.k_gtau_sh, &st);
            f.c.T = n_total * h;
            imp_solve(&ws, &p, &f.pr, &sol);
            UT_TRUE(sol.outcome == IMP_SOL_VALID);
            imp_round_best(&ws, &p, &f.pr, &sol, n_total, &rd, &st);
            UT_CHECK_EQ(st, 0u);
            UT_CHECK(rd.cost_q56 <= rd.cost_nearest_q56);
            const ref::ImpPlan pl = ref::solve(f.c);
            const ref::ImpRound rr = ref::round_best(f.c, pl, h);
            // double score of the fixed-point steps
            std::array<double, 3> t1{}, t2{};
            for (int r = 0; r < 3; ++r) {
                t1[static_cast<size_t>(r)] = rd.n1[r] * w * h;
                t2[static_cast<size_t>(r)] = rd.n2[r] * w * h;
            }
            const ref::Vec6 e = ref::terminal_error(f.c, t1, t2, sol.pattern);
            double cfx[2] = {0, 0};
            for (int k = 0; k < 6; ++k) {
                const double v = (k % 2 == 0) ? e(k) / f.c.L() : w * 100.0 * e(k) / f.c.V();
                cfx[k < 4 ? 0 : 1] += v * v;
                const double d = std::abs(rd.miss_q28[k] / Q28 * ((k % 2 == 0) ? f.c.L() : f.c.V()) - e(k));
                if (k % 2 == 0) { miss_pred_max = std::max(miss_pred_max, d); }
                else { miss_predv_max = std::max(miss_predv_max, d); }
            }
            for (int sub = 0; sub < 2; ++sub) {
                const double best = rr.cost[static_cast<size_t>(sub)][rr.choice[static_cast<size_t>(sub)]];
                const double ratio = cfx[sub] / std::max(best, 1e-300);
                // The solvers' times agree to 0.25 ms (G4); a switch moved by that much moves the
                // terminal position by <= 40 m/s * 0.25 ms = 1 cm (spec 50 §4.2), which matters only
                // when a grid unit is not much larger than 0.25 ms (the 1 ms grid): there the fixed
                // choice may exceed the double best by that much miss.
                const double dm = (h < 0.05 ? 0.01 : 0.0) / f.c.L();
                UT_CHECK(std::sqrt(cfx[sub]) <= std::sqrt(1.01 * best) + dm + 1e-12);
                worst_ratio = std::max(worst_ratio, ratio);
            }
            bool same = true;
            for (int r = 0; r < 3; ++r) {
                same = same && (rd.n1[r] == rr.n1[static_cast<size_t>(r)]) && (rd.n2[r] == rr.n2[static_cast<size_t>(r)]);
            }
            n_same += same ? 1 : 0;
            ++n;
            if (i == 0) {
                auto pos = [](const ref::Vec6 &v) { return std::sqrt(v(0) * v(0) + v(2) * v(2) + v(4) * v(4)); };
                auto vel = [](const ref::Vec6 &v) { return std::sqrt(v(1) * v(1) + v(3) * v(3) + v(5) * v(5)); };
                // spec 50 §5.3 evidence (example, single plan): nearest -> best 28.4 -> 13.5 m at
                // 1 s, 0.80 -> 0.60 m at 0.1 s (printed to 0.1 m / 0.01 m).
                // The 1 ms grid has no spec figure: the rounding miss must only shrink with the grid.
                if (h > 0.05) {
                    const double en = h > 0.5 ? 28.4 : 0.80, eb = h > 0.5 ? 13.5 : 0.60, tol = h > 0.5 ? 0.1 : 0.01;
                    UT_CHECK(std::abs(pos(rr.miss_nearest) - en) <= tol);
                    UT_CHECK(std::abs(pos(rr.miss) - eb) <= tol);
                } else {
                    UT_CHECK(pos(rr.miss) <= 0.06);   // 0.1 s grid gives 0.60 m: a 100x finer grid, <= 1/10 of it
                }
                UT_CHECK(std::abs(pos(e) - pos(rr.miss)) <= 1e-3);
                std::printf("G5 example, grid %.3f s: ref nearest |dR| %.3f m |dV| %.4f m/s -> best %.3f m %.4f m/s; "
                            "fixed best %.3f m %.4f m/s\n", h, pos(rr.miss_nearest), vel(rr.miss_nearest), pos(rr.miss),
                            vel(rr.miss), pos(e), vel(e));
            }
        }
        UT_CHECK(miss_pred_max <= 1e-3);
        UT_CHECK(miss_predv_max <= 16.0 / Q28 * 35.3555);
        std::printf("G5 grid %.3f s: %d cases, same steps as double %d, worst cost ratio fixed/double-best %.6f, "
                    "predicted-miss error max %.3g m, %.3g m/s\n", h, n, n_same, worst_ratio, miss_pred_max, miss_predv_max);
    }
}

int main(void)
{
    UT_CASES(cases) = {UT_CASE(golden_model_kernels), UT_CASE(golden_paper_example), UT_CASE(golden_monte_carlo),
                       UT_CASE(golden_rounding)};
    return UT_RUN("imp_golden", cases);
}
