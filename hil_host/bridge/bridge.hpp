// bridge.hpp — the transport-independent bridge core: gate + validator + backend.
//
// The LCM node is a thin shell: on a GNC_SENSOR message it calls on_bytes() (or on_frame()),
// then publishes reply.cmd when reply.publish_cmd and reply.tlm when reply.publish_tlm.
//
//   decode fails / header malformed  -> malformed++, nothing published, gate unchanged
//   crc32 does not match the bytes   -> crc_rej++, nothing published, gate unchanged
//   utime != seq * period_us         -> time_rej++, nothing published, gate unchanged
//   seq beyond last + kMaxSeqJump    -> jump_rej++, nothing published (seq_gate.hpp: the window
//                                       and the deliberate resynchronisation, resyncs++)
// Every refusal leaves the gate as it was and publishes nothing, so the plant re-sends the frame
// after retx_ms (spec 00 §5.2): one corrupted transmission costs one re-send, not the loop.
//   Stale                            -> stale++, nothing published
//   Duplicate                        -> dups++, cached command re-published (no telemetry)
//   Step / Gap                       -> ranges checked (last good + STALE bit), backend step,
//                                       command k and telemetry k published
//   backend refuses the step         -> nothing published, gate unchanged
//   telecommand (on_command)         -> queued; handed to the backend just before the step of
//                                       the first frame with seq >= apply_seq (cmds++), in
//                                       arrival order; queue full or refused -> cmd_rej++
#ifndef HIL_BRIDGE_BRIDGE_HPP
#define HIL_BRIDGE_BRIDGE_HPP

#include <cstddef>
#include <cstdint>

#include "backend.hpp"
#include "bridge_types.hpp"
#include "frame_validator.hpp"
#include "seq_gate.hpp"

namespace bridge {

enum class Outcome { Stepped, Gap, Duplicate, Stale, Malformed, BadCrc, BadTime, Jump, BackendFailed };

struct Reply {
    Outcome outcome = Outcome::Malformed;
    bool publish_cmd = false;
    bool publish_tlm = false;
    Command cmd{};
    Telemetry tlm{};
};

class Bridge {
public:
    Bridge(Backend &be, const SensorLimits &lim, std::int64_t first_seq = 0)
        : be_(be), gate_(first_seq), val_(lim) {}

    Reply on_frame(const Frame &f);
    Reply on_bytes(const std::uint8_t *buf, std::size_t len);   // encoded gnc::sensor_frame_v2_t
    // One table chunk: forwarded to the backend between steps; table_rej counts refusals.
    TableAck on_table(const TableChunk &c);
    // One telecommand, queued until the first frame with seq >= apply_seq (then handed to the
    // backend before that step). false: refused (queue full: cmd_rej).
    bool on_command(const FswCommand &c);
    // The plant's missed-command count (from its heartbeat/summary); stored as reported.
    void set_missed(std::int32_t n) { counters_.missed = (n < 0) ? 0 : n; }
    // For SiAdapter users: fold adapter counters (nonfinite_rej, range_rej, malformed) in.
    Counters &counters_mut() { return counters_; }

    const Counters &counters() const { return counters_; }
    const SeqGate &gate() const { return gate_; }

private:
    void deliver_commands(std::int64_t seq);

    Backend &be_;
    SeqGate gate_;
    FrameValidator val_;
    Counters counters_{};
    FswCommand cmdq_[kCmdQueue] = {};   // in arrival order
    std::size_t cmdq_n_ = 0;
};

}  // namespace bridge

#endif  // HIL_BRIDGE_BRIDGE_HPP
