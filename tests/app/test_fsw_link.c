/*
 * test_fsw_link.c — the serial link's framing and decoder (fsw/app/fsw_link.c, spec 00 §6.1), host
 * and target.
 *
 * Golden frames come from an independent oracle, tests/app/gen_link_vectors.py (Python struct,
 * zlib.crc32 and a COBS encoder written from the COBS paper); regenerate with
 *   python3 tests/app/gen_link_vectors.py
 * The decoder is tested on every error kind (each counted exactly once), on resynchronisation
 * after corrupted frames, and on seeded random streams for its invariants: frames + errors equals
 * the non-empty runs, an accepted frame re-encodes to exactly its wire bytes, and a clean frame
 * between delimiters is always accepted whatever came before it.
 */
#include "fsw_link.h"
#include "fx.h"
#include "ut.h"

static const uint8_t V_SENSOR_WITH_ZERO[23] = {
    0x06, 0x01, 0x02, 0x34, 0x12, 0x0B, 0x06, 0x68, 0x65, 0x6C, 0x6C, 0x6F, 0x0A, 0x77, 0x6F, 0x72,
    0x6C, 0x64, 0x12, 0x39, 0x46, 0x8E, 0x00,
};
static const uint8_t V_PING_EMPTY[12] = {
    0x03, 0x01, 0x08, 0x01, 0x01, 0x01, 0x05, 0xC7, 0x39, 0xEE, 0x4A, 0x00,
};
static const uint8_t V_TLM_300_NO_ZERO[313] = {
    0xFF, 0x01, 0x04, 0xFF, 0xFF, 0x2C, 0x01, 0x01, 0x02, 0x03, 0x04, 0x05, 0x06, 0x07, 0x08, 0x09,
    0x0A, 0x0B, 0x0C, 0x0D, 0x0E, 0x0F, 0x10, 0x11, 0x12, 0x13, 0x14, 0x15, 0x16, 0x17, 0x18, 0x19,
    0x1A, 0x1B, 0x1C, 0x1D, 0x1E, 0x1F, 0x20, 0x21, 0x22, 0x23, 0x24, 0x25, 0x26, 0x27, 0x28, 0x29,
    0x2A, 0x2B, 0x2C, 0x2D, 0x2E, 0x2F, 0x30, 0x31, 0x32, 0x33, 0x34, 0x35, 0x36, 0x37, 0x38, 0x39,
    0x3A, 0x3B, 0x3C, 0x3D, 0x3E, 0x3F, 0x40, 0x41, 0x42, 0x43, 0x44, 0x45, 0x46, 0x47, 0x48, 0x49,
    0x4A, 0x4B, 0x4C, 0x4D, 0x4E, 0x4F, 0x50, 0x51, 0x52, 0x53, 0x54, 0x55, 0x56, 0x57, 0x58, 0x59,
    0x5A, 0x5B, 0x5C, 0x5D, 0x5E, 0x5F, 0x60, 0x61, 0x62, 0x63, 0x64, 0x65, 0x66, 0x67, 0x68, 0x69,
    0x6A, 0x6B, 0x6C, 0x6D, 0x6E, 0x6F, 0x70, 0x71, 0x72, 0x73, 0x74, 0x75, 0x76, 0x77, 0x78, 0x79,
    0x7A, 0x7B, 0x7C, 0x7D, 0x7E, 0x7F, 0x80, 0x81, 0x82, 0x83, 0x84, 0x85, 0x86, 0x87, 0x88, 0x89,
    0x8A, 0x8B, 0x8C, 0x8D, 0x8E, 0x8F, 0x90, 0x91, 0x92, 0x93, 0x94, 0x95, 0x96, 0x97, 0x98, 0x99,
    0x9A, 0x9B, 0x9C, 0x9D, 0x9E, 0x9F, 0xA0, 0xA1, 0xA2, 0xA3, 0xA4, 0xA5, 0xA6, 0xA7, 0xA8, 0xA9,
    0xAA, 0xAB, 0xAC, 0xAD, 0xAE, 0xAF, 0xB0, 0xB1, 0xB2, 0xB3, 0xB4, 0xB5, 0xB6, 0xB7, 0xB8, 0xB9,
    0xBA, 0xBB, 0xBC, 0xBD, 0xBE, 0xBF, 0xC0, 0xC1, 0xC2, 0xC3, 0xC4, 0xC5, 0xC6, 0xC7, 0xC8, 0xC9,
    0xCA, 0xCB, 0xCC, 0xCD, 0xCE, 0xCF, 0xD0, 0xD1, 0xD2, 0xD3, 0xD4, 0xD5, 0xD6, 0xD7, 0xD8, 0xD9,
    0xDA, 0xDB, 0xDC, 0xDD, 0xDE, 0xDF, 0xE0, 0xE1, 0xE2, 0xE3, 0xE4, 0xE5, 0xE6, 0xE7, 0xE8, 0xE9,
    0xEA, 0xEB, 0xEC, 0xED, 0xEE, 0xEF, 0xF0, 0xF1, 0xF2, 0xF3, 0xF4, 0xF5, 0xF6, 0xF7, 0xF8, 0x39,
    0xF9, 0xFA, 0xFB, 0xFC, 0xFD, 0xFE, 0xFF, 0x01, 0x02, 0x03, 0x04, 0x05, 0x06, 0x07, 0x08, 0x09,
    0x0A, 0x0B, 0x0C, 0x0D, 0x0E, 0x0F, 0x10, 0x11, 0x12, 0x13, 0x14, 0x15, 0x16, 0x17, 0x18, 0x19,
    0x1A, 0x1B, 0x1C, 0x1D, 0x1E, 0x1F, 0x20, 0x21, 0x22, 0x23, 0x24, 0x25, 0x26, 0x27, 0x28, 0x29,
    0x2A, 0x2B, 0x2C, 0x2D, 0x17, 0x1E, 0x96, 0x1E, 0x00,
};
static const uint8_t V_CMD_FULL_BLOCK_END[263] = {
    0x06, 0x01, 0x03, 0x07, 0x07, 0xFA, 0xFF, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01,
    0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01,
    0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01,
    0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01,
    0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01,
    0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01,
    0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01,
    0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01,
    0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01,
    0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01,
    0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01,
    0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01,
    0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01,
    0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01,
    0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01,
    0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01,
    0x01, 0xB0, 0x1D, 0xB3, 0xFF, 0x01, 0x00,
};

static fsw_link_dec_t s_dec;
static uint8_t s_wire[FSW_LINK_MAX_WIRE];
static uint8_t s_wire2[FSW_LINK_MAX_WIRE];

static bool feed(fsw_link_dec_t *d, const uint8_t *b, uint32_t n, uint32_t *accepted)
{
    uint32_t i;
    bool last = false;
    for (i = 0u; i < n; i++) {
        last = fsw_link_rx_byte(d, b[i]);
        if (last) {
            (*accepted)++;
        }
    }
    return last;
}

static uint32_t errors(const fsw_link_stats_t *s)
{
    return s->err_oversize + s->err_cobs + s->err_short + s->err_len + s->err_crc + s->err_version + s->err_type;
}

static bool same(const uint8_t *a, const uint8_t *b, uint32_t n)
{
    uint32_t i;
    bool eq = true;
    for (i = 0u; i < n; i++) {
        eq = eq && (a[i] == b[i]);
    }
    return eq;
}

UT_TEST(encode_matches_the_independent_oracle)
{
    static const uint8_t hello[11] = {'h', 'e', 'l', 'l', 'o', 0u, 'w', 'o', 'r', 'l', 'd'};
    static uint8_t p300[300];
    static uint8_t p250[250];
    uint32_t i;
    uint32_t n;
    for (i = 0u; i < 300u; i++) {
        p300[i] = (uint8_t)((i % 255u) + 1u);
    }
    for (i = 0u; i < 250u; i++) {
        p250[i] = 1u;
    }
    n = fsw_link_encode(FSW_LINK_T_SENSOR, 0x1234u, hello, 11u, s_wire, FSW_LINK_MAX_WIRE);
    UT_UEQ(n, sizeof V_SENSOR_WITH_ZERO);
    UT_TRUE(same(s_wire, V_SENSOR_WITH_ZERO, n));
    n = fsw_link_encode(FSW_LINK_T_PING, 0u, NULL, 0u, s_wire, FSW_LINK_MAX_WIRE);
    UT_UEQ(n, sizeof V_PING_EMPTY);
    UT_TRUE(same(s_wire, V_PING_EMPTY, n));
    n = fsw_link_encode(FSW_LINK_T_TLM, 0xFFFFu, p300, 300u, s_wire, FSW_LINK_MAX_WIRE);
    UT_UEQ(n, sizeof V_TLM_300_NO_ZERO);
    UT_TRUE(same(s_wire, V_TLM_300_NO_ZERO, n));
    n = fsw_link_encode(FSW_LINK_T_CMD, 0x0707u, p250, 250u, s_wire, FSW_LINK_MAX_WIRE);
    UT_UEQ(n, sizeof V_CMD_FULL_BLOCK_END);
    UT_TRUE(same(s_wire, V_CMD_FULL_BLOCK_END, n));
}

UT_TEST(oracle_frames_decode)
{
    uint32_t acc = 0u;
    fsw_link_dec_init(&s_dec);
    UT_TRUE(feed(&s_dec, V_SENSOR_WITH_ZERO, sizeof V_SENSOR_WITH_ZERO, &acc));
    UT_UEQ(s_dec.frame.type, FSW_LINK_T_SENSOR);
    UT_UEQ(s_dec.frame.seq, 0x1234u);
    UT_UEQ(s_dec.frame.len, 11u);
    UT_UEQ(s_dec.frame.payload[5], 0u);
    UT_UEQ(s_dec.frame.payload[10], (uint8_t)'d');
    UT_TRUE(feed(&s_dec, V_CMD_FULL_BLOCK_END, sizeof V_CMD_FULL_BLOCK_END, &acc));
    UT_UEQ(s_dec.frame.len, 250u);
    UT_TRUE(feed(&s_dec, V_TLM_300_NO_ZERO, sizeof V_TLM_300_NO_ZERO, &acc));
    UT_UEQ(s_dec.frame.payload[299], (uint8_t)((299u % 255u) + 1u));
    UT_TRUE(feed(&s_dec, V_PING_EMPTY, sizeof V_PING_EMPTY, &acc));
    UT_UEQ(s_dec.frame.len, 0u);
    UT_UEQ(acc, 4u);
    UT_UEQ(s_dec.st.frames, 4u);
    UT_UEQ(errors(&s_dec.st), 0u);
}

/* A test-local COBS encoder (the paper's algorithm, as in gen_link_vectors.py) for hand-made bodies. */
static uint32_t cobs_wrap(const uint8_t *body, uint32_t n, uint8_t *out)
{
    uint32_t code_at = 0u;
    uint32_t o = 1u;
    uint32_t i;
    uint8_t code = 1u;
    for (i = 0u; i < n; i++) {
        if (body[i] == 0u) {
            out[code_at] = code;
            code_at = o++;
            code = 1u;
        } else {
            out[o++] = body[i];
            code++;
            if (code == 0xFFu) {
                out[code_at] = code;
                code_at = o++;
                code = 1u;
            }
        }
    }
    out[code_at] = code;
    out[o++] = 0u;
    return o;
}

/* A body with a correct CRC over its first n - 4 bytes. */
static uint32_t body_with_crc(uint8_t ver, uint8_t type, uint16_t len_field, uint32_t plen, uint8_t *b)
{
    uint32_t i;
    uint32_t c;
    b[0] = ver;
    b[1] = type;
    b[2] = 0x34u;
    b[3] = 0x12u;
    b[4] = (uint8_t)(len_field & 0xFFu);
    b[5] = (uint8_t)(len_field >> 8);
    for (i = 0u; i < plen; i++) {
        b[6u + i] = (uint8_t)(i + 1u);
    }
    c = fx_crc32(0u, b, (size_t)6u + plen);
    b[6u + plen] = (uint8_t)(c & 0xFFu);
    b[7u + plen] = (uint8_t)((c >> 8) & 0xFFu);
    b[8u + plen] = (uint8_t)((c >> 16) & 0xFFu);
    b[9u + plen] = (uint8_t)(c >> 24);
    return 10u + plen;
}

UT_TEST(every_error_kind_is_counted_once_and_the_next_frame_is_accepted)
{
    static uint8_t body[FSW_LINK_MAX_WIRE];
    static uint8_t w[FSW_LINK_MAX_WIRE + 8u];
    static const uint8_t bad_code[4] = {0x05u, 1u, 2u, 0u};            /* points past the run */
    static const uint8_t ends_full[3] = {0xFFu, 1u, 0u};               /* truncated full block */
    static const uint8_t too_short[7] = {0x06u, 1u, 2u, 3u, 4u, 5u, 0u};   /* 5-byte body */
    static const uint8_t empty[2] = {0u, 0u};
    uint32_t acc = 0u;
    uint32_t i;
    uint32_t n;
    fsw_link_dec_init(&s_dec);
    (void)feed(&s_dec, empty, 2u, &acc);
    UT_UEQ(s_dec.st.empty, 2u);
    for (i = 0u; i < (FSW_LINK_MAX_COBS + 10u); i++) {
        (void)fsw_link_rx_byte(&s_dec, 0x33u);
    }
    (void)fsw_link_rx_byte(&s_dec, 0u);
    UT_UEQ(s_dec.st.err_oversize, 1u);
    (void)feed(&s_dec, bad_code, sizeof bad_code, &acc);
    UT_UEQ(s_dec.st.err_cobs, 1u);
    (void)feed(&s_dec, ends_full, sizeof ends_full, &acc);
    UT_UEQ(s_dec.st.err_cobs, 2u);
    (void)feed(&s_dec, too_short, sizeof too_short, &acc);
    UT_UEQ(s_dec.st.err_short, 1u);
    n = cobs_wrap(body, body_with_crc(1u, FSW_LINK_T_PING, 5u, 4u, body), w);      /* len 5, 4 sent */
    (void)feed(&s_dec, w, n, &acc);
    UT_UEQ(s_dec.st.err_len, 1u);
    n = cobs_wrap(body, body_with_crc(1u, FSW_LINK_T_PING, 4u, 4u, body), w);
    w[3] ^= 0x10u;                                                              /* payload bit flip */
    (void)feed(&s_dec, w, n, &acc);
    UT_UEQ(s_dec.st.err_crc, 1u);
    n = cobs_wrap(body, body_with_crc(2u, FSW_LINK_T_PING, 4u, 4u, body), w);
    (void)feed(&s_dec, w, n, &acc);
    UT_UEQ(s_dec.st.err_version, 1u);
    n = cobs_wrap(body, body_with_crc(1u, 0u, 4u, 4u, body), w);
    (void)feed(&s_dec, w, n, &acc);
    n = cobs_wrap(body, body_with_crc(1u, FSW_LINK_T_MAX + 1u, 4u, 4u, body), w);
    (void)feed(&s_dec, w, n, &acc);
    UT_UEQ(s_dec.st.err_type, 2u);
    UT_UEQ(acc, 0u);
    UT_UEQ(errors(&s_dec.st), 9u);
    /* The decoder never stopped: the next good frame is accepted. */
    n = cobs_wrap(body, body_with_crc(1u, FSW_LINK_T_PONG, 4u, 4u, body), w);
    UT_TRUE(feed(&s_dec, w, n, &acc));
    UT_UEQ(s_dec.frame.type, FSW_LINK_T_PONG);
    UT_UEQ(s_dec.frame.seq, 0x1234u);
    UT_UEQ(s_dec.st.frames, 1u);
}

UT_TEST(encode_refuses_what_it_cannot_frame)
{
    static uint8_t p[FSW_LINK_MAX_PAYLOAD + 1u];
    uint32_t i;
    uint32_t n;
    uint32_t acc = 0u;
    for (i = 0u; i < (FSW_LINK_MAX_PAYLOAD + 1u); i++) {
        p[i] = 0xFFu;
    }
    UT_UEQ(fsw_link_encode(FSW_LINK_T_TLM, 1u, p, FSW_LINK_MAX_PAYLOAD + 1u, s_wire, FSW_LINK_MAX_WIRE), 0u);
    UT_UEQ(fsw_link_encode(FSW_LINK_T_TLM, 1u, NULL, 3u, s_wire, FSW_LINK_MAX_WIRE), 0u);
    UT_UEQ(fsw_link_encode(FSW_LINK_T_TLM, 1u, p, 10u, s_wire, 21u), 0u);     /* needs 22 */
    UT_UEQ(fsw_link_encode(FSW_LINK_T_TLM, 1u, p, 10u, s_wire, 22u), 22u);
    /* The largest frame fits FSW_LINK_MAX_WIRE and decodes. */
    n = fsw_link_encode(FSW_LINK_T_TLM, 1u, p, FSW_LINK_MAX_PAYLOAD, s_wire, FSW_LINK_MAX_WIRE);
    UT_TRUE((n > 0u) && (n <= FSW_LINK_MAX_WIRE));
    fsw_link_dec_init(&s_dec);
    UT_TRUE(feed(&s_dec, s_wire, n, &acc));
    UT_UEQ(s_dec.frame.len, FSW_LINK_MAX_PAYLOAD);
}

UT_TEST(seq_serial_number_arithmetic)
{
    UT_EQ(fsw_link_seq_diff(1u, 0u), 1);
    UT_EQ(fsw_link_seq_diff(0u, 1u), -1);
    UT_EQ(fsw_link_seq_diff(0u, 0xFFFFu), 1);
    UT_EQ(fsw_link_seq_diff(0xFFFFu, 0u), -1);
    UT_EQ(fsw_link_seq_diff(0x7FFFu, 0u), 32767);
    UT_EQ(fsw_link_seq_diff(0x8000u, 0u), -32768);
    UT_EQ(fsw_link_seq_diff(5u, 5u), 0);
}

/* Seeded streams: clean frames of random type/seq/length/content, copies with random bit flips or
   truncations, and runs of random bytes, in random order. Invariants checked on every byte. */
UT_TEST(random_streams_keep_the_invariants)
{
    static uint8_t pay[FSW_LINK_MAX_PAYLOAD];
    static uint8_t run[FSW_LINK_MAX_WIRE * 2u];   /* the bytes of the current run, as received */
    uint64_t seed = 20261205u;
    uint32_t runs = 0u;
    uint32_t rn = 0u;
    uint32_t clean_sent = 0u;
    uint32_t clean_ok = 0u;
    uint32_t reenc_ok = 0u;
    uint32_t accepted = 0u;
    uint32_t it;
    fsw_link_dec_init(&s_dec);
    for (it = 0u; it < 3000u; it++) {
        uint64_t r = ut_rng_next(&seed);
        uint32_t kind = (uint32_t)(r % 4u);
        uint32_t len = (uint32_t)((r >> 8) % (FSW_LINK_MAX_PAYLOAD + 1u));
        uint32_t n;
        uint32_t i;
        bool clean = false;
        if ((r >> 40) % 3u == 0u) {
            len = len % 24u;                          /* many short frames too */
        }
        for (i = 0u; i < len; i++) {
            pay[i] = (uint8_t)(ut_rng_next(&seed) >> 56);
        }
        n = fsw_link_encode((uint8_t)(1u + ((r >> 20) % FSW_LINK_T_MAX)), (uint16_t)(r >> 24), pay, len, s_wire,
                            FSW_LINK_MAX_WIRE);
        UT_TRUE(n > 0u);
        if (kind == 1u) {                             /* bit flips, anywhere but in the delimiter */
            uint32_t f = 1u + (uint32_t)((r >> 44) % 3u);
            for (i = 0u; i < f; i++) {
                uint64_t q = ut_rng_next(&seed);
                s_wire[(uint32_t)(q % (n - 1u))] ^= (uint8_t)(1u << (uint32_t)((q >> 32) % 8u));
            }
        } else if (kind == 2u) {                      /* truncated: the rest of it never arrives */
            n = 1u + (uint32_t)((r >> 44) % (n - 1u));
            s_wire[n - 1u] = 0u;
        } else if (kind == 3u) {                      /* noise */
            n = 1u + (uint32_t)((r >> 44) % 64u);
            for (i = 0u; i < n; i++) {
                s_wire[i] = (uint8_t)(ut_rng_next(&seed) >> 56);
            }
        } else {
            clean = (rn == 0u);                       /* clean, and starting a run */
        }
        clean_sent += clean ? 1u : 0u;
        for (i = 0u; i < n; i++) {
            uint8_t b = s_wire[i];
            bool ok = fsw_link_rx_byte(&s_dec, b);
            if (b == 0u) {
                if (rn > 0u) {
                    runs++;
                }
                if (ok) {
                    uint32_t m = fsw_link_encode(s_dec.frame.type, s_dec.frame.seq, s_dec.frame.payload,
                                                 s_dec.frame.len, s_wire2, FSW_LINK_MAX_WIRE);
                    accepted++;
                    if ((m == (rn + 1u)) && same(s_wire2, run, rn)) {
                        reenc_ok++;
                    }
                    if (clean && (i == (n - 1u))) {
                        clean_ok++;
                    }
                }
                rn = 0u;
            } else {
                UT_CHECK(!ok);
                if (rn < sizeof run) {
                    run[rn] = b;
                }
                rn++;
            }
        }
        UT_CHECK_UEQ(s_dec.st.frames + errors(&s_dec.st), runs);
    }
    ut_puts("link streams: ");
    ut_put_u64(runs);
    ut_puts(" runs, ");
    ut_put_u64(accepted);
    ut_puts(" accepted, every one re-encoded identically: ");
    ut_put_u64(reenc_ok);
    ut_puts("; clean frames accepted ");
    ut_put_u64(clean_ok);
    ut_puts(" of ");
    ut_put_u64(clean_sent);
    ut_puts("\n");
    UT_UEQ(reenc_ok, accepted);
    UT_UEQ(clean_ok, clean_sent);
    UT_TRUE(clean_sent > 500u);
    UT_TRUE(errors(&s_dec.st) > 1000u);
}

int main(void)
{
    UT_CASES(cases) = {
        UT_CASE(encode_matches_the_independent_oracle), UT_CASE(oracle_frames_decode),
        UT_CASE(every_error_kind_is_counted_once_and_the_next_frame_is_accepted),
        UT_CASE(encode_refuses_what_it_cannot_frame), UT_CASE(seq_serial_number_arithmetic),
        UT_CASE(random_streams_keep_the_invariants),
    };
    return UT_RUN("fsw_link", cases);
}
