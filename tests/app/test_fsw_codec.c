/*
 * fsw_codec: little-endian field codec with a bounds-checked cursor, and the table CRC.
 * Host (CMocka) and Cortex-M3 under QEMU. Expected byte patterns are written out by hand, so
 * the test does not rely on the host's own endianness.
 */
#include "app/fsw_codec.h"
#include "fx.h"
#include "ut.h"

#define NELEM(a) (sizeof(a) / sizeof((a)[0]))

UT_TEST(codec_le_byte_layout)
{
    uint8_t b[19];
    fsw_wr_t w;
    static const uint8_t want[19] = {
        0xA5u,                                             /* u8 */
        0x34u, 0x12u,                                      /* u16 0x1234 */
        0x44u, 0x33u, 0x22u, 0x11u,                        /* u32 0x11223344 */
        0xFEu, 0xFFu, 0xFFu, 0xFFu,                        /* i32 -2 */
        0x00u, 0x00u, 0x00u, 0x00u, 0x00u, 0x00u, 0x00u, 0x80u, /* i64 INT64_MIN */
    };
    size_t i;
    fsw_wr_init(&w, b, (uint32_t)sizeof b);
    fsw_wr_u8(&w, 0xA5u);
    fsw_wr_u16(&w, 0x1234u);
    fsw_wr_u32(&w, 0x11223344u);
    fsw_wr_i32(&w, -2);
    fsw_wr_i64(&w, INT64_MIN);
    UT_TRUE(!w.err);
    UT_UEQ(w.pos, 19u);
    for (i = 0u; i < NELEM(want); i++) {
        UT_CHECK_UEQ(b[i], want[i]);
    }
}

UT_TEST(codec_round_trip_edges)
{
    static const int32_t i32v[] = {INT32_MIN, INT32_MIN + 1, -65536, -1, 0, 1, 65535, INT32_MAX};
    static const int64_t i64v[] = {INT64_MIN, INT64_MIN + 1, -((int64_t)1 << 40), -1, 0, 1,
                                   (int64_t)1 << 40, INT64_MAX};
    static const uint32_t u32v[] = {0u, 1u, 0x7FFFFFFFu, 0x80000000u, 0xDEADBEEFu, UINT32_MAX};
    static const uint16_t u16v[] = {0u, 1u, 0x7FFFu, 0x8000u, UINT16_MAX};
    uint8_t b[8u * 8u + 4u * 8u + 4u * 6u + 2u * 5u + 1u];
    fsw_wr_t w;
    fsw_rd_t r;
    size_t i;
    fsw_wr_init(&w, b, (uint32_t)sizeof b);
    for (i = 0u; i < NELEM(i64v); i++) { fsw_wr_i64(&w, i64v[i]); }
    for (i = 0u; i < NELEM(i32v); i++) { fsw_wr_i32(&w, i32v[i]); }
    for (i = 0u; i < NELEM(u32v); i++) { fsw_wr_u32(&w, u32v[i]); }
    for (i = 0u; i < NELEM(u16v); i++) { fsw_wr_u16(&w, u16v[i]); }
    fsw_wr_u8(&w, 0xFFu);
    UT_TRUE(!w.err);
    UT_UEQ(w.pos, sizeof b);
    fsw_rd_init(&r, b, (uint32_t)sizeof b);
    for (i = 0u; i < NELEM(i64v); i++) { UT_CHECK_EQ(fsw_rd_i64(&r), i64v[i]); }
    for (i = 0u; i < NELEM(i32v); i++) { UT_CHECK_EQ(fsw_rd_i32(&r), i32v[i]); }
    for (i = 0u; i < NELEM(u32v); i++) { UT_CHECK_UEQ(fsw_rd_u32(&r), u32v[i]); }
    for (i = 0u; i < NELEM(u16v); i++) { UT_CHECK_UEQ(fsw_rd_u16(&r), u16v[i]); }
    UT_UEQ(fsw_rd_u8(&r), 0xFFu);
    UT_TRUE(!r.err);
    UT_UEQ(r.pos, sizeof b);
}

UT_TEST(codec_round_trip_random)
{
    uint64_t seed = UINT64_C(0x7AB1E5EED);
    uint8_t b[8];
    int k;
    for (k = 0; k < 4096; k++) {
        uint64_t x = ut_rng_next(&seed);
        int32_t v32 = (int32_t)(uint32_t)(x >> 32);   /* GCC: modulo conversion (test only) */
        int64_t v64 = (int64_t)x;
        fsw_wr_t w;
        fsw_rd_t r;
        fsw_wr_init(&w, b, 8u);
        fsw_wr_i64(&w, v64);
        fsw_rd_init(&r, b, 8u);
        UT_EQ(fsw_rd_i64(&r), v64);
        fsw_wr_init(&w, b, 8u);
        fsw_wr_i32(&w, v32);
        fsw_rd_init(&r, b, 8u);
        UT_EQ(fsw_rd_i32(&r), v32);
        /* u32 and i32 share the wire form: the same bytes read back as either. */
        fsw_rd_init(&r, b, 8u);
        UT_UEQ(fsw_rd_u32(&r), (uint32_t)v32);
    }
}

UT_TEST(codec_read_overrun_is_sticky_and_in_bounds)
{
    /* Only the middle 3 bytes are the buffer; the guards around it must never be read into a
       result (their values would show up in it). */
    static const uint8_t mem[5] = {0xEEu, 0x01u, 0x02u, 0x03u, 0xEEu};
    fsw_rd_t r;
    fsw_rd_init(&r, &mem[1], 3u);
    UT_UEQ(fsw_rd_u32(&r), 0u);          /* would cross the end: 0, err, pos unchanged */
    UT_TRUE(r.err);
    UT_UEQ(r.pos, 0u);
    UT_UEQ(fsw_rd_u8(&r), 0u);           /* sticky: even a fitting read now fails */
    UT_UEQ(r.pos, 0u);
    fsw_rd_init(&r, &mem[1], 3u);
    UT_UEQ(fsw_rd_u16(&r), 0x0201u);
    UT_UEQ(fsw_rd_u8(&r), 0x03u);
    UT_TRUE(!r.err);
    UT_UEQ(fsw_rd_u8(&r), 0u);           /* exactly at the end */
    UT_TRUE(r.err);
    UT_UEQ(r.pos, 3u);
    fsw_rd_init(&r, &mem[1], 3u);
    UT_EQ(fsw_rd_i64(&r), 0);
    UT_TRUE(r.err);
    fsw_rd_init(&r, &mem[1], 3u);
    UT_EQ(fsw_rd_i32(&r), 0);
    UT_TRUE(r.err);
}

UT_TEST(codec_write_overrun_touches_nothing)
{
    uint8_t mem[6] = {0xEEu, 0u, 0u, 0u, 0u, 0xEEu};
    fsw_wr_t w;
    fsw_wr_init(&w, &mem[1], 4u);
    fsw_wr_u16(&w, 0xBBAAu);
    fsw_wr_u32(&w, 0x11111111u);         /* 2 + 4 > 4: nothing written */
    UT_TRUE(w.err);
    UT_UEQ(w.pos, 2u);
    fsw_wr_u8(&w, 0x55u);                /* sticky */
    UT_UEQ(w.pos, 2u);
    UT_UEQ(mem[0], 0xEEu);
    UT_UEQ(mem[1], 0xAAu);
    UT_UEQ(mem[2], 0xBBu);
    UT_UEQ(mem[3], 0u);
    UT_UEQ(mem[4], 0u);
    UT_UEQ(mem[5], 0xEEu);
    fsw_wr_init(&w, &mem[1], 4u);
    fsw_wr_i64(&w, -1);
    UT_TRUE(w.err);
    UT_UEQ(mem[1], 0xAAu);
    fsw_wr_init(&w, &mem[1], 4u);
    fsw_wr_i32(&w, -1);
    UT_TRUE(!w.err);
    fsw_wr_u8(&w, 1u);
    UT_TRUE(w.err);
    UT_UEQ(mem[5], 0xEEu);
}

UT_TEST(codec_seek_and_null)
{
    static const uint8_t b[4] = {1u, 2u, 3u, 4u};
    fsw_rd_t r;
    fsw_wr_t w;
    fsw_rd_init(&r, b, 4u);
    fsw_rd_seek(&r, 3u);
    UT_UEQ(fsw_rd_u8(&r), 4u);
    fsw_rd_seek(&r, 4u);                 /* end is a legal position */
    UT_TRUE(!r.err);
    fsw_rd_seek(&r, 5u);
    UT_TRUE(r.err);
    UT_UEQ(r.pos, 4u);
    fsw_rd_init(&r, NULL, 100u);         /* null buffer: empty, every access fails */
    UT_UEQ(r.len, 0u);
    UT_UEQ(fsw_rd_u8(&r), 0u);
    UT_TRUE(r.err);
    fsw_wr_init(&w, NULL, 100u);
    fsw_wr_u8(&w, 1u);
    UT_TRUE(w.err);
    /* Null cursors are ignored rather than dereferenced. */
    fsw_rd_init(NULL, b, 4u);
    fsw_wr_init(NULL, NULL, 4u);
    fsw_rd_seek(NULL, 0u);
    UT_UEQ(fsw_rd_u32(NULL), 0u);
    fsw_wr_u32(NULL, 0u);
}

/* n int32 in a row: the same bytes as n single writes; 9 bytes of room take two values and
   set err on the third, which leaves the cursor and the ninth byte alone. */
UT_TEST(codec_i32_vectors)
{
    static const int32_t v[3] = {-2, INT32_MAX, 0x01020304};
    static const uint8_t want[8] = {0xFEu, 0xFFu, 0xFFu, 0xFFu, 0xFFu, 0xFFu, 0xFFu, 0x7Fu};
    uint8_t b[9];
    int32_t back[3] = {0, 0, 0};
    fsw_wr_t w;
    fsw_rd_t r;
    size_t i;
    for (i = 0u; i < NELEM(b); i++) {
        b[i] = 0xEEu;
    }
    fsw_wr_init(&w, b, (uint32_t)sizeof b);
    fsw_wr_i32n(&w, v, 3u);
    UT_TRUE(w.err);
    UT_UEQ(w.pos, 8u);
    for (i = 0u; i < NELEM(want); i++) {
        UT_CHECK_UEQ(b[i], want[i]);
    }
    UT_UEQ(b[8], 0xEEu);
    fsw_rd_init(&r, b, 8u);
    fsw_rd_i32n(&r, back, 2u);
    UT_TRUE(!r.err);
    UT_EQ(back[0], -2);
    UT_EQ(back[1], INT32_MAX);
    fsw_rd_i32n(&r, back, 1u);
    UT_TRUE(r.err);
}

UT_TEST(crc32_table_check_values)
{
    /* zlib/IEEE check value, and the payload of the test table image used in
       test_fsw_table.c: zlib.crc32(bytes.fromhex("0201c800100000009cffffff40000000e8030000d2040000")). */
    static const uint8_t check[] = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};
    static const uint8_t payload[] = {
        0x02u, 0x01u, 0xC8u, 0x00u, 0x10u, 0x00u, 0x00u, 0x00u, 0x9Cu, 0xFFu, 0xFFu, 0xFFu,
        0x40u, 0x00u, 0x00u, 0x00u, 0xE8u, 0x03u, 0x00u, 0x00u, 0xD2u, 0x04u, 0x00u, 0x00u,
    };
    UT_UEQ(fx_crc32(0u, check, sizeof check), 0xCBF43926u);
    UT_UEQ(fx_crc32(0u, payload, sizeof payload), 0xE488C47Eu);
}

int main(void)
{
    UT_CASES(cases) = {
        UT_CASE(codec_le_byte_layout), UT_CASE(codec_round_trip_edges),
        UT_CASE(codec_round_trip_random), UT_CASE(codec_read_overrun_is_sticky_and_in_bounds),
        UT_CASE(codec_write_overrun_touches_nothing), UT_CASE(codec_seek_and_null),
        UT_CASE(crc32_table_check_values), UT_CASE(codec_i32_vectors),
    };
    return UT_RUN("fsw_codec", cases);
}
