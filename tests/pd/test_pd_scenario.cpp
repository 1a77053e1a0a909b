// The HOLD scenario section (sim/pd/pd_section.cpp): the shipped scenario reads,
// and every bad key or value fails naming the file, the key and the reason.
#include <string>

#include "pd/pd_section.hpp"
#include "scenario_test.hpp"

namespace {
const char *const kMinimal = "name: t\nmission: hold\nduration_s: 10\n";
}

SIM_TEST(shipped_scenario_reads)
{
    const sim::Scenario s = sim::load_scenario(SCENARIO_DIR "/pd_nominal.yaml");
    EXPECT_TRUE(s.mission == "HOLD");
    EXPECT_EQ_INT(s.period_us, 100000);
    EXPECT_TRUE(s.fsw.table == "pd_default");
    const sim::PdSetup &b = s.mission_part<sim::PdScenario>().body;
    EXPECT_NEAR(b.inertia_kgm2, 10.0, 0.0);
    EXPECT_NEAR(b.w0_radps, 0.2, 0.0);
    EXPECT_EQ_INT(b.gyro_seed, 1);
}

SIM_TEST(bad_values_are_named)
{
    const std::string base = kMinimal;
    expect_scenario_error(base + "pd: {inertia: 3}\n", {"bad.yaml", "'pd.inertia'", "unknown key"});
    expect_scenario_error(base + "pd: {inertia_kgm2: 0}\n", {"'pd.inertia_kgm2'", "out of range"});
    expect_scenario_error(base + "pd: {gyro: {seed: -1}}\n", {"'pd.gyro.seed'"});
    expect_scenario_error(base + "plant: sail\n", {"'plant'", "flies plant: pd"});
    expect_scenario_error(base + "fsw: {table: nope}\n", {"'fsw.table'", "pd_default"});
}

int main()
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(shipped_scenario_reads), cmocka_unit_test(bad_values_are_named)};
    return cmocka_run_group_tests_name("pd_scenario", tests, nullptr, nullptr);
}
