// CW rendezvous plant (spec 50 §2): exact closed-form propagation of the Clohessy-Wiltshire
// equations in the spec's frame (x along-track, y radial towards the Earth, z cross-track),
// six constant-thrust on/off thrusters (+x, -x, +y, -y, +z, -z) commanded per step as on-windows
// in valve-timer counts (1 us), split exactly at every switching instant, and the relative
// navigation sensor of §2.5.
//
// Standalone (no LCM, no scenario file): the SIL node wraps it. Independent of the double
// reference (imp_ref_*) and of fsw/. Random numbers come from the project's generator
// (sim/sensors/rng.hpp), one stream per purpose, so a seed gives the same run on every platform.
#ifndef SIM_IMPULSE_CW_PLANT_HPP
#define SIM_IMPULSE_CW_PLANT_HPP

#include <Eigen/Dense>
#include <array>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "sensors/rng.hpp"

namespace sim {

// Relative-navigation sensor (spec 50 §2.5). Profiles set sigma_p / sigma_v; a bias, a range
// limit, scripted and random dropouts and outliers come on top.
enum class NavProfile { Ideal, Nominal, Degraded, Custom };

struct NavConfig {
    NavProfile profile = NavProfile::Ideal;
    double f_nav = 1.0;                       // sample rate [Hz] (a divisor of the step rate)
    double sigma_p = 0.0;                     // white noise per axis [m] (Custom only)
    double sigma_v = 0.0;                     // [m/s] (Custom only)
    std::array<double, 3> bias_p{};           // constant bias per axis [m]
    std::array<double, 3> bias_v{};           // [m/s]
    double range_max = std::numeric_limits<double>::infinity();   // |r| beyond it: invalid
    std::vector<std::pair<double, double>> dropouts;              // scripted [t_a, t_b) [s]: invalid
    double p_drop = 0.0;                      // probability that a sample is invalid
    // Scripted outliers: at the first sample at or after time t, add (dp [m], dv [m/s]) on every axis.
    std::vector<std::pair<double, std::pair<double, double>>> outliers;
    std::uint64_t seed = 0;
    // sigma of each profile
    double sp() const;
    double sv() const;
};

// One sample as the flight code receives it: counts (position 1 mm, velocity 10 um/s, rounded
// half away from zero), the step index at which it was taken, and a validity bit.
struct NavSample {
    std::array<std::int32_t, 3> pos_mm{};
    std::array<std::int32_t, 3> vel_cnt{};
    std::uint32_t step = 0;
    bool valid = false;
};

struct CwConfig {
    double w = 1.131367e-3;               // orbit rate [rad/s]
    double a_nom = 0.04;                  // nominal thrust acceleration [m/s^2]
    double eps_c = 0.0;                   // common level error
    std::array<double, 6> eps{};          // per-thruster level error
    std::uint32_t period_us = 100000;     // valve tick = fsw period
    std::uint32_t t_min_us = 20000;       // minimum on-time of a burn
    bool stretch = false;                 // a shorter burn: false = dropped, true = stretched
    int stuck_off_j = -1;                 // thruster stuck off from stuck_off_t [s]
    double stuck_off_t = std::numeric_limits<double>::infinity();
    int stuck_on_j = -1;                  // thruster stuck on from stuck_on_t [s]
    double stuck_on_t = std::numeric_limits<double>::infinity();
    NavConfig nav;
};

class CwPlant {
public:
    using Vec6 = Eigen::Matrix<double, 6, 1>;
    using Mat6 = Eigen::Matrix<double, 6, 6>;

    CwPlant(const CwConfig &cfg, const Vec6 &x0);

    // Closed forms (spec 50 §2.2): state transition over t (any sign) and the response to a
    // constant acceleration a = (a_x, a_y, a_z) applied for t seconds from zero state.
    static Mat6 phi(double t, double w);
    static Vec6 psi(double t, double w, const Eigen::Vector3d &a);

    // One step: thruster j is on over [start_us[j], start_us[j] + len_us[j]) inside the step
    // when bit j of on_mask is set. A window that starts at 0 continues a burn that was on at
    // the end of the previous step; the minimum on-time applies to whole burns: a burn that
    // both starts and ends inside this step and is shorter than t_min is dropped (or
    // stretched). Faults apply last.
    void step(std::uint8_t on_mask, const std::array<std::uint32_t, 6> &start_us,
              const std::array<std::uint32_t, 6> &len_us);
    // Whole-step convenience: every thruster in on_mask on for the full period.
    void step_mask(std::uint8_t on_mask);

    const Vec6 &x() const { return x_; }
    double t() const { return t_s_; }
    std::uint64_t steps() const { return k_; }
    // Both thrusters of one axis commanded in one step: a flight-code violation (logged).
    std::uint32_t violations() const { return violations_; }
    // Commanded burns shorter than t_min (dropped, stretched, or cut short across steps).
    std::uint32_t short_burns() const { return short_burns_; }
    // Velocity change delivered per thruster [m/s].
    const std::array<double, 6> &dv_used() const { return dv_used_; }

    // Navigation: the latest sample at the current step (a new one every 1/f_nav; between
    // samples the previous one is held, with its own step index).
    const NavSample &nav() const { return nav_; }
    // Ideal sample of the current state (quantisation only), whatever the profile.
    void nav_counts(std::array<std::int32_t, 3> &pos_mm, std::array<std::int32_t, 3> &vel_cnt) const;

private:
    double level(int j) const { return cfg_.a_nom * (1.0 + cfg_.eps_c + cfg_.eps[static_cast<size_t>(j)]); }
    void sample_nav();

    CwConfig cfg_;
    Vec6 x_;
    double t_s_ = 0.0;
    std::uint64_t k_ = 0;
    std::uint32_t violations_ = 0;
    std::uint32_t short_burns_ = 0;
    std::array<double, 6> dv_used_{};
    std::array<bool, 6> open_{};          // burn on at the end of the previous step
    std::array<std::uint64_t, 6> open_us_{};   // its length so far
    std::uint32_t nav_div_ = 10;
    std::size_t next_outlier_ = 0;
    NavSample nav_;
    Rng rng_noise_;
    Rng rng_drop_;
};

}  // namespace sim

#endif  // SIM_IMPULSE_CW_PLANT_HPP
