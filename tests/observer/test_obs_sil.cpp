// SIL acceptance of the observer (spec 10-observer §6, §7) with the fixed-point flight code:
// plant node (sim/) ⇄ LCM ⇄ bridge node (hil_host) ⇄ fsw_step (fsw/app + fsw/observer), the
// in-process lock-step driver of hil_host/sil. One executable, one CTest entry per group
// (argv[1]) so ctest -j runs the groups side by side. argv[2] is the LCM URL (default memq://;
// the udpm entries pass a private udpm URL each).
//
// Bounds are the spec's acceptance figures (expected values in comments). The one place where
// the shipped design does not reach a spec figure (the gyro-noise tails, fsw/observer/README.md
// "Open item") is checked against the double-precision reference FSW run on the same scenario
// (the same loop with sim/observer/obs_ref in place of the flight code): the fixed-point loop
// must be no noisier than the double loop by more than 25 %, and the gap to the spec is printed
// as OPEN. That check fails on a fixed-point regression; it cannot hide a design change because
// the reference shares the tables.
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>

#include "observer/obs_metrics.hpp"
#include "observer/observer_section.hpp"
#include "scenario/scenario.hpp"
#include "sil_run.hpp"
extern "C" {
#include "fsw_table.h"
#include "obs.h"
}
// last: cmocka.h defines macros (fail, ...) that clash with the standard library headers
#include "sim_test.hpp"

namespace {

const std::string kDir = SIL_SCENARIO_DIR;
const std::string kImg = SIL_IMAGE_DIR;
std::string g_url = "memq://";

sim::Scenario scn(const char *file)
{
    return sim::load_scenario(kDir + "/" + file);
}

// The scenario's DETUMBLE part (the sail, its sensors, the boot table overrides).
sim::SailScenario &sail(sim::Scenario &s) { return s.mission_part<sim::SailScenario>(); }

// The run's DETUMBLE metrics (hil_host/missions/observer/obs_metrics.hpp).
const host::ObsMetrics &obs(const sil::InprocResult &r) { return r.metrics<host::ObsMetrics>(); }

sil::InprocResult run(const sim::Scenario &s, const char *label, const std::string &fsw = "fixed",
                      const std::vector<sil::Upload> &up = {}, const std::string &log = std::string())
{
    sil::InprocOptions o;
    o.url = g_url;
    o.fsw = fsw;
    o.uploads = up;
    o.log_path = log;
    const sil::InprocResult r = sil::run_inproc(s, o);
    const host::ObsMetrics &m = obs(r);
    std::printf("%-36s %-4s t_s %7.2f  t_s+ %7.2f  K %.5f  bdot %.3f  mu %.4f  w %.3f  w_end %.2e  tail_w %.2e  "
                "tail_mu %.2e  missed %llu  %s\n",
                label, fsw == "fixed" ? "fx" : "ref", m.t_s, m.t_s_plus, m.k_hat_final, m.peak_bdot_degs,
                m.peak_mu_deg, m.peak_w_degs, m.w_final_degs, m.max_w_tail_degs, m.max_mu_tail_deg,
                static_cast<unsigned long long>(r.plant.missed), r.plant.reason.c_str());
    return r;
}

std::int64_t tlm(const sil::InprocResult &r, const char *k)
{
    const auto it = r.core.tlm.find(k);
    return it == r.core.tlm.end() ? -1 : it->second;
}

std::int64_t br(const sil::InprocResult &r, const char *k)
{
    return sil::frame_counter(r.core, k);
}

// Every nominal run: completed, lock-step clean (deterministic), no SAT outside the designated
// points (fx status bits 0..7 of the sticky health), never SAFE.
void expect_clean(const sil::InprocResult &r)
{
    EXPECT_TRUE(!r.plant.diverged);
    EXPECT_TRUE(r.plant.deterministic());
    EXPECT_EQ_INT(r.core.tlm_n, r.plant.steps);
    EXPECT_EQ_INT(tlm(r, "health_sticky") & 0xFF, 0);
    EXPECT_TRUE(r.core.t_first_fx_s < 0.0);
    EXPECT_EQ_INT(tlm(r, "n_safe"), 0);
    EXPECT_EQ_INT(tlm(r, "mode"), 2);
}

// The noise tail of spec 10 S0-5 / S0-7: the spec figure where met; otherwise no more than 25 %
// above the double reference loop on the same scenario and seed (see the header comment).
void expect_noise_tail(const sim::Scenario &s, const sil::InprocResult &fx, double spec, const char *label)
{
    if (obs(fx).max_w_tail_degs <= spec) {
        return;
    }
    const sil::InprocResult rf = run(s, label, "ref");
    std::printf("OPEN %s: max |w| over the last 20 s %.3e deg/s (spec <= %.1e); double reference %.3e\n", label,
                obs(fx).max_w_tail_degs, spec, obs(rf).max_w_tail_degs);
    EXPECT_LE(obs(fx).max_w_tail_degs, 1.25 * obs(rf).max_w_tail_degs);
}

// ---------------------------------------------------------------- S0-7 M-phys (600 s)
SIM_TEST(s07_nominal)
{
    const auto r = run(scn("s0-7_nominal_mphys.yaml"), "S0-7 nominal");
    expect_clean(r);
    EXPECT_LE(obs(r).t_s_plus, 150.0);                       // (135.8)
    EXPECT_LE(obs(r).peak_mu_deg, 7.0);                      // (6.0)
    EXPECT_LE(obs(r).peak_bdot_degs, 6.5);                   // (5.8)
    EXPECT_LE(obs(r).peak_w_degs, 6.5);                      // (5.75)
    EXPECT_NEAR(obs(r).k_hat_final, 0.01, 0.02 * 0.01);      // (0.01000)
    EXPECT_LE(obs(r).w_final_degs, 1e-4);
}

SIM_TEST(s07_khat0)
{
    for (double k0 : {0.005, 0.02}) {
        sim::Scenario s = scn("s0-7_nominal_mphys.yaml");
        sail(s).k_hat0 = k0;
        char lab[64];
        std::snprintf(lab, sizeof lab, "S0-7 K0=%.3f", k0);
        const auto r = run(s, lab);
        expect_clean(r);
        EXPECT_LE(obs(r).t_s_plus, 150.0);
        EXPECT_NEAR(obs(r).k_hat_final, 0.01, 0.02 * 0.01);
    }
}

SIM_TEST(s07_noise)
{
    for (std::uint64_t seed = 0; seed <= 2; ++seed) {
        sim::Scenario s = scn("s0-7_nominal_mphys.yaml");
        sail(s).gyro.noise_radps = 1e-5;
        sail(s).gyro.seed = seed;
        char lab[64];
        std::snprintf(lab, sizeof lab, "S0-7 noise seed %llu", static_cast<unsigned long long>(seed));
        const auto r = run(s, lab);
        expect_clean(r);
        EXPECT_LE(obs(r).t_s_plus, 150.0);                   // (134.1-136.7)
        EXPECT_NEAR(obs(r).k_hat_final, 0.01, 0.03 * 0.01);
        expect_noise_tail(s, r, 1e-3, lab);                     // (6.9e-4)
    }
}

SIM_TEST(s07_inertia)
{
    for (double jf : {0.98, 1.02}) {
        sim::Scenario s = scn("s0-7_nominal_mphys.yaml");
        sail(s).j_factor = jf;
        char lab[64];
        std::snprintf(lab, sizeof lab, "S0-7 Jx%.2f", jf);
        const auto r = run(s, lab);
        expect_clean(r);
        EXPECT_LE(obs(r).t_s, 270.0);                        // (191, 241)
        EXPECT_LE(obs(r).t_s_plus, 380.0);                   // (309-334, 270-276)
    }
    for (double jf : {0.95, 1.05}) {
        sim::Scenario s = scn("s0-7_nominal_mphys.yaml");
        sail(s).j_factor = jf;
        char lab[64];
        std::snprintf(lab, sizeof lab, "S0-7 Jx%.2f", jf);
        const auto r = run(s, lab);
        EXPECT_TRUE(!r.plant.diverged);
        EXPECT_TRUE(r.plant.deterministic());
        EXPECT_EQ_INT(tlm(r, "health_sticky") & 0xFF, 0);
        EXPECT_LE(obs(r).t_s, 400.0);                        // (354, 311)
        EXPECT_LE(obs(r).peak_mu_deg, 10.0);                 // (8.9)
        EXPECT_LE(obs(r).max_mu_tail_deg, 0.03);             // (0.016, 0.0035)
    }
}

SIM_TEST(s07_authority)
{
    const double lim[2] = {2.0, 4.0};
    const double ts_max[2] = {240.0, 160.0};                    // (205.0, 140.2)
    for (int i = 0; i < 2; ++i) {
        sim::Scenario s = scn("s0-7_nominal_mphys.yaml");
        sail(s).bdot_max_degps = lim[i];
        char lab[64];
        std::snprintf(lab, sizeof lab, "S0-7 bdot_max %.0f deg/s", lim[i]);
        const auto r = run(s, lab);
        expect_clean(r);
        EXPECT_LE(obs(r).t_s_plus, ts_max[i]);
        // vector limit holds: the limit converts to a whole number of counts (one count of slack)
        EXPECT_LE(obs(r).peak_bdot_degs, lim[i] + 1e-3);
        EXPECT_TRUE(tlm(r, "obs_n_limited") > 0);               // the limit engaged and was counted
    }
}

// ---------------------------------------------------------------- S0-5 M-paper (120 s)
SIM_TEST(s05_nominal)
{
    const auto r = run(scn("s0-5_nominal_mpaper.yaml"), "S0-5 nominal");
    expect_clean(r);
    EXPECT_LE(obs(r).t_s, 25.0);                             // (20.2)
    EXPECT_NEAR(obs(r).k_hat_final, 0.01, 0.02 * 0.01);      // (0.00999)
    EXPECT_LE(obs(r).peak_bdot_degs, 1.5);                   // (1.34)
    EXPECT_LE(obs(r).peak_mu_deg, 0.3);                      // (0.19)
    EXPECT_LE(obs(r).w_final_degs, 1e-4);                    // (3e-5)
}

SIM_TEST(s05_khat0)
{
    for (double k0 : {0.005, 0.02}) {
        sim::Scenario s = scn("s0-5_nominal_mpaper.yaml");
        sail(s).k_hat0 = k0;
        char lab[64];
        std::snprintf(lab, sizeof lab, "S0-5 K0=%.3f", k0);
        const auto r = run(s, lab);
        expect_clean(r);
        EXPECT_LE(obs(r).t_s, 25.0);                         // (20.6, 20.2)
        EXPECT_NEAR(obs(r).k_hat_final, 0.01, 0.10 * 0.01);  // (0.00925, 0.00979)
    }
}

SIM_TEST(s05_noise)
{
    for (std::uint64_t seed = 0; seed <= 2; ++seed) {
        sim::Scenario s = scn("s0-5_noise_seed0_mpaper.yaml");
        sail(s).gyro.seed = seed;
        char lab[64];
        std::snprintf(lab, sizeof lab, "S0-5 noise seed %llu", static_cast<unsigned long long>(seed));
        const auto r = run(s, lab);
        expect_clean(r);
        EXPECT_LE(obs(r).t_s, 25.0);                         // (19.7-20.6)
        EXPECT_NEAR(obs(r).k_hat_final, 0.01, 0.08 * 0.01);  // (worst +5.1 %)
        expect_noise_tail(s, r, 3e-4, lab);                     // (1.8e-4)
    }
}

SIM_TEST(s05_inertia)
{
    for (double jf : {0.95, 0.98, 1.02, 1.05}) {
        sim::Scenario s = scn("s0-5_nominal_mpaper.yaml");
        sail(s).j_factor = jf;
        s.duration_s = 200.0;
        char lab[64];
        std::snprintf(lab, sizeof lab, "S0-5 Jx%.2f 200 s", jf);
        const auto r = run(s, lab);
        EXPECT_TRUE(!r.plant.diverged);
        EXPECT_TRUE(r.plant.deterministic());
        EXPECT_EQ_INT(tlm(r, "health_sticky") & 0xFF, 0);
        EXPECT_LE(obs(r).t_s, 30.0);                         // (17.5-21.3)
        EXPECT_LE(obs(r).w_final_degs, 2e-4);
        if (jf > 1.04) {
            EXPECT_TRUE(tlm(r, "obs_n_clamp_hi") > 0);          // upper clamp engages and is counted
        }
    }
}

// ---------------------------------------------------------------- S0-8 fixed point vs double
// Same scenario through the same bridge and nodes, once with the flight code and once with the
// double reference of the step on the dequantised tables: agreement within 1 % or 2 samples on
// t_s and t_s+, 0.5 % on the final K-hat, 1 % on the peaks (spec 10 S0-8).
SIM_TEST(s08_fixed_vs_double)
{
    struct Case { const char *file; std::uint64_t seed; double noise; const char *label; };
    for (const Case c : {Case{"s0-5_nominal_mpaper.yaml", 0, 0.0, "S0-8 S0-5 nominal"},
                         Case{"s0-5_noise_seed0_mpaper.yaml", 0, 1e-5, "S0-8 S0-5 noise seed 0"},
                         Case{"s0-7_nominal_mphys.yaml", 0, 0.0, "S0-8 S0-7 nominal"}}) {
        sim::Scenario s = scn(c.file);
        sail(s).gyro.seed = c.seed;
        sail(s).gyro.noise_radps = c.noise;
        const auto fx = run(s, c.label, "fixed");
        const auto db = run(s, c.label, "ref");
        const double h = s.h_s();
        auto close_t = [h](double a, double b) { return std::fabs(a - b) <= std::max(0.01 * b, 2.0 * h + 1e-9); };
        EXPECT_TRUE(close_t(obs(fx).t_s, obs(db).t_s));
        EXPECT_TRUE(close_t(obs(fx).t_s_plus, obs(db).t_s_plus));
        EXPECT_NEAR(obs(fx).k_hat_final, obs(db).k_hat_final, 0.005 * obs(db).k_hat_final);
        EXPECT_NEAR(obs(fx).peak_bdot_degs, obs(db).peak_bdot_degs, 0.01 * obs(db).peak_bdot_degs);
        EXPECT_NEAR(obs(fx).peak_mu_deg, obs(db).peak_mu_deg, 0.01 * obs(db).peak_mu_deg);
        EXPECT_NEAR(obs(fx).peak_w_degs, obs(db).peak_w_degs, 0.01 * obs(db).peak_w_degs);
    }
}

// ---------------------------------------------------------------- the design range (issue 17)
// The detumble from initial rates across the design range, fixed point against the double loop
// by S0-8's tolerances, with no fx status bit: M-phys 1-4 deg/s on both axes (4 deg/s takes the sail
// to 29.8 deg, the model's 30 deg validity limit; 4.5 deg/s leaves it) and opposite signs; M-paper
// up to 5 deg/s. M-phys raised SAT bits from 2 deg/s until the regressor column of F_s was held in
// int64 (fsw/observer/README.md "Formats and ranges").
SIM_TEST(range_rate_sweep)
{
    struct Case { const char *file; double wy, wz; double dur_s; };
    for (const Case c : {Case{"s0-7_nominal_mphys.yaml", 1.0, 1.0, 250.0}, Case{"s0-7_nominal_mphys.yaml", 2.0, 2.0, 250.0},
                         Case{"s0-7_nominal_mphys.yaml", 3.0, 3.0, 250.0}, Case{"s0-7_nominal_mphys.yaml", 4.0, 4.0, 250.0},
                         Case{"s0-7_nominal_mphys.yaml", 3.0, -3.0, 250.0}, Case{"s0-7_nominal_mphys.yaml", -4.0, 4.0, 250.0},
                         Case{"s0-5_nominal_mpaper.yaml", 3.0, 3.0, 60.0}, Case{"s0-5_nominal_mpaper.yaml", 5.0, 5.0, 60.0},
                         Case{"s0-5_nominal_mpaper.yaml", 5.0, -5.0, 60.0}}) {
        sim::Scenario s = scn(c.file);
        constexpr double kDegToRad = 3.14159265358979323846 / 180.0;
        sail(s).w0_radps = {c.wy * kDegToRad, c.wz * kDegToRad};
        s.duration_s = c.dur_s;
        char label[80];
        std::snprintf(label, sizeof label, "range %s w0 (%.0f, %.0f) deg/s", c.file, c.wy, c.wz);
        const auto fx = run(s, label, "fixed");
        const auto db = run(s, label, "ref");
        expect_clean(fx);
        EXPECT_TRUE(obs(fx).t_s_plus > 0.0);                     // settled within the run
        const double h = s.h_s();
        auto close_t = [h](double a, double b) { return std::fabs(a - b) <= std::max(0.01 * b, 2.0 * h + 1e-9); };
        EXPECT_TRUE(close_t(obs(fx).t_s, obs(db).t_s));
        EXPECT_TRUE(close_t(obs(fx).t_s_plus, obs(db).t_s_plus));
        EXPECT_NEAR(obs(fx).k_hat_final, obs(db).k_hat_final, 0.005 * obs(db).k_hat_final);
        EXPECT_NEAR(obs(fx).peak_mu_deg, obs(db).peak_mu_deg, 0.01 * obs(db).peak_mu_deg);
        EXPECT_NEAR(obs(fx).peak_w_degs, obs(db).peak_w_degs, 0.01 * obs(db).peak_w_degs);
    }
}

// ---------------------------------------------------------------- S0-3, S0-4, S0-9
SIM_TEST(s03_paper_printed_diverges)
{
    sim::Scenario s = scn("s0-5_nominal_mpaper.yaml");
    s.fsw.table = "obs_paper_printed";
    s.period_us = 200000u;
    s.duration_s = 30.0;
    const auto r = run(s, "S0-3 paper printed (5 Hz)");
    EXPECT_TRUE(r.plant.diverged);
    EXPECT_LE(r.plant.t_end_s, 2.0 + 1e-9);                    // DIVERGED within 2 s (1.0)
    EXPECT_TRUE((obs(r).obs_health_sticky & OBS_H_CMD_LIMITED) != 0u);
    // The printed design runs the estimate through the Euler model (g h ~ 10 per step), so x-hat
    // leaves its q29 range at step 2 and saturates: reported in the fx bits, never wrapped
    // (fsw/observer/README.md). UB is excluded by the asan-ubsan run of this test.
    EXPECT_EQ_INT(r.core.tlm_n, r.plant.steps);
}

SIM_TEST(s04_5hz)
{
    sim::Scenario s = scn("s0-5_nominal_mpaper.yaml");
    s.fsw.table = "obs_5hz_paper";
    s.period_us = 200000u;
    const auto r = run(s, "S0-4 5 Hz");
    expect_clean(r);
    EXPECT_LE(obs(r).t_s, 25.0);                             // (20.4)
    EXPECT_NEAR(obs(r).k_hat_final, 0.01, 0.02 * 0.01);      // (0.01003)
    EXPECT_LE(obs(r).peak_bdot_degs, 1.5);                   // (1.29)
    EXPECT_LE(obs(r).peak_mu_deg, 0.3);                      // (0.22)
    EXPECT_LE(obs(r).w_final_degs, 1e-4);
}

SIM_TEST(s09_authority_1p2_vector_settles_per_axis_diverges)
{
    sim::Scenario s = scn("s0-5_nominal_mpaper.yaml");
    sail(s).bdot_max_degps = 1.2;
    const auto r = run(s, "S0-9 M-paper bdot_max 1.2 vector");
    expect_clean(r);
    EXPECT_LE(obs(r).t_s, 30.0);                             // (22.2)
    EXPECT_TRUE(tlm(r, "obs_n_limited") > 0);
    // The same loop clipping each axis at the same limit (analysis backend; the flight code
    // cannot: tests/observer/test_obs.c command_is_limited_as_a_vector) leaves the envelope.
    const auto p = run(s, "S0-9 M-paper bdot_max 1.2 per axis", "ref-per-axis");
    EXPECT_TRUE(p.plant.diverged);
}

SIM_TEST(s09_authority_1p0_diverges)
{
    sim::Scenario s = scn("s0-5_nominal_mpaper.yaml");
    sail(s).bdot_max_degps = 1.0;
    const auto r = run(s, "S0-9 M-paper bdot_max 1.0");
    EXPECT_TRUE(obs(r).t_persist_s >= 0.0);
    EXPECT_LE(obs(r).t_persist_s, 1.0);                      // CMD_LIMIT_PERSIST within 1 s (1.0)
    EXPECT_TRUE(r.plant.diverged);
    EXPECT_LE(r.plant.t_end_s, 30.0);                           // (26.8)
    // No fx bit up to the divergence: the regressor column of F_s saturated here from 11.86 s
    // until it was held in int64 (fsw/observer/README.md "Formats and ranges").
    EXPECT_TRUE(r.core.t_first_fx_s < 0.0);
    EXPECT_EQ_INT(tlm(r, "n_safe"), 0);   // CMD_LIMIT_PERSIST is reported, not a SAFE trigger
    EXPECT_EQ_INT(r.core.tlm_n, r.plant.steps);              // it kept commanding to the end
}

SIM_TEST(s09_frame_loss_5pct)
{
    // 5 % of the sensor frames lost, never re-sent: the plant holds the last command, the flight
    // code sees a sequence gap and predicts across it (spec 10 §4.4 step 1).
    struct Case { const char *file; bool phys; };
    for (const Case c : {Case{"s0-5_nominal_mpaper.yaml", false}, Case{"s0-7_nominal_mphys.yaml", true}}) {
        sim::Scenario s = scn(c.file);
        s.faults.drop_ppm = 50000u;
        s.faults.seed = 7u;
        s.lockstep.retx_max = 0u;
        const auto r = run(s, c.phys ? "S0-9 5% loss M-phys" : "S0-9 5% loss M-paper");
        EXPECT_TRUE(!r.plant.diverged);
        EXPECT_EQ_INT(tlm(r, "health_sticky") & 0xFF, 0);
        if (c.phys) {
            EXPECT_LE(obs(r).t_s_plus, 150.0);               // (133)
        } else {
            EXPECT_LE(obs(r).t_s, 30.0);                     // (22.1-22.3)
        }
        // every lost frame is counted on both sides and in the flight telemetry
        const auto dropped = static_cast<std::int64_t>(r.plant.faults.dropped);
        EXPECT_TRUE(dropped > 0);
        EXPECT_EQ_INT(static_cast<std::int64_t>(r.plant.missed), dropped);
        // A drop shows up at the bridge as the gap before the next delivered frame, so a drop of
        // the very last frame (no next frame) is the only one that cannot be seen there: allow 1.
        EXPECT_TRUE(r.bridge.gap_frames == dropped || r.bridge.gap_frames == dropped - 1);
        EXPECT_TRUE(tlm(r, "host_missed") == dropped || tlm(r, "host_missed") == dropped - 1);
        EXPECT_TRUE(br(r, "missed") == dropped || br(r, "missed") == dropped - 1);
        EXPECT_EQ_INT(tlm(r, "obs_n_gap"), r.bridge.gap_frames);
        EXPECT_EQ_INT(tlm(r, "n_safe"), 0);
    }
}

// ---------------------------------------------------------------- faults and bad input (§7, 00 §8)
sim::Scenario fault_scn(std::uint64_t seed)
{
    sim::Scenario s = scn("s0-5_nominal_mpaper.yaml");
    s.faults.seed = seed;
    return s;
}

// A run with faults still settles like the nominal one (t_s <= 25 s) and never goes SAFE.
void expect_converged(const sil::InprocResult &r)
{
    EXPECT_TRUE(!r.plant.diverged);
    EXPECT_LE(obs(r).t_s, 25.0);
    EXPECT_NEAR(obs(r).k_hat_final, 0.01, 0.02 * 0.01);
    EXPECT_EQ_INT(tlm(r, "n_safe"), 0);
    EXPECT_EQ_INT(tlm(r, "health_sticky") & 0xFF, 0);
}

SIM_TEST(fault_duplicated_frames)
{
    sim::Scenario s = fault_scn(5);
    s.faults.dup_ppm = 20000u;
    const auto r = run(s, "fault: 2 % duplicated frames");
    expect_converged(r);
    const auto dup = static_cast<std::int64_t>(r.plant.faults.duplicated);
    EXPECT_TRUE(dup > 0);
    EXPECT_EQ_INT(r.bridge.dups, dup);                          // answered from the cache ...
    EXPECT_EQ_INT(r.bridge.stepped, r.plant.steps);             // ... never stepped twice
    EXPECT_EQ_INT(static_cast<std::int64_t>(r.plant.dup_cmds), dup);   // the plant ignores the 2nd
    EXPECT_TRUE(r.plant.deterministic());
    EXPECT_EQ_INT(tlm(r, "obs_n_gap"), 0);
}

SIM_TEST(fault_reordered_frames)
{
    sim::Scenario s = fault_scn(5);
    s.faults.reorder_ppm = 10000u;
    const auto r = run(s, "fault: 1 % reordered frames");
    expect_converged(r);
    const auto re = static_cast<std::int64_t>(r.plant.faults.reordered);
    EXPECT_TRUE(re > 0);
    // A held-back frame k is re-published (retx) and answered; its late original arrives after
    // frame k: the bridge answers it from the cache (seq == last) or drops it (seq < last).
    EXPECT_EQ_INT(static_cast<std::int64_t>(r.plant.retx), re);
    EXPECT_EQ_INT(r.bridge.dups + r.bridge.stale, re);
    EXPECT_EQ_INT(static_cast<std::int64_t>(r.plant.missed), 0);
    EXPECT_EQ_INT(r.bridge.stepped, r.plant.steps);
}

SIM_TEST(fault_truncated_and_bitflipped_frames)
{
    sim::Scenario s = fault_scn(5);
    s.faults.truncate_ppm = 10000u;
    const auto t = run(s, "fault: 1 % truncated frames");
    expect_converged(t);
    const auto tr = static_cast<std::int64_t>(t.plant.faults.truncated);
    EXPECT_TRUE(tr > 0);
    EXPECT_EQ_INT(t.bridge.malformed, tr);                      // undecodable: refused whole
    EXPECT_EQ_INT(static_cast<std::int64_t>(t.plant.retx), tr); // and re-sent by the plant
    EXPECT_EQ_INT(tlm(t, "host_rejected"), tr);                 // reported in flight telemetry
    EXPECT_EQ_INT(t.bridge.stepped, t.plant.steps);

    // Every flipped frame fails its crc32 (or, flipped in the fingerprint, does not decode): it is
    // refused before any field is used and re-sent, so the flight code flies exactly the clean
    // run's commands (issue 18: before the CRC, one flip in seq locked the loop out for 10 s).
    const auto clean = run(fault_scn(5), "fault: clean reference");
    s = fault_scn(5);
    s.faults.bitflip_ppm = 10000u;
    const auto b = run(s, "fault: 1 % bit-flipped frames");
    const auto fl = static_cast<std::int64_t>(b.plant.faults.bitflipped);
    EXPECT_TRUE(fl > 0);
    EXPECT_EQ_INT(b.bridge.crc_rej + b.bridge.malformed, fl);
    EXPECT_EQ_INT(static_cast<std::int64_t>(b.plant.retx), fl);
    EXPECT_EQ_INT(b.bridge.range_rej + b.bridge.time_rej + b.bridge.jump_rej, 0);
    EXPECT_EQ_INT(static_cast<std::int64_t>(b.plant.missed), 0);
    EXPECT_TRUE(b.core.digest_cmd == clean.core.digest_cmd);
    EXPECT_EQ_INT(static_cast<std::int64_t>(b.core.cmd_n), static_cast<std::int64_t>(clean.core.cmd_n));
    EXPECT_NEAR(obs(b).t_s, obs(clean).t_s, 0.0);                  // bit-identical flight
    EXPECT_NEAR(obs(b).k_hat_final, obs(clean).k_hat_final, 0.0);
    EXPECT_EQ_INT(tlm(b, "n_safe"), 0);
}

SIM_TEST(fault_nan_and_out_of_range_gyro)
{
    // 1 s of NaN gyro truth (the plant's conversion marks the channel STALE, count 0) and 1 s of
    // an INT32_MAX count (beyond the sensor table: the bridge's range check marks it stale).
    sim::Scenario s = fault_scn(5);
    s.faults.nan_s = {{30.0, 31.0}};
    s.faults.spike_s = {{40.0, 41.0}};
    const auto r = run(s, "fault: NaN 30-31 s, spike 40-41 s");
    expect_converged(r);
    EXPECT_EQ_INT(static_cast<std::int64_t>(r.plant.nan_frames), 50);
    EXPECT_EQ_INT(static_cast<std::int64_t>(r.plant.spike_frames), 50);
    EXPECT_EQ_INT(r.bridge.range_rej, 50);                      // the spike, never passed as a count
    EXPECT_EQ_INT(tlm(r, "n_chan_rej"), 100);                   // both windows, one axis each
    EXPECT_EQ_INT(tlm(r, "obs_n_skip"), 100);                   // the axis skipped its update
    EXPECT_TRUE((tlm(r, "obs_health_sticky") & OBS_H_MEAS_SKIP) != 0);
    EXPECT_EQ_INT(tlm(r, "obs_n_lost"), 0);                     // the other axis kept it alive
    EXPECT_TRUE(r.plant.deterministic());
}

// A wild but in-range sample from the gyro itself: bit 19 of counts[0] flipped (0.5 rad/s, inside
// the range check) at 74.8 s on S0-5. Before the innovation gate it drove K-hat from 0.0098 to its
// 0.02 clamp and t_s to 120 s; now it is rejected and counted once, and the run settles as the
// unfaulted one: t_s within 10 %, K-hat within 2 % (both measured identical to 1e-4).
// Then the same glitch at pseudo-random times and channels (a reduced set of the README's 24).
double glitch_time(std::uint64_t seed)
{
    std::uint64_t z = seed * 0x9E3779B97F4A7C15ull + 0x632BE59BD9B4E019ull;   // splitmix64 step
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return 0.02 * static_cast<double>(1u + (z % 5998u));   // a sample time in (0, 120) s
}

void expect_like_unfaulted(const sil::InprocResult &r, const sil::InprocResult &base)
{
    EXPECT_TRUE(!r.plant.diverged);
    EXPECT_NEAR(obs(r).t_s, obs(base).t_s, 0.10 * obs(base).t_s);
    EXPECT_NEAR(obs(r).k_hat_final, obs(base).k_hat_final, 0.02 * obs(base).k_hat_final);
    EXPECT_EQ_INT(tlm(r, "obs_n_innov"), 1);                     // one rejection, counted
    EXPECT_EQ_INT(tlm(r, "n_safe"), 0);
    EXPECT_EQ_INT(tlm(r, "health_sticky") & 0xFF, 0);
    EXPECT_TRUE((obs(r).obs_health_sticky & (OBS_H_INNOV_PERSIST | OBS_H_ADAPT_FROZEN)) == 0u);
}

SIM_TEST(fault_gyro_glitch_bit19)
{
    const sim::Scenario s0 = scn("s0-5_nominal_mpaper.yaml");
    const auto base = run(s0, "glitch: none");
    sim::Scenario s = s0;
    sail(s).gyro.glitch_s = 74.8;
    sail(s).gyro.glitch_channel = 0u;
    sail(s).gyro.glitch_bit = 19u;
    const auto r = run(s, "glitch: bit 19 of y at 74.8 s");
    expect_like_unfaulted(r, base);
    for (std::uint64_t seed = 1; seed <= 4; ++seed) {
        sail(s).gyro.glitch_s = glitch_time(seed);
        sail(s).gyro.glitch_channel = static_cast<std::uint32_t>(seed & 1u);
        char lab[64];
        std::snprintf(lab, sizeof lab, "glitch: bit 19 ch %u at %.2f s", sail(s).gyro.glitch_channel, sail(s).gyro.glitch_s);
        expect_like_unfaulted(run(s, lab), base);
    }
}

std::vector<std::uint8_t> image(const char *name)
{
    std::ifstream f(kImg + "/" + name, std::ios::binary);
    EXPECT_TRUE(static_cast<bool>(f));
    return std::vector<std::uint8_t>((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

SIM_TEST(fault_corrupt_table_uploads)
{
    // Uploads during S0-7: a CRC-corrupted image at 20 s, an out-of-range one (bdot_max above the
    // hardware limit) at 30 s, then a valid revision 2 at 40 s. Images from the design tool's
    // independent writer (tools/observer image). Both bad ones are refused with their reason,
    // the old table stays active, the good one is committed at a step boundary, and the loop
    // settles exactly as without uploads (same tables).
    const sim::Scenario s = scn("s0-7_nominal_mphys.yaml");
    struct Bad { const char *file; std::uint32_t reason; double t; std::int32_t rev; };
    for (const Bad b : {Bad{"obs_phys_bad_crc.bin", FSW_TBL_R_CRC, 20.0, 3},
                        Bad{"obs_phys_bdot_over_hw.bin", FSW_TBL_R_INVARIANT, 30.0, 4}}) {
        const auto r = run(s, b.file, "fixed", {sil::Upload{b.t, image(b.file), b.file}});
        expect_clean(r);
        EXPECT_EQ_INT(r.bridge.table_rej, 1);
        EXPECT_EQ_INT(tlm(r, "n_tbl_rej"), 1);
        EXPECT_EQ_INT(tlm(r, "tbl_reason") & 0xFF, b.reason);
        EXPECT_EQ_INT(r.core.last_ack_result, 2);            // RESULT_REJECTED
        EXPECT_EQ_INT(tlm(r, "tbl_revision"), 1);               // the boot table stays
        EXPECT_TRUE((tlm(r, "health_sticky") & 0x4000) != 0);   // FSW_H_TBL_REJ was reported
        EXPECT_LE(obs(r).t_s_plus, 150.0);
    }
    const auto base = run(s, "uploads: none");
    const auto r = run(s, "uploads: bad CRC, bad range, good rev 2", "fixed",
                       {sil::Upload{20.0, image("obs_phys_bad_crc.bin"), "obs_phys_bad_crc.bin"},
                        sil::Upload{30.0, image("obs_phys_bdot_over_hw.bin"), "obs_phys_bdot_over_hw.bin"},
                        sil::Upload{40.0, image("obs_phys_rev2.bin"), "obs_phys_rev2.bin"}});
    expect_clean(r);
    EXPECT_EQ_INT(tlm(r, "n_tbl_rej"), 2);
    EXPECT_EQ_INT(tlm(r, "n_tbl_acc"), 1);
    EXPECT_EQ_INT(tlm(r, "tbl_revision"), 2);
    EXPECT_EQ_INT(tlm(r, "obs_revision"), 2);
    EXPECT_EQ_INT(r.core.last_ack_result, 0);                // RESULT_ACCEPTED
    EXPECT_NEAR(obs(r).t_s_plus, obs(base).t_s_plus, 1e-9);   // same content: same loop
    EXPECT_NEAR(obs(r).k_hat_final, obs(base).k_hat_final, 1e-12);
}

// ---------------------------------------------------------------- determinism
std::vector<std::uint8_t> slurp(const std::string &p)
{
    std::ifstream f(p, std::ios::binary);
    return std::vector<std::uint8_t>((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

SIM_TEST(determinism_same_scenario_twice)
{
    // memq logs carry simulation-time timestamps, so two runs must give identical files.
    const sim::Scenario s = scn("s0-5_noise_seed0_mpaper.yaml");
    const std::string a = std::string(SIL_OUT_DIR) + "/det_a.lcmlog", b = std::string(SIL_OUT_DIR) + "/det_b.lcmlog";
    const auto ra = run(s, "determinism run 1", "fixed", {}, a);
    const auto rb = run(s, "determinism run 2", "fixed", {}, b);
    const auto la = slurp(a), lb = slurp(b);
    EXPECT_TRUE(la.size() > 1000000u);
    EXPECT_TRUE(la == lb);
    EXPECT_EQ_INT(static_cast<std::int64_t>(ra.log_events), static_cast<std::int64_t>(rb.log_events));
}

}  // namespace

int main(int argc, char **argv)
{
    const std::string g = (argc > 1) ? argv[1] : "all";
    if (argc > 2) {
        g_url = argv[2];
    }
    const CMUnitTest s07[] = {cmocka_unit_test(s07_nominal), cmocka_unit_test(s07_khat0),
                              cmocka_unit_test(s07_noise)};
    const CMUnitTest s07b[] = {cmocka_unit_test(s07_inertia), cmocka_unit_test(s07_authority)};
    const CMUnitTest s05[] = {cmocka_unit_test(s05_nominal), cmocka_unit_test(s05_khat0),
                              cmocka_unit_test(s05_noise), cmocka_unit_test(s05_inertia)};
    const CMUnitTest s08[] = {cmocka_unit_test(s08_fixed_vs_double)};
    const CMUnitTest range[] = {cmocka_unit_test(range_rate_sweep)};
    const CMUnitTest other[] = {cmocka_unit_test(s03_paper_printed_diverges), cmocka_unit_test(s04_5hz),
                                cmocka_unit_test(s09_authority_1p2_vector_settles_per_axis_diverges),
                                cmocka_unit_test(s09_authority_1p0_diverges), cmocka_unit_test(s09_frame_loss_5pct)};
    const CMUnitTest faults[] = {cmocka_unit_test(fault_duplicated_frames), cmocka_unit_test(fault_reordered_frames),
                                 cmocka_unit_test(fault_truncated_and_bitflipped_frames),
                                 cmocka_unit_test(fault_nan_and_out_of_range_gyro),
                                 cmocka_unit_test(fault_gyro_glitch_bit19),
                                 cmocka_unit_test(fault_corrupt_table_uploads),
                                 cmocka_unit_test(determinism_same_scenario_twice)};
    // The udpm entry: the nominal acceptance cases over a real multicast socket (one process,
    // wall-clock lock-step of spec 00 §5.2 instead of the memq queue discipline).
    const CMUnitTest udpm[] = {cmocka_unit_test(s05_nominal), cmocka_unit_test(s07_nominal),
                               cmocka_unit_test(s04_5hz)};
    int rc = 0;
    if (g == "s07" || g == "all") { rc += cmocka_run_group_tests_name("sil_s07", s07, nullptr, nullptr); }
    if (g == "s07b" || g == "all") { rc += cmocka_run_group_tests_name("sil_s07b", s07b, nullptr, nullptr); }
    if (g == "s05" || g == "all") { rc += cmocka_run_group_tests_name("sil_s05", s05, nullptr, nullptr); }
    if (g == "s08" || g == "all") { rc += cmocka_run_group_tests_name("sil_s08", s08, nullptr, nullptr); }
    if (g == "range" || g == "all") { rc += cmocka_run_group_tests_name("sil_range", range, nullptr, nullptr); }
    if (g == "other" || g == "all") { rc += cmocka_run_group_tests_name("sil_other", other, nullptr, nullptr); }
    if (g == "faults" || g == "all") { rc += cmocka_run_group_tests_name("sil_faults", faults, nullptr, nullptr); }
    if (g == "udpm") { rc += cmocka_run_group_tests_name("sil_udpm", udpm, nullptr, nullptr); }
    return rc;
}
