// Scenario loader checks: the shipped S0-5 / S0-7 files, and clear errors that name the file and
// the key for unknown keys, bad values, missing keys and out-of-range values.
#include <string>

#include "scenario/scenario.hpp"
#include "sim_test.hpp"

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

const char *kMinimal =
    "name: t\n"
    "model: M-phys\n"
    "sigma: 1\n"
    "duration_s: 10\n";

// Parses text that must fail; the message must contain every one of the fragments.
void expect_error(const std::string &yaml, std::initializer_list<const char *> fragments)
{
    try {
        (void)sim::parse_scenario(yaml, "bad.yaml");
        std::printf("  no error for:\n%s\n", yaml.c_str());
        EXPECT_TRUE(false);
    } catch (const sim::ScenarioError &e) {
        const std::string msg = e.what();
        std::printf("  -> %s\n", msg.c_str());
        for (const char *f : fragments) {
            if (msg.find(f) == std::string::npos) {
                std::printf("  missing '%s' in message\n", f);
                EXPECT_TRUE(false);
            }
        }
    }
}

}  // namespace

SIM_TEST(test_shipped_scenarios)
{
    const sim::Scenario a = sim::load_scenario(SIM_SCENARIO_DIR "/s0-5_nominal_mpaper.yaml");
    EXPECT_EQ_INT(a.sigma, -1);
    EXPECT_EQ_INT(a.period_us, 20000);
    EXPECT_EQ_INT(a.n_steps(), 6000);
    EXPECT_NEAR(a.k2_true_per_s2, 0.01, 0.0);
    EXPECT_NEAR(a.w0_radps[0], 1.0 * kDeg, 1e-18);
    EXPECT_NEAR(a.w0_radps[1], 1.0 * kDeg, 1e-18);
    EXPECT_NEAR(a.gyro.noise_radps, 0.0, 0.0);
    EXPECT_NEAR(a.gyro.lsb_radps(), 1.0 / 1048576.0, 0.0);
    EXPECT_EQ_INT(a.gyro.max_cnt, 1048575);
    EXPECT_NEAR(a.gimbal.hw_limit_radps, 0.35, 0.0);
    EXPECT_NEAR(a.mu_max_rad, 30.0 * kDeg, 1e-15);
    EXPECT_NEAR(a.w_max_radps, 30.0 * kDeg, 1e-15);
    EXPECT_TRUE(a.source.find("s0-5_nominal_mpaper.yaml") != std::string::npos);
    const sim::Scenario b = sim::load_scenario(SIM_SCENARIO_DIR "/s0-7_nominal_mphys.yaml");
    EXPECT_EQ_INT(b.sigma, +1);
    EXPECT_EQ_INT(b.n_steps(), 30000);
    const sim::Scenario c = sim::load_scenario(SIM_SCENARIO_DIR "/s0-5_noise_seed0_mpaper.yaml");
    EXPECT_NEAR(c.gyro.noise_radps, 1e-5, 0.0);
    EXPECT_EQ_INT(c.gyro.seed, 0);
    // Defaults fill what a minimal file leaves out.
    const sim::Scenario m = sim::parse_scenario(kMinimal, "min.yaml");
    EXPECT_EQ_INT(m.period_us, 20000);
    EXPECT_NEAR(m.w0_radps[0], 1.0 * kDeg, 1e-18);
    EXPECT_TRUE(m.propagator == sim::Propagator::Zoh);
}

SIM_TEST(test_scenario_errors)
{
    const std::string base = kMinimal;
    expect_error(base + "gyro:\n  noise: 1e-5\n", {"bad.yaml", "'gyro.noise'", "unknown key", "line 6"});
    expect_error(base + "dt: 0.02\n", {"bad.yaml", "'dt'", "unknown key"});
    expect_error("name: t\nmodel: M-phys\nsigma: 2\nduration_s: 10\n", {"bad.yaml", "'sigma'", "out of range"});
    expect_error("name: t\nmodel: M-phys\nsigma: 0\nduration_s: 10\n", {"'sigma'", "+1 (M-phys) or -1"});
    expect_error("name: t\nmodel: M-phys\nsigma: -1\nduration_s: 10\n", {"'model'", "contradicts"});
    expect_error("name: t\nmodel: M-foo\nsigma: 1\nduration_s: 10\n", {"'model'", "M-phys or M-paper"});
    expect_error("name: t\nmodel: M-phys\nduration_s: 10\n", {"bad.yaml", "'sigma'", "missing required key"});
    expect_error(base + "k2_true_per_s2: abc\n", {"'k2_true_per_s2'", "not a number", "abc"});
    expect_error(base + "k2_true_per_s2: .nan\n", {"'k2_true_per_s2'", "finite"});
    expect_error(base + "gyro:\n  noise_radps: -1e-5\n", {"'gyro.noise_radps'", "out of range"});
    expect_error(base + "gyro:\n  seed: -3\n", {"'gyro.seed'", "non-negative"});
    expect_error(base + "period_us: 20000.5\n", {"'period_us'", "not an integer"});
    expect_error(base + "w0_degps: [1]\n", {"'w0_degps'", "two numbers"});
    expect_error(base + "w0_degps: [1, x]\n", {"'w0_degps[1]'", "not a number"});
    expect_error(base + "w0_degps: [40, 0]\n", {"'w0_degps'", "w_max"});
    expect_error(base + "propagator: euler\n", {"'propagator'", "zoh or ode"});
    expect_error(base + "limits: 3\n", {"'limits'", "mapping"});
    expect_error(base + "duration_s: 0.001\n", {"bad.yaml", "'duration_s'", "duplicate key", "line 5"});
    expect_error("name: t\nmodel: M-phys\nsigma: 1\nduration_s: 0.001\n", {"'duration_s'", "shorter than one period"});
    expect_error("name: [unclosed\n", {"bad.yaml", "YAML syntax error"});
    expect_error("", {"bad.yaml", "empty"});
    try {
        (void)sim::load_scenario("/nonexistent/dir/s.yaml");
        EXPECT_TRUE(false);
    } catch (const sim::ScenarioError &e) {
        std::printf("  -> %s\n", e.what());
        EXPECT_TRUE(std::string(e.what()).find("/nonexistent/dir/s.yaml") != std::string::npos);
    }
}

// The rendezvous plant's section and the test conductor's commands, in flight units.
SIM_TEST(test_cw_and_commands)
{
    const sim::Scenario s = sim::parse_scenario(
        "name: r\nplant: cw\nduration_s: 1100\n"
        "cw:\n  x0: [5000, -1, 4000, -1, 4000, -1]\n  eps_c: 0.02\n"
        "  stuck_off: {thruster: 0, t_s: 10}\n"
        "  nav: {profile: nominal, seed: 3, dropouts_s: [[150, 450]]}\n"
        "commands:\n"
        "  - {t_s: 0, cmd: MODE, mode: RENDEZVOUS}\n"
        "  - {t_s: 1, cmd: IMP_START, t0_s: 10, tf_s: 1065, target_pos_m: [1.5, -2, 0.001], target_vel_mps: [0.01, 0, -0.00002]}\n"
        "  - {t_s: 900, cmd: IMP_ABORT}\n",
        "r.yaml");
    EXPECT_TRUE(s.plant == "cw");
    EXPECT_EQ_INT(s.period_us, 100000);                         // the valve tick default
    EXPECT_TRUE(s.fsw.table == "imp_default");
    EXPECT_NEAR(s.cw.eps_c, 0.02, 0.0);
    EXPECT_EQ_INT(s.cw.stuck_off_j, 0);
    EXPECT_NEAR(s.cw.nav.sigma_p_m, 0.1, 0.0);                  // the nominal profile, spec 50 §2.5
    EXPECT_NEAR(s.cw.nav.sigma_v_mps, 1e-3, 0.0);
    EXPECT_EQ_INT(s.cw.nav.dropouts_s.size(), 1);
    EXPECT_EQ_INT(s.commands.size(), 3);
    EXPECT_EQ_INT(s.commands[0].cmd, 1);
    EXPECT_EQ_INT(s.commands[0].args[0], 4);
    EXPECT_EQ_INT(s.commands[1].cmd, 2);
    EXPECT_EQ_INT(s.commands[1].args[0], 100);                  // 10 s / 0.1 s
    EXPECT_EQ_INT(s.commands[1].args[1], 10650);
    EXPECT_EQ_INT(s.commands[1].args[2], 1500);                 // mm
    EXPECT_EQ_INT(s.commands[1].args[3], -2000);
    EXPECT_EQ_INT(s.commands[1].args[4], 1);
    EXPECT_EQ_INT(s.commands[1].args[5], 1000);                 // 10 um/s
    EXPECT_EQ_INT(s.commands[1].args[7], -2);
    EXPECT_EQ_INT(s.commands[2].cmd, 3);
    expect_error("name: r\nplant: cw\nduration_s: 10\nsigma: 1\n", {"'sigma'", "not a key of plant: cw"});
    expect_error("name: r\nplant: cw\nduration_s: 10\ncw: {nav: {profile: perfect}}\n", {"cw.nav.profile"});
    expect_error("name: r\nplant: cw\nduration_s: 10\ncw: {nav: {f_hz: 3}}\n", {"whole number of fsw periods"});
    expect_error("name: r\nplant: cw\nduration_s: 10\ncommands: [{t_s: 5, cmd: MODE, mode: X}]\n", {"commands[0].mode"});
    expect_error("name: r\nplant: cw\nduration_s: 10\ncommands: [{t_s: 5, cmd: IMP_ABORT}, {t_s: 1, cmd: IMP_ABORT}]\n",
                 {"time order"});
    expect_error("name: r\nplant: cw\nduration_s: 10\ncommands: [{t_s: 5, cmd: FIRE}]\n", {"unknown command"});
    expect_error(std::string(kMinimal) + "cw: {eps_c: 0.1}\n", {"only for plant: cw"});
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_shipped_scenarios),
        cmocka_unit_test(test_scenario_errors),
        cmocka_unit_test(test_cw_and_commands),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
