// The RESPIN scenario section (sim/respin/respin_section.cpp): the shipped scenario reads,
// and every bad key or value fails naming the file, the key and the reason.
#include <string>

#include "respin/respin_section.hpp"
#include "scenario_test.hpp"

namespace {
const char *const kMinimal = "name: t\nmission: respin\nduration_s: 10\n";
}

SIM_TEST(shipped_scenario_reads)
{
    const sim::Scenario s = sim::load_scenario(SCENARIO_DIR "/respin_nominal.yaml");
    EXPECT_TRUE(s.mission == "RESPIN");
    EXPECT_EQ_INT(s.period_us, 100000);
    EXPECT_TRUE(s.fsw.table == "rsp_default");
    const sim::RespinSetup &b = s.mission_part<sim::RespinScenario>().body;
    EXPECT_NEAR(b.inertia_kgm2, 10.0, 0.0);
    EXPECT_NEAR(b.w0_radps, 0.2, 0.0);
    EXPECT_EQ_INT(b.gyro_seed, 1);
}

SIM_TEST(bad_values_are_named)
{
    const std::string base = kMinimal;
    expect_scenario_error(base + "respin: {inertia: 3}\n", {"bad.yaml", "'respin.inertia'", "unknown key"});
    expect_scenario_error(base + "respin: {inertia_kgm2: 0}\n", {"'respin.inertia_kgm2'", "out of range"});
    expect_scenario_error(base + "respin: {gyro: {seed: -1}}\n", {"'respin.gyro.seed'"});
    expect_scenario_error(base + "plant: sail\n", {"'plant'", "flies plant: respin"});
    expect_scenario_error(base + "fsw: {table: nope}\n", {"'fsw.table'", "rsp_default"});
}

int main()
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(shipped_scenario_reads), cmocka_unit_test(bad_values_are_named)};
    return cmocka_run_group_tests_name("respin_scenario", tests, nullptr, nullptr);
}
