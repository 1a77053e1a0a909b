// respin_section.hpp — the RESPIN mission's part of a scenario (spec 30 §2): the rigid gyrostat
// (principal inertia, initial total momentum g0 along g_dir or a seeded random direction, H(0) = 0),
// its three reaction wheels, the rate gyro and wheel-speed sensors in counts.
// The scenario core hands it every key it does not own (sim/scenario/scenario.hpp).
//
//   mission: respin
//   plant: respin (the default), period_us (default 100000)
//   respin: {g0_nms, g_dir: [x, y, z] | g_dir_seed, inertia_kgm2: [Jx, Jy, Jz], omega_max_radps,
//            n_sub, elastic: none | E1 | E2,
//            wheel: {iw_kgm2, torque_max_nm, h_max_nms, coulomb_nm, viscous_nmps},
//            gyro: {noise_radps, bias_radps: [x, y, z], scale_ppm: [x, y, z], seed}}
//   fsw: {table: rsp_default | rsp_printed | rsp_ts05 (Ts = 0.5 s: period_us 500000)}
// Defaults: spec 30 §2 (J = diag(2900, 3600, 670), I_w = 0.01, 0.15 N m, 5 N m s, no friction),
// g0 = 300 N m s along e_z, RK4 with n_sub = 4 steps per tick, ideal gyro (no noise, bias, scale).
// g_dir is normalised; g_dir_seed (mutually exclusive with g_dir) draws a uniform direction.
// Sensor faults are the scenario core's (faults: nan_s / nan_channel, spike_s / spike_channel on
// channels 0..5, injected by the plant node), link faults likewise: the plant adds none of its own.
#ifndef SIM_RSP_SECTION_HPP
#define SIM_RSP_SECTION_HPP

#include <array>
#include <cstdint>
#include <memory>
#include <string>

#include "respin/rsp_ref.hpp"
#include "scenario/scenario.hpp"

extern "C" {
#include "rsp.h"
}

namespace sim {

// Channels (fsw/respin/rsp_iface.py). Sensors 0..2 gyro, 3..5 wheel speed; actuators 0..2 wheel
// motor torque command (= -M).
constexpr double kRespinRateLsbRadps = ref::kRspGyroLsbRadps;       // sensors 0..2: 2^-22 rad/s
constexpr double kRespinWhlSpeedLsbRadps = ref::kRspWhlLsbRadps;    // sensors 3..5: 2^-10 rad/s
constexpr double kRespinTorqueLsbNm = ref::kRspTorqueLsbNm;         // actuators 0..2: 2^-17 N m
constexpr std::int32_t kRespinGyroMaxCnt = ref::kRspGyroMaxCnt;     // +-2^22 counts, SAT at full scale
constexpr std::int32_t kRespinWhlSpeedMaxCnt = ref::kRspWhlMaxCnt;  // +-600 rad/s
constexpr std::uint32_t kRespinSensorChannels = 6u;
constexpr std::uint32_t kRespinActuatorChannels = 3u;

struct RespinSetup {
    std::array<double, 3> j_kgm2{{2900.0, 3600.0, 670.0}};   // principal inertia, y the major axis
    double iw_kgm2 = 0.01;                           // wheel rotor inertia
    double torque_max_nm = 0.15;                     // motor torque limit
    double h_max_nms = 5.0;                          // hard momentum limit per wheel
    double coulomb_nm = 0.0;                         // bearing friction (fault tests; default none)
    double viscous_nmps = 0.0;                       // N m per rad/s of wheel speed
    double g0_nms = 300.0;                           // |G|
    std::array<double, 3> g_dir{{0.0, 0.0, 1.0}};    // direction of G(0) in body axes (normalised)
    bool g_dir_random = false;                       // draw g_dir from g_dir_seed instead
    std::uint64_t g_dir_seed = 1u;
    double omega_max_radps = 1.0;                    // |omega| beyond it: DIVERGED (the gyro range)
    int n_sub = 4;                                   // RK4 steps per tick (h = Ts / n_sub)
    std::string elastic;                             // modal set (spec 30 §2): "" rigid, "E1", "E2"
    double gyro_noise_radps = 0.0;                   // white noise per sample (1 sigma)
    std::array<double, 3> gyro_bias_radps{{0.0, 0.0, 0.0}};
    std::array<double, 3> gyro_scale_ppm{{0.0, 0.0, 0.0}};
    std::uint64_t gyro_seed = 1u;
};

struct RespinScenario final : MissionScenario {
    RespinSetup body;
    std::unique_ptr<MissionScenario> clone() const override { return std::make_unique<RespinScenario>(*this); }
};

const MissionSection &respin_section();

// The RESPIN setup of a scenario (throws std::bad_cast for another mission's scenario).
const RespinSetup &respin_setup(const Scenario &s);
// The gyrostat model a setup flies (ref::gyrostat_tick).
ref::GyrostatModel respin_model(const RespinSetup &b);

// The boot table a scenario names (rsp_default, rsp_printed, rsp_ts05). Throws std::invalid_argument for an
// unknown name.
rsp_params_t respin_boot_table(const std::string &name);

// The initial direction of G a setup flies (g_dir normalised, or the seeded random draw).
std::array<double, 3> respin_initial_direction(const RespinSetup &b);

}  // namespace sim

#endif
