#include "bridge_node.hpp"

#include <chrono>
#include <stdexcept>

#include "channels.hpp"
#include "gnc/sil_ctl_t.hpp"
#include "gnc/table_ack_t.hpp"
#include "gnc/table_upload_v2_t.hpp"
#include "lcm_codec.hpp"

namespace sil {

BridgeNode::BridgeNode(lcm_t *lcm, bridge::Bridge &core) : lcm_(lcm), core_(core), buf_(4096)
{
    if (lcm_ == nullptr) {
        throw std::invalid_argument("BridgeNode: null lcm_t");
    }
    subs_[0] = lcm_subscribe(lcm_, kChSensor, &BridgeNode::on_sensor_cb, this);
    subs_[1] = lcm_subscribe(lcm_, kChTblUp, &BridgeNode::on_table_cb, this);
    subs_[2] = lcm_subscribe(lcm_, kChCtl, &BridgeNode::on_ctl_cb, this);
    subs_[3] = lcm_subscribe(lcm_, kChFswCmd, &BridgeNode::on_fsw_cmd_cb, this);
}

BridgeNode::~BridgeNode()
{
    for (auto *s : subs_) {
        if (s != nullptr) { lcm_unsubscribe(lcm_, s); }
    }
}

void BridgeNode::on_sensor_cb(const lcm_recv_buf_t *rb, const char *, void *user)
{
    auto *self = static_cast<BridgeNode *>(user);
    ++self->frames_;
    const bridge::Reply r = self->core_.on_bytes(static_cast<const std::uint8_t *>(rb->data), rb->data_size);
    if (r.publish_cmd) {
        gnc::actuator_cmd_v2_t m{};
        bridge::to_lcm(r.cmd, m);
        const int n = bridge::encode(m, self->buf_.data(), self->buf_.size());
        if (n > 0) { lcm_publish(self->lcm_, kChCmd, self->buf_.data(), static_cast<unsigned>(n)); }
    }
    if (r.publish_tlm) {
        gnc::fsw_tlm_frame_t m{};
        bridge::to_lcm(r.tlm, m);
        const int n = bridge::encode(m, self->buf_.data(), self->buf_.size());
        if (n > 0) { lcm_publish(self->lcm_, kChTlm, self->buf_.data(), static_cast<unsigned>(n)); }
    }
}

int table_upload_to_ack(bridge::Bridge &core, const std::uint8_t *data, std::size_t len, std::uint8_t *ack_buf,
                        std::size_t ack_cap, bool *bad)
{
    gnc::table_upload_v2_t m;
    bridge::TableAck a{};
    const bridge::Wire w = bridge::decode(data, len, m);
    *bad = w != bridge::Wire::Ok || m.n < 0 || m.n > 256;
    if (*bad) {
        bridge::sat_inc((w == bridge::Wire::BadCrc) ? core.counters_mut().crc_rej : core.counters_mut().malformed);
        a.result = bridge::kTableRejected;
        a.reason = 1;   // FSW_TBL_R_CHUNK_LEN: the chunk itself is unusable
    } else {
        bridge::TableChunk c{};
        c.utime = m.utime;
        c.table_id = m.table_id;
        c.revision = m.revision;
        c.total_len = m.total_len;
        c.offset = m.offset;
        c.n = m.n;
        c.data = m.data;
        a = core.on_table(c);
    }
    gnc::table_ack_t ack{};
    ack.utime = a.utime;
    ack.table_id = a.table_id;
    ack.revision = a.revision;
    ack.result = a.result;
    ack.reason = a.reason;
    ack.bytes_received = a.bytes_received;
    return ack.encode(ack_buf, 0, static_cast<int>(ack_cap));
}

void BridgeNode::on_table_cb(const lcm_recv_buf_t *rb, const char *, void *user)
{
    auto *self = static_cast<BridgeNode *>(user);
    bool bad = false;
    const int n = table_upload_to_ack(self->core_, static_cast<const std::uint8_t *>(rb->data), rb->data_size,
                                      self->buf_.data(), self->buf_.size(), &bad);
    if (bad) {
        ++self->bad_uploads_;
    }
    if (n > 0) { lcm_publish(self->lcm_, kChTblAck, self->buf_.data(), static_cast<unsigned>(n)); }
}

void BridgeNode::on_fsw_cmd_cb(const lcm_recv_buf_t *rb, const char *, void *user)
{
    auto *self = static_cast<BridgeNode *>(user);
    bridge::FswCommand c{};
    const bridge::Wire w = bridge::decode_fsw_cmd(static_cast<const std::uint8_t *>(rb->data), rb->data_size, c);
    if (w != bridge::Wire::Ok) {
        bridge::sat_inc(self->core_.counters_mut().cmd_rej);
        if (w == bridge::Wire::BadCrc) {
            bridge::sat_inc(self->core_.counters_mut().crc_rej);
        }
        return;
    }
    (void)self->core_.on_command(c);
}

void BridgeNode::on_ctl_cb(const lcm_recv_buf_t *rb, const char *, void *user)
{
    auto *self = static_cast<BridgeNode *>(user);
    gnc::sil_ctl_t m;
    if (m.decode(rb->data, 0, static_cast<int>(rb->data_size)) < 0) {
        return;
    }
    if (m.node_id == gnc::sil_ctl_t::NODE_PLANT && m.command == gnc::sil_ctl_t::CMD_HEARTBEAT) {
        self->core_.set_missed(m.status);
    }
    if (m.command == gnc::sil_ctl_t::CMD_STOP) {
        self->stopped_ = true;
    }
}

void BridgeNode::publish_ready()
{
    gnc::sil_ctl_t m{};
    m.command = gnc::sil_ctl_t::CMD_READY;
    m.node_id = gnc::sil_ctl_t::NODE_BRIDGE;
    const int n = m.encode(buf_.data(), 0, static_cast<int>(buf_.size()));
    if (n > 0) { lcm_publish(lcm_, kChCtl, buf_.data(), static_cast<unsigned>(n)); }
}

int BridgeNode::serve(int idle_timeout_ms)
{
    using Clock = std::chrono::steady_clock;
    auto last = Clock::now();
    while (!stopped_) {
        if (frames_ == 0) {
            publish_ready();
        }
        const int r = lcm_handle_timeout(lcm_, 100);
        if (r > 0) {
            last = Clock::now();
        } else if (std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - last).count() >
                   idle_timeout_ms) {
            return 1;
        }
    }
    return 0;
}

}  // namespace sil
