#include "sil_run.hpp"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <sys/stat.h>

#include "bridge.hpp"
#include "bridge_node.hpp"
#include "channels.hpp"
#include "gnc/table_upload_v2_t.hpp"
#include "lcm_codec.hpp"
#include "log_tap.hpp"

namespace sil {

namespace {

std::uint32_t le32(const std::vector<std::uint8_t> &b, std::size_t off)
{
    return static_cast<std::uint32_t>(b[off]) | (static_cast<std::uint32_t>(b[off + 1]) << 8) |
           (static_cast<std::uint32_t>(b[off + 2]) << 16) | (static_cast<std::uint32_t>(b[off + 3]) << 24);
}

}  // namespace

Upload upload_from_file(const std::string &path, double t_s)
{
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) {
        throw std::invalid_argument("table image '" + path + "': cannot be read (" + std::strerror(errno) + ")");
    }
    if (!S_ISREG(st.st_mode)) {
        throw std::invalid_argument("table image '" + path + "': not a regular file");
    }
    if (static_cast<std::uint64_t>(st.st_size) > FSW_TABLE_CAP_BYTES) {
        throw std::invalid_argument("table image '" + path + "': " + std::to_string(st.st_size) +
                                    " bytes, more than the loader's " + std::to_string(FSW_TABLE_CAP_BYTES));
    }
    std::ifstream f(path, std::ios::binary);
    if (!f) {
        throw std::invalid_argument("table image '" + path + "': cannot be read (" + std::strerror(errno) + ")");
    }
    Upload u;
    u.t_s = t_s;
    u.what = path;
    std::vector<char> bytes(static_cast<std::size_t>(st.st_size) + 1u);
    f.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (f.bad()) {
        throw std::invalid_argument("table image '" + path + "': read error");
    }
    u.image.assign(bytes.begin(), bytes.begin() + f.gcount());
    if (u.image.size() < FSW_TABLE_HDR_BYTES) {
        throw std::invalid_argument("table image '" + path + "': " + std::to_string(u.image.size()) +
                                    " bytes, shorter than the " + std::to_string(FSW_TABLE_HDR_BYTES) +
                                    "-byte table header");
    }
    if (u.image.size() > FSW_TABLE_CAP_BYTES) {
        throw std::invalid_argument("table image '" + path + "': " + std::to_string(u.image.size()) +
                                    " bytes, more than the loader's " + std::to_string(FSW_TABLE_CAP_BYTES));
    }
    return u;
}

std::vector<std::vector<std::uint8_t>> upload_messages(const Upload &u, std::int64_t utime_us)
{
    std::vector<std::vector<std::uint8_t>> msgs;
    std::vector<std::uint8_t> buf(1024);
    const std::size_t total = u.image.size();
    // Table id and revision from the image's own header (fsw_table.h): the chunks can never
    // disagree with the image they carry.
    const std::int32_t table_id = (total >= 2u) ? static_cast<std::int32_t>(u.image[0] | (u.image[1] << 8)) : 0;
    const std::uint32_t rev = (total >= 12u) ? le32(u.image, 8) : 0u;
    for (std::size_t off = 0; off < total; off += 256u) {
        gnc::table_upload_v2_t m{};
        m.utime = utime_us;
        m.table_id = table_id;
        m.revision = static_cast<std::int32_t>(rev & 0x7FFFFFFFu);
        m.total_len = static_cast<std::int32_t>(total);
        m.offset = static_cast<std::int32_t>(off);
        const std::size_t n = (total - off < 256u) ? (total - off) : 256u;
        m.n = static_cast<std::int16_t>(n);
        for (std::size_t i = 0; i < n; ++i) {
            m.data[i] = u.image[off + i];
        }
        const int len = bridge::encode(m, buf.data(), buf.size());   // sealed with its crc32
        if (len > 0) {
            msgs.emplace_back(buf.begin(), buf.begin() + len);
        }
    }
    return msgs;
}

void publish_upload(lcm_t *lcm, const Upload &u, std::int64_t utime_us)
{
    for (const std::vector<std::uint8_t> &m : upload_messages(u, utime_us)) {
        lcm_publish(lcm, kChTblUp, m.data(), static_cast<unsigned>(m.size()));
    }
}

std::uint64_t missed_run_bound(const sim::Scenario &scn)
{
    const std::uint64_t period_us = (scn.period_us == 0u) ? 1u : scn.period_us;
    return static_cast<std::uint64_t>(scn.lockstep.deadline_ms) * 1000u / period_us;
}

std::string loss_of_control(const sim::Scenario &scn, const PlantSummary &p)
{
    std::string why;
    if (p.diverged) {
        // the plant's own words ("DIVERGED: ... |mu_y| = 30.3 deg > 30 deg"), without the prefix
        const std::string pre = "DIVERGED: ";
        why = "PLANT_DIVERGED: " + (p.reason.rfind(pre, 0) == 0 ? p.reason.substr(pre.size()) : p.reason);
    }
    if (p.missed_run_max > missed_run_bound(scn)) {
        // The plant held one command longer than the lock-step lets a single command be late:
        // the spacecraft flew open loop, whatever the flight software computed meanwhile.
        char b[256];
        std::snprintf(b, sizeof b,
                      "MISSED_COMMANDS: %llu consecutive missed commands held the last command for %.3f s, "
                      "more than lockstep.deadline_ms = %u ms allows (%llu periods of %u us)",
                      static_cast<unsigned long long>(p.missed_run_max),
                      static_cast<double>(p.missed_run_max) * scn.h_s(), scn.lockstep.deadline_ms,
                      static_cast<unsigned long long>(missed_run_bound(scn)), scn.period_us);
        why += (why.empty() ? "" : "; ") + std::string(b);
    }
    return why;
}

void plant_summary(const sim::Scenario &scn, const PlantSummary &p, host::Summary &s, const bool *same_streams)
{
    s.add_int("plant_steps", static_cast<std::int64_t>(p.steps));
    s.add("plant_t_end_s", p.t_end_s, "%g");
    s.add_int("plant_missed", static_cast<std::int64_t>(p.missed));
    s.add_int("plant_missed_run_max", static_cast<std::int64_t>(p.missed_run_max));
    s.add_int("plant_missed_run_bound", static_cast<std::int64_t>(missed_run_bound(scn)));
    s.add_int("plant_retx", static_cast<std::int64_t>(p.retx));
    s.add_int("plant_late_cmds", static_cast<std::int64_t>(p.late_cmds));
    s.add_int("plant_dup_cmds", static_cast<std::int64_t>(p.dup_cmds));
    s.add_int("plant_bad_cmds", static_cast<std::int64_t>(p.bad_cmds));
    s.add_int("plant_crc_cmds", static_cast<std::int64_t>(p.crc_cmds));
    s.add_int("plant_nan_frames", static_cast<std::int64_t>(p.nan_frames));
    s.add_int("plant_spike_frames", static_cast<std::int64_t>(p.spike_frames));
    s.add_int("fault_injected_frames", static_cast<std::int64_t>(p.faults.in));
    s.add_int("fault_delivered", static_cast<std::int64_t>(p.faults.delivered));
    s.add_int("fault_dropped", static_cast<std::int64_t>(p.faults.dropped));
    s.add_int("fault_duplicated", static_cast<std::int64_t>(p.faults.duplicated));
    s.add_int("fault_reordered", static_cast<std::int64_t>(p.faults.reordered));
    s.add_int("fault_bitflipped", static_cast<std::int64_t>(p.faults.bitflipped));
    s.add_int("fault_truncated", static_cast<std::int64_t>(p.faults.truncated));
    s.add_int("plant_diverged", p.diverged ? 1 : 0);
    s.add_str("plant_end", p.reason.empty() ? std::string("completed") : p.reason);
    if (same_streams != nullptr) {
        s.add_str("deterministic", *same_streams ? "yes" : "no (two flights of this run published different "
                                                           "command or telemetry streams)");
        s.add_str("deterministic_basis", "two flights compared (stream digests)");
    } else if (p.sync) {
        s.add_str("deterministic", "yes");
        s.add_str("deterministic_basis", "memq lock-step: no clock in the loop, faults drawn from the seed "
                                         "(not compared; --determinism-check flies the run twice)");
    } else {
        s.add_str("deterministic", p.deterministic() ? "yes" : "no (missed or re-sent frames)");
        s.add_str("deterministic_basis", "udpm lock-step: re-sent and missed frames are wall-clock decisions");
    }
    const std::string lost = loss_of_control(scn, p);
    s.add_int("loss_of_control", lost.empty() ? 0 : 1);
    s.add_str("loss_of_control_reason", lost.empty() ? std::string("none") : lost);
}

void run_header(const sim::Scenario &scn, const std::string &fsw, const std::string &url, host::Summary &s)
{
    s.add_str("scenario", scn.name);
    s.add_str("scenario_file", scn.source);
    s.add_str("table", scn.fsw.table_file.empty() ? scn.fsw.table : scn.fsw.table_file);
    s.add_str("fsw", fsw);
    s.add_str("transport", url);
}

std::unique_ptr<bridge::InProcessFswBackend> make_fixed_backend(const sim::Scenario &scn)
{
    const host::MissionHost &mh = host::mission_host(scn.mission);
    // With a table file the flight software boots without a table and takes the file by upload
    // before its first step (run_uploads): the upload path flies in every such run, and a
    // configuration at any period boots (no built-in table of that period is needed).
    std::vector<std::uint8_t> boot = scn.fsw.table_file.empty() ? mh.boot_image(scn) : std::vector<std::uint8_t>{};
    std::unique_ptr<bridge::InProcessFswBackend> be(new bridge::InProcessFswBackend(host::fsw_cfg(scn), std::move(boot)));
    if (be->boot_rc() != FSW_OK) {
        throw std::runtime_error("the " + std::string(mh.iface().name) + " boot table '" + scn.fsw.table +
                                 "' was refused by the flight loader: " +
                                 host::describe_reason(mh.iface(), be->fsw().tlm.tbl_reason) +
                                 " (scenario period_us " + std::to_string(scn.period_us) + ")");
    }
    return be;
}

bridge::SensorLimits run_limits(const sim::Scenario &scn)
{
    if (scn.fsw.table_file.empty()) {
        return make_fixed_backend(scn)->sensor_limits();
    }
    // the file booted directly: same loader checks; run_uploads reports a refusal in words
    bridge::InProcessFswBackend be(host::fsw_cfg(scn), upload_from_file(scn.fsw.table_file, 0.0).image);
    return be.sensor_limits();
}

void check_upload(const sim::Scenario &scn, const Upload &u)
{
    const host::MissionHost &mh = host::mission_host(scn.mission);
    std::unique_ptr<bridge::InProcessFswBackend> be = make_fixed_backend(scn);
    const std::int32_t table_id = static_cast<std::int32_t>(u.image[0] | (u.image[1] << 8));
    bridge::TableAck ack{};
    for (std::size_t off = 0; off < u.image.size(); off += bridge::kMaxChunk) {
        bridge::TableChunk c{};
        c.table_id = table_id;
        c.revision = static_cast<std::int32_t>(le32(u.image, 8) & 0x7FFFFFFFu);
        c.total_len = static_cast<std::int32_t>(u.image.size());
        c.offset = static_cast<std::int32_t>(off);
        c.n = static_cast<std::int16_t>(std::min<std::size_t>(bridge::kMaxChunk, u.image.size() - off));
        c.data = u.image.data() + off;
        (void)be->table_chunk(c, ack);
        if (ack.result == bridge::kTableRejected) {
            break;
        }
    }
    if (ack.result != bridge::kTableAccepted) {
        char id[16];
        std::snprintf(id, sizeof id, "0x%04X", static_cast<unsigned>(table_id & 0xFFFF));
        throw std::invalid_argument("table image '" + u.what + "' (table id " + id + ") refused by the " +
                                    std::string(mh.iface().name) + " flight loader: " +
                                    host::describe_reason(mh.iface(), static_cast<std::uint32_t>(ack.reason)) +
                                    "; the run is not started");
    }
}

std::vector<Upload> run_uploads(const sim::Scenario &scn, const std::vector<Upload> &extra)
{
    std::vector<Upload> v;
    if (!scn.fsw.table_file.empty()) {
        v.push_back(upload_from_file(scn.fsw.table_file, 0.0));
        check_upload(scn, v.back());
    }
    v.insert(v.end(), extra.begin(), extra.end());
    return v;
}

namespace {

// One flight of the scenario on its own lcm_t. same_as: the metrics of an earlier flight of the
// same run, whose streams this one's are compared with (the determinism check).
InprocResult fly(const sim::Scenario &scn, const InprocOptions &opt, const CoreMetrics *same_as)
{
    const host::MissionHost &mh = host::mission_host(scn.mission);
    std::vector<Upload> uploads = run_uploads(scn, opt.uploads);
    lcm_t *lcm = lcm_create(opt.url.c_str());
    if (lcm == nullptr) {
        throw std::runtime_error("lcm_create failed for URL '" + opt.url + "'");
    }
    InprocResult res;
    try {
        std::unique_ptr<bridge::InProcessFswBackend> fixed = make_fixed_backend(scn);
        std::unique_ptr<bridge::Backend> refbe;
        if (opt.fsw != "fixed") {
            // The reference flies the same table as the flight code would: the scenario's table
            // file, else its boot table. It takes no uploads.
            const std::vector<std::uint8_t> image = scn.fsw.table_file.empty() ? mh.boot_image(scn) : uploads.front().image;
            refbe = mh.make_ref(scn, opt.fsw, image);
            if (!scn.fsw.table_file.empty()) {
                uploads.erase(uploads.begin());
            }
        }
        bridge::Backend &be = refbe ? *refbe : static_cast<bridge::Backend &>(*fixed);
        bridge::Bridge core(be, run_limits(scn));
        BridgeNode bn(lcm, core);
        const bool sync = opt.url.rfind("memq://", 0) == 0;
        PlantNode pn(lcm, scn, sync);
        std::unique_ptr<LogTap> tap;
        if (!opt.log_path.empty()) {
            tap.reset(new LogTap(lcm, opt.log_path, [&pn]() { return pn.utime_us(); }));
        }
        MetricsTap mt(lcm, scn);
        std::vector<bool> sent(uploads.size(), false);
        pn.set_before_frame([&](std::uint64_t, std::int64_t utime) {
            for (std::size_t i = 0; i < uploads.size(); ++i) {
                if (!sent[i] && static_cast<double>(utime) * 1e-6 >= uploads[i].t_s) {
                    publish_upload(lcm, uploads[i], utime);
                    sent[i] = true;
                }
            }
        });
        if (opt.progress) {
            pn.set_progress([](std::uint64_t k, std::uint64_t n) {
                if (k % 5000u == 0u || k == n) {
                    std::fprintf(stderr, "\r  sil: step %llu / %llu (%3.0f %%)", static_cast<unsigned long long>(k),
                                 static_cast<unsigned long long>(n), 100.0 * static_cast<double>(k) / static_cast<double>(n));
                    if (k == n) { std::fprintf(stderr, "\n"); }
                }
            });
        }
        const auto w0 = std::chrono::steady_clock::now();
        res.plant = pn.run();
        res.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
        if (!sync) {
            // udpm: the last command came back before the plant ended, its telemetry may still
            // be on the socket. Drain until 50 ms of silence (at most 1 s).
            for (int quiet = 0, total = 0; quiet < 50 && total < 1000; total += 10) {
                quiet = (lcm_handle_timeout(lcm, 10) > 0) ? 0 : quiet + 10;
            }
        }
        res.core = mt.core();
        res.mission = mt.mission_ptr();
        res.bridge = core.counters();
        res.log_events = tap ? tap->events() : 0u;
        bool same = true;
        if (same_as != nullptr) {
            same = same_as->digest_cmd == res.core.digest_cmd && same_as->digest_tlm == res.core.digest_tlm &&
                   same_as->cmd_n == res.core.cmd_n && same_as->tlm_n == res.core.tlm_n;
            res.determinism_failed = !same;
        }
        res.loss_of_control = loss_of_control(scn, res.plant);
        run_header(scn, be.name(), opt.url, res.summary);
        plant_summary(scn, res.plant, res.summary, same_as != nullptr ? &same : nullptr);
        mt.summary(res.summary, &res.bridge);
        res.summary.add("wall_s", res.wall_s, "%g");
        res.summary.add("steps_per_s", res.wall_s > 0.0 ? static_cast<double>(res.plant.steps) / res.wall_s : 0.0, "%g");
    } catch (...) {
        lcm_destroy(lcm);
        throw;
    }
    lcm_destroy(lcm);
    return res;
}

}  // namespace

InprocResult run_inproc(const sim::Scenario &scn, const InprocOptions &opt)
{
    if (!opt.determinism_check) {
        return fly(scn, opt, nullptr);
    }
    // The first flight only gives the streams to compare with: no log, no progress line.
    InprocOptions quiet = opt;
    quiet.log_path.clear();
    quiet.progress = false;
    const InprocResult first = fly(scn, quiet, nullptr);
    return fly(scn, opt, &first.core);
}

}  // namespace sil
