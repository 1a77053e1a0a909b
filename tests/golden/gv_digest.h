/*
 * gv_digest.h — CRC-32 digests of golden-vector replays (spec 00 §6.4), the pattern of
 * tests/golden/fx_digest.c: every record is serialised word by word, little-endian (never as
 * raw struct bytes, whose padding is indeterminate), into fx_crc32. A replay prints
 *     digest <set> <records> <crc>
 * per set; tests/golden/digest.cmake saves the host's lines and makes each Cortex-M build
 * reproduce them bit for bit.
 *
 * Mission-agnostic: each module's record header (tests/<module>/gv_<prefix>.h) builds on these
 * helpers, among other things for the fingerprint of the flight table its vectors were made for.
 * C99; the host generators include it inside extern "C".
 */
#ifndef TESTS_GOLDEN_GV_DIGEST_H
#define TESTS_GOLDEN_GV_DIGEST_H

#include <stdint.h>
#include <stddef.h>
#include "fx.h"

typedef struct {
    uint32_t crc;
    uint32_t n;     /* records */
} gv_dg_t;

static inline void gv_dg_begin(gv_dg_t *d)
{
    d->crc = 0u;
    d->n = 0u;
}

static inline void gv_dg_u32(gv_dg_t *d, uint32_t v)
{
    uint8_t b[4];
    b[0] = (uint8_t)(v & 0xFFu);
    b[1] = (uint8_t)((v >> 8) & 0xFFu);
    b[2] = (uint8_t)((v >> 16) & 0xFFu);
    b[3] = (uint8_t)((v >> 24) & 0xFFu);
    d->crc = fx_crc32(d->crc, b, 4u);
}

static inline void gv_dg_i32(gv_dg_t *d, int32_t v) { gv_dg_u32(d, (uint32_t)v); }

static inline void gv_dg_i32n(gv_dg_t *d, const int32_t *v, uint32_t n)
{
    uint32_t i;
    for (i = 0u; i < n; i++) {
        gv_dg_i32(d, v[i]);
    }
}

/* A const record made only of 32-bit members (the gv_*_t layouts), as words. */
static inline void gv_dg_words(gv_dg_t *d, const void *rec, size_t bytes)
{
    const uint32_t *w = (const uint32_t *)rec;
    size_t i;
    for (i = 0u; i < (bytes / 4u); i++) {
        gv_dg_u32(d, w[i]);
    }
}

#endif /* TESTS_GOLDEN_GV_DIGEST_H */
