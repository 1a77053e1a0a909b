// batch.hpp — the in-process lock-step driver without a transport: the same plant (the scenario's
// mission section), the same encoded packets (sensor frames sealed with their CRC, commands,
// telemetry), the same bridge core and fsw_step, the same metrics (MetricsTap fed the bytes the LCM
// callbacks would receive) as `sil run` over memq — only the LCM provider and its queue are left out,
// so a long run costs what the plant, the codec and the flight code cost.
//
// A fault-free memq SIL run and a batch run of the same scenario publish identical command and
// telemetry streams (the summary's stream digests): CTest sil_batch_matches_lcm proves it per
// mission. Table files and uploads take the same upload path (sealed chunks through the core, acks to
// the metrics; CTest sil_batch_table_file_matches_memq). Not for runs that need the transport: a
// scenario with faults is refused (std::invalid_argument, nothing flown) — fly it with `sil run`.
#ifndef HIL_SIL_BATCH_HPP
#define HIL_SIL_BATCH_HPP

#include "pil_run.hpp"
#include "sil_run.hpp"

namespace sil {

// The result has the shape of run_inproc's: plant summary, core and mission metrics, bridge
// counters, summary keys (transport "batch"), wall time.
// extra: --upload images, after the scenario's table file (if any).
// pil: fly the flight software on that board instead of in this process (pil_run.hpp); the
// result's board_exit is then the board's verdict (PilRun::finish; 1 when the link went down).
// log_path: write the run's messages to this LCM event log (simulation-time timestamps).
InprocResult run_batch(const sim::Scenario &scn, const std::vector<Upload> &extra = {}, bool progress = false,
                       PilRun *pil = nullptr, const std::string &log_path = std::string());

}  // namespace sil

#endif  // HIL_SIL_BATCH_HPP
