// test_bridge_unit.cpp — bridge core units (spec 00 §5.1, §5.2, §8): the sequence table row by
// row, the frame validator's keep-last-good, the SI adapter's finiteness/range checks before any
// cast, and the LCM codec helpers.
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>

#include "bridge.hpp"
#include "bridge_test_util.hpp"
#include "frame_validator.hpp"
#include "lcm_codec.hpp"
#include "seq_gate.hpp"
#include "si_adapter.hpp"

using namespace bridge;

namespace {

constexpr std::int32_t kPeriod = 20000;

SensorLimits limits_pm(std::int32_t m)
{
    SensorLimits l{};
    l.n_channels = 2;
    l.period_us = kPeriod;
    l.ch[0] = ChannelLimits{-m, m};
    l.ch[1] = ChannelLimits{-m, m};
    return l;
}

// §5.2, row by row, through the whole core (fake backend records every step).
void gate_table_rows(void **)
{
    bt::FakeBackend be;
    Bridge br(be, limits_pm(1000000));

    // seq == last + 1 (first frame, last = first_seq - 1): step, command k and telemetry k.
    Reply r = br.on_frame(bt::make_frame(0, kPeriod));
    assert_true(r.outcome == Outcome::Stepped);
    assert_true(r.publish_cmd && r.publish_tlm);
    assert_int_equal(r.cmd.seq, 0);
    assert_int_equal(r.tlm.seq, 0);
    assert_int_equal(be.seen.size(), 1);

    // seq == last: cached command re-published, no step, dups++.
    r = br.on_frame(bt::make_frame(0, kPeriod));
    assert_true(r.outcome == Outcome::Duplicate);
    assert_true(r.publish_cmd && !r.publish_tlm);
    assert_int_equal(r.cmd.seq, 0);
    assert_int_equal(r.cmd.counts[0], 0);
    assert_int_equal(be.seen.size(), 1);
    assert_int_equal(br.counters().dups, 1);

    r = br.on_frame(bt::make_frame(1, kPeriod));
    assert_true(r.outcome == Outcome::Stepped);
    assert_int_equal(r.cmd.counts[0], 10);

    // seq < last: dropped, stale++, nothing published.
    r = br.on_frame(bt::make_frame(0, kPeriod));
    assert_true(r.outcome == Outcome::Stale);
    assert_false(r.publish_cmd || r.publish_tlm);
    assert_int_equal(br.counters().stale, 1);
    assert_int_equal(be.seen.size(), 2);

    // gap (seq > last + 1): step, gaps++ (one event), gap_frames += 2.
    r = br.on_frame(bt::make_frame(4, kPeriod));
    assert_true(r.outcome == Outcome::Gap);
    assert_true(r.publish_cmd && r.publish_tlm);
    assert_int_equal(r.cmd.seq, 4);
    assert_int_equal(r.cmd.counts[0], 40);
    assert_int_equal(br.counters().gaps, 1);
    assert_int_equal(br.counters().gap_frames, 2);
    assert_int_equal(r.tlm.counters.gaps, 1);
    assert_int_equal(be.seen.size(), 3);

    // Duplicate of the gap frame answers from the cache (command 4), a late 3 is stale.
    r = br.on_frame(bt::make_frame(4, kPeriod));
    assert_true(r.outcome == Outcome::Duplicate);
    assert_int_equal(r.cmd.seq, 4);
    assert_int_equal(r.cmd.counts[0], 40);
    r = br.on_frame(bt::make_frame(3, kPeriod));
    assert_true(r.outcome == Outcome::Stale);
    r = br.on_frame(bt::make_frame(5, kPeriod));
    assert_true(r.outcome == Outcome::Stepped);

    const Counters &c = br.counters();
    assert_int_equal(c.stepped, 4);
    assert_int_equal(c.dups, 2);
    assert_int_equal(c.stale, 2);
    assert_int_equal(c.gaps, 1);
    assert_int_equal(be.seen.size(), 4);
    // Telemetry carries the counters as of this step.
    assert_int_equal(r.tlm.counters.dups, 2);
    assert_int_equal(r.tlm.counters.stale, 2);
}

void gate_before_first_and_first_seq(void **)
{
    SeqGate g(10);
    assert_int_equal(g.last(), 9);
    assert_true(g.classify(9) == GateAction::Stale);   // == last, but nothing cached: stale
    assert_true(g.classify(3) == GateAction::Stale);
    assert_true(g.classify(10) == GateAction::Step);
    assert_true(g.classify(12) == GateAction::Gap);
    Counters c{};
    Command cmd{};
    cmd.seq = 12;
    const Command *out = g.commit(GateAction::Gap, 12, &cmd, c);
    assert_non_null(out);
    assert_int_equal(c.gaps, 1);
    assert_int_equal(c.gap_frames, 2);
    assert_int_equal(g.last(), 12);
    assert_true(g.classify(12) == GateAction::Duplicate);
    assert_null(g.answer(GateAction::Stale, c));
    assert_int_equal(c.stale, 1);
}

// Rejected frames (malformed header, backend refusal) leave the gate untouched.
void gate_unchanged_on_reject(void **)
{
    bt::FakeBackend be;
    Bridge br(be, limits_pm(1000000));
    Frame bad = bt::make_frame(0, kPeriod);
    bad.n_counts = 3;
    assert_true(br.on_frame(bad).outcome == Outcome::Malformed);
    bad = bt::make_frame(0, kPeriod);
    bad.period_us = kPeriod + 1;
    assert_true(br.on_frame(bad).outcome == Outcome::Malformed);
    bad = bt::make_frame(0, kPeriod);
    bad.seq = -1;
    assert_true(br.on_frame(bad).outcome == Outcome::Malformed);
    assert_int_equal(br.counters().malformed, 3);
    assert_int_equal(br.gate().last(), -1);

    be.fail_next = true;
    assert_true(br.on_frame(bt::make_frame(0, kPeriod)).outcome == Outcome::BackendFailed);
    assert_int_equal(br.gate().last(), -1);
    assert_true(br.on_frame(bt::make_frame(0, kPeriod)).outcome == Outcome::Stepped);
    assert_int_equal(br.counters().stepped, 1);

    // Undecodable bytes are malformed too.
    const std::uint8_t junk[5] = {1, 2, 3, 4, 5};
    assert_true(br.on_bytes(junk, sizeof junk).outcome == Outcome::Malformed);
    assert_int_equal(br.counters().malformed, 4);
    gnc::fsw_tlm_frame_t m{};
    Telemetry t{};
    t.counters = br.counters();
    to_lcm(t, m);
    assert_int_equal(m.rejected, 4);
}

// A forward jump beyond the window (kMaxSeqJump) is a corrupted seq, not a gap: refused, the
// gate stays put and the next genuine frame steps. The largest legal jump is a gap.
void gate_refuses_implausible_jump(void **)
{
    bt::FakeBackend be;
    Bridge br(be, limits_pm(1000000));
    assert_true(br.on_frame(bt::make_frame(0, kPeriod)).outcome == Outcome::Stepped);
    Frame f = bt::make_frame(1 + (INT64_C(1) << 40), kPeriod);   // one high bit flipped, utime consistent
    assert_true(br.on_frame(f).outcome == Outcome::Jump);
    f = bt::make_frame(kMaxSeqJump + 1, kPeriod);                  // last = 0: one beyond the window
    assert_true(br.on_frame(f).outcome == Outcome::Jump);
    assert_int_equal(br.counters().jump_rej, 2);
    assert_int_equal(br.counters().malformed, 0);
    assert_int_equal(br.gate().last(), 0);
    assert_true(br.on_frame(bt::make_frame(1, kPeriod)).outcome == Outcome::Stepped);
    assert_true(br.on_frame(bt::make_frame(1 + kMaxSeqJump, kPeriod)).outcome == Outcome::Gap);
    assert_int_equal(br.counters().gap_frames, static_cast<int>(kMaxSeqJump - 1));
    assert_int_equal(br.counters().resyncs, 0);
}

// utime must be seq * period_us: a frame whose seq or utime was corrupted (in either) is refused.
void gate_refuses_inconsistent_time(void **)
{
    bt::FakeBackend be;
    Bridge br(be, limits_pm(1000000));
    assert_true(br.on_frame(bt::make_frame(0, kPeriod)).outcome == Outcome::Stepped);
    Frame f = bt::make_frame(1, kPeriod);
    f.utime ^= INT64_C(1) << 44;    // the flipped utime of issue 18 (17 592 202 884 416 us)
    assert_true(br.on_frame(f).outcome == Outcome::BadTime);
    f = bt::make_frame(1, kPeriod);
    f.seq = 2;                      // seq flipped, utime says frame 1: in the window, still refused
    assert_true(br.on_frame(f).outcome == Outcome::BadTime);
    assert_int_equal(br.counters().time_rej, 2);
    assert_int_equal(br.gate().last(), 0);
    assert_int_equal(be.seen.size(), 1);
    assert_true(br.on_frame(bt::make_frame(1, kPeriod)).outcome == Outcome::Stepped);
}

// Every one of the 64 bits of seq, flipped in frame k with a utime that agrees (the sender itself
// got it wrong, so neither the CRC nor the time rule can see it): the loop is never locked out.
// Each flip is refused or stepped as a small gap, and the genuine frames that follow step, so at
// most kMaxSeqJump - 1 commands are skipped and none after the next genuine frame.
void gate_every_seq_bit(void **)
{
    const std::int64_t k = 43;
    for (int b = 0; b < 64; ++b) {
        bt::FakeBackend be;
        Bridge br(be, limits_pm(1000000));
        for (std::int64_t i = 0; i < k; ++i) {
            assert_true(br.on_frame(bt::make_frame(i, kPeriod)).outcome == Outcome::Stepped);
        }
        const std::uint64_t flipped = static_cast<std::uint64_t>(k) ^ (UINT64_C(1) << b);
        std::int64_t fs = 0;
        std::memcpy(&fs, &flipped, sizeof fs);
        Frame f = bt::make_frame(0, kPeriod);
        f.seq = fs;
        f.utime = (fs >= 0 && fs <= INT64_MAX / kPeriod) ? fs * kPeriod : f.utime;
        const Outcome o = br.on_frame(f).outcome;
        std::int64_t next = k;
        if (o == Outcome::Gap || o == Outcome::Stepped) {
            assert_true(fs > k - 1 && fs - (k - 1) <= kMaxSeqJump);   // only a small forward jump steps
            next = fs + 1;
        } else {
            assert_true(o == Outcome::Jump || o == Outcome::Stale || o == Outcome::Malformed || o == Outcome::BadTime ||
                        o == Outcome::Duplicate);
        }
        // The plant re-sends k (or has moved on to next): everything after steps normally.
        for (std::int64_t i = next; i < next + 20; ++i) {
            const Outcome oi = br.on_frame(bt::make_frame(i, kPeriod)).outcome;
            assert_true(oi == Outcome::Stepped);
        }
        assert_int_equal(br.counters().resyncs, 0);
    }
}

// A plant that genuinely jumped is followed, deliberately: kResyncFrames consecutive frames each
// one ahead of the last (re-sends in between neither help nor hurt); a genuine in-window frame
// in between ends the run.
void gate_resynchronises_after_consistent_frames(void **)
{
    bt::FakeBackend be;
    Bridge br(be, limits_pm(1000000));
    assert_true(br.on_frame(bt::make_frame(0, kPeriod)).outcome == Outcome::Stepped);
    const std::int64_t j = 5000;
    assert_true(br.on_frame(bt::make_frame(j, kPeriod)).outcome == Outcome::Jump);
    assert_true(br.on_frame(bt::make_frame(j, kPeriod)).outcome == Outcome::Jump);       // re-send
    assert_true(br.on_frame(bt::make_frame(j + 1, kPeriod)).outcome == Outcome::Jump);
    assert_true(br.on_frame(bt::make_frame(1, kPeriod)).outcome == Outcome::Stepped);     // run broken
    assert_true(br.on_frame(bt::make_frame(j + 2, kPeriod)).outcome == Outcome::Jump);    // starts anew
    assert_true(br.on_frame(bt::make_frame(j + 3, kPeriod)).outcome == Outcome::Jump);
    assert_true(br.on_frame(bt::make_frame(j + 3, kPeriod)).outcome == Outcome::Jump);    // re-send
    assert_true(br.on_frame(bt::make_frame(j + 4, kPeriod)).outcome == Outcome::Gap);     // resync
    assert_int_equal(br.counters().resyncs, 1);
    assert_int_equal(br.counters().jump_rej, 6);
    assert_int_equal(br.gate().last(), j + 4);
    assert_true(br.on_frame(bt::make_frame(j + 5, kPeriod)).outcome == Outcome::Stepped);
    // a non-consecutive run (j+100, j+102, j+104) never resynchronises
    for (std::int64_t i = 0; i < 6; ++i) {
        assert_true(br.on_frame(bt::make_frame(j + 100 + 2 * i, kPeriod)).outcome == Outcome::Jump);
    }
    assert_int_equal(br.counters().resyncs, 1);
}

// The crc32 seals every encoded byte: each single-bit flip of an encoded sensor frame is refused
// (BadCrc, or Malformed when the flip hits the fingerprint), and the gate is untouched.
void crc_refuses_every_single_bit_flip(void **)
{
    bt::FakeBackend be;
    Bridge br(be, limits_pm(1000000));
    assert_true(br.on_frame(bt::make_frame(0, kPeriod)).outcome == Outcome::Stepped);
    gnc::sensor_frame_v2_t m{};
    to_lcm(bt::make_frame(1, kPeriod), m);
    std::uint8_t buf[256];
    const int n = encode(m, buf, sizeof buf);
    assert_int_equal(n, 122);
    int crc = 0, mal = 0;
    for (int bit = 0; bit < n * 8; ++bit) {
        std::uint8_t c[256];
        std::memcpy(c, buf, static_cast<std::size_t>(n));
        c[bit / 8] = static_cast<std::uint8_t>(c[bit / 8] ^ (1u << (bit % 8)));
        const Outcome o = br.on_bytes(c, static_cast<std::size_t>(n)).outcome;
        if (bit < 64) {
            assert_true(o == Outcome::Malformed);   // fingerprint: not this type
            ++mal;
        } else {
            assert_true(o == Outcome::BadCrc);
            ++crc;
        }
    }
    assert_int_equal(br.counters().crc_rej, crc);
    assert_int_equal(br.counters().malformed, mal);
    assert_int_equal(br.gate().last(), 0);
    assert_int_equal(be.seen.size(), 1);
    assert_true(br.on_bytes(buf, static_cast<std::size_t>(n)).outcome == Outcome::Stepped);
    gnc::fsw_tlm_frame_t t{};
    Telemetry tl{};
    tl.counters = br.counters();
    to_lcm(tl, t);
    assert_int_equal(t.rejected, crc + mal);
}

// The other sealed types: a command, a telecommand and a table chunk refuse a flipped bit too,
// and nothing of the refused message is handed out.
void crc_seals_every_sealed_type(void **)
{
    std::uint8_t buf[512];
    Command c{};
    c.seq = 7; c.utime = 7 * kPeriod; c.n_counts = 1; c.counts[0] = 99;
    gnc::actuator_cmd_v2_t a{};
    to_lcm(c, a);
    int n = encode(a, buf, sizeof buf);
    assert_int_equal(n, 102);
    Command d{};
    assert_true(decode_command(buf, static_cast<std::size_t>(n), d) == Wire::Ok);
    assert_int_equal(d.counts[0], 99);
    buf[20] = static_cast<std::uint8_t>(buf[20] ^ 4u);
    d = Command{};
    assert_true(decode_command(buf, static_cast<std::size_t>(n), d) == Wire::BadCrc);
    assert_int_equal(d.seq, 0);

    FswCommand fc{};
    fc.cmd = 1; fc.args[0] = 3; fc.apply_seq = 10;
    gnc::fsw_cmd_v2_t fm{};
    to_lcm(fc, fm);
    n = encode(fm, buf, sizeof buf);
    assert_int_equal(n, 64);
    FswCommand fd{};
    assert_true(decode_fsw_cmd(buf, static_cast<std::size_t>(n), fd) == Wire::Ok);
    assert_int_equal(fd.args[0], 3);
    buf[n - 1] = static_cast<std::uint8_t>(buf[n - 1] ^ 0x80u);   // the crc itself
    assert_true(decode_fsw_cmd(buf, static_cast<std::size_t>(n), fd) == Wire::BadCrc);

    gnc::table_upload_v2_t u{};
    u.table_id = 2; u.revision = 5; u.total_len = 3; u.n = 3; u.data[0] = 1; u.data[1] = 2; u.data[2] = 3;
    n = encode(u, buf, sizeof buf);
    assert_int_equal(n, 294);
    gnc::table_upload_v2_t v{};
    assert_true(decode(buf, static_cast<std::size_t>(n), v) == Wire::Ok);
    assert_int_equal(v.data[2], 3);
    buf[40] = static_cast<std::uint8_t>(buf[40] ^ 1u);
    assert_true(decode(buf, static_cast<std::size_t>(n), v) == Wire::BadCrc);
    assert_int_equal(v.revision, 0);
}

// Out-of-range counts: last good value, STALE bit for the flight code, range_rej.
// A table commit in the backend changes the channel ranges: the bridge applies them from the
// frame after the step that reported them, and keeps the last good values across the change.
void limits_follow_the_backend_table(void **)
{
    bt::FakeBackend be;
    Bridge br(be, limits_pm(100));
    const SensorLimits wide = limits_pm(1000);
    Frame f = bt::make_frame(0, kPeriod);
    f.counts[0] = 60;
    be.new_limits = &wide;                       // reported after this step
    (void)br.on_frame(f);
    assert_int_equal(be.seen[0].counts[0], 60);
    f = bt::make_frame(1, kPeriod);
    f.counts[0] = 500;                           // outside the old range, inside the new
    (void)br.on_frame(f);
    assert_int_equal(be.seen[1].counts[0], 500);
    assert_int_equal(be.seen[1].status[0], 0);
    assert_int_equal(br.counters().range_rej, 0);
    f = bt::make_frame(2, kPeriod);
    f.counts[0] = 1001;                          // outside the new range: last good is 500
    (void)br.on_frame(f);
    assert_int_equal(be.seen[2].counts[0], 500);
    assert_int_equal(be.seen[2].status[0], kStatusStale);
    assert_int_equal(br.counters().range_rej, 1);
}

void validator_keeps_last_good(void **)
{
    bt::FakeBackend be;
    Bridge br(be, limits_pm(100));
    Frame f = bt::make_frame(0, kPeriod);
    f.counts[0] = 50;
    f.counts[1] = -100;                      // edge value: accepted
    assert_true(br.on_frame(f).outcome == Outcome::Stepped);
    assert_int_equal(be.seen[0].counts[1], -100);
    assert_int_equal(be.seen[0].status[0], 0);

    f = bt::make_frame(1, kPeriod);
    f.counts[0] = 101;                       // just outside
    f.counts[1] = 100;                       // edge
    Reply r = br.on_frame(f);
    assert_true(r.outcome == Outcome::Stepped);   // the frame still steps
    assert_int_equal(be.seen[1].counts[0], 50);   // last good value
    assert_int_equal(be.seen[1].status[0], kStatusStale);
    assert_int_equal(be.seen[1].counts[1], 100);
    assert_int_equal(be.seen[1].status[1], 0);
    assert_int_equal(br.counters().range_rej, 1);
    assert_int_equal(r.tlm.counters.range_rej, 1);

    // Plant-held (STALE) in-range value passes with its bit but is not a new "last good".
    f = bt::make_frame(2, kPeriod);
    f.counts[0] = 7;
    f.status[0] = kStatusStale | kStatusSat;
    f.counts[1] = INT32_MIN;
    (void)br.on_frame(f);
    assert_int_equal(be.seen[2].counts[0], 7);
    assert_int_equal(be.seen[2].status[0], kStatusStale | kStatusSat);
    assert_int_equal(be.seen[2].counts[1], 100);
    assert_int_equal(be.seen[2].status[1], kStatusStale);
    f = bt::make_frame(3, kPeriod);
    f.counts[0] = -1000;
    f.counts[1] = 0;
    (void)br.on_frame(f);
    assert_int_equal(be.seen[3].counts[0], 50);
    assert_int_equal(br.counters().range_rej, 3);

    // Before any good value, the held value is 0.
    bt::FakeBackend be2;
    Bridge br2(be2, limits_pm(100));
    f = bt::make_frame(0, kPeriod);
    f.counts[0] = 500;
    f.counts[1] = 1;
    (void)br2.on_frame(f);
    assert_int_equal(be2.seen[0].counts[0], 0);
    assert_int_equal(be2.seen[0].status[0], kStatusStale);
}

SiAdapter make_si()
{
    SiChannel ch[3]{};
    ch[0] = SiChannel{0.5, 0.0, -100, 100};
    ch[1] = SiChannel{1.0, 0.0, INT32_MIN, INT32_MAX};
    ch[2] = SiChannel{1e-10, 0.0, -1000, 1000};
    return SiAdapter(ch, 3);
}

void si_adapter_values(void **)
{
    const SiAdapter si = make_si();
    std::int32_t k = 12345;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    assert_true(si.convert(0, nan, &k) == SiAdapter::Conv::NonFinite);
    assert_true(si.convert(0, inf, &k) == SiAdapter::Conv::NonFinite);
    assert_true(si.convert(0, -inf, &k) == SiAdapter::Conv::NonFinite);
    assert_true(si.convert(2, 1e300, &k) == SiAdapter::Conv::NonFinite);   // finite, /lsb = inf
    assert_int_equal(k, 12345);                                            // never written
    assert_true(si.convert(0, 1e10, &k) == SiAdapter::Conv::Range);
    assert_true(si.convert(0, -1e300, &k) == SiAdapter::Conv::Range);
    assert_true(si.convert(0, 50.25, &k) == SiAdapter::Conv::Range);       // 100.5 -> 101
    assert_int_equal(k, 12345);
    assert_true(si.convert(0, 50.0, &k) == SiAdapter::Conv::Ok);
    assert_int_equal(k, 100);
    assert_true(si.convert(0, -50.0, &k) == SiAdapter::Conv::Ok);
    assert_int_equal(k, -100);
    assert_true(si.convert(0, 50.2, &k) == SiAdapter::Conv::Ok);           // 100.4 -> 100
    assert_int_equal(k, 100);
    assert_true(si.convert(0, -0.25, &k) == SiAdapter::Conv::Ok);          // -0.5 -> -1 (away)
    assert_int_equal(k, -1);
    // int32 edges, exact in double.
    assert_true(si.convert(1, 2147483647.0, &k) == SiAdapter::Conv::Ok);
    assert_int_equal(k, INT32_MAX);
    assert_true(si.convert(1, -2147483648.0, &k) == SiAdapter::Conv::Ok);
    assert_int_equal(k, INT32_MIN);
    assert_true(si.convert(1, 2147483647.5, &k) == SiAdapter::Conv::Range);
    assert_true(si.convert(1, -2147483648.5, &k) == SiAdapter::Conv::Range);
    assert_true(si.convert(1, 9.3e18, &k) == SiAdapter::Conv::Range);
    assert_true(si.convert(1, std::numeric_limits<double>::denorm_min(), &k) == SiAdapter::Conv::Ok);
    assert_int_equal(k, 0);
    assert_true(si.convert(3, 1.0, &k) == SiAdapter::Conv::Range);         // no such channel
}

void si_adapter_frames(void **)
{
    SiAdapter si = make_si();
    Counters c{};
    SiFrame in{};
    in.seq = 0;
    in.period_us = kPeriod;
    in.n_values = 3;
    in.value[0] = 10.0;
    in.value[1] = -7.0;
    in.value[2] = 1e-8;
    Frame f{};
    assert_true(si.to_frame(in, &f, c));
    assert_int_equal(f.counts[0], 20);
    assert_int_equal(f.counts[1], -7);
    assert_int_equal(f.counts[2], 100);
    assert_int_equal(f.n_counts, 3);

    // Any NaN/Inf rejects the frame before any conversion: nothing written, counted per value.
    Frame g = f;
    g.counts[0] = 999;
    SiFrame bad = in;
    bad.seq = 1;
    bad.value[1] = std::numeric_limits<double>::quiet_NaN();
    bad.value[2] = -std::numeric_limits<double>::infinity();
    assert_false(si.to_frame(bad, &g, c));
    assert_int_equal(g.counts[0], 999);
    assert_int_equal(c.nonfinite_rej, 2);
    bad.value[1] = 1.0;
    bad.value[2] = 1e300;        // finite but the scaled value is not
    assert_false(si.to_frame(bad, &g, c));
    assert_int_equal(c.nonfinite_rej, 3);
    assert_int_equal(c.range_rej, 0);

    // Out of range: last good count, STALE; absent: last good count, STALE, not counted.
    SiFrame r = in;
    r.seq = 2;
    r.value[0] = 1e9;
    r.value[1] = std::nullopt;
    assert_true(si.to_frame(r, &f, c));
    assert_int_equal(f.counts[0], 20);
    assert_int_equal(f.status[0], kStatusStale);
    assert_int_equal(f.counts[1], -7);
    assert_int_equal(f.status[1], kStatusStale);
    assert_int_equal(f.counts[2], 100);
    assert_int_equal(f.status[2], 0);
    assert_int_equal(c.range_rej, 1);

    SiFrame wrong = in;
    wrong.n_values = 4;
    assert_false(si.to_frame(wrong, &f, c));
    assert_int_equal(c.malformed, 1);
    assert_int_equal(rejected_total(c), 5);
}

// A NaN SI frame never reaches the step: the bridge sees only accepted frames.
void si_nan_never_steps(void **)
{
    bt::FakeBackend be;
    Bridge br(be, limits_pm(100));
    SiChannel ch[2]{SiChannel{1.0, 0.0, -100, 100}, SiChannel{1.0, 0.0, -100, 100}};
    SiAdapter si(ch, 2);
    for (std::int64_t k = 0; k < 4; ++k) {
        SiFrame in{};
        in.seq = k;
        in.utime = k * kPeriod;
        in.period_us = kPeriod;
        in.n_values = 2;
        in.value[0] = (k == 1) ? std::numeric_limits<double>::quiet_NaN() : 1.0;
        in.value[1] = 2.0;
        Frame f{};
        if (si.to_frame(in, &f, br.counters_mut())) {
            (void)br.on_frame(f);
        }
    }
    assert_int_equal(be.seen.size(), 3);
    assert_int_equal(br.counters().nonfinite_rej, 1);
    assert_int_equal(br.counters().gaps, 1);   // the plant would re-publish 1; here it did not
}

void codec_roundtrip(void **)
{
    Frame f = bt::make_frame(123, kPeriod);
    f.status[1] = kStatusSat;
    f.plant_flags = 2;
    f.scenario_flags = -5;
    gnc::sensor_frame_v2_t m{};
    to_lcm(f, m);
    std::uint8_t buf[256];
    const int n = encode(m, buf, sizeof buf);
    assert_int_equal(n, 122);
    assert_int_equal(encode(m, buf, 121), -1);
    Frame g{};
    assert_true(decode_frame(buf, static_cast<std::size_t>(n), g) == Wire::Ok);
    assert_int_equal(g.seq, 123);
    assert_int_equal(g.utime, f.utime);
    assert_memory_equal(g.counts, f.counts, sizeof f.counts);
    assert_memory_equal(g.status, f.status, sizeof f.status);
    assert_int_equal(g.plant_flags, 2);
    assert_int_equal(g.scenario_flags, -5);
    assert_true(decode_frame(buf, static_cast<std::size_t>(n - 1), g) == Wire::Malformed);
    buf[0] = static_cast<std::uint8_t>(buf[0] ^ 1u);    // fingerprint
    assert_true(decode_frame(buf, static_cast<std::size_t>(n), g) == Wire::Malformed);
    m.n_counts = 17;
    assert_false(from_lcm(m, g));

    Command c{};
    c.seq = 9;
    c.n_counts = 2;
    c.counts[0] = -3;
    c.fsw_health = 0x80000101u;
    gnc::actuator_cmd_v2_t a{};
    to_lcm(c, a);
    assert_int_equal(a.fsw_health, INT32_MIN + 0x101);
    assert_int_equal(encode(a, buf, sizeof buf), 102);
    Command d{};
    assert_true(decode_command(buf, 102, d) == Wire::Ok);
    assert_int_equal(d.fsw_health, 0x80000101u);
    assert_int_equal(d.counts[0], -3);

    Telemetry t{};
    t.seq = 4;
    t.tlm_len = 2;
    t.tlm[0] = 0xAB;
    t.tlm[1] = 0xCD;
    t.tlm[2] = 0xEE;   // beyond tlm_len: zero on the wire
    t.counters.dups = 1; t.counters.stale = 2; t.counters.gaps = 3; t.counters.nonfinite_rej = 4;
    t.counters.range_rej = 5; t.counters.missed = 6; t.counters.table_rej = 7; t.counters.malformed = 8;
    t.counters.crc_rej = 9; t.counters.time_rej = 10; t.counters.jump_rej = 11;
    gnc::fsw_tlm_frame_t tm{};
    to_lcm(t, tm);
    assert_int_equal(tm.tlm[1], 0xCD);
    assert_int_equal(tm.tlm[2], 0);
    assert_int_equal(tm.dups, 1); assert_int_equal(tm.stale, 2); assert_int_equal(tm.gaps, 3);
    assert_int_equal(tm.nonfinite_rej, 4); assert_int_equal(tm.range_rej, 5);
    assert_int_equal(tm.missed, 6); assert_int_equal(tm.table_rej, 7);
    assert_int_equal(tm.rejected, 4 + 5 + 7 + 8 + 9 + 10 + 11);
    assert_int_equal(encode(tm, buf, sizeof buf), -1);
    std::uint8_t big[600];
    assert_int_equal(encode(tm, big, sizeof big), 574);
}

void counters_saturate(void **)
{
    std::int32_t c = INT32_MAX - 1;
    sat_inc(c);
    assert_int_equal(c, INT32_MAX);
    sat_inc(c);
    assert_int_equal(c, INT32_MAX);
    std::int32_t d = 0;
    sat_inc(d, INT64_MAX);
    assert_int_equal(d, INT32_MAX);
    SeqGate g(0);
    Counters k{};
    Command cmd{};
    assert_non_null(g.commit(GateAction::Gap, kMaxSeq, &cmd, k));   // huge gap: no overflow
    assert_int_equal(k.gap_frames, INT32_MAX);
}

}  // namespace

// Telecommands wait for their frame, go to the backend just before its step in arrival order,
// and a full queue refuses (cmd_rej) without touching the others.
class CmdBackend final : public bridge::Backend {
public:
    bool reset() override { return true; }
    bool step(const Frame &f, bridge::StepOutput &out) override
    {
        out = bridge::StepOutput{};
        steps.push_back({f.seq, static_cast<std::int64_t>(got.size())});
        return true;
    }
    bool command(const bridge::FswCommand &c) override
    {
        got.push_back(c.cmd);
        return c.cmd != 99;   // 99: a command this backend does not take
    }
    const char *name() const override { return "cmd"; }
    std::vector<std::int32_t> got;
    std::vector<std::pair<std::int64_t, std::int64_t>> steps;   // (seq, commands seen before it)
};

void telecommands_wait_for_their_frame(void **)
{
    CmdBackend be;
    Bridge br(be, limits_pm(1000000));
    bridge::FswCommand c{};
    c.apply_seq = 2; c.cmd = 1;
    assert_true(br.on_command(c));
    c.apply_seq = 0; c.cmd = 2;
    assert_true(br.on_command(c));
    c.apply_seq = 2; c.cmd = 99;
    assert_true(br.on_command(c));
    for (std::int64_t k = 0; k < 4; ++k) {
        (void)br.on_frame(bt::make_frame(k, kPeriod));
    }
    assert_int_equal(be.got.size(), 3);
    assert_int_equal(be.got[0], 2);                 // due at frame 0
    assert_int_equal(be.got[1], 1);                 // due at 2, in arrival order
    assert_int_equal(be.got[2], 99);
    assert_int_equal(be.steps[0].second, 1);        // frame 0 stepped after its command
    assert_int_equal(be.steps[1].second, 1);
    assert_int_equal(be.steps[2].second, 3);
    assert_int_equal(br.counters().cmds, 2);
    assert_int_equal(br.counters().cmd_rej, 1);     // the backend refused 99
    for (std::size_t i = 0; i < bridge::kCmdQueue; ++i) {
        c.apply_seq = 100;
        assert_true(br.on_command(c));
    }
    assert_false(br.on_command(c));                 // full: refused and counted
    assert_int_equal(br.counters().cmd_rej, 2);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(gate_table_rows),
        cmocka_unit_test(gate_before_first_and_first_seq),
        cmocka_unit_test(gate_unchanged_on_reject),
        cmocka_unit_test(gate_refuses_implausible_jump),
        cmocka_unit_test(telecommands_wait_for_their_frame),
        cmocka_unit_test(validator_keeps_last_good),
        cmocka_unit_test(limits_follow_the_backend_table),
        cmocka_unit_test(si_adapter_values),
        cmocka_unit_test(si_adapter_frames),
        cmocka_unit_test(si_nan_never_steps),
        cmocka_unit_test(gate_refuses_inconsistent_time),
        cmocka_unit_test(gate_every_seq_bit),
        cmocka_unit_test(gate_resynchronises_after_consistent_frames),
        cmocka_unit_test(crc_refuses_every_single_bit_flip),
        cmocka_unit_test(crc_seals_every_sealed_type),
        cmocka_unit_test(codec_roundtrip),
        cmocka_unit_test(counters_saturate),
    };
    return cmocka_run_group_tests_name("bridge_unit", tests, nullptr, nullptr);
}
