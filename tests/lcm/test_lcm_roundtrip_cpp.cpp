// test_lcm_roundtrip_cpp.cpp — generated C++ bindings of every gnc LCM type (spec 00 §5.1).
// For each type: the C binding encodes the shared pattern (lcm_pattern.h); the C++ binding
// decodes it, every field is compared with the C struct, and the C++ re-encoding must be
// byte-identical to the C encoding. Then a C++-only round trip through caller buffers.
// Plain main (ut.h is C-only); exit status 0 = pass.
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <vector>

#include "gnc/actuator_cmd_t.hpp"
#include "gnc/fsw_tlm_frame_t.hpp"
#include "gnc/sensor_frame_t.hpp"
#include "gnc/sil_ctl_t.hpp"
#include "gnc/sim_truth_t.hpp"
#include "gnc/table_ack_t.hpp"
#include "gnc/table_upload_t.hpp"
#include "gnc/actuator_cmd_v2_t.hpp"
#include "gnc/fsw_cmd_v2_t.hpp"
#include "gnc/sensor_frame_v2_t.hpp"
#include "gnc/table_upload_v2_t.hpp"
#include "lcm_pattern.h"

namespace {

int g_failures = 0;

void check(bool ok, const char *what, const char *type, int line)
{
    if (!ok) {
        std::fprintf(stderr, "%s:%d: %s: check failed: %s\n", __FILE__, line, type, what);
        ++g_failures;
    }
}
#define CHECK(c) check((c), #c, type, __LINE__)

// Bitwise equality, so -0.0 / inf / subnormal doubles are compared exactly (no float ==).
template <typename A, typename B>
bool same_bits(const A &a, const B &b)
{
    static_assert(sizeof(A) == sizeof(B), "field width mismatch between C and C++ bindings");
    return std::memcmp(&a, &b, sizeof(A)) == 0;
}
#define CHECK_FIELD(f) CHECK(same_bits(c.f, x.f))
#define CHECK_ARRAY(f) CHECK(sizeof(c.f) == sizeof(x.f) && std::memcmp(c.f, x.f, sizeof(c.f)) == 0)

void compare(const char *type, const gnc_sensor_frame_t &c, const gnc::sensor_frame_t &x)
{
    CHECK_FIELD(utime); CHECK_FIELD(seq); CHECK_FIELD(period_us); CHECK_FIELD(n_counts);
    CHECK_ARRAY(counts); CHECK_ARRAY(status); CHECK_FIELD(scenario_flags); CHECK_FIELD(plant_flags);
}
void compare(const char *type, const gnc_actuator_cmd_t &c, const gnc::actuator_cmd_t &x)
{
    CHECK_FIELD(utime); CHECK_FIELD(seq); CHECK_FIELD(n_counts); CHECK_ARRAY(counts);
    CHECK_FIELD(fsw_mode); CHECK_FIELD(fsw_health);
}
void compare(const char *type, const gnc_fsw_tlm_frame_t &c, const gnc::fsw_tlm_frame_t &x)
{
    CHECK_FIELD(utime); CHECK_FIELD(seq); CHECK_FIELD(tlm_layout_version); CHECK_FIELD(tlm_len);
    CHECK_ARRAY(tlm); CHECK_FIELD(dups); CHECK_FIELD(stale); CHECK_FIELD(gaps);
    CHECK_FIELD(rejected); CHECK_FIELD(nonfinite_rej); CHECK_FIELD(range_rej); CHECK_FIELD(missed);
    CHECK_FIELD(table_rej);
}
void compare(const char *type, const gnc_sim_truth_t &c, const gnc::sim_truth_t &x)
{
    CHECK_FIELD(utime); CHECK_FIELD(seq); CHECK_ARRAY(state); CHECK_ARRAY(extra); CHECK_FIELD(events);
}
void compare(const char *type, const gnc_table_upload_t &c, const gnc::table_upload_t &x)
{
    CHECK_FIELD(utime); CHECK_FIELD(table_id); CHECK_FIELD(revision); CHECK_FIELD(total_len);
    CHECK_FIELD(offset); CHECK_FIELD(n); CHECK_ARRAY(data);
}
void compare(const char *type, const gnc_table_ack_t &c, const gnc::table_ack_t &x)
{
    CHECK_FIELD(utime); CHECK_FIELD(table_id); CHECK_FIELD(revision); CHECK_FIELD(result);
    CHECK_FIELD(reason); CHECK_FIELD(bytes_received);
}
void compare(const char *type, const gnc_sil_ctl_t &c, const gnc::sil_ctl_t &x)
{
    CHECK_FIELD(utime); CHECK_FIELD(command); CHECK_ARRAY(scenario); CHECK_FIELD(seed);
    CHECK_FIELD(node_id); CHECK_FIELD(status);
}
void compare(const char *type, const gnc_sensor_frame_v2_t &c, const gnc::sensor_frame_v2_t &x)
{
    CHECK_FIELD(utime); CHECK_FIELD(seq); CHECK_FIELD(period_us); CHECK_FIELD(n_counts);
    CHECK_ARRAY(counts); CHECK_ARRAY(status); CHECK_FIELD(scenario_flags); CHECK_FIELD(plant_flags);
    CHECK_FIELD(crc32);
}
void compare(const char *type, const gnc_actuator_cmd_v2_t &c, const gnc::actuator_cmd_v2_t &x)
{
    CHECK_FIELD(utime); CHECK_FIELD(seq); CHECK_FIELD(n_counts); CHECK_ARRAY(counts);
    CHECK_FIELD(fsw_mode); CHECK_FIELD(fsw_health); CHECK_FIELD(crc32);
}
void compare(const char *type, const gnc_table_upload_v2_t &c, const gnc::table_upload_v2_t &x)
{
    CHECK_FIELD(utime); CHECK_FIELD(table_id); CHECK_FIELD(revision); CHECK_FIELD(total_len);
    CHECK_FIELD(offset); CHECK_FIELD(n); CHECK_ARRAY(data); CHECK_FIELD(crc32);
}
void compare(const char *type, const gnc_fsw_cmd_v2_t &c, const gnc::fsw_cmd_v2_t &x)
{
    CHECK_FIELD(utime); CHECK_FIELD(apply_seq); CHECK_FIELD(cmd); CHECK_ARRAY(args); CHECK_FIELD(crc32);
}

// One static scratch buffer per direction; the bindings encode into caller memory.
unsigned char g_c_buf[PAT_SIZE_MAX];
unsigned char g_x_buf[PAT_SIZE_MAX];
unsigned char g_x_buf2[PAT_SIZE_MAX];

template <typename CT, typename XT>
void run(const char *type, void (*fill)(CT *), int (*c_encode)(void *, int, int, const CT *), int len)
{
    CT c;
    fill(&c);
    const int n = c_encode(g_c_buf, 0, static_cast<int>(sizeof g_c_buf), &c);
    CHECK(n == len);

    // C -> C++: decode, compare fields, re-encode byte-identically.
    XT x;
    CHECK(x.decode(g_c_buf, 0, n) == n);
    compare(type, c, x);
    CHECK(x.getEncodedSize() == len);
    CHECK(x.encode(g_x_buf, 0, static_cast<int>(sizeof g_x_buf)) == n);
    CHECK(std::memcmp(g_c_buf, g_x_buf, static_cast<size_t>(n)) == 0);

    // C++ -> C++ round trip, then C++ -> C: the C decoder reads the C++ bytes back to the pattern.
    XT y;
    CHECK(y.decode(g_x_buf, 0, n) == n);
    CHECK(y.encode(g_x_buf2, 0, static_cast<int>(sizeof g_x_buf2)) == n);
    CHECK(std::memcmp(g_x_buf, g_x_buf2, static_cast<size_t>(n)) == 0);
    compare(type, c, y);

    // Bounds: one byte short is refused both ways; a foreign fingerprint is refused.
    CHECK(x.encode(g_x_buf2, 0, n - 1) < 0);
    CHECK(y.decode(g_x_buf, 0, n - 1) < 0);
    g_x_buf[0] ^= 0x01u;
    CHECK(y.decode(g_x_buf, 0, n) < 0);
    g_x_buf[0] ^= 0x01u;

    // Fingerprint agrees between the bindings.
    uint64_t fp = 0;
    for (int i = 0; i < 8; ++i) {
        fp = (fp << 8) | g_c_buf[i];
    }
    CHECK(fp == static_cast<uint64_t>(XT::getHash()));
    std::printf("%-16s %4d bytes  fingerprint 0x%016llX  ok\n", type, n,
                static_cast<unsigned long long>(fp));
}

}  // namespace

int main()
{
    run<gnc_sensor_frame_t, gnc::sensor_frame_t>("sensor_frame_t", pat_sensor,
                                                 gnc_sensor_frame_t_encode, PAT_SIZE_SENSOR);
    run<gnc_actuator_cmd_t, gnc::actuator_cmd_t>("actuator_cmd_t", pat_act,
                                                 gnc_actuator_cmd_t_encode, PAT_SIZE_ACT);
    run<gnc_fsw_tlm_frame_t, gnc::fsw_tlm_frame_t>("fsw_tlm_frame_t", pat_tlm,
                                                   gnc_fsw_tlm_frame_t_encode, PAT_SIZE_TLM);
    run<gnc_sim_truth_t, gnc::sim_truth_t>("sim_truth_t", pat_truth,
                                           gnc_sim_truth_t_encode, PAT_SIZE_TRUTH);
    run<gnc_table_upload_t, gnc::table_upload_t>("table_upload_t", pat_upload,
                                                 gnc_table_upload_t_encode, PAT_SIZE_UPLOAD);
    run<gnc_table_ack_t, gnc::table_ack_t>("table_ack_t", pat_ack,
                                           gnc_table_ack_t_encode, PAT_SIZE_ACK);
    run<gnc_sil_ctl_t, gnc::sil_ctl_t>("sil_ctl_t", pat_ctl, gnc_sil_ctl_t_encode, PAT_SIZE_CTL);
    run<gnc_sensor_frame_v2_t, gnc::sensor_frame_v2_t>("sensor_frame_v2_t", pat_sensor2,
                                                       gnc_sensor_frame_v2_t_encode, PAT_SIZE_SENSOR2);
    run<gnc_actuator_cmd_v2_t, gnc::actuator_cmd_v2_t>("actuator_cmd_v2_t", pat_act2,
                                                       gnc_actuator_cmd_v2_t_encode, PAT_SIZE_ACT2);
    run<gnc_table_upload_v2_t, gnc::table_upload_v2_t>("table_upload_v2_t", pat_upload2,
                                                       gnc_table_upload_v2_t_encode, PAT_SIZE_UPLOAD2);
    run<gnc_fsw_cmd_v2_t, gnc::fsw_cmd_v2_t>("fsw_cmd_v2_t", pat_cmd2, gnc_fsw_cmd_v2_t_encode, PAT_SIZE_CMD2);

    // Constants reach the C++ binding.
    const char *type = "constants";
    CHECK(gnc::sensor_frame_t::STATUS_SAT == 2);
    CHECK(gnc::sil_ctl_t::CMD_HEARTBEAT == 4);
    CHECK(gnc::table_ack_t::RESULT_ACCEPTED == 0);

    std::printf("%s: %d failure(s)\n", g_failures == 0 ? "PASS" : "FAIL", g_failures);
    return g_failures == 0 ? 0 : 1;
}
