// si_adapter.hpp — optional SI-unit input adapter (spec 00 §5.1 "SI adapter", §8).
//
// A third-party plant may deliver SI doubles instead of counts. Converting NaN, +-Inf or an
// out-of-range double to an integer is undefined behaviour in C and C++, so every value is
// checked with std::isfinite, scaled, checked with std::isfinite again (a tiny LSB can
// overflow the quotient), and range-checked against the channel's count limits BEFORE the one
// cast, which then converts an integral double inside [min, max] (exact).
//
//   count = round_half_away(value / lsb + offset_counts), accepted iff min <= count_real <= max
//
// Outcomes per frame:
//  - any present value non-finite (value or scaled value): the whole frame is rejected,
//    nonfinite_rej counts every non-finite value, and nothing is produced (fsw not stepped);
//  - a finite value outside [min, max]: range_rej++, the channel keeps its last good count
//    with STATUS_STALE (as FrameValidator does for counts);
//  - an absent value (std::nullopt): last good count with STATUS_STALE, not counted.
#ifndef HIL_BRIDGE_SI_ADAPTER_HPP
#define HIL_BRIDGE_SI_ADAPTER_HPP

#include <cstdint>
#include <optional>

#include "bridge_types.hpp"

namespace bridge {

struct SiChannel {
    double lsb = 1.0;             // SI units per count (> 0, finite)
    double offset_counts = 0.0;   // added after scaling (bias in counts)
    std::int32_t min = INT32_MIN; // count limits (the sensor table's)
    std::int32_t max = INT32_MAX;
};

struct SiFrame {
    std::int64_t utime = 0;
    std::int64_t seq = 0;
    std::int32_t period_us = 0;
    std::int16_t n_values = 0;
    std::optional<double> value[kMaxCounts];
    std::int8_t status[kMaxCounts] = {};
    std::int32_t scenario_flags = 0;
    std::int32_t plant_flags = 0;
};

class SiAdapter {
public:
    SiAdapter(const SiChannel *ch, std::size_t n);

    // Converts one value; true and *out set when finite and in range. Pure: no counters.
    enum class Conv { Ok, NonFinite, Range };
    Conv convert(std::size_t ch, double v, std::int32_t *out) const;

    // Converts a frame. Returns false (frame rejected, *out untouched) when any present value
    // is non-finite or n_values is outside [0, channels]; true otherwise.
    bool to_frame(const SiFrame &in, Frame *out, Counters &c);

private:
    SiChannel ch_[kMaxCounts] = {};
    std::size_t n_ = 0;
    std::int32_t last_good_[kMaxCounts] = {};
};

}  // namespace bridge

#endif  // HIL_BRIDGE_SI_ADAPTER_HPP
