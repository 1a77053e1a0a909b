// pd_section.hpp — the HOLD mission's part of a scenario (spec 40 §2.6, §7, §8): the gyrodine plant
// (single channels or the coupled three-channel plant), its frequency schedule, disturbances, the
// attitude sensors and encoders, and the torque actuators. The scenario core hands it every key it
// does not own (sim/scenario/scenario.hpp); unknown keys are refused, every number range-checked.
//
//   mission: hold
//   plant: pd (the only variant; period_us 250000, the only period: Ty = 0.25 s, spec 40 §2.4)
//   pd:
//     plant: single | coupled           default single (§2.2 x 3 | §2.1)
//     coupling_sign: 1 | -1             coupled only; sign of the a Ib body-gimbal cross terms
//     scale: {coupling, ix, h}          true-plant I_i, Ix, H multipliers, each [0.5, 2] (default 1);
//                                       refused when a channel's mass matrix is not positive definite
//     latency_samples: 0 | 1            extra actuator delay: a command received at sample k acts
//                                       over [t_{k+1}, t_{k+2})
//     f_hz: 0.03                        f_min [Hz], [0.005, 0.2]
//     f_steps: [{t_s, f_hz}, ...]       piecewise constant, strictly increasing t_s; switches at the
//                                       first sample boundary at or after t_s (state continuous)
//     x0_rad: [yaw, roll, pitch]        default [0, 0, 0.017], each [-1, 1]; all other states 0
//     kicks: [{t_s, dx_rad: [y, r, p]}] x += dx at the first sample boundary at or after t_s
//                                       (non-decreasing t_s; dx each [-1, 1])
//     sensor: {noise_rad: 2e-6 | [y, r, p] ([0, 0.01]), bias_rad: [y, r, p] ([-0.1, 0.1]),
//              seed: 1, frozen: [{t0_s, t1_s, channel}], offset: [{t0_s, t1_s, channel, rad}]}
//              channel: the attitude channel 0..2 (yaw, roll, pitch); windows [t0_s, t1_s) on the
//              sample time; offset rad in [-10, 10] (a large one leaves the range: SAT)
//     actuator: {max_nm: 2.0}           torque limit M_max [N m], [1e-3, 100]
//   fsw: {table: pd_default}
#ifndef SIM_PD_SECTION_HPP
#define SIM_PD_SECTION_HPP

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "scenario/scenario.hpp"

extern "C" {
#include "pd.h"
}

namespace sim {

// ---- the channel contract (fixed; the flight code is written against it) --------------------------
constexpr std::uint32_t kPdPeriodUs = 250000u;                    // Ty = 0.25 s
constexpr std::uint32_t kPdSensorChannels = 6u;
constexpr std::uint32_t kPdChAtt = 0u;                            // 0..2 attitude yaw, roll, pitch
constexpr std::uint32_t kPdChEnc = 3u;                            // 3..5 gimbal encoder yaw, roll, pitch
constexpr double kPdAttLsbRad = 1.0 / 67108864.0;                 // 2^-26 rad
constexpr std::int32_t kPdAttMaxCnt = 33554432;                   // round(0.5 rad / 2^-26) = 2^25: SAT
constexpr double kPdEncLsbRad = 1.0 / 16777216.0;                 // 2^-24 rad
constexpr std::int32_t kPdEncMaxCnt = 52707179;                   // round(pi / 2^-24): SAT
constexpr std::uint32_t kPdActuatorChannels = 3u;                 // 0..2 gimbal torque yaw, roll, pitch
constexpr double kPdTorqueLsbNm = 1.0 / 1048576.0;                // 2^-20 N m
// The template placeholder's rate-gyro LSB, still named by hil_host/missions/pd (the placeholder
// reference backend) until that is rewritten; no channel of this plant has this unit.
constexpr double kPdRateLsbRadps = 1.0 / 1048576.0;

enum class PdPlantKind { Single, Coupled };

struct PdFStep {
    double t_s = 0.0;
    double f_hz = 0.03;
};

struct PdKick {
    double t_s = 0.0;
    std::array<double, 3> dx_rad{{0.0, 0.0, 0.0}};
};

// A sensor window on attitude channel `channel` over sample times [t0_s, t1_s).
struct PdWindow {
    double t0_s = 0.0, t1_s = 0.0;
    std::uint32_t channel = 0u;
    double rad = 0.0;   // offset windows only
};

struct PdSetup {
    PdPlantKind kind = PdPlantKind::Single;
    int coupling_sign = 1;
    double scale_coupling = 1.0, scale_ix = 1.0, scale_h = 1.0;
    std::uint32_t latency_samples = 0u;
    double f_hz = 0.03;
    std::vector<PdFStep> f_steps;                     // strictly increasing t_s
    std::array<double, 3> x0_rad{{0.0, 0.0, 0.017}};
    std::vector<PdKick> kicks;                        // non-decreasing t_s
    std::array<double, 3> noise_rad{{2e-6, 2e-6, 2e-6}};
    std::array<double, 3> bias_rad{{0.0, 0.0, 0.0}};
    std::uint64_t sensor_seed = 1u;
    std::vector<PdWindow> frozen, offset;
    double act_max_nm = 2.0;
};

struct PdScenario final : MissionScenario {
    PdSetup body;
    std::unique_ptr<MissionScenario> clone() const override { return std::make_unique<PdScenario>(*this); }
};

const MissionSection &pd_section();

// The boot table a scenario names (pd_default). Throws std::invalid_argument for an unknown name.
pd_table_t pd_boot_table(const std::string &name);

}  // namespace sim

#endif
