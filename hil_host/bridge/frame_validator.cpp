#include "frame_validator.hpp"

namespace bridge {

FrameVerdict FrameValidator::check_header(const Frame &f) const
{
    FrameVerdict v = FrameVerdict::Ok;
    if ((f.seq < 0) || (f.seq > kMaxSeq)) {
        v = FrameVerdict::Malformed;
    } else if ((f.n_counts != lim_.n_channels) || (f.n_counts < 0) ||
               (f.n_counts > static_cast<std::int16_t>(kMaxCounts))) {
        v = FrameVerdict::Malformed;
    } else if ((lim_.period_us != 0) && (f.period_us != lim_.period_us)) {
        v = FrameVerdict::Malformed;
    } else {
        v = FrameVerdict::Ok;
    }
    return v;
}

int FrameValidator::apply_ranges(Frame &f, Counters &c)
{
    int rejected = 0;
    const std::size_t n = (f.n_counts > 0) ? static_cast<std::size_t>(f.n_counts) : 0u;
    for (std::size_t i = 0; (i < n) && (i < kMaxCounts); ++i) {
        const std::int32_t v = f.counts[i];
        if ((v < lim_.ch[i].min) || (v > lim_.ch[i].max)) {
            f.counts[i] = last_good_[i];
            f.status[i] = static_cast<std::int8_t>(f.status[i] | kStatusStale);
            sat_inc(c.range_rej);
            ++rejected;
        } else if ((f.status[i] & kStatusStale) == 0) {
            last_good_[i] = v;
        } else {
            // plant-held value: in range, passed on with the plant's STALE bit, not "fresh"
        }
    }
    return rejected;
}

}  // namespace bridge
