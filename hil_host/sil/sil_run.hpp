// sil_run.hpp — the in-process lock-step driver (spec 00 §5.3): plant node, bridge node with the
// fixed-point flight code, metrics and (optionally) the event-log tap on ONE lcm_t, alternated
// on one thread. With memq:// it is fully deterministic.
#ifndef HIL_SIL_RUN_HPP
#define HIL_SIL_RUN_HPP

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "bridge_types.hpp"
#include "fsw_backend.hpp"
#include "metrics.hpp"
#include "plant_node.hpp"
#include "scenario/scenario.hpp"

namespace sil {

struct Upload {
    double t_s = 0.0;                 // published before the first frame at or after t_s
    std::int32_t table_id = 0x0B01;
    std::int32_t revision = 2;
    std::vector<std::uint8_t> image;  // whole image, sent in 256-byte chunks
};

// Which flight software closes the loop: the fixed-point flight code through the executive
// (the product), or the double reference of the observer step (spec 10 S0-8), optionally with
// per-axis command clipping (analysis only, spec 10 S0-9).
enum class FswKind { Fixed, Ref, RefPerAxis };
FswKind fsw_kind(const std::string &name);   // "fixed" | "ref" | "ref-per-axis"; throws otherwise

struct InprocOptions {
    std::string url = "memq://";
    FswKind fsw = FswKind::Fixed;
    std::string log_path;             // empty: no log
    std::vector<Upload> uploads;
    bool progress = false;            // progress line on stderr
};

struct InprocResult {
    PlantSummary plant;
    Metrics metrics;
    bridge::Counters bridge{};
    std::uint64_t log_events = 0;
    double wall_s = 0.0;              // wall clock of the lock-step loop (benchmarks only)
    std::string summary;              // key = value lines (plant, bridge, metrics)
};

InprocResult run_inproc(const sim::Scenario &scn, const InprocOptions &opt);

// The fixed-point flight software for a scenario: the executive with the boot table the
// scenario names (observer for plant sail, impulse scheduler for plant cw). Throws when the
// table's period differs from the scenario's.
std::unique_ptr<bridge::InProcessFswBackend> make_fixed_backend(const sim::Scenario &scn);

// Publishes one table image in chunks on GNC_TBL_UP.
void publish_upload(lcm_t *lcm, const Upload &u, std::int64_t utime_us);

std::string plant_summary(const PlantSummary &p);

// The metrics tap for a scenario (rendezvous metrics for plant cw, at the t_f of its first
// IMP_START command).
void configure_metrics(MetricsTap &mt, const sim::Scenario &scn);

}  // namespace sil

#endif  // HIL_SIL_RUN_HPP
