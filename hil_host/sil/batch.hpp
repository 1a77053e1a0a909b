// batch.hpp — the in-process lock-step driver without a transport: the same plant (the scenario's
// mission section), the same encoded packets (sensor frames sealed with their CRC, commands,
// telemetry), the same bridge core and fsw_step, the same metrics (MetricsTap fed the bytes the LCM
// callbacks would receive) as `sil run` over memq — only the LCM provider and its queue are left out,
// so a long run costs what the plant, the codec and the flight code cost.
//
// A fault-free memq SIL run and a batch run of the same scenario publish identical command and
// telemetry streams (the summary's stream digests): CTest sil_batch_matches_lcm proves it per
// mission. Not for runs that need the transport: a scenario with faults, an upload or a table file
// is refused (std::invalid_argument, nothing flown) — fly those with `sil run`.
#ifndef HIL_SIL_BATCH_HPP
#define HIL_SIL_BATCH_HPP

#include "sil_run.hpp"

namespace sil {

// The result has the shape of run_inproc's: plant summary, core and mission metrics, bridge
// counters, summary keys (transport "batch"), wall time.
InprocResult run_batch(const sim::Scenario &scn, bool progress = false);

}  // namespace sil

#endif  // HIL_SIL_BATCH_HPP
