#include "qemu_board.hpp"

#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <stdexcept>
#include <vector>

#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <sys/un.h>

extern char **environ;

namespace pil {

namespace {

using Clock = std::chrono::steady_clock;

std::atomic<unsigned> g_instance{0};

bool carries(const std::string &s)
{
    for (const char ch : s) {
        if (ch == ' ' || ch == '\t' || ch == '\n' || ch == ',') {
            return false;
        }
    }
    return true;
}

int exit_code(int status)
{
    if (WIFEXITED(status)) {
        return WEXITSTATUS(status);
    }
    if (WIFSIGNALED(status)) {
        return 128 + WTERMSIG(status);
    }
    return 255;
}

// A pollable handle on the child (Linux 5.3+), so waiting needs no sleep loop; -1 when absent.
int pidfd_of(pid_t pid)
{
#ifdef SYS_pidfd_open
    return static_cast<int>(::syscall(SYS_pidfd_open, pid, 0));
#else
    (void)pid;
    return -1;
#endif
}

}  // namespace

QemuBoard::QemuBoard(const QemuOptions &opt) : opt_(opt)
{
    if (opt_.qemu_run.empty() || opt_.elf.empty() || opt_.dir.empty()) {
        throw std::invalid_argument("QemuBoard: qemu_run, elf and dir are required");
    }
    const std::string base =
        opt_.dir + "/" +
        (opt_.name.empty() ? ("pil-" + std::to_string(::getpid()) + "-" + std::to_string(g_instance++)) : opt_.name);
    sock_ = base + ".sock";
    semi_ = base + ".semi.log";
    console_ = base + ".console.log";
    const std::size_t max_sock = sizeof(sockaddr_un{}.sun_path) - 1u;
    if (sock_.size() > max_sock) {
        throw std::runtime_error("QemuBoard: socket path '" + sock_ + "' has " + std::to_string(sock_.size()) +
                                 " characters; AF_UNIX allows " + std::to_string(max_sock) +
                                 ": give a shorter directory");
    }
    if (!carries(sock_) || !carries(semi_)) {
        throw std::runtime_error("QemuBoard: directory '" + opt_.dir +
                                 "' holds white space or ',', which QEMU's options (and qemu-run.sh's word "
                                 "splitting of QEMU_ARGS) cannot carry");
    }
    (void)::unlink(sock_.c_str());   // a socket left by a killed run would make QEMU's bind fail

    std::vector<std::string> env;
    for (char **e = environ; *e != nullptr; ++e) {
        const std::string kv(*e);
        if (kv.rfind("QEMU_TIMEOUT=", 0) != 0 && kv.rfind("QEMU_SEMI_LOG=", 0) != 0 && kv.rfind("QEMU_ARGS=", 0) != 0) {
            env.push_back(kv);
        }
    }
    env.push_back("QEMU_TIMEOUT=" + std::to_string(opt_.timeout_s));
    env.push_back("QEMU_SEMI_LOG=" + semi_);
    std::string qargs = "-icount shift=3 -chardev socket,id=pil0,path=" + sock_ +
                        ",server=on,wait=on -serial chardev:pil0";
    if (!opt_.extra_args.empty()) {
        qargs += " " + opt_.extra_args;
    }
    env.push_back("QEMU_ARGS=" + qargs);
    std::vector<char *> envp;
    for (std::string &s : env) {
        envp.push_back(&s[0]);
    }
    envp.push_back(nullptr);
    std::vector<std::string> args{opt_.qemu_run, opt_.machine, opt_.elf};
    std::vector<char *> argv;
    for (std::string &s : args) {
        argv.push_back(&s[0]);
    }
    argv.push_back(nullptr);

    posix_spawn_file_actions_t fa;
    posix_spawnattr_t at;
    (void)posix_spawn_file_actions_init(&fa);
    (void)posix_spawnattr_init(&at);
    (void)posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, console_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    (void)posix_spawn_file_actions_adddup2(&fa, STDOUT_FILENO, STDERR_FILENO);
    // Its own process group: the destructor ends the shell, `timeout` and QEMU together, and a
    // terminal's Ctrl-C to the host does not reach them half-way.
    sigset_t none, all;
    sigemptyset(&none);
    sigfillset(&all);
    (void)posix_spawnattr_setpgroup(&at, 0);
    (void)posix_spawnattr_setsigmask(&at, &none);
    (void)posix_spawnattr_setsigdefault(&at, &all);
    (void)posix_spawnattr_setflags(&at, static_cast<short>(POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGMASK |
                                                           POSIX_SPAWN_SETSIGDEF));
    pid_t pid = -1;
    const int rc = posix_spawn(&pid, opt_.qemu_run.c_str(), &fa, &at, argv.data(), envp.data());
    (void)posix_spawn_file_actions_destroy(&fa);
    (void)posix_spawnattr_destroy(&at);
    if (rc != 0) {
        throw std::runtime_error("QemuBoard: cannot start " + opt_.qemu_run + ": " + std::strerror(rc));
    }
    pid_ = pid;
}

QemuBoard::~QemuBoard()
{
    if (pid_ > 0 && !exited_) {
        terminate();
    }
    (void)::unlink(sock_.c_str());
}

bool QemuBoard::reap(bool block)
{
    if (exited_ || pid_ <= 0) {
        return true;
    }
    int st = 0;
    pid_t r;
    do {
        r = ::waitpid(pid_, &st, block ? 0 : WNOHANG);
    } while (r < 0 && errno == EINTR);
    if (r == pid_) {
        exited_ = true;
        status_ = exit_code(st);
        return true;
    }
    if (r < 0) {   // not our child any more (reaped elsewhere): nothing left to wait for
        exited_ = true;
        status_ = 255;
        return true;
    }
    return false;
}

bool QemuBoard::running() { return !reap(false); }

void QemuBoard::terminate()
{
    (void)::kill(-pid_, SIGTERM);
    // `timeout --kill-after=10` would follow up itself; a group that ignores SIGTERM gets
    // SIGKILL from here after 5 s so the host never hangs in a destructor.
    const Clock::time_point until = Clock::now() + std::chrono::seconds(5);
    while (!reap(false)) {
        if (Clock::now() >= until) {
            (void)::kill(-pid_, SIGKILL);
            (void)reap(true);
            break;
        }
        const timespec ts{0, 10L * 1000L * 1000L};
        (void)::nanosleep(&ts, nullptr);
    }
}

std::unique_ptr<LinkPort> QemuBoard::port()
{
    return open_unix_socket(sock_, opt_.connect_timeout_ms, [this]() { return running(); });
}

int QemuBoard::wait_exit(int timeout_ms)
{
    if (reap(false)) {
        return status_;
    }
    const Clock::time_point deadline = Clock::now() + std::chrono::milliseconds((timeout_ms < 0) ? 0 : timeout_ms);
    const int pfd = pidfd_of(pid_);
    while (!reap(false)) {
        const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
        if (left <= 0) {
            if (pfd >= 0) {
                (void)::close(pfd);
            }
            terminate();
            return 124;
        }
        if (pfd >= 0) {
            pollfd p{pfd, POLLIN, 0};
            (void)::poll(&p, 1, static_cast<int>((left > 0x7FFFFFFF) ? 0x7FFFFFFF : left));
        } else {
            const timespec ts{0, 10L * 1000L * 1000L};   // no pidfd: look every 10 ms
            (void)::nanosleep(&ts, nullptr);
        }
    }
    if (pfd >= 0) {
        (void)::close(pfd);
    }
    return status_;
}

}  // namespace pil
