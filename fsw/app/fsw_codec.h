/*
 * fsw_codec.h — little-endian, field-by-field codec over a caller buffer (spec 00 §3.2).
 *
 * Tables and messages are encoded one field at a time; structs are never copied as bytes, so
 * padding and host endianness never reach an image. A cursor carries the buffer, its length,
 * the position and a sticky error flag:
 *  - an access that would cross the end sets `err`, returns 0 (reads) or writes nothing
 *    (writes), and leaves `pos` unchanged; it never touches memory outside [buf, buf + len);
 *  - once `err` is set every later access fails the same way, so a decoder may read a whole
 *    record and test the flag once at the end.
 * Signed values are two's complement on the wire; decoding maps them back without relying on
 * an implementation-defined unsigned-to-signed conversion.
 */
#ifndef FSW_APP_CODEC_H
#define FSW_APP_CODEC_H

#include <stdint.h>
#include <stdbool.h>
#include <stddef.h>

typedef struct {
    const uint8_t *buf;   /* bytes to decode (not owned) */
    uint32_t len;         /* bytes available at buf */
    uint32_t pos;         /* next byte to read */
    bool err;             /* sticky: an access crossed the end */
} fsw_rd_t;

typedef struct {
    uint8_t *buf;         /* destination (not owned) */
    uint32_t len;         /* capacity of buf */
    uint32_t pos;         /* next byte to write = bytes written so far */
    bool err;             /* sticky: a write would have crossed the end */
} fsw_wr_t;

/* A null buf is treated as an empty buffer (len 0): every access then fails cleanly. */
void     fsw_rd_init(fsw_rd_t *r, const uint8_t *buf, uint32_t len);
void     fsw_wr_init(fsw_wr_t *w, uint8_t *buf, uint32_t len);
/* Moves to absolute position pos (pos == len allowed); beyond len sets err, pos unchanged. */
void     fsw_rd_seek(fsw_rd_t *r, uint32_t pos);

uint8_t  fsw_rd_u8(fsw_rd_t *r);
uint16_t fsw_rd_u16(fsw_rd_t *r);
uint32_t fsw_rd_u32(fsw_rd_t *r);
int32_t  fsw_rd_i32(fsw_rd_t *r);
int64_t  fsw_rd_i64(fsw_rd_t *r);

void     fsw_wr_u8(fsw_wr_t *w, uint8_t v);
void     fsw_wr_u16(fsw_wr_t *w, uint16_t v);
void     fsw_wr_u32(fsw_wr_t *w, uint32_t v);
void     fsw_wr_i32(fsw_wr_t *w, int32_t v);
/* n int32 values in a row (the tables' vectors and matrices); an overrun sets err as for one. */
void     fsw_wr_i32n(fsw_wr_t *w, const int32_t *v, uint32_t n);
void     fsw_rd_i32n(fsw_rd_t *r, int32_t *v, uint32_t n);
void     fsw_wr_i64(fsw_wr_t *w, int64_t v);

#endif /* FSW_APP_CODEC_H */
