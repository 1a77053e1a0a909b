// The scenario core (sim/scenario): what every mission's scenario has — the mission key, the
// flight table by name or file, link and sensor faults, lock-step timing, the test conductor's
// MODE commands — and clear errors that name the file and the key. The missions' own keys are
// tested in tests/<module> (test_obs_scenario, test_imp_scenario).
#include <algorithm>
#include <string>
#include <vector>

#include "scenario/scenario.hpp"
#include "scenario_test.hpp"
#include "sim_test.hpp"

namespace {

// Every registered mission accepts this with nothing else (its defaults fill the rest) — the
// sail needs its model identity, which the observer section requires.
std::string minimal(const std::string &mission, const std::string &duration_s = "10")
{
    std::string s = "name: t\nmission: " + mission + "\nduration_s: " + duration_s + "\n";
    if (mission == "detumble") {
        s += "model: M-phys\nsigma: 1\n";
    }
    return s;
}

std::string lower(const std::string &m)
{
    std::string low = m;
    for (char &c : low) { c = static_cast<char>(c + ((c >= 'A' && c <= 'Z') ? 32 : 0)); }
    return low;
}

// The fragments plus the names of every mission of this build (as the scenario writes them).
std::vector<std::string> with_missions(std::vector<std::string> fragments)
{
    for (const std::string &m : sim::mission_names()) { fragments.push_back(lower(m)); }
    return fragments;
}

}  // namespace

SIM_TEST(test_core_keys)
{
    for (const std::string &m : sim::mission_names()) {
        const sim::Scenario s = sim::parse_scenario(minimal(lower(m)) +
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
        EXPECT_EQ_INT(s.commands[0].cmd, 1);                    // fsw_cmd_v2_t CMD_MODE
        EXPECT_EQ_INT(s.commands[0].args[0], 1);                // STANDBY
        EXPECT_TRUE(s.commands[1].args[0] != 0 && s.commands[1].args[0] != 1 && s.commands[1].args[0] != 3);   // its own
        // A copy of a scenario owns its own mission part.
        sim::Scenario c = s;
        EXPECT_TRUE(!c.part.empty());
    }
}

// The core's checks and messages, with every mission of this build in turn as the vehicle: a
// shared test names no mission, because FSW_MISSIONS may configure any subset of them.
SIM_TEST(test_core_errors)
{
    EXPECT_TRUE(!sim::mission_names().empty());
    expect_scenario_error("name: t\nduration_s: 10\n", with_missions({"bad.yaml", "'mission'", "missing required key"}));
    expect_scenario_error("name: t\nmission: orbit\nduration_s: 10\n", with_missions({"'mission'", "unknown mission 'orbit'"}));
    for (const std::string &m : sim::mission_names()) {
        std::printf("mission %s\n", m.c_str());
        const std::string base = minimal(lower(m));
        const std::vector<std::string> tables = sim::mission_section(m).tables();
        EXPECT_TRUE(!tables.empty());
        const std::string line = "line " + std::to_string(std::count(base.begin(), base.end(), '\n') + 1);
        expect_scenario_error(base + "dt: 0.02\n", {"bad.yaml", "'dt'", "unknown key"});
        expect_scenario_error(base + "period_us: 20000.5\n", {"'period_us'", "not an integer"});
        expect_scenario_error(base + "duration_s: 0.001\n", {"bad.yaml", "'duration_s'", "duplicate key", line});
        // 0.4 ms rounds to zero steps at every period a table allows (>= 1 ms; n_steps rounds half up)
        expect_scenario_error(minimal(lower(m), "0.0004"), {"'duration_s'", "shorter than one period"});
        std::vector<std::string> unknown_table{"'fsw.table'", "unknown " + m + " table 'no_such_table'"};
        unknown_table.insert(unknown_table.end(), tables.begin(), tables.end());   // the valid ones listed
        expect_scenario_error(base + "fsw: {table: no_such_table}\n", unknown_table);
        expect_scenario_error(base + "fsw: {table_file: ''}\n", {"'fsw.table_file'", "must name"});
        expect_scenario_error(base + "fsw: {table: " + tables.front() + ", table_file: t.bin}\n",
                              {"'fsw.table'", "cannot be combined with fsw.table_file"});
        expect_scenario_error(base + "faults: {drop_ppm: 2000000}\n", {"'faults.drop_ppm'", "out of range"});
        expect_scenario_error(base + "faults: {nan_channel: 16}\n", {"'faults.nan_channel'", "out of range"});
        expect_scenario_error(base + "faults: {gyro_nan_s: [1, 2]}\n", {"'faults.gyro_nan_s'", "unknown key"});
        expect_scenario_error(base + "lockstep: {retx_max: -1}\n", {"'lockstep.retx_max'", "out of range"});
        expect_scenario_error(base + "commands: [{t_s: 5, cmd: MODE, mode: X}]\n", {"commands[0].mode", "STANDBY"});
        expect_scenario_error(base + "commands: [{t_s: 5, cmd: MODE, mode: SAFE}, {t_s: 1, cmd: MODE, mode: SAFE}]\n",
                              {"time order"});
        expect_scenario_error(base + "commands: [{t_s: 5, cmd: FIRE}]\n", {"unknown command 'FIRE'", m});
        expect_scenario_error(base + "commands: [{t_s: 5}]\n", {"commands[0]", "needs t_s and cmd"});
    }
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
