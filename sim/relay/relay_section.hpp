// relay_section.hpp — the RELAY mission's part of a scenario (spec 20 §2): a rigid axis with up to
// four undamped elastic modes, the angle sensor in counts and the three-level actuator.
// The scenario core hands it every key it does not own (sim/scenario/scenario.hpp).
//
//   mission: relay
//   plant: relay (the default), period_us (default 1000)
//   relay: {m_u_radps2, m_eps_radps2, xbar0_rad, xbardot0_radps, x_max_rad, abar_from_s,
//           modes: [{omega_radps, k, xt0_rad, xtdot0_radps}, ...],
//           sensor: {noise_rad, bias_rad, seed}, actuator: {scale_error, delay_ticks}}
//   fsw: {table: rly_default | rly_improved | rly_paper | rly_fixed_031 | rly_fixed_03389}
// Defaults: the source's example (spec 20 §2.1), published initial state.
#ifndef SIM_RLY_SECTION_HPP
#define SIM_RLY_SECTION_HPP

#include <cstdint>
#include <memory>
#include <string>

#include "relay/rly_ref.hpp"
#include "scenario/scenario.hpp"

extern "C" {
#include "rly.h"
}

namespace sim {

constexpr double kRelayAngleLsbRad = 1.0 / 16777216.0;   // sensor channel 0: 2^-24 rad
constexpr std::int32_t kRelayAngleMaxCnt = 8388608;       // +-2^23 counts (+-0.5 rad)

struct RelaySetup {
    ref::RelayModel model;                 // m_u, m_eps, modes
    ref::RelayState state0;                // published initial state
    double x_max_rad = 0.5;                // |x| beyond it: DIVERGED
    double noise_rad = 0.0;                // white noise per sample (1 sigma)
    double bias_rad = 0.0;
    std::uint64_t seed = 1u;
    double scale_error = 0.0;              // applied moment = (1 + scale_error) m
    std::uint32_t delay_ticks = 0u;        // 0 or 1: transport delay of the command
    // Metrics only (the plant ignores it): the summary adds the true mean envelope over
    // [abar_from_s, end] (abar_true_from_rad), e.g. 20 000 s for S5/S7's late mean; < 0: not reported.
    double abar_from_s = -1.0;
};

struct RelayScenario final : MissionScenario {
    RelaySetup body;
    std::unique_ptr<MissionScenario> clone() const override { return std::make_unique<RelayScenario>(*this); }
};

const MissionSection &relay_section();

// The boot table a scenario names. Throws std::invalid_argument for an unknown name.
rly_params_t relay_boot_table(const std::string &name);

}  // namespace sim

#endif
