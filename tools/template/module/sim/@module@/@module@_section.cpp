#include "@module@/@module@_section.hpp"

#include <stdexcept>
#include <yaml-cpp/yaml.h>

#include "@module@/@module@_plant.hpp"
#include "scenario/reader.hpp"

extern "C" {
#include "@prefix@_tables.h"
}

namespace sim {

namespace {

class @Class@Section final : public MissionSection {
public:
    const char *mission() const override { return "@MISSION@"; }
    std::vector<std::string> root_keys() const override { return {"@module@"}; }
    std::vector<std::string> tables() const override { return {"@prefix@_default"}; }

    void defaults(Scenario &s) const override
    {
        s.period_us = 100000u;
        s.plant = "@module@";
        s.part = MissionPart(std::make_unique<@Class@Scenario>());
    }

    void parse(const YAML::Node &root, const Reader &r, Scenario &s) const override
    {
        @Class@Setup &b = s.mission_part<@Class@Scenario>().body;
        if (s.plant != "@module@") {
            r.fail("plant", root["plant"], "mission @mission@ flies plant: @module@, not '" + s.plant + "'");
        }
        const YAML::Node m = root["@module@"];
        if (!m) {
            return;
        }
        r.check_keys(m, "@module@", {"inertia_kgm2", "w0_radps", "torque_dist_nm", "w_max_radps", "gyro", "actuator"});
        if (m["inertia_kgm2"]) { b.inertia_kgm2 = r.number(m["inertia_kgm2"], "@module@.inertia_kgm2", 1e-3, 1e6); }
        if (m["w0_radps"]) { b.w0_radps = r.number(m["w0_radps"], "@module@.w0_radps", -10.0, 10.0); }
        if (m["torque_dist_nm"]) { b.torque_dist_nm = r.number(m["torque_dist_nm"], "@module@.torque_dist_nm", -10.0, 10.0); }
        if (m["w_max_radps"]) { b.w_max_radps = r.number(m["w_max_radps"], "@module@.w_max_radps", 1e-3, 100.0); }
        if (const YAML::Node g = m["gyro"]) {
            r.check_keys(g, "@module@.gyro", {"noise_radps", "bias_radps", "max_cnt", "seed"});
            if (g["noise_radps"]) { b.gyro_noise_radps = r.number(g["noise_radps"], "@module@.gyro.noise_radps", 0.0, 1.0); }
            if (g["bias_radps"]) { b.gyro_bias_radps = r.number(g["bias_radps"], "@module@.gyro.bias_radps", -1.0, 1.0); }
            if (g["max_cnt"]) {
                b.gyro_max_cnt = static_cast<std::int32_t>(r.integer(g["max_cnt"], "@module@.gyro.max_cnt", 1, 2147483647));
            }
            if (g["seed"]) { b.gyro_seed = r.unsigned64(g["seed"], "@module@.gyro.seed"); }
        }
        if (const YAML::Node a = m["actuator"]) {
            r.check_keys(a, "@module@.actuator", {"max_nm"});
            if (a["max_nm"]) { b.act_max_nm = r.number(a["max_nm"], "@module@.actuator.max_nm", 1e-6, 100.0); }
        }
    }

    std::unique_ptr<Plant> make_plant(const Scenario &s) const override
    {
        return std::unique_ptr<Plant>(new @Class@Plant(s));
    }

    std::uint64_t noise_seed(const Scenario &s) const override
    {
        return s.mission_part<@Class@Scenario>().body.gyro_seed;
    }
};

}  // namespace

const MissionSection &@module@_section()
{
    static const @Class@Section sec;
    return sec;
}

@prefix@_params_t @module@_boot_table(const std::string &name)
{
    if (name == "@prefix@_default") { return @PREFIX@_TBL_DEFAULT; }
    throw std::invalid_argument("unknown @module@ table '" + name + "'");
}

}  // namespace sim
