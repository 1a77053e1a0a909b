// bridge_types.hpp — transport-independent messages and counters of the host bridge
// (spec 00 §5.1, §5.2, §8). Plain fixed-size structs mirroring the LCM types field for field;
// lcm_codec.hpp converts them to and from the generated gnc:: C++ types and wire bytes.
#ifndef HIL_BRIDGE_TYPES_HPP
#define HIL_BRIDGE_TYPES_HPP

#include <cstddef>
#include <cstdint>

namespace bridge {

constexpr std::size_t kMaxCounts = 16;   // sensor_frame_v2_t / actuator_cmd_v2_t counts[16]
constexpr std::size_t kMaxTlm = 512;     // fsw_tlm_frame_t tlm[512]

// Frames outside [0, kMaxSeq] are malformed, so seq +- 1 arithmetic never overflows.
constexpr std::int64_t kMaxSeq = INT64_C(1) << 62;

constexpr std::int8_t kStatusStale = 1;  // sensor_frame_v2_t::STATUS_STALE
constexpr std::int8_t kStatusSat = 2;    // sensor_frame_v2_t::STATUS_SAT

// Plant -> bridge: sensor frame k (integer counts only).
struct Frame {
    std::int64_t utime = 0;
    std::int64_t seq = 0;
    std::int32_t period_us = 0;
    std::int16_t n_counts = 0;
    std::int32_t counts[kMaxCounts] = {};
    std::int8_t status[kMaxCounts] = {};
    std::int32_t scenario_flags = 0;
    std::int32_t plant_flags = 0;
};

// Bridge -> plant: command k (utime and seq echoed from frame k).
struct Command {
    std::int64_t utime = 0;
    std::int64_t seq = 0;
    std::int16_t n_counts = 0;
    std::int32_t counts[kMaxCounts] = {};
    std::int32_t fsw_mode = 0;
    std::uint32_t fsw_health = 0;   // carried as int32 bits on the wire
};

constexpr std::size_t kMaxChunk = 256;   // table_upload_v2_t data[256]
constexpr std::int32_t kTableAccepted = 0;   // table_ack_t RESULT_*
constexpr std::int32_t kTablePartial = 1;
constexpr std::int32_t kTableRejected = 2;

// Tools -> bridge: one table_upload_v2_t chunk (data points into the decoded message).
struct TableChunk {
    std::int64_t utime = 0;
    std::int32_t table_id = 0;
    std::int32_t revision = 0;
    std::int32_t total_len = 0;
    std::int32_t offset = 0;
    std::int16_t n = 0;
    const std::uint8_t *data = nullptr;
};

// Bridge -> tools: table_ack_t.
struct TableAck {
    std::int64_t utime = 0;
    std::int32_t table_id = 0;
    std::int32_t revision = 0;
    std::int32_t result = kTableRejected;
    std::int32_t reason = 0;
    std::int32_t bytes_received = 0;
};

// Ground / test conductor -> flight software: one telecommand (gnc::fsw_cmd_v2_t). The bridge
// holds it until the first frame with seq >= apply_seq and hands it to the backend just before
// that frame's step.
constexpr std::size_t kCmdArgs = 8;
constexpr std::size_t kCmdQueue = 16;     // telecommands held at once; more are refused (cmd_rej)
constexpr std::int32_t kCmdMode = 1;      // fsw_cmd_v2_t CMD_MODE; a mission's telecommands carry its
                                          // namespaced ids (>= 0x100, hil_host/lcmtypes/fsw_cmd_v2_t.lcm)
struct FswCommand {
    std::int64_t utime = 0;
    std::int64_t apply_seq = 0;
    std::int32_t cmd = 0;
    std::int32_t args[kCmdArgs] = {};
};

// Cumulative bridge counters; every one saturates at INT32_MAX (fsw_tlm_frame_t comment).
struct Counters {
    std::int32_t stepped = 0;        // backend steps (seq == last+1 or a gap)
    std::int32_t dups = 0;           // seq == last: cached command re-published
    std::int32_t stale = 0;          // seq < last: dropped
    std::int32_t gaps = 0;           // gap events: seq > last+1 (stepped)
    std::int32_t gap_frames = 0;     // frames skipped over by the gap events (sum of seq-last-1)
    std::int32_t nonfinite_rej = 0;  // SI values rejected by std::isfinite (before any cast)
    std::int32_t range_rej = 0;      // channel values outside the sensor-table limits
    std::int32_t malformed = 0;      // frames refused whole: undecodable, n_counts/period/seq bad
    std::int32_t missed = 0;         // missed commands reported by the plant
    std::int32_t table_rej = 0;      // table uploads refused (loader, module veto, or no uploads)
    std::int32_t cmds = 0;           // telecommands handed to the flight software
    std::int32_t cmd_rej = 0;        // telecommands refused by the bridge (queue full, unknown, no backend support)
    std::int32_t crc_rej = 0;        // messages refused on their crc32 (sensor frames, table chunks, telecommands)
    std::int32_t time_rej = 0;       // sensor frames whose utime != seq * period_us
    std::int32_t jump_rej = 0;       // sensor frames whose seq jumps beyond the window (kMaxSeqJump)
    std::int32_t resyncs = 0;        // deliberate resynchronisations to an out-of-window seq (kResyncFrames)
};

// Bridge -> logger: telemetry of step k plus the counters.
struct Telemetry {
    std::int64_t utime = 0;
    std::int64_t seq = 0;
    std::int32_t tlm_layout_version = 0;
    std::int16_t tlm_len = 0;
    std::uint8_t tlm[kMaxTlm] = {};
    Counters counters;
};

// Saturating counter increment by a non-negative amount (INT32_MAX sticks; by is clamped).
inline void sat_inc(std::int32_t &c, std::int64_t by = 1)
{
    const std::int64_t b = (by < 0) ? 0 : ((by > INT32_MAX) ? INT32_MAX : by);
    const std::int64_t v = static_cast<std::int64_t>(c) + b;
    c = (v > INT32_MAX) ? INT32_MAX : static_cast<std::int32_t>(v);
}

// "rejected" of fsw_tlm_frame_t: every rejection event, i.e. nonfinite_rej + range_rej +
// table_rej + malformed + crc_rej + time_rej + jump_rej, saturating.
inline std::int32_t rejected_total(const Counters &c)
{
    const std::int64_t v = static_cast<std::int64_t>(c.nonfinite_rej) + c.range_rej + c.table_rej +
                           c.malformed + c.crc_rej + c.time_rej + c.jump_rej;
    return (v > INT32_MAX) ? INT32_MAX : static_cast<std::int32_t>(v);
}

// uint32 bit set <-> int32 wire value without implementation-defined conversions.
inline std::int32_t bits_to_i32(std::uint32_t v)
{
    return (v <= 0x7FFFFFFFu) ? static_cast<std::int32_t>(v)
                              : static_cast<std::int32_t>(static_cast<std::int64_t>(v) - INT64_C(0x100000000));
}
inline std::uint32_t i32_to_bits(std::int32_t v)
{
    return (v >= 0) ? static_cast<std::uint32_t>(v)
                    : static_cast<std::uint32_t>(static_cast<std::int64_t>(v) + INT64_C(0x100000000));
}

}  // namespace bridge

#endif  // HIL_BRIDGE_TYPES_HPP
