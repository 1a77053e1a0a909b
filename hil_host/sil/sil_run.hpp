// sil_run.hpp — the in-process lock-step driver (spec 00 §5.3): plant node, bridge node with the
// fixed-point flight code (or a mission's double reference), metrics and (optionally) the
// event-log tap on ONE lcm_t, alternated on one thread. With memq:// it is fully deterministic.
// Mission-agnostic: the scenario's mission supplies its plant, boot table, reference and metrics
// (hil_host/missions/<module>).
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

// A table image sent to the flight software through the table upload path. Table id and revision
// are the image header's own (a ground tool writes them), so an upload cannot disagree with them.
struct Upload {
    double t_s = 0.0;                 // published before the first frame at or after t_s
    std::vector<std::uint8_t> image;  // whole image, sent in 256-byte chunks
    std::string what;                 // its origin, for messages (a file name)
};

// An upload of an image file; throws std::invalid_argument with a clear message for a file that
// cannot be read, is empty, or is shorter than a table header.
Upload upload_from_file(const std::string &path, double t_s);

struct InprocOptions {
    std::string url = "memq://";
    std::string fsw = "fixed";        // "fixed", or one of the mission's reference kinds ("ref", ...)
    std::string log_path;             // empty: no log
    std::vector<Upload> uploads;
    bool progress = false;            // progress line on stderr
    // Fly the scenario twice and compare the command and telemetry streams (their digests): the
    // summary's determinism verdict is then that comparison's.
    bool determinism_check = false;
};

struct InprocResult {
    PlantSummary plant;
    CoreMetrics core;
    std::shared_ptr<const host::MissionMetrics> mission;
    bridge::Counters bridge{};
    std::uint64_t log_events = 0;
    double wall_s = 0.0;              // wall clock of the lock-step loop (benchmarks only)
    host::Summary summary;            // plant, bridge, executive and mission keys
    std::string loss_of_control;      // empty: the run kept control (loss_of_control())
    bool determinism_failed = false;  // determinism_check: the two flights' streams differ
    int board_exit = 0;               // PIL (run_batch with a board): the board's exit code, 1 on link down
    // The mission's metrics as its own type (host::ObsMetrics, host::ImpMetrics, ...).
    template <class T> const T &metrics() const { return dynamic_cast<const T &>(*mission); }
};

InprocResult run_inproc(const sim::Scenario &scn, const InprocOptions &opt);

// The fixed-point flight software for a scenario: the executive booted from the mission's boot
// table the scenario names, or without a table when the scenario names a table file (the file
// then arrives by upload before the first step, run_uploads). Throws std::runtime_error naming
// the refusal when the boot table does not load (e.g. its period differs from the scenario's).
std::unique_ptr<bridge::InProcessFswBackend> make_fixed_backend(const sim::Scenario &scn);

// The bridge's sensor limits at the start of a run: the ranges of the table the run flies (the
// table file's when the scenario names one, else the boot table's), checked by the flight loader.
bridge::SensorLimits run_limits(const sim::Scenario &scn);

// The uploads of a run: the scenario's table_file (at t = 0, before the first step) and the extra
// ones given. The table file is first loaded into a scratch copy of the flight software through
// the same upload path: a file the flight loader or the mission's module check refuses is an
// error (std::invalid_argument) that names the file and the reason in words (the field and its
// allowed range), before any run starts.
std::vector<Upload> run_uploads(const sim::Scenario &scn, const std::vector<Upload> &extra);

// Loads an upload into a scratch flight software booted like the run's, through the upload
// path; throws std::invalid_argument naming the file and the loader's reason when it is refused.
void check_upload(const sim::Scenario &scn, const Upload &u);

// The loss-of-control rule (README "Loss of control"): the reason when the run lost control —
// the plant diverged (the mission's validity criterion, sim/<module>), or the plant held one
// command through more consecutive missed commands than lockstep.deadline_ms covers
// (missed_run_bound) — else empty.
std::string loss_of_control(const sim::Scenario &scn, const PlantSummary &p);
// The most consecutive missed commands a run may have: floor(deadline_ms / period).
std::uint64_t missed_run_bound(const sim::Scenario &scn);

// One table image as its table_upload_v2_t messages (256-byte chunks, each sealed), in order.
std::vector<std::vector<std::uint8_t>> upload_messages(const Upload &u, std::int64_t utime_us);
// Publishes them on GNC_TBL_UP.
void publish_upload(lcm_t *lcm, const Upload &u, std::int64_t utime_us);

// The plant's keys, the determinism verdict (same_streams: the result of comparing two
// flights' streams, null when not compared) and the loss-of-control verdict.
void plant_summary(const sim::Scenario &scn, const PlantSummary &p, host::Summary &s,
                   const bool *same_streams = nullptr);
// The head of every summary: scenario, mission, table, flight software, transport.
void run_header(const sim::Scenario &scn, const std::string &fsw, const std::string &url, host::Summary &s);

}  // namespace sil

#endif  // HIL_SIL_RUN_HPP
