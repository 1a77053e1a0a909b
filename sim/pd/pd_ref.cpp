#include "pd/pd_ref.hpp"

#include <cmath>

namespace ref {

PdTable dequantise(const pd_params_t &p)
{
    PdTable t;
    t.k_nms = std::ldexp(static_cast<double>(p.gain_q16), -12);
    t.u_max_nm = std::ldexp(static_cast<double>(p.u_max_cnt), -16);
    t.rate_max_radps = std::ldexp(static_cast<double>(p.rate_max_cnt), -20);
    t.n_sat = p.n_sat;
    return t;
}

PdOut pd_law(const PdTable &t, double omega_radps)
{
    PdOut o;
    const double u = -t.k_nms * omega_radps;
    o.limited = std::fabs(u) > t.u_max_nm;
    o.tau_nm = o.limited ? std::copysign(t.u_max_nm, u) : u;
    return o;
}

}  // namespace ref
