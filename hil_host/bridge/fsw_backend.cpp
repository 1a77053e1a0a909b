#include "fsw_backend.hpp"

#include <cmath>
#include <stdexcept>

extern "C" {
#include "imp_tables.h"
#include "obs_tables.h"
}

namespace bridge {

static_assert(FSW_TC_IMP_START == static_cast<std::uint32_t>(kCmdImpStart) &&
                  FSW_TC_IMP_ABORT == static_cast<std::uint32_t>(kCmdImpAbort) &&
                  FSW_TC_IMP_CLEAR == static_cast<std::uint32_t>(kCmdImpClear),
              "fsw_cmd_t CMD_IMP_* and FSW_TC_* must agree");

namespace {

std::int32_t q_of(double v, int q, const char *what)
{
    const double s = std::ldexp(v, q);
    if (!std::isfinite(s) || s < 1.0 || s > 2147483647.0) {
        throw std::invalid_argument(std::string("boot table override out of range: ") + what);
    }
    return static_cast<std::int32_t>(std::floor(s + 0.5));
}

std::uint32_t sat_u32(std::int32_t v) { return (v < 0) ? 0u : static_cast<std::uint32_t>(v); }

}  // namespace

obs_params_t boot_obs_table(const std::string &name, double k_hat0_per_s2, double bdot_max_degps)
{
    const obs_params_t *t = nullptr;
    if (name == "obs_50hz_phys") { t = &OBS_TBL_50HZ_PHYS; }
    if (name == "obs_50hz_paper") { t = &OBS_TBL_50HZ_PAPER; }
    if (name == "obs_5hz_paper") { t = &OBS_TBL_5HZ_PAPER; }
    if (name == "obs_paper_printed") { t = &OBS_TBL_PAPER_PRINTED; }
    if (t == nullptr) {
        throw std::invalid_argument("unknown observer table '" + name + "'");
    }
    obs_params_t p = *t;
    if (k_hat0_per_s2 > 0.0) {   // kappa = K / 0.01 in q28
        p.kappa_init_q28 = q_of(k_hat0_per_s2 / 0.01, static_cast<int>(OBS_KAPPA_Q), "k_hat0");
    }
    if (bdot_max_degps > 0.0) {
        p.bdot_max_q29 = q_of(bdot_max_degps * M_PI / 180.0, static_cast<int>(OBS_U_Q), "bdot_max_degps");
    }
    return p;
}

imp_params_t boot_imp_table(const std::string &name)
{
    if (name == "imp_default") { return IMP_TBL_DEFAULT; }
    if (name == "imp_1s") { return IMP_TBL_1S; }
    if (name == "imp_sub1ms") { return IMP_TBL_SUB1MS; }
    throw std::invalid_argument("unknown impulse table '" + name + "'");
}

InProcessFswBackend::InProcessFswBackend(const obs_params_t &boot, std::uint32_t revision,
                                         std::uint16_t stale_max)
    : boot_(boot), revision_(revision), f_(new fsw_t())
{
    cfg_.period_us = boot.period_us;
    cfg_.stale_max = stale_max;
    cfg_.boot_mode = FSW_MODE_DETUMBLE;
    cfg_.mission = FSW_MISSION_DETUMBLE;
    ok_ = reset();
}

InProcessFswBackend::InProcessFswBackend(const imp_params_t &boot_imp, std::uint32_t revision)
    : boot_imp_(boot_imp), revision_(revision), f_(new fsw_t())
{
    cfg_.period_us = boot_imp.period_us;
    cfg_.stale_max = 250u;   // not a SAFE trigger for nav (fsw_exec.c); kept for the checks
    cfg_.boot_mode = FSW_MODE_RENDEZVOUS;
    cfg_.mission = FSW_MISSION_RENDEZVOUS;
    ok_ = reset();
}

bool InProcessFswBackend::reset()
{
    *f_ = fsw_t{};
    out_ = fsw_out_t{};
    ok_ = (cfg_.mission == FSW_MISSION_RENDEZVOUS) ? (fsw_init_rdv(f_.get(), &cfg_, &boot_imp_, revision_) == FSW_OK)
                                                    : (fsw_init(f_.get(), &cfg_, &boot_, revision_) == FSW_OK);
    return ok_;
}

SensorLimits InProcessFswBackend::sensor_limits() const
{
    SensorLimits l{};
    if (cfg_.mission == FSW_MISSION_RENDEZVOUS) {
        l.n_channels = static_cast<std::int16_t>(FSW_RDV_N_SENS);
        l.period_us = static_cast<std::int32_t>(cfg_.period_us);
        for (std::size_t i = 0; i < FSW_RDV_N_SENS; ++i) {
            const std::int32_t m = (i < 3u) ? FSW_NAV_POS_MAX_MM : ((i < 6u) ? FSW_NAV_VEL_MAX_CNT : INT32_MAX);
            l.ch[i].min = (i < 6u) ? -m : 0;
            l.ch[i].max = m;
        }
        return l;
    }
    l.n_channels = static_cast<std::int16_t>(FSW_N_SENS);
    l.period_us = static_cast<std::int32_t>(boot_.period_us);
    const std::int32_t m = (boot_.gyro_max_cnt > 0) ? (boot_.gyro_max_cnt - 1) : 0;
    for (std::size_t i = 0; i < FSW_N_SENS; ++i) {
        l.ch[i].min = -m;
        l.ch[i].max = m;
    }
    return l;
}

void InProcessFswBackend::host_counters(const Counters &c)
{
    missed_ = sat_u32(c.missed);
    rejected_ = sat_u32(rejected_total(c));
}

bool InProcessFswBackend::step(const Frame &f, StepOutput &out)
{
    // A boot failure still steps: the executive is then in SAFE and commands safe values.
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
    in.mode_cmd = mode_cmd_;
    mode_cmd_ = FSW_CMD_NONE;
    in.tc = tc_;
    for (std::size_t i = 0; i < 8u; ++i) { in.tc_arg[i] = tc_arg_[i]; tc_arg_[i] = 0; }
    tc_ = FSW_TC_NONE;
    in.host_missed = missed_;
    in.host_rejected = rejected_;
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

bool InProcessFswBackend::command(const FswCommand &c)
{
    // The executive checks the target mode itself (refused ones are counted in its telemetry);
    // here only a negative value, which has no uint32 meaning, is refused.
    if (c.cmd == kCmdMode && c.args[0] >= 0) {
        mode_cmd_ = static_cast<std::uint32_t>(c.args[0]);
        return true;
    }
    // Module telecommands go to the executive, which refuses them outside the mission mode.
    if (c.cmd == kCmdImpStart || c.cmd == kCmdImpAbort || c.cmd == kCmdImpClear) {
        tc_ = static_cast<std::uint32_t>(c.cmd);   // FSW_TC_* share the fsw_cmd_t values
        for (std::size_t i = 0; i < 8u; ++i) { tc_arg_[i] = c.args[i]; }
        return true;
    }
    return false;
}

bool InProcessFswBackend::table_chunk(const TableChunk &c, TableAck &ack)
{
    ack = TableAck{};
    ack.table_id = c.table_id;
    ack.revision = c.revision;
    if (c.table_id < 0 || c.table_id > 0xFFFF || c.revision < 0 || c.total_len < 0 || c.offset < 0 ||
        c.n < 0 || static_cast<std::size_t>(c.n) > kMaxChunk) {
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
    const fsw_table_t *t = fsw_mission_table(f_.get());   // the mission's table (observer or impulse)
    ack.bytes_received = static_cast<std::int32_t>(t->cand_got);
    if (f_->tlm.n_tbl_rej != rej0 || rc != FSW_OK) {
        ack.result = kTableRejected;
        ack.reason = static_cast<std::int32_t>(why & 0xFFFFu);
    } else if (t->state == FSW_TBL_S_READY) {
        ack.result = kTableAccepted;   // validated; active from the next step (RENDEZVOUS: the
                                       // first one with the scheduler idle or terminal)
        ack.bytes_received = c.total_len;
    } else {
        ack.result = kTablePartial;
    }
    return true;
}

}  // namespace bridge
