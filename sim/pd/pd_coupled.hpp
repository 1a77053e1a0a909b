// pd_coupled — the three-channel gyrodine plant of spec 40 §2.1 and the three independent §2.2
// channels, both in one state layout, discretised by the exact ZOH of pd_model (ref::pd::zoh).
// The physics parameters are the ref::pd::Channel definitions (§2.4): nothing is restated here.
//
// Degrees of freedom (n_dof = 10; the mode count comes from the channels: yaw 2, roll 1, pitch 1):
//   0..2  x_k      body angle of channel k = yaw, roll, pitch [rad]
//   3..5  beta_k   gimbal angle of gyrodine k [rad]
//   6..9  q        elastic coordinates: yaw mode 1, yaw mode 2, roll, pitch [rad]
// State s = [dof; dof'] (20), input u = the three gimbal torques M_k [N m] (columns of B).
//
// Coupled (§2.1), a = cos(pi/4), sigma = coupling sign (+1 or -1), bilinear terms omitted (§2.1):
//   body k:   I_k x_k'' - H beta_k' + a Ib [sigma sum_{j!=k} beta_j'' + a (2 x_k'' + sum_{j!=k} x_j'')]
//             + sum_i I^k_i q^k_i'' = 0
//   gimbal k: Ib beta_k'' + kbd beta_k' + kbs beta_k + sigma a Ib sum_{j!=k} x_j'' + H x_k' = M_k
//   mode i:   r^k_i x_k'' + q^k_i'' + Omega_i^2 q^k_i = 0
// Second-order form Mm q'' + C q' + K q = F u. Each mode row is scaled by I_i / r_i (an exact row
// scaling, the same solution), which makes Mm symmetric: Mm = [[body, I_i], [I_i, I_i / r_i]], the
// kinetic-energy matrix of the linear model. Mm is asserted symmetric and positive definite
// (Cholesky): per channel that needs Ix - sum_i r_i I_i > 0 (yaw 23 407, roll 3 415, pitch
// 46 470 N m s^2 nominal), which bounds the robustness scales (coupling / ix).
// sigma multiplies only the a Ib body-gimbal cross terms; the a^2 Ib body-body terms stay positive.
#ifndef SIM_PD_PD_COUPLED_HPP
#define SIM_PD_PD_COUPLED_HPP

#include <array>
#include <vector>

#include <Eigen/Dense>

#include "pd/pd_model.hpp"

namespace ref::pd {

constexpr int kChannels = 3;  // yaw, roll, pitch

// Robustness scales of the true plant (spec 40 §7 A3-9): modal coupling inertias I_i, body
// inertias Ix and gyrodine momentum H. The flight code does not know them.
struct Scales {
    double coupling = 1.0;
    double ix = 1.0;
    double h = 1.0;
};

Channel scaled(const Channel &ch, const Scales &s);
// yaw, roll, pitch (Channel::yaw() ...), scaled, with sample period Ty.
std::array<Channel, kChannels> three_channels(const Scales &s = {}, double Ty = 0.25);

// Where each channel's coordinates sit in the state.
struct Layout {
    int n_dof = 0;
    std::array<int, kChannels> q_off{};   // first elastic dof of channel k
    std::array<int, kChannels> n_q{};     // its number of modes
    static int x(int k) { return k; }
    static int beta(int k) { return kChannels + k; }
    int q(int k, int i) const { return q_off[static_cast<std::size_t>(k)] + i; }
    int n_modes() const { return n_dof - 2 * kChannels; }
};
Layout layout(const std::array<Channel, kChannels> &ch);

struct SecondOrder {
    Eigen::MatrixXd Mm, C, K, F;   // n_dof x n_dof (F: n_dof x 3)
    std::vector<double> omega;     // Omega of each elastic dof, in dof order [rad/s]
};
// cross = false drops every a Ib term (three independent §2.2 channels in the symmetric form; used
// for the positive-definiteness check of the single plant). sign: +1 or -1.
// Throws std::invalid_argument when Mm is not symmetric positive definite (scales out of reach).
SecondOrder second_order(const std::array<Channel, kChannels> &ch, double f_hz, int sign, bool cross = true);

struct StateSpace {
    Eigen::MatrixXd A, B;   // 2 n_dof x 2 n_dof, 2 n_dof x 3
};
// A = [[0, I], [-Mm^-1 K, -Mm^-1 C]], B = [0; Mm^-1 F].
StateSpace state_space(const SecondOrder &so);

// Exact ZOH of the coupled plant (one block exponential).
DiscreteN discretise_coupled(const std::array<Channel, kChannels> &ch, double f_hz, int sign, double Ty);
// The three single channels: each channel's ref::pd::discretise(ch_k, f) (Ad, Bd) placed in the
// layout above; the cross-channel blocks are exact zeros, so a channel at rest with no command
// stays exactly at rest.
DiscreteN discretise_single(const std::array<Channel, kChannels> &ch, double f_hz, double Ty);

}  // namespace ref::pd

#endif
