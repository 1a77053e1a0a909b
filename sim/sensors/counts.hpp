// counts.hpp — the one SI -> sensor count conversion every plant uses (spec 00 §5.1).
#ifndef SIM_SENSORS_COUNTS_HPP
#define SIM_SENSORS_COUNTS_HPP

#include <cstdint>

#include "plant/plant.hpp"   // status bits

namespace sim {

// SI value -> counts, rounding to nearest (ties away from zero). The NaN/Inf and range checks
// come BEFORE the conversion, because converting NaN or an out-of-range double to an integer is
// undefined behaviour. Returns the count; status gets kStatusSat at |count| == max_cnt and
// kStatusSat | kStatusNonFinite (count 0) for a non-finite input.
std::int32_t counts_from_si(double v_si, double lsb_si, std::int32_t max_cnt, std::uint8_t *status);

}  // namespace sim

#endif
