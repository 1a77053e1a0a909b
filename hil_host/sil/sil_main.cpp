// sil — software-in-the-loop driver (spec 00 §5), for any mission of the build.
//
//   sil run    --scenario F [--url memq://|udpm://...] [--log F] [--summary F] [--summary-json F]
//              [--upload IMG@T]... [--progress] [--fsw fixed|ref|...] [--determinism-check] [--batch]
//              [--duration S] [--pil ELF [--pil-machine M] | --pil-serial DEV [--pil-baud N] | --pil-loopback]
//              [--compare-sil] [--pil-insn CSV] [--pil-dir D] [--pil-timeout-ms N]
//              a board run: the batch driver with the flight software on the board (hil_host/pil);
//              --compare-sil flies SIL first and requires byte-identical streams (exit 4 otherwise)
//              --batch: no transport (batch.hpp): the same plant, packets, bridge core, fsw_step and
//              metrics without LCM, for long runs; fault-free scenarios (table files and uploads too);
//              --log writes the event log a memq run would. Otherwise: plant + bridge (fixed-point
//              flight code, or the mission's double reference) + log tap in ONE process on one lcm_t.
//   sil plant  --scenario F --url udpm://... [--summary F] [--summary-json F] [--ready-timeout-ms N] [--progress]
//   sil bridge --scenario F --url udpm://... [--idle-timeout-ms N]
//   sil ping   --url udpm://...    one runner heartbeat on GNC_CTL (logger start-up handshake)
//   sil logger --url udpm://... --log F [--idle-timeout-ms N]   lossless event logger of a udpm run
//   sil check  --scenario F    the scenario as a run would read it, its table (boot table, or the
//              table file through the flight upload path), without flying: one JSON line, or the
//              error and exit 1 (the campaign runner checks every dispersion's extremes with it)
// Exit (README "sil run: the command-line contract"):
//   0  run completed in control
//   1  error: the scenario does not load or its table is refused (nothing flown), or the summary
//      could not be written after the run, or a board run failed (link down, board fault or canary)
//   2  usage: a bad option or option value, named on stderr; nothing flown
//   3  LOSS OF CONTROL: the run flew, the plant diverged or missed more consecutive commands than
//      the scenario's deadline covers; the summary (written) says why (sil_run.hpp loss_of_control)
//   4  --determinism-check: the two flights' command/telemetry streams differ; --compare-sil: the
//      board's differ from SIL's
//   77 lcm_create failed (no multicast on loopback)
#include "fsw_cli.hpp"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

#include <sys/stat.h>
#include <unistd.h>

#include "bridge.hpp"
#include "bridge_node.hpp"
#include "channels.hpp"
#include "fsw_backend.hpp"
#include "gnc/sil_ctl_t.hpp"
#include "log_tap.hpp"
#include "metrics.hpp"
#include "plant_node.hpp"
#include "batch.hpp"
#include "sil_run.hpp"

namespace {

constexpr int kExitError = 1, kExitUsage = 2, kExitLossOfControl = 3, kExitNotDeterministic = 4;

// A bad option value, found before anything flies: exit kExitUsage.
struct UsageError : std::invalid_argument {
    using std::invalid_argument::invalid_argument;
};

void write_text(const std::string &path, const std::string &s)
{
    if (path.empty()) {
        return;
    }
    std::ofstream f(path);
    f << s;
    if (!f) {
        throw std::runtime_error("cannot write '" + path + "'");
    }
}

lcm_t *create_or_exit(const std::string &url)
{
    lcm_t *l = lcm_create(url.c_str());
    if (l == nullptr) {
        std::fprintf(stderr, "sil: lcm_create failed for '%s' (no multicast route on loopback? try "
                             "'ip route add 239.0.0.0/8 dev lo')\n", url.c_str());
        std::exit(77);
    }
    return l;
}

// IMG@T: a table image file and the run time (s) before whose frame it is uploaded. Table id and
// revision are the image header's own.
sil::Upload parse_upload(const std::string &arg, double duration_s)
try {
    const auto at = arg.rfind('@');
    if (at == std::string::npos || at == 0 || at + 1 >= arg.size()) {
        throw std::invalid_argument("--upload " + arg + ": expected IMAGE@T_S (a table image file and a time in s)");
    }
    const std::string t = arg.substr(at + 1);
    if (t.find(':') != std::string::npos) {
        throw std::invalid_argument("--upload " + arg + ": no revision suffix: table id and revision come from "
                                    "the image header");
    }
    double ts = 0.0;
    std::size_t used = 0;
    try {
        ts = std::stod(t, &used);
    } catch (const std::exception &) {
        used = 0;
    }
    if (used != t.size() || !(ts >= 0.0)) {
        throw std::invalid_argument("--upload " + arg + ": time '" + t + "' is not a non-negative number of seconds");
    }
    if (ts >= duration_s) {
        throw std::invalid_argument("--upload " + arg + ": time " + t + " s is not inside the run (duration " +
                                    std::to_string(duration_s) + " s)");
    }
    sil::Upload u = sil::upload_from_file(arg.substr(0, at), ts);
    u.what = arg.substr(0, at);
    return u;
} catch (const std::invalid_argument &e) {
    const std::string m = e.what();
    throw UsageError(m.rfind("--upload", 0) == 0 ? m : "--upload " + arg + ": " + m);
}

// An output file named by an option: it must be creatable or writable now, so that a run is
// never flown only to fail writing its result.
void check_output(const char *opt, const std::string &path)
{
    if (path.empty()) {
        return;
    }
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0) {
        if (S_ISDIR(st.st_mode)) {
            throw UsageError(std::string(opt) + " " + path + ": is a directory");
        }
        if (::access(path.c_str(), W_OK) != 0) {
            throw UsageError(std::string(opt) + " " + path + ": not writable (" + std::strerror(errno) + ")");
        }
        return;
    }
    const std::size_t slash = path.rfind('/');
    const std::string dir = (slash == std::string::npos) ? std::string(".") : (slash == 0 ? std::string("/") : path.substr(0, slash));
    if (::stat(dir.c_str(), &st) != 0 || !S_ISDIR(st.st_mode)) {
        throw UsageError(std::string(opt) + " " + path + ": directory '" + dir + "' does not exist");
    }
    if (::access(dir.c_str(), W_OK | X_OK) != 0) {
        throw UsageError(std::string(opt) + " " + path + ": cannot create a file in '" + dir + "' (" +
                         std::strerror(errno) + ")");
    }
}

// Every option of `sil run`, checked before anything flies (README "sil run: the command-line
// contract"). Fills o.
void check_run(const sim::Scenario &scn, const std::string &url, const std::string &fsw,
               const std::vector<std::string> &uploads, const std::string &log, const std::string &summary,
               const std::string &summary_json, sil::InprocOptions &o)
{
    o.url = url.empty() ? "memq://" : url;
    if (o.url.rfind("memq://", 0) != 0 && o.url.rfind("udpm://", 0) != 0) {
        throw UsageError("--url " + o.url + ": sil run flies over memq:// (deterministic, the default) or "
                         "udpm://GROUP:PORT?ttl=0");
    }
    const host::MissionHost &mh = host::mission_host(scn.mission);
    const std::vector<std::string> kinds = mh.ref_kinds();
    if (fsw != "fixed" && std::find(kinds.begin(), kinds.end(), fsw) == kinds.end()) {
        std::string l = "fixed";
        for (const std::string &k : kinds) {
            l += ", " + k;
        }
        throw UsageError("--fsw " + fsw + ": not a flight software of the " + std::string(mh.iface().name) +
                         " mission (" + l + ")");
    }
    o.fsw = fsw;
    if (!uploads.empty() && fsw != "fixed") {
        throw UsageError("--upload needs --fsw fixed: the reference flight software takes no table uploads");
    }
    for (const std::string &u : uploads) {
        o.uploads.push_back(parse_upload(u, scn.duration_s));
        try {
            sil::check_upload(scn, o.uploads.back());
        } catch (const std::invalid_argument &e) {
            throw UsageError("--upload " + u + ": " + e.what());
        }
    }
    check_output("--log", log);
    check_output("--summary", summary);
    check_output("--summary-json", summary_json);
    const std::pair<const char *, const std::string *> outs[] = {{"--log", &log}, {"--summary", &summary},
                                                                 {"--summary-json", &summary_json}};
    for (std::size_t i = 0; i < 3u; ++i) {
        for (std::size_t j = i + 1u; j < 3u; ++j) {
            if (!outs[i].second->empty() && *outs[i].second == *outs[j].second) {
                throw UsageError(std::string(outs[i].first) + " and " + outs[j].first + " name the same file '" +
                                 *outs[i].second + "'");
            }
        }
    }
    o.log_path = log;
}

void write_summary(const host::Summary &s, const std::string &text, const std::string &json)
{
    write_text(text, s.text());
    write_text(json, s.json());
}

int ping(const std::string &url)
{
    // One runner heartbeat on GNC_CTL: the run script publishes it until the logger has written
    // something, so the logger is known to be listening before the run starts.
    lcm_t *lcm = create_or_exit(url);
    gnc::sil_ctl_t m{};
    m.command = gnc::sil_ctl_t::CMD_HEARTBEAT;
    m.node_id = gnc::sil_ctl_t::NODE_RUNNER;
    std::vector<std::uint8_t> b(static_cast<std::size_t>(m.getEncodedSize()));
    const int n = m.encode(b.data(), 0, static_cast<int>(b.size()));
    const int rc = (n > 0) ? lcm_publish(lcm, sil::kChCtl, b.data(), static_cast<unsigned>(n)) : -1;
    lcm_destroy(lcm);
    return rc == 0 ? 0 : 1;
}

int logger(const std::string &url, const std::string &log, int idle_ms)
{
    // Separate-process logger of a udpm run: every channel to a standard LCM event log,
    // wall-clock timestamps, until the plant's STOP plus 500 ms of silence (idle_ms without any
    // message ends it too). Lossless where lcm-logger is not (log_tap.hpp).
    lcm_t *lcm = create_or_exit(url);
    std::uint64_t n = 0;
    {
        sil::LogTap tap(lcm, log, []() {
            return static_cast<std::int64_t>(std::chrono::duration_cast<std::chrono::microseconds>(
                std::chrono::system_clock::now().time_since_epoch()).count());
        });
        bool stop = false;
        lcm_subscription_t *sub = lcm_subscribe(
            lcm, sil::kChCtl,
            [](const lcm_recv_buf_t *rb, const char *, void *u) {
                gnc::sil_ctl_t m;
                if (m.decode(rb->data, 0, static_cast<int>(rb->data_size)) >= 0 &&
                    m.command == gnc::sil_ctl_t::CMD_STOP && m.node_id == gnc::sil_ctl_t::NODE_PLANT) {
                    *static_cast<bool *>(u) = true;
                }
            },
            &stop);
        int quiet_ms = 0;
        const int tick = 50;
        while (quiet_ms < (stop ? 500 : idle_ms)) {
            const int r = lcm_handle_timeout(lcm, tick);
            quiet_ms = (r > 0) ? 0 : quiet_ms + tick;
        }
        lcm_unsubscribe(lcm, sub);
        n = tap.events();
    }
    lcm_destroy(lcm);
    std::fprintf(stderr, "sil logger: %llu events to %s\n", static_cast<unsigned long long>(n), log.c_str());
    return 0;
}

void progress_line(sil::PlantNode &pn, const char *who)
{
    pn.set_progress([who](std::uint64_t k, std::uint64_t n) {
        if (k % 5000u == 0u || k == n) {
            std::fprintf(stderr, "\r  %s: step %llu / %llu", who, static_cast<unsigned long long>(k),
                         static_cast<unsigned long long>(n));
            if (k == n) { std::fprintf(stderr, "\n"); }
        }
    });
}

}  // namespace

// --pil-faults drop=P,flip=P,trunc=P,seed=N: per-frame probabilities (fractions) to ppm.
void parse_pil_faults(const std::string &spec, sil::PilRunOptions &o)
{
    std::size_t pos = 0;
    while (pos < spec.size()) {
        std::size_t end = spec.find(',', pos);
        end = (end == std::string::npos) ? spec.size() : end;
        const std::string item = spec.substr(pos, end - pos);
        const std::size_t eq = item.find('=');
        const std::string k = item.substr(0, eq);
        const std::string v = (eq == std::string::npos) ? std::string() : item.substr(eq + 1);
        char *stop = nullptr;
        const double x = std::strtod(v.c_str(), &stop);
        if (eq == std::string::npos || v.empty() || stop == nullptr || *stop != '\0' || !(x >= 0.0)) {
            throw UsageError("--pil-faults " + spec + ": '" + item + "' is not KEY=VALUE with a number >= 0");
        }
        if (k == "seed") {
            o.fault_seed = static_cast<std::uint64_t>(x);
            pos = end + 1;
            continue;
        }
        if (x > 1.0) {
            throw UsageError("--pil-faults " + spec + ": " + k + " is a fraction in [0, 1]");
        }
        const std::uint32_t ppm = static_cast<std::uint32_t>(x * 1e6 + 0.5);
        if (k == "drop") {
            o.drop_ppm = ppm;
        } else if (k == "flip") {
            o.flip_ppm = ppm;
        } else if (k == "trunc") {
            o.trunc_ppm = ppm;
        } else {
            throw UsageError("--pil-faults " + spec + ": unknown key '" + k + "' (drop, flip, trunc, seed)");
        }
        pos = end + 1;
    }
}

int main(int argc, char **argv)
try {
    CLI::App app{"sil — software-in-the-loop driver: plant, bridge and flight code over LCM"};
    app.require_subcommand(1);
    std::string scn_path, url, log, summary, summary_json, fsw = "fixed";
    std::vector<std::string> uploads;
    bool progress = false, det_check = false, batch = false, compare_sil = false;
    int ready_ms = 10000, idle_ms = 30000;
    double duration = 0.0;
    sil::PilRunOptions pil;
    const std::string url_help = "LCM URL, e.g. udpm://239.255.76.67:7667?ttl=0";
    const CLI::Validator non_empty(
        [](std::string &v) { return v.empty() ? std::string("must not be empty") : std::string(); }, "", "NonEmpty");

    CLI::App *run = app.add_subcommand("run", "plant + bridge + flight code in one process (memq by default)");
    run->add_option("--scenario", scn_path, "scenario YAML")->required()->check(CLI::ExistingFile);
    run->add_option("--url", url, "LCM URL: memq:// (default) or udpm://...")->check(non_empty);
    run->add_option("--log", log, "LCM event log to write")->check(non_empty);
    run->add_option("--summary", summary, "summary text to write")->check(non_empty);
    run->add_option("--summary-json", summary_json, "summary JSON to write")->check(non_empty);
    run->add_option("--upload", uploads, "IMAGE@T_S: upload a table image (table id and revision from its "
                                         "header) before the first frame at or after T_S s; repeatable");
    run->add_option("--fsw", fsw, "flight software: fixed, or the mission's reference (ref, ...)")->check(non_empty);
    run->add_flag("--progress", progress, "progress line on stderr")->disable_flag_override();
    run->add_flag("--determinism-check", det_check,
                  "fly the run twice and compare the command/telemetry streams (the determinism verdict)")
        ->disable_flag_override();
    run->add_flag("--batch", batch, "no transport: the in-process lock-step driver (same plant, packets, bridge, "
                                    "flight code, uploads, metrics and --log; no LCM, no faults)")
        ->disable_flag_override();
    run->add_option("--duration", duration, "fly only the first S seconds of the scenario (reduced runs)")
        ->check(CLI::PositiveNumber);
    // PIL / HIL (spec 00 §6, hil_host/pil): the batch driver with the flight software on a board.
    run->add_option("--pil", pil.elf, "PIL: fly the flight software in this board image (fsw_pil.elf) under QEMU")
        ->check(CLI::ExistingFile);
    run->add_option("--pil-machine", pil.machine, "QEMU machine for --pil: mps2-an385 (M3, default) or mps2-an386 (M4)")
        ->check(CLI::IsMember({"mps2-an385", "mps2-an386"}));
    run->add_option("--pil-serial", pil.serial, "HIL: the board on this serial device (raw 8N1, e.g. ttyUSB0)")
        ->check(non_empty);
    run->add_option("--pil-baud", pil.baud, "HIL: the serial rate (default 921600)")->check(CLI::PositiveNumber);
    run->add_flag("--pil-loopback", pil.loopback, "the board session compiled for the host, in this process (the "
                                                  "link protocol without an emulator)")
        ->disable_flag_override();
    run->add_option("--pil-dir", pil.dir, "directory for QEMU's socket and logs (default: current)")->check(CLI::ExistingDirectory);
    run->add_option("--pil-timeout-ms", pil.timeout_ms, "link: wait this long for a reply before re-sending")
        ->check(CLI::PositiveNumber);
    run->add_option("--pil-insn", pil.insn_csv, "write the board's per-step instruction counts (CSV)")->check(non_empty);
    run->add_option("--pil-retx", pil.retx, "link: re-sends of one request before a step is missed (default 3)")
        ->check(CLI::Range(0, 100));
    run->add_option("--pil-down-after", pil.down_after, "link: consecutive missed steps that mean the link is down")
        ->check(CLI::Range(1, 100000));
    std::string pil_faults, pil_hash;
    run->add_option("--pil-faults", pil_faults, "faults on the link's byte stream, per frame, both ways: "
                                                "drop=P,flip=P,trunc=P,seed=N (P a fraction, e.g. 0.05)")
        ->check(non_empty);
    run->add_option("--pil-reset-at", pil.reset_at, "fault injection: reset the board before step K")
        ->check(CLI::NonNegativeNumber);
    run->add_option("--pil-silent-at", pil.silent_at, "fault injection: the board falls silent at step K")
        ->check(CLI::NonNegativeNumber);
    run->add_option("--pil-layout-hash", pil_hash, "test hook: expect this layout hash (hex) from the board")
        ->check(non_empty);
    run->add_flag("--compare-sil", compare_sil, "with a board: fly the run in SIL first and require byte-identical "
                                                "command and telemetry streams (exit 4 otherwise)")
        ->disable_flag_override();

    CLI::App *plant = app.add_subcommand("plant", "the plant node of a separate-process run");
    plant->add_option("--scenario", scn_path, "scenario YAML")->required()->check(CLI::ExistingFile);
    plant->add_option("--url", url, url_help)->required();
    plant->add_option("--summary", summary, "summary text to write");
    plant->add_option("--summary-json", summary_json, "summary JSON to write");
    plant->add_option("--ready-timeout-ms", ready_ms, "wait this long for the bridge")
        ->check(fsw_cli::Int())->check(CLI::Range(1, 600000));
    plant->add_flag("--progress", progress, "progress line on stderr");

    CLI::App *br = app.add_subcommand("bridge", "the bridge node (fixed-point flight code) of a separate-process run");
    br->add_option("--scenario", scn_path, "scenario YAML")->required()->check(CLI::ExistingFile);
    br->add_option("--url", url, url_help)->required();
    br->add_option("--idle-timeout-ms", idle_ms, "end after this long without a message")
        ->check(fsw_cli::Int())->check(CLI::Range(1, 3600000));

    CLI::App *ck = app.add_subcommand("check", "read a scenario and check its table without flying");
    ck->add_option("--scenario", scn_path, "scenario YAML")->required()->check(CLI::ExistingFile);

    CLI::App *pg = app.add_subcommand("ping", "one runner heartbeat on GNC_CTL");
    pg->add_option("--url", url, url_help)->required();

    CLI::App *lg = app.add_subcommand("logger", "lossless event logger of a udpm run");
    lg->add_option("--url", url, url_help)->required();
    lg->add_option("--log", log, "LCM event log to write")->required();
    lg->add_option("--idle-timeout-ms", idle_ms, "end after this long without a message")
        ->check(fsw_cli::Int())->check(CLI::Range(1, 3600000));

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError &e) {
        const int rc = app.exit(e);
        return (rc == 0) ? 0 : kExitUsage;
    }

    try {
        if (*pg) {
            return ping(url);
        }
        if (*lg) {
            return logger(url, log, idle_ms);
        }
        sim::Scenario scn = sim::load_scenario(scn_path);
        if (duration > 0.0) {
            if (duration > scn.duration_s) {
                throw UsageError("--duration " + std::to_string(duration) + " s is longer than scenario '" + scn.name +
                                 "' (" + std::to_string(scn.duration_s) + " s)");
            }
            scn.duration_s = duration;
        }
        if (*ck) {
            (void)sil::run_uploads(scn, {});                   // a table file through the upload path
            (void)sil::make_fixed_backend(scn);                // the boot table through the loader
            host::Summary s;
            sil::run_header(scn, "check", "", s);
            s.add_str("mission", scn.mission);
            s.add_int("period_us", scn.period_us);
            s.add_int("steps", static_cast<std::int64_t>(scn.n_steps()));
            std::string j = s.json();
            j.erase(std::remove(j.begin(), j.end(), '\n'), j.end());
            std::cout << j << "\n";
            return 0;
        }
        if (*run) {
            sil::InprocOptions o;
            check_run(scn, url, fsw, uploads, log, summary, summary_json, o);
            o.progress = progress;
            o.determinism_check = det_check;
            if (batch && (!url.empty() || det_check || fsw != "fixed")) {
                throw UsageError("--batch flies without a transport: no --url, --determinism-check "
                                 "or --fsw other than fixed");
            }
            if (batch && scn.faults.any()) {
                throw UsageError("--batch: scenario '" + scn.name + "' has faults, which act on the transport; fly it "
                                 "without --batch");
            }
            parse_pil_faults(pil_faults, pil);
            if (!pil_hash.empty()) {
                pil.expect_hash_set = true;
                pil.expect_hash = static_cast<std::uint32_t>(std::stoul(pil_hash, nullptr, 16));
            }
            const int n_boards = (pil.loopback ? 1 : 0) + (pil.elf.empty() ? 0 : 1) + (pil.serial.empty() ? 0 : 1);
            if (n_boards > 1) {
                throw UsageError("--pil, --pil-serial and --pil-loopback name one board each: give one");
            }
            if (pil.active() && (!url.empty() || det_check || fsw != "fixed" || scn.faults.any())) {
                throw UsageError("a board run (--pil, --pil-serial, --pil-loopback) flies the batch driver: no --url, "
                                 "--determinism-check, --fsw other than fixed, or transport faults");
            }
            if (compare_sil && !pil.active()) {
                throw UsageError("--compare-sil needs a board (--pil, --pil-serial or --pil-loopback)");
            }
            sil::InprocResult r;
            bool streams_differ = false;
            if (pil.active()) {
                sil::InprocResult ref;
                if (compare_sil) {
                    ref = sil::run_batch(scn, o.uploads, progress);
                }
                sil::PilRun board(scn, pil);
                r = sil::run_batch(scn, o.uploads, progress, &board, log);
                if (compare_sil) {
                    streams_differ = ref.core.digest_cmd != r.core.digest_cmd || ref.core.digest_tlm != r.core.digest_tlm;
                    r.summary.add_int("pil_vs_sil_same_streams", streams_differ ? 0 : 1);
                }
            } else {
                r = batch ? sil::run_batch(scn, o.uploads, progress, nullptr, log) : sil::run_inproc(scn, o);
            }
            std::cout << r.summary.text();
            write_summary(r.summary, summary, summary_json);
            if (r.board_exit != 0) {
                std::fprintf(stderr, "sil: the board run failed (exit %d): see the pil_* summary keys\n", r.board_exit);
                return kExitError;
            }
            if (streams_differ) {
                std::fprintf(stderr, "sil: PIL and SIL command/telemetry streams differ\n");
                return kExitNotDeterministic;
            }
            if (!r.loss_of_control.empty()) {
                std::fprintf(stderr, "sil: LOSS OF CONTROL: %s\n", r.loss_of_control.c_str());
                return kExitLossOfControl;
            }
            if (r.determinism_failed) {
                std::fprintf(stderr, "sil: NOT DETERMINISTIC: two flights of the run published different "
                                     "command or telemetry streams\n");
                return kExitNotDeterministic;
            }
            return 0;
        }
        if (*br) {
            lcm_t *lcm = create_or_exit(url);
            int rc = 1;
            {   // the node unsubscribes in its destructor: it must go before lcm_destroy
                std::unique_ptr<bridge::InProcessFswBackend> be = sil::make_fixed_backend(scn);
                bridge::Bridge core(*be, sil::run_limits(scn));
                sil::BridgeNode bn(lcm, core);
                rc = bn.serve(idle_ms);
                std::fprintf(stderr, "sil bridge: %s after %llu frames\n", rc == 0 ? "STOP" : "idle timeout",
                             static_cast<unsigned long long>(bn.frames()));
            }
            lcm_destroy(lcm);
            return rc == 0 ? 0 : 1;
        }
        // plant
        check_output("--summary", summary);
        check_output("--summary-json", summary_json);
        lcm_t *lcm = create_or_exit(url);
        host::Summary s;
        std::string lost;
        {
            sil::PlantNode pn(lcm, scn, false);
            sil::MetricsTap mt(lcm, scn);
            const std::vector<sil::Upload> ups = sil::run_uploads(scn, {});
            std::vector<bool> sent(ups.size(), false);
            pn.set_before_frame([&](std::uint64_t, std::int64_t utime) {
                for (std::size_t i = 0; i < ups.size(); ++i) {
                    if (!sent[i] && static_cast<double>(utime) * 1e-6 >= ups[i].t_s) {
                        sil::publish_upload(lcm, ups[i], utime);
                        sent[i] = true;
                    }
                }
            });
            if (!pn.wait_for_bridge(ready_ms)) {
                std::fprintf(stderr, "sil plant: no bridge READY on %s within %d ms\n", url.c_str(), ready_ms);
                lcm_destroy(lcm);
                return 1;
            }
            if (progress) {
                progress_line(pn, "sil plant");
            }
            const sil::PlantSummary p = pn.run();
            // Let the last telemetry arrive before the summary.
            for (int i = 0; i < 20 && lcm_handle_timeout(lcm, 10) > 0; ++i) {
            }
            sil::run_header(scn, "sil-fsw", url, s);
            sil::plant_summary(scn, p, s);
            mt.summary(s);
            lost = sil::loss_of_control(scn, p);
        }
        lcm_destroy(lcm);
        std::cout << s.text();
        write_summary(s, summary, summary_json);
        if (!lost.empty()) {
            std::fprintf(stderr, "sil plant: LOSS OF CONTROL: %s\n", lost.c_str());
            return kExitLossOfControl;
        }
        return 0;
    } catch (const UsageError &e) {
        std::fprintf(stderr, "sil: %s\n", e.what());
        return kExitUsage;
    }
} catch (const std::exception &e) {
    // Whatever escaped (also from CLI11's set-up or a summary write): a message, never an abort.
    std::fprintf(stderr, "sil: %s\n", e.what());
    return kExitError;
} catch (...) {
    std::fprintf(stderr, "sil: unexpected error\n");
    return kExitError;
}
