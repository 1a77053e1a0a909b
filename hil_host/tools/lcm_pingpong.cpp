// lcm_pingpong — raw LCM round-trip rate with sensor-frame-sized messages: the "LCM ceiling"
// of spec 00 §9, reported beside the SIL rate (SIL rate / ceiling = efficiency).
//
// One round trip = the "plant" encodes a gnc::sensor_frame_v2_t (122 bytes on the wire) into a
// static buffer and publishes it; the "bridge" decodes it and answers with a
// gnc::actuator_cmd_v2_t (98 bytes) echoing seq; the plant decodes the answer. No fsw_step, no
// plant model: this is the transport and binding cost only.
//
//   memq  one lcm_t shared by both ends (memq is scoped to one instance, spec 00 §5.3);
//         lcm_handle_timeout alternated on one thread, like the in-process SIL driver.
//   udpm  two lcm_t on one URL, the bridge on its own thread (or, with --fork, in a child
//         process, as in a two-process SIL run); each end subscribes only to the channel it
//         does not publish (udpm delivers a node's own publications back to it). A frame
//         unanswered after --retx-ms is re-published (lock-step rule, spec 00 §5.2); this also
//         covers the child's start-up, which the warm-up absorbs.
//
// usage: lcm_pingpong [--transport memq|udpm] [--url URL] [--n N] [--reps R] [--warmup W]
//                     [--retx-ms MS] [--fork]        (command line: CLI11; --help lists them)
//   --url defaults to LCM_DEFAULT_URL for udpm, else udpm://239.255.76.67:7667?ttl=0.
// Prints one line per repetition and a summary line starting with "lcm_pingpong:"
// (round trips/s median/min/max over repetitions; round-trip time min and median).
// Exit 0 on success, 1 on failure (timeout/decode error), 2 on bad usage, 77 if lcm_create
// returns NULL (no multicast on loopback). A benchmark: never a timed pass/fail.
#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <thread>
#include <vector>

#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <lcm/lcm.h>

#include "fsw_cli.hpp"

#include "gnc/actuator_cmd_v2_t.hpp"
#include "gnc/sensor_frame_v2_t.hpp"

namespace {

using Clock = std::chrono::steady_clock;

constexpr const char *kChSensor = "PP_SENSOR";
constexpr const char *kChCmd = "PP_CMD";
constexpr const char *kChStop = "PP_STOP";   // plant -> forked bridge: end of run
constexpr int kBufLen = 256;

struct Options {
    std::string transport = "memq";
    std::string url;
    long n = 10000;
    long reps = 5;
    long warmup = 200;
    int retx_ms = 100;
    bool fork_bridge = false;
};

// ---------------------------------------------------------------- bridge end
struct Bridge {
    lcm_t *lcm = nullptr;
    gnc::sensor_frame_v2_t rx;
    gnc::actuator_cmd_v2_t tx;
    std::array<std::uint8_t, kBufLen> buf{};
    long frames = 0;
    long errors = 0;

    static void on_sensor(const lcm_recv_buf_t *rbuf, const char *, void *user)
    {
        auto *self = static_cast<Bridge *>(user);
        self->handle(rbuf);
    }
    void handle(const lcm_recv_buf_t *rbuf)
    {
        if (rx.decode(rbuf->data, 0, static_cast<int>(rbuf->data_size)) < 0) {
            ++errors;
            return;
        }
        ++frames;
        tx.utime = rx.utime;
        tx.seq = rx.seq;
        tx.n_counts = rx.n_counts;
        for (int i = 0; i < 16; ++i) {
            tx.counts[i] = rx.counts[i] / 2;
        }
        tx.fsw_mode = 1;
        tx.fsw_health = 0;
        const int n = tx.encode(buf.data(), 0, kBufLen);
        if (n < 0 || lcm_publish(lcm, kChCmd, buf.data(), static_cast<unsigned>(n)) != 0) {
            ++errors;
        }
    }
};

// ---------------------------------------------------------------- plant end
struct Plant {
    lcm_t *lcm = nullptr;
    gnc::sensor_frame_v2_t tx;
    gnc::actuator_cmd_v2_t rx;
    std::array<std::uint8_t, kBufLen> buf{};
    bool got = false;
    long errors = 0;
    long retx = 0;
    int frame_len = 0;

    static void on_cmd(const lcm_recv_buf_t *rbuf, const char *, void *user)
    {
        auto *self = static_cast<Plant *>(user);
        if (self->rx.decode(rbuf->data, 0, static_cast<int>(rbuf->data_size)) < 0) {
            ++self->errors;
            return;
        }
        if (self->rx.seq == self->tx.seq) {   // late duplicates of earlier frames are ignored
            self->got = true;
        }
    }
    int publish(std::int64_t k)
    {
        tx.utime = k * 20000;
        tx.seq = k;
        tx.period_us = 20000;
        tx.n_counts = 16;
        for (int i = 0; i < 16; ++i) {
            tx.counts[i] = static_cast<std::int32_t>(k % 100000) * 16 + i;
            tx.status[i] = 0;
        }
        frame_len = tx.encode(buf.data(), 0, kBufLen);
        if (frame_len < 0) {
            return -1;
        }
        return lcm_publish(lcm, kChSensor, buf.data(), static_cast<unsigned>(frame_len));
    }
    int republish()
    {
        ++retx;
        return lcm_publish(lcm, kChSensor, buf.data(), static_cast<unsigned>(frame_len));
    }
};

struct RepResult {
    double rate = 0.0;      // round trips per second
    double rtt_min = 0.0;   // microseconds
    double rtt_med = 0.0;   // microseconds
};

double median(std::vector<double> v)
{
    if (v.empty()) {
        return 0.0;
    }
    const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2U);
    std::nth_element(v.begin(), mid, v.end());
    return *mid;
}

// One round trip. memq: both ends on one lcm_t, dispatched here. udpm: the bridge thread answers.
bool round_trip(Plant &plant, lcm_t *bridge_lcm_or_null, std::int64_t k, int retx_ms)
{
    plant.got = false;
    if (plant.publish(k) != 0) {
        return false;
    }
    int idle_ms = 0;
    int total_ms = 0;
    while (!plant.got) {
        if (bridge_lcm_or_null != nullptr) {
            // memq: the first call delivers the frame to the bridge, which publishes the command;
            // the second delivers the command to the plant.
            if (lcm_handle_timeout(bridge_lcm_or_null, retx_ms) <= 0) {
                return false;   // memq never loses a message: a timeout is a failure
            }
            continue;
        }
        const int r = lcm_handle_timeout(plant.lcm, 1);
        if (r < 0) {
            return false;
        }
        if (r == 0) {
            ++idle_ms;
            ++total_ms;
            if (total_ms > 10000) {
                return false;
            }
            if (idle_ms >= retx_ms && !plant.got) {
                idle_ms = 0;
                if (plant.republish() != 0) {
                    return false;
                }
            }
        }
    }
    return true;
}

bool run_rep(Plant &plant, lcm_t *memq, const Options &o, std::int64_t &k, RepResult &res)
{
    std::vector<double> rtt;
    rtt.reserve(static_cast<std::size_t>(o.n));
    const auto t0 = Clock::now();
    for (long i = 0; i < o.n; ++i) {
        const auto a = Clock::now();
        if (!round_trip(plant, memq, k++, o.retx_ms)) {
            std::fprintf(stderr, "lcm_pingpong: round trip %ld failed\n", i);
            return false;
        }
        const auto b = Clock::now();
        rtt.push_back(std::chrono::duration<double, std::micro>(b - a).count());
    }
    const double secs = std::chrono::duration<double>(Clock::now() - t0).count();
    res.rate = static_cast<double>(o.n) / secs;
    res.rtt_min = *std::min_element(rtt.begin(), rtt.end());
    res.rtt_med = median(rtt);
    return true;
}

// Forked bridge process: answers frames until PP_STOP, or 30 s without any frame.
void on_stop(const lcm_recv_buf_t *, const char *, void *user)
{
    *static_cast<bool *>(user) = true;
}

int run_child_bridge(const std::string &url)
{
    Bridge bridge;
    bool stop = false;
    bridge.lcm = lcm_create(url.c_str());
    if (bridge.lcm == nullptr) {
        return 77;
    }
    (void)lcm_subscribe(bridge.lcm, kChSensor, &Bridge::on_sensor, &bridge);
    (void)lcm_subscribe(bridge.lcm, kChStop, &on_stop, &stop);
    int idle = 0;
    while (!stop && idle < 300) {
        const int r = lcm_handle_timeout(bridge.lcm, 100);
        if (r < 0) {
            break;
        }
        idle = (r == 0) ? idle + 1 : 0;
    }
    lcm_destroy(bridge.lcm);
    return bridge.errors == 0 ? 0 : 1;
}

}  // namespace

int main(int argc, char **argv)
{
    Options o;
    CLI::App app{"lcm_pingpong: raw LCM round-trip rate with sensor-frame-sized messages (the LCM "
                 "ceiling beside the SIL rate). A benchmark: never a timed pass/fail.\n"
                 "Exit 0 done, 1 round trip or decode failure, 2 bad usage, 77 lcm_create returned NULL.",
                 "lcm_pingpong"};
    fsw_cli::last_value_wins(app);
    const long kLongMax = std::numeric_limits<long>::max();
    app.add_option("--transport", o.transport, "memq (one lcm_t, one thread) or udpm")
        ->check(CLI::IsMember({"memq", "udpm"}))
        ->capture_default_str();
    app.add_option("--url", o.url, "udpm URL (default $LCM_DEFAULT_URL, else udpm://239.255.76.67:7667?ttl=0)");
    app.add_option("--n", o.n, "round trips per repetition")
        ->transform(fsw_cli::Int())
        ->check(CLI::Range(1L, kLongMax).description(">= 1"))
        ->capture_default_str();
    app.add_option("--reps", o.reps, "repetitions")
        ->transform(fsw_cli::Int())
        ->check(CLI::Range(1L, kLongMax).description(">= 1"))
        ->capture_default_str();
    app.add_option("--warmup", o.warmup, "round trips before the first repetition")
        ->transform(fsw_cli::Int())
        ->check(CLI::Range(0L, kLongMax).description(">= 0"))
        ->capture_default_str();
    app.add_option("--retx-ms", o.retx_ms, "udpm: re-publish a frame unanswered after MS ms")
        ->transform(fsw_cli::Int())
        ->check(CLI::Range(1, 10000).description("1..10000"))
        ->capture_default_str();
    app.add_flag("--fork", o.fork_bridge, "udpm: run the bridge end in a child process");
    const int rc = fsw_cli::parse(app, argc, argv, 2);
    if (rc >= 0) {
        return rc;
    }
    const bool memq = o.transport == "memq";
    if (memq) {
        o.url = "memq://";
    } else if (o.url.empty()) {
        const char *env = std::getenv("LCM_DEFAULT_URL");
        o.url = (env != nullptr) ? env : "udpm://239.255.76.67:7667?ttl=0";
    }

    // --fork: the bridge runs in a child process (before any lcm_t or thread exists here).
    const bool forked = !memq && o.fork_bridge;
    pid_t child = -1;
    if (forked) {
        std::fflush(stdout);
        child = fork();
        if (child < 0) {
            std::perror("lcm_pingpong: fork");
            return 1;
        }
        if (child == 0) {
            std::_Exit(run_child_bridge(o.url));
        }
    }

    Plant plant;
    Bridge bridge;
    plant.lcm = lcm_create(o.url.c_str());
    if (plant.lcm == nullptr) {
        std::printf("SKIP: lcm_create(\"%s\") returned NULL (no multicast route on loopback?)\n",
                    o.url.c_str());
        return 77;
    }
    bridge.lcm = (memq || forked) ? plant.lcm : lcm_create(o.url.c_str());
    if (bridge.lcm == nullptr) {
        std::printf("SKIP: second lcm_create(\"%s\") returned NULL\n", o.url.c_str());
        lcm_destroy(plant.lcm);
        return 77;
    }
    lcm_subscription_t *sb = forked ? nullptr
                             : lcm_subscribe(bridge.lcm, kChSensor, &Bridge::on_sensor, &bridge);
    lcm_subscription_t *sp = lcm_subscribe(plant.lcm, kChCmd, &Plant::on_cmd, &plant);

    std::atomic<bool> stop{false};
    std::thread bridge_thread;
    if (!memq && !forked) {
        bridge_thread = std::thread([&bridge, &stop] {
            while (!stop.load(std::memory_order_relaxed)) {
                if (lcm_handle_timeout(bridge.lcm, 20) < 0) {
                    ++bridge.errors;
                    break;
                }
            }
        });
    }

    lcm_t *const dispatch = memq ? plant.lcm : nullptr;
    std::int64_t k = 0;
    bool ok = true;
    for (long i = 0; i < o.warmup && ok; ++i) {
        ok = round_trip(plant, dispatch, k++, o.retx_ms);
    }
    std::vector<RepResult> reps;
    for (long r = 0; r < o.reps && ok; ++r) {
        RepResult res;
        ok = run_rep(plant, dispatch, o, k, res);
        if (ok) {
            reps.push_back(res);
            std::printf("rep %ld: %.0f round trips/s, rtt min %.1f us, median %.1f us\n", r + 1,
                        res.rate, res.rtt_min, res.rtt_med);
        }
    }

    stop.store(true);
    if (bridge_thread.joinable()) {
        bridge_thread.join();
    }
    long child_errors = 0;
    if (forked) {
        // Datagrams may be lost: repeat STOP until the child has exited (at most ~3 s).
        static const std::uint8_t stop_msg[1] = { 0 };
        int status = 0;
        pid_t done = 0;
        for (int i = 0; i < 300 && done == 0; ++i) {
            (void)lcm_publish(plant.lcm, kChStop, stop_msg, 1U);
            (void)lcm_handle_timeout(plant.lcm, 10);
            done = waitpid(child, &status, WNOHANG);
        }
        if (done == 0) {
            (void)kill(child, SIGTERM);
            (void)waitpid(child, &status, 0);
            child_errors = 1;
        } else if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
            child_errors = 1;
        }
    } else {
        (void)lcm_unsubscribe(bridge.lcm, sb);
    }
    (void)lcm_unsubscribe(plant.lcm, sp);
    if (!memq && !forked) {
        lcm_destroy(bridge.lcm);
    }
    lcm_destroy(plant.lcm);

    const long errors = plant.errors + bridge.errors + child_errors;
    if (!ok || errors != 0) {
        std::fprintf(stderr, "lcm_pingpong: FAILED (%ld decode/publish error(s))\n", errors);
        return 1;
    }
    std::vector<double> rates;
    std::vector<double> meds;
    double rtt_min = reps.front().rtt_min;
    for (const RepResult &r : reps) {
        rates.push_back(r.rate);
        meds.push_back(r.rtt_med);
        rtt_min = std::min(rtt_min, r.rtt_min);
    }
    std::printf("lcm_pingpong: transport=%s%s url=%s frame=%dB cmd=%dB n=%ld reps=%ld "
                "rate_median=%.0f rate_min=%.0f rate_max=%.0f rtt_min_us=%.1f rtt_median_us=%.1f "
                "retx=%ld",
                o.transport.c_str(), forked ? "(fork)" : "", o.url.c_str(), plant.frame_len,
                bridge.tx.getEncodedSize(), o.n, o.reps, median(rates),
                *std::min_element(rates.begin(), rates.end()),
                *std::max_element(rates.begin(), rates.end()), rtt_min, median(meds), plant.retx);
    if (!forked) {
        std::printf(" bridge_frames=%ld", bridge.frames);   // the forked child keeps its own count
    }
    std::printf("\n");
    return 0;
}
