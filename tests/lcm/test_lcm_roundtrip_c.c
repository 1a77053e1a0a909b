/*
 * test_lcm_roundtrip_c.c — generated C bindings of every gnc LCM type (spec 00 §5.1):
 * encode into caller-owned static buffers and decode back (never _publish or _copy, which
 * allocate), pinned encoded sizes and fingerprints (the never-reorder rule), bounds checks.
 */
#include <stdint.h>
#include <string.h>

#include "lcm_types.h"
#include "ut.h"

static uint8_t buf_[PAT_SIZE_MAX + 16];
static lcm_any_t ref_, got_;
static uint8_t buf2_[PAT_SIZE_MAX + 16];

/* fill -> encode -> decode (into a zeroed object) -> identical bytes, including padding. */
UT_TEST(roundtrip_every_type)
{
    size_t i;
    for (i = 0; i < LCM_N_TYPES; ++i) {
        const lcm_type_ops_t *t = &lcm_types[i];
        int n;
        lcm_types[i].fill(&ref_);
        UT_EQ(t->size_of(&ref_), t->encoded_len);
        memset(buf_, 0xEE, sizeof buf_);
        n = t->enc(buf_, 0, (int)sizeof buf_, &ref_);
        UT_EQ(n, t->encoded_len);
        UT_EQ(buf_[n], 0xEE);                       /* nothing written past the message */
        memset(&got_, 0, sizeof got_);
        UT_EQ(t->dec(buf_, 0, n, &got_), n);
        UT_EQ(memcmp(&ref_, &got_, t->size), 0);
    }
}

/* Decode into a dirty object: every field is written (re-encoding gives the same bytes). */
UT_TEST(decode_overwrites_every_field)
{
    size_t i;
    for (i = 0; i < LCM_N_TYPES; ++i) {
        const lcm_type_ops_t *t = &lcm_types[i];
        int n;
        t->fill(&ref_);
        n = t->enc(buf_, 0, (int)sizeof buf_, &ref_);
        UT_EQ(n, t->encoded_len);
        memset(&got_, 0xA5, sizeof got_);
        UT_EQ(t->dec(buf_, 0, n, &got_), n);
        UT_EQ(t->enc(buf2_, 0, (int)sizeof buf2_, &got_), n);
        UT_EQ(memcmp(buf_, buf2_, (size_t)n), 0);
    }
}

/* Encoding at an offset inside a larger buffer, as a bridge packing several messages would. */
UT_TEST(roundtrip_at_offset)
{
    size_t i;
    for (i = 0; i < LCM_N_TYPES; ++i) {
        const lcm_type_ops_t *t = &lcm_types[i];
        int n;
        t->fill(&ref_);
        n = t->enc(buf_, 5, t->encoded_len + 5, &ref_);   /* maxlen counts from buf, LCM style */
        UT_EQ(n, t->encoded_len);
        memset(&got_, 0, sizeof got_);
        UT_EQ(t->dec(buf_, 5, n + 5, &got_), n);
        UT_EQ(memcmp(&ref_, &got_, t->size), 0);
    }
}

/* One byte short: encode and decode both refuse, and neither writes past maxlen. */
UT_TEST(short_buffers_are_refused)
{
    size_t i;
    for (i = 0; i < LCM_N_TYPES; ++i) {
        const lcm_type_ops_t *t = &lcm_types[i];
        int n = t->encoded_len;
        t->fill(&ref_);
        memset(buf_, 0xEE, sizeof buf_);
        UT_TRUE(t->enc(buf_, 0, n - 1, &ref_) < 0);
        UT_EQ(buf_[n - 1], 0xEE);
        UT_EQ(t->enc(buf_, 0, n, &ref_), n);
        memset(&got_, 0, sizeof got_);
        UT_TRUE(t->dec(buf_, 0, n - 1, &got_) < 0);
        UT_TRUE(t->dec(buf_, 0, 7, &got_) < 0);
    }
}

/* A message of another type (or a corrupted fingerprint) is refused, never misread. */
UT_TEST(wrong_fingerprint_is_refused)
{
    size_t i, j;
    for (i = 0; i < LCM_N_TYPES; ++i) {
        const lcm_type_ops_t *t = &lcm_types[i];
        int n;
        t->fill(&ref_);
        n = t->enc(buf_, 0, (int)sizeof buf_, &ref_);
        UT_EQ(n, t->encoded_len);
        buf_[3] ^= 0x10u;
        UT_TRUE(t->dec(buf_, 0, n, &got_) < 0);
        buf_[3] ^= 0x10u;
        for (j = 0; j < LCM_N_TYPES; ++j) {
            if (j != i) {
                UT_TRUE(lcm_types[j].dec(buf_, 0, n, &got_) < 0);
            }
        }
    }
}

/* The never-reorder rule, enforced: sizes and fingerprints are pinned (see lcm_types.h). */
UT_TEST(layout_is_pinned)
{
    size_t i, j;
    for (i = 0; i < LCM_N_TYPES; ++i) {
        const lcm_type_ops_t *t = &lcm_types[i];
        t->fill(&ref_);
        UT_EQ(t->enc(buf_, 0, (int)sizeof buf_, &ref_), t->encoded_len);
        UT_CHECK_UEQ(lcm_be64(buf_), t->fingerprint);
        for (j = 0; j < i; ++j) {
            UT_CHECK(lcm_types[j].fingerprint != t->fingerprint);
        }
    }
}

/* Constants from the .lcm files reach the C header. */
UT_TEST(constants_are_generated)
{
    UT_EQ(GNC_SENSOR_FRAME_T_STATUS_STALE, 1);
    UT_EQ(GNC_SENSOR_FRAME_T_STATUS_SAT, 2);
    UT_EQ(GNC_TABLE_ACK_T_RESULT_REJECTED, 2);
    UT_EQ(GNC_SIL_CTL_T_CMD_START, 1);
    UT_EQ(GNC_SIL_CTL_T_CMD_SUMMARY, 5);
    UT_EQ(GNC_SIL_CTL_T_NODE_BRIDGE, 2);
}

int main(void)
{
    UT_CASES(cases) = {
        UT_CASE(roundtrip_every_type),
        UT_CASE(decode_overwrites_every_field),
        UT_CASE(roundtrip_at_offset),
        UT_CASE(short_buffers_are_refused),
        UT_CASE(wrong_fingerprint_is_refused),
        UT_CASE(layout_is_pinned),
        UT_CASE(constants_are_generated),
    };
    return UT_RUN("lcm_roundtrip_c", cases);
}
