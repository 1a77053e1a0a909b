// pd_fest_quant — the one quantiser of the estimator's table block: FestParams (double, from
// make_fest_params on the channel's nominal model) -> pd_fest_params_t (fsw/pd/pd_fest.h). The
// table tool (pd_analysis fest-params -> tools/pd design) and the golden tests both use it, so
// the flight table and the tested constants cannot drift apart.
#ifndef SIM_PD_PD_FEST_QUANT_HPP
#define SIM_PD_PD_FEST_QUANT_HPP

#include <string>

#include "pd/pd_fest_ref.hpp"

extern "C" {
#include "pd_fest.h"
}

namespace ref::pd {

// Throws std::invalid_argument when a constant does not fit its format (a mantissa row of zeros is
// stored as 0 with shift 0).
pd_fest_params_t quantise_fest(const FestParams &p);
// The block as JSON: {"n_sec": .., ..., "ad_m": [[..]..], ...} in the field order of pd_fest.h
std::string fest_params_json(const pd_fest_params_t &q);

}  // namespace ref::pd

#endif
