// The RESPIN double reference (sim/respin/rsp_ref) and its closed loop with the rigid wheel plant
// (sim/respin/respin_plant): A1 (linearised stability of the LIN law), single ticks of the law's
// state machine (regions, hysteresis, a_f re-selection and latch, guard, distribution), and the
// reference closed loop of spec 30 §3.5 / §7 A2, A3, A5 against the spec's evidence.
//
// Groups (argv[1]): "unit" (default) = A1, the tick cases and the first 600 s of the nominal
// closed loop (invariants, determinism); "long" = the 12 000 s nominal NEAREST and PRINTED runs,
// noise-free and with the shipped scenarios' sensors (120 000 ticks each, ~1.1 s each in the Debug
// host build; CTest label golden).
//
// The reference closed loop flies the spec's configuration noise-free (spec 30 §3.5 evidence):
// g(0) = e_z, g0 = 300 N m s, H(0) = 0, the boot tables rsp_default / rsp_printed, through the
// sensors' counts (2^-22 rad/s, 2^-10 rad/s: quantisation only) and the int16 torque counts.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>

#include "respin/respin_plant.hpp"
#include "respin/respin_section.hpp"
#include "respin/rsp_ref.hpp"
extern "C" {
#include "rsp_tables.h"
}
#include "sim_test.hpp"

namespace {

sim::Scenario nominal_scenario(double duration_s)
{
    sim::Scenario s;
    sim::respin_section().defaults(s);
    s.name = "respin_ref_nominal";
    s.mission = "RESPIN";
    s.duration_s = duration_s;
    sim::RespinSetup &b = s.mission_part<sim::RespinScenario>().body;
    b.g0_nms = 300.0;
    b.g_dir = {{0.0, 0.0, 1.0}};
    return s;
}

// A shipped scenario (sim/respin/scenarios), read with the RESPIN section alone.
sim::Scenario shipped(const std::string &file)
{
    const std::string path = std::string(SCENARIO_DIR) + "/" + file;
    std::ifstream in(path);
    std::stringstream ss;
    ss << in.rdbuf();
    const sim::SectionLookup lookup = [](const std::string &m) -> const sim::MissionSection * {
        return m == "RESPIN" ? &sim::respin_section() : nullptr;
    };
    return sim::parse_scenario_with(ss.str(), path, lookup, {"RESPIN"});
}

double now_s()
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

void print_run(const char *what, const sim::RespinLoopRun &r, double wall_s)
{
    std::printf("%s: %llu ticks in %.2f s wall; g0_ref %.6f; first |xi|<0.01 at %.1f s, settled from %.1f s, "
                "DONE at %.1f s; end: |xi| %.3e C_phi %.6f a_f %+d region %u T %.5f J |omega - omega_f f| %.2e "
                "|H| %.2e; switches %u (last 2000 s: %u); max ||G|/g0-1| %.1e, max |H_i| %.6f, "
                "max |E_check - T| %.2e J, max |r_E| %.2e J, max |dG_I|/g0 %.1e, max |cmd| %.6f N m\n",
                what, static_cast<unsigned long long>(r.ticks), wall_s, r.g0_ref_nms, r.t_first_conv_s, r.t_settle_s,
                r.t_done_s, r.xi_end, r.cphi_end, r.a_f_end, r.region_end, r.t_end_j, r.omega_err_end_radps,
                r.h_end_nms, r.n_switch, r.n_switch_tail, r.max_g_rel_err, r.max_h_abs_nms, r.max_energy_err_j,
                r.max_abs_re_j, r.max_gi_dev_rel, r.max_torque_cmd_nm);
}

// A5 invariants, every run. |G| is re-projected after each RK4 step (rounding only: 1e-12 is
// 1000x the double's 2e-16 per operation over the run's worst case and still 1000x below the
// spec's 1e-9); |H_i| <= 5 + 1e-9 (the plant's hard limit); energy check <= 0.1 J (A5; the spec's
// batch maximum is 0.002 J). The inertial momentum G_I = R_IB G is constant: 1e-6 relative bounds
// the drift of the unit quaternion integrated by RK4 over 120 000 ticks (measured ~1e-9).
void expect_invariants(const sim::RespinLoopRun &r, double re_max_j = 0.01)
{
    EXPECT_TRUE(!r.diverged);
    EXPECT_LE(r.max_g_rel_err, 1e-12);
    EXPECT_LE(r.max_h_abs_nms, 5.0 + 1e-9);
    EXPECT_LE(r.max_energy_err_j, 0.1);
    EXPECT_LE(r.max_gi_dev_rel, 1e-6);
    // Commands within the motor limit up to the count's rounding (M_max = 0.15 N m rounds to
    // 19 661 counts = 0.1500015 N m): 1 LSB.
    EXPECT_LE(r.max_torque_cmd_nm, 0.15 + ref::kRspTorqueLsbNm);
    // Reference energy residual r_E = T - T0 - W (§8): trapezoid work on measured rates, O(Ts^2);
    // noise-free the spec's rigid nominal figure is <= 0.003 J (0.01 J leaves 3x). With the §2
    // gyro errors T itself is off by 2 x scale x T (100 ppm: 0.013 J at 67 J) plus J omega sigma
    // (0.003 J): those runs are held to the fsw's A2 bound, 0.5 J.
    EXPECT_LE(r.max_abs_re_j, re_max_j);
}

ref::RespinLawState started(std::uint32_t region, std::int32_t a_f, bool guard = false)
{
    ref::RespinLawState s;
    s.started = true;
    s.region = region;
    s.a_f = a_f;
    s.latched = region != RSP_RG_FAR;
    s.guard = guard;
    return s;
}

// g with |xi| = x (in the x-z plane along e_x) and g_y = sign * sqrt(1 - x^2).
ref::V3 g_at(double xi_abs, double sign_y)
{
    return {{xi_abs, sign_y * std::sqrt(1.0 - xi_abs * xi_abs), 0.0}};
}

}  // namespace

// ------------------------------------------------------------------------------------------------
// A1

SIM_TEST(a1_linearised_lin_law)
{
    const ref::RespinTable t = ref::dequantise(RSP_TBL_DEFAULT);
    // The spec's point: g0 = 300, m = 1.5, k = 0.07, D = I (the table's values, dequantised, are
    // within 2^-24 relative of these; the eigenvalues move by far less than the 1e-4 quoted digit).
    const ref::LinResult p = ref::linearise_lin(t.j_kgm2, 300.0, 1.5, 0.07, +1.0);
    const ref::LinResult f = ref::linearise_lin(t.j_kgm2, 300.0, 1.5, 0.07, -1.0);
    for (std::size_t i = 0; i < p.eig_re.size(); ++i) {
        std::printf("  law:     lambda_%zu = %+.6f %+.6fi\n", i, p.eig_re[i], p.eig_im[i]);
    }
    for (std::size_t i = 0; i < f.eig_re.size(); ++i) {
        std::printf("  flipped: lambda_%zu = %+.6f %+.6fi\n", i, f.eig_re[i], f.eig_im[i]);
    }
    std::printf("A1: slowest %.6f 1/s (spec -0.0077, accept [-0.0080, -0.0070]); xi sign flipped %.6f (spec +0.0079)\n",
                p.slowest_re, f.slowest_re);
    EXPECT_TRUE(p.eig_re.size() == 5u);
    // The acceptance window of A1 itself.
    EXPECT_TRUE(p.slowest_re >= -0.0080 && p.slowest_re <= -0.0070);
    // The spec quotes 2 significant digits: +-0.00005 is its rounding, +0.00005 margin for the
    // last digit of the source's own computation.
    EXPECT_NEAR(p.slowest_re, -0.0077, 1e-4);
    EXPECT_TRUE(f.slowest_re > 0.0);
    EXPECT_NEAR(f.slowest_re, 0.0079, 1e-4);
    // Row and column G_y of the 6x6 Jacobian are zero (the removed |G| direction).
    double gy = 0.0;
    for (std::size_t j = 0; j < 6u; ++j) {
        gy += std::fabs(p.a[6u + j]) + std::fabs(p.a[j * 6u + 1u]);
    }
    EXPECT_NEAR(gy, 0.0, 0.0);
    // Same with the exact table values (what the flight flies).
    const ref::LinResult q = ref::linearise_lin(t.j_kgm2, 300.0, t.m_nm, t.k_pnms, +1.0);
    EXPECT_NEAR(q.slowest_re, p.slowest_re, 1e-6);
}

// ------------------------------------------------------------------------------------------------
// Single ticks

SIM_TEST(law_first_tick_and_far_relay)
{
    const ref::RespinTable t = ref::dequantise(RSP_TBL_DEFAULT);
    const ref::V3 h0{{0.0, 0.0, 0.0}};
    // g = e_z: C_phi = 0, Sgn 0 = +1 decides a_f = +1 (spec 30 §9); FAR; M_i = -M* Sgn g_i = -M*.
    ref::RespinLawOut o = ref::rsp_law_tick(t, ref::RespinLawState(), {{0.0, 0.0, 1.0}}, h0);
    EXPECT_EQ_INT(o.next.region, RSP_RG_FAR);
    EXPECT_EQ_INT(o.next.a_f, 1);
    EXPECT_TRUE(!o.next.latched);
    EXPECT_NEAR(o.xi_abs, 1.0, 0.0);
    EXPECT_NEAR(o.cphi, 0.0, 0.0);
    for (std::size_t i = 0; i < 3u; ++i) {
        EXPECT_NEAR(o.mcmd_nm[i], -t.mstar_nm, 0.0);
        EXPECT_NEAR(o.mdel_nm[i], -t.mstar_nm, 0.0);
        EXPECT_NEAR(o.whl_torque_nm[i], t.mstar_nm, 0.0);
        EXPECT_TRUE(!o.clip[i] && !o.hbound[i]);
    }
    // NEAREST in FAR: g_y < 0 flips a_f; PRINTED keeps it.
    const ref::V3 gneg = g_at(0.8, -1.0);
    o = ref::rsp_law_tick(t, started(RSP_RG_FAR, 1), gneg, h0);
    EXPECT_EQ_INT(o.next.a_f, -1);
    EXPECT_TRUE(o.cphi > 0.0);
    ref::RespinTable tp = ref::dequantise(RSP_TBL_PRINTED);
    o = ref::rsp_law_tick(tp, started(RSP_RG_FAR, 1), gneg, h0);
    EXPECT_EQ_INT(o.next.a_f, 1);
    EXPECT_TRUE(o.cphi < 0.0);
    // First tick near -e_y: a_f = Sgn g_y = -1, plain thresholds (|xi| = 0.3: MID), latched.
    o = ref::rsp_law_tick(t, ref::RespinLawState(), g_at(0.3, -1.0), h0);
    EXPECT_EQ_INT(o.next.region, RSP_RG_MID);
    EXPECT_EQ_INT(o.next.a_f, -1);
    EXPECT_TRUE(o.next.latched);
    EXPECT_TRUE(!o.switched);
}

SIM_TEST(law_hysteresis)
{
    const ref::RespinTable t = ref::dequantise(RSP_TBL_DEFAULT);
    const ref::V3 h0{{0.0, 0.0, 0.0}};
    struct Case {
        std::uint32_t from;
        double xi;
        std::uint32_t to;
    };
    const double e1 = t.eps1, e2 = t.eps2, he = t.heps, d = 1e-9;
    const Case cases[] = {
        {RSP_RG_LIN, e1 + he - d, RSP_RG_LIN}, {RSP_RG_LIN, e1 + he + d, RSP_RG_MID},
        {RSP_RG_LIN, e2 + he + d, RSP_RG_FAR}, {RSP_RG_MID, e1 - he + d, RSP_RG_MID},
        {RSP_RG_MID, e1 - he - d, RSP_RG_LIN}, {RSP_RG_MID, e2 + he - d, RSP_RG_MID},
        {RSP_RG_MID, e2 + he + d, RSP_RG_FAR}, {RSP_RG_FAR, e2 - he + d, RSP_RG_FAR},
        {RSP_RG_FAR, e2 - he - d, RSP_RG_MID}, {RSP_RG_FAR, e1 - he - d, RSP_RG_LIN},
    };
    for (const Case &c : cases) {
        const ref::RespinLawOut o = ref::rsp_law_tick(t, started(c.from, 1), g_at(c.xi, 1.0), h0);
        if (o.next.region != c.to) {
            std::printf("  from %u at |xi| = %.10f: region %u, expected %u\n", c.from, c.xi, o.next.region, c.to);
        }
        EXPECT_EQ_INT(o.next.region, c.to);
        EXPECT_TRUE(o.switched == (c.from != c.to));
    }
    // Guard: no FAR; a_f re-selected while |xi| > eps2 (NEAREST), latched below.
    ref::RespinLawOut o = ref::rsp_law_tick(t, started(RSP_RG_MID, 1, true), g_at(0.9, -1.0), h0);
    EXPECT_EQ_INT(o.next.region, RSP_RG_MID);
    EXPECT_EQ_INT(o.next.a_f, -1);
    EXPECT_TRUE(!o.next.latched);
    o = ref::rsp_law_tick(t, started(RSP_RG_MID, 1, true), g_at(0.4, -1.0), h0);
    EXPECT_EQ_INT(o.next.a_f, 1);
    EXPECT_TRUE(o.next.latched);
    ref::RespinLawState first;
    first.guard = true;
    o = ref::rsp_law_tick(t, first, {{0.0, 0.0, 1.0}}, h0);
    EXPECT_EQ_INT(o.next.region, RSP_RG_MID);
}

SIM_TEST(law_lin_mid_and_distribution)
{
    const ref::RespinTable t = ref::dequantise(RSP_TBL_DEFAULT);
    // LIN: M = -m [xi - k H]; xi = a_f (-g_z, 0, g_x).
    const ref::V3 g{{0.01, std::sqrt(1.0 - 0.0001 - 0.0004), -0.02}};
    const ref::V3 h{{0.3, -0.2, 0.1}};
    ref::RespinLawOut o = ref::rsp_law_tick(t, started(RSP_RG_LIN, -1), g, h);
    const double xi[3] = {-(-1.0) * g[2], 0.0, -1.0 * g[0]};
    for (std::size_t i = 0; i < 3u; ++i) {
        EXPECT_NEAR(o.mcmd_nm[i], -t.m_nm * (xi[i] - t.k_pnms * h[i]), 1e-15);
        EXPECT_NEAR(o.e_xi[i], 0.0, 0.0);
    }
    EXPECT_TRUE(o.cphi < 0.0);   // near -f: LIN built on f (the PRINTED defect's situation)
    // MID: M = -m [e_xi Sgn C_phi - k H], e_xi = xi / |xi|; per-axis clip to M_max.
    const ref::V3 gm = g_at(0.3, 1.0);
    o = ref::rsp_law_tick(t, started(RSP_RG_MID, 1), gm, h);
    EXPECT_NEAR(o.e_xi[2], 1.0, 1e-15);
    EXPECT_NEAR(o.mcmd_nm[2], -t.m_nm * (1.0 - t.k_pnms * h[2]), 1e-15);
    EXPECT_TRUE(o.clip[2]);
    EXPECT_NEAR(o.mdel_nm[2], -t.mmax_nm, 0.0);
    EXPECT_NEAR(o.mdel_nm[0], -t.m_nm * (-t.k_pnms * h[0]), 1e-15);
    // Momentum-bound clamp (§4): at H = h_lim a moment that would raise H (M < 0) is cut to 0;
    // past it a moment back; at H = -h_lim + 0.005 at most (h_lim + H) / Ts = 0.005 / 0.1.
    std::array<bool, 3> clip{}, hb{};
    const ref::V3 m = ref::rsp_distribute(t, {{-0.1, 0.1, 0.1}}, {{t.hlim_nms, t.hlim_nms + 0.01, -t.hlim_nms + 0.005}},
                                          &clip, &hb);
    EXPECT_NEAR(m[0], 0.0, 1e-12);
    EXPECT_TRUE(hb[0]);
    EXPECT_NEAR(m[1], 0.1, 0.0);     // (H - h_lim)/Ts = 0.1 is the floor, 0.1 passes
    EXPECT_TRUE(!hb[1]);
    EXPECT_NEAR(m[2], 0.05, 1e-9);
    EXPECT_TRUE(hb[2]);
    const ref::V3 m2 = ref::rsp_distribute(t, {{-0.1, 0.0, 0.0}}, {{t.hlim_nms + 0.02, 0.0, 0.0}}, &clip, &hb);
    EXPECT_NEAR(m2[0], 0.2 > t.mmax_nm ? t.mmax_nm : 0.2, 1e-9);   // a moment back, clipped to M_max
}

SIM_TEST(module_g0_phase_and_invalid_gyro)
{
    const ref::RespinTable t = ref::dequantise(RSP_TBL_DEFAULT);
    ref::RespinRef r(t);
    ref::RespinRefIn in;
    // omega = 300 / 670 rad/s about z in counts (G = 300 e_z).
    in.gyro_cnt = {{0, 0, static_cast<std::int32_t>(std::lround(300.0 / 670.0 / ref::kRspGyroLsbRadps))}};
    ref::RespinRefOut o;
    for (std::uint32_t k = 0; k < t.n_g0; ++k) {
        o = r.step(in);
        EXPECT_NEAR(o.whl_torque_nm[2], 0.0, 0.0);   // zero command while g0 is averaged
    }
    EXPECT_EQ_INT(o.phase, RSP_PH_RUN);
    EXPECT_NEAR(r.g0_nms(), 670.0 * static_cast<double>(in.gyro_cnt[2]) * ref::kRspGyroLsbRadps, 1e-9);
    o = r.step(in);
    EXPECT_EQ_INT(o.region, RSP_RG_FAR);
    EXPECT_EQ_INT(o.a_f, 1);
    EXPECT_NEAR(o.whl_torque_nm[0], t.mstar_nm, 0.0);
    // A saturated gyro word: zero command, state kept.
    ref::RespinRefIn bad = in;
    bad.sat = 0x1u;
    o = r.step(bad);
    EXPECT_TRUE(!o.valid);
    EXPECT_NEAR(o.whl_torque_nm[0], 0.0, 0.0);
    EXPECT_EQ_INT(o.region, RSP_RG_FAR);
    // Low momentum: g0 < g_min commands zero for ever.
    ref::RespinRef low(t);
    ref::RespinRefIn lin;
    lin.gyro_cnt = {{0, 0, static_cast<std::int32_t>(std::lround(1.0 / 670.0 / ref::kRspGyroLsbRadps))}};
    for (int k = 0; k < 60; ++k) {
        o = low.step(lin);
    }
    EXPECT_EQ_INT(o.phase, RSP_PH_LOW);
    EXPECT_TRUE((o.health & RSP_H_LOW_MOMENTUM) != 0u);
    EXPECT_NEAR(o.whl_torque_nm[2], 0.0, 0.0);
}

// ------------------------------------------------------------------------------------------------
// Closed loop

SIM_TEST(closed_loop_first_600s)
{
    // The suite's reduced run: 600 s of the nominal case. The far relay (M = -M* (1, 1, 1) from
    // g = e_z) drains energy and drives the wheels into the momentum-bound clamp.
    const double t0 = now_s();
    const sim::RespinLoopRun r = sim::run_respin_reference(nominal_scenario(600.0), RSP_TBL_DEFAULT);
    print_run("nominal 600 s", r, now_s() - t0);
    expect_invariants(r);
    EXPECT_NEAR(r.g0_ref_nms, 300.0, 1e-4);   // quantisation of |Jw + H| only (2^-22 rad/s * 670 kg m^2)
    EXPECT_EQ_INT(r.region_end, RSP_RG_FAR);
    EXPECT_TRUE(r.t_end_j < 67.16);            // energy drained (T0 = 300^2 / (2 670) = 67.16 J)
    EXPECT_TRUE(r.max_h_abs_nms > 4.9 && r.max_h_abs_nms <= 4.98 + 1e-3);   // at the h_lim clamp
    // Determinism: a noisy run twice gives the same trajectory bit for bit.
    sim::Scenario s = nominal_scenario(600.0);
    sim::RespinSetup &b = s.mission_part<sim::RespinScenario>().body;
    b.gyro_noise_radps = 1e-5;
    b.gyro_bias_radps = {{3e-6, -4e-6, 5e-6}};
    b.gyro_scale_ppm = {{80.0, -60.0, 100.0}};
    b.gyro_seed = 7u;
    const sim::RespinLoopRun n1 = sim::run_respin_reference(s, RSP_TBL_DEFAULT);
    const sim::RespinLoopRun n2 = sim::run_respin_reference(s, RSP_TBL_DEFAULT);
    EXPECT_TRUE(std::memcmp(&n1.t_end_j, &n2.t_end_j, sizeof(double)) == 0);
    EXPECT_TRUE(std::memcmp(&n1.xi_end, &n2.xi_end, sizeof(double)) == 0);
    EXPECT_EQ_INT(n1.n_switch, n2.n_switch);
    expect_invariants(n1, 0.5);
}

// A2 noise-free (spec 30 §3.5 evidence): first |xi| < 0.01 at 6 592 s, stays from 6 750 s, ends at
// -e_y (a_f = -1), T_end = g0^2 / (2 J_y) = 12.50 J.
SIM_TEST(closed_loop_nominal_nearest_12000s)
{
    const double t0 = now_s();
    const sim::RespinLoopRun r = sim::run_respin_reference(nominal_scenario(12000.0), RSP_TBL_DEFAULT);
    print_run("nominal NEAREST 12000 s", r, now_s() - t0);
    expect_invariants(r);
    // Tolerances: the spec's evidence comes from RK4 at h = 0.1 s on unquantised values; this loop
    // integrates at 0.025 s through the counts, and the far relay turns such differences into tie
    // decisions (§6: "later only metrics are compared"). The far phase is ~5 800 s of a 0.15 N m
    // relay; +-2 % of the capture time (+-130 s) covers a few relay ties and stays far inside A2's
    // "converged by 8 000 s".
    EXPECT_TRUE(r.t_first_conv_s > 0.0);
    EXPECT_NEAR(r.t_first_conv_s, 6592.0, 130.0);
    EXPECT_NEAR(r.t_settle_s, 6750.0, 130.0);
    EXPECT_TRUE(r.t_settle_s > 0.0 && r.t_settle_s <= 8000.0);
    EXPECT_EQ_INT(r.a_f_end, -1);
    EXPECT_TRUE(r.cphi_end > 0.0);
    EXPECT_LE(r.xi_end, 0.01);
    // A2's end figures: T_end within 0.05 J of 12.50 J, |omega - omega_f f| < 1e-4 rad/s, |H| < 0.05.
    EXPECT_NEAR(r.t_end_j, 12.50, 0.05);
    EXPECT_LE(r.omega_err_end_radps, 1e-4);
    EXPECT_LE(r.h_end_nms, 0.05);
    EXPECT_TRUE(r.t_done_s > 0.0);
}

// A3 (spec 30 §7): PRINTED ends near -f, sliding along |xi| ~ eps1 (evidence at 12 000 s:
// C_phi = -0.994, |xi| = 0.113; |xi| cycling in 0.025-0.11), region switches still rising.
SIM_TEST(closed_loop_printed_12000s)
{
    const double t0 = now_s();
    const sim::RespinLoopRun r = sim::run_respin_reference(nominal_scenario(12000.0), RSP_TBL_PRINTED);
    print_run("PRINTED 12000 s", r, now_s() - t0);
    expect_invariants(r);
    EXPECT_LE(r.cphi_end, -0.99);
    EXPECT_TRUE(r.xi_end > 0.01 && r.xi_end < 0.15);
    EXPECT_TRUE(r.n_switch_tail > 0u);
    EXPECT_TRUE(r.t_settle_s < 0.0);
    EXPECT_EQ_INT(r.a_f_end, 1);
}

// A2 with the §2 sensors (the shipped respin_nominal.yaml: noise 1e-5 rad/s, bias <= 5e-6 rad/s,
// scale <= 100 ppm, quantisation). Spec evidence: converged 6 761 s, |omega - omega_f f| 7.7e-7,
// |H| 6.5e-4 at 12 000 s; the pass criteria of A2 are asserted as written.
SIM_TEST(closed_loop_nominal_noisy_a2)
{
    const sim::Scenario s = shipped("respin_nominal.yaml");
    const double t0 = now_s();
    const sim::RespinLoopRun r = sim::run_respin_reference(s, sim::respin_boot_table(s.fsw.table));
    print_run("A2 noisy (respin_nominal.yaml)", r, now_s() - t0);
    expect_invariants(r, 0.5);
    EXPECT_TRUE(r.t_settle_s > 0.0 && r.t_settle_s <= 8000.0);
    EXPECT_NEAR(r.t_settle_s, 6761.0, 130.0);    // the same 2 % as the noise-free case
    EXPECT_LE(r.omega_err_end_radps, 1e-4);
    EXPECT_LE(r.h_end_nms, 0.05);
    EXPECT_NEAR(r.t_end_j, 12.50, 0.05);
}

// A3 with the §2 sensors (the shipped respin_printed.yaml).
SIM_TEST(closed_loop_printed_noisy_a3)
{
    const sim::Scenario s = shipped("respin_printed.yaml");
    const double t0 = now_s();
    const sim::RespinLoopRun r = sim::run_respin_reference(s, sim::respin_boot_table(s.fsw.table));
    print_run("A3 noisy (respin_printed.yaml)", r, now_s() - t0);
    expect_invariants(r, 0.5);
    EXPECT_LE(r.cphi_end, -0.99);
    EXPECT_TRUE(r.xi_end > 0.01 && r.xi_end < 0.15);
    EXPECT_TRUE(r.n_switch_tail > 0u);
}

int main(int argc, char **argv)
{
    const std::string group = argc > 1 ? argv[1] : "unit";
    if (group == "long") {
        const struct CMUnitTest tests[] = {cmocka_unit_test(closed_loop_nominal_nearest_12000s),
                                           cmocka_unit_test(closed_loop_printed_12000s),
                                           cmocka_unit_test(closed_loop_nominal_noisy_a2),
                                           cmocka_unit_test(closed_loop_printed_noisy_a3)};
        return cmocka_run_group_tests_name("rsp_ref_long", tests, nullptr, nullptr);
    }
    const struct CMUnitTest tests[] = {cmocka_unit_test(a1_linearised_lin_law), cmocka_unit_test(law_first_tick_and_far_relay),
                                       cmocka_unit_test(law_hysteresis), cmocka_unit_test(law_lin_mid_and_distribution),
                                       cmocka_unit_test(module_g0_phase_and_invalid_gyro),
                                       cmocka_unit_test(closed_loop_first_600s)};
    return cmocka_run_group_tests_name("rsp_ref", tests, nullptr, nullptr);
}
