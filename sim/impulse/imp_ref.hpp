// imp_ref — the impulse scheduler's switching-time solver in double precision with Eigen
// (spec 50-impulse §6). Independent of the fixed-point code: it reads fsw/impulse/imp.h only for
// the constants that name outcomes, causes and polarity bits.
//
// Same decision logic as fsw/impulse/imp_solve.c (impulsive solution and feasibility gate, rule,
// then search in ascending pattern index with ties within dv_tie to the lower index; guards:
// iteration limit, divergence outside (-tau_f, 2 tau_f), |pivot| < pivot_min, pivot ratio,
// validity +-tol_tau at convergence), solved in the nondimensional system of §4.1 so that every
// threshold means the same thing; only the arithmetic differs. Also the independent checks of
// §6: Phi against the matrix exponential, Psi against adaptive quadrature, J against central
// differences, the piecewise closed form against an RK4 integration of the schedule.
#pragma once

#include <Eigen/Dense>
#include <array>
#include <cstdint>
#include <vector>

extern "C" {
#include "imp.h"
}

namespace ref {

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

// One rendezvous problem in SI: orbit rate w [rad/s], a_nom [m/s^2], horizon T [s], states
// (x, x', y, y', z, z') [m, m/s], thrust factors alpha_j (thruster j = +x, -x, +y, -y, +z, -z).
struct ImpCase {
    double w = 1.131367e-3;
    double a_nom = 0.04;
    double T = 1055.0;
    Vec6 x0 = Vec6::Zero();
    Vec6 xt = Vec6::Zero();
    std::array<double, 6> alpha{{1, 1, 1, 1, 1, 1}};
    double L() const { return a_nom / (w * w); }   // length unit [m]
    double V() const { return a_nom / w; }         // velocity unit [m/s]
};

// Guards and thresholds, nondimensional (the flight table's values by default).
struct ImpGuards {
    int max_iter = 10;
    double r_tol = 32.0 / 268435456.0;             // 32 LSB of q28
    double pivot_min = 1.0 / 1024.0;               // 2^-10
    double pivot_ratio = 1.0 / 4096.0;             // 2^-12
    double rho_warn = 0.38;
    double rho_reject = 0.55;
    double dv_tie = 2.828418e-5;                   // 1 mm/s in V units at 400 km
    double tol_tau = 1.0 / 536870912.0;            // validity +-1 LSB of q29
};

// The flight table's guards in the reference's nondimensional units, so that reference and
// fixed-point code test the same thresholds (ImpFsw, the golden generator, imp_mc).
ImpGuards guards_from_table(const imp_params_t &p);

// Nondimensional model (w = a_nom = 1). Rows of Psi / Phi e_r: 4 for axes x, y; 2 for z.
Eigen::Matrix4d phi_xy(double tau);
Eigen::Matrix2d phi_z(double tau);
Mat6 phi(double tau);
Eigen::VectorXd psi(int axis, double sig);
Eigen::VectorXd phi_e(int axis, double sig);

struct ImpIter {
    std::array<double, 2> t1{}, t2{};   // nondimensional times of this iterate
    Eigen::VectorXd f;                  // residual at this iterate
};

struct ImpAttempt {
    unsigned cause = IMP_FAIL_NONE;     // IMP_FAIL_*
    int iters = 0;
    std::array<double, 2> t1{}, t2{};
    double fmax = 0;
    std::vector<ImpIter> hist;          // iterates 0..iters
};

// Nondimensional problem derived from an ImpCase.
struct ImpNd {
    double tauf;
    Vec6 x0, xt;
    std::array<double, 6> alpha;
};
ImpNd nondim(const ImpCase &c);

Eigen::VectorXd residual(const ImpNd &p, int sub, unsigned pat, const std::array<double, 2> &t1,
                         const std::array<double, 2> &t2);
Eigen::MatrixXd jacobian(const ImpNd &p, int sub, unsigned pat, const std::array<double, 2> &t1,
                         const std::array<double, 2> &t2);

// One attempt from (t1, t2) (the flight code's guards); damping `gain` = (1 - l0)(1 - l1) of
// the paper's pole placement (1 = Newton).
ImpAttempt attempt(const ImpNd &p, const ImpGuards &g, int sub, unsigned pat, std::array<double, 2> t1,
                   std::array<double, 2> t2, double gain = 1.0);

struct ImpPlan {
    unsigned outcome = IMP_SOL_NO_SOLUTION;
    unsigned pattern = 0;                  // 6-bit polarity pattern
    bool marginal = false;
    std::array<unsigned, 2> how{};         // IMP_HOW_*
    std::array<int, 2> iters{};
    std::array<double, 3> t1{}, t2{};      // nondimensional
    std::array<double, 3> dv1{}, dv2{};    // impulsive signed dv, nondimensional
    std::array<double, 3> rho{};
    std::array<double, 2> dv{};            // plan dv per subsystem, nondimensional
    std::array<unsigned, IMP_FAIL_N> fail_cnt{};
    int attempts = 0;
};

ImpPlan solve(const ImpCase &c, const ImpGuards &g = ImpGuards());

// Options of a plan (the flight code's imp_problem_t fields): re-plan (rho reported, not gated),
// warm start per subsystem with the 6-bit pattern and times, thrusters to avoid.
struct ImpSolveOpt {
    bool replan = false;
    unsigned warm_mask = 0;
    unsigned warm_pattern = 0;
    std::array<double, 3> warm_t1{}, warm_t2{};
    unsigned thr_off = 0;
};
// The same decision logic on a nondimensional problem: warm (if asked and allowed), rule (if
// not tried and allowed), then every other allowed pattern in ascending index, least dv, ties
// within dv_tie to the lower index.
ImpPlan solve_nd(const ImpNd &p, const ImpGuards &g, const ImpSolveOpt &o);

// The terminal error of a schedule (nondimensional times, 6-bit pattern) in SI: closed form.
Vec6 terminal_error(const ImpCase &c, const std::array<double, 3> &t1, const std::array<double, 3> &t2,
                    unsigned pattern);
// The same by RK4 integration of the CW equations, splitting steps at every switching instant.
Vec6 terminal_error_rk(const ImpCase &c, const std::array<double, 3> &t1, const std::array<double, 3> &t2,
                       unsigned pattern, double h_s = 0.5);

// Best rounding (spec 50 §5.3) of a valid plan onto a grid of h_s seconds (T a multiple of h_s):
// floor/ceil per interior switch, every valid choice scored by the exact closed form, cost
// |dR|^2 + (w t_w)^2 |dV|^2 nondimensional, lowest wins (ties to the lower index).
struct ImpRound {
    std::array<long, 3> n1{}, n2{};
    std::array<unsigned, 2> choice{}, nearest{};
    std::array<std::array<double, 16>, 2> cost{};   // per choice (inf when invalid)
    Vec6 miss = Vec6::Zero();                       // SI terminal error of the choice
    Vec6 miss_nearest = Vec6::Zero();
};
ImpRound round_best(const ImpCase &c, const ImpPlan &pl, double h_s, double t_w = 100.0);

// Independent checks (nondimensional): Phi by Eigen's MatrixExponential, Psi by adaptive
// Simpson quadrature of Phi(u) e_r, J by central differences.
Mat6 phi_expm(double tau);
Eigen::VectorXd psi_quad(int axis, double sig, double tol = 1e-13);
Eigen::MatrixXd jacobian_fd(const ImpNd &p, int sub, unsigned pat, const std::array<double, 2> &t1,
                            const std::array<double, 2> &t2, double h = 1e-6);

}  // namespace ref

// ------------------------------------------------------------------ reference FSW (spec 50 §6)
//
// The whole scheduler in double precision with the flight code's decision logic (imp.c,
// imp_tl.c, imp_nav.c, imp_sched.c): START checks, plan with warm -> rule -> search, best
// rounding onto the valve grid with the minimum-impulse and coast rules, timeline, re-plan
// epochs and FINAL, thrust-level calibration, nav outlier gate, stuck-valve monitor, expected
// miss, interlock. Same in/out structs as the flight module (imp_in_t -> imp_out_t), so a SIL
// run can swap it in ("reference FSW") to bound SIL metrics. Differences from the flight code,
// by design: the plan is computed in the step it starts (the flight job spreads it over steps,
// at most plan_iter_per_step work units each, and always finishes before t_a with a valid
// table), so PLANNING is never reported and no plan is late; telemetry fills the counters,
// mode, pattern, thrust factors, expected miss and monitor fields only.
namespace ref {

class ImpFsw {
public:
    explicit ImpFsw(const imp_params_t &p);
    void init();
    void step(const imp_in_t &in, imp_out_t &out);
    unsigned mode() const { return mode_; }
    const std::array<double, 6> &alpha() const { return alpha_; }

    struct Nav {
        std::uint32_t step = 0;
        Vec6 x = Vec6::Zero();
        bool valid = false;
    };
    struct Tl {
        std::uint32_t ta = 0, ntot = 0;
        std::array<std::uint32_t, 3> n1{}, n2{};
        std::array<double, 3> t1{}, t2{};
        std::array<unsigned, 3> thr1{}, thr2{};
        unsigned pattern = 0;
        bool valid = false;
    };
    // Best rounding of a valid plan onto the grid (nondimensional problem p, n_total grid units).
    void round_plan(const ImpNd &p, const ImpPlan &pl, std::uint32_t n_total, std::array<std::uint32_t, 3> &n1,
                    std::array<std::uint32_t, 3> &n2, Vec6 &miss) const;

private:
    struct Seg {
        unsigned thr;
        std::uint64_t s, e;
    };
    struct Win {
        std::array<Vec6, 6> r;
        std::array<std::uint64_t, 6> on{};
        Vec6 xp = Vec6::Zero(), m = Vec6::Zero();
    };

    double tau_g(std::uint64_t n) const { return static_cast<double>(n) * dg_; }
    Vec6 convert(const std::int32_t *pos, const std::int32_t *vel) const;
    bool covers(std::uint32_t k) const { return static_cast<std::uint64_t>(k) * G_ >= lost_g_; }
    bool fresh(std::uint32_t k) const;
    static bool active(unsigned m);
    static bool terminal(unsigned m);
    void burn_response(Win &w, unsigned j, std::uint64_t bs, std::uint64_t be, std::uint64_t k1g, std::uint64_t k2g,
                       std::uint64_t teg) const;
    void log_response(Win &w, std::uint64_t k1g, std::uint64_t k2g, std::uint64_t teg) const;
    void tl_response(Win &w, const Tl &tl, std::uint64_t k1g, std::uint64_t k2g, std::uint64_t teg) const;
    Vec6 predict(const Win &w, const Vec6 &x1, std::uint64_t dgu) const;
    Win window(const Nav &a, const Nav &b) const;
    Vec6 propagate(const Nav &nv, std::uint32_t now, std::uint32_t ta, bool use_tl) const;
    bool gate_ok(const Nav &c) const;
    unsigned fd_evaluate(const Win &w, std::uint32_t span);
    unsigned fd_step();
    unsigned nav_intake(const imp_in_t &in);
    void log_add(unsigned j, std::uint64_t a, std::uint64_t b, std::uint64_t step_g);
    void log_prune();
    bool cal_done(unsigned j) const;
    void cal_reset();
    bool cal_epoch();
    bool final_at(std::uint32_t ta) const;
    bool plan(const ImpNd &nd, const ImpSolveOpt &o, std::uint32_t ta, Tl &tl);
    void start_replan(const imp_in_t &in, unsigned kind, std::uint32_t ta);
    unsigned start(const imp_in_t &in);
    unsigned command(const imp_in_t &in);
    void fd_react(const imp_in_t &in, unsigned ev);
    void epoch(const imp_in_t &in, bool regular);
    void progress(const imp_in_t &in);
    unsigned fire(std::uint32_t k, unsigned avail, imp_out_t &out);
    unsigned health(const imp_in_t &in, imp_out_t &out);

    imp_params_t p_;
    double w_, dg_, wv_;
    std::uint32_t G_, us_, nmin_;
    ImpGuards g_;
    // state
    unsigned mode_ = IMP_MODE_IDLE;
    std::uint32_t t0_ = 0, tf_ = 0, next_tp_ = 0;
    bool retry_ = false, marginal_ = false;
    std::uint32_t latched_ = 0;
    unsigned stuck_off_ = 0;
    unsigned stuck_j_ = 0xFF;
    Tl act_, pend_;
    Nav nav_;
    bool seen_ = false;
    std::uint32_t seen_step_ = 0;
    std::vector<Seg> log_;
    std::uint64_t lost_g_ = 0;
    Nav cal_ref_;
    std::array<double, 6> sum_w_{}, sum_wa_{}, alpha_{};
    std::array<unsigned, 6> n_acc_{};
    Nav fd_x0_;
    std::array<unsigned, 6> cnt_off_{}, cnt_on_{};
    std::array<std::uint64_t, 6> on_tot_{};
    std::array<double, 3> exp_dr_{}, exp_dv_{};
    Vec6 miss_ = Vec6::Zero();
    std::uint32_t plans_ = 0, failed_ = 0, skipped_ = 0, cmd_rej_ = 0, nav_rej_ = 0, cal_rej_ = 0, kept_ = 0;
    unsigned rej_reason_ = 0, pattern_ = 0;
    std::uint32_t health_sticky_ = 0;
};

}  // namespace ref
