// rsp_ref.hpp — the RESPIN law in double precision: the reference the fixed-point flight
// code is proven against (golden tests, the reference backend of `sil run --fsw ref`). It reads
// the same table, dequantised: K = gain_q16 / 2^12 N m s, u_max = u_max_cnt * 2^-16 N m.
#ifndef SIM_RSP_REF_HPP
#define SIM_RSP_REF_HPP

extern "C" {
#include "rsp.h"
}

namespace ref {

struct RespinTable {
    double k_nms = 0.0;        // tau = -K omega
    double u_max_nm = 0.0;
    double rate_max_radps = 0.0;
    unsigned n_sat = 0u;
};

struct RespinOut {
    double tau_nm = 0.0;
    bool limited = false;
};

RespinTable dequantise(const rsp_params_t &p);
// The command for a measured body rate (rad/s).
RespinOut rsp_law(const RespinTable &t, double omega_radps);

}  // namespace ref

#endif
