#include "observer/observer_section.hpp"

#include <cmath>
#include <stdexcept>
#include <yaml-cpp/yaml.h>

#include "observer/sail_plant.hpp"
#include "scenario/reader.hpp"

extern "C" {
#include "obs_tables.h"
}

namespace sim {

namespace {

constexpr double kDegToRad = 3.14159265358979323846 / 180.0;

std::int32_t q_of(double v, int q, const char *what)
{
    const double s = std::ldexp(v, q);
    if (!std::isfinite(s) || s < 1.0 || s > 2147483647.0) {
        throw std::invalid_argument(std::string("boot table override out of range: ") + what);
    }
    return static_cast<std::int32_t>(std::floor(s + 0.5));
}

class ObserverSection final : public MissionSection {
public:
    const char *mission() const override { return "DETUMBLE"; }

    std::vector<std::string> root_keys() const override
    {
        return {"model", "sigma", "k2_true_per_s2", "j_factor", "w0_degps", "mu0_deg", "mudot0_degps", "propagator",
                "ode_substeps", "gyro", "gimbal", "limits"};
    }
    std::vector<std::string> fsw_keys() const override { return {"k_hat0", "bdot_max_degps"}; }

    std::vector<std::string> tables() const override
    {
        return {"obs_50hz_phys", "obs_50hz_paper", "obs_5hz_paper", "obs_paper_printed"};
    }

    void defaults(Scenario &s) const override
    {
        s.period_us = 20000u;
        s.plant = "sail";
        auto m = std::make_unique<SailScenario>();
        m->sigma = +1;
        m->w0_radps = {1.0 * kDegToRad, 1.0 * kDegToRad};
        m->mu_max_rad = 30.0 * kDegToRad;
        m->w_max_radps = 30.0 * kDegToRad;
        s.part = MissionPart(std::move(m));
    }

    void parse(const YAML::Node &root, const Reader &r, Scenario &s) const override
    {
        SailScenario &m = s.mission_part<SailScenario>();
        if (s.plant != "sail") {
            r.fail("plant", root["plant"], "mission detumble flies plant: sail, not '" + s.plant + "'");
        }
        // The sail's identity (spec 10 §2.2: every scenario names its sigma).
        for (const char *k : {"model", "sigma"}) {
            if (!root[k]) {
                r.fail(k, root[k], "missing required key");
            }
        }
        const std::int64_t sig = r.integer(root["sigma"], "sigma", -1, 1);
        if (sig == 0) {
            r.fail("sigma", root["sigma"], "must be +1 (M-phys) or -1 (M-paper)");
        }
        m.sigma = static_cast<int>(sig);
        // sigma and model are both required and must agree, so a run never mixes them silently.
        const std::string model = r.choice(root["model"], "model", {"M-phys", "M-paper"});
        if (model != sigma_name(m.sigma)) {
            r.fail("model", root["model"], "'" + model + "' contradicts sigma = " + std::to_string(m.sigma));
        }
        if (root["k2_true_per_s2"]) {
            m.k2_true_per_s2 = r.number(root["k2_true_per_s2"], "k2_true_per_s2", 1e-6, 1.0);
        }
        if (root["j_factor"]) {
            m.j_factor = r.number(root["j_factor"], "j_factor", 0.5, 2.0);
        }
        if (root["w0_degps"]) {
            const auto w = r.pair(root["w0_degps"], "w0_degps", -1000.0, 1000.0);
            m.w0_radps = {w[0] * kDegToRad, w[1] * kDegToRad};
        }
        if (root["mu0_deg"]) {
            const auto a = r.pair(root["mu0_deg"], "mu0_deg", -90.0, 90.0);
            m.mu0_rad = {a[0] * kDegToRad, a[1] * kDegToRad};
        }
        if (root["mudot0_degps"]) {
            const auto a = r.pair(root["mudot0_degps"], "mudot0_degps", -1000.0, 1000.0);
            m.mudot0_radps = {a[0] * kDegToRad, a[1] * kDegToRad};
        }
        if (root["propagator"]) {
            m.propagator = (r.choice(root["propagator"], "propagator", {"zoh", "ode"}) == "ode") ? Propagator::Ode
                                                                                                 : Propagator::Zoh;
        }
        if (root["ode_substeps"]) {
            m.ode_substeps = static_cast<std::uint32_t>(r.integer(root["ode_substeps"], "ode_substeps", 0, 1000000));
        }
        if (const YAML::Node g = root["gyro"]) {
            r.check_keys(g, "gyro", {"noise_radps", "bias_radps", "bias_sigma_radps", "seed", "lsb_shift", "max_cnt",
                                    "glitch_s", "glitch_channel", "glitch_bit"});
            if (g["noise_radps"]) {
                m.gyro.noise_radps = r.number(g["noise_radps"], "gyro.noise_radps", 0.0, 1.0);
            }
            if (g["bias_radps"]) {
                m.gyro.bias_radps = r.pair(g["bias_radps"], "gyro.bias_radps", -1.0, 1.0);
            }
            if (g["bias_sigma_radps"]) {
                m.gyro.bias_sigma_radps = r.number(g["bias_sigma_radps"], "gyro.bias_sigma_radps", 0.0, 1.0);
            }
            if (g["seed"]) {
                m.gyro.seed = r.unsigned64(g["seed"], "gyro.seed");
            }
            if (g["lsb_shift"]) {
                m.gyro.lsb_shift = static_cast<int>(r.integer(g["lsb_shift"], "gyro.lsb_shift", 0, 30));
            }
            if (g["max_cnt"]) {
                m.gyro.max_cnt = static_cast<std::int32_t>(r.integer(g["max_cnt"], "gyro.max_cnt", 1, INT32_MAX));
            }
            if (g["glitch_s"]) {
                m.gyro.glitch_s = r.number(g["glitch_s"], "gyro.glitch_s", 0.0, 1.0e7);
            }
            if (g["glitch_channel"]) {
                m.gyro.glitch_channel = static_cast<std::uint32_t>(r.integer(g["glitch_channel"], "gyro.glitch_channel", 0, 1));
            }
            if (g["glitch_bit"]) {
                m.gyro.glitch_bit = static_cast<std::uint32_t>(r.integer(g["glitch_bit"], "gyro.glitch_bit", 0, 31));
            }
        }
        if (const YAML::Node g = root["gimbal"]) {
            r.check_keys(g, "gimbal", {"lsb_shift", "hw_limit_radps"});
            if (g["lsb_shift"]) {
                m.gimbal.lsb_shift = static_cast<int>(r.integer(g["lsb_shift"], "gimbal.lsb_shift", 0, 30));
            }
            if (g["hw_limit_radps"]) {
                m.gimbal.hw_limit_radps = r.number(g["hw_limit_radps"], "gimbal.hw_limit_radps", 1e-6, 10.0);
            }
        }
        if (const YAML::Node l = root["limits"]) {
            r.check_keys(l, "limits", {"mu_max_deg", "w_max_degps"});
            if (l["mu_max_deg"]) {
                m.mu_max_rad = r.number(l["mu_max_deg"], "limits.mu_max_deg", 1e-6, 90.0) * kDegToRad;
            }
            if (l["w_max_degps"]) {
                m.w_max_radps = r.number(l["w_max_degps"], "limits.w_max_degps", 1e-6, 1000.0) * kDegToRad;
            }
        }
        if (const YAML::Node f = root["fsw"]) {
            if (f["k_hat0"]) {
                m.k_hat0 = r.number(f["k_hat0"], "fsw.k_hat0", 1e-4, 0.1);
            }
            if (f["bdot_max_degps"]) {
                m.bdot_max_degps = r.number(f["bdot_max_degps"], "fsw.bdot_max_degps", 0.01, 20.0);
            }
        }
        for (std::size_t i = 0; i < 2u; ++i) {
            if (std::fabs(m.w0_radps[i]) > m.w_max_radps) {
                r.fail("w0_degps", root["w0_degps"], "initial rate beyond limits.w_max_degps");
            }
            if (std::fabs(m.mu0_rad[i]) > m.mu_max_rad) {
                r.fail("mu0_deg", root["mu0_deg"], "initial tilt beyond limits.mu_max_deg");
            }
        }
    }

    std::unique_ptr<Plant> make_plant(const Scenario &s) const override
    {
        return std::unique_ptr<Plant>(new SailPlant(s));
    }

    std::uint64_t noise_seed(const Scenario &s) const override { return s.mission_part<SailScenario>().gyro.seed; }
};

}  // namespace

const MissionSection &observer_section()
{
    static const ObserverSection s;
    return s;
}

double GyroConfig::lsb_radps() const { return std::ldexp(1.0, -lsb_shift); }
double GimbalConfig::lsb_radps() const { return std::ldexp(1.0, -lsb_shift); }

Scenario sail_default_scenario()
{
    Scenario s;
    s.name = "default";
    s.source = "<built-in>";
    s.mission = "DETUMBLE";
    observer_section().defaults(s);
    s.fsw.table = observer_section().tables().front();
    s.duration_s = 120.0;
    return s;
}

const char *sigma_name(int sigma) { return sigma > 0 ? "M-phys" : "M-paper"; }

obs_params_t observer_boot_table(const std::string &name, double k_hat0_per_s2, double bdot_max_degps)
{
    const obs_params_t *t = nullptr;
    if (name == "obs_50hz_phys") { t = &OBS_TBL_50HZ_PHYS; }
    if (name == "obs_50hz_paper") { t = &OBS_TBL_50HZ_PAPER; }
    if (name == "obs_5hz_paper") { t = &OBS_TBL_5HZ_PAPER; }
    if (name == "obs_paper_printed") { t = &OBS_TBL_PAPER_PRINTED; }
    if (t == nullptr) {
        throw std::invalid_argument("unknown observer table '" + name + "'");
    }
    obs_params_t p = *t;
    if (k_hat0_per_s2 > 0.0) {   // kappa = K / 0.01 in q28
        p.kappa_init_q28 = q_of(k_hat0_per_s2 / 0.01, static_cast<int>(OBS_KAPPA_Q), "k_hat0");
    }
    if (bdot_max_degps > 0.0) {
        p.bdot_max_q29 = q_of(bdot_max_degps * kDegToRad, static_cast<int>(OBS_U_Q), "bdot_max_degps");
    }
    return p;
}

obs_params_t observer_boot_table(const Scenario &s)
{
    const SailScenario &m = s.mission_part<SailScenario>();
    return observer_boot_table(s.fsw.table, m.k_hat0, m.bdot_max_degps);
}

}  // namespace sim
