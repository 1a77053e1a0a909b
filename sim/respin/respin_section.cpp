#include "respin/respin_section.hpp"

#include <cmath>
#include <stdexcept>
#include <yaml-cpp/yaml.h>

#include "respin/respin_plant.hpp"
#include "respin/rsp_table_list.hpp"
#include "scenario/reader.hpp"
#include "sensors/rng.hpp"

extern "C" {
#include "rsp_tables.h"
}

namespace sim {

namespace {

void parse_wheel(const YAML::Node &w, const Reader &r, RespinSetup &m)
{
    r.check_keys(w, "respin.wheel", {"iw_kgm2", "torque_max_nm", "h_max_nms", "coulomb_nm", "viscous_nmps"});
    if (w["iw_kgm2"]) { m.iw_kgm2 = r.number(w["iw_kgm2"], "respin.wheel.iw_kgm2", 1e-4, 1.0); }
    if (w["torque_max_nm"]) { m.torque_max_nm = r.number(w["torque_max_nm"], "respin.wheel.torque_max_nm", 1e-3, 1.0); }
    if (w["h_max_nms"]) { m.h_max_nms = r.number(w["h_max_nms"], "respin.wheel.h_max_nms", 0.1, 50.0); }
    if (w["coulomb_nm"]) { m.coulomb_nm = r.number(w["coulomb_nm"], "respin.wheel.coulomb_nm", 0.0, 0.1); }
    if (w["viscous_nmps"]) { m.viscous_nmps = r.number(w["viscous_nmps"], "respin.wheel.viscous_nmps", 0.0, 1e-2); }
}

// Four numbers (the gyrodines' beta0), read like Reader::triple.
std::array<double, 4> quad(const YAML::Node &n, const Reader &r, const std::string &key, double lo, double hi)
{
    if (!n.IsSequence() || n.size() != 4u) {
        r.fail(key, n, "must be a list of four numbers [b1, b2, b3, b4]");
    }
    return {{r.number(n[0], key + "[0]", lo, hi), r.number(n[1], key + "[1]", lo, hi), r.number(n[2], key + "[2]", lo, hi),
             r.number(n[3], key + "[3]", lo, hi)}};
}

void parse_cmg(const YAML::Node &c, const Reader &r, RespinSetup &b)
{
    constexpr double kTwoPi = 6.283185307179586476925286766559;
    r.check_keys(c, "respin.cmg", {"hg_nms", "umax_radps", "beta0_rad", "rotor_speed_radps", "rotor_fault"});
    if (c["hg_nms"]) { b.cmg_hg_nms = r.number(c["hg_nms"], "respin.cmg.hg_nms", 0.1, 100.0); }
    if (c["umax_radps"]) { b.cmg_umax_radps = r.number(c["umax_radps"], "respin.cmg.umax_radps", 1e-3, 1.0); }
    if (c["beta0_rad"]) { b.cmg_beta0_rad = quad(c["beta0_rad"], r, "respin.cmg.beta0_rad", -kTwoPi, kTwoPi); }
    // The rotor-speed counts (2^-8 rad/s, up to 1.5 x nominal with a fault) stay below full scale.
    if (c["rotor_speed_radps"]) {
        b.cmg_rotor_speed_radps = r.number(c["rotor_speed_radps"], "respin.cmg.rotor_speed_radps", 1.0, 20000.0);
    }
    if (const YAML::Node f = c["rotor_fault"]) {
        r.check_keys(f, "respin.cmg.rotor_fault", {"t_s", "index", "scale"});
        for (const char *k : {"t_s", "index", "scale"}) {
            if (!f[k]) {
                r.fail(std::string("respin.cmg.rotor_fault.") + k, f, "missing: a rotor fault needs t_s, index and scale");
            }
        }
        b.rotor_fault = true;
        b.rotor_fault_t_s = r.number(f["t_s"], "respin.cmg.rotor_fault.t_s", 0.0, 1e7);
        b.rotor_fault_index = static_cast<std::uint32_t>(r.integer(f["index"], "respin.cmg.rotor_fault.index", 0, 3));
        b.rotor_fault_scale = r.number(f["scale"], "respin.cmg.rotor_fault.scale", 0.0, 1.5);
    }
}

void parse_gyro(const YAML::Node &g, const Reader &r, RespinSetup &b)
{
    r.check_keys(g, "respin.gyro", {"noise_radps", "bias_radps", "scale_ppm", "seed"});
    if (g["noise_radps"]) { b.gyro_noise_radps = r.number(g["noise_radps"], "respin.gyro.noise_radps", 0.0, 1e-2); }
    if (g["bias_radps"]) { b.gyro_bias_radps = r.triple(g["bias_radps"], "respin.gyro.bias_radps", -1e-2, 1e-2); }
    if (g["scale_ppm"]) { b.gyro_scale_ppm = r.triple(g["scale_ppm"], "respin.gyro.scale_ppm", -1e4, 1e4); }
    if (g["seed"]) { b.gyro_seed = r.unsigned64(g["seed"], "respin.gyro.seed"); }
}

// A wheel table flown against gyrodines (or the reverse) commands an actuator that is not there:
// refused for the built-in tables (a table_file is the flight's to judge).
void check_act_kind(const YAML::Node &at, const Reader &r, const Scenario &s)
{
    if (!s.fsw.table_file.empty()) {
        return;
    }
    const bool cmg = s.mission_part<RespinScenario>().body.gyrodines;
    for (const RespinNamedTable &t : kRespinTables) {
        if (s.fsw.table == t.name && (t.table->act_kind == RSP_ACT_GYRODINES) != cmg) {
            r.fail("respin.actuator", at,
                   std::string("is ") + (cmg ? "gyrodines" : "wheels") + " but table '" + s.fsw.table + "' flies " +
                       (cmg ? "wheels" : "gyrodines"));
        }
    }
}

class RespinSection final : public MissionSection {
public:
    const char *mission() const override { return "RESPIN"; }
    std::vector<std::string> root_keys() const override { return {"respin"}; }
    std::vector<std::string> tables() const override
    {
        std::vector<std::string> v;
        for (const RespinNamedTable &t : kRespinTables) {
            v.emplace_back(t.name);
        }
        return v;
    }

    void defaults(Scenario &s) const override
    {
        s.period_us = 100000u;
        s.plant = "respin";
        s.part = MissionPart(std::make_unique<RespinScenario>());
    }

    void parse(const YAML::Node &root, const Reader &r, Scenario &s) const override
    {
        RespinSetup &b = s.mission_part<RespinScenario>().body;
        if (s.plant != "respin") {
            r.fail("plant", root["plant"], "mission respin flies plant: respin, not '" + s.plant + "'");
        }
        const YAML::Node m = root["respin"];
        if (!m) {
            const YAML::Node f = root["fsw"];
            check_act_kind((f && f.IsMap() && f["table"]) ? f["table"] : root, r, s);
            return;
        }
        r.check_keys(m, "respin", {"g0_nms", "g_dir", "g_dir_seed", "inertia_kgm2", "omega_max_radps", "n_sub", "wheel",
                                   "gyro", "elastic", "actuator", "cmg"});
        if (m["g0_nms"]) { b.g0_nms = r.number(m["g0_nms"], "respin.g0_nms", 1e-3, 1000.0); }
        if (m["g_dir"] && m["g_dir_seed"]) {
            r.fail("respin.g_dir_seed", m["g_dir_seed"], "give g_dir or g_dir_seed, not both");
        }
        if (m["g_dir"]) {
            const std::array<double, 3> d = r.triple(m["g_dir"], "respin.g_dir", -1e3, 1e3);
            const double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            if (!(n > 1e-9)) {
                r.fail("respin.g_dir", m["g_dir"], "must not be the zero vector");
            }
            b.g_dir = {{d[0] / n, d[1] / n, d[2] / n}};
            b.g_dir_random = false;
        }
        if (m["g_dir_seed"]) {
            b.g_dir_seed = r.unsigned64(m["g_dir_seed"], "respin.g_dir_seed");
            b.g_dir_random = true;
        }
        if (m["inertia_kgm2"]) { b.j_kgm2 = r.triple(m["inertia_kgm2"], "respin.inertia_kgm2", 1.0, 1e5); }
        if (m["omega_max_radps"]) { b.omega_max_radps = r.number(m["omega_max_radps"], "respin.omega_max_radps", 1e-3, 10.0); }
        if (m["n_sub"]) { b.n_sub = static_cast<int>(r.integer(m["n_sub"], "respin.n_sub", 1, 100)); }
        if (m["elastic"]) {
            const std::string e = r.choice(m["elastic"], "respin.elastic", {"none", "E1", "E2"});
            b.elastic = (e == "none") ? std::string() : e;
        }
        if (!b.elastic.empty()) {
            // RK4 at h = Ts / n_sub must resolve the fastest free-free mode (spec 30 §2: Omega h <= 0.25).
            ref::GyrostatModel gm;
            gm.j_kgm2 = b.j_kgm2;
            ref::gyrostat_set_modes(gm, b.elastic);
            const double wmax = ref::gyrostat_fastest_mode_radps(gm);
            const double h = static_cast<double>(s.period_us) * 1e-6 / static_cast<double>(b.n_sub);
            if (wmax * h > 0.25) {
                r.fail("respin.n_sub", m["n_sub"] ? m["n_sub"] : m["elastic"],
                       "RK4 step too long for modal set " + b.elastic + ": need n_sub >= " +
                           std::to_string(static_cast<int>(std::ceil(wmax * static_cast<double>(s.period_us) * 1e-6 / 0.25))));
            }
        }
        if (m["actuator"]) {
            b.gyrodines = r.choice(m["actuator"], "respin.actuator", {"wheels", "gyrodines"}) == "gyrodines";
        }
        if (const YAML::Node w = m["wheel"]) {
            if (b.gyrodines) {
                r.fail("respin.wheel", w, "the wheels are not fitted (respin.actuator: gyrodines)");
            }
            parse_wheel(w, r, b);
        }
        if (const YAML::Node c = m["cmg"]) {
            if (!b.gyrodines) {
                r.fail("respin.cmg", c, "the gyrodines are not fitted (needs respin.actuator: gyrodines)");
            }
            parse_cmg(c, r, b);
        }
        check_act_kind(m["actuator"] ? m["actuator"] : m, r, s);
        if (const YAML::Node g = m["gyro"]) {
            parse_gyro(g, r, b);
        }
    }

    std::unique_ptr<Plant> make_plant(const Scenario &s) const override
    {
        return std::unique_ptr<Plant>(new RespinPlant(s));
    }

    std::uint64_t noise_seed(const Scenario &s) const override
    {
        return s.mission_part<RespinScenario>().body.gyro_seed;
    }
};

}  // namespace

const MissionSection &respin_section()
{
    static const RespinSection sec;
    return sec;
}

const RespinSetup &respin_setup(const Scenario &s)
{
    return s.mission_part<RespinScenario>().body;
}

ref::GyrostatModel respin_model(const RespinSetup &b)
{
    ref::GyrostatModel m;
    m.j_kgm2 = b.j_kgm2;
    m.iw_kgm2 = b.iw_kgm2;
    m.torque_max_nm = b.torque_max_nm;
    m.h_max_nms = b.h_max_nms;
    m.coulomb_nm = b.coulomb_nm;
    m.viscous_nmps = b.viscous_nmps;
    ref::gyrostat_set_modes(m, b.elastic);
    m.cmg = b.gyrodines;
    m.hg_nms = b.cmg_hg_nms;
    m.umax_radps = b.cmg_umax_radps;
    m.beta0_rad = b.cmg_beta0_rad;
    // Nominal rotors at t = 0; the plant applies rotor_fault when its time comes.
    m.rotor_scale = {{1.0, 1.0, 1.0, 1.0}};
    return m;
}

rsp_params_t respin_boot_table(const std::string &name)
{
    for (const RespinNamedTable &t : kRespinTables) {
        if (name == t.name) {
            return *t.table;
        }
    }
    throw std::invalid_argument("unknown respin table '" + name + "'");
}

std::array<double, 3> respin_initial_direction(const RespinSetup &b)
{
    if (!b.g_dir_random) {
        return b.g_dir;
    }
    // Uniform on the sphere: a normalised 3-D standard normal (stream 2 of the seed, independent of
    // the gyro's streams). A draw of norm below 1e-6 (probability ~1e-19) is redrawn.
    Rng rng(b.g_dir_seed, 2u);
    for (;;) {
        const double x = rng.gaussian(), y = rng.gaussian(), z = rng.gaussian();
        const double n = std::sqrt(x * x + y * y + z * z);
        if (n > 1e-6) {
            return {{x / n, y / n, z / n}};
        }
    }
}

}  // namespace sim
