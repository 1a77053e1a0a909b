#include "lcm_codec.hpp"

#include <climits>

#include <zlib.h>

namespace bridge {

// One meaning per status bit on both sides of the codec.
static_assert(kStatusStale == gnc::sensor_frame_v2_t::STATUS_STALE, "bridge STALE bit != wire");
static_assert(kStatusSat == gnc::sensor_frame_v2_t::STATUS_SAT, "bridge SAT bit != wire");

namespace {

bool n_ok(std::int16_t n, std::size_t cap)
{
    return (n >= 0) && (static_cast<std::size_t>(n) <= cap);
}

int len_of(std::size_t cap)
{
    return (cap > static_cast<std::size_t>(INT_MAX)) ? INT_MAX : static_cast<int>(cap);
}

template <typename M>
int encode_any(const M &m, std::uint8_t *buf, std::size_t cap)
{
    const int need = m.getEncodedSize();
    if ((buf == nullptr) || (need < 0) || (static_cast<std::size_t>(need) > cap)) {
        return -1;
    }
    const int r = m.encode(buf, 0, need);
    return (r == need) ? r : -1;
}

constexpr std::size_t kCrcLen = 4u;   // crc32 is the last field: the last 4 encoded bytes

// zlib's crc32 is the CRC-32 the wire specifies (IEEE, reflected, init and final xor 0xFFFFFFFF: the
// flight's fx_crc32 and Python's zlib.crc32 give the same check value, test_fx_core). The host uses
// the library's table-driven one: with the flight's 64-byte nibble table, sealing and checking frames
// took a third of a Release `sil run --batch` (perf); zlib made the run 27 % faster.
std::uint32_t crc_of(const std::uint8_t *buf, std::size_t n)
{
    const std::size_t len = n - kCrcLen;   // callers pass n >= kCrcLen; frames are < 1 KiB
    return static_cast<std::uint32_t>(
        ::crc32(0uL, buf, static_cast<uInt>(len)));
}

// LCM encodes int32 big-endian.
void put_be32(std::uint8_t *p, std::uint32_t v)
{
    p[0] = static_cast<std::uint8_t>(v >> 24);
    p[1] = static_cast<std::uint8_t>(v >> 16);
    p[2] = static_cast<std::uint8_t>(v >> 8);
    p[3] = static_cast<std::uint8_t>(v);
}

std::uint32_t get_be32(const std::uint8_t *p)
{
    return (static_cast<std::uint32_t>(p[0]) << 24) | (static_cast<std::uint32_t>(p[1]) << 16) |
           (static_cast<std::uint32_t>(p[2]) << 8) | static_cast<std::uint32_t>(p[3]);
}

// Encodes, then overwrites the crc32 field in the bytes (whatever m.crc32 held).
template <typename M>
int encode_sealed(const M &m, std::uint8_t *buf, std::size_t cap)
{
    const int n = encode_any(m, buf, cap);
    if (n >= static_cast<int>(kCrcLen)) {
        const std::size_t un = static_cast<std::size_t>(n);
        put_be32(buf + un - kCrcLen, crc_of(buf, un));
    }
    return n;
}

template <typename M>
bool decode_any(const std::uint8_t *buf, std::size_t len, M &m)
{
    if (buf == nullptr) {
        return false;
    }
    const int n = len_of(len);
    return m.decode(buf, 0, n) == m.getEncodedSize();
}

// The CRC is checked on the received bytes; the length is the type's (fixed) encoded size, so
// trailing bytes beyond it are outside the seal and ignored, as LCM's decode ignores them.
template <typename M>
Wire decode_sealed(const std::uint8_t *buf, std::size_t len, M &m)
{
    if (!decode_any(buf, len, m)) {
        return Wire::Malformed;
    }
    const std::size_t n = static_cast<std::size_t>(m.getEncodedSize());
    if (get_be32(buf + n - kCrcLen) != crc_of(buf, n)) {
        m = M{};   // nothing of a message that failed its check is handed out
        return Wire::BadCrc;
    }
    return Wire::Ok;
}

}  // namespace

void to_lcm(const Frame &f, gnc::sensor_frame_v2_t &m)
{
    m.utime = f.utime;
    m.seq = f.seq;
    m.period_us = f.period_us;
    m.n_counts = f.n_counts;
    for (std::size_t i = 0; i < kMaxCounts; ++i) {
        m.counts[i] = f.counts[i];
        m.status[i] = f.status[i];
    }
    m.scenario_flags = f.scenario_flags;
    m.plant_flags = f.plant_flags;
}

bool from_lcm(const gnc::sensor_frame_v2_t &m, Frame &f)
{
    if (!n_ok(m.n_counts, kMaxCounts)) {
        return false;
    }
    f.utime = m.utime;
    f.seq = m.seq;
    f.period_us = m.period_us;
    f.n_counts = m.n_counts;
    for (std::size_t i = 0; i < kMaxCounts; ++i) {
        f.counts[i] = m.counts[i];
        f.status[i] = m.status[i];
    }
    f.scenario_flags = m.scenario_flags;
    f.plant_flags = m.plant_flags;
    return true;
}

void to_lcm(const Command &c, gnc::actuator_cmd_v2_t &m)
{
    m.utime = c.utime;
    m.seq = c.seq;
    m.n_counts = c.n_counts;
    for (std::size_t i = 0; i < kMaxCounts; ++i) {
        m.counts[i] = c.counts[i];
    }
    m.fsw_mode = c.fsw_mode;
    m.fsw_health = bits_to_i32(c.fsw_health);
}

bool from_lcm(const gnc::actuator_cmd_v2_t &m, Command &c)
{
    if (!n_ok(m.n_counts, kMaxCounts)) {
        return false;
    }
    c.utime = m.utime;
    c.seq = m.seq;
    c.n_counts = m.n_counts;
    for (std::size_t i = 0; i < kMaxCounts; ++i) {
        c.counts[i] = m.counts[i];
    }
    c.fsw_mode = m.fsw_mode;
    c.fsw_health = i32_to_bits(m.fsw_health);
    return true;
}

void to_lcm(const Telemetry &t, gnc::fsw_tlm_frame_t &m)
{
    m.utime = t.utime;
    m.seq = t.seq;
    m.tlm_layout_version = t.tlm_layout_version;
    const std::int16_t n = n_ok(t.tlm_len, kMaxTlm) ? t.tlm_len : static_cast<std::int16_t>(0);
    m.tlm_len = n;
    for (std::size_t i = 0; i < kMaxTlm; ++i) {
        m.tlm[i] = (i < static_cast<std::size_t>(n)) ? t.tlm[i] : static_cast<std::uint8_t>(0);
    }
    const Counters &c = t.counters;
    m.dups = c.dups;
    m.stale = c.stale;
    m.gaps = c.gaps;
    m.rejected = rejected_total(c);
    m.nonfinite_rej = c.nonfinite_rej;
    m.range_rej = c.range_rej;
    m.missed = c.missed;
    m.table_rej = c.table_rej;
}

int encode(const gnc::sensor_frame_v2_t &m, std::uint8_t *buf, std::size_t cap) { return encode_sealed(m, buf, cap); }
int encode(const gnc::actuator_cmd_v2_t &m, std::uint8_t *buf, std::size_t cap) { return encode_sealed(m, buf, cap); }
int encode(const gnc::fsw_tlm_frame_t &m, std::uint8_t *buf, std::size_t cap) { return encode_any(m, buf, cap); }
int encode(const gnc::fsw_cmd_v2_t &m, std::uint8_t *buf, std::size_t cap) { return encode_sealed(m, buf, cap); }
int encode(const gnc::table_upload_v2_t &m, std::uint8_t *buf, std::size_t cap) { return encode_sealed(m, buf, cap); }

Wire decode(const std::uint8_t *buf, std::size_t len, gnc::sensor_frame_v2_t &m) { return decode_sealed(buf, len, m); }
Wire decode(const std::uint8_t *buf, std::size_t len, gnc::actuator_cmd_v2_t &m) { return decode_sealed(buf, len, m); }
Wire decode(const std::uint8_t *buf, std::size_t len, gnc::fsw_cmd_v2_t &m) { return decode_sealed(buf, len, m); }
Wire decode(const std::uint8_t *buf, std::size_t len, gnc::table_upload_v2_t &m) { return decode_sealed(buf, len, m); }

Wire decode_frame(const std::uint8_t *buf, std::size_t len, Frame &f)
{
    gnc::sensor_frame_v2_t m{};
    const Wire w = decode_sealed(buf, len, m);
    return (w != Wire::Ok) ? w : (from_lcm(m, f) ? Wire::Ok : Wire::Malformed);
}

Wire decode_command(const std::uint8_t *buf, std::size_t len, Command &c)
{
    gnc::actuator_cmd_v2_t m{};
    const Wire w = decode_sealed(buf, len, m);
    return (w != Wire::Ok) ? w : (from_lcm(m, c) ? Wire::Ok : Wire::Malformed);
}

void to_lcm(const FswCommand &c, gnc::fsw_cmd_v2_t &m)
{
    m.utime = c.utime;
    m.apply_seq = c.apply_seq;
    m.cmd = c.cmd;
    for (std::size_t i = 0; i < kCmdArgs; ++i) { m.args[i] = c.args[i]; }
}

Wire decode_fsw_cmd(const std::uint8_t *buf, std::size_t len, FswCommand &c)
{
    gnc::fsw_cmd_v2_t m{};
    const Wire w = decode_sealed(buf, len, m);
    if (w != Wire::Ok) {
        return w;
    }
    c.utime = m.utime;
    c.apply_seq = m.apply_seq;
    c.cmd = m.cmd;
    for (std::size_t i = 0; i < kCmdArgs; ++i) { c.args[i] = m.args[i]; }
    return Wire::Ok;
}

}  // namespace bridge
