#include "metrics.hpp"

#include <cstdio>
#include <utility>

#include "channels.hpp"
#include "lcm_codec.hpp"
#include "gnc/actuator_cmd_v2_t.hpp"
#include "gnc/fsw_tlm_frame_t.hpp"
#include "gnc/sim_truth_t.hpp"
#include "gnc/table_ack_t.hpp"

namespace sil {

namespace {
// fsw_tlm_frame_t's bridge counters as CoreMetrics::bridge holds them (the summary's order, which
// was the former map's alphabetical one).
const char *const kFrameCounters[] = {"dups", "gaps", "missed", "nonfinite_rej", "range_rej", "rejected", "stale",
                                      "table_rej"};
static_assert(sizeof kFrameCounters / sizeof kFrameCounters[0] == std::tuple_size<decltype(CoreMetrics::bridge)>::value,
              "one name per frame counter");

// The executive's counters every mission's summary carries (fsw_iface.py HEAD).
const char *const kExecFields[] = {"mode", "n_chan_rej", "n_stale_steps", "n_in_bad", "n_tbl_acc", "n_tbl_rej",
                                   "tbl_revision", "n_scrub_err", "n_safe", "n_mode_rej", "host_missed",
                                   "host_rejected", "n_tc", "n_tc_rej"};

void fnv1a(std::uint64_t &h, const void *data, std::size_t n)
{
    const auto *b = static_cast<const std::uint8_t *>(data);
    for (std::size_t i = 0; i < n; ++i) {
        h = (h ^ b[i]) * 0x100000001B3u;
    }
}

std::string hex64(std::uint64_t v)
{
    char b[24];
    std::snprintf(b, sizeof b, "%016llx", static_cast<unsigned long long>(v));
    return b;
}

}  // namespace

MetricsTap::MetricsTap(lcm_t *lcm, const sim::Scenario &scn)
    : lcm_(lcm), im_(host::iface_mission(scn.mission)), layout_(host::tlm_layout(im_)),
      mission_(host::mission_host(scn.mission).make_metrics(scn)), i_health_(layout_.at("health")),
      i_tbl_rev_(layout_.at("tbl_revision")), i_tbl_acc_(layout_.at("n_tbl_acc"))
{
    if (lcm_ == nullptr) {
        return;
    }
    subs_[0] = lcm_subscribe(lcm_, kChTruth, &MetricsTap::on_truth, this);
    subs_[1] = lcm_subscribe(lcm_, kChCmd, &MetricsTap::on_cmd, this);
    subs_[2] = lcm_subscribe(lcm_, kChTlm, &MetricsTap::on_tlm, this);
    subs_[3] = lcm_subscribe(lcm_, kChTblAck, &MetricsTap::on_ack, this);
}

void MetricsTap::feed(const char *channel, const std::uint8_t *data, std::size_t len)
{
    lcm_recv_buf_t rb{};
    rb.data = const_cast<std::uint8_t *>(data);   // the callbacks only read it (LCM's own signature)
    rb.data_size = static_cast<std::uint32_t>(len);
    const std::string ch(channel);
    if (ch == kChTruth) {
        on_truth(&rb, channel, this);
    } else if (ch == kChCmd) {
        on_cmd(&rb, channel, this);
    } else if (ch == kChTlm) {
        on_tlm(&rb, channel, this);
    } else if (ch == kChTblAck) {
        on_ack(&rb, channel, this);
    } else {
        // not a channel the metrics read
    }
}

MetricsTap::~MetricsTap()
{
    for (auto *s : subs_) {
        if (s != nullptr) { lcm_unsubscribe(lcm_, s); }
    }
}

void MetricsTap::on_truth(const lcm_recv_buf_t *rb, const char *, void *user)
{
    auto *self = static_cast<MetricsTap *>(user);
    gnc::sim_truth_t t;
    if (t.decode(rb->data, 0, static_cast<int>(rb->data_size)) < 0) {
        return;
    }
    self->mission_->on_truth(t);
    ++self->m_.truth_n;
}

void MetricsTap::on_cmd(const lcm_recv_buf_t *rb, const char *, void *user)
{
    auto *self = static_cast<MetricsTap *>(user);
    fnv1a(self->m_.digest_cmd, rb->data, rb->data_size);
    gnc::actuator_cmd_v2_t c;
    if (bridge::decode(static_cast<const std::uint8_t *>(rb->data), rb->data_size, c) != bridge::Wire::Ok) {
        return;
    }
    self->mission_->on_cmd(c);
    ++self->m_.cmd_n;
}

void MetricsTap::on_tlm(const lcm_recv_buf_t *rb, const char *, void *user)
{
    auto *self = static_cast<MetricsTap *>(user);
    gnc::fsw_tlm_frame_t f;
    CoreMetrics &m = self->m_;
    fnv1a(m.digest_tlm, rb->data, rb->data_size);
    if (f.decode(rb->data, 0, static_cast<int>(rb->data_size)) < 0 || f.tlm_len < 0 || f.tlm_len > 512 ||
        static_cast<std::uint32_t>(f.tlm_layout_version) != self->im_.layout_version ||
        !host::decode_tlm(self->layout_, f.tlm, static_cast<std::size_t>(f.tlm_len), self->last_)) {
        ++m.tlm_bad;
        return;
    }
    const std::vector<std::int64_t> &v = self->last_;
    const double ts = static_cast<double>(f.utime) * 1e-6;
    const auto health = static_cast<std::uint32_t>(v[self->i_health_]);
    self->mission_->on_tlm(v, ts);
    if (m.t_first_fx_s < 0.0 && (health & 0xFFu) != 0u) {
        m.t_first_fx_s = ts;
        m.first_fx_bits = health & 0xFFu;
    }
    m.bridge = {f.dups, f.gaps, f.missed, f.nonfinite_rej, f.range_rej, f.rejected, f.stale, f.table_rej};
    if (m.tbl_revision_first < 0) {
        m.tbl_revision_first = v[self->i_tbl_rev_];
    }
    if (v[self->i_tbl_acc_] != m.n_tbl_acc_last) {
        m.n_tbl_acc_last = v[self->i_tbl_acc_];
        m.t_tbl_commit_s = ts;
    }
    ++m.tlm_n;
}

void MetricsTap::on_ack(const lcm_recv_buf_t *rb, const char *, void *user)
{
    auto *self = static_cast<MetricsTap *>(user);
    gnc::table_ack_t a;
    if (a.decode(rb->data, 0, static_cast<int>(rb->data_size)) < 0) {
        return;
    }
    self->m_.last_ack_result = a.result;
    self->m_.last_ack_reason = a.reason;
    if (a.result == gnc::table_ack_t::RESULT_ACCEPTED) {
        ++self->m_.ack_accepted;
    } else if (a.result == gnc::table_ack_t::RESULT_REJECTED) {
        ++self->m_.ack_rejected;
    } else {
        // a chunk stored, more expected: not an upload's outcome
    }
    ++self->m_.ack_n;
}

const CoreMetrics &MetricsTap::core() const
{
    if (!last_.empty()) {
        m_.tlm.clear();
        for (std::size_t i = 0; i < last_.size(); ++i) {
            m_.tlm[layout_.names[i]] = last_[i];
        }
    }
    return m_;
}

std::int64_t frame_counter(const CoreMetrics &m, const std::string &name)
{
    for (std::size_t i = 0; i < m.bridge.size(); ++i) {
        if (name == kFrameCounters[i]) {
            return m.bridge[i];
        }
    }
    return -1;
}

void MetricsTap::summary(host::Summary &s, const bridge::Counters *bridge_final) const
{
    const CoreMetrics &m = core();
    s.add_str("mission", im_.name);
    s.add("t_first_fx_status_s", m.t_first_fx_s, "%.2f");
    s.add_int("first_fx_status_bits", m.first_fx_bits);
    s.add_int("steps_truth", static_cast<std::int64_t>(m.truth_n));
    s.add_int("steps_tlm", static_cast<std::int64_t>(m.tlm_n));
    s.add_int("tlm_undecodable", static_cast<std::int64_t>(m.tlm_bad));
    if (bridge_final != nullptr) {
        const bridge::Counters &c = *bridge_final;
        s.add_str("bridge_counters_from", "bridge core, end of run");
        const std::pair<const char *, std::int32_t> kv[] = {
            {"stepped", c.stepped}, {"dups", c.dups}, {"stale", c.stale}, {"gaps", c.gaps},
            {"gap_frames", c.gap_frames}, {"nonfinite_rej", c.nonfinite_rej}, {"range_rej", c.range_rej},
            {"malformed", c.malformed}, {"missed", c.missed}, {"table_rej", c.table_rej}, {"cmds", c.cmds},
            {"cmd_rej", c.cmd_rej}, {"crc_rej", c.crc_rej}, {"time_rej", c.time_rej}, {"jump_rej", c.jump_rej},
            {"resyncs", c.resyncs}, {"rejected", bridge::rejected_total(c)}};
        for (const auto &e : kv) {
            s.add_int(std::string("bridge_") + e.first, e.second);
        }
    } else {
        s.add_str("bridge_counters_from", "last telemetry frame (the bridge is another process)");
        for (std::size_t i = 0; i < m.bridge.size(); ++i) {
            s.add_int(std::string("bridge_") + kFrameCounters[i], m.bridge[i]);
        }
    }
    for (const char *k : kExecFields) {
        const auto it = m.tlm.find(k);
        s.add_int(std::string("fsw_") + k, it == m.tlm.end() ? 0 : it->second);
    }
    const auto hs = m.tlm.find("health_sticky");
    const std::uint32_t sticky = (hs == m.tlm.end()) ? 0u : static_cast<std::uint32_t>(hs->second);
    s.add_hex("fsw_health_sticky", sticky);
    s.add_str("fsw_health_sticky_names", host::bits_str(sticky, iface::kExecHealth, iface::kNumExecHealth));
    const auto tr = m.tlm.find("tbl_reason");
    const std::uint32_t reason = (tr == m.tlm.end()) ? 0u : static_cast<std::uint32_t>(tr->second);
    s.add_hex("fsw_tbl_reason", reason);
    s.add_str("fsw_tbl_reason_text", reason == 0u ? std::string("none") : host::describe_reason(im_, reason));
    s.add_int("table_acks", static_cast<std::int64_t>(m.ack_n));
    // Every mission's table counters, here so that no mission's summary can lack them.
    s.add_int("table_uploads_accepted", static_cast<std::int64_t>(m.ack_accepted));
    s.add_int("table_uploads_rejected", static_cast<std::int64_t>(m.ack_rejected));
    s.add_int("table_revision_boot", m.tbl_revision_first);
    const auto rev = m.tlm.find("tbl_revision");
    s.add_int("table_revision_active", rev == m.tlm.end() ? -1 : rev->second);
    s.add("t_table_commit_s", m.t_tbl_commit_s, "%.2f");
    s.add_str("stream_digest_cmd", hex64(m.digest_cmd));
    s.add_str("stream_digest_tlm", hex64(m.digest_tlm));
    mission_->summary(s);
}

}  // namespace sil
