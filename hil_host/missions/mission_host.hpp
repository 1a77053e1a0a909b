// mission_host.hpp — what the host side needs from a mission, behind one interface, and the
// shared helpers every mission's host class uses (README "Design: one module, one folder").
//
// Each registered mission has one MissionHost in hil_host/missions/<module>/<module>_host.cpp:
// its boot table image for a scenario, its double-precision reference backend, its SIL metrics.
// The registry generated from missions.json (host_missions_gen.cpp) finds it by name, so the
// bridge core, the SIL runner and the summary writer never name a mission. Names and telemetry
// layouts come from the generated iface tables (tools/iface), never from parsing C.
#ifndef HIL_MISSIONS_MISSION_HOST_HPP
#define HIL_MISSIONS_MISSION_HOST_HPP

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "backend.hpp"
#include "iface_gen.hpp"
#include "scenario/scenario.hpp"

extern "C" {
#include "fsw_exec.h"
}

namespace gnc {
class sim_truth_t;
class actuator_cmd_v2_t;
}  // namespace gnc

namespace host {

// ------------------------------------------------------------------------- telemetry layouts

// A mission's telemetry layout as the host reads it (from the generated iface tables).
struct TlmLayout {
    const iface::Mission *m = nullptr;
    std::vector<std::string> names;
    std::vector<char> types;                      // 'b' u8, 'h' u16, 'u' u32, 'i' i32, 'q' i64
    std::vector<int> q;                           // fraction bits, -1 for none
    std::size_t bytes = 0;
    std::map<std::string, std::size_t> idx;
    // Index of a field; throws std::out_of_range naming the field and the mission.
    std::size_t at(const std::string &name) const;
};

const iface::Mission &iface_mission(const std::string &name);          // throws std::invalid_argument
const iface::Mission *iface_by_layout(std::uint32_t layout_version);   // nullptr when unknown
const TlmLayout &tlm_layout(const iface::Mission &m);                  // built once per mission
// Raw values of one encoded telemetry in its layout; false when the length or bytes do not fit.
bool decode_tlm(const TlmLayout &l, const std::uint8_t *buf, std::size_t len, std::vector<std::int64_t> &v);
// "0x00001240 (MEAS_SKIP K_CLAMP_LO)" for a health word: fx bits 0..7, then the names given.
std::string bits_str(std::uint32_t word, const iface::Name *names, std::size_t n);
std::string mode_name(const iface::Mission &m, std::uint32_t mode);

// A table reason word in words: "RANGE_HI: field 8 (bdot_max_q29) above its allowed [1, 4096]",
// using the mission's table field names and the flight loader's own descriptor for the range.
std::string describe_reason(const iface::Mission &m, std::uint32_t reason);

// ----------------------------------------------------------------------------- summaries

// Ordered key = value lines of a run (summary.txt) and the same as JSON (summary.json, which the
// Python report reads instead of re-deriving the metrics).
class Summary {
public:
    void add(const std::string &key, double v, const char *fmt = "%.6g");
    void add_int(const std::string &key, std::int64_t v);
    void add_hex(const std::string &key, std::uint32_t v);
    void add_str(const std::string &key, const std::string &v);
    std::string text() const;
    std::string json() const;
    bool has(const std::string &key) const;
    double number(const std::string &key) const;   // throws std::out_of_range

private:
    struct Item {
        std::string key, text;
        bool numeric = false;
        double value = 0.0;
        bool integer = false;
        std::int64_t ivalue = 0;
    };
    std::vector<Item> items_;
};

// ------------------------------------------------------------------------------- metrics

// A mission's part of the live SIL metrics (truth, commands and its decoded telemetry).
class MissionMetrics {
public:
    virtual ~MissionMetrics() = default;
    virtual void on_truth(const gnc::sim_truth_t &t) = 0;
    virtual void on_cmd(const gnc::actuator_cmd_v2_t &c) = 0;
    // v: the telemetry of step k in the mission's layout (tlm_layout(m)); t_s its sample time.
    virtual void on_tlm(const std::vector<std::int64_t> &v, double t_s) = 0;
    virtual void summary(Summary &s) const = 0;
};

// ---------------------------------------------------------------------------- the mission

class MissionHost {
public:
    virtual ~MissionHost() = default;
    virtual const iface::Mission &iface() const = 0;
    // The boot table image a scenario names (built-in table with the scenario's overrides),
    // revision 1; throws std::invalid_argument for a table that does not exist.
    virtual std::vector<std::uint8_t> boot_image(const sim::Scenario &s) const = 0;
    // Consecutive invalid steps before SAFE (fsw_cfg_t.stale_max).
    virtual std::uint16_t stale_max() const { return 250u; }
    // The double-precision reference flight software flying the table image `image` (its kinds:
    // "ref", and for the observer "ref-per-axis").
    virtual std::vector<std::string> ref_kinds() const = 0;
    virtual std::unique_ptr<bridge::Backend> make_ref(const sim::Scenario &s, const std::string &kind,
                                                      const std::vector<std::uint8_t> &image) const = 0;
    virtual std::unique_ptr<MissionMetrics> make_metrics(const sim::Scenario &s) const = 0;
};

// The host class of a mission of this build; throws std::invalid_argument naming the missions.
const MissionHost &mission_host(const std::string &mission);

// The executive's configuration for a scenario: its mission, period and the mission mode at boot.
fsw_cfg_t fsw_cfg(const sim::Scenario &s);

// The payload of a table image after its 16-byte header (for the reference backends, which
// decode it with the flight's own decoder); throws std::invalid_argument when too short.
std::pair<const std::uint8_t *, std::uint32_t> image_payload(const std::vector<std::uint8_t> &image);
std::uint32_t image_revision(const std::vector<std::uint8_t> &image);

}  // namespace host

#endif  // HIL_MISSIONS_MISSION_HOST_HPP
