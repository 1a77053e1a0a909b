// Abstract plant (spec 00 §5.1, §5.2): the simulator owns the clock and speaks in integer counts.
//
// One period k, as the lock-step protocol drives it:
//   frame = plant.sense();          // counts sampled at t_k, before command k
//   plant.apply(cmd_k);             // held over [t_k, t_k + h) (and beyond, if no new command)
//   state = plant.propagate();      // t_k -> t_{k+1}; checks the state, may end the run DIVERGED
// No floating-point value crosses the interface except truth telemetry.
#ifndef SIM_PLANT_PLANT_HPP
#define SIM_PLANT_PLANT_HPP

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "scenario/scenario.hpp"

namespace sim {

// Fixed-size channel arrays mirror the LCM types (fixed arrays only, spec 00 §5.1).
constexpr std::size_t kMaxChannels = 16u;

// Per-channel sensor status bits. STALE and SAT have the values and meanings of the wire
// (gnc::sensor_frame_v2_t STATUS_STALE / STATUS_SAT) and of the flight code (FSW_ST_STALE /
// FSW_ST_SAT): one meaning per bit everywhere. NonFinite is the plant's own detail; the plant
// node publishes it as STALE.
constexpr std::uint8_t kStatusStale = 0x01u;      // the sensor delivered no valid sample (dropout, out of range)
constexpr std::uint8_t kStatusSat = 0x02u;        // count at full scale (true value may be beyond it)
constexpr std::uint8_t kStatusNonFinite = 0x04u;  // truth was NaN/Inf; the count is 0 and SAT is also set

struct SensorFrame {
    std::int64_t utime_us = 0;     // t_k
    std::uint32_t seq = 0u;        // k
    std::uint32_t period_us = 0u;
    std::uint32_t n_ch = 0u;
    std::array<std::int32_t, kMaxChannels> cnt{};
    std::array<std::uint8_t, kMaxChannels> status{};
};

struct ActuatorCmd {
    std::uint32_t seq = 0u;        // echoed from the frame it answers
    std::uint32_t n_ch = 0u;
    std::array<std::int32_t, kMaxChannels> cnt{};
};

// Something that happened to the truth but is not visible in counts (e.g. a hardware clip).
struct TruthEvent {
    std::int64_t utime_us = 0;
    std::uint32_t seq = 0u;
    std::string kind;              // "ACT_CLIP", ...
    int channel = 0;
    double requested = 0.0;        // SI value asked for
    double applied = 0.0;          // SI value applied
};

enum class RunState { Running, Done, Diverged };

class Plant {
public:
    virtual ~Plant() = default;
    Plant() = default;
    Plant(const Plant &) = delete;
    Plant &operator=(const Plant &) = delete;

    // Start a run: state, clock (k = 0), noise streams and held command (zero) from the scenario.
    virtual void reset(const Scenario &scn) = 0;
    // Sensor counts at t_k. Advances the noise stream: call once per period.
    virtual SensorFrame sense() = 0;
    // Command to hold from t_k on. Not calling it holds the previous one (a missed command).
    virtual void apply(const ActuatorCmd &cmd) = 0;
    // Advance one period, then check(). A DIVERGED or DONE run no longer advances.
    virtual RunState propagate() = 0;
    // Finite-state and validity check of the current state.
    virtual RunState check() const = 0;

    virtual std::uint32_t seq() const = 0;
    virtual std::int64_t utime_us() const = 0;
    // Truth telemetry in SI units, named by truth_names() (units in the names).
    virtual std::vector<double> truth() const = 0;
    virtual std::vector<std::string> truth_names() const = 0;
    virtual const std::vector<TruthEvent> &events() const = 0;
    // Why the run ended DIVERGED (empty otherwise).
    virtual std::string diverged_reason() const = 0;
    // The truth message's payload (sim_truth_t state[16], extra[8]); each plant documents its
    // layout next to its truth_names(). Analysis only.
    virtual void truth_message(std::array<double, 16> &state, std::array<double, 8> &extra) const = 0;
};

}  // namespace sim

#endif
