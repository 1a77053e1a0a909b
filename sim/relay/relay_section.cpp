#include "relay/relay_section.hpp"

#include <stdexcept>
#include <yaml-cpp/yaml.h>

#include "relay/relay_plant.hpp"
#include "scenario/reader.hpp"

extern "C" {
#include "rly_tables.h"
}

namespace sim {

namespace {

void parse_modes(const YAML::Node &ms, const Reader &r, RelaySetup &b)
{
    if (!ms.IsSequence() || ms.size() > static_cast<std::size_t>(ref::kRelayMaxModes)) {
        r.fail("relay.modes", ms, "a list of at most 4 modes");
    }
    b.model.n_modes = static_cast<int>(ms.size());
    for (std::size_t i = 0; i < ms.size(); ++i) {
        const YAML::Node m = ms[i];
        const std::string at = "relay.modes[" + std::to_string(i) + "]";
        r.check_keys(m, at, {"omega_radps", "k", "xt0_rad", "xtdot0_radps"});
        if (!m["omega_radps"]) {
            r.fail(at + ".omega_radps", m, "required: the mode's natural frequency");
        }
        b.model.omega_radps[i] = r.number(m["omega_radps"], at + ".omega_radps", 1e-3, 6.0);
        b.model.k[i] = m["k"] ? r.number(m["k"], at + ".k", -1.0, 1.0) : 0.0;
        b.state0.q_rad[i] = m["xt0_rad"] ? r.number(m["xt0_rad"], at + ".xt0_rad", -1e-3, 1e-3) : 0.0;
        b.state0.qdot_radps[i] = m["xtdot0_radps"] ? r.number(m["xtdot0_radps"], at + ".xtdot0_radps", -1e-3, 1e-3) : 0.0;
    }
    for (std::size_t i = ms.size(); i < static_cast<std::size_t>(ref::kRelayMaxModes); ++i) {
        b.model.omega_radps[i] = 0.0;
        b.model.k[i] = 0.0;
        b.state0.q_rad[i] = 0.0;
        b.state0.qdot_radps[i] = 0.0;
    }
}

class RelaySection final : public MissionSection {
public:
    const char *mission() const override { return "RELAY"; }
    std::vector<std::string> root_keys() const override { return {"relay"}; }
    std::vector<std::string> tables() const override
    {
        return {"rly_default", "rly_improved", "rly_paper", "rly_fixed_031", "rly_fixed_03389"};
    }

    void defaults(Scenario &s) const override
    {
        s.period_us = 1000u;
        s.plant = "relay";
        s.part = MissionPart(std::make_unique<RelayScenario>());
    }

    void parse(const YAML::Node &root, const Reader &r, Scenario &s) const override
    {
        RelaySetup &b = s.mission_part<RelayScenario>().body;
        if (s.plant != "relay") {
            r.fail("plant", root["plant"], "mission relay flies plant: relay, not '" + s.plant + "'");
        }
        const YAML::Node m = root["relay"];
        if (!m) {
            return;
        }
        r.check_keys(m, "relay", {"m_u_radps2", "m_eps_radps2", "xbar0_rad", "xbardot0_radps", "x_max_rad", "abar_from_s", "modes",
                                  "sensor", "actuator"});
        if (m["m_u_radps2"]) { b.model.m_u_radps2 = r.number(m["m_u_radps2"], "relay.m_u_radps2", 1e-9, 1e-1); }
        if (m["m_eps_radps2"]) { b.model.m_eps_radps2 = r.number(m["m_eps_radps2"], "relay.m_eps_radps2", 0.0, 1e-1); }
        if (m["xbar0_rad"]) { b.state0.xbar_rad = r.number(m["xbar0_rad"], "relay.xbar0_rad", -0.1, 0.1); }
        if (m["xbardot0_radps"]) {
            b.state0.xbardot_radps = r.number(m["xbardot0_radps"], "relay.xbardot0_radps", -0.01, 0.01);
        }
        if (m["x_max_rad"]) { b.x_max_rad = r.number(m["x_max_rad"], "relay.x_max_rad", 1e-4, 0.5); }
        if (m["abar_from_s"]) { b.abar_from_s = r.number(m["abar_from_s"], "relay.abar_from_s", 0.0, 1e7); }
        if (m["modes"]) { parse_modes(m["modes"], r, b); }
        if (const YAML::Node g = m["sensor"]) {
            r.check_keys(g, "relay.sensor", {"noise_rad", "bias_rad", "seed"});
            if (g["noise_rad"]) { b.noise_rad = r.number(g["noise_rad"], "relay.sensor.noise_rad", 0.0, 1e-3); }
            if (g["bias_rad"]) { b.bias_rad = r.number(g["bias_rad"], "relay.sensor.bias_rad", -1e-3, 1e-3); }
            if (g["seed"]) { b.seed = r.unsigned64(g["seed"], "relay.sensor.seed"); }
        }
        if (const YAML::Node a = m["actuator"]) {
            r.check_keys(a, "relay.actuator", {"scale_error", "delay_ticks"});
            if (a["scale_error"]) { b.scale_error = r.number(a["scale_error"], "relay.actuator.scale_error", -0.1, 0.1); }
            if (a["delay_ticks"]) {
                b.delay_ticks = static_cast<std::uint32_t>(r.integer(a["delay_ticks"], "relay.actuator.delay_ticks", 0, 1));
            }
        }
    }

    std::unique_ptr<Plant> make_plant(const Scenario &s) const override
    {
        return std::unique_ptr<Plant>(new RelayPlant(s));
    }

    std::uint64_t noise_seed(const Scenario &s) const override
    {
        return s.mission_part<RelayScenario>().body.seed;
    }
};

}  // namespace

const MissionSection &relay_section()
{
    static const RelaySection sec;
    return sec;
}

rly_params_t relay_boot_table(const std::string &name)
{
    if (name == "rly_default") { return RLY_TBL_DEFAULT; }
    if (name == "rly_improved") { return RLY_TBL_IMPROVED; }
    if (name == "rly_paper") { return RLY_TBL_PAPER; }
    if (name == "rly_fixed_031") { return RLY_TBL_FIXED_031; }
    if (name == "rly_fixed_03389") { return RLY_TBL_FIXED_03389; }
    throw std::invalid_argument("unknown relay table '" + name + "'");
}

}  // namespace sim
