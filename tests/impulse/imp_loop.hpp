// Host closed loop of the impulse scheduler against the CW plant (no LCM): the fixed-point
// module (fsw/impulse) or the double reference FSW (sim/impulse ref::ImpFsw), with the same
// imp_in_t / imp_out_t. Used by the A4-4 ... A4-7 tests.
//
// Time origin: plant time 0 is the START step (step 0); t0 = plan_lead steps later, and the
// plant starts at Phi(-t0) X0 so that its state at t0 is exactly X0 (the paper's example is then
// flown as printed: X0 at t0, T = t_f - t0 = 1055 s). Fault and dropout times are plant times.
#ifndef TESTS_IMPULSE_IMP_LOOP_HPP
#define TESTS_IMPULSE_IMP_LOOP_HPP

#include <array>
#include <cstdint>
#include <vector>

#include "impulse/cw_plant.hpp"
#include "impulse/imp_ref_fsw.hpp"

extern "C" {
#include "imp.h"
#include "imp_tables.h"
}

namespace imploop {

using Vec6 = sim::CwPlant::Vec6;

struct Cfg {
    imp_params_t p = IMP_TBL_DEFAULT;
    sim::CwConfig plant;                  // period_us is taken from p
    Vec6 x0 = Vec6::Zero();               // state at t0 [m, m/s]
    double T = 1055.0;                    // t_f - t0 [s]
    bool use_ref = false;                 // fly the reference FSW instead of the flight code
    std::uint8_t avail = 0x3Fu;
    std::int64_t start_step = 0;          // START command at this step (-1: never)
    std::uint32_t t0_override = 0;        // t0 step (0: start_step + plan_lead)
    std::uint32_t tf_override = 0;        // t_f step (0: t0 + T / h)
    bool keep_trace = false;              // record per-step masks and health
};

struct Out {
    Vec6 xf = Vec6::Zero();               // plant state at t_f
    double mr = 0, mv = 0;                // |dR| [m], |dV| [m/s] at t_f
    double dv = 0;                        // delta-v delivered [m/s]
    std::array<double, 6> dv_j{};
    double plan_dv = 0;                   // the open-loop plan's delta-v (double reference solver) [m/s]
    unsigned mode = 0;                    // final mode
    std::uint32_t health_or = 0;          // OR of every step's health
    std::uint32_t fx_or = 0;              // OR of every step's fx status bits (health 0..7)
    std::uint32_t st_sticky = 0;          // flight code: sticky fx status at the end
    std::uint32_t plans = 0, failed = 0, late = 0, skipped = 0, nav_rej = 0, cal_rej = 0, cmd_rej = 0;
    std::uint32_t violations = 0, short_burns = 0, interlock_steps = 0;
    std::uint32_t accepted = 0;           // flight code: accepted plans seen finishing
    std::int32_t fres_max = 0;            // flight code: largest final |F| of an accepted plan [LSB]
    std::int64_t k_stuck_off = -1, k_stuck_on = -1, k_thrust_level = -1, k_nav_stale = -1,
                 k_expected_miss = -1, k_abort = -1, k_first_on = -1, k_last_on = -1;
    std::int64_t k_second_burn = -1;      // earliest second-burn start of the START timeline
    bool on_after_abort = false;
    unsigned stuck_j = 0xFF;
    std::array<double, 6> alpha{};
    std::uint32_t t0 = 0, tf = 0;
    std::uint32_t crc = 0;                // CRC-32 of every step's outputs (determinism)
    imp_tlm_t tlm{};                      // last telemetry
    std::vector<std::uint8_t> masks;      // keep_trace
    std::vector<std::uint32_t> healths;
};

// The paper's example (spec 50 §3.4) at t0.
Vec6 example_x0();
// A seeded random state of the nominal box (+-5 km, +-1 m/s per component), project generator.
Vec6 random_x0(std::uint64_t seed, double pos = 5000.0, double vel = 1.0);

Out fly(const Cfg &c);

// Order statistics of a sample (nearest rank): median and p95.
double quantile(std::vector<double> v, double q);

}  // namespace imploop

#endif  // TESTS_IMPULSE_IMP_LOOP_HPP
