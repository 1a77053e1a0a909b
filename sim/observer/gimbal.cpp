#include "observer/gimbal.hpp"

#include <cmath>

#include "sensors/counts.hpp"

namespace sim {

std::array<double, 2> GimbalActuators::apply(const std::array<std::int32_t, 2> &cnt, std::uint32_t seq,
                                             std::int64_t utime_us, std::vector<TruthEvent> *events) const
{
    std::array<double, 2> out{};
    for (std::size_t i = 0; i < 2u; ++i) {
        const double req = static_cast<double>(cnt[i]) * cfg_.lsb_radps();
        double app = req;
        if (req > cfg_.hw_limit_radps) {
            app = cfg_.hw_limit_radps;
        } else if (req < -cfg_.hw_limit_radps) {
            app = -cfg_.hw_limit_radps;
        }
        if (!(app <= req && app >= req)) {  // clipped (compared without ==, -Wfloat-equal)
            TruthEvent ev;
            ev.utime_us = utime_us;
            ev.seq = seq;
            ev.kind = "ACT_CLIP";
            ev.channel = static_cast<int>(i);
            ev.requested = req;
            ev.applied = app;
            events->push_back(ev);
        }
        out[i] = app;
    }
    return out;
}

std::int32_t GimbalActuators::counts(double rate_radps, std::uint8_t *status) const
{
    return counts_from_si(rate_radps, cfg_.lsb_radps(), INT32_MAX, status);
}

}  // namespace sim
