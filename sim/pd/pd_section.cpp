#include "pd/pd_section.hpp"

#include <stdexcept>
#include <string>
#include <vector>
#include <yaml-cpp/yaml.h>

#include "pd/pd_coupled.hpp"
#include "pd/pd_plant.hpp"
#include "pd/pd_table_list.hpp"
#include "scenario/reader.hpp"

extern "C" {
#include "pd_tables.h"
}

namespace sim {

namespace {

// A list of mappings (f_steps, kicks, windows): each item's keys checked, the required ones present.
template <class F>
void each_item(const YAML::Node &n, const Reader &r, const std::string &key, const std::vector<std::string> &keys,
               const std::vector<std::string> &required, F on_item)
{
    if (!n.IsSequence()) {
        r.fail(key, n, "must be a list of mappings");
    }
    for (std::size_t i = 0; i < n.size(); ++i) {
        const std::string k = key + "[" + std::to_string(i) + "]";
        r.check_keys(n[i], k, keys);
        for (const std::string &q : required) {
            if (!n[i][q]) {
                r.fail(k + "." + q, n[i], "missing required key");
            }
        }
        on_item(n[i], k);
    }
}

PdWindow parse_window(const YAML::Node &w, const Reader &r, const std::string &k, bool offset)
{
    PdWindow v;
    v.t0_s = r.number(w["t0_s"], k + ".t0_s", 0.0, 1e7);
    v.t1_s = r.number(w["t1_s"], k + ".t1_s", 0.0, 1e7);
    if (!(v.t1_s > v.t0_s)) {
        r.fail(k + ".t1_s", w["t1_s"], "must be after t0_s");
    }
    v.channel = static_cast<std::uint32_t>(r.integer(w["channel"], k + ".channel", 0, 2));
    if (offset) {
        v.rad = r.number(w["rad"], k + ".rad", -10.0, 10.0);
    }
    return v;
}

void parse_sensor(const YAML::Node &g, const Reader &r, PdSetup &b)
{
    r.check_keys(g, "pd.sensor", {"noise_rad", "bias_rad", "seed", "frozen", "offset"});
    if (const YAML::Node n = g["noise_rad"]) {
        // One sigma for all three attitude channels, or one per channel.
        if (n.IsSequence()) {
            b.noise_rad = r.triple(n, "pd.sensor.noise_rad", 0.0, 0.01);
        } else {
            const double v = r.number(n, "pd.sensor.noise_rad", 0.0, 0.01);
            b.noise_rad = {{v, v, v}};
        }
    }
    if (g["bias_rad"]) { b.bias_rad = r.triple(g["bias_rad"], "pd.sensor.bias_rad", -0.1, 0.1); }
    if (g["seed"]) { b.sensor_seed = r.unsigned64(g["seed"], "pd.sensor.seed"); }
    if (g["frozen"]) {
        each_item(g["frozen"], r, "pd.sensor.frozen", {"t0_s", "t1_s", "channel"}, {"t0_s", "t1_s", "channel"},
                  [&](const YAML::Node &w, const std::string &k) { b.frozen.push_back(parse_window(w, r, k, false)); });
    }
    if (g["offset"]) {
        each_item(g["offset"], r, "pd.sensor.offset", {"t0_s", "t1_s", "channel", "rad"},
                  {"t0_s", "t1_s", "channel", "rad"},
                  [&](const YAML::Node &w, const std::string &k) { b.offset.push_back(parse_window(w, r, k, true)); });
    }
}

class PdSection final : public MissionSection {
public:
    const char *mission() const override { return "HOLD"; }
    std::vector<std::string> root_keys() const override { return {"pd"}; }
    std::vector<std::string> tables() const override
    {
        std::vector<std::string> v;
        for (const PdNamedTable &t : kPdTables) { v.emplace_back(t.name); }
        return v;
    }

    void defaults(Scenario &s) const override
    {
        s.period_us = kPdPeriodUs;
        s.plant = "pd";
        s.part = MissionPart(std::make_unique<PdScenario>());
    }

    void parse(const YAML::Node &root, const Reader &r, Scenario &s) const override
    {
        PdSetup &b = s.mission_part<PdScenario>().body;
        if (s.plant != "pd") {
            r.fail("plant", root["plant"], "mission hold flies plant: pd, not '" + s.plant + "'");
        }
        // The sensors sample, and the flight law differences, at Ty = 0.25 s (spec 40 §2.4).
        if (s.period_us != kPdPeriodUs) {
            r.fail("period_us", root["period_us"], "mission hold runs at period_us: 250000 (Ty = 0.25 s)");
        }
        const YAML::Node m = root["pd"];
        if (!m) {
            return;
        }
        r.check_keys(m, "pd", {"plant", "coupling_sign", "scale", "latency_samples", "f_hz", "f_steps", "x0_rad", "kicks",
                               "sensor", "actuator"});
        if (m["plant"]) {
            b.kind = r.choice(m["plant"], "pd.plant", {"single", "coupled"}) == "coupled" ? PdPlantKind::Coupled
                                                                                         : PdPlantKind::Single;
        }
        if (const YAML::Node c = m["coupling_sign"]) {
            if (b.kind != PdPlantKind::Coupled) {
                r.fail("pd.coupling_sign", c, "only with pd.plant: coupled (the single channels have no cross terms)");
            }
            b.coupling_sign = static_cast<int>(r.integer(c, "pd.coupling_sign", -1, 1));
            if (b.coupling_sign == 0) {
                r.fail("pd.coupling_sign", c, "must be 1 or -1");
            }
        }
        if (const YAML::Node sc = m["scale"]) {
            r.check_keys(sc, "pd.scale", {"coupling", "ix", "h"});
            if (sc["coupling"]) { b.scale_coupling = r.number(sc["coupling"], "pd.scale.coupling", 0.5, 2.0); }
            if (sc["ix"]) { b.scale_ix = r.number(sc["ix"], "pd.scale.ix", 0.5, 2.0); }
            if (sc["h"]) { b.scale_h = r.number(sc["h"], "pd.scale.h", 0.5, 2.0); }
        }
        if (m["latency_samples"]) {
            b.latency_samples = static_cast<std::uint32_t>(r.integer(m["latency_samples"], "pd.latency_samples", 0, 1));
        }
        if (m["f_hz"]) { b.f_hz = r.number(m["f_hz"], "pd.f_hz", 0.005, 0.2); }
        if (m["f_steps"]) {
            each_item(m["f_steps"], r, "pd.f_steps", {"t_s", "f_hz"}, {"t_s", "f_hz"},
                      [&](const YAML::Node &it, const std::string &k) {
                          PdFStep st;
                          st.t_s = r.number(it["t_s"], k + ".t_s", 0.0, 1e7);
                          st.f_hz = r.number(it["f_hz"], k + ".f_hz", 0.005, 0.2);
                          if (!b.f_steps.empty() && !(st.t_s > b.f_steps.back().t_s)) {
                              r.fail(k + ".t_s", it["t_s"], "f_steps must be in strictly increasing time order");
                          }
                          b.f_steps.push_back(st);
                      });
        }
        if (m["x0_rad"]) { b.x0_rad = r.triple(m["x0_rad"], "pd.x0_rad", -1.0, 1.0); }
        if (m["kicks"]) {
            each_item(m["kicks"], r, "pd.kicks", {"t_s", "dx_rad"}, {"t_s", "dx_rad"},
                      [&](const YAML::Node &it, const std::string &k) {
                          PdKick kk;
                          kk.t_s = r.number(it["t_s"], k + ".t_s", 0.0, 1e7);
                          kk.dx_rad = r.triple(it["dx_rad"], k + ".dx_rad", -1.0, 1.0);
                          if (!b.kicks.empty() && kk.t_s < b.kicks.back().t_s) {
                              r.fail(k + ".t_s", it["t_s"], "kicks must be in time order");
                          }
                          b.kicks.push_back(kk);
                      });
        }
        if (const YAML::Node g = m["sensor"]) {
            parse_sensor(g, r, b);
        }
        if (const YAML::Node a = m["actuator"]) {
            r.check_keys(a, "pd.actuator", {"max_nm"});
            if (a["max_nm"]) { b.act_max_nm = r.number(a["max_nm"], "pd.actuator.max_nm", 1e-3, 100.0); }
        }
        // The scaled true plant must still have a positive-definite mass matrix (Ix > sum r_i I_i).
        try {
            (void)ref::pd::second_order(pd_channels(b, s.h_s()), b.f_hz, b.coupling_sign, b.kind == PdPlantKind::Coupled);
        } catch (const std::invalid_argument &e) {
            r.fail("pd.scale", m["scale"] ? m["scale"] : m, e.what());
        }
    }

    std::unique_ptr<Plant> make_plant(const Scenario &s) const override
    {
        return std::unique_ptr<Plant>(new PdPlant(s));
    }

    std::uint64_t noise_seed(const Scenario &s) const override
    {
        return s.mission_part<PdScenario>().body.sensor_seed;
    }
};

}  // namespace

const MissionSection &pd_section()
{
    static const PdSection sec;
    return sec;
}

pd_table_t pd_boot_table(const std::string &name)
{
    for (const PdNamedTable &t : kPdTables) {
        if (name == t.name) { return *t.table; }
    }
    throw std::invalid_argument("unknown pd table '" + name + "'");
}

}  // namespace sim
