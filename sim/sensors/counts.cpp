#include "sensors/counts.hpp"

#include <cmath>

namespace sim {

std::int32_t counts_from_si(double v_si, double lsb_si, std::int32_t max_cnt, std::uint8_t *status)
{
    const double q = v_si / lsb_si;
    if (!std::isfinite(q)) {
        *status = static_cast<std::uint8_t>(kStatusSat | kStatusNonFinite);
        return 0;
    }
    const double full = static_cast<double>(max_cnt);
    std::int32_t c = 0;
    if (q >= full) {
        c = max_cnt;
    } else if (q <= -full) {
        c = -max_cnt;
    } else {
        // |q| < max_cnt <= 2^31 - 1, so the rounded value fits in int32.
        c = static_cast<std::int32_t>(std::round(q));
    }
    *status = (c == max_cnt || c == -max_cnt) ? kStatusSat : std::uint8_t{0u};
    return c;
}

}  // namespace sim
