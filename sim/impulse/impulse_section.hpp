// impulse_section.hpp — the RENDEZVOUS mission's part of a scenario (spec 50 §2, §7): the
// Clohessy-Wiltshire chaser, its six on/off thrusters with level errors, minimum on-time, valve
// sub-tick and scripted stuck valves, the relative-navigation sensor, and the flight table's
// operator override (thrust calibration on/off). The scenario core hands it every key it does not
// own (sim/scenario/scenario.hpp).
//
//   mission: rendezvous
//   plant: cw (the default), period_us (default 100000: the valve tick)
//   cw: {omega_radps, a_nom_mps2, x0 [x, x', y, y', z, z'], x0_epoch_s, eps_c, eps [6], t_min_us,
//        min_on: drop | stretch, subtick_us, stuck_off: {thruster, t_s}, stuck_on: {...},
//        nav: {profile: ideal | nominal | degraded | custom, f_hz, sigma_p_m, sigma_v_mps,
//              bias_p_m, bias_v_mps, range_m, dropouts_s, dropout_ppm, seed}}
//   fsw: {table: imp_default | imp_1s | imp_sub1ms, cal_enable: 0 | 1}
#ifndef SIM_IMPULSE_SECTION_HPP
#define SIM_IMPULSE_SECTION_HPP

#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "scenario/scenario.hpp"

extern "C" {
#include "imp.h"
}

namespace sim {

// Relative-navigation sensor of the rendezvous plant (spec 50 §2.5): position (1 mm) and
// velocity (10 um/s) counts in the spec's frame, a validity bit and the sample's step index.
struct NavSetup {
    std::string profile = "ideal";            // ideal | nominal | degraded | custom
    double f_hz = 1.0;                        // sample rate (must divide the fsw rate)
    double sigma_p_m = 0.0;                   // white noise per axis (set by the profile)
    double sigma_v_mps = 0.0;
    std::array<double, 3> bias_p_m{};         // constant bias per axis
    std::array<double, 3> bias_v_mps{};
    double range_m = 1.0e6;                   // beyond |r| > range_m the sample is invalid
    std::vector<std::array<double, 2>> dropouts_s;   // scripted [t0, t1) windows without samples
    std::uint32_t dropout_ppm = 0u;           // random dropouts (per sample)
    std::uint64_t seed = 0u;
};

// Clohessy-Wiltshire rendezvous plant (spec 50 §2): chaser state, six on/off thrusters with
// level errors, minimum on-time, valve tick (the fsw period) and sub-tick, scripted stuck valves.
struct CwSetup {
    double omega_radps = 1.131367e-3;         // orbit rate (400 km circular by default)
    double a_nom_mps2 = 0.04;                 // nominal acceleration per thruster
    std::array<double, 6> x0{{5000.0, -1.0, 4000.0, -1.0, 4000.0, -1.0}};   // x, x', y, y', z, z' [m, m/s]
    double x0_epoch_s = 0.0;                  // x0 is the state at this time (free drift before it)
    double eps_c = 0.0;                       // common thrust-level error
    std::array<double, 6> eps{};              // per-thruster level error (+x, -x, +y, -y, +z, -z)
    std::uint32_t t_min_us = 20000u;          // minimum on-time
    bool stretch = false;                     // shorter command: false = dropped, true = stretched
    std::uint32_t subtick_us = 0u;            // 0: whole steps
    int stuck_off_j = -1;                     // thruster stuck off from stuck_off_t_s
    double stuck_off_t_s = std::numeric_limits<double>::infinity();
    int stuck_on_j = -1;
    double stuck_on_t_s = std::numeric_limits<double>::infinity();
    NavSetup nav;
};

struct CwScenario final : MissionScenario {
    CwSetup cw;
    int cal_enable = -1;                      // flight table override: calibration 0 off / 1 on; -1 = the table's

    std::unique_ptr<MissionScenario> clone() const override { return std::make_unique<CwScenario>(*this); }
};

const MissionSection &impulse_section();

// The boot impulse table a scenario names (imp_default: 0.1 s tick; imp_1s; imp_sub1ms: 1 ms
// valve grid), with its operator override applied. Throws std::invalid_argument for an unknown name.
imp_params_t impulse_boot_table(const std::string &name);
imp_params_t impulse_boot_table(const Scenario &s);

}  // namespace sim

#endif
