// sil — software-in-the-loop driver (spec 00 §5).
//
//   sil run    --scenario F [--url memq://] [--log F] [--summary F] [--upload IMG@T[:REV]]... [--progress]
//              [--fsw fixed|ref|ref-per-axis]
//              plant + bridge (fixed-point flight code, or the double reference) + log tap in ONE
//              process on one lcm_t.
//   sil plant  --scenario F --url udpm://... [--summary F] [--ready-timeout-ms N] [--progress]
//   sil bridge --scenario F --url udpm://... [--idle-timeout-ms N]
//   sil ping   --url udpm://...    one runner heartbeat on GNC_CTL (logger start-up handshake)
//   sil logger --url udpm://... --log F [--idle-timeout-ms N]   lossless event logger of a udpm run
//              the two ends as separate processes (udpm); log with lcm-logger.
// Exit: 0 run completed (also a DIVERGED end: that is a result, in the summary), 1 error,
// 2 usage, 77 lcm_create failed (no multicast on loopback).
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>
#include <vector>

#include "bridge.hpp"
#include "bridge_node.hpp"
#include "channels.hpp"
#include "gnc/sil_ctl_t.hpp"
#include "log_tap.hpp"
#include "fsw_backend.hpp"
#include "metrics.hpp"
#include "plant_node.hpp"
#include "sil_run.hpp"

namespace {

int usage()
{
    std::fprintf(stderr,
                 "usage: sil run|plant|bridge|ping|logger --scenario FILE [--url URL] [--log FILE] [--summary FILE]\n"
                 "           [--upload IMAGE@T_S[:REV]] [--progress] [--fsw fixed|ref|ref-per-axis]\n"
                 "           [--ready-timeout-ms N] [--idle-timeout-ms N]\n");
    return 2;
}

std::vector<std::uint8_t> read_file(const std::string &p)
{
    std::ifstream f(p, std::ios::binary);
    if (!f) {
        throw std::runtime_error("cannot read '" + p + "'");
    }
    return std::vector<std::uint8_t>((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

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

}  // namespace

int main(int argc, char **argv)
{
    if (argc < 2) {
        return usage();
    }
    const std::string mode = argv[1];
    std::string scn_path, url, log, summary, fsw = "fixed";
    std::vector<sil::Upload> uploads;
    bool progress = false;
    int ready_ms = 10000, idle_ms = 30000;
    for (int i = 2; i < argc; ++i) {
        const std::string a = argv[i];
        auto val = [&](std::string &dst) {
            if (i + 1 >= argc) { std::exit(usage()); }
            dst = argv[++i];
        };
        std::string tmp;
        if (a == "--scenario") { val(scn_path); }
        else if (a == "--url") { val(url); }
        else if (a == "--log") { val(log); }
        else if (a == "--summary") { val(summary); }
        else if (a == "--progress") { progress = true; }
        else if (a == "--fsw") { val(fsw); }
        else if (a == "--ready-timeout-ms") { val(tmp); ready_ms = std::atoi(tmp.c_str()); }
        else if (a == "--idle-timeout-ms") { val(tmp); idle_ms = std::atoi(tmp.c_str()); }
        else if (a == "--upload") {
            val(tmp);
            const auto at = tmp.rfind('@');
            if (at == std::string::npos) { return usage(); }
            sil::Upload u;
            u.image = read_file(tmp.substr(0, at));
            std::string rest = tmp.substr(at + 1);
            const auto colon = rest.find(':');
            u.t_s = std::atof(rest.substr(0, colon).c_str());
            if (colon != std::string::npos) { u.revision = std::atoi(rest.substr(colon + 1).c_str()); }
            uploads.push_back(u);
        } else {
            return usage();
        }
    }
    if (mode == "ping") {
        // One runner heartbeat on GNC_CTL: the run script publishes it until the logger has
        // written something, so the logger is known to be listening before the run starts.
        if (url.empty()) {
            return usage();
        }
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
    if (mode == "logger") {
        // Separate-process logger of a udpm run: every channel to a standard LCM event log,
        // wall-clock timestamps, until the plant's STOP plus idle_ms of silence (default 30 s
        // without any message ends it too). Lossless where lcm-logger is not (log_tap.hpp).
        if (url.empty() || log.empty()) {
            return usage();
        }
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
    if (scn_path.empty()) {
        return usage();
    }
    try {
        const sim::Scenario scn = sim::load_scenario(scn_path);
        if (mode == "run") {
            sil::InprocOptions o;
            o.url = url.empty() ? "memq://" : url;
            o.log_path = log;
            o.uploads = uploads;
            o.progress = progress;
            o.fsw = sil::fsw_kind(fsw);
            const sil::InprocResult r = sil::run_inproc(scn, o);
            std::cout << r.summary;
            write_text(summary, r.summary);
            return 0;
        }
        if (url.empty()) {
            std::fprintf(stderr, "sil %s: --url is required (e.g. udpm://239.255.76.67:7667?ttl=0)\n", mode.c_str());
            return 2;
        }
        if (mode == "bridge") {
            lcm_t *lcm = create_or_exit(url);
            int rc = 1;
            {   // the node unsubscribes in its destructor: it must go before lcm_destroy
                std::unique_ptr<bridge::InProcessFswBackend> be = sil::make_fixed_backend(scn);
                bridge::Bridge core(*be, be->sensor_limits());
                sil::BridgeNode bn(lcm, core);
                rc = bn.serve(idle_ms);
                std::fprintf(stderr, "sil bridge: %s after %llu frames\n", rc == 0 ? "STOP" : "idle timeout",
                             static_cast<unsigned long long>(bn.frames()));
            }
            lcm_destroy(lcm);
            return rc == 0 ? 0 : 1;
        }
        if (mode == "plant") {
            lcm_t *lcm = create_or_exit(url);
            sil::InprocResult r;
            {
                sil::PlantNode pn(lcm, scn, false);
                sil::MetricsTap mt(lcm, scn.duration_s - 20.0);
                sil::configure_metrics(mt, scn);
                if (!pn.wait_for_bridge(ready_ms)) {
                    std::fprintf(stderr, "sil plant: no bridge READY on %s within %d ms\n", url.c_str(), ready_ms);
                    lcm_destroy(lcm);
                    return 1;
                }
                if (progress) {
                    pn.set_progress([](std::uint64_t k, std::uint64_t n) {
                        if (k % 5000u == 0u || k == n) {
                            std::fprintf(stderr, "\r  sil plant: step %llu / %llu", static_cast<unsigned long long>(k),
                                         static_cast<unsigned long long>(n));
                            if (k == n) { std::fprintf(stderr, "\n"); }
                        }
                    });
                }
                r.plant = pn.run();
                // Let the last telemetry arrive before the summary.
                for (int i = 0; i < 20 && lcm_handle_timeout(lcm, 10) > 0; ++i) {
                }
                r.summary = "scenario = " + scn.name + "\nmodel = " + sim::sigma_name(scn.sigma) + "\ntable = " +
                            scn.fsw.table + "\ntransport = " + url + "\n" + sil::plant_summary(r.plant) + mt.summary();
            }
            lcm_destroy(lcm);
            std::cout << r.summary;
            write_text(summary, r.summary);
            return 0;
        }
        return usage();
    } catch (const std::exception &e) {
        std::fprintf(stderr, "sil: %s\n", e.what());
        return 1;
    }
}
