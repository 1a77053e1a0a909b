// The RESPIN scenario section (sim/respin/respin_section.cpp): the shipped scenarios read, every
// key of the section parses into the setup the plant flies, and every bad key or value fails
// naming the file, the key and the reason.
#include <cmath>
#include <string>

#include "respin/respin_plant.hpp"
#include "respin/respin_section.hpp"
#include "scenario_test.hpp"

namespace {
const char *const kMinimal = "name: t\nmission: respin\nduration_s: 10\n";

void expect_nominal_setup(const sim::RespinSetup &b)
{
    EXPECT_NEAR(b.g0_nms, 300.0, 0.0);
    EXPECT_NEAR(b.g_dir[0], 0.0, 0.0);
    EXPECT_NEAR(b.g_dir[1], 0.0, 0.0);
    EXPECT_NEAR(b.g_dir[2], 1.0, 0.0);
    EXPECT_TRUE(!b.g_dir_random);
    EXPECT_NEAR(b.gyro_noise_radps, 1.0e-5, 0.0);      // spec 30 §2
    EXPECT_NEAR(b.gyro_bias_radps[1], -4.0e-6, 0.0);    // within 5e-6 per axis
    EXPECT_NEAR(b.gyro_scale_ppm[2], 100.0, 0.0);       // within 100 ppm
    EXPECT_EQ_INT(b.gyro_seed, 1);
    // Plant defaults of spec 30 §2.
    EXPECT_NEAR(b.j_kgm2[0], 2900.0, 0.0);
    EXPECT_NEAR(b.j_kgm2[1], 3600.0, 0.0);
    EXPECT_NEAR(b.j_kgm2[2], 670.0, 0.0);
    EXPECT_NEAR(b.iw_kgm2, 0.01, 0.0);
    EXPECT_NEAR(b.torque_max_nm, 0.15, 0.0);
    EXPECT_NEAR(b.h_max_nms, 5.0, 0.0);
    EXPECT_NEAR(b.coulomb_nm, 0.0, 0.0);
    EXPECT_NEAR(b.omega_max_radps, 1.0, 0.0);
    EXPECT_EQ_INT(b.n_sub, 4);
}
}  // namespace

SIM_TEST(shipped_scenarios_read)
{
    const sim::Scenario s = sim::load_scenario(SCENARIO_DIR "/respin_nominal.yaml");
    EXPECT_TRUE(s.mission == "RESPIN");
    EXPECT_EQ_INT(s.period_us, 100000);
    EXPECT_NEAR(s.duration_s, 12000.0, 0.0);
    EXPECT_TRUE(s.fsw.table == "rsp_default");
    expect_nominal_setup(s.mission_part<sim::RespinScenario>().body);

    const sim::Scenario p = sim::load_scenario(SCENARIO_DIR "/respin_printed.yaml");
    EXPECT_TRUE(p.fsw.table == "rsp_printed");
    EXPECT_NEAR(p.duration_s, 12000.0, 0.0);
    expect_nominal_setup(p.mission_part<sim::RespinScenario>().body);
    EXPECT_EQ_INT(sim::respin_boot_table(p.fsw.table).mode, RSP_MODE_PRINTED);
    EXPECT_EQ_INT(sim::respin_boot_table(s.fsw.table).mode, RSP_MODE_NEAREST);

    const sim::Scenario q = sim::load_scenario(SCENARIO_DIR "/respin_short.yaml");
    EXPECT_TRUE(q.duration_s <= 600.0);
    expect_nominal_setup(q.mission_part<sim::RespinScenario>().body);
}

SIM_TEST(every_key_round_trips)
{
    const sim::Scenario s = sim::parse_scenario(std::string(kMinimal) +
        "period_us: 500000\nfsw: {table: rsp_ts05}\n"
        "respin: {g0_nms: 40.5, g_dir: [3, 0, -4], inertia_kgm2: [2800, 3500, 700], omega_max_radps: 0.9,"
        " n_sub: 8,\n"
        "  wheel: {iw_kgm2: 0.02, torque_max_nm: 0.1, h_max_nms: 4.0, coulomb_nm: 1.0e-3, viscous_nmps: 2.0e-6},\n"
        "  gyro: {noise_radps: 2.0e-5, bias_radps: [1.0e-6, 2.0e-6, -3.0e-6], scale_ppm: [10, -20, 30], seed: 42}}\n",
        "t.yaml");
    EXPECT_EQ_INT(s.period_us, 500000);
    EXPECT_TRUE(s.fsw.table == "rsp_ts05");
    const sim::RespinSetup &b = s.mission_part<sim::RespinScenario>().body;
    EXPECT_NEAR(b.g0_nms, 40.5, 0.0);
    EXPECT_NEAR(b.g_dir[0], 0.6, 1e-15);    // normalised
    EXPECT_NEAR(b.g_dir[1], 0.0, 0.0);
    EXPECT_NEAR(b.g_dir[2], -0.8, 1e-15);
    EXPECT_NEAR(b.j_kgm2[0], 2800.0, 0.0);
    EXPECT_NEAR(b.j_kgm2[2], 700.0, 0.0);
    EXPECT_NEAR(b.omega_max_radps, 0.9, 0.0);
    EXPECT_EQ_INT(b.n_sub, 8);
    EXPECT_NEAR(b.iw_kgm2, 0.02, 0.0);
    EXPECT_NEAR(b.torque_max_nm, 0.1, 0.0);
    EXPECT_NEAR(b.h_max_nms, 4.0, 0.0);
    EXPECT_NEAR(b.coulomb_nm, 1.0e-3, 0.0);
    EXPECT_NEAR(b.viscous_nmps, 2.0e-6, 0.0);
    EXPECT_NEAR(b.gyro_noise_radps, 2.0e-5, 0.0);
    EXPECT_NEAR(b.gyro_bias_radps[2], -3.0e-6, 0.0);
    EXPECT_NEAR(b.gyro_scale_ppm[1], -20.0, 0.0);
    EXPECT_EQ_INT(b.gyro_seed, 42);
    EXPECT_EQ_INT(sim::respin_section().noise_seed(s), 42);

    EXPECT_TRUE(!b.gyrodines);   // the default actuator: wheels

    // The plant starts where the setup says: G(0) = g0 g_dir, H(0) = 0; all 14 sensor channels,
    // the gimbal channels at the null configuration's counts (a locked cluster), rotors at 0.
    const std::unique_ptr<sim::Plant> pl = sim::make_plant(s);
    const std::vector<double> t = pl->truth();
    EXPECT_TRUE(t.size() == pl->truth_names().size());
    EXPECT_NEAR(t[6], 40.5 * 0.6, 1e-12);
    EXPECT_NEAR(t[8], -40.5 * 0.8, 1e-12);
    EXPECT_NEAR(t[3], 0.0, 0.0);
    const sim::SensorFrame f = pl->sense();
    EXPECT_EQ_INT(f.n_ch, 14);
    EXPECT_EQ_INT(f.cnt[6], 131072);
    EXPECT_EQ_INT(f.cnt[7], 131072);
    EXPECT_EQ_INT(f.cnt[8], 917504);
    EXPECT_EQ_INT(f.cnt[9], 917504);
    for (std::size_t i = 6; i < 14u; ++i) {
        EXPECT_EQ_INT(f.status[i], 0);
        if (i >= 10u) {
            EXPECT_EQ_INT(f.cnt[i], 0);
        }
    }

    // A seeded random direction: unit length, the same for the same seed, another for another.
    const sim::Scenario r1 = sim::parse_scenario(std::string(kMinimal) + "respin: {g_dir_seed: 5}\n", "t.yaml");
    const sim::Scenario r2 = sim::parse_scenario(std::string(kMinimal) + "respin: {g_dir_seed: 5}\n", "t.yaml");
    const sim::Scenario r3 = sim::parse_scenario(std::string(kMinimal) + "respin: {g_dir_seed: 6}\n", "t.yaml");
    const std::array<double, 3> d1 = sim::respin_initial_direction(r1.mission_part<sim::RespinScenario>().body);
    const std::array<double, 3> d2 = sim::respin_initial_direction(r2.mission_part<sim::RespinScenario>().body);
    const std::array<double, 3> d3 = sim::respin_initial_direction(r3.mission_part<sim::RespinScenario>().body);
    EXPECT_NEAR(std::sqrt(d1[0] * d1[0] + d1[1] * d1[1] + d1[2] * d1[2]), 1.0, 1e-15);
    EXPECT_TRUE(d1 == d2);
    EXPECT_TRUE(!(d1 == d3));
}

SIM_TEST(bad_values_are_named)
{
    const std::string base = kMinimal;
    expect_scenario_error(base + "respin: {g0: 3}\n", {"bad.yaml", "'respin.g0'", "unknown key"});
    expect_scenario_error(base + "respin: {g0_nms: 0}\n", {"'respin.g0_nms'", "out of range"});
    expect_scenario_error(base + "respin: {g_dir: [0, 0, 0]}\n", {"'respin.g_dir'", "zero vector"});
    expect_scenario_error(base + "respin: {g_dir: [0, 1]}\n", {"'respin.g_dir'"});
    expect_scenario_error(base + "respin: {g_dir: [0, 0, 1], g_dir_seed: 3}\n", {"'respin.g_dir_seed'", "not both"});
    expect_scenario_error(base + "respin: {n_sub: 0}\n", {"'respin.n_sub'"});
    expect_scenario_error(base + "respin: {wheel: {friction: 1}}\n", {"'respin.wheel.friction'", "unknown key"});
    expect_scenario_error(base + "respin: {gyro: {seed: -1}}\n", {"'respin.gyro.seed'"});
    expect_scenario_error(base + "respin: {gyro: {noise_radps: -1.0e-5}}\n", {"'respin.gyro.noise_radps'"});
    expect_scenario_error(base + "plant: sail\n", {"'plant'", "flies plant: respin"});
    expect_scenario_error(base + "fsw: {table: nope}\n", {"'fsw.table'", "rsp_default"});
    expect_scenario_error(base + "respin: {elastic: E3}\n", {"'respin.elastic'"});
    // E1's fastest free-free mode is 8.2 rad/s: at Ts = 0.5 s RK4 needs h <= 0.25 / 8.2, n_sub >= 17
    expect_scenario_error(base + "period_us: 500000\nrespin: {elastic: E1}\n", {"'respin.n_sub'", "need n_sub >= 17"});
}

// The gyrodine keys (respin.actuator, respin.cmg): every key round-trips into the setup and the
// model, the plant publishes the superset of channels, bad values are named.
SIM_TEST(gyrodine_keys)
{
    const std::string base = std::string(kMinimal) + "fsw: {table: rsp_cmg}\n";
    const sim::Scenario s = sim::parse_scenario(base +
        "respin: {actuator: gyrodines, elastic: E1,\n"
        "  cmg: {hg_nms: 6.5, umax_radps: 0.15, beta0_rad: [0.1, -0.2, 0.3, 6.0], rotor_speed_radps: 550,\n"
        "        rotor_fault: {t_s: 300, index: 2, scale: 0.97}}}\n",
        "t.yaml");
    const sim::RespinSetup &b = s.mission_part<sim::RespinScenario>().body;
    EXPECT_TRUE(b.gyrodines);
    EXPECT_NEAR(b.cmg_hg_nms, 6.5, 0.0);
    EXPECT_NEAR(b.cmg_umax_radps, 0.15, 0.0);
    EXPECT_NEAR(b.cmg_beta0_rad[0], 0.1, 0.0);
    EXPECT_NEAR(b.cmg_beta0_rad[1], -0.2, 0.0);
    EXPECT_NEAR(b.cmg_beta0_rad[3], 6.0, 0.0);
    EXPECT_NEAR(b.cmg_rotor_speed_radps, 550.0, 0.0);
    EXPECT_TRUE(b.rotor_fault);
    EXPECT_NEAR(b.rotor_fault_t_s, 300.0, 0.0);
    EXPECT_EQ_INT(b.rotor_fault_index, 2);
    EXPECT_NEAR(b.rotor_fault_scale, 0.97, 0.0);
    const ref::GyrostatModel m = sim::respin_model(b);
    EXPECT_TRUE(m.cmg);
    EXPECT_NEAR(m.hg_nms, 6.5, 0.0);
    EXPECT_NEAR(m.umax_radps, 0.15, 0.0);
    EXPECT_NEAR(m.beta0_rad[2], 0.3, 0.0);
    EXPECT_NEAR(m.rotor_scale[2], 1.0, 0.0);   // nominal until the plant applies the fault
    EXPECT_EQ_INT(m.n_modes, 3);               // the elastic variant flies with gyrodines too

    // Defaults: h_g 7.5, u_max 0.1745, the null configuration, 600 rad/s, no fault.
    const sim::Scenario d = sim::parse_scenario(base + "respin: {actuator: gyrodines}\n", "t.yaml");
    const sim::RespinSetup &bd = d.mission_part<sim::RespinScenario>().body;
    EXPECT_NEAR(bd.cmg_hg_nms, 7.5, 0.0);
    EXPECT_NEAR(bd.cmg_umax_radps, 0.1745, 0.0);
    EXPECT_NEAR(bd.cmg_beta0_rad[0], M_PI / 4.0, 1e-16);
    EXPECT_NEAR(bd.cmg_beta0_rad[3], -M_PI / 4.0, 1e-16);
    EXPECT_NEAR(bd.cmg_rotor_speed_radps, 600.0, 0.0);
    EXPECT_TRUE(!bd.rotor_fault);
    // Its plant: H(0) = 0 at the null configuration, the wheel-speed channels 0, the gimbal
    // channels at the null counts, the rotors at 600 rad/s = 153 600 counts of 2^-8 rad/s.
    const std::unique_ptr<sim::Plant> pl = sim::make_plant(d);
    const std::vector<double> t = pl->truth();
    EXPECT_NEAR(std::fabs(t[3]) + std::fabs(t[4]) + std::fabs(t[5]), 0.0, 1e-14);
    EXPECT_NEAR(t[8], 300.0, 0.0);
    EXPECT_TRUE(pl->truth_names()[3] == "h_cmg_x_nms");
    const sim::SensorFrame f = pl->sense();
    EXPECT_EQ_INT(f.n_ch, 14);
    const std::int32_t want[14] = {0, 0, 0, 0, 0, 0, 131072, 131072, 917504, 917504, 153600, 153600, 153600, 153600};
    for (std::size_t i = 3; i < 14u; ++i) {
        EXPECT_EQ_INT(f.cnt[i], want[i]);
        EXPECT_EQ_INT(f.status[i], 0);
    }

    const std::string g = base + "respin: {actuator: gyrodines, ";
    expect_scenario_error(base + "respin: {actuator: sails}\n", {"'respin.actuator'", "wheels", "gyrodines"});
    expect_scenario_error(std::string(kMinimal) + "respin: {cmg: {hg_nms: 7.5}}\n",
                          {"'respin.cmg'", "not fitted", "actuator: gyrodines"});
    expect_scenario_error(g + "wheel: {iw_kgm2: 0.01}}\n", {"'respin.wheel'", "not fitted"});
    expect_scenario_error(g + "cmg: {hg: 7.5}}\n", {"'respin.cmg.hg'", "unknown key"});
    expect_scenario_error(g + "cmg: {hg_nms: 0}}\n", {"'respin.cmg.hg_nms'", "out of range"});
    expect_scenario_error(g + "cmg: {umax_radps: 2}}\n", {"'respin.cmg.umax_radps'", "out of range"});
    expect_scenario_error(g + "cmg: {beta0_rad: [0, 0, 0]}}\n", {"'respin.cmg.beta0_rad'", "four numbers"});
    expect_scenario_error(g + "cmg: {beta0_rad: [0, 0, 0, 7]}}\n", {"'respin.cmg.beta0_rad[3]'", "out of range"});
    expect_scenario_error(g + "cmg: {rotor_speed_radps: 0}}\n", {"'respin.cmg.rotor_speed_radps'", "out of range"});
    expect_scenario_error(g + "cmg: {rotor_fault: {t_s: 300, index: 2}}}\n",
                          {"'respin.cmg.rotor_fault.scale'", "missing"});
    expect_scenario_error(g + "cmg: {rotor_fault: {t_s: 300, index: 4, scale: 0.97}}}\n",
                          {"'respin.cmg.rotor_fault.index'"});
    expect_scenario_error(g + "cmg: {rotor_fault: {t_s: 300, index: 1, scale: 2}}}\n",
                          {"'respin.cmg.rotor_fault.scale'", "out of range"});
    expect_scenario_error(g + "cmg: {rotor_fault: {t_s: -1, index: 1, scale: 0.9}}}\n",
                          {"'respin.cmg.rotor_fault.t_s'", "out of range"});
    expect_scenario_error(g + "cmg: {rotor_fault: {t_s: 1, index: 1, scale: 0.9, when: 3}}}\n",
                          {"'respin.cmg.rotor_fault.when'", "unknown key"});
    // The table's actuator kind must be the plant's.
    expect_scenario_error(std::string(kMinimal) + "respin: {actuator: gyrodines}\n",
                          {"'respin.actuator'", "gyrodines", "'rsp_default' flies wheels"});
    expect_scenario_error(base, {"'respin.actuator'", "wheels", "'rsp_cmg' flies gyrodines"});
    expect_scenario_error(base + "respin: {g0_nms: 100}\n", {"'respin.actuator'", "'rsp_cmg' flies gyrodines"});
}

// A8's scenario (spec 30 §7): gyrodines, NEAREST, g(0) = e_z, g0 = 300, the §2 sensors, 6 000 s.
SIM_TEST(gyrodine_scenario_reads)
{
    const sim::Scenario s = sim::load_scenario(SCENARIO_DIR "/respin_cmg.yaml");
    const sim::RespinSetup &b = s.mission_part<sim::RespinScenario>().body;
    EXPECT_TRUE(s.fsw.table == "rsp_cmg");
    EXPECT_NEAR(s.duration_s, 6000.0, 0.0);
    EXPECT_TRUE(b.gyrodines);
    EXPECT_TRUE(b.elastic.empty());
    EXPECT_TRUE(!b.rotor_fault);
    EXPECT_NEAR(b.cmg_hg_nms, 7.5, 0.0);
    EXPECT_NEAR(b.cmg_umax_radps, 0.1745, 0.0);
    EXPECT_NEAR(b.cmg_beta0_rad[0], M_PI / 4.0, 1e-16);
    EXPECT_NEAR(b.cmg_beta0_rad[2], -M_PI / 4.0, 1e-16);
    EXPECT_NEAR(b.cmg_rotor_speed_radps, 600.0, 0.0);
    expect_nominal_setup(b);
    EXPECT_EQ_INT(sim::respin_boot_table(s.fsw.table).act_kind, RSP_ACT_GYRODINES);
    EXPECT_EQ_INT(sim::respin_boot_table(s.fsw.table).mode, RSP_MODE_NEAREST);
}

// The elastic scenarios (A10, A11) and the modal sets of spec 30 §2.
SIM_TEST(elastic_scenarios_and_modal_sets)
{
    const sim::Scenario e1 = sim::load_scenario(SCENARIO_DIR "/respin_e1.yaml");
    const sim::Scenario e2 = sim::load_scenario(SCENARIO_DIR "/respin_e2.yaml");
    EXPECT_TRUE(e1.mission_part<sim::RespinScenario>().body.elastic == "E1");
    EXPECT_TRUE(e2.mission_part<sim::RespinScenario>().body.elastic == "E2");
    const ref::GyrostatModel m1 = sim::respin_model(e1.mission_part<sim::RespinScenario>().body);
    EXPECT_EQ_INT(m1.n_modes, 3);
    EXPECT_EQ_INT(m1.modes[0].axis, 1);   // 1st out-of-plane bending couples with omega_y
    EXPECT_NEAR(m1.modes[0].omega_radps, 1.5, 0.0);
    EXPECT_NEAR(m1.modes[0].d_sqrtkgm, 30.0, 0.0);
    EXPECT_NEAR(m1.modes[2].delta, 0.02, 0.0);
    // free-free frequencies of the spec: 1.73, 4.3, 8.2 rad/s (the fastest sets the RK4 step)
    EXPECT_NEAR(ref::gyrostat_fastest_mode_radps(m1), 8.0 / std::sqrt(1.0 - 25.0 / 670.0), 1e-12);
    const ref::GyrostatModel m2 = sim::respin_model(e2.mission_part<sim::RespinScenario>().body);
    EXPECT_NEAR(m2.modes[0].omega_radps, 0.8, 0.0);
    EXPECT_NEAR(m2.modes[1].d_sqrtkgm, 25.0, 0.0);
    const sim::Scenario r = sim::load_scenario(SCENARIO_DIR "/respin_nominal.yaml");
    EXPECT_EQ_INT(sim::respin_model(r.mission_part<sim::RespinScenario>().body).n_modes, 0);
}

int main()
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(shipped_scenarios_read), cmocka_unit_test(every_key_round_trips),
                                       cmocka_unit_test(bad_values_are_named),
                                       cmocka_unit_test(elastic_scenarios_and_modal_sets),
                                       cmocka_unit_test(gyrodine_keys), cmocka_unit_test(gyrodine_scenario_reads)};
    return cmocka_run_group_tests_name("respin_scenario", tests, nullptr, nullptr);
}
