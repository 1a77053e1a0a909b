// frame_validator.hpp — checks a sensor frame against the sensor-limits table (spec 00 §8).
//
// Whole-frame refusal (counted in Counters::malformed; the frame never reaches the step and the
// gate is not advanced): seq outside [0, kMaxSeq], n_counts not equal to the table's channel
// count, period_us different from the table's (when the table sets one).
//
// Per channel i < n_channels ("keep last good"): a count outside [min_i, max_i] is not passed
// on. The validator substitutes the channel's last good count (0 before the first good one),
// sets STATUS_STALE on that channel and counts range_rej. The flight code sees a stale channel
// holding its last good value and applies its own persistence rule (SAFE after stale_max in the
// executive; the observer skips that axis). The plant's own status bits (STALE, SAT) pass
// through unchanged; a count with the plant's STALE bit is not a fresh good value and does not
// update the last good value.
#ifndef HIL_BRIDGE_FRAME_VALIDATOR_HPP
#define HIL_BRIDGE_FRAME_VALIDATOR_HPP

#include <cstdint>

#include "bridge_types.hpp"

namespace bridge {

struct ChannelLimits {
    std::int32_t min = INT32_MIN;
    std::int32_t max = INT32_MAX;
};

struct SensorLimits {
    std::int16_t n_channels = 0;           // frames must carry exactly this many counts
    std::int32_t period_us = 0;            // expected period; 0 = not checked
    ChannelLimits ch[kMaxCounts] = {};
};

enum class FrameVerdict { Ok, Malformed };

class FrameValidator {
public:
    explicit FrameValidator(const SensorLimits &lim) : lim_(lim) {}

    // Header checks only (no state change): seq range, n_counts, period.
    FrameVerdict check_header(const Frame &f) const;
    // Range checks on a frame whose header passed; rewrites rejected channels in place
    // (last good value + STATUS_STALE), counts range_rej, remembers good values.
    // Returns the number of channels rejected in this frame.
    int apply_ranges(Frame &f, Counters &c);

    const SensorLimits &limits() const { return lim_; }
    // New limits (a table changed the ranges); the last good values are kept.
    void set_limits(const SensorLimits &lim) { lim_ = lim; }
    std::int32_t last_good(std::size_t i) const { return last_good_[i]; }

private:
    SensorLimits lim_;
    std::int32_t last_good_[kMaxCounts] = {};
};

}  // namespace bridge

#endif  // HIL_BRIDGE_FRAME_VALIDATOR_HPP
