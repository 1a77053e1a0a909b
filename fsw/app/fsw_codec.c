/*
 * fsw_codec.c — little-endian field codec with a bounds-checked cursor (see fsw_codec.h).
 *
 * All multi-byte accesses go through two helpers that move up to 8 bytes as a uint64_t, so
 * the bounds test exists exactly once per direction. Single exit throughout (MISRA 15.5 is
 * deviated only inside fsw/fx).
 */
#include "fsw_codec.h"

/* Width of the widest field in bytes; the helpers below never move more. */
#define CODEC_MAX_BYTES 8u

void fsw_rd_init(fsw_rd_t *r, const uint8_t *buf, uint32_t len)
{
    if (r != NULL) {
        r->buf = buf;
        r->len = (buf != NULL) ? len : 0u;
        r->pos = 0u;
        r->err = false;
    }
}

void fsw_wr_init(fsw_wr_t *w, uint8_t *buf, uint32_t len)
{
    if (w != NULL) {
        w->buf = buf;
        w->len = (buf != NULL) ? len : 0u;
        w->pos = 0u;
        w->err = false;
    }
}

void fsw_rd_seek(fsw_rd_t *r, uint32_t pos)
{
    if (r != NULL) {
        if (pos <= r->len) {
            r->pos = pos;
        } else {
            r->err = true;
        }
    }
}

/* True when n more bytes fit between pos and len; written so that pos + n cannot wrap. */
static bool codec_fits(uint32_t len, uint32_t pos, uint32_t n)
{
    return (pos <= len) && (n <= (len - pos));
}

/* Reads n (1..8) bytes little-endian; 0 and err on overrun or a previous error. */
static uint64_t codec_get(fsw_rd_t *r, uint32_t n)
{
    uint64_t v = 0u;
    if (r != NULL) {
        if ((!r->err) && (r->buf != NULL) && codec_fits(r->len, r->pos, n)) {
            uint32_t i;
            for (i = 0u; (i < n) && (i < CODEC_MAX_BYTES); i++) {
                v |= ((uint64_t)r->buf[r->pos + i]) << (8u * i);
            }
            r->pos += n;
        } else {
            r->err = true;
        }
    }
    return v;
}

/* Writes the low n (1..8) bytes of v little-endian; nothing and err on overrun. */
static void codec_put(fsw_wr_t *w, uint64_t v, uint32_t n)
{
    if (w != NULL) {
        if ((!w->err) && (w->buf != NULL) && codec_fits(w->len, w->pos, n)) {
            uint32_t i;
            for (i = 0u; (i < n) && (i < CODEC_MAX_BYTES); i++) {
                w->buf[w->pos + i] = (uint8_t)((v >> (8u * i)) & 0xFFu);
            }
            w->pos += n;
        } else {
            w->err = true;
        }
    }
}

uint8_t fsw_rd_u8(fsw_rd_t *r)
{
    return (uint8_t)codec_get(r, 1u);
}

uint16_t fsw_rd_u16(fsw_rd_t *r)
{
    return (uint16_t)codec_get(r, 2u);
}

uint32_t fsw_rd_u32(fsw_rd_t *r)
{
    return (uint32_t)codec_get(r, 4u);
}

int32_t fsw_rd_i32(fsw_rd_t *r)
{
    /* Two's complement back to int32 without an out-of-range conversion: for u >= 2^31 the
       value is -(~u) - 1, and ~u lies in [0, INT32_MAX]. */
    uint32_t u = (uint32_t)codec_get(r, 4u);
    int32_t v;
    if (u <= (uint32_t)INT32_MAX) {
        v = (int32_t)u;
    } else {
        uint32_t m = ~u;
        v = -(int32_t)m - 1;
    }
    return v;
}

int64_t fsw_rd_i64(fsw_rd_t *r)
{
    uint64_t u = codec_get(r, 8u);
    int64_t v;
    if (u <= (uint64_t)INT64_MAX) {
        v = (int64_t)u;
    } else {
        uint64_t m = ~u;
        v = -(int64_t)m - 1;
    }
    return v;
}

void fsw_wr_u8(fsw_wr_t *w, uint8_t v)
{
    codec_put(w, (uint64_t)v, 1u);
}

void fsw_wr_u16(fsw_wr_t *w, uint16_t v)
{
    codec_put(w, (uint64_t)v, 2u);
}

void fsw_wr_u32(fsw_wr_t *w, uint32_t v)
{
    codec_put(w, (uint64_t)v, 4u);
}

void fsw_wr_i32(fsw_wr_t *w, int32_t v)
{
    /* Conversion of a negative value to unsigned is defined (modulo 2^32): two's complement. */
    codec_put(w, (uint64_t)(uint32_t)v, 4u);
}

void fsw_wr_i32n(fsw_wr_t *w, const int32_t *v, uint32_t n)
{
    uint32_t i;
    for (i = 0u; i < n; i++) {
        fsw_wr_i32(w, v[i]);
    }
}

void fsw_rd_i32n(fsw_rd_t *r, int32_t *v, uint32_t n)
{
    uint32_t i;
    for (i = 0u; i < n; i++) {
        v[i] = fsw_rd_i32(r);
    }
}

void fsw_wr_i64(fsw_wr_t *w, int64_t v)
{
    codec_put(w, (uint64_t)v, 8u);
}
