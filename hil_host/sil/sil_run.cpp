#include "sil_run.hpp"

#include <chrono>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "bridge.hpp"
#include "bridge_node.hpp"
#include "channels.hpp"
#include "fsw_backend.hpp"
#include "gnc/table_upload_t.hpp"
#include "log_tap.hpp"
#include "ref_backend.hpp"

namespace sil {

void publish_upload(lcm_t *lcm, const Upload &u, std::int64_t utime_us)
{
    std::vector<std::uint8_t> buf(1024);
    const std::size_t total = u.image.size();
    for (std::size_t off = 0; off < total; off += 256u) {
        gnc::table_upload_t m{};
        m.utime = utime_us;
        m.table_id = u.table_id;
        m.revision = u.revision;
        m.total_len = static_cast<std::int32_t>(total);
        m.offset = static_cast<std::int32_t>(off);
        const std::size_t n = (total - off < 256u) ? (total - off) : 256u;
        m.n = static_cast<std::int16_t>(n);
        for (std::size_t i = 0; i < n; ++i) {
            m.data[i] = u.image[off + i];
        }
        const int len = m.encode(buf.data(), 0, static_cast<int>(buf.size()));
        if (len > 0) {
            lcm_publish(lcm, kChTblUp, buf.data(), static_cast<unsigned>(len));
        }
    }
}

std::string plant_summary(const PlantSummary &p)
{
    std::ostringstream o;
    o << "plant_steps = " << p.steps << "\nplant_t_end_s = " << p.t_end_s << "\nplant_missed = " << p.missed
      << "\nplant_retx = " << p.retx << "\nplant_late_cmds = " << p.late_cmds << "\nplant_dup_cmds = " << p.dup_cmds
      << "\nplant_bad_cmds = " << p.bad_cmds << "\nplant_nan_frames = " << p.nan_frames
      << "\nplant_spike_frames = " << p.spike_frames << "\nfault_dropped = " << p.faults.dropped
      << "\nfault_duplicated = " << p.faults.duplicated << "\nfault_reordered = " << p.faults.reordered
      << "\nfault_bitflipped = " << p.faults.bitflipped << "\nfault_truncated = " << p.faults.truncated
      << "\nplant_diverged = " << (p.diverged ? 1 : 0) << "\nplant_end = " << (p.reason.empty() ? "completed" : p.reason)
      << "\ndeterministic = " << (p.deterministic() ? "yes" : "no (missed or re-sent frames)") << "\n";
    return o.str();
}

FswKind fsw_kind(const std::string &name)
{
    if (name == "fixed") { return FswKind::Fixed; }
    if (name == "ref") { return FswKind::Ref; }
    if (name == "ref-per-axis") { return FswKind::RefPerAxis; }
    throw std::invalid_argument("unknown flight software '" + name + "' (fixed, ref, ref-per-axis)");
}

void configure_metrics(MetricsTap &mt, const sim::Scenario &scn)
{
    if (scn.plant != "cw") {
        return;
    }
    std::int64_t t0 = -1, tf = -1;
    for (const sim::ScnCommand &c : scn.commands) {
        if (c.cmd == bridge::kCmdImpStart && tf < 0) {
            t0 = c.args[0];
            tf = c.args[1];
        }
    }
    mt.set_rendezvous(t0, tf);
}

namespace {

// The scenario's impulse boot table with its operator overrides.
imp_params_t boot_imp(const sim::Scenario &scn)
{
    imp_params_t t = bridge::boot_imp_table(scn.fsw.table);
    if (scn.fsw.cal_enable >= 0) {
        t.cal_enable = static_cast<std::uint8_t>(scn.fsw.cal_enable);
    }
    return t;
}

std::unique_ptr<bridge::Backend> make_ref_backend(const sim::Scenario &scn, FswKind kind)
{
    if (scn.plant == "cw") {
        if (kind != FswKind::Ref) {
            throw std::invalid_argument("plant cw: only --fsw fixed or ref");
        }
        return std::unique_ptr<bridge::Backend>(new bridge::RefImpBackend(boot_imp(scn)));
    }
    const obs_params_t t = bridge::boot_obs_table(scn.fsw.table, scn.fsw.k_hat0, scn.fsw.bdot_max_degps);
    return std::unique_ptr<bridge::Backend>(new bridge::RefObsBackend(t, kind == FswKind::RefPerAxis));
}

}  // namespace

std::unique_ptr<bridge::InProcessFswBackend> make_fixed_backend(const sim::Scenario &scn)
{
    std::unique_ptr<bridge::InProcessFswBackend> be;
    std::uint32_t period = 0u;
    if (scn.plant == "cw") {
        const imp_params_t t = boot_imp(scn);
        period = t.period_us;
        be.reset(new bridge::InProcessFswBackend(t));
    } else {
        const obs_params_t t = bridge::boot_obs_table(scn.fsw.table, scn.fsw.k_hat0, scn.fsw.bdot_max_degps);
        period = t.period_us;
        be.reset(new bridge::InProcessFswBackend(t));
    }
    if (period != scn.period_us) {
        throw std::runtime_error("scenario period_us " + std::to_string(scn.period_us) + " != table " +
                                 scn.fsw.table + " period " + std::to_string(period));
    }
    return be;
}

InprocResult run_inproc(const sim::Scenario &scn, const InprocOptions &opt)
{
    lcm_t *lcm = lcm_create(opt.url.c_str());
    if (lcm == nullptr) {
        throw std::runtime_error("lcm_create failed for URL '" + opt.url + "'");
    }
    InprocResult res;
    try {
        std::unique_ptr<bridge::InProcessFswBackend> fixed = make_fixed_backend(scn);
        std::unique_ptr<bridge::Backend> refbe;
        if (opt.fsw != FswKind::Fixed) {
            refbe = make_ref_backend(scn, opt.fsw);
        }
        bridge::Backend &be = refbe ? *refbe : static_cast<bridge::Backend &>(*fixed);
        bridge::Bridge core(be, fixed->sensor_limits());
        BridgeNode bn(lcm, core);
        const bool sync = opt.url.rfind("memq://", 0) == 0;
        PlantNode pn(lcm, scn, sync);
        std::unique_ptr<LogTap> tap;
        if (!opt.log_path.empty()) {
            tap.reset(new LogTap(lcm, opt.log_path, [&pn]() { return pn.utime_us(); }));
        }
        MetricsTap mt(lcm, scn.duration_s - 20.0);
        configure_metrics(mt, scn);
        std::vector<bool> sent(opt.uploads.size(), false);
        pn.set_before_frame([&](std::uint64_t, std::int64_t utime) {
            for (std::size_t i = 0; i < opt.uploads.size(); ++i) {
                if (!sent[i] && static_cast<double>(utime) * 1e-6 >= opt.uploads[i].t_s) {
                    publish_upload(lcm, opt.uploads[i], utime);
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
        if (!sync && !pn.wait_for_bridge(0)) {
            // same process: the bridge is subscribed already; nothing to wait for
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
        res.metrics = mt.m();
        res.bridge = core.counters();
        res.log_events = tap ? tap->events() : 0u;
        std::ostringstream o;
        o << "scenario = " << scn.name << "\nmodel = " << sim::sigma_name(scn.sigma) << "\ntable = " << scn.fsw.table
          << "\nfsw = " << be.name() << "\ntransport = " << opt.url << "\n"
          << plant_summary(res.plant) << mt.summary() << "wall_s = " << res.wall_s << "\nsteps_per_s = "
          << (res.wall_s > 0.0 ? static_cast<double>(res.plant.steps) / res.wall_s : 0.0) << "\n";
        res.summary = o.str();
    } catch (...) {
        lcm_destroy(lcm);
        throw;
    }
    lcm_destroy(lcm);
    return res;
}

}  // namespace sil
