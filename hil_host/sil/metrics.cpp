#include "metrics.hpp"

#include "channels.hpp"
#include "lcm_codec.hpp"
#include "gnc/actuator_cmd_v2_t.hpp"
#include "gnc/fsw_tlm_frame_t.hpp"
#include "gnc/sim_truth_t.hpp"
#include "gnc/table_ack_t.hpp"

namespace sil {

namespace {
// The executive's counters every mission's summary carries (fsw_iface.py HEAD).
const char *const kExecFields[] = {"mode", "n_chan_rej", "n_stale_steps", "n_in_bad", "n_tbl_acc", "n_tbl_rej",
                                   "tbl_revision", "n_scrub_err", "n_safe", "n_mode_rej", "host_missed",
                                   "host_rejected", "n_tc", "n_tc_rej"};
}  // namespace

MetricsTap::MetricsTap(lcm_t *lcm, const sim::Scenario &scn)
    : lcm_(lcm), im_(host::iface_mission(scn.mission)), layout_(host::tlm_layout(im_)),
      mission_(host::mission_host(scn.mission).make_metrics(scn)), i_health_(layout_.at("health"))
{
    subs_[0] = lcm_subscribe(lcm_, kChTruth, &MetricsTap::on_truth, this);
    subs_[1] = lcm_subscribe(lcm_, kChCmd, &MetricsTap::on_cmd, this);
    subs_[2] = lcm_subscribe(lcm_, kChTlm, &MetricsTap::on_tlm, this);
    subs_[3] = lcm_subscribe(lcm_, kChTblAck, &MetricsTap::on_ack, this);
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
    gnc::actuator_cmd_v2_t c;
    if (bridge::decode(static_cast<const std::uint8_t *>(rb->data), rb->data_size, c) != bridge::Wire::Ok) {
        return;
    }
    self->mission_->on_cmd(c);
    ++self->m_.cmd_n;
    const auto *b = static_cast<const std::uint8_t *>(rb->data);
    for (std::size_t i = 0; i < static_cast<std::size_t>(rb->data_size); ++i) {
        self->m_.cmd_digest = (self->m_.cmd_digest ^ b[i]) * UINT64_C(1099511628211);
    }
}

void MetricsTap::on_tlm(const lcm_recv_buf_t *rb, const char *, void *user)
{
    auto *self = static_cast<MetricsTap *>(user);
    gnc::fsw_tlm_frame_t f;
    CoreMetrics &m = self->m_;
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
    m.bridge = {{"dups", f.dups}, {"stale", f.stale}, {"gaps", f.gaps}, {"rejected", f.rejected},
                {"nonfinite_rej", f.nonfinite_rej}, {"range_rej", f.range_rej}, {"missed", f.missed},
                {"table_rej", f.table_rej}};
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

void MetricsTap::summary(host::Summary &s) const
{
    const CoreMetrics &m = core();
    s.add_str("mission", im_.name);
    s.add("t_first_fx_status_s", m.t_first_fx_s, "%.2f");
    s.add_int("first_fx_status_bits", m.first_fx_bits);
    s.add_int("steps_truth", static_cast<std::int64_t>(m.truth_n));
    s.add_int("steps_tlm", static_cast<std::int64_t>(m.tlm_n));
    s.add_int("tlm_undecodable", static_cast<std::int64_t>(m.tlm_bad));
    for (const auto &kv : m.bridge) {
        s.add_int("bridge_" + kv.first, kv.second);
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
    mission_->summary(s);
}

}  // namespace sil
