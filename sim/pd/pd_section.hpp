// pd_section.hpp — the HOLD mission's part of a scenario: a rigid body about one axis
// (inertia, initial rate, constant disturbance torque), its rate gyro and its torque actuator.
// The scenario core hands it every key it does not own (sim/scenario/scenario.hpp).
//
//   mission: hold
//   plant: pd (the default), period_us (default 100000)
//   pd: {inertia_kgm2, w0_radps, torque_dist_nm, w_max_radps,
//            gyro: {noise_radps, bias_radps, max_cnt, seed}, actuator: {max_nm}}
//   fsw: {table: pd_default}
#ifndef SIM_PD_SECTION_HPP
#define SIM_PD_SECTION_HPP

#include <cstdint>
#include <memory>
#include <string>

#include "scenario/scenario.hpp"

extern "C" {
#include "pd.h"
}

namespace sim {

constexpr double kPdRateLsbRadps = 1.0 / 1048576.0;    // sensor channel 0: 2^-20 rad/s
constexpr double kPdTorqueLsbNm = 1.0 / 65536.0;       // actuator channel 0: 2^-16 N m

struct PdSetup {
    double inertia_kgm2 = 10.0;
    double w0_radps = 0.2;                    // body rate at t = 0
    double torque_dist_nm = 0.0;              // constant disturbance torque
    double w_max_radps = 10.0;                // beyond it the run is DIVERGED
    double gyro_noise_radps = 0.0;            // white noise per sample (1 sigma)
    double gyro_bias_radps = 0.0;
    std::int32_t gyro_max_cnt = 524288;       // full scale (0.5 rad/s); the count clips there (SAT)
    std::uint64_t gyro_seed = 1u;
    double act_max_nm = 1.0;                  // hardware torque limit (clip, a TruthEvent)
};

struct PdScenario final : MissionScenario {
    PdSetup body;
    std::unique_ptr<MissionScenario> clone() const override { return std::make_unique<PdScenario>(*this); }
};

const MissionSection &pd_section();

// The boot table a scenario names (pd_default). Throws std::invalid_argument for an unknown name.
pd_params_t pd_boot_table(const std::string &name);

}  // namespace sim

#endif
