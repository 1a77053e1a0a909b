/*
 * fuzz_table_loader — libFuzzer entry point for the table loader (spec 00 §8 "Fuzzing").
 * Built with clang -fsanitize=fuzzer,address,undefined (preset `fuzz`) or, without clang,
 * linked with fuzz_replay_main.c as a corpus + seeded pseudo-random replay (label `fuzz`).
 *
 * Input format (every byte string is a valid input; see tests/fuzz/README.md):
 *   d[0]        ctrl: bit0 write a matching header (id, version, length field),
 *                     bit1 recompute the header CRC, bit2 total = TT_TOTAL (40 bytes),
 *                     bit3 swap id to another table, bit4 bump the layout version
 *   d[1..2]     total_raw (u16 LE): image length = total_raw % 4200 unless bit2
 *   d[3..]      the staging image (min(total, available) bytes; the rest is zero),
 *   then ops, one op byte each plus operands (missing operands read as 0):
 *     op & 7 == 0..2  chunk of the staging image: u16 offset, u8 n; op bit6 widens n to
 *                     45..300 (exercises n > 256); bit5 flips one data byte (OVERLAP);
 *                     bit4 wrong table id; bit3 with bit7 clear: total_len + 1, with bit7
 *                     set: revision + 1
 *     3  end of upload          4  commit                  5  scrub (+ flip/unflip probe)
 *     6  abort (bit3 clear) or veto with an operand detail byte (bit3 set)
 *     7  whole upload of the staging image in chunks of (u8 + 1) bytes, forward or (bit3)
 *        backward; bit4 sends end + commit afterwards
 *     bit5 of ops 3..6: also send a NULL / zero-length / NULL-data chunk (op bits 6..7)
 *
 * The harness boots the test table 0x7E57 (tests/app/tbl_test_desc.h), then runs the ops and
 * checks after each one (a violation is __builtin_trap(), or abort() without the builtin):
 *   - the active image is bit-identical to before unless a commit swapped (so every rejection
 *     leaves it untouched), and a payload always exists;
 *   - the four counters never decrease; a counted rejection adds exactly one to `rejects`,
 *     returns the rc of its reason class, leaves the loader IDLE and sets last_reason;
 *   - rc == FSW_OK exactly when the reason word is NONE;
 *   - a READY candidate and every committed table pass an independent re-check of the
 *     descriptor (header, CRC computed bitwise here, per-field ranges, relations), and a
 *     commit installs exactly the candidate that was READY;
 *   - the scrub passes on the active table, and catches a flipped payload bit.
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "app/fsw_table.h"
#include "tbl_test_desc.h"
#include "fuzz_input.h"

#define FZ_STAGE_MAX 4200u
#define FZ_MAX_OPS   512u
#define FZ_MAX_SENDS 1024u  /* chunks per input (keeps an input's cost bounded: exec/s) */

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static uint32_t fz_rd_le(const uint8_t *p, uint32_t w)
{
    uint32_t v = 0u;
    uint32_t i;
    for (i = w; i > 0u; i--) {
        v = (v << 8) | p[i - 1u];
    }
    return v;
}

static void fz_wr_le(uint8_t *p, uint32_t v, uint32_t w)
{
    uint32_t i;
    for (i = 0u; i < w; i++) {
        p[i] = (uint8_t)(v >> (8u * i));
    }
}

/* Bitwise zlib/IEEE CRC-32, independent of fx_crc32. */
static uint32_t fz_crc32(const uint8_t *p, uint32_t n)
{
    uint32_t c = 0xFFFFFFFFu;
    uint32_t i;
    uint32_t k;
    for (i = 0u; i < n; i++) {
        c ^= p[i];
        for (k = 0u; k < 8u; k++) {
            c = ((c & 1u) != 0u) ? ((c >> 1) ^ 0xEDB88320u) : (c >> 1);
        }
    }
    return c ^ 0xFFFFFFFFu;
}

/* Raw field value, decoded here (not with fsw_codec). */
static int64_t fz_field(const uint8_t *payload, const fsw_field_lim_t *f)
{
    const uint8_t *p = &payload[f->offset];
    int64_t v;
    switch (f->type) {
    case FSW_FT_U8:
        v = (int64_t)p[0];
        break;
    case FSW_FT_U16:
        v = (int64_t)fz_rd_le(p, 2u);
        break;
    case FSW_FT_U32:
        v = (int64_t)fz_rd_le(p, 4u);
        break;
    default: { /* FSW_FT_I32: two's complement without an implementation-defined cast */
        uint32_t u = fz_rd_le(p, 4u);
        v = (u >= 0x80000000u) ? ((int64_t)u - INT64_C(0x100000000)) : (int64_t)u;
        break;
    }
    }
    return v;
}

/* The descriptor's own check, re-done independently over a whole image. */
static int fz_image_ok(const fsw_table_desc_t *d, const uint8_t *img, uint32_t total)
{
    int ok = (total >= FSW_TABLE_HDR_BYTES) && (total <= FSW_TABLE_CAP_BYTES);
    uint32_t i;
    if (ok) {
        const uint8_t *pl = &img[FSW_TABLE_HDR_BYTES];
        uint32_t plen = total - FSW_TABLE_HDR_BYTES;
        ok = (fz_rd_le(&img[0], 2u) == d->table_id) && (fz_rd_le(&img[2], 2u) == d->layout_version) &&
             (fz_rd_le(&img[4], 4u) == plen) && (plen == d->payload_len) &&
             (fz_rd_le(&img[12], 4u) == fz_crc32(pl, plen));
        for (i = 0u; ok && (i < d->n_fields); i++) {
            int64_t v = fz_field(pl, &d->fields[i]);
            ok = (v >= d->fields[i].min) && (v <= d->fields[i].max);
        }
        for (i = 0u; ok && (i < d->n_rels); i++) {
            int64_t va = fz_field(pl, &d->fields[d->rels[i].a]);
            int64_t vb = fz_field(pl, &d->fields[d->rels[i].b]);
            ok = (va + (int64_t)d->rels[i].margin) <= vb;
        }
    }
    return ok;
}

/* rc class of a counted reason code (fsw/app/README.md table). */
static fsw_rc_t fz_rc_of(uint32_t code)
{
    fsw_rc_t rc;
    if (code == FSW_TBL_R_CHUNK_LEN) {
        rc = FSW_ERR_ARG;
    } else if ((code >= FSW_TBL_R_OVERSIZE) && (code <= FSW_TBL_R_OVERLAP)) {
        rc = FSW_ERR_CHUNK;
    } else if (code == FSW_TBL_R_MISSING) {
        rc = FSW_ERR_INCOMPLETE;
    } else if (code == FSW_TBL_R_DECODE) {
        rc = FSW_ERR_DECODE;
    } else if ((code == FSW_TBL_R_CRC) || (code == FSW_TBL_R_SCRUB)) {
        rc = FSW_ERR_CRC;
    } else if ((code >= FSW_TBL_R_ID) && (code <= FSW_TBL_R_LENGTH)) {
        rc = FSW_ERR_HEADER;
    } else if ((code == FSW_TBL_R_RANGE_LO) || (code == FSW_TBL_R_RANGE_HI)) {
        rc = FSW_ERR_RANGE;
    } else if ((code == FSW_TBL_R_INVARIANT) || (code == FSW_TBL_R_MODULE)) {
        rc = FSW_ERR_INVARIANT;
    } else {
        rc = FSW_ERR_STATE;   /* BUSY, NO_UPLOAD: not counted */
    }
    return rc;
}

typedef struct {
    uint8_t img[FSW_TABLE_CAP_BYTES];   /* active image before the op */
    uint32_t len;
    uint32_t rejects, accepts, commits, scrub_errs;
    uint8_t cand[FSW_TABLE_CAP_BYTES];  /* READY candidate before the op, if any */
    uint32_t cand_len;                  /* 0 when not READY */
} fz_snap_t;

typedef struct {
    fsw_table_t t;
    fz_snap_t s;
    uint8_t stage[FZ_STAGE_MAX];
    uint32_t total;
    uint32_t sends;                     /* chunks sent so far by this input */
} fz_ctx_t;

static void fz_snap(fz_ctx_t *x)
{
    const fsw_table_t *t = &x->t;
    x->s.len = t->active_len;
    FZ_CHECK((t->active <= 1u) && (t->active_len >= FSW_TABLE_HDR_BYTES) &&
             (t->active_len <= FSW_TABLE_CAP_BYTES));
    (void)memcpy(x->s.img, t->img[t->active], t->active_len);
    x->s.rejects = t->rejects;
    x->s.accepts = t->accepts;
    x->s.commits = t->commits;
    x->s.scrub_errs = t->scrub_errs;
    x->s.cand_len = 0u;
    if (t->state == FSW_TBL_S_READY) {
        x->s.cand_len = t->cand_total;
        (void)memcpy(x->s.cand, t->img[t->active ^ 1u], t->cand_total);
    }
}

/* Invariants after one operation that returned (rc, why); swapped = a commit returned true. */
static void fz_after(fz_ctx_t *x, int has_rc, fsw_rc_t rc, uint32_t why, int swapped)
{
    const fsw_table_t *t = &x->t;
    const fz_snap_t *s = &x->s;
    uint32_t len = 0u;
    uint32_t code = why & 0xFFu;
    const uint8_t *pl = fsw_table_payload(t, &len);

    FZ_CHECK(t->state <= FSW_TBL_S_READY);
    FZ_CHECK(t->active <= 1u);
    FZ_CHECK((pl != NULL) && (len + FSW_TABLE_HDR_BYTES == t->active_len));
    FZ_CHECK(pl == &t->img[t->active][FSW_TABLE_HDR_BYTES]);
    /* counters never decrease */
    FZ_CHECK(t->rejects >= s->rejects);
    FZ_CHECK(t->accepts >= s->accepts);
    FZ_CHECK(t->commits >= s->commits);
    FZ_CHECK(t->scrub_errs >= s->scrub_errs);

    if (swapped) {
        /* exactly the candidate that was READY, and it passes the descriptor's own check */
        FZ_CHECK(s->cand_len != 0u);
        FZ_CHECK(t->active_len == s->cand_len);
        FZ_CHECK(memcmp(t->img[t->active], s->cand, s->cand_len) == 0);
        FZ_CHECK(fz_image_ok(t->desc, t->img[t->active], t->active_len));
        FZ_CHECK((t->commits == s->commits + 1u) || (s->commits == UINT32_MAX));
        FZ_CHECK(t->state == FSW_TBL_S_IDLE);
    } else {
        /* no swap: the active image is bit-identical (rejections never touch it) */
        FZ_CHECK(t->active_len == s->len);
        FZ_CHECK(memcmp(t->img[t->active], s->img, s->len) == 0);
        FZ_CHECK(t->commits == s->commits);
    }
    /* so the active table always passes its own check: the boot table is checked once, and
       it changes only by a swap, checked above */

    if (has_rc) {
        FZ_CHECK((rc == FSW_OK) == (code == FSW_TBL_R_NONE));
        if ((code != FSW_TBL_R_NONE) && (code != FSW_TBL_R_BUSY) &&
            (code != FSW_TBL_R_NO_UPLOAD)) {
            /* a counted rejection */
            FZ_CHECK(code <= FSW_TBL_R_MODULE);
            FZ_CHECK(rc == fz_rc_of(code));
            FZ_CHECK((t->rejects == s->rejects + 1u) || (s->rejects == UINT32_MAX));
            FZ_CHECK(t->last_reason == why);
            FZ_CHECK(t->state == FSW_TBL_S_IDLE);
        } else {
            FZ_CHECK(t->rejects == s->rejects);
        }
        if ((code == FSW_TBL_R_BUSY) || (code == FSW_TBL_R_NO_UPLOAD)) {
            FZ_CHECK(rc == FSW_ERR_STATE);
        }
    }
    if (t->state == FSW_TBL_S_READY) {
        /* an accepted candidate passes the descriptor's own check */
        uint32_t clen = 0u;
        const uint8_t *cp = fsw_table_candidate(t, &clen);
        FZ_CHECK((cp != NULL) && (clen + FSW_TABLE_HDR_BYTES == t->cand_total));
        if (s->cand_len == 0u) {
            /* newly accepted */
            FZ_CHECK(fz_image_ok(t->desc, t->img[t->active ^ 1u], t->cand_total));
            FZ_CHECK((t->accepts == s->accepts + 1u) || (s->accepts == UINT32_MAX));
        } else {
            /* still the same validated candidate (BUSY chunks, end, scrub leave it alone) */
            FZ_CHECK((t->cand_total == s->cand_len) &&
                     (memcmp(t->img[t->active ^ 1u], s->cand, s->cand_len) == 0));
            FZ_CHECK(t->accepts == s->accepts);
        }
    } else if (t->state == FSW_TBL_S_LOADING) {
        FZ_CHECK((t->cand_got < t->cand_total) && (t->cand_total <= FSW_TABLE_CAP_BYTES));
    } else {
        FZ_CHECK(fsw_table_candidate(t, NULL) == NULL);
    }
}

/* Sends one chunk whose data lives in an exactly-sized heap copy (so ASan sees overreads). */
static void fz_send(fz_ctx_t *x, uint16_t id, uint32_t rev, uint32_t total, uint32_t off,
                    uint32_t n, uint32_t flip)
{
    fsw_table_chunk_t c;
    uint32_t why = 0xDEADu;
    fsw_rc_t rc;
    uint8_t *buf;
    uint32_t i;
    if (x->sends >= FZ_MAX_SENDS) {
        return;
    }
    x->sends++;
    buf = (uint8_t *)malloc((n > 0u) ? n : 1u);
    FZ_CHECK(buf != NULL);
    for (i = 0u; i < n; i++) {
        uint32_t k = off + i;
        buf[i] = (k < FZ_STAGE_MAX) ? x->stage[k] : (uint8_t)k;
    }
    if ((flip != 0u) && (n > 0u)) {
        buf[flip % n] ^= (uint8_t)(1u << (flip & 7u));
    }
    c.table_id = id;
    c.revision = rev;
    c.total_len = total;
    c.offset = off;
    c.n = n;
    c.data = buf;
    fz_snap(x);
    rc = fsw_table_chunk(&x->t, &c, &why);
    fz_after(x, 1, rc, why, 0);
    free(buf);
}

static uint32_t fz_stage_rev(const fz_ctx_t *x)
{
    return fz_rd_le(&x->stage[8], 4u);
}

/* Odd chunks: NULL chunk, zero length, NULL data (all CHUNK_LEN). */
static void fz_bad_chunk(fz_ctx_t *x, uint32_t kind)
{
    fsw_table_chunk_t c;
    uint32_t why = 0xDEADu;
    fsw_rc_t rc;
    c.table_id = (uint16_t)TT_ID;
    c.revision = fz_stage_rev(x);
    c.total_len = x->total;
    c.offset = 0u;
    c.n = (kind == 1u) ? 0u : 4u;
    c.data = (kind == 2u) ? NULL : x->stage;
    fz_snap(x);
    rc = fsw_table_chunk(&x->t, (kind == 0u) ? NULL : &c, &why);
    fz_after(x, 1, rc, why, 0);
    FZ_CHECK(((why & 0xFFu) == FSW_TBL_R_CHUNK_LEN) || ((why & 0xFFu) == FSW_TBL_R_BUSY));
}

static void fz_commit(fz_ctx_t *x)
{
    bool sw;
    uint32_t was_ready;
    fz_snap(x);
    was_ready = (x->t.state == FSW_TBL_S_READY) ? 1u : 0u;
    sw = fsw_table_commit(&x->t);
    FZ_CHECK((sw ? 1u : 0u) == was_ready);
    fz_after(x, 0, FSW_OK, 0u, sw ? 1 : 0);
}

static void fz_scrub(fz_ctx_t *x, uint32_t operand)
{
    fsw_rc_t rc;
    fz_snap(x);
    rc = fsw_table_scrub(&x->t);
    FZ_CHECK(rc == FSW_OK);
    FZ_CHECK(x->t.scrub_errs == x->s.scrub_errs);
    fz_after(x, 0, FSW_OK, 0u, 0);
    if ((operand & 1u) != 0u) {
        /* probe: flip one payload bit of the active image, scrub must catch it, then restore */
        uint8_t *img = x->t.img[x->t.active];
        uint32_t plen = x->t.active_len - FSW_TABLE_HDR_BYTES;
        uint32_t k = FSW_TABLE_HDR_BYTES + ((operand >> 1) % plen);
        uint32_t errs = x->t.scrub_errs;
        img[k] ^= (uint8_t)(1u << ((operand >> 4) & 7u));
        FZ_CHECK(fsw_table_scrub(&x->t) == FSW_ERR_CRC);
        FZ_CHECK((x->t.scrub_errs == errs + 1u) || (errs == UINT32_MAX));
        FZ_CHECK(x->t.last_reason == FSW_TBL_R_SCRUB);
        img[k] ^= (uint8_t)(1u << ((operand >> 4) & 7u));
        FZ_CHECK(fsw_table_scrub(&x->t) == FSW_OK);
    }
}

/* Whole staging image in chunks of `step` bytes, forward or backward. */
static void fz_upload(fz_ctx_t *x, uint32_t step, uint32_t backward)
{
    uint32_t total = x->total;
    uint32_t nch = (total + step - 1u) / step;
    uint32_t j;
    for (j = 0u; (j < nch) && (x->sends < FZ_MAX_SENDS); j++) {
        uint32_t idx = (backward != 0u) ? (nch - 1u - j) : j;
        uint32_t off = idx * step;
        uint32_t n = ((total - off) < step) ? (total - off) : step;
        fz_send(x, (uint16_t)TT_ID, fz_stage_rev(x), total, off, n, 0u);
    }
}

static void fz_prepare(fz_ctx_t *x, fz_in_t *in)
{
    uint32_t ctrl = fz_u8(in);
    uint32_t total_raw = fz_u16(in);
    uint32_t i;
    uint32_t ncopy;
    x->total = ((ctrl & 4u) != 0u) ? TT_TOTAL : (total_raw % FZ_STAGE_MAX);
    (void)memset(x->stage, 0, sizeof x->stage);
    ncopy = x->total;
    if ((in->n - in->pos) < ncopy) {
        ncopy = (uint32_t)(in->n - in->pos);
    }
    for (i = 0u; i < ncopy; i++) {
        x->stage[i] = (uint8_t)fz_u8(in);
    }
    if (((ctrl & 1u) != 0u) && (x->total >= FSW_TABLE_HDR_BYTES)) {
        fz_wr_le(&x->stage[0], ((ctrl & 8u) != 0u) ? (TT_ID ^ 0x100u) : TT_ID, 2u);
        fz_wr_le(&x->stage[2], TT_VERSION + (((ctrl & 16u) != 0u) ? 1u : 0u), 2u);
        fz_wr_le(&x->stage[4], x->total - FSW_TABLE_HDR_BYTES, 4u);
    }
    if (((ctrl & 2u) != 0u) && (x->total >= FSW_TABLE_HDR_BYTES) &&
        (x->total <= FSW_TABLE_CAP_BYTES)) {
        fz_wr_le(&x->stage[12],
                 fz_crc32(&x->stage[FSW_TABLE_HDR_BYTES], x->total - FSW_TABLE_HDR_BYTES), 4u);
    }
}

static void fz_op(fz_ctx_t *x, fz_in_t *in, uint32_t op)
{
    uint32_t kind = op & 7u;
    uint32_t why = 0xDEADu;
    fsw_rc_t rc;
    if (kind <= 2u) {
        uint32_t off = fz_u16(in);
        uint32_t n = fz_u8(in) + (((op & 0x40u) != 0u) ? 45u : 1u);
        uint32_t flip = ((op & 0x20u) != 0u) ? (fz_u8(in) | 0x100u) : 0u;
        uint16_t id = (uint16_t)(((op & 0x10u) != 0u) ? (TT_ID ^ 0x0001u) : TT_ID);
        uint32_t total = x->total;
        uint32_t rev = fz_stage_rev(x);
        if ((op & 0x08u) != 0u) {
            if ((op & 0x80u) != 0u) {
                rev++;
            } else {
                total++;
            }
        }
        if ((op & 0x80u) == 0u) {
            /* mostly in range, so uploads make progress */
            off = (x->total > 0u) ? (off % x->total) : off;
        }
        fz_send(x, id, rev, total, off, n, flip);
    } else if (kind == 7u) {
        fz_upload(x, fz_u8(in) + 1u, op & 8u);
        if ((op & 0x10u) != 0u) {
            fz_snap(x);
            rc = fsw_table_end(&x->t, &why);
            fz_after(x, 1, rc, why, 0);
            fz_commit(x);
        }
    } else {
        if ((op & 0x20u) != 0u) {
            fz_bad_chunk(x, (op >> 6) % 3u);
        }
        if (kind == 3u) {
            fz_snap(x);
            rc = fsw_table_end(&x->t, &why);
            fz_after(x, 1, rc, why, 0);
        } else if (kind == 4u) {
            fz_commit(x);
        } else if (kind == 5u) {
            fz_scrub(x, fz_u8(in));
        } else if ((op & 8u) == 0u) {
            fz_snap(x);
            fsw_table_abort(&x->t);
            fz_after(x, 0, FSW_OK, 0u, 0);
            FZ_CHECK(x->t.state == FSW_TBL_S_IDLE);
        } else {
            uint32_t was_ready = (x->t.state == FSW_TBL_S_READY) ? 1u : 0u;
            uint32_t detail = fz_u8(in);
            fz_snap(x);
            rc = fsw_table_veto(&x->t, detail, &why);
            fz_after(x, 1, rc, why, 0);
            FZ_CHECK(why == ((was_ready != 0u) ? (FSW_TBL_R_MODULE | (detail << 8)) :
                                                 FSW_TBL_R_NO_UPLOAD));
        }
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    /* static: 2 x 4 KiB images + snapshots are too large for a comfortable stack frame */
    static fz_ctx_t x;
    uint8_t boot[TT_TOTAL];
    tt_params_t p;
    uint32_t why = 0xDEADu;
    fz_in_t in;
    uint32_t nops = 0u;

    in.d = data;
    in.n = size;
    in.pos = 0u;
    tt_defaults(&p);
    FZ_CHECK(tt_build(boot, (uint32_t)sizeof boot, &p, (uint16_t)TT_ID, (uint16_t)TT_VERSION,
                      1u) == TT_TOTAL);
    FZ_CHECK(fsw_table_init(&x.t, &tt_desc, boot, TT_TOTAL, &why) == FSW_OK);
    FZ_CHECK((why == FSW_TBL_R_NONE) && (x.t.commits == 1u) && (x.t.rejects == 0u));
    FZ_CHECK(fz_image_ok(&tt_desc, x.t.img[x.t.active], x.t.active_len));

    x.sends = 0u;
    fz_prepare(&x, &in);
    while ((in.pos < in.n) && (nops < FZ_MAX_OPS)) {
        fz_op(&x, &in, fz_u8(&in));
        nops++;
    }
    /* always finish with end, commit and scrub */
    fz_snap(&x);
    {
        fsw_rc_t rc = fsw_table_end(&x.t, &why);
        fz_after(&x, 1, rc, why, 0);
    }
    fz_commit(&x);
    fz_scrub(&x, 0u);
    return 0;
}
