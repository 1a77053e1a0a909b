// qemu_board.hpp — the PIL board image under QEMU (spec 00 §6.2): one emulated board per object,
// started through tools/qemu-run.sh (which wraps `timeout`), its UART0 on a unix socket in
// server mode with wait=on, so the guest starts only when the host connects (a deterministic
// start). -icount shift=3 makes TLM's instruction counts meaningful (spec 00 §6.4).
#ifndef HIL_PIL_QEMU_BOARD_HPP
#define HIL_PIL_QEMU_BOARD_HPP

#include <memory>
#include <string>

#include <sys/types.h>

#include "link_port.hpp"

namespace pil {

struct QemuOptions {
    std::string qemu_run;            // path of tools/qemu-run.sh
    std::string machine = "mps2-an385";
    std::string elf;                 // the board image (fsw_pil.elf)
    std::string dir;                 // the socket and the logs go here (must exist)
    int timeout_s = 120;             // QEMU_TIMEOUT: the whole run, then `timeout` ends it (124)
    int connect_timeout_ms = 10000;  // port(): how long QEMU may take to open its socket
    std::string extra_args;          // appended to QEMU_ARGS (word-split by qemu-run.sh)
    // Base name of the socket and logs in dir; empty: "pil-<pid>-<n>", unique among concurrent
    // runs. A test that runs alone may fix it, so its logs are overwritten rather than piling up.
    std::string name;
};

class QemuBoard {
public:
    // Spawns QEMU at once (its guest waits for port()). Throws std::runtime_error when the
    // socket path would be too long for AF_UNIX (107 characters) or the paths hold characters
    // QEMU's option syntax or qemu-run.sh's word splitting cannot carry (white space, ',').
    explicit QemuBoard(const QemuOptions &opt);
    // Still running: SIGTERM to its process group, then waits for it.
    ~QemuBoard();
    QemuBoard(const QemuBoard &) = delete;
    QemuBoard &operator=(const QemuBoard &) = delete;

    // Connects to the board's UART (the guest starts running now). Call once.
    std::unique_ptr<LinkPort> port();
    // The guest's exit code (0 pass, 236 stack canary, 238 fault, 124 QEMU's timeout; 128 + n
    // when killed by signal n). When it has not exited within timeout_ms it is terminated and
    // 124 is returned.
    int wait_exit(int timeout_ms);
    bool running();
    pid_t pid() const { return pid_; }

    const std::string &socket_path() const { return sock_; }
    const std::string &semi_log() const { return semi_; }        // the guest's semihosting console
    const std::string &console_log() const { return console_; }  // qemu-run.sh's stdout and stderr

private:
    void terminate();
    bool reap(bool block);

    QemuOptions opt_;
    std::string sock_, semi_, console_;
    pid_t pid_ = -1;
    bool exited_ = false;
    int status_ = 0;   // the exit code, once exited_
};

}  // namespace pil

#endif  // HIL_PIL_QEMU_BOARD_HPP
