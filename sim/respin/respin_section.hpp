// respin_section.hpp — the RESPIN mission's part of a scenario (spec 30 §2): the rigid gyrostat
// (principal inertia, initial total momentum g0 along g_dir or a seeded random direction), its
// momentum actuator — three reaction wheels (H(0) = 0) or the four-gyrodine cluster (H(0) =
// H(beta0), 0 at the null configuration) — the rate gyro, wheel-speed, gimbal-angle and rotor-speed
// sensors in counts. The scenario core hands it every key it does not own (sim/scenario/scenario.hpp).
//
//   mission: respin
//   plant: respin (the default), period_us (default 100000)
//   respin: {g0_nms, g_dir: [x, y, z] | g_dir_seed, inertia_kgm2: [Jx, Jy, Jz], omega_max_radps,
//            n_sub, elastic: none | E1 | E2, actuator: wheels | gyrodines,
//            wheel: {iw_kgm2, torque_max_nm, h_max_nms, coulomb_nm, viscous_nmps},     (wheels only)
//            cmg: {hg_nms, umax_radps, beta0_rad: [b1, b2, b3, b4], rotor_speed_radps,  (gyrodines only)
//                  rotor_fault: {t_s, index, scale}},
//            gyro: {noise_radps, bias_radps: [x, y, z], scale_ppm: [x, y, z], seed}}
//   fsw: {table: rsp_default | rsp_printed | rsp_ts05 (Ts = 0.5 s: period_us 500000) | rsp_cmg ...}
// Defaults: spec 30 §2 (J = diag(2900, 3600, 670), I_w = 0.01, 0.15 N m, 5 N m s, no friction;
// gyrodines h_g = 7.5 N m s, u_max = 0.1745 rad/s, beta0 = (pi/4, pi/4, -pi/4, -pi/4), rotors at
// 600 rad/s), actuator wheels, g0 = 300 N m s along e_z, RK4 with n_sub = 4 steps per tick, ideal
// gyro (no noise, bias, scale). g_dir is normalised; g_dir_seed (mutually exclusive with g_dir)
// draws a uniform direction. rotor_fault (all three keys): from t_s on, rotor index (0..3) has, and
// reads, scale times its nominal momentum and speed. The boot table's actuator kind (act_kind) must
// be the scenario's actuator (a built-in table is checked; a table_file is the flight's to judge).
// Sensor faults are the scenario core's (faults: nan_s / nan_channel, spike_s / spike_channel on
// channels 0..5, injected by the plant node), link faults likewise: the plant adds none of its own.
#ifndef SIM_RSP_SECTION_HPP
#define SIM_RSP_SECTION_HPP

#include <array>
#include <cstdint>
#include <memory>
#include <string>

#include "respin/rsp_cmg_ref.hpp"
#include "respin/rsp_ref.hpp"
#include "scenario/scenario.hpp"

extern "C" {
#include "rsp.h"
}

namespace sim {

// Channels (fsw/respin/rsp_iface.py), the superset for both actuator kinds: sensors 0..2 gyro,
// 3..5 wheel speed, 6..9 gimbal angle of gyrodine 1..4, 10..13 rotor speed of gyrodine 1..4;
// actuators 0..2 wheel motor torque command (= -M), 3..6 gimbal rate command of gyrodine 1..4.
constexpr double kRespinRateLsbRadps = ref::kRspGyroLsbRadps;       // sensors 0..2: 2^-22 rad/s
constexpr double kRespinWhlSpeedLsbRadps = ref::kRspWhlLsbRadps;    // sensors 3..5: 2^-10 rad/s
constexpr double kRespinGimbalLsbRad = ref::kCmgEncLsbRad;          // sensors 6..9: 2 pi / 2^20 rad
constexpr std::uint32_t kRespinGimbalCounts = ref::kCmgEncCounts;   // one turn: counts in [0, 2^20)
constexpr double kRespinRotorLsbRadps = 1.0 / 256.0;                // sensors 10..13: 2^-8 rad/s
constexpr double kRespinTorqueLsbNm = ref::kRspTorqueLsbNm;         // actuators 0..2: 2^-17 N m
constexpr double kRespinGimbalRateLsbRadps = ref::kCmgRateLsbRadps; // actuators 3..6: 2^-16 rad/s
constexpr std::int32_t kRespinGyroMaxCnt = ref::kRspGyroMaxCnt;     // +-2^22 counts, SAT at full scale
constexpr std::int32_t kRespinWhlSpeedMaxCnt = ref::kRspWhlMaxCnt;  // +-600 rad/s
constexpr std::int32_t kRespinRotorMaxCnt = 16777216;               // 2^24 counts = 65 536 rad/s (SAT)
constexpr std::int32_t kRespinGimbalRateLimitCnt = 11437;           // u_max = 0.1745 rad/s, rounded up
constexpr std::uint32_t kRespinChGyro = 0u, kRespinChWhlSpeed = 3u, kRespinChGimbal = 6u, kRespinChRotor = 10u;
constexpr std::uint32_t kRespinActTorque = 0u, kRespinActGimbalRate = 3u;
constexpr std::uint32_t kRespinSensorChannels = 14u;
constexpr std::uint32_t kRespinActuatorChannels = 7u;

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
    bool gyrodines = false;                          // actuator: false wheels, true the gyrodine cluster
    double cmg_hg_nms = 7.5;                         // rotor momentum h_g
    double cmg_umax_radps = 0.1745;                  // gimbal rate limit (the plant clips to it)
    std::array<double, 4> cmg_beta0_rad{{ref::kRspCmgNullRad, ref::kRspCmgNullRad, -ref::kRspCmgNullRad,
                                         -ref::kRspCmgNullRad}};   // null configuration: H(0) = 0
    double cmg_rotor_speed_radps = 600.0;            // nominal rotor speed (the rotor-speed sensor)
    bool rotor_fault = false;                        // from rotor_fault_t_s on, rotor rotor_fault_index
    double rotor_fault_t_s = 0.0;                    // has and reads rotor_fault_scale times nominal
    std::uint32_t rotor_fault_index = 0u;
    double rotor_fault_scale = 1.0;
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
