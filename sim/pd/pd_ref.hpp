// pd_ref.hpp — the HOLD law in double precision: the reference the fixed-point flight
// code is proven against (golden tests, the reference backend of `sil run --fsw ref`). It reads
// the same table, dequantised: K = gain_q16 / 2^12 N m s, u_max = u_max_cnt * 2^-16 N m.
#ifndef SIM_PD_REF_HPP
#define SIM_PD_REF_HPP

extern "C" {
#include "pd.h"
}

namespace ref {

struct PdTable {
    double k_nms = 0.0;        // tau = -K omega
    double u_max_nm = 0.0;
    double rate_max_radps = 0.0;
    unsigned n_sat = 0u;
};

struct PdOut {
    double tau_nm = 0.0;
    bool limited = false;
};

PdTable dequantise(const pd_params_t &p);
// The command for a measured body rate (rad/s).
PdOut pd_law(const PdTable &t, double omega_radps);

}  // namespace ref

#endif
