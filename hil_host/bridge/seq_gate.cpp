#include "seq_gate.hpp"

namespace bridge {

GateAction SeqGate::classify(std::int64_t seq) const
{
    GateAction a = GateAction::Step;
    if (seq == last_) {
        // A duplicate needs a cached command; before the first step "last" was never stepped.
        a = have_cache_ ? GateAction::Duplicate : GateAction::Stale;
    } else if (seq < last_) {
        a = GateAction::Stale;
    } else if (seq - last_ > kMaxSeqJump) {   // seq > last_ >= -1 here: no overflow
        a = GateAction::Jump;
    } else if (seq > last_ + 1) {
        a = GateAction::Gap;
    } else {
        a = GateAction::Step;
    }
    return a;
}

GateAction SeqGate::jump(std::int64_t seq, Counters &c)
{
    if ((run_len_ > 0) && (seq == run_last_)) {
        // a re-send of the run's newest frame: neither progress nor a break
    } else if ((run_len_ > 0) && (seq == run_last_ + 1)) {   // seq <= kMaxSeq: no overflow
        ++run_len_;
        run_last_ = seq;
    } else {
        run_len_ = 1;
        run_last_ = seq;
    }
    GateAction a = GateAction::Jump;
    if (run_len_ >= kResyncFrames) {
        sat_inc(c.resyncs);
        run_len_ = 0;
        run_last_ = -1;
        a = GateAction::Gap;
    } else {
        sat_inc(c.jump_rej);
    }
    return a;
}

const Command *SeqGate::commit(GateAction a, std::int64_t seq, const Command *cmd, Counters &c)
{
    const Command *out = nullptr;
    switch (a) {
    case GateAction::Step:
    case GateAction::Gap:
        if (cmd != nullptr) {
            if (a == GateAction::Gap) {
                sat_inc(c.gaps);
                sat_inc(c.gap_frames, seq - last_ - 1);
            }
            sat_inc(c.stepped);
            last_ = seq;
            run_len_ = 0;   // an accepted frame ends any out-of-window run
            run_last_ = -1;
            cache_ = *cmd;
            have_cache_ = true;
            out = &cache_;
        }
        break;
    case GateAction::Duplicate:
        sat_inc(c.dups);
        out = &cache_;
        break;
    case GateAction::Stale:
        sat_inc(c.stale);
        break;
    case GateAction::Jump:
        break;   // counted by jump()
    }
    return out;
}

}  // namespace bridge
