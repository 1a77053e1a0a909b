/*
 * fsw_link.h — the serial link's framing (spec 00 §6.1), one source for the host and the board.
 *
 * A frame on the wire is COBS(body) followed by a 0x00 delimiter. The body is little-endian:
 *   0  u8   proto_version (FSW_LINK_VERSION)
 *   1  u8   type (FSW_LINK_T_*)
 *   2  u16  seq (serial-number arithmetic: fsw_link_seq_diff)
 *   4  u16  len <= FSW_LINK_MAX_PAYLOAD
 *   6  len  payload
 *   6+len u32 CRC-32 (fx_crc32) over bytes 0 .. 5+len
 * The decoder takes one byte at a time into fixed buffers and resynchronises at every delimiter,
 * so a corrupted frame loses only itself; no length field is trusted to find a frame's end. Every
 * non-empty delimiter-terminated run of bytes is counted exactly once: as a frame or as one kind of
 * error. Only the encoder's canonical COBS form is accepted, so an accepted frame re-encodes to
 * exactly the bytes it arrived as.
 */
#ifndef FSW_APP_LINK_H
#define FSW_APP_LINK_H

#include <stdint.h>
#include <stdbool.h>

#define FSW_LINK_VERSION      1u
#define FSW_LINK_MAX_PAYLOAD  512u
#define FSW_LINK_HDR          6u
#define FSW_LINK_CRC          4u
#define FSW_LINK_MIN_BODY     (FSW_LINK_HDR + FSW_LINK_CRC)
#define FSW_LINK_MAX_BODY     (FSW_LINK_HDR + FSW_LINK_MAX_PAYLOAD + FSW_LINK_CRC)      /* 522 */
/* COBS: one code byte per started block of up to 254 body bytes, and one more when the body ends
   exactly on a full block (the encoder always closes with a final block). */
#define FSW_LINK_MAX_COBS     (FSW_LINK_MAX_BODY + (FSW_LINK_MAX_BODY / 254u) + 1u)     /* 525 */
#define FSW_LINK_MAX_WIRE     (FSW_LINK_MAX_COBS + 1u)                                   /* + delimiter */

/* Packet types (spec 00 §6.1). 0 is never a type, so a frame of zeros is refused. */
#define FSW_LINK_T_HELLO        1u   /* board -> host: version, layout hash, build id, board id */
#define FSW_LINK_T_SENSOR       2u   /* host -> board: fsw_in_t, seq = k */
#define FSW_LINK_T_CMD          3u   /* board -> host: the actuator part of fsw_out_t */
#define FSW_LINK_T_TLM          4u   /* board -> host: fsw_tlm_t (+ instruction count) */
#define FSW_LINK_T_TABLE_CHUNK  5u
#define FSW_LINK_T_TABLE_ACK    6u
#define FSW_LINK_T_MODE_CMD     7u
#define FSW_LINK_T_PING         8u
#define FSW_LINK_T_PONG         9u
#define FSW_LINK_T_LINK_STATS  10u
#define FSW_LINK_T_ERROR       11u
/* The PIL session's own (fsw_pil.h): the board boots from host-sent configuration and image, and
   reports its channel ranges, so one board image serves every registered mission. */
#define FSW_LINK_T_BOOT        12u   /* host -> board: fsw_cfg_t + the staged boot image's length, CRC */
#define FSW_LINK_T_BOOT_ACK    13u   /* board -> host: fsw_init's verdict + channel ranges */
#define FSW_LINK_T_LIMITS      14u   /* board -> host: channel ranges after a table commit */
#define FSW_LINK_T_MAX         14u

/* Receive counters. Every delimiter ends one run of bytes; an empty run (back-to-back delimiters,
   e.g. a sender's leading sync byte) is `empty`; any other run is counted in exactly one of
   frames .. err_type, so frames + errors == non-empty runs (checked by the tests). */
typedef struct {
    uint32_t bytes;          /* bytes fed to the decoder */
    uint32_t empty;          /* empty runs: not errors */
    uint32_t frames;         /* accepted */
    uint32_t err_oversize;   /* more than FSW_LINK_MAX_COBS bytes before the delimiter */
    uint32_t err_cobs;       /* a code byte pointing past the run, or a non-canonical end */
    uint32_t err_short;      /* body shorter than header + CRC */
    uint32_t err_len;        /* len field disagrees with the body's size (or exceeds the maximum) */
    uint32_t err_crc;
    uint32_t err_version;
    uint32_t err_type;       /* 0 or above FSW_LINK_T_MAX */
} fsw_link_stats_t;

/* An accepted frame: payload points into the decoder's body buffer, valid until the next byte. */
typedef struct {
    uint8_t type;
    uint16_t seq;
    uint16_t len;
    const uint8_t *payload;
} fsw_link_frame_t;

typedef struct {
    uint8_t raw[FSW_LINK_MAX_COBS];    /* COBS bytes of the run being received */
    uint32_t n;                        /* bytes in raw */
    bool overflow;                     /* this run outgrew raw: dropped at its delimiter */
    uint8_t body[FSW_LINK_MAX_COBS];   /* the last run, decoded (a hostile run decodes to up to n - 1 bytes) */
    fsw_link_frame_t frame;            /* the last accepted frame */
    fsw_link_stats_t st;
} fsw_link_dec_t;

void fsw_link_dec_init(fsw_link_dec_t *d);

/* One received byte. True when it was the delimiter of a valid frame, now in d->frame. */
bool fsw_link_rx_byte(fsw_link_dec_t *d, uint8_t b);

/* Encodes one frame (body with CRC, COBS, the delimiter) into out. Returns the bytes written, or 0
   (nothing usable written) when len exceeds FSW_LINK_MAX_PAYLOAD, payload is NULL with len > 0,
   or cap is too small; FSW_LINK_MAX_WIRE is always enough. */
uint32_t fsw_link_encode(uint8_t type, uint16_t seq, const uint8_t *payload, uint32_t len, uint8_t *out,
                         uint32_t cap);

/* a - b in serial-number arithmetic (RFC 1982 for 16 bits): positive when a is newer than b,
   in [-32768, 32767]. */
int32_t fsw_link_seq_diff(uint16_t a, uint16_t b);

#endif /* FSW_APP_LINK_H */
