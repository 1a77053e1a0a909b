// Linear model of the solar-sail platform (spec 10 §2.1, §2.2).
//
// State x = [w_y, w_z, mu_y, mudot_y, mu_z, mudot_z] (rad/s, rad/s, rad, rad/s, rad, rad/s);
// input u = [bdot_y, bdot_z] (gimbal rates, rad/s); y = [w_y, w_z].
// sigma = +1 is "M-phys" (the printed A_s, the physics), sigma = -1 is "M-paper" (the matrix
// behind the paper's numbers). Both are first-class: every caller passes sigma explicitly.
#ifndef SIM_OBSERVER_SAIL_MODEL_HPP
#define SIM_OBSERVER_SAIL_MODEL_HPP

#include <Eigen/Dense>

namespace sim {

using Mat6 = Eigen::Matrix<double, 6, 6>;
using Mat62 = Eigen::Matrix<double, 6, 2>;
using Mat26 = Eigen::Matrix<double, 2, 6>;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Vec2 = Eigen::Matrix<double, 2, 1>;

// State indices, so that code reads as physics rather than as magic numbers.
enum SailIdx : int { kWy = 0, kWz = 1, kMuY = 2, kMuDotY = 3, kMuZ = 4, kMuDotZ = 5 };

struct SailParams {
    double jc_kgm2 = 61175.0;          // sail transverse inertia (reduced)
    double ja_kgm2 = 122350.0;         // sail polar inertia, 2*J_C
    double j_kgm2 = 1200.0;            // nominal platform transverse inertia
    double spin_radps = 0.5;           // sail spin rate Omega (about -x)
    double k2_per_s2 = 0.01;           // mount stiffness per unit J_C (truth)
    int sigma = +1;                    // +1 M-phys, -1 M-paper
    double j_factor = 1.0;             // true J = j_factor * j_kgm2 (inertia-error runs)

    double j_true_kgm2() const { return j_factor * j_kgm2; }
    // Rotor momentum H = J_A * Omega: a property of the rotor, unchanged by j_factor.
    double h_rotor_nms() const { return ja_kgm2 * spin_radps; }
    double g_radps() const { return 2.0 * spin_radps * jc_kgm2 / j_true_kgm2(); }
    double c() const { return 1.0 + jc_kgm2 / j_true_kgm2(); }
};

// A_s = A_s0 + k2 * A_k2 (spec 10 §2.2).
Mat6 sail_a_s0(const SailParams &p);
Mat6 sail_a_k2(const SailParams &p);
Mat6 sail_a_s(const SailParams &p);
Mat62 sail_b_s(const SailParams &p);

// Transverse momentum rows m (2x6) for which m*A_s = 0 when the rows match sigma (spec 10 §2.3):
// h_y = (J+J_C) w_y + J_C mudot_y - s*H mu_z,  h_z = (J+J_C) w_z + J_C mudot_z + s*H mu_y,
// with s = rows_sigma. m*B_s = [[0, -H], [+H, 0]], i.e. hdot = -H bdot_z, +H bdot_y.
Mat26 sail_momentum_rows(const SailParams &p, int rows_sigma);

// The continuous equations written out line by line, independently of the A_s assembly, so that
// the ODE option cross-checks the matrices as well as the discretisation.
void sail_deriv(const SailParams &p, const double x[6], const double u_radps[2], double dx[6]);

// Exact zero-order hold: E = expm([[A_s, B_s], [0, 0]] * h); Phi = E11, Gamma = E12.
struct SailZoh {
    Mat6 phi;
    Mat62 gamma;
};
SailZoh sail_zoh(const SailParams &p, double h_s);

// dPhi/dk2 and dGamma/dk2 at p.k2_per_s2 (spec 10 §4.1): the top-right 8x8 block of the Van Loan
// exponential expm([[Abar, Ebar], [0, Abar]] h), Abar = [[A_s, B_s], [0, 0]], Ebar = [[A_k2, 0], [0, 0]].
SailZoh sail_zoh_dk2(const SailParams &p, double h_s);

}  // namespace sim

#endif
