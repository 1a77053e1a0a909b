// observer_section.hpp — the DETUMBLE mission's part of a scenario (spec 10 §2.4, §6): the sail
// platform (model, stiffness, initial state, validity limits, propagator), its rate gyros and
// gimbal-rate actuators, and the operator overrides of the boot table. The scenario core hands
// it every key it does not own (sim/scenario/scenario.hpp).
//
//   mission: detumble
//   model: M-phys | M-paper, sigma: +1 | -1 (both required, and they must agree)
//   k2_true_per_s2, j_factor, w0_degps [y, z], mu0_deg, mudot0_degps, propagator: zoh | ode,
//   ode_substeps, gyro: {noise_radps, bias_radps, bias_sigma_radps, seed, lsb_shift, max_cnt,
//         glitch_s, glitch_channel, glitch_bit},
//   gimbal: {lsb_shift, hw_limit_radps}, limits: {mu_max_deg, w_max_degps},
//   fsw: {table: obs_50hz_phys | obs_50hz_paper | obs_5hz_paper | obs_paper_printed,
//         k_hat0, bdot_max_degps}
#ifndef SIM_OBSERVER_SECTION_HPP
#define SIM_OBSERVER_SECTION_HPP

#include <array>
#include <cstdint>
#include <memory>

#include "scenario/scenario.hpp"

extern "C" {
#include "obs.h"
}

namespace sim {

struct GyroConfig {
    double noise_radps = 0.0;                 // white noise 1-sigma per sample
    std::array<double, 2> bias_radps{};       // fixed constant bias (y, z)
    double bias_sigma_radps = 0.0;            // extra constant bias drawn once per run from the seed
    std::uint64_t seed = 0u;
    int lsb_shift = 20;                       // LSB = 2^-lsb_shift rad/s
    std::int32_t max_cnt = (1 << 20) - 1;     // full scale, counts; SAT at |count| == max_cnt
    // One wild but in-range sample from the sensor itself (a single-event upset in the gyro's
    // output register): the sample at t = glitch_s (the step nearest it) has bit glitch_bit of
    // the two's-complement count of glitch_channel flipped. Off when glitch_s < 0.
    double glitch_s = -1.0;
    std::uint32_t glitch_channel = 0u;
    std::uint32_t glitch_bit = 19u;
    double lsb_radps() const;
};

struct GimbalConfig {
    int lsb_shift = 20;                       // LSB = 2^-lsb_shift rad/s
    double hw_limit_radps = 0.35;             // hardware clip per axis
    double lsb_radps() const;
};

enum class Propagator { Zoh, Ode };

struct SailScenario final : MissionScenario {
    int sigma = +1;                           // +1 M-phys, -1 M-paper
    double k2_true_per_s2 = 0.01;
    double j_factor = 1.0;
    std::array<double, 2> w0_radps{};
    std::array<double, 2> mu0_rad{};
    std::array<double, 2> mudot0_radps{};
    GyroConfig gyro;
    GimbalConfig gimbal;
    double mu_max_rad = 0.0;                  // DIVERGED above this |mu| (per axis)
    double w_max_radps = 0.0;                 // DIVERGED above this |w| (per axis)
    Propagator propagator = Propagator::Zoh;
    std::uint32_t ode_substeps = 0u;          // 0: automatic (|lambda|max * h_sub <= 1e-3)
    // Operator overrides of the boot table (fsw:), 0 = the table's value.
    double k_hat0 = 0.0;                      // K-hat(0) in s^-2
    double bdot_max_degps = 0.0;              // command vector limit

    std::unique_ptr<MissionScenario> clone() const override { return std::make_unique<SailScenario>(*this); }
};

const MissionSection &observer_section();

// Built-in defaults (spec 10 §6): DETUMBLE, M-phys, 50 Hz, w0 = (1, 1) deg/s, no noise, 120 s.
Scenario sail_default_scenario();
const char *sigma_name(int sigma);            // "M-phys" / "M-paper"

// The boot observer table a scenario names, with its operator overrides applied. Throws
// std::invalid_argument for an unknown name or an override that does not fit its Q format.
obs_params_t observer_boot_table(const std::string &name, double k_hat0_per_s2 = 0.0, double bdot_max_degps = 0.0);
obs_params_t observer_boot_table(const Scenario &s);

}  // namespace sim

#endif
