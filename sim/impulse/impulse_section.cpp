#include "impulse/impulse_section.hpp"

#include <cmath>
#include <stdexcept>
#include <yaml-cpp/yaml.h>

#include "impulse/cw_sil_plant.hpp"
#include "scenario/reader.hpp"

extern "C" {
#include "imp_tables.h"
}

namespace sim {

namespace {

void parse_nav(const YAML::Node &n, const Reader &r, NavSetup &v)
{
    r.check_keys(n, "cw.nav", {"profile", "f_hz", "sigma_p_m", "sigma_v_mps", "bias_p_m", "bias_v_mps", "range_m",
                               "dropouts_s", "dropout_ppm", "seed"});
    if (n["profile"]) {
        v.profile = r.choice(n["profile"], "cw.nav.profile", {"ideal", "nominal", "degraded", "custom"});
        if (v.profile == "ideal") {
            v.sigma_p_m = 0.0; v.sigma_v_mps = 0.0;
        } else if (v.profile == "nominal") {
            v.sigma_p_m = 0.1; v.sigma_v_mps = 1e-3;      // spec 50 §2.5
        } else if (v.profile == "degraded") {
            v.sigma_p_m = 0.5; v.sigma_v_mps = 5e-3;
        } else {
            /* custom: the sigmas below */
        }
    }
    if (n["sigma_p_m"] || n["sigma_v_mps"]) {
        if (v.profile != "custom") {
            r.fail("cw.nav", n, "sigma_p_m / sigma_v_mps need profile: custom");
        }
        if (n["sigma_p_m"]) { v.sigma_p_m = r.number(n["sigma_p_m"], "cw.nav.sigma_p_m", 0.0, 1000.0); }
        if (n["sigma_v_mps"]) { v.sigma_v_mps = r.number(n["sigma_v_mps"], "cw.nav.sigma_v_mps", 0.0, 10.0); }
    }
    if (n["f_hz"]) { v.f_hz = r.number(n["f_hz"], "cw.nav.f_hz", 0.01, 100.0); }
    if (n["bias_p_m"]) { v.bias_p_m = r.triple(n["bias_p_m"], "cw.nav.bias_p_m", -1000.0, 1000.0); }
    if (n["bias_v_mps"]) { v.bias_v_mps = r.triple(n["bias_v_mps"], "cw.nav.bias_v_mps", -10.0, 10.0); }
    if (n["range_m"]) { v.range_m = r.number(n["range_m"], "cw.nav.range_m", 1.0, 1.0e7); }
    if (n["dropout_ppm"]) {
        v.dropout_ppm = static_cast<std::uint32_t>(r.integer(n["dropout_ppm"], "cw.nav.dropout_ppm", 0, 1000000));
    }
    if (n["seed"]) { v.seed = r.unsigned64(n["seed"], "cw.nav.seed"); }
    if (const YAML::Node d = n["dropouts_s"]) {
        if (!d.IsSequence()) {
            r.fail("cw.nav.dropouts_s", d, "must be a list of [t0, t1] windows");
        }
        for (std::size_t i = 0; i < d.size(); ++i) {
            const auto w = r.pair(d[i], "cw.nav.dropouts_s[" + std::to_string(i) + "]", 0.0, 1.0e6);
            if (w[1] <= w[0]) {
                r.fail("cw.nav.dropouts_s", d[i], "window must have t1 > t0");
            }
            v.dropouts_s.push_back(w);
        }
    }
}

class ImpulseSection final : public MissionSection {
public:
    const char *mission() const override { return "RENDEZVOUS"; }
    std::vector<std::string> root_keys() const override { return {"cw"}; }
    std::vector<std::string> fsw_keys() const override { return {"cal_enable"}; }
    std::vector<std::string> tables() const override { return {"imp_default", "imp_1s", "imp_sub1ms"}; }

    void defaults(Scenario &s) const override
    {
        s.period_us = 100000u;   // valve tick = fsw period, spec 50 §2.4
        s.plant = "cw";
        s.part = MissionPart(std::make_unique<CwScenario>());
    }

    void parse(const YAML::Node &root, const Reader &r, Scenario &s) const override
    {
        CwScenario &m = s.mission_part<CwScenario>();
        if (s.plant != "cw") {
            r.fail("plant", root["plant"], "mission rendezvous flies plant: cw, not '" + s.plant + "'");
        }
        if (s.period_us < 1000u) {
            r.fail("period_us", root["period_us"], "out of range for the rendezvous: 1000 us .. 10 s");
        }
        if (s.duration_s > 1.0e6) {
            r.fail("duration_s", root["duration_s"], "out of range for the rendezvous: at most 1e6 s");
        }
        CwSetup &c = m.cw;
        if (const YAML::Node n = root["cw"]) {
            r.check_keys(n, "cw", {"omega_radps", "a_nom_mps2", "x0", "x0_epoch_s", "eps_c", "eps", "t_min_us", "min_on",
                                   "subtick_us", "stuck_off", "stuck_on", "nav"});
            if (n["x0_epoch_s"]) { c.x0_epoch_s = r.number(n["x0_epoch_s"], "cw.x0_epoch_s", 0.0, 1.0e5); }
            if (n["omega_radps"]) { c.omega_radps = r.number(n["omega_radps"], "cw.omega_radps", 8.0e-4, 1.2e-3); }
            if (n["a_nom_mps2"]) { c.a_nom_mps2 = r.number(n["a_nom_mps2"], "cw.a_nom_mps2", 1e-4, 10.0); }
            if (const YAML::Node x = n["x0"]) {
                if (!x.IsSequence() || x.size() != 6u) {
                    r.fail("cw.x0", x, "must be [x, x', y, y', z, z'] in m and m/s");
                }
                for (std::size_t i = 0; i < 6u; ++i) {
                    c.x0[i] = r.number(x[i], "cw.x0[" + std::to_string(i) + "]", -1.0e6, 1.0e6);
                }
            }
            if (n["eps_c"]) { c.eps_c = r.number(n["eps_c"], "cw.eps_c", -0.5, 0.5); }
            if (const YAML::Node e = n["eps"]) {
                if (!e.IsSequence() || e.size() != 6u) {
                    r.fail("cw.eps", e, "must list six per-thruster level errors");
                }
                for (std::size_t i = 0; i < 6u; ++i) { c.eps[i] = r.number(e[i], "cw.eps", -0.5, 0.5); }
            }
            if (n["t_min_us"]) { c.t_min_us = static_cast<std::uint32_t>(r.integer(n["t_min_us"], "cw.t_min_us", 0, 10000000)); }
            if (n["min_on"]) {
                c.stretch = r.choice(n["min_on"], "cw.min_on", {"drop", "stretch"}) == "stretch";
            }
            if (n["subtick_us"]) {
                c.subtick_us = static_cast<std::uint32_t>(r.integer(n["subtick_us"], "cw.subtick_us", 0, 1000000));
            }
            for (const char *k : {"stuck_off", "stuck_on"}) {
                if (const YAML::Node f = n[k]) {
                    r.check_keys(f, std::string("cw.") + k, {"thruster", "t_s"});
                    if (!f["thruster"] || !f["t_s"]) {
                        r.fail(std::string("cw.") + k, f, "needs thruster (0..5: +x -x +y -y +z -z) and t_s");
                    }
                    const int j = static_cast<int>(r.integer(f["thruster"], std::string("cw.") + k + ".thruster", 0, 5));
                    const double t = r.number(f["t_s"], std::string("cw.") + k + ".t_s", 0.0, 1.0e6);
                    if (std::string(k) == "stuck_off") { c.stuck_off_j = j; c.stuck_off_t_s = t; }
                    else { c.stuck_on_j = j; c.stuck_on_t_s = t; }
                }
            }
            if (n["nav"]) {
                parse_nav(n["nav"], r, c.nav);
            }
        }
        if (const YAML::Node f = root["fsw"]) {
            if (f["cal_enable"]) {
                m.cal_enable = static_cast<int>(r.integer(f["cal_enable"], "fsw.cal_enable", 0, 1));
            }
        }
        const double spn = 1.0 / (c.nav.f_hz * s.h_s());   // steps per nav sample
        if (std::fabs(spn - std::round(spn)) > 1e-9 || spn < 1.0) {
            r.fail("cw.nav.f_hz", root["cw"]["nav"], "the nav period must be a whole number of fsw periods");
        }
    }

    std::unique_ptr<Plant> make_plant(const Scenario &s) const override
    {
        return std::unique_ptr<Plant>(new CwSilPlant(s));
    }

    std::uint64_t noise_seed(const Scenario &s) const override { return s.mission_part<CwScenario>().cw.nav.seed; }
};

}  // namespace

const MissionSection &impulse_section()
{
    static const ImpulseSection s;
    return s;
}

imp_params_t impulse_boot_table(const std::string &name)
{
    if (name == "imp_default") { return IMP_TBL_DEFAULT; }
    if (name == "imp_1s") { return IMP_TBL_1S; }
    if (name == "imp_sub1ms") { return IMP_TBL_SUB1MS; }
    throw std::invalid_argument("unknown impulse table '" + name + "'");
}

imp_params_t impulse_boot_table(const Scenario &s)
{
    imp_params_t t = impulse_boot_table(s.fsw.table);
    const CwScenario &m = s.mission_part<CwScenario>();
    if (m.cal_enable >= 0) {
        t.cal_enable = static_cast<std::uint8_t>(m.cal_enable);
    }
    return t;
}

}  // namespace sim
