// log_tap.hpp — writes every message on an lcm_t to a standard LCM event log (spec 00 §5.3).
// For memq runs, which no external lcm-logger can hear, with the simulation time of the step as
// event timestamp (two runs of a scenario give byte-identical log files); and as `sil logger`
// in udpm runs (wall-clock timestamps, as lcm-logger), with a deep subscription queue.
#ifndef HIL_SIL_LOG_TAP_HPP
#define HIL_SIL_LOG_TAP_HPP

#include <cstdint>
#include <functional>
#include <string>

#include <lcm/lcm.h>
#include <lcm/eventlog.h>

namespace sil {

class LogTap {
public:
    static constexpr int kQueueCapacity = 1 << 20;   // messages held while the writer catches up

    LogTap(lcm_t *lcm, const std::string &path, std::function<std::int64_t()> clock_us);
    ~LogTap();
    LogTap(const LogTap &) = delete;
    LogTap &operator=(const LogTap &) = delete;
    std::uint64_t events() const { return n_; }

private:
    static void on_any(const lcm_recv_buf_t *rb, const char *ch, void *user);
    lcm_t *lcm_;
    lcm_eventlog_t *log_ = nullptr;
    lcm_subscription_t *sub_ = nullptr;
    std::function<std::int64_t()> clock_;
    std::uint64_t n_ = 0;
};

}  // namespace sil

#endif  // HIL_SIL_LOG_TAP_HPP
