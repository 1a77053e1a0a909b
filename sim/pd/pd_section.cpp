#include "pd/pd_section.hpp"

#include <stdexcept>
#include <yaml-cpp/yaml.h>

#include "pd/pd_plant.hpp"
#include "scenario/reader.hpp"

extern "C" {
#include "pd_tables.h"
}

namespace sim {

namespace {

class PdSection final : public MissionSection {
public:
    const char *mission() const override { return "HOLD"; }
    std::vector<std::string> root_keys() const override { return {"pd"}; }
    std::vector<std::string> tables() const override { return {"pd_default"}; }

    void defaults(Scenario &s) const override
    {
        s.period_us = 100000u;
        s.plant = "pd";
        s.part = MissionPart(std::make_unique<PdScenario>());
    }

    void parse(const YAML::Node &root, const Reader &r, Scenario &s) const override
    {
        PdSetup &b = s.mission_part<PdScenario>().body;
        if (s.plant != "pd") {
            r.fail("plant", root["plant"], "mission hold flies plant: pd, not '" + s.plant + "'");
        }
        const YAML::Node m = root["pd"];
        if (!m) {
            return;
        }
        r.check_keys(m, "pd", {"inertia_kgm2", "w0_radps", "torque_dist_nm", "w_max_radps", "gyro", "actuator"});
        if (m["inertia_kgm2"]) { b.inertia_kgm2 = r.number(m["inertia_kgm2"], "pd.inertia_kgm2", 1e-3, 1e6); }
        if (m["w0_radps"]) { b.w0_radps = r.number(m["w0_radps"], "pd.w0_radps", -10.0, 10.0); }
        if (m["torque_dist_nm"]) { b.torque_dist_nm = r.number(m["torque_dist_nm"], "pd.torque_dist_nm", -10.0, 10.0); }
        if (m["w_max_radps"]) { b.w_max_radps = r.number(m["w_max_radps"], "pd.w_max_radps", 1e-3, 100.0); }
        if (const YAML::Node g = m["gyro"]) {
            r.check_keys(g, "pd.gyro", {"noise_radps", "bias_radps", "max_cnt", "seed"});
            if (g["noise_radps"]) { b.gyro_noise_radps = r.number(g["noise_radps"], "pd.gyro.noise_radps", 0.0, 1.0); }
            if (g["bias_radps"]) { b.gyro_bias_radps = r.number(g["bias_radps"], "pd.gyro.bias_radps", -1.0, 1.0); }
            if (g["max_cnt"]) {
                b.gyro_max_cnt = static_cast<std::int32_t>(r.integer(g["max_cnt"], "pd.gyro.max_cnt", 1, 2147483647));
            }
            if (g["seed"]) { b.gyro_seed = r.unsigned64(g["seed"], "pd.gyro.seed"); }
        }
        if (const YAML::Node a = m["actuator"]) {
            r.check_keys(a, "pd.actuator", {"max_nm"});
            if (a["max_nm"]) { b.act_max_nm = r.number(a["max_nm"], "pd.actuator.max_nm", 1e-6, 100.0); }
        }
    }

    std::unique_ptr<Plant> make_plant(const Scenario &s) const override
    {
        return std::unique_ptr<Plant>(new PdPlant(s));
    }

    std::uint64_t noise_seed(const Scenario &s) const override
    {
        return s.mission_part<PdScenario>().body.gyro_seed;
    }
};

}  // namespace

const MissionSection &pd_section()
{
    static const PdSection sec;
    return sec;
}

pd_params_t pd_boot_table(const std::string &name)
{
    if (name == "pd_default") { return PD_TBL_DEFAULT; }
    throw std::invalid_argument("unknown pd table '" + name + "'");
}

}  // namespace sim
