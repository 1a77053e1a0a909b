// Golden vectors of the gyrodine steering (spec 30 §4, §6): the fixed-point flight code
// (fsw/respin/rsp_cmg.c) against its double twin (sim/respin/rsp_cmg_ref), both fed the same integer
// inputs: four encoder counts (2pi / 2^20 rad; the flight takes count << 12 as its binary angle) and
// the law's moment M_cmd in 2^-24 N m. The expected values come from the twin, never from the code
// under test.
//
// Cases: 10 000 random (fixed seed, std::mt19937_64): counts uniform in [0, 2^20), M_cmd in a uniform
// random direction with |M| uniform in [0, 4.65] N m (the law's bound, spec 30 §5); plus edge cases:
// the null configuration, |H_z| = 30 (beta = +-pi/2), internal singularities (beta = 0, (0, 0, pi, pi),
// (pi/2, pi/2, 0, 0)), each with commands of |M| = 4.65 along +-x, +-y, +-z and two diagonals (the
// max-rate commands), and 200 random geometries with |M| = 4.65.
//
// Tolerances, derived (eps = 2^-28, one LSB of Q3.28; |b| = |Hdot_c| / h_g <= 0.62, lambda0 = 0.05,
// |y| <= |b| / lambda0 = 12.4, |beta_dot| <= 1.39, |Ahat^T P^-1|_2 <= 1 / (2 sqrt lambda0) = 2.24,
// |Ahat^T P^-1 Ahat|_2 < 1, P = Ahat Ahat^T + lambda0 I):
// * Ahat: fx_sincos <= 0.751 LSB q30 = 0.19 eps, then the rounding to Q3.28: e_A = 0.69 eps per entry
//   (8 non-zero entries: |dA|_F <= 1.95 eps). H: 1/2 LSB q20 + 4 h_g 0.751 2^-30 = 0.53 LSB q20.
// * beta_dot before the scaling (spec bound 1e-6 rad/s). With the flight's Ahat in exact arithmetic:
//   d beta_dot = dA^T y - Ahat^T P^-1 (dA beta_dot + Ahat dA^T y), <= 1.95 (12.4 + 2.24 1.39 + 12.4)
//   = 54 eps. Then the flight's roundings as a backward error, each through |Ahat^T P^-1| <= 2.24:
//   P rounded (1/2 eps on 7 entries, |E|_2 <= 1.32 eps) times |y|: 37 eps; the LDL^T factor (u, L, D
//   each 1/2 eps; since |L_2k D_k| = |u_2k| <= 1 the rounding of L costs D_k eps/2 <= 1.03 eps off the
//   diagonal and |L| D eps/2 <= 1/2 eps per term on it: |E'|_2 <= 3 eps) times |y|: 83 eps; b rounded
//   to Q1.30 (eps/8): 0.5 eps; the w and y roundings (eps/2 of Q5.26 = 2 eps each, entering as L D dw,
//   |L D|_2 <= 4.6): 2 x 36 eps; the final rounding 1/2 eps. Sum 247 eps = 9.2e-7 rad/s: the spec's
//   1e-6 rad/s holds by derivation (worst-case alignment of every term; the measured maximum is
//   printed).
// * rate_cnt: equal, except +-1 where the twin's unrounded command lies within the beta_dot bound of a
//   rounding boundary: 1e-6 rad/s = 0.066 count unscaled; scaled (s > 1) the command is beta_dot_p
//   u_max / max |beta_dot|, whose error is (u_max / max) (d beta_dot_p + d max) <= 2e-6 rad/s = 0.131
//   count. Never beyond +-umax_cnt.
// * M_del (spec bound 2^-20 N m): for equal counts, 1/2 LSB q24 (final rounding) + h_g 2^-31 (the Q1.30
//   intermediate) + h_g e_A sum |cnt| 2^-16 (<= 7.5 0.69 2^-28 4 u_max = 1.4e-8) = 4.7e-8 N m, well
//   inside 2^-20 = 9.5e-7. Where the counts differ by the allowed 1, the flight's M_del is compared with
//   the twin's moment of the flight's counts (the same bound): a count is 7.5 2^-16 = 1.1e-4 N m.
// * m_s (spec bound 1e-4): a minor's error <= 2 (e_A + 4 e_A + 1/2) + 1/2 = 8.4 eps (two non-zero
//   entries in the first row, two-term cofactors rounded), m_s is the 2-norm of the four minors:
//   |d m_s| <= 2 8.4 + 1/2 (root) = 17.3 eps = 6.4e-8.
// * flags: SINGULAR equal unless |m_s,ref - ms_sing| <= 17.3 eps; RATE_LIMITED equal unless
//   |max |beta_dot_ref| - u_max| <= 9.2e-7 rad/s (the beta_dot bound); then either decision is
//   accepted (and counted).
// * No fx status for any of these inputs (all inside the ranges of rsp_cmg.c).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>

#include "respin/rsp_cmg_ref.hpp"
extern "C" {
#include "rsp_cmg.h"
}
#include "sim_test.hpp"

namespace {

constexpr double kEps = 1.0 / 268435456.0;                 // 2^-28
constexpr double kTolRate = 1e-6;                          // rad/s, spec 30 §6
constexpr double kBoundRate = 247.0 * kEps;                // derived, 9.2e-7 rad/s
constexpr double kTolMdel = 1.0 / 1048576.0;               // 2^-20 N m, spec 30 §6
constexpr double kTolMs = 1e-4;                            // spec 30 §6
constexpr double kBoundMs = 17.3 * kEps;                   // derived
constexpr double kTolH = 0.53 / 1048576.0;                 // N m s
constexpr double kTolA = 0.69 * kEps;
constexpr double kMmax = 4.65;                             // N m

rsp_cmg_params_t table()
{
    rsp_cmg_params_t p{};
    p.hg_q20 = 7864320;          // 7.5 N m s
    p.lambda_q28 = 13421773;     // 0.05
    p.umax_cnt = 11437;          // 0.1745 rad/s
    p.ms_sing_q28 = 13421773;    // 0.05
    return p;
}

struct Stats {
    std::uint64_t cases = 0, fails = 0, cnt_pm1 = 0, amb_sing = 0, amb_lim = 0, limited = 0, singular = 0;
    double rate = 0.0, mdel = 0.0, ms = 0.0, h = 0.0, a = 0.0, cb_det = 0.0, cnt_frac_margin = 1.0;
    double pm1_dist = 0.0;   // largest distance from .5 (count) of a twin command where the counts differ
};

bool near_boundary(double v, double band)
{
    const double f = std::fabs(v) - std::floor(std::fabs(v));
    return std::fabs(f - 0.5) <= band;
}

int g_prints = 0;

// One case through both; false on a violation.
bool run_case(const std::array<std::uint32_t, 4> &enc, const std::array<std::int32_t, 3> &m_q24, Stats &st)
{
    const rsp_cmg_params_t p = table();
    const ref::CmgTable t = ref::cmg_dequantise(p);
    std::uint32_t beta_bam[4];
    std::array<double, 4> beta_rad{};
    for (std::size_t k = 0; k < 4u; ++k) {
        beta_bam[k] = enc[k] << 12;
        beta_rad[k] = ref::cmg_beta_rad(enc[k]);
    }
    fx_status_t fst = 0u;
    rsp_cmg_geom_t g{};
    rsp_cmg_out_t o{};
    rsp_cmg_geom(beta_bam, p.hg_q20, &g, &fst);
    rsp_cmg_steer(&p, &g, m_q24.data(), &o, &fst);
    const ref::CmgGeom rg = ref::cmg_geom(beta_rad, t.hg_nms);
    const ref::V3 m_nm{{std::ldexp(m_q24[0], -24), std::ldexp(m_q24[1], -24), std::ldexp(m_q24[2], -24)}};
    const ref::CmgSteer r = ref::cmg_steer(t, rg, m_nm);
    ++st.cases;
    bool ok = fst == 0u;
    // geometry
    for (std::size_t i = 0; i < 3u; ++i) {
        const double eh = std::fabs(std::ldexp(g.h_q20[i], -20) - rg.h_nms[i]);
        st.h = std::max(st.h, eh);
        ok = ok && eh <= kTolH;
        for (std::size_t k = 0; k < 4u; ++k) {
            const double ea = std::fabs(std::ldexp(g.ahat_q28[i][k], -28) - rg.ahat[i][k]);
            st.a = std::max(st.a, ea);
            ok = ok && ea <= kTolA;
        }
    }
    // the twin's Cauchy-Binet against det(Ahat Ahat^T) (squared: the root amplifies rounding at 0)
    const double md = ref::cmg_ms_det(rg);
    st.cb_det = std::max(st.cb_det, std::fabs(r.ms * r.ms - md * md));
    ok = ok && std::fabs(r.ms * r.ms - md * md) <= 1e-12;
    // m_s and SINGULAR
    const double ems = std::fabs(std::ldexp(o.ms_q28, -28) - r.ms);
    st.ms = std::max(st.ms, ems);
    ok = ok && ems <= kTolMs && ems <= kBoundMs;
    const bool sing_fx = (o.flags & RSP_CMG_F_SINGULAR) != 0u;
    const bool sing_ref = (r.flags & RSP_CMG_F_SINGULAR) != 0u;
    if (sing_ref) { ++st.singular; }
    if (sing_fx != sing_ref) {
        if (std::fabs(r.ms - t.ms_sing) <= kBoundMs) {
            ++st.amb_sing;
        } else {
            ok = false;
        }
    }
    // beta_dot before the scaling
    double mx = 0.0;
    for (std::size_t k = 0; k < 4u; ++k) {
        const double e = std::fabs(std::ldexp(o.rate_q28[k], -28) - r.rate_radps[k]);
        st.rate = std::max(st.rate, e);
        ok = ok && e <= kTolRate;
        mx = std::max(mx, std::fabs(r.rate_radps[k]));
    }
    // RATE_LIMITED
    const bool lim_fx = (o.flags & RSP_CMG_F_RATE_LIMITED) != 0u;
    const bool lim_ref = (r.flags & RSP_CMG_F_RATE_LIMITED) != 0u;
    if (lim_ref) { ++st.limited; }
    if (lim_fx != lim_ref) {
        if (std::fabs(mx - t.umax_radps) <= kBoundRate) {
            ++st.amb_lim;
        } else {
            ok = false;
        }
    }
    // counts
    const double band = (lim_ref || lim_fx ? 2.0 * kTolRate : kTolRate) / ref::kCmgRateLsbRadps;
    bool same_cnt = true;
    std::array<std::int32_t, 4> fcnt{};
    for (std::size_t k = 0; k < 4u; ++k) {
        fcnt[k] = o.rate_cnt[k];
        ok = ok && std::abs(fcnt[k]) <= p.umax_cnt;
        const double f = std::fabs(r.cmd_cnt[k]) - std::floor(std::fabs(r.cmd_cnt[k]));
        if (std::fabs(r.cmd_cnt[k]) < p.umax_cnt) {
            st.cnt_frac_margin = std::min(st.cnt_frac_margin, std::fabs(f - 0.5));
        }
        if (fcnt[k] != r.rate_cnt[k]) {
            same_cnt = false;
            if (std::abs(fcnt[k] - r.rate_cnt[k]) == 1 && near_boundary(r.cmd_cnt[k], band)) {
                ++st.cnt_pm1;
                st.pm1_dist = std::max(st.pm1_dist, std::fabs(f - 0.5));
            } else {
                ok = false;
            }
        }
    }
    // M_del: the moment of the counts commanded
    const ref::V3 mref = same_cnt ? r.mdel_nm : ref::cmg_mdel(t, rg, fcnt);
    for (std::size_t i = 0; i < 3u; ++i) {
        const double e = std::fabs(std::ldexp(o.mdel_q24[i], -24) - mref[i]);
        st.mdel = std::max(st.mdel, e);
        ok = ok && e <= kTolMdel;
    }
    if (!ok) {
        ++st.fails;
        if (g_prints < 10) {
            ++g_prints;
            std::printf("FAIL enc (%u %u %u %u) M_q24 (%d %d %d) st 0x%X flags fx %u ref %u ms fx %.9f ref %.9f\n"
                        "  rate fx (%.9f %.9f %.9f %.9f) ref (%.9f %.9f %.9f %.9f)\n"
                        "  cnt fx (%d %d %d %d) ref (%d %d %d %d) ref unrounded (%.4f %.4f %.4f %.4f)\n",
                        enc[0], enc[1], enc[2], enc[3], m_q24[0], m_q24[1], m_q24[2], fst, o.flags, r.flags,
                        std::ldexp(o.ms_q28, -28), r.ms, std::ldexp(o.rate_q28[0], -28),
                        std::ldexp(o.rate_q28[1], -28), std::ldexp(o.rate_q28[2], -28),
                        std::ldexp(o.rate_q28[3], -28), r.rate_radps[0], r.rate_radps[1], r.rate_radps[2],
                        r.rate_radps[3], o.rate_cnt[0], o.rate_cnt[1], o.rate_cnt[2], o.rate_cnt[3],
                        r.rate_cnt[0], r.rate_cnt[1], r.rate_cnt[2], r.rate_cnt[3], r.cmd_cnt[0], r.cmd_cnt[1],
                        r.cmd_cnt[2], r.cmd_cnt[3]);
        }
    }
    return ok;
}

std::array<std::int32_t, 3> moment_q24(const double dir[3], double mag_nm)
{
    const double n = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    std::array<std::int32_t, 3> m{};
    for (std::size_t i = 0; i < 3u; ++i) {
        m[i] = static_cast<std::int32_t>(std::llround(std::ldexp(mag_nm * dir[i] / n, 24)));
    }
    return m;
}

void unit_dir(std::mt19937_64 &rng, double d[3])
{
    std::normal_distribution<double> nd(0.0, 1.0);
    double s = 0.0;
    do {
        s = 0.0;
        for (int i = 0; i < 3; ++i) {
            d[i] = nd(rng);
            s += d[i] * d[i];
        }
    } while (s < 1e-12);
}

}  // namespace

SIM_TEST(random_cases_and_edges)
{
    std::mt19937_64 rng(20261206u);
    std::uniform_int_distribution<std::uint32_t> cnt(0u, 1048575u);
    std::uniform_real_distribution<double> u01(0.0, 1.0);
    Stats st;
    for (int c = 0; c < 10000; ++c) {
        const std::array<std::uint32_t, 4> enc{{cnt(rng), cnt(rng), cnt(rng), cnt(rng)}};
        double d[3];
        unit_dir(rng, d);
        (void)run_case(enc, moment_q24(d, kMmax * u01(rng)), st);
    }
    const std::uint64_t n_random = st.cases;
    // Edges: null (pi/4 = 131072 counts, -pi/4 = 917504), |H_z| = 30 (+-pi/2 = 262144 / 786432),
    // internal singularities, each with the max-rate commands.
    const std::array<std::array<std::uint32_t, 4>, 6> geoms{{
        {{131072u, 131072u, 917504u, 917504u}},
        {{262144u, 262144u, 262144u, 262144u}},
        {{786432u, 786432u, 786432u, 786432u}},
        {{0u, 0u, 0u, 0u}},
        {{0u, 0u, 524288u, 524288u}},
        {{262144u, 262144u, 0u, 0u}},
    }};
    const double dirs[8][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0},
                               {0, 0, 1}, {0, 0, -1}, {1, 1, 1}, {-1, 0.5, -0.25}};
    for (const auto &e : geoms) {
        for (const auto &d : dirs) {
            EXPECT_TRUE(run_case(e, moment_q24(d, kMmax), st));
        }
        const double zero[3] = {0.0, 0.0, 1.0};
        EXPECT_TRUE(run_case(e, moment_q24(zero, 0.0), st));
    }
    // max-rate commands at random geometries
    for (int c = 0; c < 200; ++c) {
        const std::array<std::uint32_t, 4> enc{{cnt(rng), cnt(rng), cnt(rng), cnt(rng)}};
        double d[3];
        unit_dir(rng, d);
        (void)run_case(enc, moment_q24(d, kMmax), st);
    }
    std::printf("golden_rsp_cmg: %llu cases compared (%llu random, %llu edge/max-rate), %llu failed\n"
                "  max |err|: beta_dot %.3e rad/s (tol %.0e, derived bound %.2e), M_del %.3e N m (tol %.3e),\n"
                "             m_s %.3e (tol %.0e, derived %.2e), H %.3e N m s, Ahat %.3e;\n"
                "  twin Cauchy-Binet vs det(A A^T): max |m_s^2 - det| %.2e\n"
                "  counts +-1 at a rounding boundary: %llu (twin command at most %.2e count from .5 there; closest approach\n"
                "  of any twin command to a .5 boundary: %.2e count);\n"
                "  RATE_LIMITED %llu (ambiguous %llu), SINGULAR %llu (ambiguous %llu)\n",
                static_cast<unsigned long long>(st.cases), static_cast<unsigned long long>(n_random),
                static_cast<unsigned long long>(st.cases - n_random), static_cast<unsigned long long>(st.fails),
                st.rate, kTolRate, kBoundRate, st.mdel, kTolMdel, st.ms, kTolMs, kBoundMs, st.h, st.a, st.cb_det,
                static_cast<unsigned long long>(st.cnt_pm1), st.pm1_dist, st.cnt_frac_margin,
                static_cast<unsigned long long>(st.limited), static_cast<unsigned long long>(st.amb_lim),
                static_cast<unsigned long long>(st.singular), static_cast<unsigned long long>(st.amb_sing));
    EXPECT_EQ_INT(st.fails, 0);
    EXPECT_TRUE(st.cases >= 10000u + 54u + 200u);
    EXPECT_TRUE(st.limited >= 100u);    // the rate scaling is exercised
    EXPECT_TRUE(st.singular >= 30u);    // and the singular geometries
    EXPECT_LE(st.rate, kBoundRate);     // the derivation, not only the spec's bound
}

int main()
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(random_cases_and_edges)};
    return cmocka_run_group_tests_name("rsp_cmg_golden", tests, nullptr, nullptr);
}
