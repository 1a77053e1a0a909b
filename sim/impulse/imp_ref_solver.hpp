// imp_ref_solver — the impulse scheduler's switching-time solver in double precision with Eigen
// (spec 50-impulse §6). Independent of the fixed-point code: it reads fsw/impulse/imp.h only for
// the constants that name outcomes, causes and polarity bits.
//
// Same decision logic as fsw/impulse/imp_solve.c (impulsive solution and feasibility gate, rule,
// then search in ascending pattern index with ties within dv_tie to the lower index; guards:
// iteration limit, divergence outside (-tau_f, 2 tau_f), |pivot| < pivot_min, pivot ratio,
// validity +-tol_tau at convergence), solved in the nondimensional system of §4.1 so that every
// threshold means the same thing; only the arithmetic differs. The closed-form CW model (Phi,
// Psi, Phi e_r) it solves with is here too. The independent checks of a plan are in
// imp_ref_checks.hpp, the reference FSW that flies the solver in imp_ref_fsw.hpp.
#pragma once

#include <Eigen/Dense>
#include <array>
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
    std::array<unsigned, IMP_FAIL_N> n_fail{};
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

}  // namespace ref
