#include "fsw_backend.hpp"

namespace bridge {

// The wire status bits are handed to the flight code as FSW_ST_* without translation tables.
static_assert(kStatusStale == FSW_ST_STALE, "bridge STALE bit != FSW_ST_STALE");
static_assert(kStatusSat == FSW_ST_SAT, "bridge SAT bit != FSW_ST_SAT");

namespace {

std::uint32_t sat_u32(std::int32_t v) { return (v < 0) ? 0u : static_cast<std::uint32_t>(v); }

}  // namespace

bool hold_command(FswPending &p, const FswCommand &c)
{
    // The executive checks the target mode itself (refused ones are counted in its telemetry);
    // here only a negative value, which has no uint32 meaning, is refused.
    if (c.cmd == kCmdMode && c.args[0] >= 0) {
        p.mode_cmd = static_cast<std::uint32_t>(c.args[0]);
        return true;
    }
    // A telecommand carries its mission's namespace (FSW_TC_ID); the executive takes it or
    // refuses and counts it (another mission's, unknown, or outside the mission mode).
    if (c.cmd >= static_cast<std::int32_t>(1u << FSW_TC_NS_SHIFT)) {
        p.tc = static_cast<std::uint32_t>(c.cmd);
        for (std::size_t i = 0; i < FSW_TC_ARGS; ++i) { p.tc_arg[i] = c.args[i]; }
        return true;
    }
    return false;
}

void set_host_counters(FswPending &p, const Counters &c)
{
    p.missed = sat_u32(c.missed);
    p.rejected = sat_u32(rejected_total(c));
}

fsw_in_t make_fsw_in(const Frame &f, FswPending &p)
{
    fsw_in_t in{};
    in.utime_us = f.utime;
    in.seq = f.seq;
    in.n_counts = (f.n_counts < 0) ? 0u
                : ((f.n_counts > static_cast<std::int16_t>(FSW_IN_MAX)) ? FSW_IN_MAX
                                                                         : static_cast<std::uint32_t>(f.n_counts));
    for (std::size_t i = 0; i < FSW_IN_MAX; ++i) {
        in.counts[i] = f.counts[i];
        std::uint8_t st = 0u;
        if ((f.status[i] & kStatusStale) != 0) { st = static_cast<std::uint8_t>(st | FSW_ST_STALE); }
        if ((f.status[i] & kStatusSat) != 0) { st = static_cast<std::uint8_t>(st | FSW_ST_SAT); }
        in.status[i] = st;
    }
    in.mode_cmd = p.mode_cmd;
    p.mode_cmd = FSW_CMD_NONE;
    in.tc = p.tc;
    for (std::size_t i = 0; i < FSW_TC_ARGS; ++i) { in.tc_arg[i] = p.tc_arg[i]; p.tc_arg[i] = 0; }
    p.tc = FSW_TC_NONE;
    in.host_missed = p.missed;
    in.host_rejected = p.rejected;
    return in;
}

InProcessFswBackend::InProcessFswBackend(const fsw_cfg_t &cfg, std::vector<std::uint8_t> boot)
    : cfg_(cfg), boot_(std::move(boot)), f_(new fsw_t())
{
    (void)reset();
}

bool InProcessFswBackend::reset()
{
    *f_ = fsw_t{};
    out_ = fsw_out_t{};
    boot_rc_ = fsw_init(f_.get(), &cfg_, boot_.empty() ? nullptr : boot_.data(), static_cast<std::uint32_t>(boot_.size()));
    lim_tbl_acc_ = 0u;
    return boot_rc_ == FSW_OK;
}

SensorLimits InProcessFswBackend::sensor_limits() const
{
    SensorLimits l{};
    fsw_range_t r[FSW_IN_MAX] = {};
    std::uint32_t n = 0u;
    fsw_sensor_ranges(f_.get(), r, &n);
    l.n_channels = static_cast<std::int16_t>(n);
    l.period_us = static_cast<std::int32_t>(cfg_.period_us);
    for (std::size_t i = 0; i < n && i < kMaxCounts; ++i) {
        if (r[i].min <= r[i].max) {   // else no table: left open (ChannelLimits' defaults)
            l.ch[i].min = r[i].min;
            l.ch[i].max = r[i].max;
        }
    }
    return l;
}

bool InProcessFswBackend::limits_changed(SensorLimits &lim)
{
    if (f_->tlm.n_tbl_acc == lim_tbl_acc_) {
        return false;
    }
    lim_tbl_acc_ = f_->tlm.n_tbl_acc;
    lim = sensor_limits();
    return true;
}

void InProcessFswBackend::host_counters(const Counters &c) { set_host_counters(pend_, c); }

bool InProcessFswBackend::step(const Frame &f, StepOutput &out)
{
    // A boot failure still steps: the executive is then in SAFE and commands safe values.
    const fsw_in_t in = make_fsw_in(f, pend_);
    fsw_step(f_.get(), &in, &out_);

    out = StepOutput{};
    out.n_counts = static_cast<std::int16_t>(out_.n_act);
    for (std::size_t i = 0; i < out_.n_act && i < kMaxCounts; ++i) { out.counts[i] = out_.act_cnt[i]; }
    out.fsw_mode = static_cast<std::int32_t>(out_.mode);
    out.fsw_health = out_.health;
    out.tlm_layout_version = static_cast<std::int32_t>(fsw_tlm_layout(&out_.tlm));
    out.tlm_len = static_cast<std::int16_t>(fsw_tlm_encode(&out_.tlm, out.tlm, static_cast<std::uint32_t>(kMaxTlm)));
    return true;
}

bool InProcessFswBackend::command(const FswCommand &c) { return hold_command(pend_, c); }

bool InProcessFswBackend::table_chunk(const TableChunk &c, TableAck &ack)
{
    ack = TableAck{};
    ack.table_id = c.table_id;
    ack.revision = c.revision;
    if (c.table_id < 0 || c.table_id > 0xFFFF || c.revision < 0 || c.total_len < 0 || c.offset < 0 ||
        c.n <= 0 || static_cast<std::size_t>(c.n) > kMaxChunk) {
        ack.result = kTableRejected;
        ack.reason = static_cast<std::int32_t>(FSW_TBL_R_CHUNK_LEN);
        return true;
    }
    fsw_table_chunk_t ch{};
    ch.table_id = static_cast<std::uint16_t>(c.table_id);
    ch.revision = static_cast<std::uint32_t>(c.revision);
    ch.total_len = static_cast<std::uint32_t>(c.total_len);
    ch.offset = static_cast<std::uint32_t>(c.offset);
    ch.n = static_cast<std::uint32_t>(c.n);
    ch.data = c.data;
    std::uint32_t why = 0u;
    const std::uint32_t rej0 = f_->tlm.n_tbl_rej;
    const fsw_rc_t rc = fsw_table_upload(f_.get(), &ch, &why);
    const fsw_table_t *t = fsw_mission_table(f_.get());
    ack.bytes_received = static_cast<std::int32_t>(t->cand_got);
    if (f_->tlm.n_tbl_rej != rej0 || rc != FSW_OK) {
        ack.result = kTableRejected;
        ack.reason = static_cast<std::int32_t>(why & 0xFFFFu);
    } else if (t->state == FSW_TBL_S_READY) {
        ack.result = kTableAccepted;   // validated; active at the first step its commit rule allows
        ack.bytes_received = c.total_len;
    } else {
        ack.result = kTablePartial;
    }
    return true;
}

}  // namespace bridge
