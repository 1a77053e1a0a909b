#include "scenario/scenario.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <initializer_list>
#include <set>
#include <sstream>

namespace sim {

namespace {

constexpr double kDegToRad = 3.14159265358979323846 / 180.0;

// Collects the source name so every message says which file and key failed.
class Reader {
public:
    explicit Reader(std::string source) : source_(std::move(source)) {}

    [[noreturn]] void fail(const std::string &key, const YAML::Node &node, const std::string &what) const
    {
        std::ostringstream os;
        os << source_ << ": key '" << key << "'";
        if (node.IsDefined() && node.Mark().line >= 0) {
            os << " (line " << (node.Mark().line + 1) << ")";
        }
        os << ": " << what;
        throw ScenarioError(os.str());
    }

    [[noreturn]] void fail_file(const std::string &what) const { throw ScenarioError(source_ + ": " + what); }

    // Unknown keys are errors: a misspelt optional key would otherwise silently keep its default.
    void check_keys(const YAML::Node &map, const std::string &prefix, std::initializer_list<const char *> allowed) const
    {
        if (!map.IsMap()) {
            fail(prefix.empty() ? std::string("<document>") : prefix, map, "must be a mapping");
        }
        std::set<std::string> seen;
        for (const auto &kv : map) {
            const std::string k = kv.first.Scalar();
            // yaml-cpp 0.7 accepts duplicate keys and silently uses the first; refuse them.
            if (!seen.insert(k).second) {
                fail(join(prefix, k), kv.first, "duplicate key");
            }
            bool ok = false;
            for (const char *a : allowed) {
                ok = ok || (k == a);
            }
            if (!ok) {
                fail(join(prefix, k), kv.first, "unknown key");
            }
        }
    }

    static std::string join(const std::string &prefix, const std::string &k)
    {
        return prefix.empty() ? k : prefix + "." + k;
    }

    double number(const YAML::Node &n, const std::string &key, double lo, double hi) const
    {
        if (!n.IsScalar()) {
            fail(key, n, "must be a number");
        }
        double v = 0.0;
        try {
            v = n.as<double>();
        } catch (const YAML::Exception &) {
            fail(key, n, "not a number: '" + n.Scalar() + "'");
        }
        if (!std::isfinite(v)) {
            fail(key, n, "must be finite, got '" + n.Scalar() + "'");
        }
        if (!(v >= lo && v <= hi)) {
            std::ostringstream os;
            os << "out of range: " << n.Scalar() << " not in [" << lo << ", " << hi << "]";
            fail(key, n, os.str());
        }
        return v;
    }

    std::int64_t integer(const YAML::Node &n, const std::string &key, std::int64_t lo, std::int64_t hi) const
    {
        if (!n.IsScalar()) {
            fail(key, n, "must be an integer");
        }
        long long v = 0;
        try {
            v = n.as<long long>();
        } catch (const YAML::Exception &) {
            fail(key, n, "not an integer: '" + n.Scalar() + "'");
        }
        if (v < lo || v > hi) {
            std::ostringstream os;
            os << "out of range: " << v << " not in [" << lo << ", " << hi << "]";
            fail(key, n, os.str());
        }
        return static_cast<std::int64_t>(v);
    }

    std::uint64_t unsigned64(const YAML::Node &n, const std::string &key) const
    {
        if (!n.IsScalar() || n.Scalar().empty() || n.Scalar()[0] == '-') {
            fail(key, n, "must be a non-negative integer");
        }
        try {
            return n.as<unsigned long long>();
        } catch (const YAML::Exception &) {
            fail(key, n, "not a non-negative integer: '" + n.Scalar() + "'");
        }
    }

    std::array<double, 2> pair(const YAML::Node &n, const std::string &key, double lo, double hi) const
    {
        if (!n.IsSequence() || n.size() != 2u) {
            fail(key, n, "must be a list of two numbers [y, z]");
        }
        return {number(n[0], key + "[0]", lo, hi), number(n[1], key + "[1]", lo, hi)};
    }

    std::string text(const YAML::Node &n, const std::string &key) const
    {
        if (!n.IsScalar()) {
            fail(key, n, "must be a string");
        }
        return n.Scalar();
    }

    const std::string &source() const { return source_; }

private:
    std::string source_;
};

void parse_faults_lockstep(const YAML::Node &root, const Reader &r, Scenario &s)
{
    if (const YAML::Node f = root["faults"]) {
        r.check_keys(f, "faults", {"seed", "drop_ppm", "dup_ppm", "reorder_ppm", "reorder_window", "bitflip_ppm",
                                   "truncate_ppm", "gyro_nan_s", "gyro_spike_s"});
        auto ppm = [&](const char *k, std::uint32_t &v) {
            if (f[k]) {
                v = static_cast<std::uint32_t>(r.integer(f[k], std::string("faults.") + k, 0, 1000000));
            }
        };
        if (f["seed"]) {
            s.faults.seed = r.unsigned64(f["seed"], "faults.seed");
        }
        ppm("drop_ppm", s.faults.drop_ppm);
        ppm("dup_ppm", s.faults.dup_ppm);
        ppm("reorder_ppm", s.faults.reorder_ppm);
        ppm("bitflip_ppm", s.faults.bitflip_ppm);
        ppm("truncate_ppm", s.faults.truncate_ppm);
        if (f["reorder_window"]) {
            s.faults.reorder_window = static_cast<std::uint32_t>(r.integer(f["reorder_window"], "faults.reorder_window", 1, 100));
        }
        if (f["gyro_nan_s"]) {
            s.faults.gyro_nan_s = r.pair(f["gyro_nan_s"], "faults.gyro_nan_s", 0.0, 1.0e5);
        }
        if (f["gyro_spike_s"]) {
            s.faults.gyro_spike_s = r.pair(f["gyro_spike_s"], "faults.gyro_spike_s", 0.0, 1.0e5);
        }
    }
    if (const YAML::Node l = root["lockstep"]) {
        r.check_keys(l, "lockstep", {"retx_ms", "deadline_ms", "retx_max"});
        if (l["retx_ms"]) {
            s.lockstep.retx_ms = static_cast<std::uint32_t>(r.integer(l["retx_ms"], "lockstep.retx_ms", 1, 60000));
        }
        if (l["deadline_ms"]) {
            s.lockstep.deadline_ms = static_cast<std::uint32_t>(r.integer(l["deadline_ms"], "lockstep.deadline_ms", 1, 600000));
        }
        if (l["retx_max"]) {
            s.lockstep.retx_max = static_cast<std::uint32_t>(r.integer(l["retx_max"], "lockstep.retx_max", 0, 100));
        }
    }
}

// commands: [{t_s, cmd: MODE|IMP_START|IMP_ABORT|IMP_CLEAR, ...}] in flight units (steps, counts).
void parse_commands(const YAML::Node &root, const Reader &r, Scenario &s)
{
    const YAML::Node cs = root["commands"];
    if (!cs) {
        return;
    }
    if (!cs.IsSequence()) {
        r.fail("commands", cs, "must be a list of commands");
    }
    const double h = s.h_s();
    double t_prev = -1.0;
    for (std::size_t i = 0; i < cs.size(); ++i) {
        const YAML::Node c = cs[i];
        const std::string key = "commands[" + std::to_string(i) + "]";
        r.check_keys(c, key, {"t_s", "cmd", "mode", "t0_s", "tf_s", "target_pos_m", "target_vel_mps"});
        if (!c["t_s"] || !c["cmd"]) {
            r.fail(key, c, "needs t_s and cmd");
        }
        ScnCommand sc;
        sc.t_s = r.number(c["t_s"], key + ".t_s", 0.0, 1.0e6);
        if (sc.t_s < t_prev) {
            r.fail(key + ".t_s", c["t_s"], "commands must be in time order");
        }
        t_prev = sc.t_s;
        const std::string name = r.text(c["cmd"], key + ".cmd");
        if (name == "MODE") {
            sc.cmd = 1;
            const std::string m = c["mode"] ? r.text(c["mode"], key + ".mode") : std::string();
            const char *modes[] = {"BOOT", "STANDBY", "DETUMBLE", "SAFE", "RENDEZVOUS"};
            sc.args[0] = -1;
            for (std::int32_t k = 0; k < 5; ++k) {
                if (m == modes[k]) { sc.args[0] = k; }
            }
            if (sc.args[0] < 0) {
                r.fail(key + ".mode", c["mode"], "MODE needs mode: STANDBY | DETUMBLE | SAFE | RENDEZVOUS");
            }
        } else if (name == "IMP_START") {
            sc.cmd = 2;
            for (const char *k : {"t0_s", "tf_s"}) {
                if (!c[k]) { r.fail(key, c, std::string("IMP_START needs ") + k); }
            }
            const double t0 = r.number(c["t0_s"], key + ".t0_s", 0.0, 1.0e6);
            const double tf = r.number(c["tf_s"], key + ".tf_s", 0.0, 1.0e6);
            sc.args[0] = static_cast<std::int32_t>(std::llround(t0 / h));
            sc.args[1] = static_cast<std::int32_t>(std::llround(tf / h));
            for (int a = 0; a < 3; ++a) {
                if (c["target_pos_m"]) {
                    sc.args[static_cast<std::size_t>(2 + a)] = static_cast<std::int32_t>(std::llround(
                        r.number(c["target_pos_m"][static_cast<std::size_t>(a)], key + ".target_pos_m", -1.0e6, 1.0e6) * 1000.0));
                }
                if (c["target_vel_mps"]) {
                    sc.args[static_cast<std::size_t>(5 + a)] = static_cast<std::int32_t>(std::llround(
                        r.number(c["target_vel_mps"][static_cast<std::size_t>(a)], key + ".target_vel_mps", -100.0, 100.0) * 1.0e5));
                }
            }
        } else if (name == "IMP_ABORT") {
            sc.cmd = 3;
        } else if (name == "IMP_CLEAR") {
            sc.cmd = 4;
        } else {
            r.fail(key + ".cmd", c["cmd"], "unknown command '" + name + "' (MODE, IMP_START, IMP_ABORT, IMP_CLEAR)");
        }
        s.commands.push_back(sc);
    }
}

std::array<double, 3> triple(const Reader &r, const YAML::Node &n, const std::string &key, double lo, double hi)
{
    if (!n.IsSequence() || n.size() != 3u) {
        r.fail(key, n, "must be a list of three numbers [x, y, z]");
    }
    return {r.number(n[0], key + "[0]", lo, hi), r.number(n[1], key + "[1]", lo, hi), r.number(n[2], key + "[2]", lo, hi)};
}

void parse_nav(const YAML::Node &n, const Reader &r, NavSetup &v)
{
    r.check_keys(n, "cw.nav", {"profile", "f_hz", "sigma_p_m", "sigma_v_mps", "bias_p_m", "bias_v_mps", "range_m",
                               "dropouts_s", "dropout_ppm", "seed"});
    if (n["profile"]) {
        v.profile = r.text(n["profile"], "cw.nav.profile");
        if (v.profile == "ideal") {
            v.sigma_p_m = 0.0; v.sigma_v_mps = 0.0;
        } else if (v.profile == "nominal") {
            v.sigma_p_m = 0.1; v.sigma_v_mps = 1e-3;      // spec 50 §2.5
        } else if (v.profile == "degraded") {
            v.sigma_p_m = 0.5; v.sigma_v_mps = 5e-3;
        } else if (v.profile != "custom") {
            r.fail("cw.nav.profile", n["profile"], "must be ideal, nominal, degraded or custom");
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
    if (n["bias_p_m"]) { v.bias_p_m = triple(r, n["bias_p_m"], "cw.nav.bias_p_m", -1000.0, 1000.0); }
    if (n["bias_v_mps"]) { v.bias_v_mps = triple(r, n["bias_v_mps"], "cw.nav.bias_v_mps", -10.0, 10.0); }
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

// plant: cw (spec 50 §2).
void parse_cw_root(const YAML::Node &root, const Reader &r, Scenario &s)
{
    for (const char *k : {"model", "sigma", "k2_true_per_s2", "j_factor", "w0_degps", "mu0_deg", "mudot0_degps",
                          "propagator", "ode_substeps", "gyro", "gimbal", "limits"}) {
        if (root[k]) {
            r.fail(k, root[k], "not a key of plant: cw");
        }
    }
    s.period_us = 100000u;   // valve tick = fsw period, spec 50 §2.4
    s.fsw.table = "imp_default";
    if (root["period_us"]) {
        s.period_us = static_cast<std::uint32_t>(r.integer(root["period_us"], "period_us", 1000, 10000000));
    }
    s.duration_s = r.number(root["duration_s"], "duration_s", 0.0, 1.0e6);
    if (const YAML::Node c = root["cw"]) {
        r.check_keys(c, "cw", {"omega_radps", "a_nom_mps2", "x0", "x0_epoch_s", "eps_c", "eps", "t_min_us", "min_on",
                               "subtick_us", "stuck_off", "stuck_on", "nav"});
        if (c["x0_epoch_s"]) { s.cw.x0_epoch_s = r.number(c["x0_epoch_s"], "cw.x0_epoch_s", 0.0, 1.0e5); }
        if (c["omega_radps"]) { s.cw.omega_radps = r.number(c["omega_radps"], "cw.omega_radps", 8.0e-4, 1.2e-3); }
        if (c["a_nom_mps2"]) { s.cw.a_nom_mps2 = r.number(c["a_nom_mps2"], "cw.a_nom_mps2", 1e-4, 10.0); }
        if (const YAML::Node x = c["x0"]) {
            if (!x.IsSequence() || x.size() != 6u) {
                r.fail("cw.x0", x, "must be [x, x', y, y', z, z'] in m and m/s");
            }
            for (std::size_t i = 0; i < 6u; ++i) {
                s.cw.x0[i] = r.number(x[i], "cw.x0[" + std::to_string(i) + "]", -1.0e6, 1.0e6);
            }
        }
        if (c["eps_c"]) { s.cw.eps_c = r.number(c["eps_c"], "cw.eps_c", -0.5, 0.5); }
        if (const YAML::Node e = c["eps"]) {
            if (!e.IsSequence() || e.size() != 6u) {
                r.fail("cw.eps", e, "must list six per-thruster level errors");
            }
            for (std::size_t i = 0; i < 6u; ++i) { s.cw.eps[i] = r.number(e[i], "cw.eps", -0.5, 0.5); }
        }
        if (c["t_min_us"]) { s.cw.t_min_us = static_cast<std::uint32_t>(r.integer(c["t_min_us"], "cw.t_min_us", 0, 10000000)); }
        if (c["min_on"]) {
            const std::string m = r.text(c["min_on"], "cw.min_on");
            if (m != "drop" && m != "stretch") {
                r.fail("cw.min_on", c["min_on"], "must be drop or stretch");
            }
            s.cw.stretch = (m == "stretch");
        }
        if (c["subtick_us"]) { s.cw.subtick_us = static_cast<std::uint32_t>(r.integer(c["subtick_us"], "cw.subtick_us", 0, 1000000)); }
        for (const char *k : {"stuck_off", "stuck_on"}) {
            if (const YAML::Node f = c[k]) {
                r.check_keys(f, std::string("cw.") + k, {"thruster", "t_s"});
                if (!f["thruster"] || !f["t_s"]) {
                    r.fail(std::string("cw.") + k, f, "needs thruster (0..5: +x -x +y -y +z -z) and t_s");
                }
                const int j = static_cast<int>(r.integer(f["thruster"], std::string("cw.") + k + ".thruster", 0, 5));
                const double t = r.number(f["t_s"], std::string("cw.") + k + ".t_s", 0.0, 1.0e6);
                if (std::string(k) == "stuck_off") { s.cw.stuck_off_j = j; s.cw.stuck_off_t_s = t; }
                else { s.cw.stuck_on_j = j; s.cw.stuck_on_t_s = t; }
            }
        }
        if (c["nav"]) {
            parse_nav(c["nav"], r, s.cw.nav);
        }
    }
    if (const YAML::Node f = root["fsw"]) {
        r.check_keys(f, "fsw", {"table", "cal_enable"});
        if (f["cal_enable"]) {
            s.fsw.cal_enable = static_cast<int>(r.integer(f["cal_enable"], "fsw.cal_enable", 0, 1));
        }
        if (f["table"]) {
            s.fsw.table = r.text(f["table"], "fsw.table");
            if (s.fsw.table != "imp_default" && s.fsw.table != "imp_1s" && s.fsw.table != "imp_sub1ms") {
                r.fail("fsw.table", f["table"], "unknown rendezvous table '" + s.fsw.table +
                                                    "' (imp_default, imp_1s, imp_sub1ms)");
            }
        }
    }
    parse_faults_lockstep(root, r, s);
    parse_commands(root, r, s);
    if (s.n_steps() == 0u) {
        r.fail("duration_s", root["duration_s"], "shorter than one period");
    }
    const double spn = 1.0 / (s.cw.nav.f_hz * s.h_s());   // steps per nav sample
    if (std::fabs(spn - std::round(spn)) > 1e-9 || spn < 1.0) {
        r.fail("cw.nav.f_hz", root["cw"]["nav"], "the nav period must be a whole number of fsw periods");
    }
}

Scenario parse_root(const YAML::Node &root, const Reader &r)
{
    Scenario s = default_scenario();
    s.source = r.source();
    if (!root.IsDefined() || root.IsNull()) {
        r.fail_file("empty scenario");
    }
    r.check_keys(root, "",
                 {"name", "plant", "model", "sigma", "k2_true_per_s2", "j_factor", "period_us", "duration_s",
                  "w0_degps", "mu0_deg", "mudot0_degps", "propagator", "ode_substeps", "gyro", "gimbal", "limits",
                  "fsw", "faults", "lockstep", "cw", "commands"});

    for (const char *k : {"name", "duration_s"}) {
        if (!root[k]) {
            r.fail(k, root[k], "missing required key");
        }
    }
    s.name = r.text(root["name"], "name");
    if (root["plant"]) {
        s.plant = r.text(root["plant"], "plant");
        if (s.plant != "sail" && s.plant != "cw") {
            r.fail("plant", root["plant"], "unknown plant '" + s.plant + "' (known: sail, cw)");
        }
    }
    if (s.plant == "cw") {
        parse_cw_root(root, r, s);
        return s;
    }
    // The sail's identity (spec 10 §2.2: every scenario names its sigma).
    for (const char *k : {"model", "sigma"}) {
        if (!root[k]) {
            r.fail(k, root[k], "missing required key");
        }
    }
    if (root["cw"]) {
        r.fail("cw", root["cw"], "only for plant: cw");
    }
    const std::int64_t sig = r.integer(root["sigma"], "sigma", -1, 1);
    if (sig == 0) {
        r.fail("sigma", root["sigma"], "must be +1 (M-phys) or -1 (M-paper)");
    }
    s.sigma = static_cast<int>(sig);
    // sigma and model are both required and must agree, so a run never mixes them silently.
    const std::string model = r.text(root["model"], "model");
    if (model != "M-phys" && model != "M-paper") {
        r.fail("model", root["model"], "must be M-phys or M-paper, got '" + model + "'");
    }
    if (model != sigma_name(s.sigma)) {
        r.fail("model", root["model"], "'" + model + "' contradicts sigma = " + std::to_string(s.sigma));
    }
    if (root["k2_true_per_s2"]) {
        s.k2_true_per_s2 = r.number(root["k2_true_per_s2"], "k2_true_per_s2", 1e-6, 1.0);
    }
    if (root["j_factor"]) {
        s.j_factor = r.number(root["j_factor"], "j_factor", 0.5, 2.0);
    }
    if (root["period_us"]) {
        s.period_us = static_cast<std::uint32_t>(r.integer(root["period_us"], "period_us", 100, 10000000));
    }
    s.duration_s = r.number(root["duration_s"], "duration_s", 0.0, 1.0e5);
    if (root["w0_degps"]) {
        const auto w = r.pair(root["w0_degps"], "w0_degps", -1000.0, 1000.0);
        s.w0_radps = {w[0] * kDegToRad, w[1] * kDegToRad};
    }
    if (root["mu0_deg"]) {
        const auto m = r.pair(root["mu0_deg"], "mu0_deg", -90.0, 90.0);
        s.mu0_rad = {m[0] * kDegToRad, m[1] * kDegToRad};
    }
    if (root["mudot0_degps"]) {
        const auto m = r.pair(root["mudot0_degps"], "mudot0_degps", -1000.0, 1000.0);
        s.mudot0_radps = {m[0] * kDegToRad, m[1] * kDegToRad};
    }
    if (root["propagator"]) {
        const std::string p = r.text(root["propagator"], "propagator");
        if (p == "zoh") {
            s.propagator = Propagator::Zoh;
        } else if (p == "ode") {
            s.propagator = Propagator::Ode;
        } else {
            r.fail("propagator", root["propagator"], "must be zoh or ode, got '" + p + "'");
        }
    }
    if (root["ode_substeps"]) {
        s.ode_substeps = static_cast<std::uint32_t>(r.integer(root["ode_substeps"], "ode_substeps", 0, 1000000));
    }

    if (const YAML::Node g = root["gyro"]) {
        r.check_keys(g, "gyro", {"noise_radps", "bias_radps", "bias_sigma_radps", "seed", "lsb_shift", "max_cnt"});
        if (g["noise_radps"]) {
            s.gyro.noise_radps = r.number(g["noise_radps"], "gyro.noise_radps", 0.0, 1.0);
        }
        if (g["bias_radps"]) {
            s.gyro.bias_radps = r.pair(g["bias_radps"], "gyro.bias_radps", -1.0, 1.0);
        }
        if (g["bias_sigma_radps"]) {
            s.gyro.bias_sigma_radps = r.number(g["bias_sigma_radps"], "gyro.bias_sigma_radps", 0.0, 1.0);
        }
        if (g["seed"]) {
            s.gyro.seed = r.unsigned64(g["seed"], "gyro.seed");
        }
        if (g["lsb_shift"]) {
            s.gyro.lsb_shift = static_cast<int>(r.integer(g["lsb_shift"], "gyro.lsb_shift", 0, 30));
        }
        if (g["max_cnt"]) {
            s.gyro.max_cnt = static_cast<std::int32_t>(r.integer(g["max_cnt"], "gyro.max_cnt", 1, INT32_MAX));
        }
    }
    if (const YAML::Node g = root["gimbal"]) {
        r.check_keys(g, "gimbal", {"lsb_shift", "hw_limit_radps"});
        if (g["lsb_shift"]) {
            s.gimbal.lsb_shift = static_cast<int>(r.integer(g["lsb_shift"], "gimbal.lsb_shift", 0, 30));
        }
        if (g["hw_limit_radps"]) {
            s.gimbal.hw_limit_radps = r.number(g["hw_limit_radps"], "gimbal.hw_limit_radps", 1e-6, 10.0);
        }
    }
    if (const YAML::Node l = root["limits"]) {
        r.check_keys(l, "limits", {"mu_max_deg", "w_max_degps"});
        if (l["mu_max_deg"]) {
            s.mu_max_rad = r.number(l["mu_max_deg"], "limits.mu_max_deg", 1e-6, 90.0) * kDegToRad;
        }
        if (l["w_max_degps"]) {
            s.w_max_radps = r.number(l["w_max_degps"], "limits.w_max_degps", 1e-6, 1000.0) * kDegToRad;
        }
    }
    if (const YAML::Node f = root["fsw"]) {
        r.check_keys(f, "fsw", {"table", "k_hat0", "bdot_max_degps"});
        if (f["table"]) {
            s.fsw.table = r.text(f["table"], "fsw.table");
            bool known = false;
            for (const char *t : {"obs_50hz_phys", "obs_50hz_paper", "obs_5hz_paper", "obs_paper_printed"}) {
                known = known || (s.fsw.table == t);
            }
            if (!known) {
                r.fail("fsw.table", f["table"], "unknown table '" + s.fsw.table + "'");
            }
        }
        if (f["k_hat0"]) {
            s.fsw.k_hat0 = r.number(f["k_hat0"], "fsw.k_hat0", 1e-4, 0.1);
        }
        if (f["bdot_max_degps"]) {
            s.fsw.bdot_max_degps = r.number(f["bdot_max_degps"], "fsw.bdot_max_degps", 0.01, 20.0);
        }
    }
    parse_faults_lockstep(root, r, s);
    parse_commands(root, r, s);
    // Cross-key checks.
    if (s.n_steps() == 0u) {
        r.fail("duration_s", root["duration_s"], "shorter than one period");
    }
    for (std::size_t i = 0; i < 2u; ++i) {
        if (std::fabs(s.w0_radps[i]) > s.w_max_radps) {
            r.fail("w0_degps", root["w0_degps"], "initial rate beyond limits.w_max_degps");
        }
        if (std::fabs(s.mu0_rad[i]) > s.mu_max_rad) {
            r.fail("mu0_deg", root["mu0_deg"], "initial tilt beyond limits.mu_max_deg");
        }
    }
    return s;
}

}  // namespace

bool FaultSetup::any() const
{
    return (drop_ppm | dup_ppm | reorder_ppm | bitflip_ppm | truncate_ppm) != 0u || gyro_nan_s[0] >= 0.0 ||
           gyro_spike_s[0] >= 0.0;
}

double GyroConfig::lsb_radps() const { return std::ldexp(1.0, -lsb_shift); }
double GimbalConfig::lsb_radps() const { return std::ldexp(1.0, -lsb_shift); }

std::uint64_t Scenario::n_steps() const
{
    const double n = std::floor(duration_s / h_s() + 0.5);
    // duration_s is range-checked by the loader; guard anyway before the cast (UB otherwise).
    if (!(n >= 0.0 && n < 1.0e12)) {
        return 0u;
    }
    return static_cast<std::uint64_t>(n);
}

Scenario default_scenario()
{
    Scenario s;
    s.name = "default";
    s.source = "<built-in>";
    s.sigma = +1;
    s.w0_radps = {1.0 * kDegToRad, 1.0 * kDegToRad};
    s.mu_max_rad = 30.0 * kDegToRad;
    s.w_max_radps = 30.0 * kDegToRad;
    return s;
}

const char *sigma_name(int sigma) { return sigma > 0 ? "M-phys" : "M-paper"; }

Scenario parse_scenario(const std::string &yaml_text, const std::string &source_name)
{
    const Reader r(source_name);
    YAML::Node root;
    try {
        root = YAML::Load(yaml_text);
    } catch (const YAML::Exception &e) {
        r.fail_file(std::string("YAML syntax error: ") + e.what());
    }
    try {
        return parse_root(root, r);
    } catch (const ScenarioError &) {
        throw;
    } catch (const YAML::Exception &e) {
        r.fail_file(std::string("YAML error: ") + e.what());
    }
}

Scenario load_scenario(const std::string &path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        throw ScenarioError(path + ": cannot open scenario file");
    }
    std::ostringstream ss;
    ss << in.rdbuf();
    return parse_scenario(ss.str(), path);
}

}  // namespace sim
