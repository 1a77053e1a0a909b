// The RELAY scenario section (sim/relay/relay_section.cpp): the shipped scenarios read with the
// source's example as defaults, and every bad key or value fails naming the file, the key and
// the reason.
#include <string>

#include "relay/relay_section.hpp"
#include "scenario_test.hpp"

namespace {
const char *const kMinimal = "name: t\nmission: relay\nduration_s: 10\n";
}

SIM_TEST(shipped_scenario_reads)
{
    const sim::Scenario s = sim::load_scenario(SCENARIO_DIR "/relay_nominal.yaml");
    EXPECT_TRUE(s.mission == "RELAY");
    EXPECT_EQ_INT(s.period_us, 1000);
    EXPECT_TRUE(s.fsw.table == "rly_default");
    const sim::RelaySetup &b = s.mission_part<sim::RelayScenario>().body;
    EXPECT_EQ_INT(b.model.n_modes, 2);
    EXPECT_NEAR(b.model.omega_radps[1], 0.755, 0.0);     // spec 20 §2.1
    EXPECT_NEAR(b.model.k[0], 0.0213, 0.0);
    EXPECT_NEAR(b.state0.xbar_rad, 4.5e-4, 0.0);
    EXPECT_NEAR(b.state0.xbardot_radps, 2.2e-5, 0.0);
    EXPECT_NEAR(b.state0.q_rad[0], 2.75e-6, 0.0);
    EXPECT_EQ_INT(b.seed, 1);
}

SIM_TEST(modes_and_options_parse)
{
    const sim::Scenario s = sim::parse_scenario(std::string(kMinimal) +
        "relay: {modes: [{omega_radps: 0.5, k: 0.01, xt0_rad: 1.0e-6}], sensor: {noise_rad: 1.0e-7, seed: 9},"
        " actuator: {scale_error: 0.01, delay_ticks: 1}}\n", "t.yaml");
    const sim::RelaySetup &b = s.mission_part<sim::RelayScenario>().body;
    EXPECT_EQ_INT(b.model.n_modes, 1);
    EXPECT_NEAR(b.model.omega_radps[0], 0.5, 0.0);
    EXPECT_NEAR(b.model.omega_radps[1], 0.0, 0.0);
    EXPECT_NEAR(b.noise_rad, 1.0e-7, 0.0);
    EXPECT_EQ_INT(b.delay_ticks, 1);
}

SIM_TEST(bad_values_are_named)
{
    const std::string base = kMinimal;
    expect_scenario_error(base + "relay: {m_u: 3}\n", {"bad.yaml", "'relay.m_u'", "unknown key"});
    expect_scenario_error(base + "relay: {m_u_radps2: 0}\n", {"'relay.m_u_radps2'", "out of range"});
    expect_scenario_error(base + "relay: {sensor: {seed: -1}}\n", {"'relay.sensor.seed'"});
    expect_scenario_error(base + "relay: {actuator: {delay_ticks: 2}}\n", {"'relay.actuator.delay_ticks'"});
    expect_scenario_error(base + "relay: {modes: [{k: 0.1}]}\n", {"'relay.modes[0].omega_radps'"});
    expect_scenario_error(base + "relay: {modes: [{omega_radps: 1}, {omega_radps: 1}, {omega_radps: 1},"
                                 " {omega_radps: 1}, {omega_radps: 1}]}\n", {"'relay.modes'", "at most 4"});
    expect_scenario_error(base + "plant: sail\n", {"'plant'", "flies plant: relay"});
    expect_scenario_error(base + "fsw: {table: nope}\n", {"'fsw.table'", "rly_default"});
}

int main()
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(shipped_scenario_reads), cmocka_unit_test(modes_and_options_parse),
                                       cmocka_unit_test(bad_values_are_named)};
    return cmocka_run_group_tests_name("relay_scenario", tests, nullptr, nullptr);
}
