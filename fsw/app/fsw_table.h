/*
 * fsw_table.h — versioned parameter-table images: chunked upload, validation, double-buffered
 * activation and scrubbing (spec 00 §3.2, §8 "table error"). Details: fsw/app/README.md.
 *
 * Image = 16-byte header + payload, all little-endian (fsw_codec):
 *   off 0  u16 table_id        off 2  u16 layout_version   off 4  u32 length (payload bytes)
 *   off 8  u32 revision        off 12 u32 crc32 of the payload (zlib/IEEE, fx_crc32)
 *
 * One fsw_table_t (caller-owned, no globals) holds one table: the active image and a candidate
 * being uploaded, in two buffers whose roles swap on commit. Validation order on completion:
 *   decode (header readable, length field == image bytes - 16) -> CRC -> header (table id,
 *   layout version, payload length against the descriptor) -> per-field [min, max] ->
 *   cross-field relations.
 * Every failure leaves the active image untouched, increments `rejects` (saturating) and
 * stores a reason word: code in bits 0..7, detail (field or relation index) in bits 8..15.
 */
#ifndef FSW_APP_TABLE_H
#define FSW_APP_TABLE_H

#include <stdint.h>
#include <stdbool.h>
#include <stddef.h>
#include "fx.h"
#include "fsw_ids.h"

#define FSW_TABLE_HDR_BYTES   16u    /* header size on the wire */
#define FSW_TABLE_CAP_BYTES   4096u  /* largest image, header included */
#define FSW_TABLE_CHUNK_MAX   256u   /* largest upload chunk (one link packet) */
#define FSW_TABLE_FIELDS_MAX  255u   /* field/relation index must fit the 8-bit detail */
#define FSW_TABLE_MAP_WORDS   (FSW_TABLE_CAP_BYTES / 32u)  /* arrival bitmap, 1 bit a byte */

/* Field types of the limits descriptor (wire width 1, 2, 4, 4 bytes). */
#define FSW_FT_U8   1u
#define FSW_FT_U16  2u
#define FSW_FT_U32  3u
#define FSW_FT_I32  4u

/* Reason codes (bits 0..7 of the reason word; 0 = no rejection since init): FSW_TBL_R_* in
   fsw_ids.h, generated from fsw_iface.py. */
#define FSW_TBL_DETAIL_SHIFT    8u   /* reason word = code | (detail << FSW_TBL_DETAIL_SHIFT) */

/* Loader states (fsw_table_t.state). */
#define FSW_TBL_S_IDLE     0u  /* no upload in progress; candidate buffer free */
#define FSW_TBL_S_LOADING  1u  /* chunks arriving */
#define FSW_TBL_S_READY    2u  /* candidate validated; swapped in by fsw_table_commit */

/* One range-checked field: a value of `type` at byte `offset` of the payload. */
typedef struct {
    uint16_t offset;
    uint8_t type;            /* FSW_FT_* */
    int64_t min;             /* inclusive, raw (unscaled) wire value */
    int64_t max;             /* inclusive */
} fsw_field_lim_t;

/* Cross-field relation: value[a] + margin <= value[b], evaluated exactly in int64 on raw
   values (the generator makes both fields the same format). A strict "<" is margin + 1. */
typedef struct {
    uint8_t a;               /* field index into fsw_table_desc_t.fields */
    uint8_t b;
    int32_t margin;
} fsw_field_rel_t;

/* Generated, const description of one table layout. */
typedef struct {
    uint16_t table_id;
    uint16_t layout_version;
    uint32_t payload_len;              /* exact payload bytes of this layout */
    const fsw_field_lim_t *fields;
    uint32_t n_fields;                 /* <= FSW_TABLE_FIELDS_MAX */
    const fsw_field_rel_t *rels;
    uint32_t n_rels;                   /* <= FSW_TABLE_FIELDS_MAX */
} fsw_table_desc_t;

/* One upload chunk (a TABLE_LOAD packet). */
typedef struct {
    uint16_t table_id;       /* routes the chunk; must equal the descriptor's id */
    uint32_t revision;       /* ties the chunks of one upload together */
    uint32_t total_len;      /* whole image, header included; fixed by the first chunk */
    uint32_t offset;         /* of data[0] within the image */
    uint32_t n;              /* 1..FSW_TABLE_CHUNK_MAX */
    const uint8_t *data;
} fsw_table_chunk_t;

typedef struct {
    const fsw_table_desc_t *desc;
    uint8_t img[2][FSW_TABLE_CAP_BYTES];   /* img[active] active, the other the candidate */
    uint32_t got[FSW_TABLE_MAP_WORDS];     /* candidate bytes received, 1 bit a byte */
    uint32_t active;                       /* 0 or 1 */
    uint32_t active_len;                   /* active image bytes; 0 = no active table */
    uint32_t state;                        /* FSW_TBL_S_* */
    uint32_t cand_total;                   /* upload in progress: total_len, revision, */
    uint32_t cand_rev;                     /*   and bytes received so far */
    uint32_t cand_got;
    /* Telemetry (saturating counters, fx_cnt_inc). */
    uint32_t rejects;                      /* table_rej of spec 00 §8 */
    uint32_t accepts;                      /* candidates validated */
    uint32_t commits;                      /* candidates swapped in */
    uint32_t scrub_errs;                   /* scrub CRC mismatches */
    uint32_t last_reason;                  /* reason word of the latest rejection */
} fsw_table_t;

/*
 * Binds t to desc and, if boot != NULL, validates boot[0..boot_len) as the first active image
 * (same checks as an upload). Returns FSW_ERR_ARG for a malformed descriptor (payload too
 * large, field beyond the payload, unknown type, min > max, relation index out of range).
 * *why (may be NULL) receives the reason word of a boot image rejection.
 */
fsw_rc_t fsw_table_init(fsw_table_t *t, const fsw_table_desc_t *desc, const uint8_t *boot,
                        uint32_t boot_len, uint32_t *why);
/*
 * Accepts one chunk. FSW_OK while the upload is incomplete, and FSW_OK with state READY when
 * this chunk completed an image that validated. Any failure discards the candidate (except
 * FSW_TBL_R_BUSY, which keeps the validated one), counts a reject and sets *why.
 */
fsw_rc_t fsw_table_chunk(fsw_table_t *t, const fsw_table_chunk_t *c, uint32_t *why);
/* End of upload (ground's "load done"): FSW_ERR_INCOMPLETE if bytes are still missing. */
fsw_rc_t fsw_table_end(fsw_table_t *t, uint32_t *why);
/* Drops an upload in progress or a validated, uncommitted candidate. Not a reject. */
void     fsw_table_abort(fsw_table_t *t);
/* Step boundary: swaps a READY candidate in (index flip). True when it swapped. */
bool     fsw_table_commit(fsw_table_t *t);
/* Re-checks the active payload CRC. FSW_ERR_CRC (scrub_errs++) on mismatch, FSW_ERR_STATE
   when there is no active table. The image is left as it is; the executive decides. */
fsw_rc_t fsw_table_scrub(fsw_table_t *t);
/*
 * Module-level check hook (no function pointers): when a chunk leaves the table READY, the
 * executive decodes the candidate payload (fsw_table_candidate) into the module's params
 * struct, runs xxx_params_check through its switch on table_id, and on failure calls
 * fsw_table_veto with the module's why: the candidate is dropped, a reject is counted and the
 * reason word becomes FSW_TBL_R_MODULE | (detail & 0xFF) << 8 (FSW_ERR_INVARIANT).
 * fsw_table_veto outside READY: FSW_ERR_STATE, reason NO_UPLOAD, nothing counted.
 */
const uint8_t *fsw_table_candidate(const fsw_table_t *t, uint32_t *len);
fsw_rc_t fsw_table_veto(fsw_table_t *t, uint32_t detail, uint32_t *why);
/* The veto detail of a module check's why word, one rule for every module: 1 + the index of its
   lowest set bit (bits 0..30), FSW_VETO_UNDECODED for an empty word or a candidate that did not
   decode. */
#define FSW_VETO_UNDECODED 0xFFu
uint32_t fsw_table_veto_detail(uint32_t why);
/* Active payload (NULL when none) and its length in *len (may be NULL); decode it with
   fsw_codec at the descriptor's offsets. */
const uint8_t *fsw_table_payload(const fsw_table_t *t, uint32_t *len);
/* Revision of the active image (0 when none). */
uint32_t fsw_table_revision(const fsw_table_t *t);
/* Writes the 16-byte header of an image whose payload (payload_len bytes) already follows it at
   img + FSW_TABLE_HDR_BYTES: table id, layout version, length, revision and the payload CRC.
   The module codecs (fsw/<module>/<prefix>_table.c) build their images with it. */
void     fsw_table_write_header(uint8_t *img, uint16_t table_id, uint16_t layout, uint32_t payload_len,
                                uint32_t revision);

#endif /* FSW_APP_TABLE_H */
