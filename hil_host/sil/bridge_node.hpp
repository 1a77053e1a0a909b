// bridge_node.hpp — the LCM shell around bridge::Bridge (hil_host/bridge): decode, hand to the
// core, publish what the core says. Subscribes GNC_SENSOR, GNC_TBL_UP, GNC_CTL, GNC_FSW_CMD; publishes
// GNC_CMD, GNC_TLM, GNC_TBL_ACK (never a channel it subscribes to: udpm loops them back).
#ifndef HIL_SIL_BRIDGE_NODE_HPP
#define HIL_SIL_BRIDGE_NODE_HPP

#include <cstdint>
#include <vector>

#include <lcm/lcm.h>

#include "bridge.hpp"

namespace sil {

// One table_upload_v2_t message as received (sealed bytes) through the core: a message that does not
// decode is counted (crc_rej or malformed; *bad set) and refused as FSW_TBL_R_CHUNK_LEN. Writes the
// encoded table_ack_t to ack_buf and returns its length (< 0: did not fit). BridgeNode publishes it;
// the batch driver hands it to the metrics.
int table_upload_to_ack(bridge::Bridge &core, const std::uint8_t *data, std::size_t len, std::uint8_t *ack_buf,
                        std::size_t ack_cap, bool *bad);

class BridgeNode {
public:
    BridgeNode(lcm_t *lcm, bridge::Bridge &core);
    ~BridgeNode();
    BridgeNode(const BridgeNode &) = delete;
    BridgeNode &operator=(const BridgeNode &) = delete;

    // Separate-process mode: announce READY until the first frame, then serve until STOP (or
    // idle_timeout_ms without any message). Returns 0 on STOP, 1 on idle timeout.
    int serve(int idle_timeout_ms);
    bool stopped() const { return stopped_; }
    std::uint64_t frames() const { return frames_; }
    std::uint64_t bad_uploads() const { return bad_uploads_; }

private:
    static void on_sensor_cb(const lcm_recv_buf_t *rb, const char *ch, void *user);
    static void on_table_cb(const lcm_recv_buf_t *rb, const char *ch, void *user);
    static void on_ctl_cb(const lcm_recv_buf_t *rb, const char *ch, void *user);
    static void on_fsw_cmd_cb(const lcm_recv_buf_t *rb, const char *ch, void *user);
    void publish_ready();

    lcm_t *lcm_;
    bridge::Bridge &core_;
    lcm_subscription_t *subs_[4] = {nullptr, nullptr, nullptr, nullptr};
    std::vector<std::uint8_t> buf_;
    bool stopped_ = false;
    std::uint64_t frames_ = 0;
    std::uint64_t bad_uploads_ = 0;
};

}  // namespace sil

#endif  // HIL_SIL_BRIDGE_NODE_HPP
