#include "log_tap.hpp"

#include "channels.hpp"

#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace sil {

LogTap::LogTap(lcm_t *lcm, const std::string &path, std::function<std::int64_t()> clock_us)
    : lcm_(lcm), clock_(std::move(clock_us))
{
    log_ = lcm_eventlog_create(path.c_str(), "w");
    if (log_ == nullptr) {
        throw std::runtime_error("cannot create LCM log '" + path + "'");
    }
    sub_ = lcm_subscribe(lcm_, ".*", &LogTap::on_any, this);
    if (sub_ == nullptr) {
        throw std::runtime_error("cannot subscribe the LCM log tap");
    }
    // LCM's default per-subscription queue is 30 messages; a logger that falls behind for a few
    // milliseconds (two busy cores) would drop silently. This is why lcm-logger lost 120 of
    // 6000 telemetry messages in one udpm run out of five (hil_host/sil/README.md).
    (void)lcm_subscription_set_queue_capacity(sub_, kQueueCapacity);
}

LogTap::~LogTap()
{
    if (sub_ != nullptr) { lcm_unsubscribe(lcm_, sub_); }
    if (log_ != nullptr) { lcm_eventlog_destroy(log_); }
}

void LogTap::on_any(const lcm_recv_buf_t *rb, const char *ch, void *user)
{
    auto *self = static_cast<LogTap *>(user);
    lcm_eventlog_event_t ev{};
    ev.eventnum = static_cast<int64_t>(self->n_);
    ev.timestamp = self->clock_ ? self->clock_() : 0;
    ev.channellen = static_cast<int32_t>(std::strlen(ch));
    ev.datalen = static_cast<int32_t>(rb->data_size);
    ev.channel = const_cast<char *>(ch);
    ev.data = rb->data;
    if (lcm_eventlog_write_event(self->log_, &ev) == 0) {
        ++self->n_;
    }
    // Run-control messages are rare: flushing them makes the log's start (and end) visible on
    // disk at once, which the udpm run script's logger handshake waits for.
    if (std::strcmp(ch, kChCtl) == 0) {
        (void)std::fflush(self->log_->f);
    }
}

}  // namespace sil
