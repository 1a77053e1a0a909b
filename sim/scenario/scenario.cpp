#include "scenario/scenario.hpp"

#include <yaml-cpp/yaml.h>

#include <cctype>
#include <cmath>
#include <set>
#include <sstream>

#include "iface_gen.hpp"
#include "scenario/reader.hpp"

namespace sim {

// ------------------------------------------------------------------------------------- Reader

void Reader::fail(const std::string &key, const YAML::Node &node, const std::string &what) const
{
    std::ostringstream os;
    os << source_ << ": key '" << key << "'";
    if (node.IsDefined() && node.Mark().line >= 0) {
        os << " (line " << (node.Mark().line + 1) << ")";
    }
    os << ": " << what;
    throw ScenarioError(os.str());
}

void Reader::fail_file(const std::string &what) const { throw ScenarioError(source_ + ": " + what); }

std::string Reader::join(const std::string &prefix, const std::string &k)
{
    return prefix.empty() ? k : prefix + "." + k;
}

void Reader::check_keys(const YAML::Node &map, const std::string &prefix, const std::vector<std::string> &allowed) const
{
    if (!map.IsMap()) {
        fail(prefix.empty() ? std::string("<document>") : prefix, map, "must be a mapping");
    }
    std::set<std::string> seen;
    for (const auto &kv : map) {
        const std::string k = kv.first.Scalar();
        if (!seen.insert(k).second) {
            fail(join(prefix, k), kv.first, "duplicate key");
        }
        bool ok = false;
        for (const std::string &a : allowed) {
            ok = ok || (k == a);
        }
        if (!ok) {
            fail(join(prefix, k), kv.first, "unknown key");
        }
    }
}

void Reader::check_keys(const YAML::Node &map, const std::string &prefix, std::initializer_list<const char *> allowed) const
{
    check_keys(map, prefix, std::vector<std::string>(allowed.begin(), allowed.end()));
}

void Reader::refuse(const YAML::Node &root, std::initializer_list<const char *> keys, const std::string &why) const
{
    for (const char *k : keys) {
        if (root[k]) {
            fail(k, root[k], why);
        }
    }
}

double Reader::number(const YAML::Node &n, const std::string &key, double lo, double hi) const
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

std::int64_t Reader::integer(const YAML::Node &n, const std::string &key, std::int64_t lo, std::int64_t hi) const
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

std::uint64_t Reader::unsigned64(const YAML::Node &n, const std::string &key) const
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

std::array<double, 2> Reader::pair(const YAML::Node &n, const std::string &key, double lo, double hi) const
{
    if (!n.IsSequence() || n.size() != 2u) {
        fail(key, n, "must be a list of two numbers");
    }
    return {number(n[0], key + "[0]", lo, hi), number(n[1], key + "[1]", lo, hi)};
}

std::array<double, 3> Reader::triple(const YAML::Node &n, const std::string &key, double lo, double hi) const
{
    if (!n.IsSequence() || n.size() != 3u) {
        fail(key, n, "must be a list of three numbers [x, y, z]");
    }
    return {number(n[0], key + "[0]", lo, hi), number(n[1], key + "[1]", lo, hi), number(n[2], key + "[2]", lo, hi)};
}

std::string Reader::text(const YAML::Node &n, const std::string &key) const
{
    if (!n.IsScalar()) {
        fail(key, n, "must be a string");
    }
    return n.Scalar();
}

std::string Reader::choice(const YAML::Node &n, const std::string &key, std::initializer_list<const char *> words) const
{
    const std::string v = text(n, key);
    std::string list;
    for (const char *w : words) {
        if (v == w) {
            return v;
        }
        list += list.empty() ? std::string(w) : (std::string(", ") + w);
    }
    fail(key, n, "must be one of " + list + ", got '" + v + "'");
}

// ------------------------------------------------------------------------------ core parser

namespace {

std::string upper(std::string s)
{
    for (char &c : s) {
        c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    }
    return s;
}

std::vector<std::string> plus(std::vector<std::string> a, const std::vector<std::string> &b)
{
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

const iface::Mission *iface_mission(const std::string &name)
{
    for (std::size_t i = 0; i < iface::kNumMissions; ++i) {
        if (name == iface::kMissions[i].name) {
            return &iface::kMissions[i];
        }
    }
    return nullptr;
}

void parse_faults_lockstep(const YAML::Node &root, const Reader &r, const MissionSection &sec, Scenario &s)
{
    if (const YAML::Node f = root["faults"]) {
        r.check_keys(f, "faults", plus({"seed", "drop_ppm", "dup_ppm", "reorder_ppm", "reorder_window", "bitflip_ppm",
                                        "truncate_ppm", "flip_frame", "flip_bit", "nan_s", "nan_channel", "spike_s",
                                        "spike_channel"},
                                       sec.fault_keys()));
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
        if (f["flip_frame"]) {
            s.faults.flip_frame = r.integer(f["flip_frame"], "faults.flip_frame", 0, INT64_C(1) << 40);
        }
        if (f["flip_bit"]) {
            s.faults.flip_bit = static_cast<std::uint32_t>(r.integer(f["flip_bit"], "faults.flip_bit", 0, 8 * 1024 - 1));
        }
        if (f["reorder_window"]) {
            s.faults.reorder_window = static_cast<std::uint32_t>(r.integer(f["reorder_window"], "faults.reorder_window", 1, 100));
        }
        if (f["nan_s"]) {
            s.faults.nan_s = r.pair(f["nan_s"], "faults.nan_s", 0.0, 1.0e7);
        }
        if (f["spike_s"]) {
            s.faults.spike_s = r.pair(f["spike_s"], "faults.spike_s", 0.0, 1.0e7);
        }
        if (f["nan_channel"]) {
            s.faults.nan_channel = static_cast<std::uint32_t>(r.integer(f["nan_channel"], "faults.nan_channel", 0, 15));
        }
        if (f["spike_channel"]) {
            s.faults.spike_channel = static_cast<std::uint32_t>(r.integer(f["spike_channel"], "faults.spike_channel", 0, 15));
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

// The mode names of a mission's executive: the executive's own and the mission's mode.
std::vector<std::string> mode_names(const iface::Mission &m)
{
    std::vector<std::string> v;
    for (std::size_t i = 0; i < iface::kNumExecModes; ++i) {
        v.emplace_back(iface::kExecModes[i].name);
    }
    v.emplace_back(m.name);
    return v;
}

// commands: [{t_s, cmd: MODE | <telecommand>, ...}]: MODE takes mode: <name>; a telecommand takes
// its arguments in scenario units, converted to flight units by the interface description.
void parse_commands(const YAML::Node &root, const Reader &r, const iface::Mission &m, Scenario &s)
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
        if (!c.IsMap() || !c["t_s"] || !c["cmd"]) {
            r.fail(key, c, "needs t_s and cmd");
        }
        ScnCommand sc;
        sc.t_s = r.number(c["t_s"], key + ".t_s", 0.0, 1.0e7);
        if (sc.t_s < t_prev) {
            r.fail(key + ".t_s", c["t_s"], "commands must be in time order");
        }
        t_prev = sc.t_s;
        sc.name = r.text(c["cmd"], key + ".cmd");
        if (sc.name == "MODE") {
            r.check_keys(c, key, {"t_s", "cmd", "mode"});
            sc.cmd = iface::kCmdMode;
            const std::string want = c["mode"] ? r.text(c["mode"], key + ".mode") : std::string();
            sc.args[0] = -1;
            std::string list;
            for (std::size_t k = 0; k < iface::kNumExecModes; ++k) {
                if (want == iface::kExecModes[k].name) {
                    sc.args[0] = static_cast<std::int32_t>(iface::kExecModes[k].value);
                }
            }
            if (want == m.name) {
                sc.args[0] = static_cast<std::int32_t>(m.mode);
            }
            for (const std::string &n : mode_names(m)) {
                list += (list.empty() ? "" : " | ") + n;
            }
            if (sc.args[0] < 0) {
                r.fail(key + ".mode", c["mode"], "MODE needs mode: " + list);
            }
            s.commands.push_back(sc);
            continue;
        }
        const iface::Tc *tc = nullptr;
        std::string names = "MODE";
        for (std::size_t k = 0; k < m.n_tcs; ++k) {
            names += std::string(", ") + m.tcs[k].name;
            if (sc.name == m.tcs[k].name) {
                tc = &m.tcs[k];
            }
        }
        if (tc == nullptr) {
            r.fail(key + ".cmd", c["cmd"], "unknown command '" + sc.name + "' for mission " + m.name + " (" + names + ")");
        }
        std::vector<std::string> allowed{"t_s", "cmd"};
        for (std::size_t a = 0; a < tc->n_args; ++a) {
            allowed.emplace_back(tc->args[a].name);
        }
        r.check_keys(c, key, allowed);
        sc.cmd = tc->id;
        std::size_t word = 0;
        for (std::size_t a = 0; a < tc->n_args; ++a) {
            const iface::TcArg &arg = tc->args[a];
            const YAML::Node v = c[arg.name];
            const std::string ak = key + "." + arg.name;
            if (!v && arg.required) {
                r.fail(key, c, sc.name + " needs " + arg.name);
            }
            for (int e = 0; e < arg.n; ++e, ++word) {
                if (!v || word >= sc.args.size()) {
                    continue;
                }
                double x = 0.0;
                if (arg.n == 1) {
                    x = r.number(v, ak, arg.lo, arg.hi);
                } else {
                    if (!v.IsSequence() || v.size() != static_cast<std::size_t>(arg.n)) {
                        r.fail(ak, v, "must be a list of " + std::to_string(arg.n) + " numbers");
                    }
                    x = r.number(v[static_cast<std::size_t>(e)], ak, arg.lo, arg.hi);
                }
                const double w = arg.steps ? (x / h) : (x * arg.scale);
                if (!(std::fabs(w) <= 2147483647.0)) {
                    r.fail(ak, v, "does not fit the flight's int32 argument");
                }
                sc.args[word] = static_cast<std::int32_t>(std::llround(w));
            }
        }
        s.commands.push_back(sc);
    }
}

}  // namespace

bool FaultSetup::any() const
{
    return (drop_ppm | dup_ppm | reorder_ppm | bitflip_ppm | truncate_ppm) != 0u || nan_s[0] >= 0.0 || spike_s[0] >= 0.0 ||
           flip_frame >= 0;
}

std::uint64_t Scenario::n_steps() const
{
    if (period_us == 0u) {
        return 0u;
    }
    const double n = std::floor(duration_s / h_s() + 0.5);
    // duration_s is range-checked by the loader; guard anyway before the cast (UB otherwise).
    if (!(n >= 0.0 && n < 1.0e12)) {
        return 0u;
    }
    return static_cast<std::uint64_t>(n);
}

Scenario parse_scenario_with(const std::string &yaml_text, const std::string &source_name, const SectionLookup &lookup,
                             const std::vector<std::string> &known)
{
    const Reader r(source_name);
    YAML::Node root;
    try {
        root = YAML::Load(yaml_text);
    } catch (const YAML::Exception &e) {
        r.fail_file(std::string("YAML syntax error: ") + e.what());
    }
    try {
        if (!root.IsDefined() || root.IsNull()) {
            r.fail_file("empty scenario");
        }
        if (!root.IsMap()) {
            r.fail_file("a scenario is a mapping of keys");
        }
        std::string list;
        for (const std::string &k : known) {
            std::string l = k;
            for (char &ch : l) {
                ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
            }
            list += (list.empty() ? "" : ", ") + l;
        }
        for (const char *k : {"name", "mission", "duration_s"}) {
            if (!root[k]) {
                r.fail(k, root[k], std::string("missing required key") +
                                       (std::string(k) == "mission" ? " (the mission it flies: " + list + ")" : ""));
            }
        }
        Scenario s;
        s.source = r.source();
        s.name = r.text(root["name"], "name");
        s.mission = upper(r.text(root["mission"], "mission"));
        const MissionSection *sec = lookup(s.mission);
        const iface::Mission *im = iface_mission(s.mission);
        if (sec == nullptr || im == nullptr) {
            r.fail("mission", root["mission"], "unknown mission '" + r.text(root["mission"], "mission") +
                                                   "' (this build flies: " + list + ")");
        }
        sec->defaults(s);
        r.check_keys(root, "", plus({"name", "mission", "plant", "period_us", "duration_s", "fsw", "faults", "lockstep",
                                     "commands"},
                                    sec->root_keys()));
        const std::vector<std::string> tables = sec->tables();
        if (s.fsw.table.empty() && !tables.empty()) {
            s.fsw.table = tables.front();
        }
        if (root["plant"]) {
            s.plant = r.text(root["plant"], "plant");   // the mission's parser checks the variant
        }
        if (root["period_us"]) {
            s.period_us = static_cast<std::uint32_t>(r.integer(root["period_us"], "period_us", 100, 10000000));
        }
        s.duration_s = r.number(root["duration_s"], "duration_s", 0.0, 1.0e7);
        if (const YAML::Node f = root["fsw"]) {
            r.check_keys(f, "fsw", plus({"table", "table_file"}, sec->fsw_keys()));
            if (f["table"]) {
                s.fsw.table = r.text(f["table"], "fsw.table");
                bool ok = false;
                std::string tl;
                for (const std::string &t : tables) {
                    ok = ok || (t == s.fsw.table);
                    tl += (tl.empty() ? "" : ", ") + t;
                }
                if (!ok) {
                    r.fail("fsw.table", f["table"], "unknown " + std::string(im->name) + " table '" + s.fsw.table +
                                                        "' (" + tl + ")");
                }
            }
            if (f["table_file"]) {
                s.fsw.table_file = r.text(f["table_file"], "fsw.table_file");
                if (s.fsw.table_file.empty()) {
                    r.fail("fsw.table_file", f["table_file"], "must name a table image file");
                }
                // The file is the whole table: the flight software boots without one and takes
                // it by upload, so a built-in table or its tuning keys would be silently unused.
                for (const std::string &k : plus({"table"}, sec->fsw_keys())) {
                    if (f[k]) {
                        r.fail("fsw." + k, f[k], "cannot be combined with fsw.table_file (the file is the whole table)");
                    }
                }
            }
        }
        parse_faults_lockstep(root, r, *sec, s);
        sec->parse(root, r, s);
        if (s.n_steps() == 0u) {
            r.fail("duration_s", root["duration_s"], "shorter than one period");
        }
        parse_commands(root, r, *im, s);
        return s;
    } catch (const ScenarioError &) {
        throw;
    } catch (const YAML::Exception &e) {
        r.fail_file(std::string("YAML error: ") + e.what());
    }
}

}  // namespace sim
