// The relay plant and reference alone (spec 20 §2.3 S1, §3.3, §4.1), reduced for the suite; the
// full 20 000-s comparison is `relay_exactness` (sim/relay, README "Exactness"):
//   - RK4 at 1e-4 s against driver 2 at the same tick over 1 000 s from the published state: the
//     first 40 switch times within 1e-6 s (switching is quantised to the same ticks: measured 0 s),
//     the mean envelope over [100, 1000] s within 0.5 %;
//   - driver 1 (continuous law) against RK4: the first 10 switch times within 10 ms (spec 2.5 ms);
//   - the estimator identity: the copy's amplitude bounds the mode, max(|x~_i| - a_i) <= 1e-15 rad;
//   - the lock-step plant (sim::RelayPlant, driver 3) reproduces driver 2's switch times exactly when
//     it is driven by the same tick law (integer elapsed ticks from the anchor, no accumulated time).
#include <cmath>
#include <cstdio>

#include "relay/relay_plant.hpp"
#include "relay/rly_ref.hpp"
#include "scenario/scenario.hpp"

// last: cmocka.h defines macros (fail, ...) that clash with the standard library headers
#include "sim_test.hpp"

SIM_TEST(s1_reduced_rk4_against_the_event_drivers)
{
    const ref::RelayModel model;
    const ref::RelayState s0;
    ref::RelayLaw law;
    law.h_s = 1e-4;
    ref::RunOptions opt;
    opt.abar_t0_s = 100.0;
    opt.abar_t1_s = 1000.0;
    const ref::RelayRun d2 = ref::run_tick_sampled(model, law, s0, 1000.0, opt);
    const ref::RelayRun rk = ref::run_rk4(model, law, s0, 1000.0, 1e-4, opt);
    const ref::RelayRun d1 = ref::run_continuous(model, law, s0, 1000.0, opt);
    EXPECT_TRUE(d2.switches.size() >= 40u && rk.switches.size() >= 40u && d1.switches.size() >= 40u);
    double dmax2 = 0.0, dmax1 = 0.0;
    for (std::size_t i = 0; i < 40u; ++i) {
        dmax2 = std::fmax(dmax2, std::fabs(rk.switches[i].t_s - d2.switches[i].t_s));
        EXPECT_EQ_INT(rk.switches[i].level, d2.switches[i].level);
        if (i < 10u) {
            dmax1 = std::fmax(dmax1, std::fabs(rk.switches[i].t_s - d1.switches[i].t_s));
        }
    }
    const double rel = std::fabs(rk.abar_rad / d2.abar_rad - 1.0);
    std::printf("S1 (1000 s): first 40 switches RK4 vs driver 2 max |dt| %.3g s; first 10 RK4 vs driver 1 %.3g s;"
                " abar RK4 %.6g, driver 2 %.6g (%.3g %%), driver 1 %.6g\n",
                dmax2, dmax1, rk.abar_rad, d2.abar_rad, 100.0 * rel, d1.abar_rad);
    EXPECT_LE(dmax2, 1e-6);
    EXPECT_LE(rel, 0.005);
    EXPECT_LE(dmax1, 0.010);
}

SIM_TEST(copy_amplitude_bounds_the_mode)
{
    const ref::RelayModel model;
    const ref::RelayState s0;
    ref::EnvelopeCopy copy(model, 1e-3, s0, 1);
    ref::TickLawD law = ref::make_tick_law_double(ref::RelayLaw{});
    ref::RelayState anchor = s0, now = s0;
    int lvl = 1;
    std::uint64_t ticks = 0;
    double worst = -1.0;
    for (int k = 0; k < 300000; ++k) {
        for (int i = 0; i < 2; ++i) {
            worst = std::fmax(worst, std::fabs(now.q_rad[static_cast<std::size_t>(i)]) - copy.a_i_rad(i));
        }
        const int cmd = law.step(now.x());
        if (cmd != lvl) {
            anchor = now;
            ticks = 0;
            lvl = cmd;
        }
        copy.advance(cmd);
        ++ticks;
        now = ref::propagate(model, anchor, lvl, static_cast<double>(ticks) * 1e-3);
    }
    std::printf("estimator identity over 300 s: max(|x~_i| - a_i) = %.3g rad\n", worst);
    EXPECT_LE(worst, 1e-15);
}

SIM_TEST(lock_step_plant_matches_driver_2)
{
    sim::Scenario s = sim::parse_scenario("name: t\nmission: relay\nduration_s: 300\n", "t.yaml");
    sim::RelayPlant plant(s);
    ref::RelayLaw law;
    ref::RunOptions opt;
    opt.quantise = true;
    const ref::RelayRun d2 = ref::run_tick_sampled(ref::RelayModel{}, law, ref::RelayState{}, 300.0, opt);
    ref::TickLaw tl = ref::make_tick_law(law, false);
    std::vector<double> sw;
    int lvl = 1;
    for (int k = 0; k < 300000; ++k) {
        const sim::SensorFrame f = plant.sense();
        const int cmd = tl.step(f.cnt[0]);
        if (cmd != lvl) {
            sw.push_back(k * 1e-3);
            lvl = cmd;
        }
        sim::ActuatorCmd c;
        c.n_ch = 1u;
        c.cnt[0] = (cmd == 2) ? RLY_LVL_FULL_POS : (cmd == -2) ? RLY_LVL_FULL_NEG
                 : (cmd == 1) ? RLY_LVL_WEAK_POS : (cmd == -1) ? RLY_LVL_WEAK_NEG : RLY_LVL_OFF;
        plant.apply(c);
        (void)plant.propagate();
    }
    std::size_t n = std::min(sw.size(), d2.switches.size());
    double dmax = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        dmax = std::fmax(dmax, std::fabs(sw[i] - d2.switches[i].t_s));
    }
    std::printf("lock-step plant vs driver 2 (q24): %zu / %zu switches, max |dt| %.3g s\n", sw.size(),
                d2.switches.size(), dmax);
    EXPECT_EQ_INT(sw.size(), d2.switches.size());
    EXPECT_LE(dmax, 1e-9);
}

int main()
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(s1_reduced_rk4_against_the_event_drivers),
                                       cmocka_unit_test(copy_amplitude_bounds_the_mode),
                                       cmocka_unit_test(lock_step_plant_matches_driver_2)};
    return cmocka_run_group_tests_name("rly_ref", tests, nullptr, nullptr);
}
