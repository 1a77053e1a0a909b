// seq_gate.hpp — the lock-step sequence table of spec 00 §5.2, with the cached last command.
//
//   seq == last + 1  -> Step      (run the step; publish command k and telemetry k)
//   seq == last      -> Duplicate (re-publish the cached command, no step)        dups++
//   seq <  last      -> Stale     (drop)                                          stale++
//   seq >  last + 1  -> Gap       (step; count the gap)          gaps++, gap_frames += seq-last-1
//   seq >  last + kMaxSeqJump -> Jump (refused)                                   jump_rej++
//
// The window. In lock-step the plant sends frame k+1 only after command k arrived or its
// deadline passed, so a forward jump of g frames needs g consecutive frames each lost in all of
// its 1 + retx_max transmissions: at the 30 % loss the fault tests fly (retx_max 3) that is
// 0.3^4 = 0.8 % per frame, and 8 in a row about 10^-17. A larger jump is not loss but a
// corrupted seq, and stepping it would put "last" in the future and make every later frame
// stale — the loop locked out (issue 18: frame 43 arriving as 555 cost 512 commands). So it is
// refused, and the plant re-sends the frame. A plant that genuinely jumped (restarted, or its
// clock moved) is followed deliberately: kResyncFrames consecutive out-of-window frames, each
// exactly one ahead of the previous one (re-sends of the same seq neither advance nor break the
// run), make the last of them a Gap (resyncs++). A transient corruption cannot do that: the
// next genuine frame is in the window and clears the run.
//
// Before the first step, "last" is first_seq - 1, so a first frame above first_seq is a gap and
// one below it is stale. classify() does not change state: the caller validates a Step/Gap
// frame and only then commit()s it with the command it produced, so a rejected frame leaves
// the gate untouched (the plant re-publishes it after retx_ms).
#ifndef HIL_BRIDGE_SEQ_GATE_HPP
#define HIL_BRIDGE_SEQ_GATE_HPP

#include <cstdint>

#include "bridge_types.hpp"

namespace bridge {

enum class GateAction { Step, Gap, Duplicate, Stale, Jump };

// Largest forward step taken as a gap (seq - last); see the window rule above.
constexpr std::int64_t kMaxSeqJump = 8;
// Consecutive, consistent out-of-window frames that resynchronise the gate.
constexpr std::int32_t kResyncFrames = 3;

class SeqGate {
public:
    explicit SeqGate(std::int64_t first_seq = 0) : last_(first_seq - 1) {}

    GateAction classify(std::int64_t seq) const;
    // For a Jump: records seq in the resynchronisation run and returns Gap when it completes
    // the run (resyncs++; the caller then steps it as a gap), else Jump (jump_rej++, refused).
    GateAction jump(std::int64_t seq, Counters &c);
    // Counts the decision. For Step/Gap also stores seq as last and cmd as the cache.
    // Returns the command to publish (the new one, or the cached one for Duplicate), or
    // nullptr for Stale.
    const Command *commit(GateAction a, std::int64_t seq, const Command *cmd, Counters &c);
    // Convenience for Duplicate/Stale (no new command).
    const Command *answer(GateAction a, Counters &c) { return commit(a, last_, nullptr, c); }

    std::int64_t last() const { return last_; }
    bool has_cache() const { return have_cache_; }
    const Command &cached() const { return cache_; }

private:
    std::int64_t last_;
    bool have_cache_ = false;
    Command cache_{};
    std::int64_t run_last_ = -1;   // last seq of the current out-of-window run (-1: none)
    std::int32_t run_len_ = 0;     // distinct consecutive seqs in that run
};

}  // namespace bridge

#endif  // HIL_BRIDGE_SEQ_GATE_HPP
