// pil_backend.hpp — the bridge's `pil` backend (spec 00 §6.1): the flight software on a board
// (or QEMU, or the board session in this process) behind the framed serial link.
//
// Same interface and same meaning as InProcessFswBackend: a frame becomes the same fsw_in_t
// (bridge::make_fsw_in), the board's executive steps it, and CMD/TLM come back as the same
// StepOutput. The link is fsw/app/fsw_link (framing) and fsw/app/fsw_pil (payloads), the C code
// the board runs, so both ends read every byte the same way. Session and retransmission rules:
// hil_host/pil/README.md.
#ifndef HIL_PIL_BACKEND_HPP
#define HIL_PIL_BACKEND_HPP

#include <chrono>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "backend.hpp"
#include "frame_validator.hpp"
#include "fsw_backend.hpp"
#include "link_port.hpp"

extern "C" {
#include "fsw_link.h"
#include "fsw_pil.h"
}

namespace pil {

struct PilOptions {
    int timeout_ms = 2000;   // per SENSOR transmission: how long to wait for CMD and TLM
    // Control requests (HELLO, boot staging, BOOT, uploads, stats, END) wait at least this long:
    // they are rare, and a 256-byte chunk takes tens of ms through QEMU's UART under -icount,
    // so a step timeout tuned for fault tests must not starve the boot.
    int ctl_timeout_ms = 2000;
    int retx = 3;            // retransmissions of one request after the first
    int down_after = 5;      // consecutive steps without a reply: the link is down
    std::uint32_t expect_hash = fsw_pil_layout_hash();   // the host's own layout unless a test says otherwise
    bool log = true;         // board ERRORs and link events to stderr
};

struct PilCounters {
    std::uint64_t tx_frames = 0;      // frames written (retransmissions included)
    std::uint64_t tx_bytes = 0;       // their bytes on the wire
    std::uint64_t board_resets = 0;   // unsolicited HELLOs during the session: the board restarted
    std::uint64_t rx_frames = 0;      // frames the decoder accepted
    std::uint64_t retx = 0;           // retransmissions (any request)
    std::uint64_t timeouts = 0;       // transmissions whose reply did not come in time
    std::uint64_t missed_steps = 0;   // step() calls that produced no output
    std::uint64_t unexpected = 0;     // accepted frames nobody was waiting for (late duplicates, ...)
    std::uint64_t board_errors = 0;   // ERROR packets received
    fsw_pil_error_t last_error{};     // the latest of them
    bool link_down = false;
    fsw_link_stats_t rx{};            // the host decoder's counters
};

class PilBackend final : public bridge::Backend {
public:
    // cfg and boot_image as InProcessFswBackend's (an empty image boots without a table). No
    // I/O here: reset() opens the session.
    PilBackend(const fsw_cfg_t &cfg, std::vector<std::uint8_t> boot_image, std::unique_ptr<LinkPort> port,
               PilOptions opt = PilOptions{});

    // HELLO (version, layout hash, mission checked: std::runtime_error naming both values on a
    // mismatch), boot-image staging, BOOT. True when the board's fsw_init said FSW_OK; throws
    // when the link does not carry the session (no reply after the retransmissions, port closed,
    // staging refused). After a false the board steps in SAFE, as the in-process executive does.
    bool reset() override;
    bool step(const bridge::Frame &f, bridge::StepOutput &out) override;
    const char *name() const override { return "pil"; }
    void host_counters(const bridge::Counters &c) override;
    // One chunk to the board's fsw_table_upload; false when the board did not answer (the
    // bridge then acks REJECTED itself and counts it).
    bool table_chunk(const bridge::TableChunk &c, bridge::TableAck &ack) override;
    bool command(const bridge::FswCommand &c) override;
    bool limits_changed(bridge::SensorLimits &lim) override;

    // BOOT_ACK's verdict: fsw_init's fsw_rc_t, or FSW_PIL_BOOT_BAD_IMAGE / _BAD_CFG (negative).
    std::int32_t boot_rc() const { return boot_rc_; }
    std::uint32_t boot_reason() const { return boot_reason_; }
    // The board's channel ranges (BOOT_ACK, then every LIMITS) as the bridge's validator limits,
    // mapped exactly as InProcessFswBackend::sensor_limits().
    bridge::SensorLimits sensor_limits() const { return limits_; }
    const fsw_pil_hello_t &hello() const { return hello_; }
    bool link_down() const { return c_.link_down; }
    const PilCounters &counters();
    // TLM's instruction count of every step that produced output, in order (0 from the host harness).
    const std::vector<std::uint32_t> &insn() const { return insn_; }

    // LINK_STATS: the board's counters; nullopt when it does not answer.
    std::optional<fsw_pil_stats_t> link_stats();
    // PING with payload (<= FSW_PIL_PING_MAX bytes): true when PONG echoes it.
    bool ping(const std::vector<std::uint8_t> &payload);
    // MODE_CMD END: the board acknowledges and leaves its session (the QEMU image then exits 0).
    bool end_session();
    // Fault injection (spec 00 §8 "board reset mid-run"): MODE_CMD RESET, the board acknowledges and
    // resets. The backend is not told: it must find the restarted board by itself (its HELLO).
    bool inject_reset();

    LinkPort &port() { return *port_; }

private:
    using Clock = std::chrono::steady_clock;
    struct Rx {
        std::uint8_t type = 0;
        std::uint16_t seq = 0;
        std::vector<std::uint8_t> pay;
    };
    enum class Result { Ok, NoReply, Refused };

    void send(std::uint8_t type, std::uint16_t seq, const std::uint8_t *pay, std::uint32_t len);
    void send_wire(const std::vector<std::uint8_t> &wire);
    bool next(Rx &r, Clock::time_point deadline);
    void stray(const Rx &r);
    Result transact(std::uint8_t type, const std::vector<std::uint8_t> &pay, std::uint8_t reply_type, Rx &reply);
    std::uint16_t next_ctl_seq() { return ++ctl_seq_; }
    void handshake();
    void stage();
    bool stage_once();
    void boot();
    bool decode_limits(const std::uint8_t *p, std::size_t n, bridge::SensorLimits &lim) const;
    void go_down(const std::string &why);
    void log(const std::string &msg) const;

    fsw_cfg_t cfg_{};
    std::vector<std::uint8_t> boot_;
    std::unique_ptr<LinkPort> port_;
    PilOptions opt_;
    std::unique_ptr<fsw_link_dec_t> dec_;   // ~1 KiB of buffers: with the object, not the stack
    std::deque<Rx> rxq_;
    PilCounters c_{};
    fsw_pil_hello_t hello_{};
    bool hello_seen_ = false;
    bool session_ = false;                  // reset() got through BOOT
    bool booted_ = false;                   // a BOOT_ACK came: the board is booted for good
    std::int32_t boot_rc_ = -1;
    std::uint32_t boot_reason_ = 0;
    bridge::SensorLimits limits_{};
    bool limits_pending_ = false;
    std::uint32_t lim_gen_ = 0;             // the board's limits generation (BOOT_ACK, then each CMD)
    bridge::FswPending pend_;
    std::uint16_t ctl_seq_ = 0;
    int fails_in_row_ = 0;
    // The SENSOR of a step that got no reply: a step() on the same frame seq re-sends exactly
    // these bytes, so the commands it carried are neither lost nor applied twice.
    bool have_unanswered_ = false;
    std::int64_t unanswered_seq_ = 0;
    std::vector<std::uint8_t> sensor_wire_;
    std::vector<std::uint32_t> insn_;
};

}  // namespace pil

#endif  // HIL_PIL_BACKEND_HPP
