// test_pil_backend.cpp — the bridge's `pil` backend against the board session run in this
// process (LoopbackBoardPort), with and without the byte-stream fault layer (spec 00 §6.1, §8),
// for the DETUMBLE mission. The in-process executive (InProcessFswBackend) is the reference:
// every step's StepOutput must be byte-identical, whatever the link lost on the way.
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <thread>

#include <fcntl.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include "pil_test_util.hpp"

extern "C" {
#include "fsw_link.h"
#include "fsw_pil.h"
}

using namespace bridge;
using pil::FaultyPort;
using pil::LoopbackBoardPort;

namespace {

using namespace pt;

constexpr std::int64_t kSteps = 300;

// The port under test: the in-process board session, optionally behind the fault layer. A base
// of Rig, so it exists before the twin takes the port.
struct Ports {
    LoopbackBoardPort *board = nullptr;   // owned through port (and faults)
    FaultyPort *faults = nullptr;
    std::unique_ptr<pil::LinkPort> port;

    explicit Ports(const pil::FaultPortConfig *fc)
    {
        std::unique_ptr<LoopbackBoardPort> lb(new LoopbackBoardPort(0xB01Du));
        board = lb.get();
        port = std::move(lb);
        if (fc != nullptr) {
            std::unique_ptr<FaultyPort> fp(new FaultyPort(std::move(port), *fc));
            faults = fp.get();
            port = std::move(fp);
        }
    }
};

pil::PilOptions quiet(pil::PilOptions o)
{
    o.log = false;
    return o;
}

struct Rig : Ports, Twin {
    explicit Rig(const pil::FaultPortConfig *fc = nullptr, pil::PilOptions opt = pil::PilOptions{})
        : Ports(fc), Twin(std::move(Ports::port), quiet(opt))
    {
    }
};

void handshake_boot_and_limits(void **)
{
    Rig r;
    assert_true(r.pil->reset());
    assert_int_equal(r.pil->boot_rc(), 0);
    assert_int_equal(r.ip.boot_rc(), FSW_OK);
    assert_int_equal(r.pil->hello().board_id, FSW_PIL_BOARD_HOST);
    assert_int_equal(r.pil->hello().build_id, 0xB01Du);
    assert_int_equal(r.pil->hello().layout_hash, fsw_pil_layout_hash());
    assert_true(r.board->board().booted);
    expect_same_limits(r.ip.sensor_limits(), r.pil->sensor_limits());
    assert_int_equal(r.pil->sensor_limits().n_channels, 2);
    const pil::PilCounters &c = r.pil->counters();
    assert_int_equal(c.retx, 0);
    assert_int_equal(c.timeouts, 0);
    // 668-byte image: 3 chunks, then BOOT (the HELLO came by itself).
    assert_int_equal(c.tx_frames, 4);
    assert_int_equal(c.rx_frames, 5);
    assert_true(r.pil->ping({1, 2, 0, 3}));
}

void steps_identical_to_in_process(void **)
{
    Rig r;
    assert_true(r.pil->reset());
    for (std::int64_t k = 0; k < kSteps; ++k) {
        r.step(k);
    }
    const pil::PilCounters &c = r.pil->counters();
    assert_int_equal(r.replays, 0);
    assert_int_equal(c.retx, 0);
    assert_int_equal(c.timeouts, 0);
    assert_int_equal(c.missed_steps, 0);
    assert_int_equal(c.unexpected, 0);
    assert_int_equal(c.board_errors, 0);
    assert_int_equal(c.rx.frames, c.rx_frames);
    assert_int_equal(r.pil->insn().size(), kSteps);
    for (std::uint32_t n : r.pil->insn()) {
        assert_int_equal(n, 0);   // the host harness has no instruction counter
    }
    // The commands reached the board through SENSOR and were taken exactly once.
    assert_int_equal(r.board->board().fsw.tlm.n_tc_rej, r.ip.fsw().tlm.n_tc_rej);
    assert_int_equal(r.ip.fsw().tlm.n_tc_rej, 1);
    const std::optional<fsw_pil_stats_t> s = r.pil->link_stats();
    assert_true(s.has_value());
    assert_int_equal(s->steps, kSteps);
    assert_int_equal(s->dups, 0);
    assert_int_equal(s->stale, 0);
    assert_int_equal(s->errors, 0);
    assert_int_equal(s->boots, 1);
    assert_int_equal(s->rx.frames, 3 + 1 + kSteps + 1);   // chunks, BOOT, SENSORs, LINK_STATS
}

// Uploads img to both in chunks of `chunk` bytes; every ack identical. Returns the last result.
std::int32_t upload_both(Twin &r, const std::vector<std::uint8_t> &img, std::uint32_t revision, std::size_t chunk)
{
    std::int32_t last = -1;
    for (std::size_t off = 0; off < img.size(); off += chunk) {
        TableChunk c{};
        c.table_id = static_cast<std::int32_t>(OBS_TBL_ID);
        c.revision = static_cast<std::int32_t>(revision);
        c.total_len = static_cast<std::int32_t>(img.size());
        c.offset = static_cast<std::int32_t>(off);
        c.n = static_cast<std::int16_t>((img.size() - off < chunk) ? (img.size() - off) : chunk);
        c.data = img.data() + off;
        TableAck a{}, b{};
        assert_true(r.ip.table_chunk(c, a));
        assert_true(r.pil->table_chunk(c, b));
        expect_same_ack(a, b);
        last = a.result;
    }
    return last;
}

void table_upload_mid_run(void **)
{
    Rig r;
    assert_true(r.pil->reset());
    std::int64_t k = 0;
    for (; k < 100; ++k) {
        r.step(k);
    }
    // A corrupted upload first: refused on its last chunk (CRC), identically, and counted.
    std::vector<std::uint8_t> bad = det_image(OBS_TBL_50HZ_PAPER, 2u);
    bad[FSW_TABLE_HDR_BYTES + 10u] ^= 0x40u;
    assert_int_equal(upload_both(r, bad, 2u, 100u), kTableRejected);
    for (; k < 120; ++k) {
        r.step(k);
    }
    // Then a good one: ACCEPTED, committed at a step boundary, LIMITS -> limits_changed on both
    // at the same step (checked in Rig::step).
    assert_int_equal(upload_both(r, det_image(OBS_TBL_50HZ_PAPER, 3u), 3u, 100u), kTableAccepted);
    for (; k < kSteps; ++k) {
        r.step(k);
    }
    assert_int_equal(r.ip.fsw().tlm.n_tbl_acc, 1);
    assert_int_equal(r.ip.fsw().tlm.n_tbl_rej, 1);
    assert_int_equal(r.ip.fsw().tlm.tbl_revision, 3);
    assert_int_equal(r.board->board().fsw.tlm.tbl_revision, 3);
    expect_same_limits(r.ip.sensor_limits(), r.pil->sensor_limits());
    // A chunk the link cannot carry (n == 0) gets the in-process backend's own refusal.
    TableChunk z{};
    z.table_id = static_cast<std::int32_t>(OBS_TBL_ID);
    z.total_len = 10;
    TableAck b{};
    assert_true(r.pil->table_chunk(z, b));
    assert_int_equal(b.result, kTableRejected);
    assert_int_equal(b.reason, static_cast<std::int32_t>(FSW_TBL_R_CHUNK_LEN));
    assert_int_equal(r.pil->counters().missed_steps, 0);
}

void faults_absorbed_by_retransmission(void **)
{
    pil::FaultPortConfig fc{};
    fc.seed = 0x5EED0F17u;
    fc.to_board.drop_ppm = 50000;
    fc.to_board.bitflip_ppm = 50000;
    fc.to_host.drop_ppm = 50000;
    fc.to_host.bitflip_ppm = 50000;
    Rig r(&fc);
    assert_true(r.pil->reset());   // handshake, staging and BOOT through the faults too
    for (std::int64_t k = 0; k < kSteps; ++k) {
        r.step(k);
    }
    const pil::PilCounters &c = r.pil->counters();
    const pil::FaultCounts &f = r.faults->counts();
    assert_true(f.dropped_to_board > 0 && f.dropped_to_host > 0);
    assert_true(f.flipped_to_board > 0 && f.flipped_to_host > 0);
    assert_true(c.retx > 0);
    assert_true(c.timeouts > 0);
    assert_int_equal(c.missed_steps, r.replays);
    assert_int_equal(c.link_down, false);
    const std::uint64_t host_errs = std::uint64_t{c.rx.err_oversize} + c.rx.err_cobs + c.rx.err_short + c.rx.err_len +
                                    c.rx.err_crc + c.rx.err_version + c.rx.err_type;
    assert_true(host_errs > 0);
    const fsw_pil_board_t &b = r.board->board();
    print_message("faults: to board %llu dropped %llu flipped, to host %llu dropped %llu flipped; host retx %llu "
                  "timeouts %llu replays %lld unexpected %llu decoder errors %llu; board dups %u stale %u errors %u\n",
                  static_cast<unsigned long long>(f.dropped_to_board), static_cast<unsigned long long>(f.flipped_to_board),
                  static_cast<unsigned long long>(f.dropped_to_host), static_cast<unsigned long long>(f.flipped_to_host),
                  static_cast<unsigned long long>(c.retx), static_cast<unsigned long long>(c.timeouts),
                  static_cast<long long>(r.replays), static_cast<unsigned long long>(c.unexpected),
                  static_cast<unsigned long long>(host_errs), b.st.dups, b.st.stale, b.st.errors);
    assert_true(b.st.dups > 0);                 // lost replies were answered from the cache
    assert_int_equal(b.st.steps, kSteps);       // and the board stepped each frame exactly once
    const fsw_link_stats_t &bs = b.dec.st;
    assert_true(bs.err_oversize + bs.err_cobs + bs.err_short + bs.err_len + bs.err_crc + bs.err_version + bs.err_type > 0);
    // Same seed, same faults, same counters.
    Rig r2(&fc);
    assert_true(r2.pil->reset());
    for (std::int64_t k = 0; k < kSteps; ++k) {
        r2.step(k);
    }
    assert_int_equal(r2.pil->counters().retx, r.pil->counters().retx);
    assert_int_equal(r2.pil->counters().rx.err_crc, r.pil->counters().rx.err_crc);
    assert_int_equal(r2.board->board().st.dups, b.st.dups);
}

void stall_misses_then_link_down(void **)
{
    pil::FaultPortConfig fc{};   // no random faults: only the stalls
    Rig r(&fc);
    assert_true(r.pil->reset());
    const pil::PilOptions o{};
    std::int64_t k = 0;
    for (; k < 150; ++k) {
        r.step(k);
    }
    // A deaf board at the step carrying the mode command: all 1 + retx SENSORs are lost, the
    // step gives nothing; the plant's re-send re-sends the same SENSOR, command included, and
    // the board steps it once (Rig::step compares with the in-process step, which took it).
    r.faults->stall_to_board(static_cast<std::uint32_t>(o.retx + 1));
    r.step(k);
    ++k;
    assert_int_equal(r.replays, 1);
    assert_int_equal(r.pil->counters().missed_steps, 1);
    assert_int_equal(r.board->board().st.steps, k);
    assert_int_equal(r.board->board().st.dups, 0);
    assert_int_equal(r.board->board().fsw.mode, FSW_MODE_STANDBY);

    // A silent board: every reply (CMD + TLM) of the first transmission and all retransmissions.
    r.faults->stall(2u * static_cast<std::uint32_t>(o.retx + 1));
    StepOutput out{};
    assert_false(r.pil->step(frame_k(k), out));
    assert_int_equal(r.pil->counters().missed_steps, 2);
    assert_int_equal(r.pil->counters().retx, 2 * o.retx);
    assert_false(r.pil->link_down());
    // The plant re-sends frame k: the board answers from its cache, and the result is still the
    // in-process step k (stepped once on both sides).
    r.step(k);
    ++k;
    assert_int_equal(r.board->board().st.steps, k);
    assert_int_equal(r.board->board().st.dups, o.retx + 1);

    // A board that stays silent: down_after failed steps in a row take the link down.
    r.faults->stall(1000000u);
    for (int i = 0; i < o.down_after; ++i) {
        assert_false(r.pil->link_down());
        assert_false(r.pil->step(frame_k(k), out));
    }
    assert_true(r.pil->link_down());
    assert_int_equal(r.pil->counters().missed_steps, 2 + o.down_after);
    const std::uint64_t tx = r.pil->counters().tx_frames;
    assert_false(r.pil->step(frame_k(k + 1), out));   // down: nothing is sent any more
    assert_int_equal(r.pil->counters().tx_frames, tx);
}

void layout_hash_mismatch_refused(void **)
{
    pil::PilOptions o{};
    o.expect_hash = fsw_pil_layout_hash() ^ 0x00A5A500u;
    Rig r(nullptr, o);
    char host[16], board[16];
    std::snprintf(host, sizeof host, "0x%08x", o.expect_hash);
    std::snprintf(board, sizeof board, "0x%08x", fsw_pil_layout_hash());
    bool threw = false;
    try {
        (void)r.pil->reset();
    } catch (const std::runtime_error &e) {
        threw = true;
        const std::string m = e.what();
        assert_true(m.find(host) != std::string::npos);
        assert_true(m.find(board) != std::string::npos);
        assert_true(m.find("0x0001") != std::string::npos);   // the board id
    }
    assert_true(threw);
    StepOutput out{};
    assert_false(r.pil->step(frame_k(0), out));   // no session
}

void mission_not_on_board_refused(void **)
{
    fsw_cfg_t cfg = det_cfg();
    cfg.mission = 31u;
    pil::PilOptions o{};
    o.log = false;
    pil::PilBackend be(cfg, {}, std::unique_ptr<pil::LinkPort>(new LoopbackBoardPort()), o);
    bool threw = false;
    try {
        (void)be.reset();
    } catch (const std::runtime_error &e) {
        threw = true;
        assert_true(std::string(e.what()).find("mission 31") != std::string::npos);
    }
    assert_true(threw);
}

void malformed_sensor_answered_with_error(void **)
{
    Rig r;
    assert_true(r.pil->reset());
    std::int64_t k = 0;
    for (; k < 10; ++k) {
        r.step(k);
    }
    // A SENSOR of 10 bytes, straight onto the link.
    const std::uint8_t pay[10] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
    std::uint8_t wire[FSW_LINK_MAX_WIRE];
    const std::uint32_t n = fsw_link_encode(static_cast<std::uint8_t>(FSW_LINK_T_SENSOR), 10u, pay, sizeof pay, wire,
                                            sizeof wire);
    assert_true(n > 0u);
    assert_true(r.board->write(wire, n));
    for (; k < 30; ++k) {
        r.step(k);
    }
    const pil::PilCounters &c = r.pil->counters();
    assert_int_equal(c.board_errors, 1);
    assert_int_equal(c.last_error.code, FSW_PIL_E_LEN);
    assert_int_equal(c.last_error.type, FSW_LINK_T_SENSOR);
    assert_int_equal(c.last_error.detail, sizeof pay);
    assert_int_equal(c.retx, 0);
    assert_int_equal(c.missed_steps, 0);
    assert_int_equal(r.board->board().st.errors, 1);
    assert_int_equal(r.board->board().st.steps, 30);
}

void end_session_closes_the_board(void **)
{
    Rig r;
    assert_true(r.pil->reset());
    r.step(0);
    assert_true(r.pil->end_session());
    assert_true(r.board->ended());
    StepOutput out{};
    assert_false(r.pil->step(frame_k(1), out));
    bool threw = false;
    try {
        (void)r.pil->reset();   // booted once: a new session needs a restarted board
    } catch (const std::runtime_error &) {
        threw = true;
    }
    assert_true(threw);
}

// The fault layer alone: deterministic per seed, and every frame it passes on intact is
// byte-identical to the one written.
void fault_port_deterministic(void **)
{
    pil::FaultPortConfig fc{};
    fc.seed = 99u;
    fc.to_board.drop_ppm = 100000;
    fc.to_board.truncate_ppm = 100000;
    fc.to_board.bitflip_ppm = 100000;
    auto run = [&](pil::FaultCounts &counts) {
        std::unique_ptr<LoopbackBoardPort> lb(new LoopbackBoardPort());
        const LoopbackBoardPort *raw = lb.get();
        FaultyPort fp(std::move(lb), fc);
        std::uint8_t wire[FSW_LINK_MAX_WIRE];
        for (std::uint16_t i = 0; i < 400; ++i) {
            const std::uint8_t pay[4] = {static_cast<std::uint8_t>(i), 0, 1, 2};
            const std::uint32_t n = fsw_link_encode(static_cast<std::uint8_t>(FSW_LINK_T_PING), i, pay, sizeof pay, wire,
                                                    sizeof wire);
            assert_true(fp.write(wire, n));
        }
        counts = fp.counts();
        return raw->board().dec.st;
    };
    pil::FaultCounts c1{}, c2{};
    const fsw_link_stats_t s1 = run(c1);
    const fsw_link_stats_t s2 = run(c2);
    assert_int_equal(c1.frames_to_board, 400);
    assert_true(c1.dropped_to_board > 20 && c1.truncated_to_board > 20 && c1.flipped_to_board > 20);
    assert_int_equal(c1.dropped_to_board, c2.dropped_to_board);
    assert_int_equal(c1.truncated_to_board, c2.truncated_to_board);
    assert_int_equal(c1.flipped_to_board, c2.flipped_to_board);
    assert_int_equal(s1.frames, s2.frames);
    assert_int_equal(s1.err_crc, s2.err_crc);
    // Frames untouched by any fault are accepted; every damaged one is refused (CRC-32 catches
    // one flipped bit and any cut), so accepted = passed untouched.
    const std::uint64_t damaged_or_gone = c1.dropped_to_board + c1.truncated_to_board + c1.flipped_to_board;
    assert_true(s1.frames >= 400u - damaged_or_gone);
    assert_true(s1.frames <= 400u - c1.dropped_to_board);
}

// A board at the far end of a real file descriptor (a pty master, an accepted socket): a thread
// moves bytes between the fd and an in-process board session, as a board's UART loop would, and
// writes its replies in 7-byte pieces, so the host sees frames split across reads.
class FdBoard {
public:
    explicit FdBoard(int fd) : fd_(fd), th_([this] { run(); }) {}
    ~FdBoard()
    {
        stop_ = true;
        th_.join();
        (void)::close(fd_);
    }
    FdBoard(const FdBoard &) = delete;
    FdBoard &operator=(const FdBoard &) = delete;
    std::uint32_t steps() const { return steps_; }

private:
    void run()
    {
        std::uint8_t buf[512];
        while (!stop_) {
            long m;
            while ((m = board_.read(buf, sizeof buf, 0)) > 0) {
                for (long off = 0; off < m; off += 7) {
                    const std::size_t n = static_cast<std::size_t>(std::min<long>(7, m - off));
                    std::size_t done = 0;
                    while (done < n) {
                        const ssize_t w = ::write(fd_, buf + off + static_cast<long>(done), n - done);
                        if (w > 0) {
                            done += static_cast<std::size_t>(w);
                        } else if (errno != EINTR && errno != EAGAIN) {
                            return;
                        }
                    }
                }
            }
            steps_ = board_.board().st.steps;
            pollfd p{fd_, POLLIN, 0};
            if (::poll(&p, 1, 20) <= 0) {   // 20 ms: only how soon stop_ is noticed
                continue;
            }
            const ssize_t n = ::read(fd_, buf, sizeof buf);
            if (n > 0) {
                (void)board_.write(buf, static_cast<std::size_t>(n));
            } else if (n == 0 || (errno != EINTR && errno != EAGAIN)) {
                return;
            }
        }
    }

    LoopbackBoardPort board_;   // before th_: the thread uses it from its first instruction
    int fd_;
    std::atomic<bool> stop_{false};
    std::atomic<std::uint32_t> steps_{0};
    std::thread th_;
};

// FdPort over a tty: open_serial on a pty's slave (raw 8N1, read back), the board on its master.
void serial_pty_session(void **)
{
    const int master = ::posix_openpt(O_RDWR | O_NOCTTY);
    assert_true(master >= 0);
    assert_int_equal(::grantpt(master), 0);
    assert_int_equal(::unlockpt(master), 0);
    const std::string slave = ::ptsname(master);
    std::unique_ptr<pil::LinkPort> port = pil::open_serial(slave, 921600);
    assert_true(port->describe().find(slave) != std::string::npos);
    FdBoard fb(master);
    Twin t(std::move(port), quiet(pil::PilOptions{}));
    assert_true(t.pil->reset());
    for (std::int64_t k = 0; k < 60; ++k) {
        t.step(k);
    }
    assert_int_equal(t.pil->counters().retx, 0);
    assert_int_equal(t.pil->counters().unexpected, 0);
    assert_true(t.pil->end_session());
}

// FdPort over a unix socket (open_unix_socket), the board on the accepted end.
void unix_socket_session(void **)
{
    const std::string path = "/tmp/test_pil_backend-" + std::to_string(::getpid()) + ".sock";
    (void)::unlink(path.c_str());
    const int lfd = ::socket(AF_UNIX, SOCK_STREAM, 0);
    assert_true(lfd >= 0);
    sockaddr_un a{};
    a.sun_family = AF_UNIX;
    std::memcpy(a.sun_path, path.c_str(), path.size() + 1u);
    assert_int_equal(::bind(lfd, reinterpret_cast<const sockaddr *>(&a), sizeof a), 0);
    assert_int_equal(::listen(lfd, 1), 0);
    std::unique_ptr<pil::LinkPort> port = pil::open_unix_socket(path, 1000);
    const int afd = ::accept(lfd, nullptr, nullptr);
    assert_true(afd >= 0);
    (void)::close(lfd);
    (void)::unlink(path.c_str());
    std::unique_ptr<FdBoard> fb(new FdBoard(afd));
    Twin t(std::move(port), quiet(pil::PilOptions{}));
    assert_true(t.pil->reset());
    for (std::int64_t k = 0; k < 60; ++k) {
        t.step(k);
    }
    assert_int_equal(t.pil->counters().retx, 0);
    // The board's end closes: the next step fails at once and the link is down (no hang for the
    // retransmissions, no SIGPIPE).
    fb.reset();
    StepOutput out{};
    assert_false(t.pil->step(frame_k(60), out));
    assert_true(t.pil->link_down());
}

void port_errors_name_their_target(void **)
{
    bool threw = false;
    try {
        (void)pil::open_serial("ttyPIL_NO_SUCH_DEVICE", 115200);
    } catch (const std::runtime_error &e) {
        threw = true;
        const std::string m = e.what();
        assert_true(m.find("/dev/ttyPIL_NO_SUCH_DEVICE") != std::string::npos);
        assert_true(m.find("No such file") != std::string::npos);
    }
    assert_true(threw);
    threw = false;
    try {
        (void)pil::open_serial("/dev/null", 12345);
    } catch (const std::runtime_error &e) {
        threw = true;
        assert_true(std::string(e.what()).find("12345") != std::string::npos);
    }
    assert_true(threw);
    threw = false;
    try {
        (void)pil::open_unix_socket("/tmp/" + std::string(120, 'x'), 10);
    } catch (const std::runtime_error &e) {
        threw = true;
        assert_true(std::string(e.what()).find("107") != std::string::npos);
    }
    assert_true(threw);
    threw = false;
    try {
        (void)pil::open_unix_socket("/tmp/test_pil_backend-none.sock", 30);   // three 10 ms retries
    } catch (const std::runtime_error &e) {
        threw = true;
        assert_true(std::string(e.what()).find("/tmp/test_pil_backend-none.sock") != std::string::npos);
    }
    assert_true(threw);
}

}  // namespace

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(handshake_boot_and_limits),
        cmocka_unit_test(steps_identical_to_in_process),
        cmocka_unit_test(table_upload_mid_run),
        cmocka_unit_test(faults_absorbed_by_retransmission),
        cmocka_unit_test(stall_misses_then_link_down),
        cmocka_unit_test(layout_hash_mismatch_refused),
        cmocka_unit_test(mission_not_on_board_refused),
        cmocka_unit_test(malformed_sensor_answered_with_error),
        cmocka_unit_test(end_session_closes_the_board),
        cmocka_unit_test(fault_port_deterministic),
        cmocka_unit_test(serial_pty_session),
        cmocka_unit_test(unix_socket_session),
        cmocka_unit_test(port_errors_name_their_target),
    };
    return cmocka_run_group_tests_name("pil_backend", tests, nullptr, nullptr);
}
