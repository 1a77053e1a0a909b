// backend.hpp — where the flight software runs, behind one call (ARCHITECTURE "hil_host").
//
// The bridge core hands a validated frame k to step() and gets command k and the telemetry
// bytes back. InProcessFswBackend (fsw_backend.hpp) runs the flight code in this process (SIL);
// a serial PIL/HIL backend (framed link to a board or QEMU) implements the same interface, so
// the LCM node never changes.
#ifndef HIL_BRIDGE_BACKEND_HPP
#define HIL_BRIDGE_BACKEND_HPP

#include <cstdint>

#include "bridge_types.hpp"
#include "frame_validator.hpp"

namespace bridge {

struct StepOutput {
    std::int16_t n_counts = 0;
    std::int32_t counts[kMaxCounts] = {};
    std::int32_t fsw_mode = 0;
    std::uint32_t fsw_health = 0;
    std::int32_t tlm_layout_version = 0;
    std::int16_t tlm_len = 0;                 // 0..kMaxTlm
    std::uint8_t tlm[kMaxTlm] = {};
};

class Backend {
public:
    virtual ~Backend() = default;
    // (Re)initialise the flight software; true on success.
    virtual bool reset() = 0;
    // One step on frame k. false = the backend could not produce a command (e.g. link down);
    // the bridge then publishes nothing and does not advance its gate.
    virtual bool step(const Frame &f, StepOutput &out) = 0;
    virtual const char *name() const = 0;
    // Host counters the flight software reports in its telemetry (missed, rejected); called by
    // the bridge before every step. Default: not reported.
    virtual void host_counters(const Counters &) {}
    // One table-upload chunk, between steps. false: this backend takes no uploads (the bridge
    // then acks REJECTED itself). ack.result is the loader's verdict.
    virtual bool table_chunk(const TableChunk &, TableAck &) { return false; }
    // One telecommand for the next step (the bridge calls it just before step()). false: this
    // backend takes no such command (the bridge counts cmd_rej).
    virtual bool command(const FswCommand &) { return false; }
    // After a step: true, with the new limits, when the flight software's channel ranges
    // changed in it (a table committed). The bridge applies them from the next frame on.
    virtual bool limits_changed(SensorLimits &) { return false; }
};

}  // namespace bridge

#endif  // HIL_BRIDGE_BACKEND_HPP
