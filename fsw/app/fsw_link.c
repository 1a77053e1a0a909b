/*
 * fsw_link.c — COBS framing, CRC and the byte-at-a-time decoder of the serial link (spec 00 §6.1).
 */
#include "fsw_link.h"
#include "fsw_codec.h"
#include "fx.h"

#define COBS_FULL 0xFFu   /* code of a block of 254 non-zero bytes with no zero after it */

void fsw_link_dec_init(fsw_link_dec_t *d)
{
    uint32_t i;
    for (i = 0u; i < FSW_LINK_MAX_COBS; i++) {
        d->raw[i] = 0u;
    }
    for (i = 0u; i < FSW_LINK_MAX_COBS; i++) {
        d->body[i] = 0u;
    }
    d->n = 0u;
    d->overflow = false;
    d->frame.type = 0u;
    d->frame.seq = 0u;
    d->frame.len = 0u;
    d->frame.payload = d->body;
    d->st.bytes = 0u;
    d->st.empty = 0u;
    d->st.frames = 0u;
    d->st.err_oversize = 0u;
    d->st.err_cobs = 0u;
    d->st.err_short = 0u;
    d->st.err_len = 0u;
    d->st.err_crc = 0u;
    d->st.err_version = 0u;
    d->st.err_type = 0u;
}

/* Decodes raw[0..n) into body; returns the body size, or -1 for a malformed or non-canonical run.
   Canonical (what fsw_link_encode writes): every block but the last ends with an implied zero
   unless its code is COBS_FULL, and the last block is never COBS_FULL (the encoder closes a full
   block with a final, possibly empty, one). raw holds no zero: zeros end runs. */
static int32_t cobs_decode(const uint8_t *raw, uint32_t n, uint8_t *body)
{
    uint32_t i = 0u;
    uint32_t o = 0u;
    bool ok = true;
    uint32_t blocks = 0u;
    /* Each pass consumes at least one byte (the code), so n passes bound the loop. */
    while (ok && (i < n) && (blocks < FSW_LINK_MAX_COBS)) {
        uint32_t code = raw[i];
        uint32_t end = i + code;      /* index of the next code byte */
        blocks++;
        if (end > n) {
            ok = false;               /* the code points past the run */
        } else {
            uint32_t k;
            for (k = i + 1u; k < end; k++) {
                body[o] = raw[k];
                o++;
            }
            if (end < n) {
                if (code != COBS_FULL) {
                    body[o] = 0u;
                    o++;
                }
            } else if (code == COBS_FULL) {
                ok = false;           /* ends on a full block: not the canonical form */
            } else {
                /* the last block: no implied zero */
            }
            i = end;
        }
    }
    return ok ? (int32_t)o : -1;
}

/* One complete run raw[0..n): decode and check it, count it once, fill d->frame if accepted. */
static bool finish_run(fsw_link_dec_t *d)
{
    bool ok = false;
    if (d->overflow) {
        d->st.err_oversize++;
    } else if (d->n == 0u) {
        d->st.empty++;
    } else {
        int32_t m = cobs_decode(d->raw, d->n, d->body);
        if (m < 0) {
            d->st.err_cobs++;
        } else if ((uint32_t)m < FSW_LINK_MIN_BODY) {
            d->st.err_short++;
        } else {
            uint32_t bl = (uint32_t)m;
            fsw_rd_t r;
            uint8_t ver;
            uint8_t type;
            uint16_t seq;
            uint16_t len;
            fsw_rd_init(&r, d->body, bl);
            ver = fsw_rd_u8(&r);
            type = fsw_rd_u8(&r);
            seq = fsw_rd_u16(&r);
            len = fsw_rd_u16(&r);
            if (((uint32_t)len > FSW_LINK_MAX_PAYLOAD) || (((uint32_t)len + FSW_LINK_MIN_BODY) != bl)) {
                d->st.err_len++;
            } else {
                uint32_t crc_rx;
                fsw_rd_seek(&r, FSW_LINK_HDR + (uint32_t)len);
                crc_rx = fsw_rd_u32(&r);
                if (fx_crc32(0u, d->body, (size_t)FSW_LINK_HDR + (size_t)len) != crc_rx) {
                    d->st.err_crc++;
                } else if (ver != FSW_LINK_VERSION) {
                    d->st.err_version++;
                } else if ((type == 0u) || (type > FSW_LINK_T_MAX)) {
                    d->st.err_type++;
                } else {
                    d->frame.type = type;
                    d->frame.seq = seq;
                    d->frame.len = len;
                    d->frame.payload = &d->body[FSW_LINK_HDR];
                    d->st.frames++;
                    ok = true;
                }
            }
        }
    }
    d->n = 0u;
    d->overflow = false;
    return ok;
}

bool fsw_link_rx_byte(fsw_link_dec_t *d, uint8_t b)
{
    bool ok = false;
    d->st.bytes++;
    if (b == 0u) {
        ok = finish_run(d);
    } else if (d->n < FSW_LINK_MAX_COBS) {
        d->raw[d->n] = b;
        d->n++;
    } else {
        d->overflow = true;           /* keep counting bytes; the run is dropped at its delimiter */
    }
    return ok;
}

/* Streaming COBS encoder: the body goes byte by byte into out, so no body buffer is needed (the
   board's per-function stack budget is 256 bytes). The caller checks the capacity once. */
typedef struct {
    uint8_t *out;
    uint32_t code_at;    /* where the open block's code byte goes */
    uint32_t o;          /* next output byte */
    uint32_t code;       /* the open block's code: 1 + its data bytes */
} cobs_enc_t;

static void cobs_put(cobs_enc_t *e, uint8_t b)
{
    if (b == 0u) {
        e->out[e->code_at] = (uint8_t)e->code;
        e->code_at = e->o;
        e->o++;
        e->code = 1u;
    } else {
        e->out[e->o] = b;
        e->o++;
        e->code++;
        if (e->code == COBS_FULL) {
            e->out[e->code_at] = (uint8_t)e->code;
            e->code_at = e->o;
            e->o++;
            e->code = 1u;
        }
    }
}

uint32_t fsw_link_encode(uint8_t type, uint16_t seq, const uint8_t *payload, uint32_t len, uint8_t *out,
                         uint32_t cap)
{
    uint32_t n = 0u;
    uint32_t bl = len + FSW_LINK_MIN_BODY;
    if ((len <= FSW_LINK_MAX_PAYLOAD) && ((payload != NULL) || (len == 0u)) && (out != NULL) &&
        (cap >= (bl + (bl / 254u) + 2u))) {   /* the worst case of COBS plus the delimiter */
        uint8_t hdr[FSW_LINK_HDR];
        fsw_wr_t w;
        cobs_enc_t e;
        uint32_t crc;
        uint32_t i;
        fsw_wr_init(&w, hdr, FSW_LINK_HDR);
        fsw_wr_u8(&w, (uint8_t)FSW_LINK_VERSION);
        fsw_wr_u8(&w, type);
        fsw_wr_u16(&w, seq);
        fsw_wr_u16(&w, (uint16_t)len);
        crc = fx_crc32(0u, hdr, (size_t)FSW_LINK_HDR);
        if (len > 0u) {
            crc = fx_crc32(crc, payload, (size_t)len);
        }
        e.out = out;
        e.code_at = 0u;
        e.o = 1u;
        e.code = 1u;
        for (i = 0u; i < FSW_LINK_HDR; i++) {
            cobs_put(&e, hdr[i]);
        }
        for (i = 0u; i < len; i++) {
            cobs_put(&e, payload[i]);
        }
        for (i = 0u; i < FSW_LINK_CRC; i++) {
            cobs_put(&e, (uint8_t)((crc >> (8u * i)) & 0xFFu));   /* little-endian */
        }
        out[e.code_at] = (uint8_t)e.code;   /* the final block, also after a full one */
        out[e.o] = 0u;
        n = e.o + 1u;
    }
    return n;
}

int32_t fsw_link_seq_diff(uint16_t a, uint16_t b)
{
    uint32_t d = ((uint32_t)a - (uint32_t)b) & 0xFFFFu;
    return (d >= 0x8000u) ? ((int32_t)d - 65536) : (int32_t)d;
}
