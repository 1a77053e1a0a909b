#include "respin/rsp_cmg_ref.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

namespace ref {

namespace {

double det3(const Eigen::Matrix3d &m) { return m.determinant(); }

// The spec's rounding (half away from zero) of a count; |v| is far below 2^31 here.
std::int32_t round_cnt(double v) { return static_cast<std::int32_t>(std::lround(v)); }

}  // namespace

CmgTable cmg_dequantise(const rsp_cmg_params_t &p)
{
    CmgTable t;
    t.hg_nms = std::ldexp(static_cast<double>(p.hg_q20), -20);
    t.lambda = std::ldexp(static_cast<double>(p.lambda_q28), -28);
    t.umax_cnt = p.umax_cnt;
    t.umax_radps = std::ldexp(static_cast<double>(p.umax_cnt), -16);
    t.ms_sing = std::ldexp(static_cast<double>(p.ms_sing_q28), -28);
    return t;
}

double cmg_beta_rad(std::uint32_t encoder_cnt)
{
    return static_cast<double>(encoder_cnt % kCmgEncCounts) * kCmgEncLsbRad;
}

CmgGeom cmg_geom(const std::array<double, 4> &beta_rad, double hg_nms)
{
    std::array<double, 4> s{}, c{};
    for (std::size_t p = 0; p < 4u; ++p) {
        s[p] = std::sin(beta_rad[p]);
        c[p] = std::cos(beta_rad[p]);
    }
    CmgGeom g;
    g.h_nms = {{hg_nms * (c[2] - c[3]), hg_nms * (c[0] - c[1]), hg_nms * (s[0] + s[1] + s[2] + s[3])}};
    // columns (0, -s1, c1), (0, s2, c2), (-s3, 0, c3), (s4, 0, c4)
    g.ahat[0] = {{0.0, 0.0, -s[2], s[3]}};
    g.ahat[1] = {{-s[0], s[1], 0.0, 0.0}};
    g.ahat[2] = {{c[0], c[1], c[2], c[3]}};
    return g;
}

double cmg_ms(const CmgGeom &g)
{
    double sum = 0.0;
    for (std::size_t skip = 0; skip < 4u; ++skip) {
        Eigen::Matrix3d m;
        Eigen::Index k = 0;
        for (std::size_t j = 0; j < 4u; ++j) {
            if (j == skip) { continue; }
            for (std::size_t i = 0; i < 3u; ++i) { m(static_cast<Eigen::Index>(i), k) = g.ahat[i][j]; }
            ++k;
        }
        const double d = det3(m);
        sum += d * d;
    }
    return std::sqrt(sum);
}

double cmg_ms_det(const CmgGeom &g)
{
    Eigen::Matrix<double, 3, 4> a;
    for (std::size_t i = 0; i < 3u; ++i) {
        for (std::size_t j = 0; j < 4u; ++j) {
            a(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = g.ahat[i][j];
        }
    }
    const Eigen::Matrix3d aat = a * a.transpose();
    return std::sqrt(std::max(0.0, det3(aat)));
}

V3 cmg_mdel(const CmgTable &t, const CmgGeom &g, const std::array<std::int32_t, 4> &cnt)
{
    V3 m{};
    for (std::size_t i = 0; i < 3u; ++i) {
        double a = 0.0;
        for (std::size_t p = 0; p < 4u; ++p) { a += g.ahat[i][p] * (static_cast<double>(cnt[p]) * kCmgRateLsbRadps); }
        m[i] = -t.hg_nms * a;
    }
    return m;
}

CmgSteer cmg_steer(const CmgTable &t, const CmgGeom &g, const V3 &mcmd_nm)
{
    CmgSteer o;
    Eigen::Matrix<double, 3, 4> a;
    for (std::size_t i = 0; i < 3u; ++i) {
        for (std::size_t j = 0; j < 4u; ++j) {
            a(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = g.ahat[i][j];
        }
    }
    o.ms = cmg_ms(g);
    if (o.ms < t.ms_sing) { o.flags |= RSP_CMG_F_SINGULAR; }
    // Hdot_c = -M_cmd; y = (A A^T + lambda0 I)^-1 Hdot_c / h_g (symmetric positive definite)
    const Eigen::Matrix3d p = a * a.transpose() + t.lambda * Eigen::Matrix3d::Identity();
    const Eigen::Vector3d b(-mcmd_nm[0] / t.hg_nms, -mcmd_nm[1] / t.hg_nms, -mcmd_nm[2] / t.hg_nms);
    const Eigen::Vector3d y = p.ldlt().solve(b);
    const Eigen::Vector4d bd = a.transpose() * y;
    double mx = 0.0;
    for (std::size_t k = 0; k < 4u; ++k) {
        o.rate_radps[k] = bd(static_cast<Eigen::Index>(k));
        mx = std::max(mx, std::fabs(o.rate_radps[k]));
    }
    o.s = mx / t.umax_radps;
    const bool limited = o.s > 1.0;
    if (limited) { o.flags |= RSP_CMG_F_RATE_LIMITED; }
    for (std::size_t k = 0; k < 4u; ++k) {
        o.cmd_cnt[k] = (limited ? o.rate_radps[k] / o.s : o.rate_radps[k]) / kCmgRateLsbRadps;
        o.rate_cnt[k] = std::clamp(round_cnt(o.cmd_cnt[k]), -t.umax_cnt, t.umax_cnt);
    }
    o.mdel_nm = cmg_mdel(t, g, o.rate_cnt);
    return o;
}

}  // namespace ref
