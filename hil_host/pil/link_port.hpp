// link_port.hpp — the byte stream under the PIL session (spec 00 §6.1, §8): a serial device, a
// QEMU UART socket, the board session run in this process, and a seeded fault layer over any of
// them. The session (pil_backend.hpp) frames and decodes; a port only moves bytes, and a read
// may return any part of a frame, several frames, or a frame's tail.
#ifndef HIL_PIL_LINK_PORT_HPP
#define HIL_PIL_LINK_PORT_HPP

#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "fault_rng.hpp"

extern "C" {
#include "fsw_pil.h"
}

namespace pil {

class LinkPort {
public:
    virtual ~LinkPort() = default;
    // The whole buffer is sent (or queued for sending), or false: the link is broken.
    virtual bool write(const std::uint8_t *buf, std::size_t n) = 0;
    // > 0: bytes read into buf; 0: nothing within timeout_ms (a port that can tell that nothing
    // more will come without further input, like the in-process board, returns 0 at once);
    // < 0: closed or failed.
    virtual long read(std::uint8_t *buf, std::size_t cap, int timeout_ms) = 0;
    // For messages: what this port is connected to.
    virtual std::string describe() const = 0;
};

// A file descriptor (socket or tty), owned and closed here. Non-blocking underneath: reads wait
// in poll(), writes wait for POLLOUT between partial writes (at most write_timeout_ms in all).
class FdPort final : public LinkPort {
public:
    FdPort(int fd, std::string what, bool is_socket, int write_timeout_ms = 5000);
    ~FdPort() override;
    FdPort(const FdPort &) = delete;
    FdPort &operator=(const FdPort &) = delete;

    bool write(const std::uint8_t *buf, std::size_t n) override;
    long read(std::uint8_t *buf, std::size_t cap, int timeout_ms) override;
    std::string describe() const override;
    // The reason of the last failed write or read ("" if none).
    const std::string &last_error() const { return err_; }

private:
    int fd_;
    std::string what_;
    bool sock_;
    int write_timeout_ms_;
    std::string err_;
};

// Connects to a listening AF_UNIX stream socket, retrying every 10 ms while the path does not
// exist yet or refuses (QEMU creates it some time after it starts). keep_waiting, when given,
// is asked between tries (false: give up at once, e.g. the server process has exited).
// Throws std::runtime_error naming the path.
std::unique_ptr<LinkPort> open_unix_socket(const std::string &path, int connect_timeout_ms,
                                           const std::function<bool()> &keep_waiting = {});

// A serial device in raw 8N1, no flow control, VMIN = VTIME = 0. dev without '/' is taken under
// /dev ("ttyUSB0"). baud: 9600 .. 921600, and 1000000 .. 4000000 where the platform has them.
// Throws std::runtime_error naming the device (and the errno text, or the unsupported rate).
std::unique_ptr<LinkPort> open_serial(const std::string &dev, int baud);
// The rates open_serial takes on this platform, ascending.
std::vector<int> serial_bauds();

// The board's session (fsw/app/fsw_pil.c) run in this process: the host harness of spec 00 §6.1.
// Bytes written are fed to the board one at a time, as the board image's UART loop does; its
// replies are queued for read(), which never blocks. After a MODE_CMD END the board is gone:
// writes fail and reads report closed once the queue is empty.
class LoopbackBoardPort final : public LinkPort {
public:
    explicit LoopbackBoardPort(std::uint32_t build_id = 0u);
    bool write(const std::uint8_t *buf, std::size_t n) override;
    long read(std::uint8_t *buf, std::size_t cap, int timeout_ms) override;
    std::string describe() const override { return "in-process board session (host harness)"; }

    const fsw_pil_board_t &board() const { return *b_; }
    bool ended() const { return ended_; }
    std::size_t queued() const { return out_.size(); }

private:
    void take_tx();

    std::unique_ptr<fsw_pil_board_t> b_;   // tens of KiB (fsw_t): on the heap
    std::deque<std::uint8_t> out_;
    bool ended_ = false;
};

// Per-direction fault rates, parts per million per frame (integer decisions, as hil_host/fault).
struct FaultRates {
    std::uint32_t drop_ppm = 0;       // the whole frame, delimiter included, is gone
    std::uint32_t truncate_ppm = 0;   // its tail is cut: 1 .. len-1 bytes kept, then the delimiter
    std::uint32_t bitflip_ppm = 0;    // one bit of one byte before the delimiter inverted
};

struct FaultPortConfig {
    std::uint64_t seed = 1;
    FaultRates to_board;
    FaultRates to_host;
};

struct FaultCounts {
    std::uint64_t frames_to_board = 0;   // frames seen (delimiter-terminated runs, empty ones excluded)
    std::uint64_t frames_to_host = 0;
    std::uint64_t dropped_to_board = 0;
    std::uint64_t dropped_to_host = 0;
    std::uint64_t truncated_to_board = 0;
    std::uint64_t truncated_to_host = 0;
    std::uint64_t flipped_to_board = 0;
    std::uint64_t flipped_to_host = 0;
    std::uint64_t stalled = 0;           // board -> host frames swallowed by stall()
    std::uint64_t stalled_to_board = 0;  // host -> board frames swallowed by stall_to_board()
};

// A seeded, deterministic fault layer on the byte stream (spec 00 §8, "corrupted or truncated
// UART frame", "board silent"), over another port. It cuts each direction into frames at the
// 0x00 delimiters and decides per frame, in this order, with the same draws whatever the
// outcome (so a seed fixes the faults of frame n of a direction, whatever happened before):
// drop, truncate, bit flip. A flip that makes a 0x00 splits the frame in two on the wire; the
// decoder counts both pieces as errors, which is what a real line does. Bytes after the last
// delimiter wait for theirs. stall(n) swallows the next n board -> host frames (a silent board),
// stall_to_board(n) the next n host -> board frames (a deaf one); both draw as usual, so they do
// not shift the random faults of later frames.
class FaultyPort final : public LinkPort {
public:
    FaultyPort(std::unique_ptr<LinkPort> inner, const FaultPortConfig &cfg);
    bool write(const std::uint8_t *buf, std::size_t n) override;
    long read(std::uint8_t *buf, std::size_t cap, int timeout_ms) override;
    std::string describe() const override;

    void stall(std::uint32_t n_frames) { stall_left_ += n_frames; }
    // The other way: the next n host -> board frames are swallowed (a deaf board).
    void stall_to_board(std::uint32_t n_frames) { deaf_left_ += n_frames; }
    // New rates from now on (the random streams continue).
    void set_rates(const FaultRates &to_board, const FaultRates &to_host);
    const FaultCounts &counts() const { return c_; }
    LinkPort &inner() { return *inner_; }

private:
    struct Dir {
        FaultRates rates;
        fault::Xoshiro256ss rng;
        std::vector<std::uint8_t> run;   // bytes since the last delimiter
    };
    // One delimiter-terminated frame (run + 0x00) through the faults; appends what survives.
    template <class Out>
    void pass_frame(Dir &d, bool to_host, Out &out);

    std::unique_ptr<LinkPort> inner_;
    Dir to_board_;
    Dir to_host_;
    std::deque<std::uint8_t> out_;       // board -> host bytes that survived
    std::uint64_t stall_left_ = 0;
    std::uint64_t deaf_left_ = 0;
    FaultCounts c_{};
};

}  // namespace pil

#endif  // HIL_PIL_LINK_PORT_HPP
