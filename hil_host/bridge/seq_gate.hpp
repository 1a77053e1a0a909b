// seq_gate.hpp — the lock-step sequence table of spec 00 §5.2, with the cached last command.
//
//   seq == last + 1  -> Step      (run the step; publish command k and telemetry k)
//   seq == last      -> Duplicate (re-publish the cached command, no step)        dups++
//   seq <  last      -> Stale     (drop)                                          stale++
//   seq >  last + 1  -> Gap       (step; count the gap)          gaps++, gap_frames += seq-last-1
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

enum class GateAction { Step, Gap, Duplicate, Stale };

class SeqGate {
public:
    explicit SeqGate(std::int64_t first_seq = 0) : last_(first_seq - 1) {}

    GateAction classify(std::int64_t seq) const;
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
};

}  // namespace bridge

#endif  // HIL_BRIDGE_SEQ_GATE_HPP
