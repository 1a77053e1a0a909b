// @prefix@_ref.hpp — the @MISSION@ law in double precision: the reference the fixed-point flight
// code is proven against (golden tests, the reference backend of `sil run --fsw ref`). It reads
// the same table, dequantised: K = gain_q16 / 2^12 N m s, u_max = u_max_cnt * 2^-16 N m.
#ifndef SIM_@PREFIX@_REF_HPP
#define SIM_@PREFIX@_REF_HPP

extern "C" {
#include "@prefix@.h"
}

namespace ref {

struct @Class@Table {
    double k_nms = 0.0;        // tau = -K omega
    double u_max_nm = 0.0;
    double rate_max_radps = 0.0;
    unsigned n_sat = 0u;
};

struct @Class@Out {
    double tau_nm = 0.0;
    bool limited = false;
};

@Class@Table dequantise(const @prefix@_params_t &p);
// The command for a measured body rate (rad/s).
@Class@Out @prefix@_law(const @Class@Table &t, double omega_radps);

}  // namespace ref

#endif
