// rly_ref_params.hpp — the reference adaptation's parameters read from a flight table, so the twin
// and the flight code run on one set of numbers (golden G5, rly_long's reference runs).
#ifndef SIM_RLY_REF_PARAMS_HPP
#define SIM_RLY_REF_PARAMS_HPP

#include <cstdint>

#include "relay/rly_ref.hpp"

extern "C" {
#include "rly.h"
}

namespace ref {

inline AdaptParams adapt_params_of(const rly_params_t &p)
{
    AdaptParams a;
    a.mode = static_cast<AdaptMode>(p.adapt_mode);
    a.tmin_windows = p.tmin_windows;
    a.dk_q16 = p.dk_q16;
    a.kt0_q16 = p.kt0_q16;
    a.kt_min_q16 = p.kt_min_q16;
    a.kt_max_q16 = p.kt_max_q16;
    a.delta0_num = p.delta0_num;
    a.delta0_den = p.delta0_den;
    a.n_small = p.n_small;
    a.n_ignore = p.n_ignore;
    a.count_before_tmin = p.count_before_tmin != 0u;
    a.learn_after_tmin = p.learn_after_tmin != 0u;
    a.seed = p.seed;
    a.gate_dk = p.gate_dk;
    a.probe_settle = p.probe_settle;
    a.cliff_num = p.cliff_num;
    a.cliff_den = p.cliff_den;
    a.retreat_dk = p.retreat_dk;
    a.unfreeze_num = p.unfreeze_num;
    a.unfreeze_den = p.unfreeze_den;
    a.unfreeze_windows = p.unfreeze_windows;
    // alarm < 2^32, win_ticks <= 2^21 (rly_params_check): the product < 2^53
    a.escape_s = static_cast<std::uint64_t>(p.env_alarm_q40) * p.win_ticks;
    return a;
}

}  // namespace ref

#endif
