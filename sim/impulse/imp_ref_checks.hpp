// imp_ref_checks — the independent checks of the impulse double reference (spec 50-impulse §6),
// used by the golden tests and the Monte Carlo (tools/impulse/imp_mc): the terminal error of a
// schedule by the closed form and by an RK4 integration of the CW equations, the best rounding
// of a plan onto a grid scored by that closed form, Phi against the matrix exponential, Psi
// against adaptive quadrature, J against central differences.
#pragma once

#include <Eigen/Dense>
#include <array>

#include "impulse/imp_ref_solver.hpp"

namespace ref {

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
