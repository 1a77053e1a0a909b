#include "pil_backend.hpp"

#include <algorithm>

#include <cinttypes>
#include <cstdio>
#include <iostream>
#include <stdexcept>
#include <utility>

extern "C" {
#include "fsw_codec.h"
#include "fx.h"
}

namespace pil {

namespace {

std::string hex(std::uint32_t v, int digits = 8)
{
    char b[16];
    std::snprintf(b, sizeof b, "0x%0*" PRIx32, digits, v);
    return b;
}

std::uint32_t le32(const std::vector<std::uint8_t> &img, std::size_t off)
{
    std::uint32_t v = 0u;
    for (std::size_t i = 0; i < 4u; ++i) {
        if (off + i < img.size()) {
            v |= static_cast<std::uint32_t>(img[off + i]) << (8u * i);
        }
    }
    return v;
}

const char *type_name(std::uint8_t t)
{
    static const char *const names[] = {"?",          "HELLO",     "SENSOR",     "CMD",   "TLM",
                                        "TABLE_CHUNK", "TABLE_ACK", "MODE_CMD",   "PING",  "PONG",
                                        "LINK_STATS", "ERROR",     "BOOT",       "BOOT_ACK", "LIMITS"};
    return (t < sizeof names / sizeof names[0]) ? names[t] : "?";
}

const char *error_name(std::uint16_t code)
{
    switch (code) {
    case FSW_PIL_E_LEN: return "E_LEN";
    case FSW_PIL_E_NOT_BOOTED: return "E_NOT_BOOTED";
    case FSW_PIL_E_TYPE: return "E_TYPE";
    case FSW_PIL_E_STAGE: return "E_STAGE";
    case FSW_PIL_E_TLM_SIZE: return "E_TLM_SIZE";
    case FSW_PIL_E_FIELD: return "E_FIELD";
    default: return "E_?";
    }
}

}  // namespace

PilBackend::PilBackend(const fsw_cfg_t &cfg, std::vector<std::uint8_t> boot_image, std::unique_ptr<LinkPort> port,
                       PilOptions opt)
    : cfg_(cfg), boot_(std::move(boot_image)), port_(std::move(port)), opt_(opt), dec_(new fsw_link_dec_t())
{
    if (!port_) {
        throw std::invalid_argument("PilBackend: no link port");
    }
    if (opt_.timeout_ms < 0 || opt_.retx < 0 || opt_.down_after < 1) {
        throw std::invalid_argument("PilBackend: timeout_ms >= 0, retx >= 0, down_after >= 1");
    }
    fsw_link_dec_init(dec_.get());
}

void PilBackend::log(const std::string &msg) const
{
    if (opt_.log) {
        std::cerr << "pil: " << msg << "\n";
    }
}

const PilCounters &PilBackend::counters()
{
    c_.rx = dec_->st;
    return c_;
}

// ------------------------------------------------------------------ link

void PilBackend::send_wire(const std::vector<std::uint8_t> &wire)
{
    if (!port_->write(wire.data(), wire.size())) {
        go_down("write failed on " + port_->describe());
        throw std::runtime_error("pil: write failed on " + port_->describe());
    }
    ++c_.tx_frames;
    c_.tx_bytes += wire.size();
}

void PilBackend::send(std::uint8_t type, std::uint16_t seq, const std::uint8_t *pay, std::uint32_t len)
{
    std::vector<std::uint8_t> wire(FSW_LINK_MAX_WIRE);
    const std::uint32_t n = fsw_link_encode(type, seq, pay, len, wire.data(), static_cast<std::uint32_t>(wire.size()));
    if (n == 0u) {
        throw std::logic_error(std::string("pil: cannot encode a ") + type_name(type) + " of " + std::to_string(len) +
                               " bytes");
    }
    wire.resize(n);
    send_wire(wire);
}

bool PilBackend::next(Rx &r, Clock::time_point deadline)
{
    std::uint8_t buf[1024];
    while (rxq_.empty()) {
        const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
        const int ms = (left <= 0) ? 0 : static_cast<int>((left > 0x7FFFFFFF) ? 0x7FFFFFFF : left);
        const long n = port_->read(buf, sizeof buf, ms);
        if (n < 0) {
            go_down("the port closed: " + port_->describe());
            throw std::runtime_error("pil: the link closed (" + port_->describe() + ")");
        }
        if (n == 0) {
            return false;
        }
        for (long i = 0; i < n; ++i) {
            if (fsw_link_rx_byte(dec_.get(), buf[i])) {
                // The decoder's payload pointer is valid only until its next byte: copy.
                const fsw_link_frame_t &f = dec_->frame;
                Rx x;
                x.type = f.type;
                x.seq = f.seq;
                x.pay.assign(f.payload, f.payload + f.len);
                rxq_.push_back(std::move(x));
                ++c_.rx_frames;
            }
        }
        if (rxq_.empty() && Clock::now() >= deadline) {
            return false;
        }
    }
    r = std::move(rxq_.front());
    rxq_.pop_front();
    return true;
}

void PilBackend::stray(const Rx &r)
{
    if (r.type == FSW_LINK_T_ERROR) {
        fsw_pil_error_t e{};
        fsw_rd_t rd;
        fsw_rd_init(&rd, r.pay.data(), static_cast<std::uint32_t>(r.pay.size()));
        if (fsw_pil_rd_error(&rd, &e)) {
            ++c_.board_errors;
            c_.last_error = e;
            log(std::string("board ERROR ") + error_name(e.code) + " (" + std::to_string(e.code) + ") on " +
                type_name(static_cast<std::uint8_t>(e.type)) + ", detail " + std::to_string(e.detail));
            return;
        }
    }
    if (r.type == FSW_LINK_T_HELLO && session_) {
        // A board that says HELLO unasked has restarted: its executive state is gone, and flying
        // on would command from a state nobody booted. The run ends (link down) and says why.
        ++c_.board_resets;
        go_down("the board restarted during the session (unsolicited HELLO)");
    }
    ++c_.unexpected;
}

PilBackend::Result PilBackend::transact(std::uint8_t type, const std::vector<std::uint8_t> &pay, std::uint8_t reply_type,
                                        Rx &reply)
{
    // Each request gets its own link seq; the board echoes it in the reply, so a late reply to
    // an earlier request can never be taken for this one's. Retransmissions keep the seq.
    const std::uint16_t seq = next_ctl_seq();
    for (int attempt = 0; attempt <= opt_.retx; ++attempt) {
        if (attempt > 0) {
            ++c_.retx;
        }
        send(type, seq, pay.data(), static_cast<std::uint32_t>(pay.size()));
        const Clock::time_point deadline =
            Clock::now() + std::chrono::milliseconds(std::max(opt_.timeout_ms, opt_.ctl_timeout_ms));
        Rx r;
        while (next(r, deadline)) {
            if (r.type == reply_type && r.seq == seq) {
                reply = std::move(r);
                return Result::Ok;
            }
            const std::uint64_t errs = c_.board_errors;
            stray(r);
            // The board refused this request (it names its type): sending it again cannot help.
            if (c_.board_errors != errs && c_.last_error.type == type) {
                return Result::Refused;
            }
        }
        ++c_.timeouts;
    }
    return Result::NoReply;
}

void PilBackend::go_down(const std::string &why)
{
    if (!c_.link_down) {
        log("link down: " + why);
    }
    c_.link_down = true;
}

// ------------------------------------------------------------------ session

void PilBackend::handshake()
{
    // The board says HELLO when it starts; wait for that first (a QEMU guest starts when we
    // connect). Ask when it does not come, or at once when this is not the first session.
    bool got = false;
    const std::uint16_t seq = next_ctl_seq();
    for (int attempt = 0; attempt <= opt_.retx && !got; ++attempt) {
        if (attempt > 0 || hello_seen_) {
            if (attempt > 0) {
                ++c_.retx;
            }
            send(static_cast<std::uint8_t>(FSW_LINK_T_HELLO), seq, nullptr, 0u);
        }
        const Clock::time_point deadline =
            Clock::now() + std::chrono::milliseconds(std::max(opt_.timeout_ms, opt_.ctl_timeout_ms));
        Rx r;
        while (!got && next(r, deadline)) {
            if (r.type != FSW_LINK_T_HELLO) {
                stray(r);
                continue;
            }
            fsw_rd_t rd;
            fsw_rd_init(&rd, r.pay.data(), static_cast<std::uint32_t>(r.pay.size()));
            fsw_pil_hello_t h{};
            if (r.pay.size() != FSW_PIL_HELLO_BYTES || !fsw_pil_rd_hello(&rd, &h)) {
                ++c_.unexpected;
                log("HELLO of " + std::to_string(r.pay.size()) + " bytes ignored");
                continue;
            }
            hello_ = h;
            got = true;
        }
        if (!got) {
            ++c_.timeouts;
        }
    }
    if (!got) {
        throw std::runtime_error("pil: no HELLO from the board on " + port_->describe() + " (" +
                                 std::to_string(opt_.retx + 1) + " x " +
                                 std::to_string(std::max(opt_.timeout_ms, opt_.ctl_timeout_ms)) + " ms)");
    }
    hello_seen_ = true;
    const std::string board = "board " + hex(hello_.board_id, 4) + " build " + hex(hello_.build_id);
    if (hello_.version != FSW_LINK_VERSION) {
        throw std::runtime_error("pil: link protocol version mismatch: " + board + " speaks " +
                                 hex(hello_.version, 2) + ", host " + hex(FSW_LINK_VERSION, 2));
    }
    if (hello_.layout_hash != opt_.expect_hash) {
        throw std::runtime_error("pil: layout hash mismatch: " + board + " has " + hex(hello_.layout_hash) +
                                 ", host expects " + hex(opt_.expect_hash) +
                                 " (the two builds encode some payload differently: rebuild both from one tree)");
    }
    if (cfg_.mission >= 32u || ((hello_.missions >> cfg_.mission) & 1u) == 0u) {
        throw std::runtime_error("pil: " + board + " does not carry mission " + std::to_string(cfg_.mission) +
                                 " (its missions: " + hex(hello_.missions) + ")");
    }
}

bool PilBackend::stage_once()
{
    const std::uint32_t total = static_cast<std::uint32_t>(boot_.size());
    fsw_table_chunk_t c{};
    c.table_id = static_cast<std::uint16_t>(le32(boot_, 0) & 0xFFFFu);
    c.revision = le32(boot_, 8);
    c.total_len = total;
    for (std::uint32_t off = 0; off < total; off += FSW_TABLE_CHUNK_MAX) {
        c.offset = off;
        c.n = ((total - off) < FSW_TABLE_CHUNK_MAX) ? (total - off) : FSW_TABLE_CHUNK_MAX;
        c.data = boot_.data() + off;
        std::vector<std::uint8_t> pay(FSW_PIL_CHUNK_HEAD_BYTES + c.n);
        fsw_wr_t w;
        fsw_wr_init(&w, pay.data(), static_cast<std::uint32_t>(pay.size()));
        fsw_pil_wr_chunk(&w, &c);
        Rx r;
        const Result res = transact(static_cast<std::uint8_t>(FSW_LINK_T_TABLE_CHUNK), pay,
                                    static_cast<std::uint8_t>(FSW_LINK_T_TABLE_ACK), r);
        if (res == Result::Refused && c_.last_error.code == FSW_PIL_E_STAGE) {
            return false;   // the board dropped what it had staged: start over
        }
        if (res != Result::Ok) {
            throw std::runtime_error("pil: boot-image chunk at offset " + std::to_string(off) +
                                     (res == Result::Refused ? std::string(": board ERROR ") + error_name(c_.last_error.code)
                                                             : std::string(": no TABLE_ACK")) +
                                     " (" + port_->describe() + ")");
        }
        fsw_pil_ack_t a{};
        fsw_rd_t rd;
        fsw_rd_init(&rd, r.pay.data(), static_cast<std::uint32_t>(r.pay.size()));
        if (!fsw_pil_rd_ack(&rd, &a)) {
            throw std::runtime_error("pil: malformed TABLE_ACK to the boot-image chunk at offset " + std::to_string(off));
        }
        const bool last = (off + c.n == total);
        if (a.result == FSW_PIL_ACK_REJECTED) {
            throw std::runtime_error("pil: board refused the boot-image chunk at offset " + std::to_string(off) +
                                     ": reason " + hex(a.reason));
        }
        if (a.result != (last ? FSW_PIL_ACK_ACCEPTED : FSW_PIL_ACK_PARTIAL) || a.bytes_received != off + c.n) {
            throw std::runtime_error("pil: boot-image chunk at offset " + std::to_string(off) + ": board acked result " +
                                     std::to_string(a.result) + " with " + std::to_string(a.bytes_received) +
                                     " bytes staged, expected " + std::to_string(off + c.n));
        }
    }
    return true;
}

void PilBackend::stage()
{
    if (boot_.size() > FSW_TABLE_CAP_BYTES) {
        throw std::runtime_error("pil: boot image of " + std::to_string(boot_.size()) +
                                 " bytes exceeds the board's staging buffer (" + std::to_string(FSW_TABLE_CAP_BYTES) + ")");
    }
    for (int round = 0; round <= opt_.retx; ++round) {
        if (stage_once()) {
            return;
        }
        log("the board restarted the boot-image staging (E_STAGE): sending it again from offset 0");
    }
    throw std::runtime_error("pil: the board refused the boot-image staging " + std::to_string(opt_.retx + 1) + " times");
}

bool PilBackend::decode_limits(const std::uint8_t *p, std::size_t n, bridge::SensorLimits &lim) const
{
    fsw_range_t r[FSW_IN_MAX] = {};
    std::uint32_t nr = 0u;
    fsw_rd_t rd;
    fsw_rd_init(&rd, p, static_cast<std::uint32_t>(n));
    if (!fsw_pil_rd_ranges(&rd, r, &nr) || rd.pos != rd.len) {
        return false;
    }
    // InProcessFswBackend::sensor_limits' mapping: a range with min > max (no table) stays open.
    lim = bridge::SensorLimits{};
    lim.n_channels = static_cast<std::int16_t>(nr);
    lim.period_us = static_cast<std::int32_t>(cfg_.period_us);
    for (std::size_t i = 0; i < nr && i < bridge::kMaxCounts; ++i) {
        if (r[i].min <= r[i].max) {
            lim.ch[i].min = r[i].min;
            lim.ch[i].max = r[i].max;
        }
    }
    return true;
}

void PilBackend::boot()
{
    fsw_pil_boot_t b{};
    b.cfg = cfg_;
    b.image_len = static_cast<std::uint32_t>(boot_.size());
    b.image_crc = boot_.empty() ? 0u : fx_crc32(0u, boot_.data(), boot_.size());
    std::vector<std::uint8_t> pay(FSW_PIL_BOOT_BYTES);
    fsw_wr_t w;
    fsw_wr_init(&w, pay.data(), static_cast<std::uint32_t>(pay.size()));
    fsw_pil_wr_boot(&w, &b);
    Rx r;
    const Result res = transact(static_cast<std::uint8_t>(FSW_LINK_T_BOOT), pay,
                                static_cast<std::uint8_t>(FSW_LINK_T_BOOT_ACK), r);
    if (res != Result::Ok) {
        throw std::runtime_error(std::string("pil: BOOT: ") +
                                 (res == Result::Refused ? std::string("board ERROR ") + error_name(c_.last_error.code)
                                                         : std::string("no BOOT_ACK")) +
                                 " (" + port_->describe() + ")");
    }
    fsw_rd_t rd;
    fsw_rd_init(&rd, r.pay.data(), static_cast<std::uint32_t>(r.pay.size()));
    const std::int32_t rc = fsw_rd_i32(&rd);
    const std::uint32_t reason = fsw_rd_u32(&rd);
    const std::uint32_t lim_gen = fsw_rd_u32(&rd);
    bridge::SensorLimits lim{};
    if (rd.err || !decode_limits(r.pay.data() + rd.pos, r.pay.size() - rd.pos, lim)) {
        throw std::runtime_error("pil: malformed BOOT_ACK (" + std::to_string(r.pay.size()) + " bytes)");
    }
    boot_rc_ = rc;
    boot_reason_ = reason;
    limits_ = lim;
    lim_gen_ = lim_gen;
    if (rc != 0) {
        log("BOOT: rc " + std::to_string(rc) + ", reason " + hex(reason));
    }
}

bool PilBackend::reset()
{
    if (booted_) {
        // The board keeps its boot across a host HELLO: chunks would now go to the flying
        // table upload, not to the staging buffer. A new session needs a restarted board.
        throw std::runtime_error("pil: reset() after a BOOT on " + port_->describe() +
                                 ": restart the board (it stays booted across HELLO)");
    }
    session_ = false;
    c_.link_down = false;
    fails_in_row_ = 0;
    have_unanswered_ = false;
    limits_pending_ = false;
    boot_rc_ = -1;
    // One delimiter first: whatever half frame the board's decoder holds (line noise, a host
    // that died mid-frame) ends here as an error or an empty run, not as the start of HELLO.
    const std::uint8_t sync = 0u;
    if (!port_->write(&sync, 1u)) {
        throw std::runtime_error("pil: write failed on " + port_->describe());
    }
    handshake();
    stage();
    boot();
    booted_ = true;
    session_ = true;
    return boot_rc_ == 0;
}

// ------------------------------------------------------------------ flying

void PilBackend::host_counters(const bridge::Counters &c) { bridge::set_host_counters(pend_, c); }

bool PilBackend::command(const bridge::FswCommand &c) { return bridge::hold_command(pend_, c); }

bool PilBackend::limits_changed(bridge::SensorLimits &lim)
{
    if (!limits_pending_) {
        return false;
    }
    limits_pending_ = false;
    lim = limits_;
    return true;
}

bool PilBackend::step(const bridge::Frame &f, bridge::StepOutput &out)
{
    if (c_.link_down || !session_) {
        return false;
    }
    const std::uint16_t seq = static_cast<std::uint16_t>(static_cast<std::uint64_t>(f.seq) & 0xFFFFu);
    if (!(have_unanswered_ && unanswered_seq_ == f.seq)) {
        const fsw_in_t in = bridge::make_fsw_in(f, pend_);
        std::uint8_t pay[FSW_PIL_SENSOR_BYTES];
        fsw_wr_t w;
        fsw_wr_init(&w, pay, sizeof pay);
        fsw_pil_wr_sensor(&w, &in);
        sensor_wire_.assign(FSW_LINK_MAX_WIRE, 0u);
        const std::uint32_t n = fsw_link_encode(static_cast<std::uint8_t>(FSW_LINK_T_SENSOR), seq, pay, w.pos,
                                                sensor_wire_.data(), static_cast<std::uint32_t>(sensor_wire_.size()));
        sensor_wire_.resize(n);
        have_unanswered_ = true;
        unanswered_seq_ = f.seq;
    }

    bool got_cmd = false, got_tlm = false, got_lim = false;
    fsw_pil_cmd_t cmd{};
    Rx tlm;
    bridge::SensorLimits lim{};
    // Complete: CMD and TLM, and the LIMITS frame when CMD says the ranges changed (lim_gen
    // moved): a step whose LIMITS was lost is asked again, so the bridge never flies on old
    // limits while SIL would use the new ones.
    auto complete = [&]() { return got_cmd && got_tlm && (got_lim || cmd.lim_gen == lim_gen_); };
    try {
        for (int attempt = 0; attempt <= opt_.retx && !complete(); ++attempt) {
            if (attempt > 0) {
                ++c_.retx;
            }
            // A re-sent SENSOR k is answered from the board's cache when k reached it before:
            // the board steps once per seq, whatever the link lost.
            send_wire(sensor_wire_);
            const Clock::time_point deadline = Clock::now() + std::chrono::milliseconds(opt_.timeout_ms);
            Rx r;
            while (!complete() && next(r, deadline)) {
                if (r.seq != seq) {
                    stray(r);
                } else if (r.type == FSW_LINK_T_CMD) {
                    fsw_rd_t rd;
                    fsw_rd_init(&rd, r.pay.data(), static_cast<std::uint32_t>(r.pay.size()));
                    fsw_pil_cmd_t c{};
                    if (r.pay.size() == FSW_PIL_CMD_BYTES && fsw_pil_rd_cmd(&rd, &c) && c.seq == f.seq) {
                        cmd = c;
                        got_cmd = true;
                    } else {
                        ++c_.unexpected;   // same link seq, another frame (seq wrapped) or malformed
                    }
                } else if (r.type == FSW_LINK_T_TLM) {
                    if (r.pay.size() >= FSW_PIL_TLM_HEAD_BYTES &&
                        r.pay.size() - FSW_PIL_TLM_HEAD_BYTES <= bridge::kMaxTlm) {
                        tlm = std::move(r);
                        got_tlm = true;
                    } else {
                        ++c_.unexpected;
                    }
                } else if (r.type == FSW_LINK_T_LIMITS) {
                    if (decode_limits(r.pay.data(), r.pay.size(), lim)) {
                        got_lim = true;
                    } else {
                        ++c_.unexpected;
                    }
                } else {
                    stray(r);
                }
            }
            if (!complete()) {
                ++c_.timeouts;
            }
        }
    } catch (const std::runtime_error &) {
        // The port failed or closed (go_down has run): no output from this step, nor any later.
        ++c_.missed_steps;
        return false;
    }
    if (!complete()) {
        ++c_.missed_steps;
        if (++fails_in_row_ >= opt_.down_after) {
            go_down(std::to_string(fails_in_row_) + " steps in a row without CMD and TLM (" + port_->describe() + ")");
        }
        return false;
    }
    fails_in_row_ = 0;
    have_unanswered_ = false;
    if (got_lim) {
        limits_ = lim;
        limits_pending_ = true;
    }
    lim_gen_ = cmd.lim_gen;

    fsw_rd_t rd;
    fsw_rd_init(&rd, tlm.pay.data(), static_cast<std::uint32_t>(tlm.pay.size()));
    const std::uint32_t insn = fsw_rd_u32(&rd);
    const std::uint32_t layout = fsw_rd_u32(&rd);
    insn_.push_back(insn);

    out = bridge::StepOutput{};
    out.n_counts = static_cast<std::int16_t>(cmd.n_act);
    for (std::size_t i = 0; i < cmd.n_act && i < bridge::kMaxCounts; ++i) {
        out.counts[i] = cmd.act_cnt[i];
    }
    out.fsw_mode = static_cast<std::int32_t>(cmd.mode);
    out.fsw_health = cmd.health;
    out.tlm_layout_version = static_cast<std::int32_t>(layout);
    const std::size_t tl = tlm.pay.size() - FSW_PIL_TLM_HEAD_BYTES;
    out.tlm_len = static_cast<std::int16_t>(tl);
    for (std::size_t i = 0; i < tl; ++i) {
        out.tlm[i] = tlm.pay[FSW_PIL_TLM_HEAD_BYTES + i];
    }
    return true;
}

bool PilBackend::table_chunk(const bridge::TableChunk &c, bridge::TableAck &ack)
{
    ack = bridge::TableAck{};
    ack.table_id = c.table_id;
    ack.revision = c.revision;
    // InProcessFswBackend's own refusals, word for word; n == 0 too, which the link cannot carry
    // (fsw_pil_rd_chunk refuses it) and the loader refuses with the same reason.
    if (c.table_id < 0 || c.table_id > 0xFFFF || c.revision < 0 || c.total_len < 0 || c.offset < 0 || c.n <= 0 ||
        static_cast<std::size_t>(c.n) > bridge::kMaxChunk || c.data == nullptr) {
        ack.result = bridge::kTableRejected;
        ack.reason = static_cast<std::int32_t>(FSW_TBL_R_CHUNK_LEN);
        return true;
    }
    if (c_.link_down || !session_) {
        return false;
    }
    fsw_table_chunk_t ch{};
    ch.table_id = static_cast<std::uint16_t>(c.table_id);
    ch.revision = static_cast<std::uint32_t>(c.revision);
    ch.total_len = static_cast<std::uint32_t>(c.total_len);
    ch.offset = static_cast<std::uint32_t>(c.offset);
    ch.n = static_cast<std::uint32_t>(c.n);
    ch.data = c.data;
    std::vector<std::uint8_t> pay(FSW_PIL_CHUNK_HEAD_BYTES + ch.n);
    fsw_wr_t w;
    fsw_wr_init(&w, pay.data(), static_cast<std::uint32_t>(pay.size()));
    fsw_pil_wr_chunk(&w, &ch);
    Rx r;
    Result res;
    try {
        res = transact(static_cast<std::uint8_t>(FSW_LINK_T_TABLE_CHUNK), pay,
                       static_cast<std::uint8_t>(FSW_LINK_T_TABLE_ACK), r);
    } catch (const std::runtime_error &) {
        return false;
    }
    fsw_pil_ack_t a{};
    fsw_rd_t rd;
    fsw_rd_init(&rd, r.pay.data(), static_cast<std::uint32_t>(r.pay.size()));
    if (res != Result::Ok || !fsw_pil_rd_ack(&rd, &a)) {
        return false;
    }
    ack.table_id = static_cast<std::int32_t>(a.table_id);
    ack.revision = bridge::bits_to_i32(a.revision);
    ack.result = static_cast<std::int32_t>(a.result);   // FSW_PIL_ACK_* == the bridge's kTable*
    ack.reason = bridge::bits_to_i32(a.reason);
    ack.bytes_received = bridge::bits_to_i32(a.bytes_received);
    return true;
}

// ------------------------------------------------------------------ diagnostics

std::optional<fsw_pil_stats_t> PilBackend::link_stats()
{
    Rx r;
    try {
        if (transact(static_cast<std::uint8_t>(FSW_LINK_T_LINK_STATS), {}, static_cast<std::uint8_t>(FSW_LINK_T_LINK_STATS),
                     r) != Result::Ok) {
            return std::nullopt;
        }
    } catch (const std::runtime_error &) {
        return std::nullopt;
    }
    fsw_pil_stats_t s{};
    fsw_rd_t rd;
    fsw_rd_init(&rd, r.pay.data(), static_cast<std::uint32_t>(r.pay.size()));
    if (r.pay.size() != FSW_PIL_STATS_BYTES || !fsw_pil_rd_stats(&rd, &s)) {
        ++c_.unexpected;
        return std::nullopt;
    }
    return s;
}

bool PilBackend::ping(const std::vector<std::uint8_t> &payload)
{
    if (payload.size() > FSW_PIL_PING_MAX) {
        return false;
    }
    Rx r;
    try {
        return transact(static_cast<std::uint8_t>(FSW_LINK_T_PING), payload, static_cast<std::uint8_t>(FSW_LINK_T_PONG),
                        r) == Result::Ok &&
               r.pay == payload;
    } catch (const std::runtime_error &) {
        return false;
    }
}

bool PilBackend::end_session()
{
    std::vector<std::uint8_t> pay(4);
    fsw_wr_t w;
    fsw_wr_init(&w, pay.data(), static_cast<std::uint32_t>(pay.size()));
    fsw_wr_u32(&w, FSW_PIL_MODE_END);
    Rx r;
    bool ok = false;
    try {
        ok = transact(static_cast<std::uint8_t>(FSW_LINK_T_MODE_CMD), pay, static_cast<std::uint8_t>(FSW_LINK_T_MODE_CMD),
                      r) == Result::Ok &&
             r.pay == pay;
    } catch (const std::runtime_error &) {
        ok = false;
    }
    session_ = false;
    return ok;
}

bool PilBackend::inject_reset()
{
    std::vector<std::uint8_t> pay(4);
    fsw_wr_t w;
    fsw_wr_init(&w, pay.data(), static_cast<std::uint32_t>(pay.size()));
    fsw_wr_u32(&w, FSW_PIL_MODE_RESET);
    Rx r;
    return transact(static_cast<std::uint8_t>(FSW_LINK_T_MODE_CMD), pay, static_cast<std::uint8_t>(FSW_LINK_T_MODE_CMD),
                    r) == Result::Ok &&
           r.pay == pay;
}

}  // namespace pil
