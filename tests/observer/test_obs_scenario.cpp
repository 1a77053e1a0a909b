// The DETUMBLE scenario section (sim/observer/observer_section.cpp): the shipped S0-5 / S0-7
// files, the sail's defaults, and clear errors that name the file and the key.
#include <string>

#include "observer/observer_section.hpp"
#include "scenario/scenario.hpp"
#include "scenario_test.hpp"
#include "sim_test.hpp"

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

const char *kMinimal =
    "name: t\n"
    "mission: detumble\n"
    "model: M-phys\n"
    "sigma: 1\n"
    "duration_s: 10\n";

const sim::SailScenario &sail(const sim::Scenario &s) { return s.mission_part<sim::SailScenario>(); }

}  // namespace

SIM_TEST(test_shipped_scenarios)
{
    const sim::Scenario a = sim::load_scenario(SIM_SCENARIO_DIR "/s0-5_nominal_mpaper.yaml");
    EXPECT_TRUE(a.mission == "DETUMBLE");
    EXPECT_EQ_INT(sail(a).sigma, -1);
    EXPECT_EQ_INT(a.period_us, 20000);
    EXPECT_EQ_INT(a.n_steps(), 6000);
    EXPECT_NEAR(sail(a).k2_true_per_s2, 0.01, 0.0);
    EXPECT_NEAR(sail(a).w0_radps[0], 1.0 * kDeg, 1e-18);
    EXPECT_NEAR(sail(a).w0_radps[1], 1.0 * kDeg, 1e-18);
    EXPECT_NEAR(sail(a).gyro.noise_radps, 0.0, 0.0);
    EXPECT_NEAR(sail(a).gyro.lsb_radps(), 1.0 / 1048576.0, 0.0);
    EXPECT_EQ_INT(sail(a).gyro.max_cnt, 1048575);
    EXPECT_NEAR(sail(a).gimbal.hw_limit_radps, 0.35, 0.0);
    EXPECT_NEAR(sail(a).mu_max_rad, 30.0 * kDeg, 1e-15);
    EXPECT_NEAR(sail(a).w_max_radps, 30.0 * kDeg, 1e-15);
    EXPECT_TRUE(a.source.find("s0-5_nominal_mpaper.yaml") != std::string::npos);
    EXPECT_TRUE(a.fsw.table == "obs_50hz_paper");
    const sim::Scenario b = sim::load_scenario(SIM_SCENARIO_DIR "/s0-7_nominal_mphys.yaml");
    EXPECT_EQ_INT(sail(b).sigma, +1);
    EXPECT_EQ_INT(b.n_steps(), 30000);
    const sim::Scenario c = sim::load_scenario(SIM_SCENARIO_DIR "/s0-5_noise_seed0_mpaper.yaml");
    EXPECT_NEAR(sail(c).gyro.noise_radps, 1e-5, 0.0);
    EXPECT_EQ_INT(sail(c).gyro.seed, 0);
    // Defaults fill what a minimal file leaves out.
    const sim::Scenario m = sim::parse_scenario(kMinimal, "min.yaml");
    EXPECT_EQ_INT(m.period_us, 20000);
    EXPECT_TRUE(m.fsw.table == "obs_50hz_phys");
    EXPECT_NEAR(sail(m).w0_radps[0], 1.0 * kDeg, 1e-18);
    EXPECT_TRUE(sail(m).propagator == sim::Propagator::Zoh);
    // The operator overrides of the boot table.
    const sim::Scenario o = sim::parse_scenario(std::string(kMinimal) + "fsw: {k_hat0: 0.02, bdot_max_degps: 2}\n", "o.yaml");
    EXPECT_NEAR(sail(o).k_hat0, 0.02, 0.0);
    EXPECT_NEAR(sail(o).bdot_max_degps, 2.0, 0.0);
    const obs_params_t p = sim::observer_boot_table(o);
    EXPECT_EQ_INT(p.kappa_init_q28, 536870912);                // 0.02 / 0.01 = 2.0 in q28
}

SIM_TEST(test_scenario_errors)
{
    const std::string base = kMinimal;
    expect_scenario_error(base + "gyro:\n  noise: 1e-5\n", {"bad.yaml", "'gyro.noise'", "unknown key", "line 7"});
    expect_scenario_error("name: t\nmission: detumble\nmodel: M-phys\nsigma: 2\nduration_s: 10\n",
                          {"bad.yaml", "'sigma'", "out of range"});
    expect_scenario_error("name: t\nmission: detumble\nmodel: M-phys\nsigma: 0\nduration_s: 10\n",
                          {"'sigma'", "+1 (M-phys) or -1"});
    expect_scenario_error("name: t\nmission: detumble\nmodel: M-phys\nsigma: -1\nduration_s: 10\n",
                          {"'model'", "contradicts"});
    expect_scenario_error("name: t\nmission: detumble\nmodel: M-foo\nsigma: 1\nduration_s: 10\n",
                          {"'model'", "M-phys, M-paper"});
    expect_scenario_error("name: t\nmission: detumble\nmodel: M-phys\nduration_s: 10\n",
                          {"bad.yaml", "'sigma'", "missing required key"});
    expect_scenario_error(base + "k2_true_per_s2: abc\n", {"'k2_true_per_s2'", "not a number", "abc"});
    expect_scenario_error(base + "fsw: {table_file: t.bin, k_hat0: 0.01}\n",
                          {"'fsw.k_hat0'", "cannot be combined with fsw.table_file"});
    expect_scenario_error(base + "k2_true_per_s2: .nan\n", {"'k2_true_per_s2'", "finite"});
    expect_scenario_error(base + "gyro:\n  noise_radps: -1e-5\n", {"'gyro.noise_radps'", "out of range"});
    expect_scenario_error(base + "gyro:\n  seed: -3\n", {"'gyro.seed'", "non-negative"});
    expect_scenario_error(base + "w0_degps: [1]\n", {"'w0_degps'", "two numbers"});
    expect_scenario_error(base + "w0_degps: [1, x]\n", {"'w0_degps[1]'", "not a number"});
    expect_scenario_error(base + "w0_degps: [40, 0]\n", {"'w0_degps'", "w_max"});
    expect_scenario_error(base + "propagator: euler\n", {"'propagator'", "zoh, ode"});
    expect_scenario_error(base + "limits: 3\n", {"'limits'", "mapping"});
    expect_scenario_error(base + "plant: cw\n", {"'plant'", "plant: sail"});
    expect_scenario_error(base + "cw: {eps_c: 0.1}\n", {"'cw'", "unknown key"});
    expect_scenario_error(base + "fsw: {cal_enable: 1}\n", {"'fsw.cal_enable'", "unknown key"});
    expect_scenario_error(base + "commands: [{t_s: 1, cmd: IMP_START}]\n", {"unknown command 'IMP_START'", "DETUMBLE"});
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_shipped_scenarios),
        cmocka_unit_test(test_scenario_errors),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
