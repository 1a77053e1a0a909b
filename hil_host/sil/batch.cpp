#include "batch.hpp"

#include <cstring>
#include <lcm/eventlog.h>

#include <chrono>
#include <cstdio>
#include <stdexcept>

#include "bridge.hpp"
#include "bridge_node.hpp"
#include "channels.hpp"
#include "gnc/actuator_cmd_v2_t.hpp"
#include "gnc/fsw_cmd_v2_t.hpp"
#include "gnc/fsw_tlm_frame_t.hpp"
#include "lcm_codec.hpp"
#include "metrics.hpp"
#include "plant_node.hpp"
#include "scenario/scenario.hpp"

namespace sil {

namespace {

// Telecommands of the scenario at their step, through their sealed encoding (plant_node.cpp).
void deliver_commands(const sim::Scenario &scn, std::size_t &next, std::uint64_t k, std::int64_t utime, double t_s,
                      bridge::Bridge &core, std::vector<std::uint8_t> &buf)
{
    while (next < scn.commands.size() && scn.commands[next].t_s <= t_s + 1e-9) {
        const sim::ScnCommand &c = scn.commands[next++];
        gnc::fsw_cmd_v2_t m{};
        m.utime = utime;
        m.apply_seq = static_cast<std::int64_t>(k);
        m.cmd = c.cmd;
        for (std::size_t i = 0; i < 8u; ++i) { m.args[i] = c.args[i]; }
        const int n = bridge::encode(m, buf.data(), buf.size());
        bridge::FswCommand fc{};
        if (n > 0 && bridge::decode_fsw_cmd(buf.data(), static_cast<std::size_t>(n), fc) == bridge::Wire::Ok) {
            (void)core.on_command(fc);
        } else {
            bridge::sat_inc(core.counters_mut().cmd_rej);
        }
    }
}

}  // namespace

InprocResult run_batch(const sim::Scenario &scn, const std::vector<Upload> &extra, bool progress, PilRun *pil,
                       const std::string &log_path)
{
    if (scn.faults.any()) {
        throw std::invalid_argument("the batch driver flies fault-free scenarios only (faults act on the transport): "
                                    "fly '" + scn.name + "' with sil run");
    }
    // A table file and --upload images go through the upload path exactly as over memq: the
    // sealed chunks reach the bridge core before the first frame at or after their time, and the
    // acks reach the metrics (run_uploads checks every image first: a refused one flies nothing).
    const std::vector<Upload> uploads = run_uploads(scn, extra);
    std::vector<bool> sent(uploads.size(), false);
    // SIL: the executive in this process; PIL: the same executive on the board behind the link.
    // The bridge core, its limits (the run's table, checked by the host's loader) and everything
    // around them are the same, so the two runs' streams compare byte for byte.
    std::unique_ptr<bridge::InProcessFswBackend> fixed;
    if (pil == nullptr) {
        fixed = make_fixed_backend(scn);
    }
    bridge::Backend *be = (pil != nullptr) ? static_cast<bridge::Backend *>(&pil->backend()) : fixed.get();
    bridge::Bridge core(*be, run_limits(scn));
    MetricsTap mt(nullptr, scn);
    std::unique_ptr<sim::Plant> plant = sim::make_plant(scn);
    plant->reset(scn);
    // The event log of a batch run: every message a memq run would carry (sensor frames included),
    // timestamped with the simulation time, so tools.sil report reads it like any run's log.
    std::unique_ptr<lcm_eventlog_t, void (*)(lcm_eventlog_t *)> elog(nullptr, lcm_eventlog_destroy);
    if (!log_path.empty()) {
        elog.reset(lcm_eventlog_create(log_path.c_str(), "w"));
        if (!elog) {
            throw std::runtime_error("cannot create LCM log '" + log_path + "'");
        }
    }
    std::int64_t n_events = 0;
    auto log_event = [&](const char *ch, const std::uint8_t *data, std::size_t n) {
        if (elog) {
            lcm_eventlog_event_t ev{};
            ev.eventnum = n_events++;
            ev.timestamp = plant->utime_us();
            ev.channellen = static_cast<int32_t>(std::strlen(ch));
            ev.datalen = static_cast<int32_t>(n);
            ev.channel = const_cast<char *>(ch);
            ev.data = const_cast<std::uint8_t *>(data);
            (void)lcm_eventlog_write_event(elog.get(), &ev);
        }
    };
    auto tap = [&](const char *ch, const std::uint8_t *data, std::size_t n) {
        mt.feed(ch, data, n);
        log_event(ch, data, n);
    };
    std::vector<std::uint8_t> buf(4096), out(4096);
    InprocResult res;
    PlantSummary &ps = res.plant;
    ps.sync = true;
    std::uint64_t missed_run = 0;
    std::size_t next_cmd = 0;
    const std::uint64_t n = scn.n_steps();
    const auto w0 = std::chrono::steady_clock::now();
    for (std::uint64_t k = 0; k < n; ++k) {
        const std::int64_t utime = plant->utime_us();
        for (std::size_t i = 0; i < uploads.size(); ++i) {
            if (!sent[i] && static_cast<double>(utime) * 1e-6 >= uploads[i].t_s) {
                for (const std::vector<std::uint8_t> &m : upload_messages(uploads[i], utime)) {
                    bool bad = false;
                    const int na = table_upload_to_ack(core, m.data(), m.size(), out.data(), out.size(), &bad);
                    if (na > 0) {
                        tap(kChTblAck, out.data(), static_cast<std::size_t>(na));
                    }
                }
                sent[i] = true;
            }
        }
        deliver_commands(scn, next_cmd, k, utime, static_cast<double>(utime) * 1e-6, core, out);
        if (pil != nullptr) {
            pil->before_step(k);
        }
        const sim::SensorFrame f = plant->sense();
        int len = encode_truth(*plant, k, buf);
        if (len > 0) {
            tap(kChTruth, buf.data(), static_cast<std::size_t>(len));
        }
        len = encode_frame(scn, f, 0, buf);
        if (len < 0) {
            throw std::runtime_error("sensor_frame_v2_t encode failed");
        }
        log_event(kChSensor, buf.data(), static_cast<std::size_t>(len));
        const bridge::Reply r = core.on_bytes(buf.data(), static_cast<std::size_t>(len));
        bool got = false;
        sim::ActuatorCmd cmd{};
        if (r.publish_cmd) {
            gnc::actuator_cmd_v2_t m{};
            bridge::to_lcm(r.cmd, m);
            const int nb = bridge::encode(m, out.data(), out.size());
            if (nb > 0) {
                tap(kChCmd, out.data(), static_cast<std::size_t>(nb));
                if (m.seq >= 0 && static_cast<std::uint64_t>(m.seq) == k && m.n_counts >= 0 && m.n_counts <= 16) {
                    got = true;
                    cmd.seq = static_cast<std::uint32_t>(m.seq & 0xFFFFFFFF);
                    cmd.n_ch = static_cast<std::uint32_t>(m.n_counts);
                    for (std::size_t i = 0; i < cmd.n_ch && i < sim::kMaxChannels; ++i) {
                        cmd.cnt[i] = m.counts[i];
                    }
                }
            }
        }
        if (r.publish_tlm) {
            gnc::fsw_tlm_frame_t m{};
            bridge::to_lcm(r.tlm, m);
            const int nb = bridge::encode(m, out.data(), out.size());
            if (nb > 0) {
                tap(kChTlm, out.data(), static_cast<std::size_t>(nb));
            }
        }
        if (got) {
            plant->apply(cmd);
            missed_run = 0;
        } else {   // no re-send without a transport: the frame was refused, the last command holds
            ++ps.missed;
            ++missed_run;
            ps.missed_run_max = (missed_run > ps.missed_run_max) ? missed_run : ps.missed_run_max;
            core.set_missed(static_cast<std::int32_t>(ps.missed > 0x7FFFFFFFu ? 0x7FFFFFFFu : ps.missed));
        }
        if (pil != nullptr && pil->backend().link_down()) {
            ps.reason = "PIL link down at step " + std::to_string(k);
            res.board_exit = 1;
            break;
        }
        const sim::RunState st = plant->propagate();
        ++ps.steps;
        if (progress && ((k + 1) % 1000000u == 0u || k + 1 == n)) {
            std::fprintf(stderr, "\r  sil batch: step %llu / %llu", static_cast<unsigned long long>(k + 1),
                         static_cast<unsigned long long>(n));
            if (k + 1 == n) { std::fprintf(stderr, "\n"); }
        }
        if (st == sim::RunState::Diverged) {
            ps.diverged = true;
            ps.reason = "DIVERGED: " + plant->diverged_reason();
            break;
        }
    }
    res.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
    ps.t_end_s = static_cast<double>(plant->utime_us()) * 1e-6;
    res.core = mt.core();
    res.mission = mt.mission_ptr();
    res.bridge = core.counters();
    res.loss_of_control = loss_of_control(scn, ps);
    run_header(scn, be->name(), "batch", res.summary);
    plant_summary(scn, ps, res.summary, nullptr);
    mt.summary(res.summary, &res.bridge);
    res.summary.add("wall_s", res.wall_s, "%g");
    res.summary.add("steps_per_s", res.wall_s > 0.0 ? static_cast<double>(ps.steps) / res.wall_s : 0.0, "%g");
    if (pil != nullptr) {
        const int rc = pil->finish(res.summary);
        res.board_exit = (res.board_exit != 0) ? res.board_exit : rc;
    }
    return res;
}

}  // namespace sil
