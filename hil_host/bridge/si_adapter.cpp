#include "si_adapter.hpp"

#include <cmath>

namespace bridge {

SiAdapter::SiAdapter(const SiChannel *ch, std::size_t n) : n_((n < kMaxCounts) ? n : kMaxCounts)
{
    for (std::size_t i = 0; i < n_; ++i) {
        ch_[i] = ch[i];
    }
}

SiAdapter::Conv SiAdapter::convert(std::size_t i, double v, std::int32_t *out) const
{
    if (i >= n_) {
        return Conv::Range;
    }
    const SiChannel &c = ch_[i];
    if (!std::isfinite(v) || !std::isfinite(c.lsb) || !std::isfinite(c.offset_counts) ||
        !(c.lsb > 0.0)) {
        return Conv::NonFinite;
    }
    const double x = v / c.lsb + c.offset_counts;
    if (!std::isfinite(x)) {
        return Conv::NonFinite;
    }
    const double r = std::round(x);   // half away from zero, the project's one rounding rule
    // int32 limits are exact in double; r is integral, so the cast below is exact and defined.
    if ((r < static_cast<double>(c.min)) || (r > static_cast<double>(c.max))) {
        return Conv::Range;
    }
    *out = static_cast<std::int32_t>(r);
    return Conv::Ok;
}

bool SiAdapter::to_frame(const SiFrame &in, Frame *out, Counters &c)
{
    if ((in.n_values < 0) || (static_cast<std::size_t>(in.n_values) > n_)) {
        sat_inc(c.malformed);
        return false;
    }
    const std::size_t n = static_cast<std::size_t>(in.n_values);
    // Pass 1: finiteness of every present value before anything is converted or stored.
    int nonfinite = 0;
    for (std::size_t i = 0; i < n; ++i) {
        if (in.value[i].has_value() && !std::isfinite(*in.value[i])) {
            ++nonfinite;
        }
    }
    Frame f{};
    f.utime = in.utime;
    f.seq = in.seq;
    f.period_us = in.period_us;
    f.n_counts = in.n_values;
    f.scenario_flags = in.scenario_flags;
    f.plant_flags = in.plant_flags;
    std::int32_t good[kMaxCounts] = {};
    bool range_bad[kMaxCounts] = {};
    int range = 0;
    for (std::size_t i = 0; (nonfinite == 0) && (i < n); ++i) {
        f.status[i] = in.status[i];
        if (!in.value[i].has_value()) {
            f.counts[i] = last_good_[i];
            f.status[i] = static_cast<std::int8_t>(f.status[i] | kStatusStale);
            continue;
        }
        std::int32_t k = 0;
        const Conv r = convert(i, *in.value[i], &k);
        if (r == Conv::NonFinite) {
            ++nonfinite;   // finite value, non-finite after scaling
        } else if (r == Conv::Range) {
            range_bad[i] = true;
            ++range;
            f.counts[i] = last_good_[i];
            f.status[i] = static_cast<std::int8_t>(f.status[i] | kStatusStale);
        } else {
            good[i] = k;
            f.counts[i] = k;
        }
    }
    if (nonfinite != 0) {
        sat_inc(c.nonfinite_rej, nonfinite);
        return false;
    }
    sat_inc(c.range_rej, range);
    for (std::size_t i = 0; i < n; ++i) {
        if (in.value[i].has_value() && !range_bad[i] && ((in.status[i] & kStatusStale) == 0)) {
            last_good_[i] = good[i];
        }
    }
    *out = f;
    return true;
}

}  // namespace bridge
