// Closed-loop acceptance of the impulse scheduler against the CW plant (spec 50 §7 A4-4 ... A4-7),
// host only: the fixed-point module, and the double reference FSW on the same seeds. No LCM (the
// SIL node wraps the same plant); the plant, sensor and faults are those of sim/impulse/cw_plant.
//
//   test_imp_loop <group>     group = a44_ideal | a44_nominal_ex | a44_nominal_rand | a45 | a47
//
// Bounds are the spec's numbers. Every run also checks A4-6 and the flight-code invariants:
// every accepted plan's final residual <= r_tol, no fx status bit in any step (the module has no
// designated saturating points), no interlock, no plant-logged violation (both thrusters of an
// axis commanded in one step), no commanded burn shorter than t_min, and no STUCK_* or
// THRUST_LEVEL flag in the fault-free runs (false alarms).
//
// Decisions (fsw/impulse/README.md): A4-4 runs with calibration off (there is no thrust-level
// error to calibrate, and the spec's reference figures for nominal navigation are those of the
// uncalibrated loop: measured here p95 0.92 / 0.69 m against the spec's 0.99 / 0.76 m); A4-5 with
// calibration on. Random states: +-5 km / +-1 m/s per component, seeds 1000 + i of the project
// generator; nominal-nav seeds 77 + i.
#include "imp_loop.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

extern "C" {
#include "ut.h"
}

namespace {

// seconds of a step count at the 0.1 s tick
double sec(std::int64_t k) { return static_cast<double>(k) * 0.1; }

using imploop::Cfg;
using imploop::Out;

constexpr std::uint64_t kRandBase = 1000u;
constexpr std::uint64_t kNavSeedBase = 77u;

// A4-6 and the invariants, for any run of the flight code (fault-free or not).
void check_hygiene(const Cfg &c, const Out &o)
{
    UT_CHECK_EQ(o.fx_or, 0u);
    UT_CHECK_EQ(o.interlock_steps, 0u);
    UT_CHECK_EQ(o.violations, 0u);
    UT_CHECK_EQ(o.short_burns, 0u);
    if (!c.use_ref) {
        UT_CHECK_EQ(o.st_sticky, 0u);
        UT_CHECK_LE(o.fres_max, c.p.r_tol_lsb);
    }
}

// Fault-free runs: no false alarm, the mission completes. A re-plan may fail (every pattern
// converges to a non-physical order late in a mission): the timeline in force then stays, as
// spec 50 §8 prescribes; such failures are counted and reported, not errors.
void check_nominal(const Cfg &c, const Out &o)
{
    check_hygiene(c, o);
    UT_CHECK_EQ(o.health_or & (IMP_H_STUCK_OFF | IMP_H_STUCK_ON | IMP_H_THRUST_LEVEL), 0u);
    UT_CHECK_EQ(o.mode, IMP_MODE_DONE);
    UT_CHECK_EQ(o.late, 0u);
    UT_CHECK(o.failed < o.plans);
    if (!c.use_ref) { UT_CHECK(o.accepted >= 1u); }
}

Cfg base(const imp_params_t &tbl, const imploop::Vec6 &x0, bool cal)
{
    Cfg c;
    c.p = tbl;
    c.p.cal_enable = cal ? 1u : 0u;
    c.x0 = x0;
    return c;
}

struct Stats {
    std::vector<double> mr, mv, ddv;
    std::uint32_t accepted = 0, failed = 0, kept = 0, plans = 0;
    std::int32_t fres = 0;
    double med() const { return imploop::quantile(mr, 0.5); }
    double p95() const { return imploop::quantile(mr, 0.95); }
    double max() const { return imploop::quantile(mr, 1.0); }
    double vmax() const { return imploop::quantile(mv, 1.0); }
    double ddv_max() const { return imploop::quantile(ddv, 1.0); }
    void add(const Out &o)
    {
        mr.push_back(o.mr);
        mv.push_back(o.mv);
        ddv.push_back(o.dv - o.plan_dv);
        accepted += o.accepted;
        failed += o.failed;
        kept += o.tlm.plans_kept;
        plans += o.plans;
        fres = std::max(fres, o.fres_max);
    }
    void print(const char *tag) const
    {
        std::printf("%s: n %zu, |dR| median %.3f p95 %.3f max %.3f m; |dV| max %.5f m/s; dv - plan max %.3f m/s; "
                    "plans %u (failed %u, kept %u), final |F| of accepted plans max %d LSB\n", tag, mr.size(), med(),
                    p95(), max(), vmax(), ddv_max(), plans, failed, kept, fres);
    }
};

Stats run_set(const imp_params_t &tbl, bool random, int n, double eps_c, sim::NavProfile nav, bool cal, bool ref)
{
    Stats s;
    for (int i = 0; i < n; ++i) {
        const auto iu = static_cast<std::uint64_t>(i);
        Cfg c = base(tbl, random ? imploop::random_x0(kRandBase + iu) : imploop::example_x0(), cal);
        c.plant.eps_c = eps_c;
        c.plant.nav.profile = nav;
        c.plant.nav.seed = kNavSeedBase + iu;
        c.use_ref = ref;
        const Out o = imploop::fly(c);
        check_nominal(c, o);
        s.add(o);
    }
    return s;
}

// ------------------------------------------------------------------ A4-4 ideal navigation

// Example and 50 seeded random cases at 0.1 s and 1 s ticks (N = 100 s, best rounding, ideal
// navigation): miss bounds, and delta-v used <= the open-loop plan's (double reference solver)
// + 0.1 m/s (0.1 s) or + 0.8 m/s (1 s).
UT_TEST(a44_ideal_example_and_random)
{
    struct Tick {
        const imp_params_t *tbl;
        const char *name;
        double ex_r, ex_v, rnd_r, rnd_v, ddv;
    };
    const Tick ticks[2] = {{&IMP_TBL_DEFAULT, "0.1 s", 0.5, 0.005, 1.0, 0.005, 0.1},
                           {&IMP_TBL_1S, "1 s", 7.0, 0.05, 8.0, 0.05, 0.8}};
    for (const Tick &t : ticks) {
        const Stats ex = run_set(*t.tbl, false, 1, 0.0, sim::NavProfile::Ideal, false, false);
        const Stats rn = run_set(*t.tbl, true, 50, 0.0, sim::NavProfile::Ideal, false, false);
        std::printf("A4-4 example, tick %s: |dR| %.3f m, |dV| %.5f m/s, dv - plan %.3f m/s\n", t.name, ex.mr[0],
                    ex.mv[0], ex.ddv[0]);
        rn.print(t.name);
        UT_CHECK(ex.mr[0] <= t.ex_r);
        UT_CHECK(ex.mv[0] <= t.ex_v);
        UT_CHECK(rn.max() <= t.rnd_r);
        UT_CHECK(rn.vmax() <= t.rnd_v);
        UT_CHECK(ex.ddv[0] <= t.ddv);
        UT_CHECK(rn.ddv_max() <= t.ddv);
    }
}

// Not a spec item: the 1 ms valve sub-tick (spec 50 §2.4) on the example and 20 random cases.
// Rounding to 1 ms leaves ~1 cm (G5), so the closed loop must do at least as well as at 0.1 s.
UT_TEST(a44_subtick_1ms)
{
    const Stats ex = run_set(IMP_TBL_SUB1MS, false, 1, 0.0, sim::NavProfile::Ideal, false, false);
    const Stats rn = run_set(IMP_TBL_SUB1MS, true, 20, 0.0, sim::NavProfile::Ideal, false, false);
    std::printf("sub-tick 1 ms example: |dR| %.4f m, |dV| %.6f m/s, dv - plan %.4f m/s\n", ex.mr[0], ex.mv[0], ex.ddv[0]);
    rn.print("sub-tick 1 ms random");
    UT_CHECK(ex.mr[0] <= 0.5);
    UT_CHECK(rn.max() <= 1.0);
    UT_CHECK(rn.vmax() <= 0.005);
    UT_CHECK(rn.ddv_max() <= 0.1);
}

// ------------------------------------------------------------------ A4-4 nominal navigation

// 100 seeds of nominal navigation (sigma_p 0.1 m, sigma_v 1 mm/s) at 0.1 s: p95 <= 1.2 m,
// max <= 2 m, |dV| <= 0.01 m/s; and on the same seeds the reference FSW's median and p95 within
// 20 % (or 0.1 m, whichever is larger) of the flight code's.
void a44_nominal(bool random)
{
    const Stats fx = run_set(IMP_TBL_DEFAULT, random, 100, 0.0, sim::NavProfile::Nominal, false, false);
    const Stats rf = run_set(IMP_TBL_DEFAULT, random, 100, 0.0, sim::NavProfile::Nominal, false, true);
    fx.print(random ? "A4-4 nominal nav, random, flight" : "A4-4 nominal nav, example, flight");
    rf.print(random ? "A4-4 nominal nav, random, reference FSW" : "A4-4 nominal nav, example, reference FSW");
    UT_CHECK(fx.p95() <= 1.2);
    UT_CHECK(fx.max() <= 2.0);
    UT_CHECK(fx.vmax() <= 0.01);
    auto close = [](double a, double b) { return std::abs(a - b) <= std::max(0.2 * b, 0.1); };
    UT_CHECK(close(fx.med(), rf.med()));
    UT_CHECK(close(fx.p95(), rf.p95()));
}

UT_TEST(a44_nominal_nav_example) { a44_nominal(false); }
UT_TEST(a44_nominal_nav_random) { a44_nominal(true); }

// ------------------------------------------------------------------ A4-5 thrust-level error

// Ideal navigation, +2 % and -5 % common error, calibration on: example <= 1 m, 40 random <= 1 m.
// The calibrated levels (noise-free but for the nav quantisation) are within 1e-4 of the truth
// for every thruster (own windows or the pooled mean; spec 50 G7).
UT_TEST(a45_ideal_calibrated)
{
    for (double e : {0.02, -0.05}) {
        Cfg c = base(IMP_TBL_DEFAULT, imploop::example_x0(), true);
        c.plant.eps_c = e;
        const Out o = imploop::fly(c);
        check_nominal(c, o);
        std::printf("A4-5 example, %+.0f %%: |dR| %.3f m, |dV| %.5f m/s, alpha %.5f %.5f %.5f %.5f %.5f %.5f\n",
                    e * 100, o.mr, o.mv, o.alpha[0], o.alpha[1], o.alpha[2], o.alpha[3], o.alpha[4], o.alpha[5]);
        UT_CHECK(o.mr <= 1.0);
        for (double a : o.alpha) { UT_CHECK(std::abs(a - (1.0 + e)) <= 1e-4); }
        const Stats rn = run_set(IMP_TBL_DEFAULT, true, 40, e, sim::NavProfile::Ideal, true, false);
        rn.print(e > 0 ? "A4-5 random, +2 %" : "A4-5 random, -5 %");
        UT_CHECK(rn.max() <= 1.0);
    }
}

// Nominal navigation, +2 %, calibration on, 100 seeds of the example: p95 <= 2.5 m, max <= 4 m.
UT_TEST(a45_nominal_calibrated)
{
    const Stats fx = run_set(IMP_TBL_DEFAULT, false, 100, 0.02, sim::NavProfile::Nominal, true, false);
    fx.print("A4-5 nominal nav, +2 %, example");
    UT_CHECK(fx.p95() <= 2.5);
    UT_CHECK(fx.max() <= 4.0);
}

// Calibration off and +2 %: EXPECTED_MISS raised before the first second burn starts, and the
// actual miss exceeds 10 m (the flag is not vacuous). With calibration on, the same run never
// raises it: a calibration epoch is due before the second burns, so the prediction uses u_cal
// (the x burn's 215.7 s predicts 4.7 m with u_cal = 0.005), and the run indeed ends < 1 m.
UT_TEST(a45_expected_miss_is_not_vacuous)
{
    Cfg c = base(IMP_TBL_DEFAULT, imploop::example_x0(), false);
    c.plant.eps_c = 0.02;
    const Out o = imploop::fly(c);
    check_hygiene(c, o);
    std::printf("A4-5 calibration off, +2 %%: EXPECTED_MISS first at step %lld (t0 %u, first second burn at step "
                "%lld), predicted dR x %.2f m, actual |dR| %.3f m\n", static_cast<long long>(o.k_expected_miss), o.t0,
                static_cast<long long>(o.k_second_burn), o.tlm.exp_dr_q28[0] / 268435456.0 * 31250.21, o.mr);
    UT_CHECK(o.k_expected_miss >= 0);
    UT_CHECK(o.k_expected_miss < o.k_second_burn);
    UT_CHECK(o.mr > 10.0);
    Cfg on = c;
    on.p.cal_enable = 1u;
    const Out o2 = imploop::fly(on);
    UT_CHECK(o2.k_expected_miss < 0);
    UT_CHECK_EQ((o2.tlm.health_sticky & IMP_H_EXPECTED_MISS) != 0u, false);
    UT_CHECK(o2.mr <= 1.0);
}

// Per-thruster level errors: every thruster with its own accepted windows converges to its own
// level (1e-4); the others take the pooled mean, which lies between the estimates (the common-
// mode assumption of spec 50 §5.5: an individual error on a thruster that never fires a long
// enough window, here +z whose only burn is the final one, is not observable before it is used,
// and the miss is then the uncalibrated one: reported, not bounded). A level beyond cal_gate
// (+25 %) is never accepted: THRUST_LEVEL, windows discarded, thrust factors unchanged.
UT_TEST(a45_per_thruster_and_gate)
{
    Cfg c = base(IMP_TBL_DEFAULT, imploop::example_x0(), true);
    c.plant.eps = {{0.03, -0.01, 0.02, -0.02, 0.01, 0.04}};
    const Out o = imploop::fly(c);
    check_nominal(c, o);
    std::printf("per-thruster levels: alpha %.5f %.5f %.5f %.5f %.5f %.5f, windows %u %u %u %u %u %u, |dR| %.3f m\n",
                o.alpha[0], o.alpha[1], o.alpha[2], o.alpha[3], o.alpha[4], o.alpha[5], o.tlm.cal_windows[0],
                o.tlm.cal_windows[1], o.tlm.cal_windows[2], o.tlm.cal_windows[3], o.tlm.cal_windows[4],
                o.tlm.cal_windows[5], o.mr);
    double lo = 2.0, hi = 0.0;
    for (size_t j = 0; j < 6; ++j) {
        if (o.tlm.cal_windows[j] > 0) {
            UT_CHECK(std::abs(o.alpha[j] - (1.0 + c.plant.eps[j])) <= 1e-4);
            lo = std::min(lo, o.alpha[j]);
            hi = std::max(hi, o.alpha[j]);
        }
    }
    for (size_t j = 0; j < 6; ++j) {
        if (o.tlm.cal_windows[j] == 0) { UT_CHECK(o.alpha[j] >= lo && o.alpha[j] <= hi); }
    }
    UT_CHECK(o.tlm.cal_windows[0] > 0 && o.tlm.cal_windows[3] > 0 && o.tlm.cal_windows[5] > 0);
    Cfg g = base(IMP_TBL_DEFAULT, imploop::example_x0(), true);
    g.plant.eps_c = 0.25;
    const Out og = imploop::fly(g);
    check_hygiene(g, og);
    std::printf("+25 %% level: THRUST_LEVEL at step %lld, windows discarded %u, alpha %.4f\n",
                static_cast<long long>(og.k_thrust_level), og.cal_rej, og.alpha[0]);
    UT_CHECK(og.k_thrust_level >= 0);
    UT_CHECK(og.cal_rej >= 1u);
    for (double a : og.alpha) { UT_CHECK(std::abs(a - 1.0) <= 0.0); }   // exactly the table's 1.0
}

// ------------------------------------------------------------------ A4-7 faults and bad input

// The plant's time origin is the START step; t0 = 5 s. Fault times are plant times.
UT_TEST(a47_stuck_off_plus_x)
{
    Cfg c = base(IMP_TBL_DEFAULT, imploop::example_x0(), true);
    c.plant.stuck_off_j = 0;
    c.plant.stuck_off_t = 10.0;
    const Out o = imploop::fly(c);
    check_hygiene(c, o);
    const std::int64_t kf = 100;   // 10 s
    std::printf("+x stuck off from 10 s: STUCK_OFF at %.1f s (latency %.1f s), thruster %u, ABORTED at %.1f s, "
                "last output at %.1f s, plans %u (failed %u)\n", sec(o.k_stuck_off), sec(o.k_stuck_off - kf),
                o.stuck_j, sec(o.k_abort), sec(o.k_last_on), o.plans, o.failed);
    UT_CHECK(o.k_stuck_off >= kf);
    UT_CHECK(o.k_stuck_off - kf <= 210);
    UT_CHECK_EQ(o.stuck_j, 0u);
    UT_CHECK((o.health_or & (1u << IMP_H_STUCK_OFF_SH)) != 0u);      // axis x
    UT_CHECK_EQ(o.health_or & IMP_H_STUCK_ON, 0u);
    UT_CHECK_EQ(o.mode, IMP_MODE_ABORTED);
    UT_CHECK(o.k_abort >= o.k_stuck_off);
    UT_CHECK(o.k_abort - o.k_stuck_off < static_cast<std::int64_t>(c.p.plan_lead));   // the re-plan job's end
    UT_CHECK(!o.on_after_abort);
    UT_CHECK_EQ(o.failed, 1u);                                      // the re-plan avoiding +x
    UT_CHECK_EQ(o.tlm.stuck_off_mask, 0x01u);
}

UT_TEST(a47_stuck_on_minus_z)
{
    Cfg c = base(IMP_TBL_DEFAULT, imploop::example_x0(), true);
    c.plant.stuck_on_j = 5;
    c.plant.stuck_on_t = 200.0;
    const Out o = imploop::fly(c);
    check_hygiene(c, o);
    const std::int64_t kf = 2000;
    std::printf("-z stuck on from 200 s: STUCK_ON at %.1f s (latency %.1f s), thruster %u, ABORTED at %.1f s, "
                "outputs after: %s\n", sec(o.k_stuck_on), sec(o.k_stuck_on - kf), o.stuck_j, sec(o.k_abort),
                o.on_after_abort ? "yes" : "none");
    UT_CHECK(o.k_stuck_on >= kf);
    UT_CHECK(o.k_stuck_on - kf <= 210);
    UT_CHECK_EQ(o.stuck_j, 5u);
    UT_CHECK((o.health_or & (1u << (IMP_H_STUCK_ON_SH + 2u))) != 0u);   // axis z
    UT_CHECK_EQ(o.health_or & IMP_H_STUCK_OFF, 0u);
    UT_CHECK_EQ(o.mode, IMP_MODE_ABORTED);
    UT_CHECK_EQ(o.k_abort, o.k_stuck_on);
    UT_CHECK(!o.on_after_abort);
}

UT_TEST(a47_nav_lost)
{
    Cfg c = base(IMP_TBL_DEFAULT, imploop::example_x0(), true);
    c.plant.nav.dropouts = {{150.0, 450.0}};
    const Out o = imploop::fly(c);
    check_nominal(c, o);
    std::printf("nav lost 150-450 s: NAV_STALE from %.1f s, skipped epochs %u, |dR| %.3f m, |dV| %.5f m/s\n",
                sec(o.k_nav_stale), o.skipped, o.mr, o.mv);
    UT_CHECK(o.k_nav_stale > 1490 && o.k_nav_stale <= 1500 + static_cast<std::int64_t>(c.p.nav_timeout));
    UT_CHECK(o.skipped >= 2u);
    UT_CHECK(o.mr <= 0.5);
    Cfg g = c;
    g.plant.nav.dropouts = {{50.0, 1e9}};
    const Out og = imploop::fly(g);
    check_nominal(g, og);
    std::printf("nav lost for good after 50 s: |dR| %.3f m, |dV| %.5f m/s, plans %u, skipped %u\n", og.mr, og.mv,
                og.plans, og.skipped);
    UT_CHECK(og.mr <= 0.8);
    UT_CHECK_EQ(og.plans, 1u);
}

UT_TEST(a47_infeasible_and_bad_start)
{
    Cfg c = base(IMP_TBL_DEFAULT, imploop::Vec6(), true);
    c.x0 << 20000, 5, 20000, 5, 20000, 5;
    const Out o = imploop::fly(c);
    check_hygiene(c, o);
    UT_CHECK_EQ(o.mode, IMP_MODE_INFEASIBLE);
    UT_CHECK(o.k_first_on < 0);
    UT_CHECK((o.health_or & IMP_H_INFEASIBLE) != 0u);
    // START with tau_f = 2.5 rad: refused, IDLE, nothing ever on
    Cfg b = base(IMP_TBL_DEFAULT, imploop::example_x0(), true);
    b.T = 2.5 / 1.131367e-3;
    const Out ob = imploop::fly(b);
    UT_CHECK_EQ(ob.mode, IMP_MODE_IDLE);
    UT_CHECK_EQ(ob.cmd_rej, 1u);
    UT_CHECK_EQ(ob.tlm.rej_reason, IMP_REJ_TAU);
    UT_CHECK(ob.k_first_on < 0);
    // the reference FSW decides the same
    b.use_ref = true;
    c.use_ref = true;
    UT_CHECK_EQ(imploop::fly(b).mode, IMP_MODE_IDLE);
    UT_CHECK_EQ(imploop::fly(c).mode, IMP_MODE_INFEASIBLE);
}

// Outliers (100 m and 1 m/s spikes) in a nominal-nav run are discarded and do not degrade the
// A4-4 bounds; random dropouts (20 % of the samples) neither; a rerun with the same seed gives a
// bit-identical command and health stream (CRC-32 of every step's outputs).
UT_TEST(a47_outliers_dropouts_determinism)
{
    Cfg c = base(IMP_TBL_DEFAULT, imploop::example_x0(), false);
    c.plant.nav.profile = sim::NavProfile::Nominal;
    c.plant.nav.seed = 5;
    c.plant.nav.outliers = {{120.0, {100.0, 0.0}}, {333.0, {0.0, 1.0}}, {612.0, {-100.0, -1.0}}};
    const Out o = imploop::fly(c);
    check_nominal(c, o);
    std::printf("outliers: nav_rej %u, |dR| %.3f m; ", o.nav_rej, o.mr);
    UT_CHECK_EQ(o.nav_rej, 3u);
    UT_CHECK(o.mr <= 2.0);
    Cfg d = c;
    d.plant.nav.outliers.clear();
    d.plant.nav.p_drop = 0.2;
    const Out od = imploop::fly(d);
    check_nominal(d, od);
    std::printf("20 %% dropouts: |dR| %.3f m, skipped %u; ", od.mr, od.skipped);
    UT_CHECK(od.mr <= 2.0);
    const Out o2 = imploop::fly(c);
    Cfg f = base(IMP_TBL_DEFAULT, imploop::example_x0(), true);
    f.plant.stuck_on_j = 5;
    f.plant.stuck_on_t = 200.0;
    const std::uint32_t cf1 = imploop::fly(f).crc, cf2 = imploop::fly(f).crc;
    std::printf("rerun CRC 0x%08x / 0x%08x, fault run 0x%08x / 0x%08x\n", o.crc, o2.crc, cf1, cf2);
    UT_CHECK_EQ(o.crc, o2.crc);
    UT_CHECK_EQ(cf1, cf2);
    UT_CHECK(o.crc != od.crc);
}

}  // namespace

int main(int argc, char **argv)
{
    const std::string g = argc > 1 ? argv[1] : "all";
    UT_CASES(a44_ideal) = {UT_CASE(a44_ideal_example_and_random), UT_CASE(a44_subtick_1ms)};
    UT_CASES(a44_nom_ex) = {UT_CASE(a44_nominal_nav_example)};
    UT_CASES(a44_nom_rand) = {UT_CASE(a44_nominal_nav_random)};
    UT_CASES(a45) = {UT_CASE(a45_ideal_calibrated), UT_CASE(a45_nominal_calibrated),
                     UT_CASE(a45_expected_miss_is_not_vacuous), UT_CASE(a45_per_thruster_and_gate)};
    UT_CASES(a47) = {UT_CASE(a47_stuck_off_plus_x), UT_CASE(a47_stuck_on_minus_z), UT_CASE(a47_nav_lost),
                     UT_CASE(a47_infeasible_and_bad_start), UT_CASE(a47_outliers_dropouts_determinism)};
    int fails = 0;
    if (g == "a44_ideal" || g == "all") { fails += UT_RUN("imp_loop_a44_ideal", a44_ideal); }
    if (g == "a44_nominal_ex" || g == "all") { fails += UT_RUN("imp_loop_a44_nominal_ex", a44_nom_ex); }
    if (g == "a44_nominal_rand" || g == "all") { fails += UT_RUN("imp_loop_a44_nominal_rand", a44_nom_rand); }
    if (g == "a45" || g == "all") { fails += UT_RUN("imp_loop_a45", a45); }
    if (g == "a47" || g == "all") { fails += UT_RUN("imp_loop_a47", a47); }
    return fails;
}
