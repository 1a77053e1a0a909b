// HOLD in closed loop (SIL): plant node <-> LCM (memq) <-> bridge <-> fsw_step, the
// in-process lock-step driver of hil_host/sil, and the same run with the double reference in
// place of the flight code (`--fsw ref`).
//
// Bounds, derived from the default table and the nominal scenario (J = 10 kg m^2, 0.2 rad/s):
// the law saturates at 0.05 N m until |omega| = u_max / K = 0.1 rad/s (20 s at 0.005 rad/s^2),
// then decays with tau = J / K = 20 s: below 1e-3 rad/s after 20 + 20 ln(100) = 112 s. The
// bound 130 s leaves 18 s for the gyro noise (1e-5 rad/s) and quantisation; the final rate
// lies far below 1e-3 rad/s after 300 s. Fixed point vs reference: the commands differ by at
// most 1/2 LSB per step (test_pd_ref_host.cpp), so t_settle within 2 periods and the
// final rates within 1e-5 rad/s. A NaN window of 1 s on the gyro: 10 refused samples,
// MEAS_SKIP, zero torque, never SAFE (stale_max is 250 steps).
#include <cmath>
#include <cstdio>
#include <string>

#include "pd/pd_metrics.hpp"
#include "scenario/scenario.hpp"
#include "sil_run.hpp"
// last: cmocka.h defines macros (fail, ...) that clash with the standard library headers
#include "sim_test.hpp"

namespace {

sil::InprocResult fly(const sim::Scenario &s, const std::string &fsw)
{
    sil::InprocOptions o;
    o.fsw = fsw;
    return sil::run_inproc(s, o);
}

const host::PdMetrics &mm(const sil::InprocResult &r) { return r.metrics<host::PdMetrics>(); }

}  // namespace

SIM_TEST(nominal_settles_like_the_reference)
{
    const sim::Scenario s = sim::load_scenario(SCENARIO_DIR "/pd_nominal.yaml");
    const sil::InprocResult fx = fly(s, "fixed");
    const sil::InprocResult rf = fly(s, "ref");
    std::printf("fixed: t_settle %.2f s, final |w| %.3g rad/s, peak torque %.5f N m, health OR 0x%08X\n",
                mm(fx).t_settle_s, mm(fx).rate_final_radps, mm(fx).peak_torque_nm, mm(fx).health_or);
    std::printf("ref:   t_settle %.2f s, final |w| %.3g rad/s, peak torque %.5f N m\n", mm(rf).t_settle_s,
                mm(rf).rate_final_radps, mm(rf).peak_torque_nm);
    for (const sil::InprocResult *r : {&fx, &rf}) {
        EXPECT_TRUE(!r->plant.diverged && r->plant.deterministic());
        EXPECT_EQ_INT(r->plant.steps, 3000);
        EXPECT_LE(mm(*r).t_settle_s, 130.0);
        EXPECT_LE(mm(*r).rate_final_radps, 1e-4);
        EXPECT_NEAR(mm(*r).peak_torque_nm, 3277.0 / 65536.0, 1e-12);   // at the limit while saturated
    }
    EXPECT_NEAR(mm(fx).t_settle_s, mm(rf).t_settle_s, 2.0 * s.h_s() + 1e-9);
    EXPECT_NEAR(mm(fx).rate_final_radps, mm(rf).rate_final_radps, 1e-5);
    EXPECT_TRUE((mm(fx).health_or & PD_H_CMD_LIMITED) != 0u);
    EXPECT_TRUE((mm(fx).health_or & PD_H_CMD_LIMIT_PERSIST) == 0u);   // 20 s < 60 s
    EXPECT_EQ_INT(fx.summary.number("fsw_n_safe"), 0);
    EXPECT_EQ_INT(fx.summary.number("fsw_n_tbl_rej"), 0);
    EXPECT_EQ_INT(fx.summary.number("t_first_fx_status_s"), -1);
}

SIM_TEST(gyro_nan_window_is_refused_and_flown_through)
{
    sim::Scenario s = sim::load_scenario(SCENARIO_DIR "/pd_nominal.yaml");
    s.faults.nan_s = {{50.0, 51.0}};
    s.faults.nan_channel = 0u;
    const sil::InprocResult fx = fly(s, "fixed");
    std::printf("NaN window: plant nan frames %llu, fsw n_chan_rej %.0f, n_skip %.0f\n",
                static_cast<unsigned long long>(fx.plant.nan_frames), fx.summary.number("fsw_n_chan_rej"),
                fx.summary.number("fsw_pd_n_skip"));
    EXPECT_EQ_INT(fx.plant.nan_frames, 10);
    EXPECT_EQ_INT(fx.summary.number("fsw_n_chan_rej"), 10);
    EXPECT_EQ_INT(fx.summary.number("fsw_pd_n_skip"), 10);
    EXPECT_EQ_INT(fx.summary.number("fsw_n_safe"), 0);
    EXPECT_TRUE((mm(fx).health_or & PD_H_MEAS_SKIP) != 0u);
    EXPECT_LE(mm(fx).rate_final_radps, 1e-4);
}

int main()
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(nominal_settles_like_the_reference),
                                       cmocka_unit_test(gyro_nan_window_is_refused_and_flown_through)};
    return cmocka_run_group_tests_name("pd_sil", tests, nullptr, nullptr);
}
