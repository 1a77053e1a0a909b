// The HOLD scenario section (sim/pd/pd_section.cpp): the shipped scenarios read, and every bad
// key or value fails naming the file, the key and the reason.
#include <string>

#include "pd/pd_section.hpp"
#include "scenario_test.hpp"

namespace {
const char *const kMinimal = "name: t\nmission: hold\nduration_s: 10\n";
}

SIM_TEST(shipped_scenarios_read)
{
    const sim::Scenario s = sim::load_scenario(SCENARIO_DIR "/pd_nominal.yaml");
    EXPECT_TRUE(s.mission == "HOLD");
    EXPECT_EQ_INT(s.period_us, 250000);
    EXPECT_NEAR(s.duration_s, 1200.0, 0.0);
    EXPECT_TRUE(s.fsw.table == "pd_default");
    const sim::PdSetup &b = s.mission_part<sim::PdScenario>().body;
    EXPECT_TRUE(b.kind == sim::PdPlantKind::Single);
    EXPECT_NEAR(b.f_hz, 0.03, 0.0);
    EXPECT_NEAR(b.x0_rad[0], 0.0, 0.0);
    EXPECT_NEAR(b.x0_rad[2], 0.017, 0.0);
    EXPECT_NEAR(b.noise_rad[1], 2e-6, 0.0);
    EXPECT_EQ_INT(b.sensor_seed, 1);
    EXPECT_NEAR(b.act_max_nm, 2.0, 0.0);
    EXPECT_EQ_INT(sim::mission_section("HOLD").noise_seed(s), 1);

    const sim::Scenario c = sim::load_scenario(SCENARIO_DIR "/pd_coupled.yaml");
    const sim::PdSetup &bc = c.mission_part<sim::PdScenario>().body;
    EXPECT_TRUE(bc.kind == sim::PdPlantKind::Coupled);
    EXPECT_EQ_INT(bc.coupling_sign, 1);
    EXPECT_NEAR(c.duration_s, 1200.0, 0.0);
    for (double x : bc.x0_rad) {
        EXPECT_NEAR(x, 0.017, 0.0);
    }
}

SIM_TEST(every_key_reads)
{
    const sim::Scenario s = sim::parse_scenario(
        std::string(kMinimal) +
            "pd:\n"
            "  plant: coupled\n"
            "  coupling_sign: -1\n"
            "  scale: {coupling: 1.25, ix: 0.9, h: 1.1}\n"
            "  latency_samples: 1\n"
            "  f_hz: 0.05\n"
            "  f_steps: [{t_s: 1200, f_hz: 0.02}, {t_s: 1500.5, f_hz: 0.03}]\n"
            "  x0_rad: [0.01, -0.02, 0.017]\n"
            "  kicks: [{t_s: 1300, dx_rad: [0, 0, 0.017]}]\n"
            "  sensor: {noise_rad: [1.0e-6, 2.0e-6, 3.0e-6], bias_rad: [1.0e-5, 0, -1.0e-5], seed: 9,\n"
            "           frozen: [{t0_s: 5, t1_s: 6, channel: 2}], offset: [{t0_s: 1, t1_s: 2, channel: 0, rad: 0.7}]}\n"
            "  actuator: {max_nm: 1.5}\n",
        "all.yaml");
    const sim::PdSetup &b = s.mission_part<sim::PdScenario>().body;
    EXPECT_TRUE(b.kind == sim::PdPlantKind::Coupled);
    EXPECT_EQ_INT(b.coupling_sign, -1);
    EXPECT_NEAR(b.scale_coupling, 1.25, 0.0);
    EXPECT_NEAR(b.scale_ix, 0.9, 0.0);
    EXPECT_NEAR(b.scale_h, 1.1, 0.0);
    EXPECT_EQ_INT(b.latency_samples, 1);
    EXPECT_NEAR(b.f_hz, 0.05, 0.0);
    EXPECT_EQ_INT(b.f_steps.size(), 2);
    EXPECT_NEAR(b.f_steps[1].t_s, 1500.5, 0.0);
    EXPECT_NEAR(b.x0_rad[1], -0.02, 0.0);
    EXPECT_EQ_INT(b.kicks.size(), 1);
    EXPECT_NEAR(b.kicks[0].dx_rad[2], 0.017, 0.0);
    EXPECT_NEAR(b.noise_rad[2], 3e-6, 0.0);
    EXPECT_NEAR(b.bias_rad[2], -1e-5, 0.0);
    EXPECT_EQ_INT(b.sensor_seed, 9);
    EXPECT_EQ_INT(b.frozen.size(), 1);
    EXPECT_EQ_INT(b.frozen[0].channel, 2);
    EXPECT_NEAR(b.offset[0].rad, 0.7, 0.0);
    EXPECT_NEAR(b.act_max_nm, 1.5, 0.0);
    // A scalar noise applies to the three channels.
    const sim::Scenario n = sim::parse_scenario(std::string(kMinimal) + "pd: {sensor: {noise_rad: 4.0e-6}}\n", "n.yaml");
    for (double v : n.mission_part<sim::PdScenario>().body.noise_rad) {
        EXPECT_NEAR(v, 4e-6, 0.0);
    }
}

SIM_TEST(bad_values_are_named)
{
    const std::string base = kMinimal;
    expect_scenario_error(base + "pd: {inertia_kgm2: 3}\n", {"bad.yaml", "'pd.inertia_kgm2'", "unknown key"});
    expect_scenario_error(base + "pd: {plant: triple}\n", {"'pd.plant'", "single"});
    expect_scenario_error(base + "pd: {f_hz: 0.3}\n", {"'pd.f_hz'", "out of range"});
    expect_scenario_error(base + "pd: {f_hz: 0.001}\n", {"'pd.f_hz'", "out of range"});
    expect_scenario_error(base + "pd: {coupling_sign: -1}\n", {"'pd.coupling_sign'", "only with pd.plant: coupled"});
    expect_scenario_error(base + "pd: {plant: coupled, coupling_sign: 0}\n", {"'pd.coupling_sign'", "1 or -1"});
    expect_scenario_error(base + "pd: {plant: coupled, coupling_sign: 2}\n", {"'pd.coupling_sign'", "out of range"});
    expect_scenario_error(base + "pd: {latency_samples: 2}\n", {"'pd.latency_samples'", "out of range"});
    expect_scenario_error(base + "pd: {scale: {h: 3}}\n", {"'pd.scale.h'", "out of range"});
    expect_scenario_error(base + "pd: {scale: {mass: 1}}\n", {"'pd.scale.mass'", "unknown key"});
    expect_scenario_error(base + "pd: {scale: {coupling: 1.9, ix: 0.5}}\n", {"'pd.scale'", "positive definite"});
    expect_scenario_error(base + "pd: {plant: coupled, scale: {coupling: 2.0, ix: 0.5}}\n", {"'pd.scale'", "positive definite"});
    expect_scenario_error(base + "pd: {f_steps: [{t_s: 10, f_hz: 0.02}, {t_s: 10, f_hz: 0.03}]}\n",
                          {"'pd.f_steps[1].t_s'", "increasing"});
    expect_scenario_error(base + "pd: {f_steps: [{t_s: 10}]}\n", {"'pd.f_steps[0].f_hz'", "missing"});
    expect_scenario_error(base + "pd: {f_steps: [{t_s: 10, f_hz: 0.5}]}\n", {"'pd.f_steps[0].f_hz'", "out of range"});
    expect_scenario_error(base + "pd: {f_steps: {t_s: 10, f_hz: 0.05}}\n", {"'pd.f_steps'", "list"});
    expect_scenario_error(base + "pd: {x0_rad: [0, 0, 2]}\n", {"'pd.x0_rad[2]'", "out of range"});
    expect_scenario_error(base + "pd: {x0_rad: [0, 0]}\n", {"'pd.x0_rad'", "three numbers"});
    expect_scenario_error(base + "pd: {kicks: [{t_s: 5, dx_rad: [0, 0]}]}\n", {"'pd.kicks[0].dx_rad'", "three numbers"});
    expect_scenario_error(base + "pd: {kicks: [{t_s: 5, dx: [0, 0, 1]}]}\n", {"'pd.kicks[0].dx'", "unknown key"});
    expect_scenario_error(base + "pd: {kicks: [{t_s: 5, dx_rad: [0, 0, 0.1]}, {t_s: 4, dx_rad: [0, 0, 0.1]}]}\n",
                          {"'pd.kicks[1].t_s'", "time order"});
    expect_scenario_error(base + "pd: {sensor: {noise_rad: -1.0e-6}}\n", {"'pd.sensor.noise_rad'", "out of range"});
    expect_scenario_error(base + "pd: {sensor: {noise_rad: [1.0e-6, 1.0e-6]}}\n", {"'pd.sensor.noise_rad'", "three"});
    expect_scenario_error(base + "pd: {sensor: {bias_rad: [0, 0, 0.5]}}\n", {"'pd.sensor.bias_rad[2]'", "out of range"});
    expect_scenario_error(base + "pd: {sensor: {seed: -1}}\n", {"'pd.sensor.seed'"});
    expect_scenario_error(base + "pd: {sensor: {frozen: [{t0_s: 1, t1_s: 2, channel: 3}]}}\n",
                          {"'pd.sensor.frozen[0].channel'", "out of range"});
    expect_scenario_error(base + "pd: {sensor: {frozen: [{t0_s: 1, t1_s: 2}]}}\n",
                          {"'pd.sensor.frozen[0].channel'", "missing"});
    expect_scenario_error(base + "pd: {sensor: {offset: [{t0_s: 2, t1_s: 1, channel: 0, rad: 1}]}}\n",
                          {"'pd.sensor.offset[0].t1_s'", "after t0_s"});
    expect_scenario_error(base + "pd: {sensor: {offset: [{t0_s: 1, t1_s: 2, channel: 0, rad: 20}]}}\n",
                          {"'pd.sensor.offset[0].rad'", "out of range"});
    expect_scenario_error(base + "pd: {sensor: {gain: 1}}\n", {"'pd.sensor.gain'", "unknown key"});
    expect_scenario_error(base + "pd: {actuator: {max_nm: 0}}\n", {"'pd.actuator.max_nm'", "out of range"});
    expect_scenario_error(base + "period_us: 100000\n", {"'period_us'", "250000"});
    expect_scenario_error(base + "plant: sail\n", {"'plant'", "flies plant: pd"});
    expect_scenario_error(base + "fsw: {table: nope}\n", {"'fsw.table'", "pd_default"});
}

int main()
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(shipped_scenarios_read), cmocka_unit_test(every_key_reads),
                                       cmocka_unit_test(bad_values_are_named)};
    return cmocka_run_group_tests_name("pd_scenario", tests, nullptr, nullptr);
}
