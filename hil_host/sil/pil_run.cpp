#include "pil_run.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <vector>

#include "sil_run.hpp"

namespace sil {

std::string PilRunOptions::describe() const
{
    if (loopback) {
        return "pil-loopback";
    }
    if (!serial.empty()) {
        return "pil-serial:" + serial + "@" + std::to_string(baud);
    }
    return "pil-qemu:" + machine;
}

PilRun::PilRun(const sim::Scenario &scn, const PilRunOptions &opt) : opt_(opt)
{
    const host::MissionHost &mh = host::mission_host(scn.mission);
    std::unique_ptr<pil::LinkPort> port;
    if (opt.loopback) {
        port.reset(new pil::LoopbackBoardPort());
    } else if (!opt.serial.empty()) {
        port = pil::open_serial(opt.serial, opt.baud);
    } else {
        pil::QemuOptions q;
        q.qemu_run = std::string(FSW_SOURCE_DIR) + "/tools/qemu-run.sh";
        q.machine = opt.machine;
        q.elf = opt.elf;
        q.dir = opt.dir.empty() ? std::string(".") : opt.dir;
        q.timeout_s = opt.qemu_timeout_s;
        qemu_.reset(new pil::QemuBoard(q));
        port = qemu_->port();
    }
    if (opt.drop_ppm != 0u || opt.flip_ppm != 0u || opt.trunc_ppm != 0u || opt.silent_at >= 0) {
        pil::FaultPortConfig fc;
        fc.seed = opt.fault_seed;
        fc.to_board.drop_ppm = fc.to_host.drop_ppm = opt.drop_ppm;
        fc.to_board.bitflip_ppm = fc.to_host.bitflip_ppm = opt.flip_ppm;
        fc.to_board.truncate_ppm = fc.to_host.truncate_ppm = opt.trunc_ppm;
        faults_ = new pil::FaultyPort(std::move(port), fc);
        port.reset(faults_);
    }
    period_s_ = static_cast<double>(scn.period_us) * 1e-6;
    pil::PilOptions po;
    if (opt.expect_hash_set) {
        po.expect_hash = opt.expect_hash;
    }
    po.timeout_ms = opt.timeout_ms;
    po.retx = opt.retx;
    po.down_after = opt.down_after;
    // As make_fixed_backend: with a table file the board boots without a table and takes the file
    // by upload before its first step.
    std::vector<std::uint8_t> boot = scn.fsw.table_file.empty() ? mh.boot_image(scn) : std::vector<std::uint8_t>{};
    be_.reset(new pil::PilBackend(host::fsw_cfg(scn), std::move(boot), std::move(port), po));
    if (!be_->reset()) {
        throw std::runtime_error("the board (" + opt.describe() + ") refused the " + std::string(mh.iface().name) +
                                 " boot table '" + scn.fsw.table + "': BOOT_ACK rc " +
                                 std::to_string(be_->boot_rc()) + ", " +
                                 host::describe_reason(mh.iface(), be_->boot_reason()));
    }
}

PilRun::~PilRun() = default;

void PilRun::before_step(std::uint64_t k)
{
    const std::int64_t ks = static_cast<std::int64_t>(k);
    if (ks == opt_.reset_at) {
        std::fprintf(stderr, "sil: fault injection: board reset before step %lld\n", static_cast<long long>(ks));
        (void)be_->inject_reset();
    }
    if (ks == opt_.silent_at && faults_ != nullptr) {
        std::fprintf(stderr, "sil: fault injection: the board falls silent at step %lld\n", static_cast<long long>(ks));
        faults_->stall(0xFFFFFFFFu);
    }
}

int PilRun::finish(host::Summary &s)
{
    const std::optional<fsw_pil_stats_t> bs = be_->link_stats();
    const bool ended = be_->end_session();
    int rc = 0;
    if (qemu_) {
        rc = qemu_->wait_exit(10000);
    }
    const pil::PilCounters &c = be_->counters();
    std::vector<std::uint32_t> insn = be_->insn();
    s.add_str("pil_board", opt_.describe());
    s.add_hex("pil_board_id", be_->hello().board_id);
    s.add_hex("pil_build_id", be_->hello().build_id);
    s.add_hex("pil_layout_hash", be_->hello().layout_hash);
    s.add_int("pil_tx_frames", static_cast<std::int64_t>(c.tx_frames));
    s.add_int("pil_rx_frames", static_cast<std::int64_t>(c.rx_frames));
    s.add_int("pil_retx", static_cast<std::int64_t>(c.retx));
    s.add_int("pil_timeouts", static_cast<std::int64_t>(c.timeouts));
    s.add_int("pil_missed_steps", static_cast<std::int64_t>(c.missed_steps));
    s.add_int("pil_unexpected", static_cast<std::int64_t>(c.unexpected));
    s.add_int("pil_board_errors", static_cast<std::int64_t>(c.board_errors));
    s.add_int("pil_host_rx_errors", static_cast<std::int64_t>(c.rx.err_oversize) + c.rx.err_cobs + c.rx.err_short +
                                        c.rx.err_len + c.rx.err_crc + c.rx.err_version + c.rx.err_type);
    s.add_int("pil_link_down", c.link_down ? 1 : 0);
    s.add_int("pil_board_resets", static_cast<std::int64_t>(c.board_resets));
    if (faults_ != nullptr) {
        const pil::FaultCounts &f = faults_->counts();
        s.add_int("pil_fault_dropped", static_cast<std::int64_t>(f.dropped_to_board + f.dropped_to_host));
        s.add_int("pil_fault_flipped", static_cast<std::int64_t>(f.flipped_to_board + f.flipped_to_host));
        s.add_int("pil_fault_truncated", static_cast<std::int64_t>(f.truncated_to_board + f.truncated_to_host));
        s.add_int("pil_fault_stalled", static_cast<std::int64_t>(f.stalled + f.stalled_to_board));
    }
    // Link budget (spec 00 §6.1): the bytes one step moves, at the run's rate, against the serial
    // rate (8N1: 10 bit times a byte). Measured on this run's traffic, retransmissions included.
    const std::uint64_t steps = insn.empty() ? 0u : insn.size();
    if (steps > 0u && period_s_ > 0.0) {
        const double bytes_per_step = static_cast<double>(c.tx_bytes + c.rx.bytes) / static_cast<double>(steps);
        const double need_baud = bytes_per_step * 10.0 / period_s_;
        s.add("pil_link_bytes_per_step", bytes_per_step, "%.1f");
        s.add("pil_link_required_baud", need_baud, "%.0f");
        s.add_int("pil_link_baud", opt_.baud);
        s.add_int("pil_link_budget_ok", need_baud <= static_cast<double>(opt_.baud) ? 1 : 0);
        if (need_baud > static_cast<double>(opt_.baud)) {
            // Lock-step runs do not care (the plant waits), a real-time bench does: say it.
            std::fprintf(stderr, "sil: link budget: %.0f bytes a step at %.0f Hz need %.0f baud (8N1), more than %d: "
                                 "a real-time bench on this link would fall behind\n",
                         bytes_per_step, 1.0 / period_s_, need_baud, opt_.baud);
        }
    }
    if (bs) {
        const fsw_link_stats_t &r = bs->rx;
        s.add_int("pil_board_steps", bs->steps);
        s.add_int("pil_board_dups", bs->dups);
        s.add_int("pil_board_stale", bs->stale);
        s.add_int("pil_board_rx_errors", static_cast<std::int64_t>(r.err_oversize) + r.err_cobs + r.err_short +
                                             r.err_len + r.err_crc + r.err_version + r.err_type);
        s.add_int("pil_board_uart_overruns", bs->uart_overruns);
        s.add_int("pil_board_stack_used", bs->stack_used);
        s.add_int("pil_board_stack_size", bs->stack_size);
    } else {
        s.add_str("pil_board_stats", "no answer");
    }
    if (!insn.empty()) {
        if (!opt_.insn_csv.empty()) {
            std::ofstream f(opt_.insn_csv);
            f << "step,insn\n";
            for (std::size_t i = 0; i < insn.size(); ++i) {
                f << i << "," << insn[i] << "\n";
            }
        }
        std::sort(insn.begin(), insn.end());
        s.add_int("pil_insn_min", insn.front());
        s.add_int("pil_insn_median", insn[insn.size() / 2]);
        s.add_int("pil_insn_max", insn.back());
    }
    s.add_int("pil_end_acked", ended ? 1 : 0);
    s.add_int("pil_board_exit", rc);
    return (c.link_down && rc == 0) ? 1 : rc;
}

}  // namespace sil
