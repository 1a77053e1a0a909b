#include "respin/respin_section.hpp"

#include <stdexcept>
#include <yaml-cpp/yaml.h>

#include "respin/respin_plant.hpp"
#include "scenario/reader.hpp"

extern "C" {
#include "rsp_tables.h"
}

namespace sim {

namespace {

class RespinSection final : public MissionSection {
public:
    const char *mission() const override { return "RESPIN"; }
    std::vector<std::string> root_keys() const override { return {"respin"}; }
    std::vector<std::string> tables() const override { return {"rsp_default"}; }

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
            return;
        }
        r.check_keys(m, "respin", {"inertia_kgm2", "w0_radps", "torque_dist_nm", "w_max_radps", "gyro", "actuator"});
        if (m["inertia_kgm2"]) { b.inertia_kgm2 = r.number(m["inertia_kgm2"], "respin.inertia_kgm2", 1e-3, 1e6); }
        if (m["w0_radps"]) { b.w0_radps = r.number(m["w0_radps"], "respin.w0_radps", -10.0, 10.0); }
        if (m["torque_dist_nm"]) { b.torque_dist_nm = r.number(m["torque_dist_nm"], "respin.torque_dist_nm", -10.0, 10.0); }
        if (m["w_max_radps"]) { b.w_max_radps = r.number(m["w_max_radps"], "respin.w_max_radps", 1e-3, 100.0); }
        if (const YAML::Node g = m["gyro"]) {
            r.check_keys(g, "respin.gyro", {"noise_radps", "bias_radps", "max_cnt", "seed"});
            if (g["noise_radps"]) { b.gyro_noise_radps = r.number(g["noise_radps"], "respin.gyro.noise_radps", 0.0, 1.0); }
            if (g["bias_radps"]) { b.gyro_bias_radps = r.number(g["bias_radps"], "respin.gyro.bias_radps", -1.0, 1.0); }
            if (g["max_cnt"]) {
                b.gyro_max_cnt = static_cast<std::int32_t>(r.integer(g["max_cnt"], "respin.gyro.max_cnt", 1, 2147483647));
            }
            if (g["seed"]) { b.gyro_seed = r.unsigned64(g["seed"], "respin.gyro.seed"); }
        }
        if (const YAML::Node a = m["actuator"]) {
            r.check_keys(a, "respin.actuator", {"max_nm"});
            if (a["max_nm"]) { b.act_max_nm = r.number(a["max_nm"], "respin.actuator.max_nm", 1e-6, 100.0); }
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

rsp_params_t respin_boot_table(const std::string &name)
{
    if (name == "rsp_default") { return RSP_TBL_DEFAULT; }
    throw std::invalid_argument("unknown respin table '" + name + "'");
}

}  // namespace sim
