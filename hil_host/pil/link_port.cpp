#include "link_port.hpp"

#include <cerrno>
#include <chrono>
#include <cstring>
#include <stdexcept>
#include <utility>

#include <fcntl.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

namespace pil {

namespace {

using Clock = std::chrono::steady_clock;

// Milliseconds left until deadline, >= 0, rounded up so a poll never returns just short of it.
int ms_left(Clock::time_point deadline)
{
    const auto left = deadline - Clock::now();
    if (left <= Clock::duration::zero()) {
        return 0;
    }
    const auto us = std::chrono::duration_cast<std::chrono::microseconds>(left).count();
    const long long ms = (us + 999) / 1000;
    return (ms > 0x7FFFFFFF) ? 0x7FFFFFFF : static_cast<int>(ms);
}

std::string errno_text(int e) { return std::string(std::strerror(e)); }

bool set_nonblocking(int fd)
{
    const int fl = ::fcntl(fd, F_GETFL);
    return (fl >= 0) && (::fcntl(fd, F_SETFL, fl | O_NONBLOCK) == 0);
}

}  // namespace

// ------------------------------------------------------------------ FdPort

FdPort::FdPort(int fd, std::string what, bool is_socket, int write_timeout_ms)
    : fd_(fd), what_(std::move(what)), sock_(is_socket), write_timeout_ms_(write_timeout_ms)
{
}

FdPort::~FdPort()
{
    if (fd_ >= 0) {
        (void)::close(fd_);
    }
}

std::string FdPort::describe() const { return what_; }

bool FdPort::write(const std::uint8_t *buf, std::size_t n)
{
    const Clock::time_point deadline = Clock::now() + std::chrono::milliseconds(write_timeout_ms_);
    std::size_t off = 0;
    while (off < n) {
        // MSG_NOSIGNAL: a peer that went away is an error return here, not a SIGPIPE that
        // kills the whole host process.
        const ssize_t w = sock_ ? ::send(fd_, buf + off, n - off, MSG_NOSIGNAL) : ::write(fd_, buf + off, n - off);
        if (w > 0) {
            off += static_cast<std::size_t>(w);
            continue;
        }
        if (w < 0 && errno == EINTR) {
            continue;
        }
        if (w < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
            pollfd p{fd_, POLLOUT, 0};
            const int left = ms_left(deadline);
            if (left == 0) {
                err_ = "write: the peer took nothing for " + std::to_string(write_timeout_ms_) + " ms";
                return false;
            }
            const int r = ::poll(&p, 1, left);
            if (r < 0 && errno != EINTR) {
                err_ = "poll: " + errno_text(errno);
                return false;
            }
            if (r > 0 && (p.revents & (POLLERR | POLLHUP | POLLNVAL)) != 0 && (p.revents & POLLOUT) == 0) {
                err_ = "write: connection closed";
                return false;
            }
            continue;
        }
        err_ = (w < 0) ? ("write: " + errno_text(errno)) : std::string("write: wrote nothing");
        return false;
    }
    return true;
}

long FdPort::read(std::uint8_t *buf, std::size_t cap, int timeout_ms)
{
    const Clock::time_point deadline = Clock::now() + std::chrono::milliseconds((timeout_ms < 0) ? 0 : timeout_ms);
    for (;;) {
        pollfd p{fd_, POLLIN, 0};
        const int r = ::poll(&p, 1, ms_left(deadline));
        if (r < 0) {
            if (errno == EINTR) {
                continue;   // the remaining time is recomputed from the deadline
            }
            err_ = "poll: " + errno_text(errno);
            return -1;
        }
        if (r == 0) {
            return 0;
        }
        if ((p.revents & POLLIN) == 0) {
            // HUP/ERR with nothing left to read: the peer is gone.
            err_ = "read: connection closed";
            return -1;
        }
        const ssize_t n = ::read(fd_, buf, cap);
        if (n > 0) {
            return static_cast<long>(n);
        }
        if (n == 0) {
            if (sock_) {
                err_ = "read: connection closed";
                return -1;
            }
            // A tty with VMIN = VTIME = 0 reads 0 when the byte poll saw was taken elsewhere:
            // nothing yet (a hang-up shows as POLLHUP above).
        } else if (errno != EINTR && errno != EAGAIN && errno != EWOULDBLOCK) {
            err_ = "read: " + errno_text(errno);
            return -1;
        }
        if (ms_left(deadline) == 0) {
            return 0;
        }
    }
}

// ------------------------------------------------------------------ opening

std::unique_ptr<LinkPort> open_unix_socket(const std::string &path, int connect_timeout_ms,
                                           const std::function<bool()> &keep_waiting)
{
    sockaddr_un addr{};
    if (path.empty() || path.size() >= sizeof(addr.sun_path)) {
        throw std::runtime_error("open_unix_socket: '" + path + "': a unix socket path must be 1.." +
                                 std::to_string(sizeof(addr.sun_path) - 1u) + " characters (it has " +
                                 std::to_string(path.size()) + ")");
    }
    addr.sun_family = AF_UNIX;
    std::memcpy(addr.sun_path, path.c_str(), path.size() + 1u);

    const Clock::time_point deadline = Clock::now() + std::chrono::milliseconds(connect_timeout_ms);
    int last = 0;
    for (;;) {
        const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
        if (fd < 0) {
            throw std::runtime_error("open_unix_socket: " + path + ": socket: " + errno_text(errno));
        }
        int rc;
        do {
            rc = ::connect(fd, reinterpret_cast<const sockaddr *>(&addr), sizeof addr);
        } while (rc != 0 && errno == EINTR);
        if (rc == 0) {
            if (!set_nonblocking(fd)) {
                const int e = errno;
                (void)::close(fd);
                throw std::runtime_error("open_unix_socket: " + path + ": fcntl: " + errno_text(e));
            }
            return std::unique_ptr<LinkPort>(new FdPort(fd, "unix socket " + path, true));
        }
        last = errno;
        (void)::close(fd);
        // Not there yet (ENOENT), or the server has not called listen() (ECONNREFUSED): wait.
        if (last != ENOENT && last != ECONNREFUSED && last != EAGAIN) {
            throw std::runtime_error("open_unix_socket: " + path + ": connect: " + errno_text(last));
        }
        if (keep_waiting && !keep_waiting()) {
            throw std::runtime_error("open_unix_socket: " + path + ": gave up (the server is gone; last: " +
                                     errno_text(last) + ")");
        }
        if (ms_left(deadline) == 0) {
            throw std::runtime_error("open_unix_socket: " + path + ": nothing accepted within " +
                                     std::to_string(connect_timeout_ms) + " ms (last: " + errno_text(last) + ")");
        }
        const timespec ts{0, 10L * 1000L * 1000L};   // the retry interval
        (void)::nanosleep(&ts, nullptr);
    }
}

namespace {

struct BaudMap {
    int baud;
    speed_t code;
};

const BaudMap kBauds[] = {
    {9600, B9600}, {19200, B19200}, {38400, B38400}, {57600, B57600}, {115200, B115200},
    {230400, B230400},
#ifdef B460800
    {460800, B460800},
#endif
#ifdef B500000
    {500000, B500000},
#endif
#ifdef B576000
    {576000, B576000},
#endif
#ifdef B921600
    {921600, B921600},
#endif
#ifdef B1000000
    {1000000, B1000000},
#endif
#ifdef B1152000
    {1152000, B1152000},
#endif
#ifdef B1500000
    {1500000, B1500000},
#endif
#ifdef B2000000
    {2000000, B2000000},
#endif
#ifdef B2500000
    {2500000, B2500000},
#endif
#ifdef B3000000
    {3000000, B3000000},
#endif
#ifdef B3500000
    {3500000, B3500000},
#endif
#ifdef B4000000
    {4000000, B4000000},
#endif
};

}  // namespace

std::vector<int> serial_bauds()
{
    std::vector<int> v;
    for (const BaudMap &b : kBauds) {
        v.push_back(b.baud);
    }
    return v;
}

std::unique_ptr<LinkPort> open_serial(const std::string &dev, int baud)
{
    const std::string path = (dev.find('/') == std::string::npos) ? ("/dev/" + dev) : dev;
    const BaudMap *bm = nullptr;
    for (const BaudMap &b : kBauds) {
        if (b.baud == baud) {
            bm = &b;
        }
    }
    if (bm == nullptr) {
        std::string list;
        for (const BaudMap &b : kBauds) {
            list += (list.empty() ? "" : ", ") + std::to_string(b.baud);
        }
        throw std::runtime_error("open_serial: " + path + ": baud " + std::to_string(baud) +
                                 " not supported (supported: " + list + ")");
    }
    const int fd = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        throw std::runtime_error("open_serial: " + path + ": " + errno_text(errno));
    }
    auto fail = [&](const char *what) {
        const int e = errno;
        (void)::close(fd);
        throw std::runtime_error("open_serial: " + path + ": " + what + ": " + errno_text(e));
    };
    termios t{};
    if (::tcgetattr(fd, &t) != 0) {
        fail("tcgetattr (not a serial device?)");
    }
    ::cfmakeraw(&t);
    t.c_cflag &= ~static_cast<tcflag_t>(CSIZE | CSTOPB | PARENB | CRTSCTS);
    t.c_cflag |= static_cast<tcflag_t>(CS8 | CLOCAL | CREAD);
    t.c_iflag &= ~static_cast<tcflag_t>(IXON | IXOFF | IXANY);
    t.c_cc[VMIN] = 0;
    t.c_cc[VTIME] = 0;
    if (::cfsetispeed(&t, bm->code) != 0 || ::cfsetospeed(&t, bm->code) != 0) {
        fail("cfsetspeed");
    }
    if (::tcsetattr(fd, TCSANOW, &t) != 0) {
        fail("tcsetattr");
    }
    // Some drivers accept tcsetattr and keep another rate: read it back.
    termios back{};
    if (::tcgetattr(fd, &back) != 0) {
        fail("tcgetattr");
    }
    if (::cfgetospeed(&back) != bm->code) {
        errno = EINVAL;
        fail(("the driver did not take baud " + std::to_string(baud)).c_str());
    }
    // Exclusive: a second opener (a stray terminal program) would steal bytes from the session.
    (void)::ioctl(fd, TIOCEXCL);
    // Bytes from before this session (a board's earlier output) are not this session's.
    (void)::tcflush(fd, TCIOFLUSH);
    return std::unique_ptr<LinkPort>(new FdPort(fd, "serial " + path + " @" + std::to_string(baud) + " 8N1", false));
}

// ------------------------------------------------------------------ LoopbackBoardPort

LoopbackBoardPort::LoopbackBoardPort(std::uint32_t build_id) : b_(new fsw_pil_board_t())
{
    fsw_pil_board_init(b_.get(), static_cast<std::uint16_t>(FSW_PIL_BOARD_HOST), build_id);
    take_tx();   // the start-up HELLO
}

void LoopbackBoardPort::take_tx()
{
    if (b_->tx_len > 0u) {
        out_.insert(out_.end(), b_->tx, b_->tx + b_->tx_len);
        fsw_pil_board_sent(b_.get());
    }
}

bool LoopbackBoardPort::write(const std::uint8_t *buf, std::size_t n)
{
    if (ended_) {
        return false;
    }
    for (std::size_t i = 0; i < n && !ended_; ++i) {
        const fsw_pil_rx_t act = fsw_pil_board_rx(b_.get(), buf[i]);
        if (act == FSW_PIL_RX_STEP) {
            fsw_pil_board_step(b_.get());
            fsw_pil_board_finish(b_.get(), 0u);   // no instruction count on the host
        } else if (act == FSW_PIL_RX_END) {
            ended_ = true;   // the rest of buf would go to a board that has left its loop
        } else if (act == FSW_PIL_RX_RESET) {
            // The board resets after sending its ack: a new session, with the HELLO of a fresh start.
            take_tx();
            const std::uint32_t build_id = b_->build_id;
            *b_ = fsw_pil_board_t{};
            fsw_pil_board_init(b_.get(), static_cast<std::uint16_t>(FSW_PIL_BOARD_HOST), build_id);
        }
        take_tx();
    }
    return true;
}

long LoopbackBoardPort::read(std::uint8_t *buf, std::size_t cap, int)
{
    if (out_.empty()) {
        return ended_ ? -1 : 0;
    }
    std::size_t n = 0;
    while (n < cap && !out_.empty()) {
        buf[n++] = out_.front();
        out_.pop_front();
    }
    return static_cast<long>(n);
}

// ------------------------------------------------------------------ FaultyPort

FaultyPort::FaultyPort(std::unique_ptr<LinkPort> inner, const FaultPortConfig &cfg)
    : inner_(std::move(inner)),
      to_board_{cfg.to_board, fault::Xoshiro256ss(cfg.seed), {}},
      // The two directions draw from separate streams, so the faults of one do not depend on
      // how many frames the other has carried.
      to_host_{cfg.to_host, fault::Xoshiro256ss(cfg.seed ^ UINT64_C(0xA5A5A5A5DEADBEEF)), {}}
{
}

std::string FaultyPort::describe() const { return "faults over " + inner_->describe(); }

void FaultyPort::set_rates(const FaultRates &to_board, const FaultRates &to_host)
{
    to_board_.rates = to_board;
    to_host_.rates = to_host;
}

template <class Out>
void FaultyPort::pass_frame(Dir &d, bool to_host, Out &out)
{
    std::vector<std::uint8_t> &f = d.run;   // the frame without its delimiter
    if (f.empty()) {
        out.push_back(0u);   // an empty run (a sync byte) is no frame: passed as it is
        return;
    }
    ++(to_host ? c_.frames_to_host : c_.frames_to_board);
    const std::uint32_t len = static_cast<std::uint32_t>(f.size());
    const bool drop = d.rng.chance_ppm(d.rates.drop_ppm);
    const bool trunc = d.rng.chance_ppm(d.rates.truncate_ppm);
    const bool flip = d.rng.chance_ppm(d.rates.bitflip_ppm);
    const std::uint32_t keep = 1u + d.rng.below((len > 1u) ? (len - 1u) : 1u);   // 1 .. len-1
    const std::uint32_t pos = d.rng.below(len);
    const std::uint32_t bit = d.rng.below(8u);
    std::uint64_t &stall = to_host ? stall_left_ : deaf_left_;
    if (stall > 0u) {
        --stall;
        ++(to_host ? c_.stalled : c_.stalled_to_board);
        return;
    }
    if (drop) {
        ++(to_host ? c_.dropped_to_host : c_.dropped_to_board);
        return;
    }
    if (trunc && len > 1u) {
        f.resize(keep);
        ++(to_host ? c_.truncated_to_host : c_.truncated_to_board);
    }
    if (flip) {
        f[pos % f.size()] = static_cast<std::uint8_t>(f[pos % f.size()] ^ (1u << bit));
        ++(to_host ? c_.flipped_to_host : c_.flipped_to_board);
    }
    out.insert(out.end(), f.begin(), f.end());
    out.push_back(0u);
}

bool FaultyPort::write(const std::uint8_t *buf, std::size_t n)
{
    std::vector<std::uint8_t> fwd;
    for (std::size_t i = 0; i < n; ++i) {
        if (buf[i] == 0u) {
            pass_frame(to_board_, false, fwd);
            to_board_.run.clear();
        } else {
            to_board_.run.push_back(buf[i]);
        }
    }
    return fwd.empty() || inner_->write(fwd.data(), fwd.size());
}

long FaultyPort::read(std::uint8_t *buf, std::size_t cap, int timeout_ms)
{
    const Clock::time_point deadline = Clock::now() + std::chrono::milliseconds((timeout_ms < 0) ? 0 : timeout_ms);
    std::uint8_t tmp[1024];
    while (out_.empty()) {
        const long n = inner_->read(tmp, sizeof tmp, ms_left(deadline));
        if (n <= 0) {
            return n;
        }
        for (long i = 0; i < n; ++i) {
            const std::uint8_t b = tmp[i];
            if (b == 0u) {
                pass_frame(to_host_, true, out_);
                to_host_.run.clear();
            } else {
                to_host_.run.push_back(b);
            }
        }
        if (out_.empty() && ms_left(deadline) == 0) {
            return 0;
        }
    }
    std::size_t k = 0;
    while (k < cap && !out_.empty()) {
        buf[k++] = out_.front();
        out_.pop_front();
    }
    return static_cast<long>(k);
}

}  // namespace pil
