// rsp_cmg_ref.hpp — the gyrodine steering of spec 30 §2 / §4 in double precision: the twin the
// fixed-point fsw/respin/rsp_cmg.c is proven against (tests/respin/test_rsp_cmg_golden_host.cpp).
//
// It reads what the flight code reads: encoder counts (2pi / 2^20 rad, cmg_beta_rad), the table
// rsp_cmg_params_t dequantised exactly (cmg_dequantise: every field is an integer times a power of
// two), and the law's moment M_cmd as the flight holds it (2^-24 N m, exact in double). Everything
// else is plain double arithmetic of the spec's equations: no fixed-point format, no saturation.
//
//   H = h_g (c3 - c4, c1 - c2, s1 + s2 + s3 + s4);  Ahat = dH/dbeta / h_g
//   y = (Ahat Ahat^T + lambda0 I)^-1 (-M_cmd / h_g);  beta_dot = Ahat^T y     (rate_radps)
//   s = max_p |beta_dot_p| / u_max;  s > 1: beta_dot / s, RATE_LIMITED
//   rate_cnt = round half away from zero (beta_dot 2^16), then clamped to +-umax_cnt (as the flight)
//   M_del = -h_g Ahat (rate_cnt 2^-16)       (the moment the commanded counts deliver)
//   m_s = sqrt(sum of the four squared 3x3 minors of Ahat) (Cauchy-Binet); SINGULAR when m_s < ms_sing
//
// Sign chain (spec 30 §9): M_cmd is the internal moment on the body; the cluster follows -M_cmd.
#ifndef SIM_RSP_CMG_REF_HPP
#define SIM_RSP_CMG_REF_HPP

#include <array>
#include <cstdint>

#include "respin/rsp_ref.hpp"

extern "C" {
#include "rsp_cmg.h"
}

namespace ref {

constexpr double kCmgEncLsbRad = 6.283185307179586476925286766559 / 1048576.0;   // 2pi / 2^20 rad
constexpr double kCmgRateLsbRadps = 1.0 / 65536.0;                                 // 2^-16 rad/s
constexpr std::uint32_t kCmgEncCounts = 1048576u;                                  // one turn

using CmgA = std::array<std::array<double, 4>, 3>;   // Ahat, row = body axis, column = gyrodine

// The table in SI.
struct CmgTable {
    double hg_nms = 0.0;            // rotor momentum h_g
    double lambda = 0.0;            // damping lambda0
    std::int32_t umax_cnt = 0;      // rate limit in command counts
    double umax_radps = 0.0;        // the same, rad/s (umax_cnt 2^-16)
    double ms_sing = 0.0;           // SINGULAR threshold on m_s
};

CmgTable cmg_dequantise(const rsp_cmg_params_t &p);

struct CmgGeom {
    V3 h_nms{{0.0, 0.0, 0.0}};      // cluster momentum, body frame
    CmgA ahat{};                    // normalised Jacobian
};

struct CmgSteer {
    std::array<double, 4> rate_radps{{0.0, 0.0, 0.0, 0.0}};   // beta_dot before the scaling
    double s = 0.0;                                            // max |beta_dot| / u_max
    std::array<double, 4> cmd_cnt{{0.0, 0.0, 0.0, 0.0}};      // beta_dot / max(s, 1) in counts, unrounded
    std::array<std::int32_t, 4> rate_cnt{{0, 0, 0, 0}};       // rounded, clamped command
    V3 mdel_nm{{0.0, 0.0, 0.0}};                               // -h_g Ahat rate_cnt 2^-16
    double ms = 0.0;
    std::uint32_t flags = 0u;                                  // RSP_CMG_F_*
};

// Encoder count (2pi / 2^20 rad, taken modulo one turn as the flight's count << 12 wraps) -> rad.
double cmg_beta_rad(std::uint32_t encoder_cnt);

CmgGeom cmg_geom(const std::array<double, 4> &beta_rad, double hg_nms);
// m_s by Cauchy-Binet (the sum of the four squared 3x3 minors).
double cmg_ms(const CmgGeom &g);
// sqrt(det(Ahat Ahat^T)) computed directly (tests cross-check it against cmg_ms).
double cmg_ms_det(const CmgGeom &g);
// The moment commanded counts deliver: -h_g Ahat cnt 2^-16.
V3 cmg_mdel(const CmgTable &t, const CmgGeom &g, const std::array<std::int32_t, 4> &cnt);
CmgSteer cmg_steer(const CmgTable &t, const CmgGeom &g, const V3 &mcmd_nm);

}  // namespace ref

#endif
