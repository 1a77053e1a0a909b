/*
 * fsw_table.c — table upload, validation, double-buffered activation and scrub (spec 00 §3.2).
 * See fsw_table.h for the API and fsw/app/README.md for the image layout and reason codes.
 *
 * Structure: every internal step returns a reason word (FSW_TBL_R_NONE = passed), so the order
 * of the checks reads top to bottom and the public functions map the first failing reason to
 * an fsw_rc_t in one place (tbl_rc_of). Single exit everywhere (MISRA 15.5 is deviated only
 * in fsw/fx). The active buffer is never written except by init; rejection paths touch only
 * the candidate buffer, the arrival bitmap and the counters.
 */
#include "fsw_table.h"
#include "fsw_codec.h"
#include "fx.h"

#define TBL_OFF_CRC   12u   /* byte offset of the crc32 field in the header */
#define TBL_CODE_MASK 0xFFu /* reason code bits of a reason word */

FX_STATIC_ASSERT(tbl_sa_map, (FSW_TABLE_MAP_WORDS * 32u) == FSW_TABLE_CAP_BYTES);
FX_STATIC_ASSERT(tbl_sa_cap, FSW_TABLE_CAP_BYTES > FSW_TABLE_HDR_BYTES);

/* Class of failure of a reason code (the fsw_rc_t the caller sees). */
static fsw_rc_t tbl_rc_of(uint32_t reason)
{
    fsw_rc_t rc;
    switch (reason & TBL_CODE_MASK) {
    case FSW_TBL_R_NONE:
        rc = FSW_OK;
        break;
    case FSW_TBL_R_CHUNK_LEN:
        rc = FSW_ERR_ARG;
        break;
    case FSW_TBL_R_BUSY:
    case FSW_TBL_R_NO_UPLOAD:
        rc = FSW_ERR_STATE;
        break;
    case FSW_TBL_R_OVERSIZE:
    case FSW_TBL_R_UPLOAD_ID:
    case FSW_TBL_R_TOTAL_CHANGED:
    case FSW_TBL_R_REV_CHANGED:
    case FSW_TBL_R_OFFSET:
    case FSW_TBL_R_OVERLAP:
        rc = FSW_ERR_CHUNK;
        break;
    case FSW_TBL_R_MISSING:
        rc = FSW_ERR_INCOMPLETE;
        break;
    case FSW_TBL_R_DECODE:
        rc = FSW_ERR_DECODE;
        break;
    case FSW_TBL_R_CRC:
    case FSW_TBL_R_SCRUB:
        rc = FSW_ERR_CRC;
        break;
    case FSW_TBL_R_ID:
    case FSW_TBL_R_VERSION:
    case FSW_TBL_R_LENGTH:
        rc = FSW_ERR_HEADER;
        break;
    case FSW_TBL_R_RANGE_LO:
    case FSW_TBL_R_RANGE_HI:
        rc = FSW_ERR_RANGE;
        break;
    case FSW_TBL_R_INVARIANT:
    case FSW_TBL_R_MODULE:
        rc = FSW_ERR_INVARIANT;
        break;
    default:
        rc = FSW_ERR_ARG;
        break;
    }
    return rc;
}

/* Wire width of a field type in bytes; 0 for an unknown type. */
static uint32_t tbl_type_width(uint32_t type)
{
    uint32_t w;
    switch (type) {
    case FSW_FT_U8:
        w = 1u;
        break;
    case FSW_FT_U16:
        w = 2u;
        break;
    case FSW_FT_U32:
    case FSW_FT_I32:
        w = 4u;
        break;
    default:
        w = 0u;
        break;
    }
    return w;
}

/* Bounded count: a descriptor claiming more than FSW_TABLE_FIELDS_MAX entries is rejected at
   init, and loops are additionally capped here so their bound is a compile-time constant. */
static uint32_t tbl_cap_count(uint32_t n)
{
    return (n < FSW_TABLE_FIELDS_MAX) ? n : FSW_TABLE_FIELDS_MAX;
}

static bool tbl_fields_ok(const fsw_table_desc_t *d)
{
    bool ok = true;
    uint32_t n = tbl_cap_count(d->n_fields);
    uint32_t i;
    for (i = 0u; i < n; i++) {
        const fsw_field_lim_t *f = &d->fields[i];
        uint32_t w = tbl_type_width((uint32_t)f->type);
        /* Every field must lie wholly inside the payload, so later reads cannot fail. */
        if ((w == 0u) || (w > d->payload_len) || ((uint32_t)f->offset > (d->payload_len - w)) ||
            (f->min > f->max)) {
            ok = false;
        }
    }
    return ok;
}

static bool tbl_rels_ok(const fsw_table_desc_t *d)
{
    bool ok = true;
    uint32_t n = tbl_cap_count(d->n_rels);
    uint32_t i;
    for (i = 0u; i < n; i++) {
        if (((uint32_t)d->rels[i].a >= d->n_fields) || ((uint32_t)d->rels[i].b >= d->n_fields)) {
            ok = false;
        }
    }
    return ok;
}

/* A malformed descriptor is a build error of the generator, reported as FSW_ERR_ARG. */
static bool tbl_desc_ok(const fsw_table_desc_t *d)
{
    bool ok = false;
    if (d != NULL) {
        ok = (d->payload_len <= (FSW_TABLE_CAP_BYTES - FSW_TABLE_HDR_BYTES)) &&
             (d->n_fields <= FSW_TABLE_FIELDS_MAX) && (d->n_rels <= FSW_TABLE_FIELDS_MAX) &&
             ((d->n_fields == 0u) || (d->fields != NULL)) &&
             ((d->n_rels == 0u) || (d->rels != NULL));
        if (ok) {
            ok = tbl_fields_ok(d) && tbl_rels_ok(d);
        }
    }
    return ok;
}

/* Raw value of field f; the descriptor check guarantees it lies inside the payload. */
static int64_t tbl_field_value(const uint8_t *payload, uint32_t len, const fsw_field_lim_t *f)
{
    fsw_rd_t r;
    int64_t v;
    fsw_rd_init(&r, payload, len);
    fsw_rd_seek(&r, (uint32_t)f->offset);
    switch (f->type) {
    case FSW_FT_U8:
        v = (int64_t)fsw_rd_u8(&r);
        break;
    case FSW_FT_U16:
        v = (int64_t)fsw_rd_u16(&r);
        break;
    case FSW_FT_U32:
        v = (int64_t)fsw_rd_u32(&r);
        break;
    case FSW_FT_I32:
        v = (int64_t)fsw_rd_i32(&r);
        break;
    default:
        v = 0;
        break;
    }
    return v;
}

/* Per-field [min, max]; the first failing field (lowest index) is reported. */
static uint32_t tbl_check_fields(const fsw_table_desc_t *d, const uint8_t *payload, uint32_t len)
{
    uint32_t reason = FSW_TBL_R_NONE;
    uint32_t n = tbl_cap_count(d->n_fields);
    uint32_t i;
    for (i = 0u; i < n; i++) {
        const fsw_field_lim_t *f = &d->fields[i];
        int64_t v = tbl_field_value(payload, len, f);
        if (reason == FSW_TBL_R_NONE) {
            if (v < f->min) {
                reason = FSW_TBL_R_RANGE_LO | (i << FSW_TBL_DETAIL_SHIFT);
            } else if (v > f->max) {
                reason = FSW_TBL_R_RANGE_HI | (i << FSW_TBL_DETAIL_SHIFT);
            } else {
                /* in range */
            }
        }
    }
    return reason;
}

/* Cross-field relations value[a] + margin <= value[b]; exact in int64 (|values| < 2^32). */
static uint32_t tbl_check_rels(const fsw_table_desc_t *d, const uint8_t *payload, uint32_t len)
{
    uint32_t reason = FSW_TBL_R_NONE;
    uint32_t n = tbl_cap_count(d->n_rels);
    uint32_t i;
    for (i = 0u; i < n; i++) {
        const fsw_field_rel_t *rel = &d->rels[i];
        int64_t va = tbl_field_value(payload, len, &d->fields[rel->a]);
        int64_t vb = tbl_field_value(payload, len, &d->fields[rel->b]);
        if ((reason == FSW_TBL_R_NONE) && ((va + (int64_t)rel->margin) > vb)) {
            reason = FSW_TBL_R_INVARIANT | (i << FSW_TBL_DETAIL_SHIFT);
        }
    }
    return reason;
}

/* The whole validation chain in the order of spec 00 §3.2 over a complete image. */
static uint32_t tbl_validate(const fsw_table_desc_t *d, const uint8_t *img, uint32_t total)
{
    fsw_rd_t r;
    uint32_t reason = FSW_TBL_R_NONE;
    uint16_t id;
    uint16_t ver;
    uint32_t len;
    uint32_t crc;
    fsw_rd_init(&r, img, total);
    id = fsw_rd_u16(&r);
    ver = fsw_rd_u16(&r);
    len = fsw_rd_u32(&r);
    (void)fsw_rd_u32(&r);   /* revision: informative, not checked */
    crc = fsw_rd_u32(&r);
    if (r.err || (len != (total - FSW_TABLE_HDR_BYTES))) {
        reason = FSW_TBL_R_DECODE;
    } else if (fx_crc32(0u, &img[FSW_TABLE_HDR_BYTES], len) != crc) {
        reason = FSW_TBL_R_CRC;
    } else if (id != d->table_id) {
        reason = FSW_TBL_R_ID;
    } else if (ver != d->layout_version) {
        reason = FSW_TBL_R_VERSION;
    } else if (len != d->payload_len) {
        reason = FSW_TBL_R_LENGTH;
    } else {
        reason = tbl_check_fields(d, &img[FSW_TABLE_HDR_BYTES], len);
        if (reason == FSW_TBL_R_NONE) {
            reason = tbl_check_rels(d, &img[FSW_TABLE_HDR_BYTES], len);
        }
    }
    return reason;
}

/* Records the outcome: a table error counts a reject and drops the candidate; the two state
   complaints (busy, no upload) do neither, so a validated candidate survives a stray chunk. */
static fsw_rc_t tbl_finish(fsw_table_t *t, uint32_t reason, uint32_t *why)
{
    uint32_t code = reason & TBL_CODE_MASK;
    if ((code != FSW_TBL_R_NONE) && (code != FSW_TBL_R_BUSY) && (code != FSW_TBL_R_NO_UPLOAD)) {
        fx_cnt_inc(&t->rejects);
        t->last_reason = reason;
        t->state = FSW_TBL_S_IDLE;
    }
    if (why != NULL) {
        *why = reason;
    }
    return tbl_rc_of(reason);
}

static bool tbl_has(const fsw_table_t *t, uint32_t k)
{
    return (t->got[k >> 5u] & (1u << (k & 31u))) != 0u;
}

static uint32_t tbl_upload_start(fsw_table_t *t, const fsw_table_chunk_t *c)
{
    uint32_t reason = FSW_TBL_R_NONE;
    if ((c->total_len < FSW_TABLE_HDR_BYTES) || (c->total_len > FSW_TABLE_CAP_BYTES)) {
        reason = FSW_TBL_R_OVERSIZE;
    } else {
        uint32_t i;
        for (i = 0u; i < FSW_TABLE_MAP_WORDS; i++) {
            t->got[i] = 0u;
        }
        t->cand_total = c->total_len;
        t->cand_rev = c->revision;
        t->cand_got = 0u;
        t->state = FSW_TBL_S_LOADING;
    }
    return reason;
}

/* Copies a chunk into the candidate. Two passes so a chunk is taken whole or not at all: a
   re-sent byte must equal what already arrived, anything else is an inconsistent upload. */
static uint32_t tbl_chunk_store(fsw_table_t *t, const fsw_table_chunk_t *c)
{
    uint32_t reason = FSW_TBL_R_NONE;
    uint8_t *cand = t->img[(t->active ^ 1u) & 1u];
    if ((c->offset > t->cand_total) || (c->n > (t->cand_total - c->offset))) {
        reason = FSW_TBL_R_OFFSET;
    } else {
        /* c->n <= FSW_TABLE_CHUNK_MAX (checked by the caller); the cap keeps the bound static. */
        uint32_t i;
        for (i = 0u; (i < c->n) && (i < FSW_TABLE_CHUNK_MAX); i++) {
            uint32_t k = c->offset + i;
            if (tbl_has(t, k) && (cand[k] != c->data[i])) {
                reason = FSW_TBL_R_OVERLAP;
            }
        }
        if (reason == FSW_TBL_R_NONE) {
            for (i = 0u; (i < c->n) && (i < FSW_TABLE_CHUNK_MAX); i++) {
                uint32_t k = c->offset + i;
                if (!tbl_has(t, k)) {
                    t->got[k >> 5u] |= (1u << (k & 31u));
                    t->cand_got++;
                }
                cand[k] = c->data[i];
            }
        }
    }
    return reason;
}

/* Checks a chunk against the upload in progress (starting one if idle) and stores it. */
static uint32_t tbl_chunk_admit(fsw_table_t *t, const fsw_table_chunk_t *c)
{
    uint32_t reason = FSW_TBL_R_NONE;
    if ((c == NULL) || (c->data == NULL) || (c->n == 0u) || (c->n > FSW_TABLE_CHUNK_MAX)) {
        reason = FSW_TBL_R_CHUNK_LEN;
    } else if (t->state == FSW_TBL_S_READY) {
        reason = FSW_TBL_R_BUSY;
    } else if (c->table_id != t->desc->table_id) {
        reason = FSW_TBL_R_UPLOAD_ID;
    } else if (t->state == FSW_TBL_S_IDLE) {
        reason = tbl_upload_start(t, c);
    } else if (c->total_len != t->cand_total) {
        reason = FSW_TBL_R_TOTAL_CHANGED;
    } else if (c->revision != t->cand_rev) {
        reason = FSW_TBL_R_REV_CHANGED;
    } else {
        /* continues the upload in progress */
    }
    if (reason == FSW_TBL_R_NONE) {
        reason = tbl_chunk_store(t, c);
    }
    return reason;
}

/* Validates the complete candidate and marks it ready for the next commit. */
static uint32_t tbl_complete(fsw_table_t *t)
{
    uint32_t reason = tbl_validate(t->desc, t->img[(t->active ^ 1u) & 1u], t->cand_total);
    if (reason == FSW_TBL_R_NONE) {
        t->state = FSW_TBL_S_READY;
        fx_cnt_inc(&t->accepts);
    }
    return reason;
}

/* The swap is an index flip: a reader sees either the old or the new image, never a mix. */
static void tbl_swap(fsw_table_t *t)
{
    t->active = (t->active ^ 1u) & 1u;
    t->active_len = t->cand_total;
    t->state = FSW_TBL_S_IDLE;
    fx_cnt_inc(&t->commits);
}

static void tbl_clear(fsw_table_t *t)
{
    uint32_t i;
    for (i = 0u; i < FSW_TABLE_CAP_BYTES; i++) {
        t->img[0][i] = 0u;
        t->img[1][i] = 0u;
    }
    for (i = 0u; i < FSW_TABLE_MAP_WORDS; i++) {
        t->got[i] = 0u;
    }
    t->desc = NULL;
    t->active = 0u;
    t->active_len = 0u;
    t->state = FSW_TBL_S_IDLE;
    t->cand_total = 0u;
    t->cand_rev = 0u;
    t->cand_got = 0u;
    t->rejects = 0u;
    t->accepts = 0u;
    t->commits = 0u;
    t->scrub_errs = 0u;
    t->last_reason = FSW_TBL_R_NONE;
}

/* Boot image: copied whole into the candidate and put through the same validation. */
static uint32_t tbl_boot(fsw_table_t *t, const uint8_t *boot, uint32_t boot_len)
{
    uint32_t reason = FSW_TBL_R_NONE;
    if ((boot_len < FSW_TABLE_HDR_BYTES) || (boot_len > FSW_TABLE_CAP_BYTES)) {
        reason = FSW_TBL_R_OVERSIZE;
    } else {
        uint32_t i;
        for (i = 0u; i < boot_len; i++) {
            t->img[1][i] = boot[i];
        }
        t->cand_total = boot_len;
        reason = tbl_complete(t);
        if (reason == FSW_TBL_R_NONE) {
            tbl_swap(t);
        }
    }
    return reason;
}

fsw_rc_t fsw_table_init(fsw_table_t *t, const fsw_table_desc_t *desc, const uint8_t *boot,
                        uint32_t boot_len, uint32_t *why)
{
    fsw_rc_t rc = FSW_ERR_ARG;
    uint32_t reason = FSW_TBL_R_NONE;
    if (t != NULL) {
        tbl_clear(t);
        if (tbl_desc_ok(desc)) {
            t->desc = desc;
            if (boot != NULL) {
                reason = tbl_boot(t, boot, boot_len);
            }
            rc = tbl_finish(t, reason, NULL);
        }
    }
    if (why != NULL) {
        *why = reason;
    }
    return rc;
}

fsw_rc_t fsw_table_chunk(fsw_table_t *t, const fsw_table_chunk_t *c, uint32_t *why)
{
    fsw_rc_t rc = FSW_ERR_ARG;
    if ((t != NULL) && (t->desc != NULL)) {
        uint32_t reason = tbl_chunk_admit(t, c);
        if ((reason == FSW_TBL_R_NONE) && (t->cand_got == t->cand_total)) {
            reason = tbl_complete(t);
        }
        rc = tbl_finish(t, reason, why);
    } else if (why != NULL) {
        *why = FSW_TBL_R_CHUNK_LEN;
    } else {
        /* nothing to report into */
    }
    return rc;
}

fsw_rc_t fsw_table_end(fsw_table_t *t, uint32_t *why)
{
    fsw_rc_t rc = FSW_ERR_ARG;
    if (t != NULL) {
        uint32_t reason;
        if (t->state == FSW_TBL_S_LOADING) {
            /* A complete image is validated at once, so LOADING here means bytes are missing. */
            reason = FSW_TBL_R_MISSING;
        } else if (t->state == FSW_TBL_S_READY) {
            reason = FSW_TBL_R_NONE;
        } else {
            reason = FSW_TBL_R_NO_UPLOAD;
        }
        rc = tbl_finish(t, reason, why);
    }
    return rc;
}

void fsw_table_abort(fsw_table_t *t)
{
    if (t != NULL) {
        t->state = FSW_TBL_S_IDLE;
    }
}

bool fsw_table_commit(fsw_table_t *t)
{
    bool swapped = false;
    if ((t != NULL) && (t->state == FSW_TBL_S_READY)) {
        tbl_swap(t);
        swapped = true;
    }
    return swapped;
}

fsw_rc_t fsw_table_scrub(fsw_table_t *t)
{
    fsw_rc_t rc = FSW_ERR_STATE;
    if ((t != NULL) && (t->desc != NULL) && (t->active_len >= FSW_TABLE_HDR_BYTES) &&
        (t->active_len <= FSW_TABLE_CAP_BYTES)) {
        const uint8_t *img = t->img[t->active & 1u];
        uint32_t plen = t->active_len - FSW_TABLE_HDR_BYTES;
        fsw_rd_t r;
        uint16_t id;
        uint16_t ver;
        uint32_t len;
        uint32_t crc;
        fsw_rd_init(&r, img, FSW_TABLE_HDR_BYTES);
        id = fsw_rd_u16(&r);
        ver = fsw_rd_u16(&r);
        len = fsw_rd_u32(&r);
        fsw_rd_seek(&r, TBL_OFF_CRC);
        crc = fsw_rd_u32(&r);
        /* The CRC covers the payload; the header fields the executive relies on are compared
           with the descriptor and the stored length, so a flip there is caught as well. */
        if ((id == t->desc->table_id) && (ver == t->desc->layout_version) && (len == plen) &&
            (fx_crc32(0u, &img[FSW_TABLE_HDR_BYTES], plen) == crc)) {
            rc = FSW_OK;
        } else {
            fx_cnt_inc(&t->scrub_errs);
            t->last_reason = FSW_TBL_R_SCRUB;
            rc = tbl_rc_of(FSW_TBL_R_SCRUB);
        }
    }
    return rc;
}

const uint8_t *fsw_table_candidate(const fsw_table_t *t, uint32_t *len)
{
    const uint8_t *p = NULL;
    uint32_t n = 0u;
    /* READY implies cand_total was validated: HDR <= cand_total <= CAP. */
    if ((t != NULL) && (t->state == FSW_TBL_S_READY) && (t->cand_total >= FSW_TABLE_HDR_BYTES) &&
        (t->cand_total <= FSW_TABLE_CAP_BYTES)) {
        p = &t->img[(t->active ^ 1u) & 1u][FSW_TABLE_HDR_BYTES];
        n = t->cand_total - FSW_TABLE_HDR_BYTES;
    }
    if (len != NULL) {
        *len = n;
    }
    return p;
}

fsw_rc_t fsw_table_veto(fsw_table_t *t, uint32_t detail, uint32_t *why)
{
    fsw_rc_t rc = FSW_ERR_ARG;
    if (t != NULL) {
        uint32_t reason = FSW_TBL_R_NO_UPLOAD;
        if (t->state == FSW_TBL_S_READY) {
            reason = FSW_TBL_R_MODULE | ((detail & TBL_CODE_MASK) << FSW_TBL_DETAIL_SHIFT);
        }
        rc = tbl_finish(t, reason, why);
    }
    return rc;
}

uint32_t fsw_table_veto_detail(uint32_t why)
{
    uint32_t d = FSW_VETO_UNDECODED;
    uint32_t bit = 1u;
    uint32_t i;
    for (i = 0u; (i < 31u) && (d == FSW_VETO_UNDECODED); i++) {
        if ((why & bit) != 0u) {
            d = i + 1u;
        }
        bit <<= 1u;
    }
    return d;
}

const uint8_t *fsw_table_payload(const fsw_table_t *t, uint32_t *len)
{
    const uint8_t *p = NULL;
    uint32_t n = 0u;
    if ((t != NULL) && (t->active_len >= FSW_TABLE_HDR_BYTES) &&
        (t->active_len <= FSW_TABLE_CAP_BYTES)) {
        p = &t->img[t->active & 1u][FSW_TABLE_HDR_BYTES];
        n = t->active_len - FSW_TABLE_HDR_BYTES;
    }
    if (len != NULL) {
        *len = n;
    }
    return p;
}

uint32_t fsw_table_revision(const fsw_table_t *t)
{
    uint32_t rev = 0u;
    if ((t != NULL) && (t->active_len >= FSW_TABLE_HDR_BYTES)) {
        fsw_rd_t r;
        fsw_rd_init(&r, t->img[t->active & 1u], FSW_TABLE_HDR_BYTES);
        fsw_rd_seek(&r, 8u);
        rev = fsw_rd_u32(&r);
    }
    return rev;
}

void fsw_table_write_header(uint8_t *img, uint16_t table_id, uint16_t layout, uint32_t payload_len,
                            uint32_t revision)
{
    fsw_wr_t h;
    fsw_wr_init(&h, img, FSW_TABLE_HDR_BYTES);
    fsw_wr_u16(&h, table_id);
    fsw_wr_u16(&h, layout);
    fsw_wr_u32(&h, payload_len);
    fsw_wr_u32(&h, revision);
    fsw_wr_u32(&h, fx_crc32(0u, &img[FSW_TABLE_HDR_BYTES], payload_len));
}
