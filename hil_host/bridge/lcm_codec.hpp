// lcm_codec.hpp — bridge structs <-> generated LCM C++ types (gnc::*) <-> wire bytes.
// Encoding goes into caller buffers (no allocation). A decode fails (false) on a short buffer,
// a wrong fingerprint, or n_counts / tlm_len outside the array bounds.
#ifndef HIL_BRIDGE_LCM_CODEC_HPP
#define HIL_BRIDGE_LCM_CODEC_HPP

#include <cstddef>
#include <cstdint>

#include "bridge_types.hpp"
#include "gnc/actuator_cmd_t.hpp"
#include "gnc/fsw_cmd_t.hpp"
#include "gnc/fsw_tlm_frame_t.hpp"
#include "gnc/sensor_frame_t.hpp"

namespace bridge {

void to_lcm(const Frame &f, gnc::sensor_frame_t &m);
bool from_lcm(const gnc::sensor_frame_t &m, Frame &f);   // false: n_counts outside [0, 16]
void to_lcm(const Command &c, gnc::actuator_cmd_t &m);
bool from_lcm(const gnc::actuator_cmd_t &m, Command &c);
void to_lcm(const Telemetry &t, gnc::fsw_tlm_frame_t &m);  // counters -> dups..table_rej

// Encoded size (bytes) or -1 when cap is too small.
int encode(const gnc::sensor_frame_t &m, std::uint8_t *buf, std::size_t cap);
int encode(const gnc::actuator_cmd_t &m, std::uint8_t *buf, std::size_t cap);
int encode(const gnc::fsw_tlm_frame_t &m, std::uint8_t *buf, std::size_t cap);

bool decode_frame(const std::uint8_t *buf, std::size_t len, Frame &f);
bool decode_command(const std::uint8_t *buf, std::size_t len, Command &c);
void to_lcm(const FswCommand &c, gnc::fsw_cmd_t &m);
bool decode_fsw_cmd(const std::uint8_t *buf, std::size_t len, FswCommand &c);

}  // namespace bridge

#endif  // HIL_BRIDGE_LCM_CODEC_HPP
