// pil_test_util.hpp — the PIL tests' common rig: the DETUMBLE configuration and boot image, a
// deterministic frame pattern, and a twin that flies every frame through the in-process
// executive (the reference) and the `pil` backend and requires byte-identical outputs.
#ifndef TESTS_PIL_TEST_UTIL_HPP
#define TESTS_PIL_TEST_UTIL_HPP

#include <cstdio>
#include <cstring>
#include <memory>
#include <utility>
#include <vector>

#include "bridge_test_util.hpp"
#include "fsw_backend.hpp"
#include "link_port.hpp"
#include "pil_backend.hpp"

extern "C" {
#include "fsw_exec.h"
#include "obs_mission.h"
#include "obs_tables.h"
}

namespace pt {

using namespace bridge;

inline fsw_cfg_t det_cfg()
{
    fsw_cfg_t c{};
    c.period_us = OBS_TBL_50HZ_PHYS.period_us;
    c.stale_max = 50u;
    c.boot_mode = FSW_MODE_DETUMBLE;
    c.mission = FSW_MISSION_DETUMBLE;
    return c;
}

// The innovation gate in monitor mode: the synthetic gyro pattern is no motion of the model,
// and the gate would (rightly) take the executive to SAFE early, leaving little to compare
// (as tests/observer/test_obs_bridge_faults.cpp).
inline std::vector<std::uint8_t> det_image(const obs_params_t &base, std::uint32_t revision)
{
    obs_params_t p = base;
    p.d2_reject = 0u;
    std::vector<std::uint8_t> img(FSW_TABLE_HDR_BYTES + OBS_TBL_PAYLOAD);
    assert_int_equal(obs_table_encode(&p, revision, img.data(), static_cast<std::uint32_t>(img.size())), img.size());
    return img;
}

// Frame k: the bridge tests' small gyro pattern, with the plant's STALE (and one SAT) bits now
// and then, so the status path is part of what must agree.
inline Frame frame_k(std::int64_t k)
{
    Frame f = bt::make_frame(k, static_cast<std::int32_t>(OBS_TBL_50HZ_PHYS.period_us));
    if (k % 13 == 5) {
        f.status[0] = kStatusStale;
    }
    if (k % 29 == 11) {
        f.status[1] = kStatusStale;
    }
    if (k == 77) {
        f.status[0] = kStatusSat;
    }
    return f;
}

inline void expect_same(const StepOutput &a, const StepOutput &b, std::int64_t k)
{
    if (a.n_counts != b.n_counts || std::memcmp(a.counts, b.counts, sizeof a.counts) != 0 || a.fsw_mode != b.fsw_mode ||
        a.fsw_health != b.fsw_health || a.tlm_layout_version != b.tlm_layout_version || a.tlm_len != b.tlm_len ||
        std::memcmp(a.tlm, b.tlm, sizeof a.tlm) != 0) {
        fail_msg("step %lld: in-process and PIL outputs differ (mode %d/%d health 0x%x/0x%x tlm_len %d/%d)",
                 static_cast<long long>(k), a.fsw_mode, b.fsw_mode, a.fsw_health, b.fsw_health, a.tlm_len, b.tlm_len);
    }
}

inline void expect_same_limits(const SensorLimits &a, const SensorLimits &b)
{
    assert_int_equal(a.n_channels, b.n_channels);
    assert_int_equal(a.period_us, b.period_us);
    for (std::size_t i = 0; i < kMaxCounts; ++i) {
        assert_int_equal(a.ch[i].min, b.ch[i].min);
        assert_int_equal(a.ch[i].max, b.ch[i].max);
    }
}

inline void expect_same_ack(const TableAck &a, const TableAck &b)
{
    assert_int_equal(a.table_id, b.table_id);
    assert_int_equal(a.revision, b.revision);
    assert_int_equal(a.result, b.result);
    assert_int_equal(a.reason, b.reason);
    assert_int_equal(a.bytes_received, b.bytes_received);
}

// Both backends side by side, booted from the same configuration and image.
struct Twin {
    InProcessFswBackend ip;
    std::unique_ptr<pil::PilBackend> pil;
    std::int64_t replays = 0;   // step() re-called on the same frame, as the plant re-sends

    Twin(std::unique_ptr<pil::LinkPort> port, pil::PilOptions opt)
        : ip(det_cfg(), det_image(OBS_TBL_50HZ_PHYS, 1u)),
          pil(new pil::PilBackend(det_cfg(), det_image(OBS_TBL_50HZ_PHYS, 1u), std::move(port), opt))
    {
    }

    // Frame k through both, with what the bridge would hand them first (counters, commands: a
    // mode command at 150 and 180, a telecommand at 200). A PIL step without output is tried
    // again on the same frame, as the plant re-publishes it.
    void step(std::int64_t k, int max_replays = 3)
    {
        Counters c{};
        c.missed = static_cast<std::int32_t>(k / 40);
        c.range_rej = static_cast<std::int32_t>(k / 70);
        ip.host_counters(c);
        pil->host_counters(c);
        FswCommand cmd{};
        cmd.apply_seq = k;
        bool have_cmd = false;
        if (k == 150) {
            cmd.cmd = kCmdMode;
            cmd.args[0] = static_cast<std::int32_t>(FSW_MODE_STANDBY);
            have_cmd = true;
        } else if (k == 180) {
            cmd.cmd = kCmdMode;
            cmd.args[0] = static_cast<std::int32_t>(FSW_MODE_DETUMBLE);
            have_cmd = true;
        } else if (k == 200) {
            // DETUMBLE has no telecommands: the executive refuses it and says so in telemetry,
            // which must then read the same from both.
            cmd.cmd = static_cast<std::int32_t>(FSW_TC_ID(FSW_MISSION_DETUMBLE, 1u));
            cmd.args[0] = 42;
            have_cmd = true;
        }
        if (have_cmd) {
            assert_true(ip.command(cmd));
            assert_true(pil->command(cmd));
        }
        const Frame f = frame_k(k);
        StepOutput a{}, b{};
        assert_true(ip.step(f, a));
        int tries = 0;
        while (!pil->step(f, b)) {
            ++replays;
            if (++tries > max_replays) {
                fail_msg("step %lld: no PIL output after %d replays", static_cast<long long>(k), max_replays);
            }
        }
        expect_same(a, b, k);
        SensorLimits la{}, lb{};
        const bool ca = ip.limits_changed(la);
        const bool cb = pil->limits_changed(lb);
        assert_int_equal(ca, cb);
        if (ca) {
            expect_same_limits(la, lb);
        }
    }
};

}  // namespace pt

#endif  // TESTS_PIL_TEST_UTIL_HPP
