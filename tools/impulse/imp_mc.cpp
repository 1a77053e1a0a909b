// imp_mc — Monte Carlo campaign over initial conditions of the impulse scheduler's switching-time
// solver (spec 50-impulse §3.5-3.7, §4.6, §7 A4-3). One process runs the sample indices [i0, i1)
// of a seeded campaign and writes one CSV row per sample; tools/impulse/mc.py splits a campaign
// into chunks, runs them in parallel, merges them and checks A4-3.
//
//   imp_mc --box nominal|wide --seed S --i0 A --i1 B [--omega W] [--tauf TAU] [--out FILE]
//          [--no-header]          (command line: CLI11; --help lists the options; exit 2 bad usage)
//
// Sample (seed, box, i): sim::Rng(seed, (box_id << 32) | i) (sim/sensors/rng.hpp: xoshiro256**
// behind splitmix64, the project's one generator), six uniform() draws u_k in state order
// (x, x', y, y', z, z'), X0_k = (2 u_k - 1) * half-width (nominal 5 km / 1 m/s, box_id 1; wide
// 20 km / 5 m/s, box_id 2); target zero; alpha, w and a_nom from the flight table IMP_TBL_DEFAULT
// (w can be overridden, tau_f defaults to w * 1055 s). The state is quantised to the flight
// formats (q28 state, q29 tau_f) and both solvers get the same dequantised problem, as in
// tests/impulse/test_imp_golden_host.cpp, so only the arithmetic differs:
//   * reference: ref::solve (sim/impulse/imp_ref_solver, Eigen double), guards taken from the table;
//   * flight:    imp_solve (fsw/impulse, fixed point) with the table itself.
// Per sample it also re-runs the polarity rule alone from (0, tau_f) on both sides, even when
// the feasibility gate stops the plan (the rule's own failure cause, spec §3.7), and evaluates the
// fixed-point schedule in double with the closed form (the true miss).
#include "fsw_cli.hpp"
#include "impulse/imp_ref_checks.hpp"
#include "impulse/imp_ref_solver.hpp"
#include "sensors/rng.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>

extern "C" {
#include "imp.h"
#include "imp_tables.h"
}

namespace {

constexpr double Q26 = 67108864.0;
constexpr double Q28 = 268435456.0;
constexpr double Q29 = 536870912.0;
constexpr double Q30 = 1073741824.0;

struct Box {
    const char *name;
    std::uint64_t id;
    double rp;   // position half-width [m]
    double rv;   // velocity half-width [m/s]
};
constexpr std::array<Box, 2> BOXES{{{"nominal", 1u, 5000.0, 1.0}, {"wide", 2u, 20000.0, 5.0}}};

struct Options {
    const Box *box = nullptr;
    std::uint64_t seed = 1u;
    std::uint64_t i0 = 0u, i1 = 0u;
    double omega = 0;   // 0: the table's
    double tauf = 0;    // 0: omega * 1055 s
    std::string out;
    bool header = true;
};

// 0 (the default named in the help), or a value in [lo, hi]; after fsw_cli::Real(), so the text
// is a finite number.
CLI::Validator zero_or_range(double lo, double hi, const char *unit)
{
    char desc[96];
    (void)std::snprintf(desc, sizeof desc, "0 or in [%g, %g] %s", lo, hi, unit);
    return CLI::Validator(
        [lo, hi, unit](std::string &s) -> std::string {
            const double v = std::strtod(s.c_str(), nullptr);
            if (std::fpclassify(v) == FP_ZERO || (v >= lo && v <= hi)) {
                return std::string{};
            }
            char msg[128];
            (void)std::snprintf(msg, sizeof msg, "%.17g outside [%g, %g] %s (0: the default)", v, lo, hi, unit);
            return std::string(msg);
        },
        desc);
}

// Returns the options, or sets *exit_status (>= 0) when the tool must stop (--help, bad usage).
Options parse(int argc, char **argv, int *exit_status)
{
    Options o;
    std::string box;
    *exit_status = -1;
    CLI::App app{"imp_mc: Monte Carlo samples [i0, i1) of a seeded campaign of the impulse switching-time solver, "
                 "fixed point and double reference, one CSV row per sample (tools/impulse/mc.py drives it).",
                 "imp_mc"};
    fsw_cli::last_value_wins(app);
    app.add_option("--box", box, "sampling box: nominal (+-5 km, +-1 m/s) or wide (+-20 km, +-5 m/s)")
        ->required()
        ->check(CLI::IsMember(std::vector<std::string>{BOXES[0].name, BOXES[1].name}));
    app.add_option("--seed", o.seed, "campaign seed")->transform(fsw_cli::UInt())->capture_default_str();
    // At least one of --i0 / --i1 (the other defaults to 0), checked below.
    CLI::Option *oi0 = app.add_option("--i0", o.i0, "first sample index (default 0)")
                           ->transform(fsw_cli::UInt())
                           ->check(CLI::Range(std::uint64_t{0}, std::uint64_t{0xFFFFFFFFu}).description("< 2^32"));
    CLI::Option *oi1 = app.add_option("--i1", o.i1, "end of the index range, exclusive (default 0)")
                           ->transform(fsw_cli::UInt())
                           ->check(CLI::Range(std::uint64_t{0}, std::uint64_t{0xFFFFFFFFu}).description("< 2^32"));
    // spec 50 §2.3: accepted w and tau_f ranges
    app.add_option("--omega", o.omega, "orbit rate w [rad/s] (0: the table's)")
        ->transform(fsw_cli::Real())
        ->check(zero_or_range(8.0e-4, 1.2e-3, "rad/s"));
    app.add_option("--tauf", o.tauf, "tau_f = w T [rad] (0: w * 1055 s)")
        ->transform(fsw_cli::Real())
        ->check(zero_or_range(0.2, 2.0, "rad"));
    app.add_option("--out", o.out, "CSV file (default: stdout)");
    bool no_header = false;
    app.add_flag("--no-header", no_header, "omit the CSV header line");
    *exit_status = fsw_cli::parse(app, argc, argv, 2);
    if (*exit_status >= 0) {
        return o;
    }
    const char *why = nullptr;
    if (oi0->count() == 0u && oi1->count() == 0u) {
        why = "need --i0 and/or --i1";
    } else if (o.i1 < o.i0) {
        why = "need i0 <= i1";
    }
    if (why != nullptr) {
        (void)app.exit(CLI::ValidationError("--i0, --i1", why));   // prints it as CLI11 prints its own
        *exit_status = 2;
        return o;
    }
    o.header = !no_header;
    for (const Box &x : BOXES) {
        if (box == x.name) { o.box = &x; }
    }
    return o;
}

int32_t q(double v, double s) { return static_cast<int32_t>(std::lround(v * s)); }

struct Problem {
    imp_problem_t pr;
    ref::ImpCase c;   // the dequantised case the fixed-point code sees
};

Problem make_problem(const imp_params_t &p, const Box &box, std::uint64_t seed, std::uint64_t idx, double w,
                     double tauf)
{
    Problem f{};
    sim::Rng rng(seed, (box.id << 32) | idx);
    f.c.w = w;
    f.c.a_nom = p.a_nom_umps2 * 1e-6;
    for (int k = 0; k < 6; ++k) {
        const double u = rng.uniform();
        f.c.x0(k) = (2.0 * u - 1.0) * ((k % 2 == 0) ? box.rp : box.rv);
    }
    f.c.xt = ref::Vec6::Zero();
    f.pr = imp_problem_t{};   // value-initialised: no warm start, not a re-plan, future fields zero
    f.pr.tauf_q29 = q(tauf, Q29);
    f.c.T = f.pr.tauf_q29 / Q29 / w;
    for (int i = 0; i < 6; ++i) {
        const auto si = static_cast<size_t>(i);
        const double unit = (i % 2 == 0) ? f.c.L() : f.c.V();
        f.pr.x0_q28[i] = q(f.c.x0(i) / unit, Q28);
        f.pr.xt_q28[i] = q(f.c.xt(i) / unit, Q28);
        f.c.x0(i) = f.pr.x0_q28[i] / Q28 * unit;
        f.c.xt(i) = f.pr.xt_q28[i] / Q28 * unit;
        f.pr.alpha_q30[i] = p.alpha_q30[i];
        f.c.alpha[si] = p.alpha_q30[i] / Q30;
    }
    return f;
}

const char *outcome_name(unsigned o)
{
    switch (o) {
    case IMP_SOL_VALID: return "VALID";
    case IMP_SOL_NO_SOLUTION: return "NO_SOLUTION";
    case IMP_SOL_INFEASIBLE: return "INFEASIBLE";
    default: return "?";
    }
}

const char *how_name(unsigned h)
{
    switch (h) {
    case IMP_HOW_NONE: return "none";
    case IMP_HOW_WARM: return "warm";
    case IMP_HOW_RULE: return "rule";
    case IMP_HOW_SEARCH: return "search";
    default: return "?";
    }
}

const char *cause_name(unsigned c)
{
    static const char *const names[IMP_FAIL_N] = {"NONE", "ITER", "DIVERGE", "SINGULAR", "COND", "FX", "ORDER"};
    return c < IMP_FAIL_N ? names[c] : "?";
}

// Rule pattern of a subsystem (bit = 1: negative thruster) from the impulsive dv signs.
unsigned rule_local(const int32_t *dv1, const int32_t *dv2, int sub)
{
    unsigned pat = 0u;
    const int nax = sub == 0 ? 2 : 1, ax0 = sub == 0 ? 0 : 2;
    for (int k = 0; k < nax; ++k) {
        pat |= (dv1[ax0 + k] < 0 ? 1u : 0u) << (2 * k);
        pat |= (dv2[ax0 + k] < 0 ? 1u : 0u) << (2 * k + 1);
    }
    return pat;
}

unsigned rule_local_ref(const ref::ImpPlan &pl, int sub)
{
    unsigned pat = 0u;
    const int nax = sub == 0 ? 2 : 1, ax0 = sub == 0 ? 0 : 2;
    for (int k = 0; k < nax; ++k) {
        const auto r = static_cast<size_t>(ax0 + k);
        pat |= (pl.dv1[r] < 0 ? 1u : 0u) << (2 * k);
        pat |= (pl.dv2[r] < 0 ? 1u : 0u) << (2 * k + 1);
    }
    return pat;
}

double rho_max(const int32_t *rho_q28)
{
    return std::max({rho_q28[0], rho_q28[1], rho_q28[2]}) / Q28;
}

// Band of rho_max: 0 below rho_warn, 1 in [rho_warn, rho_reject], 2 above rho_reject (exact: the
// flight side compares its q28 integers, the reference its doubles).
int band_fx(const int32_t *rho_q28, const imp_params_t &p)
{
    const int32_t m = std::max({rho_q28[0], rho_q28[1], rho_q28[2]});
    return m < p.rho_warn_q28 ? 0 : (m <= p.rho_reject_q28 ? 1 : 2);
}

int band_ref(double m, const ref::ImpGuards &g) { return m < g.rho_warn ? 0 : (m <= g.rho_reject ? 1 : 2); }

// ||J^-1||inf at the reference solution, per subsystem (as tests/impulse/test_imp_golden_host.cpp).
std::array<double, 2> jinv_norm(const ref::ImpNd &p, const ref::ImpPlan &pl)
{
    const std::array<double, 2> a1{{pl.t1[0], pl.t1[1]}}, a2{{pl.t2[0], pl.t2[1]}};
    const std::array<double, 2> b1{{pl.t1[2], 0}}, b2{{pl.t2[2], 0}};
    return {{ref::jacobian(p, 0, pl.pattern & 0xFu, a1, a2).inverse().cwiseAbs().rowwise().sum().maxCoeff(),
             ref::jacobian(p, 1, (pl.pattern >> 4) & 3u, b1, b2).inverse().cwiseAbs().rowwise().sum().maxCoeff()}};
}

double norm3(const ref::Vec6 &e, int off)
{
    return std::sqrt(e(off) * e(off) + e(off + 2) * e(off + 2) + e(off + 4) * e(off + 4));
}

const char *const COLUMNS =
    "box,seed,index,x0_m,xd0_mps,y0_m,yd0_mps,z0_m,zd0_mps,tauf,"
    "outcome_fx,outcome_ref,reason_fx,reason_ref,how_xy_fx,how_z_fx,how_xy_ref,how_z_ref,"
    "pattern_fx,pattern_ref,rule_pattern_fx,rule_pattern_ref,rule_ok_fx,rule_ok_ref,"
    "rule_cause_xy_fx,rule_cause_z_fx,rule_cause_xy_ref,rule_cause_z_ref,rule_order_ref,marginal_fx,marginal_ref,"
    "rho_x,rho_y,rho_z,rho_max_ref,rho_max_fx,rho_band_ref,rho_band_fx,"
    "t1x_s,t2x_s,t1y_s,t2y_s,t1z_s,t2z_s,t1x_ref_s,t2x_ref_s,t1y_ref_s,t2y_ref_s,t1z_ref_s,t2z_ref_s,"
    "dv_fx_mps,dv_ref_mps,dv_imp_mps,it_xy_fx,it_z_fx,it_xy_ref,it_z_ref,iters_total_fx,"
    "attempts_xy_fx,attempts_z_fx,attempts_ref,fres_xy_lsb,fres_z_lsb,"
    "fail_iter_fx,fail_diverge_fx,fail_singular_fx,fail_cond_fx,fail_fx_fx,fail_order_fx,"
    "order_ok_fx,order_ok_ref,dt_max_ms,dt_bound_ms,tie,miss_r_m,miss_v_mps,miss_r_ref_m,st_ok,st_fail\n";

}  // namespace

int main(int argc, char **argv)
{
    int exit_status = -1;
    const Options o = parse(argc, argv, &exit_status);
    if (exit_status >= 0) {
        return exit_status;
    }
    const imp_params_t &p = IMP_TBL_DEFAULT;
    uint32_t why = 0u;
    if (imp_params_check(&p, &why) != FSW_OK) {
        std::fprintf(stderr, "imp_mc: the default table fails imp_params_check (why 0x%x)\n", why);
        return 1;
    }
    const double w = o.omega > 0.0 ? o.omega : p.omega_nradps * 1e-9;
    const double tauf = o.tauf > 0.0 ? o.tauf : w * 1055.0;
    const ref::ImpGuards g = ref::guards_from_table(p);

    FILE *fo = stdout;
    if (!o.out.empty()) {
        fo = std::fopen(o.out.c_str(), "w");
        if (fo == nullptr) {
            std::fprintf(stderr, "imp_mc: cannot write %s\n", o.out.c_str());
            return 1;
        }
    }
    if (o.header) { std::fputs(COLUMNS, fo); }

    auto ws = std::make_unique<imp_ws_t>();
    imp_solution_t sol{};
    const auto t_start = std::chrono::steady_clock::now();
    for (std::uint64_t idx = o.i0; idx < o.i1; ++idx) {
        const Problem f = make_problem(p, *o.box, o.seed, idx, w, tauf);
        const ref::ImpCase &c = f.c;
        const ref::ImpNd nd = ref::nondim(c);
        const ref::ImpPlan pl = ref::solve(c, g);
        imp_solve(ws.get(), &p, &f.pr, &sol);

        // The polarity rule alone from (0, tau_f), both sides, gate or not (spec §3.5 step 2).
        std::array<unsigned, 2> rc_fx{}, rc_ref{};
        unsigned rule_fx = 0u, rule_ref = 0u;
        unsigned rule_order = 0u;   // reference rule attempt ended ORDER: 1 T1 < 0, 2 T2 > T, 4 T2 < T1
        for (int sub = 0; sub < 2; ++sub) {
            const auto su = static_cast<size_t>(sub);
            const unsigned pf = rule_local(sol.dv1_q28, sol.dv2_q28, sub);
            const unsigned pr = rule_local_ref(pl, sub);
            rule_fx |= pf << (sub == 0 ? 0 : 4);
            rule_ref |= pr << (sub == 0 ? 0 : 4);
            const int32_t z1[2] = {0, 0}, z2[2] = {f.pr.tauf_q29, f.pr.tauf_q29};
            uint32_t it = 0u, fres = 0u;
            fx_status_t ast = 0u;
            rc_fx[su] = imp_attempt(ws.get(), &p, &f.pr, static_cast<uint32_t>(sub), pf, z1, z2, &it, &fres, &ast);
            const ref::ImpAttempt ra = ref::attempt(nd, g, sub, pr, {{0, 0}}, {{nd.tauf, nd.tauf}});
            rc_ref[su] = ra.cause;
            if (ra.cause == IMP_FAIL_ORDER) {
                for (size_t k = 0; k < (sub == 0 ? 2u : 1u); ++k) {
                    rule_order |= ra.t1[k] < -g.tol_tau ? 1u : 0u;
                    rule_order |= ra.t2[k] > nd.tauf + g.tol_tau ? 2u : 0u;
                    rule_order |= ra.t2[k] - ra.t1[k] < -g.tol_tau ? 4u : 0u;
                }
            }
        }
        const bool rule_ok_fx = sol.outcome == IMP_SOL_VALID && sol.how[0] == IMP_HOW_RULE && sol.how[1] == IMP_HOW_RULE;
        const bool rule_ok_ref = pl.outcome == IMP_SOL_VALID && pl.how[0] == IMP_HOW_RULE && pl.how[1] == IMP_HOW_RULE;

        const double rmax_fx = rho_max(sol.rho_q28);
        const double rmax_ref = std::max({pl.rho[0], pl.rho[1], pl.rho[2]});
        std::string reason_fx, reason_ref;
        if (sol.outcome == IMP_SOL_VALID) {
            reason_fx = "ok";
        } else if (sol.outcome == IMP_SOL_INFEASIBLE) {
            reason_fx = band_fx(sol.rho_q28, p) == 2 ? "rho>reject" : "impulsive";
        } else {
            for (int sub = 0; sub < 2; ++sub) {
                if (sol.sub_outcome[sub] != IMP_SOL_VALID) {
                    if (!reason_fx.empty()) { reason_fx += ';'; }
                    reason_fx += sub == 0 ? "xy:" : "z:";
                    reason_fx += cause_name(sol.last_fail[sub]);
                }
            }
        }
        if (pl.outcome == IMP_SOL_VALID) {
            reason_ref = "ok";
        } else if (pl.outcome == IMP_SOL_INFEASIBLE) {
            reason_ref = rmax_ref > g.rho_reject ? "rho>reject" : "impulsive";
        } else {
            reason_ref = pl.how[0] == IMP_HOW_NONE ? (pl.how[1] == IMP_HOW_NONE ? "xy;z" : "xy") : "z";
        }

        // Validity of the accepted schedules, exactly: integers (q29) for the flight code, the
        // reference's own doubles (spec §3.1: 0 <= T1 <= T2 <= T on every axis).
        int order_fx = -1, order_ref = -1;
        if (sol.outcome == IMP_SOL_VALID) {
            order_fx = 1;
            for (int r = 0; r < 3; ++r) {
                if (!(sol.t1_q29[r] >= 0 && sol.t1_q29[r] <= sol.t2_q29[r] && sol.t2_q29[r] <= f.pr.tauf_q29)) { order_fx = 0; }
            }
        }
        if (pl.outcome == IMP_SOL_VALID) {
            order_ref = 1;
            for (size_t r = 0; r < 3; ++r) {
                if (!(pl.t1[r] >= 0.0 && pl.t1[r] <= pl.t2[r] && pl.t2[r] <= nd.tauf)) { order_ref = 0; }
            }
        }
        std::array<double, 3> t1{}, t2{};
        const double nan = std::nan("");
        double dt_max_ms = nan, dt_bound_ms = nan, miss_r = nan, miss_v = nan, miss_r_ref = nan;
        int tie = 0;
        const double V = c.V();
        const double dv_fx = (sol.dv_q28[0] + sol.dv_q28[1]) / Q28 * V;
        const double dv_ref = (pl.dv[0] + pl.dv[1]) * V;
        double dv_imp = 0;
        for (size_t r = 0; r < 3; ++r) { dv_imp += (std::abs(pl.dv1[r]) + std::abs(pl.dv2[r])) * V; }
        for (int r = 0; r < 3; ++r) {
            t1[static_cast<size_t>(r)] = sol.t1_q29[r] / Q29;
            t2[static_cast<size_t>(r)] = sol.t2_q29[r] / Q29;
        }
        if (sol.outcome == IMP_SOL_VALID) {
            const ref::Vec6 e = ref::terminal_error(c, t1, t2, sol.pattern);
            miss_r = norm3(e, 0);
            miss_v = norm3(e, 1);
        }
        if (pl.outcome == IMP_SOL_VALID) {
            miss_r_ref = norm3(ref::terminal_error(c, pl.t1, pl.t2, pl.pattern), 0);
        }
        if (sol.outcome == IMP_SOL_VALID && pl.outcome == IMP_SOL_VALID) {
            if (sol.pattern == pl.pattern) {
                // First-order bound of the time error left by stopping at |F_fx| = fres: the double
                // residual there is <= fres + E_F (E_F = 16 LSB, the residual-evaluation allowance
                // of the golden test), so |dT| <= ||J^-1|| (fres + E_F) 2^-28 + 1 LSB q29 (clamp).
                const std::array<double, 2> jn = jinv_norm(nd, pl);
                dt_bound_ms = 0;
                for (size_t sub = 0; sub < 2; ++sub) {
                    dt_bound_ms = std::max(dt_bound_ms, (jn[sub] * (sol.fres_lsb[sub] + 16.0) / Q28 + 1.0 / Q29) / w * 1e3);
                }
                dt_max_ms = 0;
                for (size_t r = 0; r < 3; ++r) {
                    dt_max_ms = std::max({dt_max_ms, std::abs(t1[r] - pl.t1[r]) / w * 1e3,
                                          std::abs(t2[r] - pl.t2[r]) / w * 1e3});
                }
            } else {
                // Different patterns are a legitimate tie (spec §3.5) only if both plans' dv are
                // within the tie band; each side's dv carries its own arithmetic, hence 2 dv_tie.
                const double d = std::abs((sol.dv_q28[0] + sol.dv_q28[1]) / Q28 - (pl.dv[0] + pl.dv[1]));
                tie = d <= 2.0 * g.dv_tie ? 1 : -1;
            }
        }

        const double s1 = 1.0 / w;
        std::fprintf(fo, "%s,%llu,%llu,%.6f,%.8f,%.6f,%.8f,%.6f,%.8f,%.9f,", o.box->name,
                     static_cast<unsigned long long>(o.seed), static_cast<unsigned long long>(idx), c.x0(0), c.x0(1),
                     c.x0(2), c.x0(3), c.x0(4), c.x0(5), nd.tauf);
        std::fprintf(fo, "%s,%s,%s,%s,%s,%s,%s,%s,", outcome_name(sol.outcome), outcome_name(pl.outcome),
                     reason_fx.c_str(), reason_ref.c_str(), how_name(sol.how[0]), how_name(sol.how[1]),
                     how_name(pl.how[0]), how_name(pl.how[1]));
        std::fprintf(fo, "%u,%u,%u,%u,%d,%d,%s,%s,%s,%s,%u,%d,%d,", static_cast<unsigned>(sol.pattern), pl.pattern,
                     rule_fx, rule_ref, rule_ok_fx ? 1 : 0, rule_ok_ref ? 1 : 0, cause_name(rc_fx[0]),
                     cause_name(rc_fx[1]), cause_name(rc_ref[0]), cause_name(rc_ref[1]), rule_order, sol.marginal != 0u ? 1 : 0,
                     pl.marginal ? 1 : 0);
        std::fprintf(fo, "%.9f,%.9f,%.9f,%.9f,%.9f,%d,%d,", pl.rho[0], pl.rho[1], pl.rho[2], rmax_ref, rmax_fx,
                     band_ref(rmax_ref, g), band_fx(sol.rho_q28, p));
        for (size_t r = 0; r < 3; ++r) { std::fprintf(fo, "%.6f,%.6f,", t1[r] * s1, t2[r] * s1); }
        for (size_t r = 0; r < 3; ++r) { std::fprintf(fo, "%.6f,%.6f,", pl.t1[r] * s1, pl.t2[r] * s1); }
        std::fprintf(fo, "%.6f,%.6f,%.6f,%u,%u,%d,%d,%u,", dv_fx, dv_ref, dv_imp, static_cast<unsigned>(sol.iters[0]),
                     static_cast<unsigned>(sol.iters[1]), pl.iters[0], pl.iters[1],
                     static_cast<unsigned>(sol.iters_total));
        std::fprintf(fo, "%u,%u,%d,%d,%d,", static_cast<unsigned>(sol.attempts[0]), static_cast<unsigned>(sol.attempts[1]),
                     pl.attempts, sol.fres_lsb[0], sol.fres_lsb[1]);
        for (unsigned k = 1; k < IMP_FAIL_N; ++k) { std::fprintf(fo, "%u,", static_cast<unsigned>(sol.n_fail[k])); }
        std::fprintf(fo, "%d,%d,%.6g,%.6g,%d,%.6g,%.6g,%.6g,%u,%u\n", order_fx, order_ref, dt_max_ms, dt_bound_ms, tie, miss_r, miss_v, miss_r_ref,
                     static_cast<unsigned>(sol.st_ok), static_cast<unsigned>(sol.st_fail));
    }
    const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
    const bool ok = std::fflush(fo) == 0 && !std::ferror(fo);
    if (fo != stdout) { std::fclose(fo); }
    std::fprintf(stderr, "imp_mc: %s seed %llu [%llu, %llu): %llu samples in %.3f s\n", o.box->name,
                 static_cast<unsigned long long>(o.seed), static_cast<unsigned long long>(o.i0),
                 static_cast<unsigned long long>(o.i1), static_cast<unsigned long long>(o.i1 - o.i0), el);
    return ok ? 0 : 1;
}
