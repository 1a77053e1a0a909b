#include "bridge.hpp"

#include "lcm_codec.hpp"

namespace bridge {

namespace {

// utime must be seq * period_us (spec 00 §5.2: frame k is sampled at t_k = k h, t_0 = 0). A seq
// and a utime that disagree mean one of them is corrupted; neither can be trusted.
bool time_consistent(const Frame &f)
{
    if (f.period_us <= 0) {
        return false;
    }
    // seq is in [0, kMaxSeq] (header checked): the bound keeps the product in int64.
    if (f.seq > INT64_MAX / f.period_us) {
        return false;
    }
    return f.utime == f.seq * static_cast<std::int64_t>(f.period_us);
}

}  // namespace

Reply Bridge::on_frame(const Frame &in)
{
    Reply r{};
    if (val_.check_header(in) != FrameVerdict::Ok) {
        sat_inc(counters_.malformed);
        r.outcome = Outcome::Malformed;
        return r;
    }
    if (!time_consistent(in)) {
        sat_inc(counters_.time_rej);
        r.outcome = Outcome::BadTime;
        return r;
    }
    GateAction a = gate_.classify(in.seq);
    if (a == GateAction::Jump) {
        a = gate_.jump(in.seq, counters_);
        if (a == GateAction::Jump) {
            r.outcome = Outcome::Jump;
            return r;
        }
    }
    if ((a == GateAction::Duplicate) || (a == GateAction::Stale)) {
        const Command *c = gate_.answer(a, counters_);
        r.outcome = (a == GateAction::Duplicate) ? Outcome::Duplicate : Outcome::Stale;
        if (c != nullptr) {
            r.cmd = *c;
            r.publish_cmd = true;
        }
        return r;
    }
    Frame f = in;
    (void)val_.apply_ranges(f, counters_);
    be_.host_counters(counters_);
    deliver_commands(f.seq);
    StepOutput so{};
    if (!be_.step(f, so)) {
        r.outcome = Outcome::BackendFailed;
        return r;
    }
    SensorLimits lim{};
    if (be_.limits_changed(lim)) {
        val_.set_limits(lim);
    }
    Command cmd{};
    cmd.utime = f.utime;
    cmd.seq = f.seq;
    cmd.n_counts = (so.n_counts < 0) ? static_cast<std::int16_t>(0)
                 : ((so.n_counts > static_cast<std::int16_t>(kMaxCounts)) ? static_cast<std::int16_t>(kMaxCounts) : so.n_counts);
    for (std::size_t i = 0; i < kMaxCounts; ++i) {
        cmd.counts[i] = (i < static_cast<std::size_t>(cmd.n_counts)) ? so.counts[i] : 0;
    }
    cmd.fsw_mode = so.fsw_mode;
    cmd.fsw_health = so.fsw_health;
    const Command *c = gate_.commit(a, f.seq, &cmd, counters_);
    r.outcome = (a == GateAction::Gap) ? Outcome::Gap : Outcome::Stepped;
    r.cmd = *c;
    r.publish_cmd = true;
    r.publish_tlm = true;
    r.tlm.utime = f.utime;
    r.tlm.seq = f.seq;
    r.tlm.tlm_layout_version = so.tlm_layout_version;
    r.tlm.tlm_len = ((so.tlm_len >= 0) && (static_cast<std::size_t>(so.tlm_len) <= kMaxTlm))
                        ? so.tlm_len : static_cast<std::int16_t>(0);
    for (std::size_t i = 0; i < static_cast<std::size_t>(r.tlm.tlm_len); ++i) {
        r.tlm.tlm[i] = so.tlm[i];
    }
    r.tlm.counters = counters_;
    return r;
}

bool Bridge::on_command(const FswCommand &c)
{
    if (cmdq_n_ >= kCmdQueue) {
        sat_inc(counters_.cmd_rej);
        return false;
    }
    cmdq_[cmdq_n_++] = c;
    return true;
}

void Bridge::deliver_commands(std::int64_t seq)
{
    std::size_t keep = 0;
    for (std::size_t i = 0; i < cmdq_n_; ++i) {
        if (cmdq_[i].apply_seq <= seq) {
            sat_inc(be_.command(cmdq_[i]) ? counters_.cmds : counters_.cmd_rej);
        } else {
            cmdq_[keep++] = cmdq_[i];
        }
    }
    cmdq_n_ = keep;
}

TableAck Bridge::on_table(const TableChunk &c)
{
    TableAck a{};
    if (!be_.table_chunk(c, a)) {
        a = TableAck{};
        a.table_id = c.table_id;
        a.revision = c.revision;
        a.result = kTableRejected;
    }
    a.utime = c.utime;
    if (a.result == kTableRejected) {
        sat_inc(counters_.table_rej);
    }
    return a;
}

Reply Bridge::on_bytes(const std::uint8_t *buf, std::size_t len)
{
    Frame f{};
    const Wire w = decode_frame(buf, len, f);
    if (w != Wire::Ok) {
        Reply r{};
        if (w == Wire::BadCrc) {
            sat_inc(counters_.crc_rej);
            r.outcome = Outcome::BadCrc;
        } else {
            sat_inc(counters_.malformed);
            r.outcome = Outcome::Malformed;
        }
        return r;
    }
    return on_frame(f);
}

}  // namespace bridge
