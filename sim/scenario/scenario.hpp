// Scenario description (spec 10 §2.4, §6) and its YAML loader.
#ifndef SIM_SCENARIO_SCENARIO_HPP
#define SIM_SCENARIO_SCENARIO_HPP

#include <array>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace sim {

// Thrown for every problem in a scenario file; what() names the file, the key and (when
// yaml-cpp knows it) the line, e.g. "s.yaml: key 'gyro.noise_radps' (line 12): must be >= 0".
class ScenarioError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

struct GyroConfig {
    double noise_radps = 0.0;                 // white noise 1-sigma per sample
    std::array<double, 2> bias_radps{};       // fixed constant bias (y, z)
    double bias_sigma_radps = 0.0;            // extra constant bias drawn once per run from the seed
    std::uint64_t seed = 0u;
    int lsb_shift = 20;                       // LSB = 2^-lsb_shift rad/s
    std::int32_t max_cnt = (1 << 20) - 1;     // full scale, counts; SAT at |count| == max_cnt
    double lsb_radps() const;
};

struct GimbalConfig {
    int lsb_shift = 20;                       // LSB = 2^-lsb_shift rad/s
    double hw_limit_radps = 0.35;             // hardware clip per axis
    double lsb_radps() const;
};

enum class Propagator { Zoh, Ode };

// Flight-side set-up of a SIL run (read by the bridge, never by the plant): the boot table and
// the overrides a ground operator would upload before the run.
struct FswSetup {
    std::string table = "obs_50hz_phys";      // obs_50hz_phys | obs_50hz_paper | obs_5hz_paper | obs_paper_printed
    double k_hat0 = 0.0;                      // K-hat(0) in s^-2; 0 = the table's value
    double bdot_max_degps = 0.0;              // command vector limit; 0 = the table's value
    int cal_enable = -1;                      // plant cw: thrust calibration 0 off / 1 on; -1 = the table's
};

// Link and sensor faults injected by the plant node (spec 00 §8; 10-observer S0-9). Rates are
// integers in parts per million; one seeded stream decides them all (hil_host/fault).
struct FaultSetup {
    std::uint64_t seed = 1u;
    std::uint32_t drop_ppm = 0u, dup_ppm = 0u, reorder_ppm = 0u, reorder_window = 1u;
    std::uint32_t bitflip_ppm = 0u, truncate_ppm = 0u;
    std::array<double, 2> gyro_nan_s{{-1.0, -1.0}};     // [t0, t1): gyro y truth is NaN
    std::array<double, 2> gyro_spike_s{{-1.0, -1.0}};   // [t0, t1): gyro y count = INT32_MAX
    bool any() const;
};

// Lock-step timing (spec 00 §5.2). In the in-process memq driver "no reply yet" is final after
// the queue drains, so there the timeouts only bound the number of re-publications.
struct LockstepSetup {
    std::uint32_t retx_ms = 200u;
    std::uint32_t deadline_ms = 1000u;
    std::uint32_t retx_max = 2u;              // re-publications of one frame before it is missed
};

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

// One telecommand of the scenario's test conductor (gnc::fsw_cmd_t), published by the plant node
// before the first frame at or after t_s. args are already in flight units (steps, counts).
struct ScnCommand {
    double t_s = 0.0;
    std::int32_t cmd = 0;                     // fsw_cmd_t CMD_* (1 MODE, 2 IMP_START, 3 IMP_ABORT, 4 IMP_CLEAR)
    std::array<std::int32_t, 8> args{};
};

struct Scenario {
    std::string name;
    std::string source;                       // file it came from (for messages and logs)
    std::string plant = "sail";
    int sigma = +1;                           // +1 M-phys, -1 M-paper
    double k2_true_per_s2 = 0.01;
    double j_factor = 1.0;
    std::uint32_t period_us = 20000u;
    double duration_s = 120.0;
    std::array<double, 2> w0_radps{};
    std::array<double, 2> mu0_rad{};
    std::array<double, 2> mudot0_radps{};
    GyroConfig gyro;
    GimbalConfig gimbal;
    double mu_max_rad = 0.0;                  // DIVERGED above this |mu| (per axis)
    double w_max_radps = 0.0;                 // DIVERGED above this |w| (per axis)
    Propagator propagator = Propagator::Zoh;
    std::uint32_t ode_substeps = 0u;          // 0: automatic (|lambda|max * h_sub <= 1e-3)
    FswSetup fsw;
    FaultSetup faults;
    LockstepSetup lockstep;
    CwSetup cw;                               // plant "cw" only
    std::vector<ScnCommand> commands;         // in time order

    double h_s() const { return static_cast<double>(period_us) * 1e-6; }
    std::uint64_t n_steps() const;            // round(duration / h)
};

// Built-in defaults (spec 10 §6): M-phys, 50 Hz, w0 = (1, 1) deg/s, no noise, 120 s.
Scenario default_scenario();

// Parse YAML text; source_name is used in error messages.
Scenario parse_scenario(const std::string &yaml_text, const std::string &source_name);
// Load and parse a file; errors name the path.
Scenario load_scenario(const std::string &path);

const char *sigma_name(int sigma);  // "M-phys" / "M-paper"

}  // namespace sim

#endif
