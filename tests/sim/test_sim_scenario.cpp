// The scenario core (sim/scenario): what every mission's scenario has — the mission key, the
// flight table by name or file, link and sensor faults, lock-step timing, the test conductor's
// MODE commands — and clear errors that name the file and the key. The missions' own keys are
// tested in tests/<module> (test_obs_scenario, test_imp_scenario).
#include <string>

#include "scenario/scenario.hpp"
#include "scenario_test.hpp"
#include "sim_test.hpp"

namespace {

// Every registered mission accepts this with nothing else (its defaults fill the rest) — the
// sail needs its model identity, which the observer section requires.
std::string minimal(const std::string &mission)
{
    std::string s = "name: t\nmission: " + mission + "\nduration_s: 10\n";
    if (mission == "detumble") {
        s += "model: M-phys\nsigma: 1\n";
    }
    return s;
}

}  // namespace

SIM_TEST(test_core_keys)
{
    for (const std::string &m : sim::mission_names()) {
        std::string low = m;
        for (char &c : low) { c = static_cast<char>(c + ((c >= 'A' && c <= 'Z') ? 32 : 0)); }
        const sim::Scenario s = sim::parse_scenario(minimal(low) +
                                                        "fsw: {table_file: img.bin}\n"
                                                        "faults: {seed: 9, drop_ppm: 1000, nan_s: [1, 2], nan_channel: 1}\n"
                                                        "lockstep: {retx_ms: 50, retx_max: 3}\n"
                                                        "commands:\n  - {t_s: 1, cmd: MODE, mode: STANDBY}\n"
                                                        "  - {t_s: 2, cmd: MODE, mode: " + m + "}\n",
                                                    "core.yaml");
        EXPECT_TRUE(s.mission == m);
        EXPECT_TRUE(!s.part.empty());
        EXPECT_TRUE(s.period_us > 0u);                          // the mission's default period
        EXPECT_TRUE(!s.fsw.table.empty());                      // its default boot table
        EXPECT_TRUE(s.fsw.table_file == "img.bin");
        EXPECT_EQ_INT(s.faults.seed, 9);
        EXPECT_EQ_INT(s.faults.drop_ppm, 1000);
        EXPECT_EQ_INT(s.faults.nan_channel, 1);
        EXPECT_TRUE(s.faults.any());
        EXPECT_EQ_INT(s.lockstep.retx_ms, 50);
        EXPECT_EQ_INT(s.lockstep.retx_max, 3);
        EXPECT_EQ_INT(s.commands.size(), 2);
        EXPECT_EQ_INT(s.commands[0].cmd, 1);                    // fsw_cmd_t CMD_MODE
        EXPECT_EQ_INT(s.commands[0].args[0], 1);                // STANDBY
        EXPECT_TRUE(s.commands[1].args[0] != 0 && s.commands[1].args[0] != 1 && s.commands[1].args[0] != 3);   // its own
        // A copy of a scenario owns its own mission part.
        sim::Scenario c = s;
        EXPECT_TRUE(!c.part.empty());
    }
}

SIM_TEST(test_core_errors)
{
    const std::string base = minimal("detumble");
    expect_scenario_error("name: t\nduration_s: 10\n", {"bad.yaml", "'mission'", "missing required key", "detumble"});
    expect_scenario_error("name: t\nmission: orbit\nduration_s: 10\n", {"'mission'", "unknown mission 'orbit'",
                                                                         "rendezvous"});
    expect_scenario_error(base + "dt: 0.02\n", {"bad.yaml", "'dt'", "unknown key"});
    expect_scenario_error(base + "period_us: 20000.5\n", {"'period_us'", "not an integer"});
    expect_scenario_error(base + "duration_s: 0.001\n", {"bad.yaml", "'duration_s'", "duplicate key", "line 6"});
    expect_scenario_error("name: t\nmission: detumble\nmodel: M-phys\nsigma: 1\nduration_s: 0.001\n",
                          {"'duration_s'", "shorter than one period"});
    expect_scenario_error(base + "fsw: {table: obs_100hz}\n", {"'fsw.table'", "unknown DETUMBLE table", "obs_50hz_phys"});
    expect_scenario_error(base + "fsw: {table_file: ''}\n", {"'fsw.table_file'", "must name"});
    expect_scenario_error(base + "fsw: {table: obs_50hz_phys, table_file: t.bin}\n",
                          {"'fsw.table'", "cannot be combined with fsw.table_file"});
    expect_scenario_error(base + "faults: {drop_ppm: 2000000}\n", {"'faults.drop_ppm'", "out of range"});
    expect_scenario_error(base + "faults: {nan_channel: 16}\n", {"'faults.nan_channel'", "out of range"});
    expect_scenario_error(base + "faults: {gyro_nan_s: [1, 2]}\n", {"'faults.gyro_nan_s'", "unknown key"});
    expect_scenario_error(base + "lockstep: {retx_max: -1}\n", {"'lockstep.retx_max'", "out of range"});
    expect_scenario_error(base + "commands: [{t_s: 5, cmd: MODE, mode: X}]\n", {"commands[0].mode", "STANDBY"});
    expect_scenario_error(base + "commands: [{t_s: 5, cmd: MODE, mode: SAFE}, {t_s: 1, cmd: MODE, mode: SAFE}]\n",
                          {"time order"});
    expect_scenario_error(base + "commands: [{t_s: 5, cmd: FIRE}]\n", {"unknown command 'FIRE'", "DETUMBLE"});
    expect_scenario_error(base + "commands: [{t_s: 5}]\n", {"commands[0]", "needs t_s and cmd"});
    expect_scenario_error("name: [unclosed\n", {"bad.yaml", "YAML syntax error"});
    expect_scenario_error("", {"bad.yaml", "empty"});
    expect_scenario_error("- a\n- b\n", {"bad.yaml", "mapping"});
    try {
        (void)sim::load_scenario("/nonexistent/dir/s.yaml");
        EXPECT_TRUE(false);
    } catch (const sim::ScenarioError &e) {
        std::printf("  -> %s\n", e.what());
        EXPECT_TRUE(std::string(e.what()).find("/nonexistent/dir/s.yaml") != std::string::npos);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_core_keys),
        cmocka_unit_test(test_core_errors),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
