// Scenario description and its YAML loader — the mission-agnostic core (spec 00 §5, §8).
//
// A scenario names the mission it flies (`mission:`, a name from missions.json). The core reads
// what every run has — duration and period, the flight table (a built-in one by name, or a table
// image file uploaded through the flight table path before the first step), link and sensor
// faults, lock-step timing, the test conductor's commands — and hands the rest to the mission's
// section parser (sim/<module>/<module>_section.cpp), which reads its plant, sensors and flight
// overrides into its own MissionScenario. The core never names a mission.
#ifndef SIM_SCENARIO_SCENARIO_HPP
#define SIM_SCENARIO_SCENARIO_HPP

#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <typeinfo>
#include <vector>

namespace YAML {
class Node;
}

namespace sim {

// Thrown for every problem in a scenario file; what() names the file, the key and (when
// yaml-cpp knows it) the line, e.g. "s.yaml: key 'gyro.noise_radps' (line 12): must be >= 0".
class ScenarioError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// A mission's part of a scenario: its plant, sensors and flight-side overrides (sim/<module>).
class MissionScenario {
public:
    virtual ~MissionScenario() = default;
    virtual std::unique_ptr<MissionScenario> clone() const = 0;
};

// Owns a MissionScenario with value semantics: copying a Scenario copies its mission part.
class MissionPart {
public:
    MissionPart() = default;
    explicit MissionPart(std::unique_ptr<MissionScenario> p) : p_(std::move(p)) {}
    MissionPart(const MissionPart &o) : p_(o.p_ ? o.p_->clone() : nullptr) {}
    MissionPart &operator=(const MissionPart &o)
    {
        p_ = o.p_ ? o.p_->clone() : nullptr;
        return *this;
    }
    MissionPart(MissionPart &&) = default;
    MissionPart &operator=(MissionPart &&) = default;

    bool empty() const { return !p_; }
    // The part as the mission's own type; throws std::bad_cast for another mission's scenario.
    template <class T> const T &as() const { return dynamic_cast<const T &>(deref()); }
    template <class T> T &as() { return dynamic_cast<T &>(const_cast<MissionScenario &>(deref())); }

private:
    const MissionScenario &deref() const
    {
        if (!p_) {
            throw std::logic_error("scenario has no mission part");
        }
        return *p_;
    }
    std::unique_ptr<MissionScenario> p_;
};

// Flight-side set-up of a SIL run (read by the bridge, never by the plant).
struct FswSetup {
    std::string table;        // the mission's built-in boot table, by name ("" = its default)
    std::string table_file;   // a table image (ground tools) uploaded before the first step
};

// Link and sensor faults injected by the plant node (spec 00 §8). Rates are integers in parts per
// million; one seeded stream decides them all (hil_host/fault). The sensor windows act on one
// channel of the frame: [t0, t1) a NaN truth (the one SI -> count conversion marks it STALE) or a
// count of INT32_MAX (beyond any sensor range).
struct FaultSetup {
    std::uint64_t seed = 1u;
    std::uint32_t drop_ppm = 0u, dup_ppm = 0u, reorder_ppm = 0u, reorder_window = 1u;
    std::uint32_t bitflip_ppm = 0u, truncate_ppm = 0u;
    std::int64_t flip_frame = -1;      // targeted one-shot flip of bit flip_bit of frame flip_frame's
    std::uint32_t flip_bit = 0u;       //   first transmission (encoded bytes, byte bit/8, bit bit%8)
    std::array<double, 2> nan_s{{-1.0, -1.0}};
    std::uint32_t nan_channel = 0u;
    std::array<double, 2> spike_s{{-1.0, -1.0}};
    std::uint32_t spike_channel = 0u;
    bool any() const;
};

// Lock-step timing (spec 00 §5.2). In the in-process memq driver "no reply yet" is final after
// the queue drains, so there the timeouts only bound the number of re-publications.
struct LockstepSetup {
    std::uint32_t retx_ms = 200u;
    std::uint32_t deadline_ms = 1000u;
    std::uint32_t retx_max = 2u;              // re-publications of one frame before it is missed
};

// One command of the scenario's test conductor (gnc::fsw_cmd_v2_t), published by the plant node
// before the first frame at or after t_s: MODE (cmd 1, args[0] the mode number) or one of the
// mission's telecommands (its namespaced id; args already in flight units).
struct ScnCommand {
    double t_s = 0.0;
    std::string name;                         // MODE, or the telecommand's name (IMP_START)
    std::int32_t cmd = 0;                     // gnc::fsw_cmd_v2_t cmd
    std::array<std::int32_t, 8> args{};
};

struct Scenario {
    std::string name;
    std::string source;                       // file it came from (for messages and logs)
    std::string mission;                      // registered mission name (upper case)
    std::string plant;                        // the mission's plant variant (its default if unset)
    std::uint32_t period_us = 0u;             // the mission's default unless given
    double duration_s = 0.0;
    FswSetup fsw;
    FaultSetup faults;
    LockstepSetup lockstep;
    std::vector<ScnCommand> commands;         // in time order
    MissionPart part;                         // the mission's section

    double h_s() const { return static_cast<double>(period_us) * 1e-6; }
    std::uint64_t n_steps() const;            // round(duration / h)
    template <class T> const T &mission_part() const { return part.as<T>(); }
    template <class T> T &mission_part() { return part.as<T>(); }
};

class Reader;
class Plant;

// What the core needs from a mission (sim/<module>/<module>_section.cpp). One static instance per
// mission; the registry generated from missions.json finds it by name.
class MissionSection {
public:
    virtual ~MissionSection() = default;
    virtual const char *mission() const = 0;                  // its name in missions.json
    // Keys the mission adds to the root, to fsw: and to faults:.
    virtual std::vector<std::string> root_keys() const = 0;
    virtual std::vector<std::string> fsw_keys() const { return {}; }
    virtual std::vector<std::string> fault_keys() const { return {}; }
    // Defaults before the file is read (period, plant variant, boot table).
    virtual void defaults(Scenario &s) const = 0;
    // Reads the mission's keys into s.part (and may check core values against them, e.g. the
    // period against its sensors); errors through r.fail.
    virtual void parse(const YAML::Node &root, const Reader &r, Scenario &s) const = 0;
    // Built-in boot tables by name (the first is the default).
    virtual std::vector<std::string> tables() const = 0;
    // The SIL plant of this scenario.
    virtual std::unique_ptr<Plant> make_plant(const Scenario &s) const = 0;
    // The seed of its sensor noise (reported in the run's control messages).
    virtual std::uint64_t noise_seed(const Scenario &s) const = 0;
};

// Returns the section of a registered mission, nullptr when the name is unknown.
using SectionLookup = std::function<const MissionSection *(const std::string &mission)>;

// Parse YAML text with the given missions; source_name is used in error messages.
Scenario parse_scenario_with(const std::string &yaml_text, const std::string &source_name, const SectionLookup &lookup,
                             const std::vector<std::string> &known);

// The same with the missions of this build (the generated registry, sim/missions.cpp).
Scenario parse_scenario(const std::string &yaml_text, const std::string &source_name);
Scenario load_scenario(const std::string &path);   // errors name the path
const MissionSection &mission_section(const std::string &mission);   // throws std::invalid_argument
std::vector<std::string> mission_names();                            // of this build
std::unique_ptr<Plant> make_plant(const Scenario &scn);

}  // namespace sim

#endif
