#include "lcm_codec.hpp"

#include <climits>

namespace bridge {

// One meaning per status bit on both sides of the codec.
static_assert(kStatusStale == gnc::sensor_frame_t::STATUS_STALE, "bridge STALE bit != wire");
static_assert(kStatusSat == gnc::sensor_frame_t::STATUS_SAT, "bridge SAT bit != wire");

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

template <typename M>
bool decode_any(const std::uint8_t *buf, std::size_t len, M &m)
{
    if (buf == nullptr) {
        return false;
    }
    const int n = len_of(len);
    return m.decode(buf, 0, n) == m.getEncodedSize();
}

}  // namespace

void to_lcm(const Frame &f, gnc::sensor_frame_t &m)
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

bool from_lcm(const gnc::sensor_frame_t &m, Frame &f)
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

void to_lcm(const Command &c, gnc::actuator_cmd_t &m)
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

bool from_lcm(const gnc::actuator_cmd_t &m, Command &c)
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

int encode(const gnc::sensor_frame_t &m, std::uint8_t *buf, std::size_t cap) { return encode_any(m, buf, cap); }
int encode(const gnc::actuator_cmd_t &m, std::uint8_t *buf, std::size_t cap) { return encode_any(m, buf, cap); }
int encode(const gnc::fsw_tlm_frame_t &m, std::uint8_t *buf, std::size_t cap) { return encode_any(m, buf, cap); }

bool decode_frame(const std::uint8_t *buf, std::size_t len, Frame &f)
{
    gnc::sensor_frame_t m{};
    return decode_any(buf, len, m) && from_lcm(m, f);
}

bool decode_command(const std::uint8_t *buf, std::size_t len, Command &c)
{
    gnc::actuator_cmd_t m{};
    return decode_any(buf, len, m) && from_lcm(m, c);
}

void to_lcm(const FswCommand &c, gnc::fsw_cmd_t &m)
{
    m.utime = c.utime;
    m.apply_seq = c.apply_seq;
    m.cmd = c.cmd;
    for (std::size_t i = 0; i < kCmdArgs; ++i) { m.args[i] = c.args[i]; }
}

bool decode_fsw_cmd(const std::uint8_t *buf, std::size_t len, FswCommand &c)
{
    gnc::fsw_cmd_t m{};
    if (!decode_any(buf, len, m)) {
        return false;
    }
    c.utime = m.utime;
    c.apply_seq = m.apply_seq;
    c.cmd = m.cmd;
    for (std::size_t i = 0; i < kCmdArgs; ++i) { c.args[i] = m.args[i]; }
    return true;
}

}  // namespace bridge
