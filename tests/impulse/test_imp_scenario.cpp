// The RENDEZVOUS scenario section (sim/impulse/impulse_section.cpp) and its telecommands in
// flight units (arguments converted by the interface description, fsw/impulse/imp_iface.py).
#include <string>

#include "impulse/impulse_section.hpp"
#include "scenario/scenario.hpp"
#include "scenario_test.hpp"
#include "sim_test.hpp"

extern "C" {
#include "fsw_exec.h"
}

SIM_TEST(test_cw_and_commands)
{
    const sim::Scenario s = sim::parse_scenario(
        "name: r\nmission: rendezvous\nduration_s: 1100\n"
        "cw:\n  x0: [5000, -1, 4000, -1, 4000, -1]\n  eps_c: 0.02\n"
        "  stuck_off: {thruster: 0, t_s: 10}\n"
        "  nav: {profile: nominal, seed: 3, dropouts_s: [[150, 450]]}\n"
        "fsw: {cal_enable: 0}\n"
        "commands:\n"
        "  - {t_s: 0, cmd: MODE, mode: RENDEZVOUS}\n"
        "  - {t_s: 1, cmd: IMP_START, t0_s: 10, tf_s: 1065, target_pos_m: [1.5, -2, 0.001], target_vel_mps: [0.01, 0, -0.00002]}\n"
        "  - {t_s: 900, cmd: IMP_ABORT}\n",
        "r.yaml");
    const sim::CwScenario &m = s.mission_part<sim::CwScenario>();
    EXPECT_TRUE(s.plant == "cw");
    EXPECT_EQ_INT(s.period_us, 100000);                         // the valve tick default
    EXPECT_TRUE(s.fsw.table == "imp_default");
    EXPECT_EQ_INT(m.cal_enable, 0);
    EXPECT_EQ_INT(sim::impulse_boot_table(s).cal_enable, 0);
    EXPECT_NEAR(m.cw.eps_c, 0.02, 0.0);
    EXPECT_EQ_INT(m.cw.stuck_off_j, 0);
    EXPECT_NEAR(m.cw.nav.sigma_p_m, 0.1, 0.0);                  // the nominal profile, spec 50 §2.5
    EXPECT_NEAR(m.cw.nav.sigma_v_mps, 1e-3, 0.0);
    EXPECT_EQ_INT(m.cw.nav.dropouts_s.size(), 1);
    EXPECT_EQ_INT(s.commands.size(), 3);
    EXPECT_EQ_INT(s.commands[0].cmd, 1);
    EXPECT_EQ_INT(s.commands[0].args[0], FSW_MODE_RENDEZVOUS);
    EXPECT_EQ_INT(s.commands[1].cmd, FSW_TC_ID(FSW_MISSION_RENDEZVOUS, IMP_CMD_START));
    EXPECT_EQ_INT(s.commands[1].args[0], 100);                  // 10 s / 0.1 s
    EXPECT_EQ_INT(s.commands[1].args[1], 10650);
    EXPECT_EQ_INT(s.commands[1].args[2], 1500);                 // mm
    EXPECT_EQ_INT(s.commands[1].args[3], -2000);
    EXPECT_EQ_INT(s.commands[1].args[4], 1);
    EXPECT_EQ_INT(s.commands[1].args[5], 1000);                 // 10 um/s
    EXPECT_EQ_INT(s.commands[1].args[7], -2);
    EXPECT_EQ_INT(s.commands[2].cmd, FSW_TC_ID(FSW_MISSION_RENDEZVOUS, IMP_CMD_ABORT));
    const std::string r = "name: r\nmission: rendezvous\nduration_s: 10\n";
    expect_scenario_error(r + "sigma: 1\n", {"'sigma'", "unknown key"});
    expect_scenario_error(r + "plant: sail\n", {"'plant'", "plant: cw"});
    expect_scenario_error(r + "period_us: 500\n", {"'period_us'", "1000 us"});
    expect_scenario_error(r + "cw: {nav: {profile: perfect}}\n", {"cw.nav.profile", "ideal, nominal"});
    expect_scenario_error(r + "cw: {nav: {f_hz: 3}}\n", {"whole number of fsw periods"});
    expect_scenario_error(r + "cw: {x0: [1, 2]}\n", {"'cw.x0'", "[x, x', y, y', z, z']"});
    expect_scenario_error(r + "fsw: {cal_enable: 2}\n", {"'fsw.cal_enable'", "out of range"});
    expect_scenario_error(r + "commands: [{t_s: 5, cmd: IMP_START, t0_s: 1}]\n", {"IMP_START needs tf_s"});
    expect_scenario_error(r + "commands: [{t_s: 5, cmd: IMP_START, t0_s: 1, tf_s: 2, target_pos_m: [1, 2]}]\n",
                          {"target_pos_m", "list of 3"});
    expect_scenario_error(r + "commands: [{t_s: 5, cmd: IMP_ABORT, t0_s: 1}]\n", {"'commands[0].t0_s'", "unknown key"});
    expect_scenario_error(r + "commands: [{t_s: 5, cmd: IMP_CLEAR}]\n", {"unknown command 'IMP_CLEAR'", "IMP_CLEAR_FAULTS"});
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cw_and_commands),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
