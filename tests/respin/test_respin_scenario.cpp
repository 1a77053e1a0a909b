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

    // The plant starts where the setup says: G(0) = g0 g_dir, H(0) = 0; 6 sensor channels.
    const std::unique_ptr<sim::Plant> pl = sim::make_plant(s);
    const std::vector<double> t = pl->truth();
    EXPECT_TRUE(t.size() == pl->truth_names().size());
    EXPECT_NEAR(t[6], 40.5 * 0.6, 1e-12);
    EXPECT_NEAR(t[8], -40.5 * 0.8, 1e-12);
    EXPECT_NEAR(t[3], 0.0, 0.0);
    EXPECT_EQ_INT(pl->sense().n_ch, 6);

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
                                       cmocka_unit_test(elastic_scenarios_and_modal_sets)};
    return cmocka_run_group_tests_name("respin_scenario", tests, nullptr, nullptr);
}
