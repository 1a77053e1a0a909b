// metrics.hpp — the live metrics of a SIL run, from the LCM stream: what every mission has
// (telemetry decoded in its generated layout, the executive's counters, the bridge's counters,
// the first fx status bit, table acks) and the mission's own part (host::MissionMetrics of
// hil_host/missions/<module>). Used by `sil run` / `sil plant` for summary.txt and summary.json,
// and by the SIL tests.
#ifndef HIL_SIL_METRICS_HPP
#define HIL_SIL_METRICS_HPP

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <lcm/lcm.h>

#include "bridge_types.hpp"
#include "mission_host.hpp"

namespace sil {

struct CoreMetrics {
    std::uint64_t truth_n = 0, cmd_n = 0, tlm_n = 0, ack_n = 0;
    std::uint64_t tlm_bad = 0;                    // frames whose tlm failed to decode
    double t_first_fx_s = -1.0;                   // first fx status bit (unexpected saturation), -1 = never
    std::uint32_t first_fx_bits = 0;
    std::int32_t last_ack_result = -1, last_ack_reason = 0;
    std::map<std::string, std::int64_t> tlm;      // last decoded telemetry fields (raw)
    // Last bridge counters of fsw_tlm_frame_t, in kFrameCounters order (metrics.cpp). Plain integers:
    // a name-keyed map rebuilt every frame was a tenth of a Release batch run (allocations per tick).
    std::array<std::int64_t, 8> bridge{};
    // Table uploads as the ground sees them: final acks (a PARTIAL ack is one chunk stored).
    std::uint64_t ack_accepted = 0, ack_rejected = 0;
    std::int64_t tbl_revision_first = -1;         // active revision in the first telemetry
    std::int64_t n_tbl_acc_last = 0;              // executive commit counter, last telemetry
    double t_tbl_commit_s = -1.0;                 // last telemetry whose commit counter moved, -1 = none
    // FNV-1a 64 of every command and every telemetry message, bytes as published, in arrival
    // order: two runs with equal digests produced the same streams (the determinism check).
    std::uint64_t digest_cmd = 0xCBF29CE484222325u, digest_tlm = 0xCBF29CE484222325u;
};

// One of CoreMetrics::bridge by its fsw_tlm_frame_t name ("missed", "gaps", ...); -1 if no such counter.
std::int64_t frame_counter(const CoreMetrics &m, const std::string &name);

class MetricsTap {
public:
    // lcm null: no subscriptions; the messages come through feed() (the batch driver, batch.hpp).
    MetricsTap(lcm_t *lcm, const sim::Scenario &scn);
    ~MetricsTap();
    // One message as the LCM callbacks would receive it (channel: channels.hpp).
    void feed(const char *channel, const std::uint8_t *data, std::size_t len);
    MetricsTap(const MetricsTap &) = delete;
    MetricsTap &operator=(const MetricsTap &) = delete;
    // The metrics so far; tlm is filled here from the last decoded telemetry (decoding every
    // message into a name map would cost most of a long run, so the tap keeps raw values).
    const CoreMetrics &core() const;
    const host::MissionMetrics &mission() const { return *mission_; }
    std::shared_ptr<const host::MissionMetrics> mission_ptr() const { return mission_; }
    // The core's keys (executive, bridge and table counters, decoded table reason, stream
    // digests), then the mission's. bridge_final: the bridge core's own counters at the end of
    // the run (in process); without it (the bridge is another process) the bridge keys are
    // those of the last telemetry frame, which cannot count a frame that arrived after it.
    void summary(host::Summary &s, const bridge::Counters *bridge_final = nullptr) const;

private:
    static void on_truth(const lcm_recv_buf_t *rb, const char *ch, void *user);
    static void on_cmd(const lcm_recv_buf_t *rb, const char *ch, void *user);
    static void on_tlm(const lcm_recv_buf_t *rb, const char *ch, void *user);
    static void on_ack(const lcm_recv_buf_t *rb, const char *ch, void *user);
    lcm_t *lcm_;
    const iface::Mission &im_;
    const host::TlmLayout &layout_;
    std::shared_ptr<host::MissionMetrics> mission_;
    std::size_t i_health_;
    std::size_t i_tbl_rev_, i_tbl_acc_;
    std::vector<std::int64_t> last_;     // raw values of the last telemetry, in layout order
    lcm_subscription_t *subs_[4] = {nullptr, nullptr, nullptr, nullptr};
    mutable CoreMetrics m_{};
};

}  // namespace sil

#endif  // HIL_SIL_METRICS_HPP
