// lcm_codec.hpp — bridge structs <-> generated LCM C++ types (gnc::*) <-> wire bytes.
// Encoding goes into caller buffers (no allocation). A decode is Malformed on a short buffer,
// a wrong fingerprint, or n_counts / tlm_len outside the array bounds.
//
// End-to-end integrity (spec 00 §8, hil_host/lcmtypes/README.md): every message between the plant
// side and the flight side (sensor_frame_v2_t, actuator_cmd_v2_t, table_upload_v2_t,
// fsw_cmd_v2_t) ends in crc32, the CRC-32 (IEEE, fx_crc32) of every encoded byte before it,
// fingerprint included — the serial link's rule. encode() seals it; a decode checks it on the
// received bytes before any field is handed out (BadCrc: nothing of the message is used). Every
// sender and receiver of these types goes through these functions, so no path forgets the CRC.
#ifndef HIL_BRIDGE_LCM_CODEC_HPP
#define HIL_BRIDGE_LCM_CODEC_HPP

#include <cstddef>
#include <cstdint>

#include "bridge_types.hpp"
#include "gnc/actuator_cmd_v2_t.hpp"
#include "gnc/fsw_cmd_v2_t.hpp"
#include "gnc/fsw_tlm_frame_t.hpp"
#include "gnc/sensor_frame_v2_t.hpp"
#include "gnc/table_upload_v2_t.hpp"

namespace bridge {

enum class Wire { Ok, Malformed, BadCrc };

void to_lcm(const Frame &f, gnc::sensor_frame_v2_t &m);
bool from_lcm(const gnc::sensor_frame_v2_t &m, Frame &f);   // false: n_counts outside [0, 16]
void to_lcm(const Command &c, gnc::actuator_cmd_v2_t &m);
bool from_lcm(const gnc::actuator_cmd_v2_t &m, Command &c);
void to_lcm(const Telemetry &t, gnc::fsw_tlm_frame_t &m);  // counters -> dups..table_rej

// Encoded size (bytes) or -1 when cap is too small.
int encode(const gnc::sensor_frame_v2_t &m, std::uint8_t *buf, std::size_t cap);
int encode(const gnc::actuator_cmd_v2_t &m, std::uint8_t *buf, std::size_t cap);
int encode(const gnc::fsw_tlm_frame_t &m, std::uint8_t *buf, std::size_t cap);
int encode(const gnc::fsw_cmd_v2_t &m, std::uint8_t *buf, std::size_t cap);        // sealed
int encode(const gnc::table_upload_v2_t &m, std::uint8_t *buf, std::size_t cap);   // sealed
// (the sensor_frame_v2_t and actuator_cmd_v2_t encodes above are sealed too)

// Raw decodes of the sealed types: Ok only when the fingerprint, length and CRC all hold.
Wire decode(const std::uint8_t *buf, std::size_t len, gnc::sensor_frame_v2_t &m);
Wire decode(const std::uint8_t *buf, std::size_t len, gnc::actuator_cmd_v2_t &m);
Wire decode(const std::uint8_t *buf, std::size_t len, gnc::fsw_cmd_v2_t &m);
Wire decode(const std::uint8_t *buf, std::size_t len, gnc::table_upload_v2_t &m);

Wire decode_frame(const std::uint8_t *buf, std::size_t len, Frame &f);
Wire decode_command(const std::uint8_t *buf, std::size_t len, Command &c);
void to_lcm(const FswCommand &c, gnc::fsw_cmd_v2_t &m);
Wire decode_fsw_cmd(const std::uint8_t *buf, std::size_t len, FswCommand &c);

}  // namespace bridge

#endif  // HIL_BRIDGE_LCM_CODEC_HPP
