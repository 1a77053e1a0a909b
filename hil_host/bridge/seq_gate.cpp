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
    } else if (seq > last_ + 1) {   // seq > last_ here, so no overflow in the subtraction below
        a = GateAction::Gap;
    } else {
        a = GateAction::Step;
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
    }
    return out;
}

}  // namespace bridge
