// Every mission's telemetry layout, field by field (issue: "tests check each layout field by
// field, not by size"). Field i of the mission's fsw_tlm_t is set to pattern(i) through its own
// lvalue (generated from the field list), encoded by the flight encoder (fsw_tlm_encode: the
// generated fsw_tlm_head.c, act/health, <prefix>_tlm.c), then read back by the host's reader
// (hil_host/missions decode_tlm over the generated iface tables) and compared field by field by
// name. The encoded bytes go to OUT_DIR/<MISSION>.bin for tlm_layout_check.py, which decodes them
// with tools.iface (the Python decoder the reports use). A field written at another offset, with
// another type, or twice shows as the first field whose value differs.
#include <cstdio>
#include <string>
#include <vector>

#include "mission_host.hpp"
#include "sim_test.hpp"
#include "tlm_pattern.h"

namespace {

std::string g_out;

std::int64_t expected(std::size_t i, char type)
{
    const auto k = static_cast<std::uint32_t>(i);
    switch (type) {
    case 'b': return tlm_pat_u8(k);
    case 'h': return tlm_pat_u16(k);
    case 'u': return tlm_pat_u32(k);
    case 'i': return tlm_pat_i32(k);
    default: return tlm_pat_i64(k);
    }
}

}  // namespace

SIM_TEST(every_field_of_every_layout)
{
    EXPECT_TRUE(iface::kNumMissions >= 1u);
    for (std::size_t mi = 0; mi < iface::kNumMissions; ++mi) {
        const iface::Mission &m = iface::kMissions[mi];
        const host::TlmLayout &l = host::tlm_layout(m);
        static fsw_tlm_t t;   // large: static storage
        t = fsw_tlm_t{};
        tlm_pattern_fill(&t, m.id);
        std::vector<std::uint8_t> buf(l.bytes + 8u, 0xA5u);
        const std::uint32_t n = fsw_tlm_encode(&t, buf.data(), static_cast<std::uint32_t>(buf.size()));
        EXPECT_EQ_INT(n, l.bytes);
        EXPECT_EQ_INT(n, m.tlm_bytes);
        EXPECT_EQ_INT(fsw_tlm_layout(&t), m.layout_version);
        EXPECT_EQ_INT(fsw_tlm_encode(&t, buf.data(), n - 1u), 0);   // too small: nothing
        buf.resize(n);
        std::vector<std::int64_t> v;
        EXPECT_TRUE(host::decode_tlm(l, buf.data(), buf.size(), v));
        EXPECT_EQ_INT(v.size(), m.n_tlm);
        unsigned bad = 0u;
        for (std::size_t i = 0; i < v.size() && i < m.n_tlm; ++i) {
            if (v[i] != expected(i, l.types[i])) {
                std::printf("%s field %zu %s: read %lld, wrote %lld\n", m.name, i, l.names[i].c_str(),
                            static_cast<long long>(v[i]), static_cast<long long>(expected(i, l.types[i])));
                ++bad;
            }
        }
        EXPECT_EQ_INT(bad, 0);
        std::printf("%s: %zu fields, %u bytes, layout 0x%08X: %s\n", m.name, v.size(), n,
                    static_cast<unsigned>(m.layout_version), bad == 0u ? "every field read back" : "MISMATCH");
        if (!g_out.empty()) {
            const std::string path = g_out + "/" + m.name + ".bin";
            std::FILE *f = std::fopen(path.c_str(), "wb");
            EXPECT_TRUE(f != nullptr);
            if (f != nullptr) {
                EXPECT_EQ_INT(std::fwrite(buf.data(), 1, buf.size(), f), buf.size());
                std::fclose(f);
            }
        }
    }
}

int main(int argc, char **argv)
{
    g_out = (argc > 1) ? argv[1] : "";
    const struct CMUnitTest tests[] = {cmocka_unit_test(every_field_of_every_layout)};
    return cmocka_run_group_tests_name("tlm_layout", tests, nullptr, nullptr);
}
