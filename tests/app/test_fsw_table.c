/*
 * fsw_table: chunked upload, validation order and reason codes, double-buffered commit, scrub.
 * Host (CMocka) and Cortex-M3 under QEMU. Every rejection test checks the reason word and that
 * the active image (all FSW_TABLE_CAP_BYTES of its buffer, its length and index) is
 * bit-identical to before, as spec 00 §3.2 and §8 require.
 */
#include "app/fsw_table.h"
#include "app/fsw_codec.h"
#include "fx.h"
#include "tbl_test_desc.h"
#include "ut.h"

#define CODE(why)   ((why) & 0xFFu)
#define DETAIL(why) (((why) >> FSW_TBL_DETAIL_SHIFT) & 0xFFu)

/* Large objects live in static storage: the target test stack is small. */
static fsw_table_t g_t;
static uint8_t g_boot[FSW_TABLE_CAP_BYTES];
static uint8_t g_img[FSW_TABLE_CAP_BYTES + 64u];
static uint8_t g_snap[FSW_TABLE_CAP_BYTES];
static uint32_t g_snap_len;
static uint32_t g_snap_idx;

static uint32_t g_boot_len;

/* Boots g_t from a good revision-1 image. */
static void boot_good(void)
{
    tt_params_t p;
    uint32_t why = 99u;
    tt_defaults(&p);
    g_boot_len = tt_build(g_boot, sizeof g_boot, &p, (uint16_t)TT_ID, (uint16_t)TT_VERSION, 1u);
    UT_CHECK_UEQ(fsw_table_init(&g_t, &tt_desc, g_boot, g_boot_len, &why), FSW_OK);
    UT_CHECK_UEQ(why, FSW_TBL_R_NONE);
    UT_CHECK_UEQ(fsw_table_revision(&g_t), 1u);
}

static void snap_take(void)
{
    uint32_t i;
    for (i = 0u; i < FSW_TABLE_CAP_BYTES; i++) {
        g_snap[i] = g_t.img[g_t.active][i];
    }
    g_snap_len = g_t.active_len;
    g_snap_idx = g_t.active;
}

static int snap_same(void)
{
    uint32_t i;
    int same = (g_t.active_len == g_snap_len) && (g_t.active == g_snap_idx);
    for (i = 0u; i < FSW_TABLE_CAP_BYTES; i++) {
        if (g_t.img[g_t.active][i] != g_snap[i]) {
            same = 0;
        }
    }
    return same;
}

/* Uploads img[0..total) in chunks of `step` bytes (last one shorter), in reverse order when
   `reverse`; stops at the first non-OK result, which it returns with its reason word. */
static fsw_rc_t upload(const uint8_t *img, uint32_t total, uint32_t step, int reverse,
                       uint32_t revision, uint32_t *why)
{
    uint32_t nchunks = (total + step - 1u) / step;
    uint32_t k;
    fsw_rc_t rc = FSW_OK;
    *why = 0u;
    for (k = 0u; (k < nchunks) && (rc == FSW_OK); k++) {
        uint32_t idx = (reverse != 0) ? (nchunks - 1u - k) : k;
        fsw_table_chunk_t c;
        c.table_id = (uint16_t)TT_ID;
        c.revision = revision;
        c.total_len = total;
        c.offset = idx * step;
        c.n = ((total - c.offset) < step) ? (total - c.offset) : step;
        c.data = &img[c.offset];
        rc = fsw_table_chunk(&g_t, &c, why);
    }
    return rc;
}

/* Boots a good table, uploads the defective g_img[0..total) and checks the rejection. */
static void expect_reject(uint32_t total, fsw_rc_t rc_want, uint32_t why_want)
{
    uint32_t why = 0u;
    fsw_rc_t rc;
    boot_good();
    snap_take();
    rc = upload(g_img, total, 16u, 0, 2u, &why);
    if (rc == FSW_OK) {
        UT_CHECK_UEQ(g_t.state, FSW_TBL_S_LOADING);
        rc = fsw_table_end(&g_t, &why);
    }
    UT_CHECK_UEQ(rc, rc_want);
    UT_CHECK_UEQ(why, why_want);
    UT_CHECK_UEQ(g_t.last_reason, why_want);
    UT_CHECK_UEQ(g_t.rejects, 1u);
    UT_CHECK_UEQ(g_t.state, FSW_TBL_S_IDLE);
    UT_CHECK(!fsw_table_commit(&g_t));
    UT_CHECK(snap_same());
    UT_CHECK_UEQ(fsw_table_revision(&g_t), 1u);
    UT_CHECK_UEQ(fsw_table_scrub(&g_t), FSW_OK);
}

static uint32_t build_params(const tt_params_t *p)
{
    return tt_build(g_img, sizeof g_img, p, (uint16_t)TT_ID, (uint16_t)TT_VERSION, 2u);
}

static uint32_t build_default(void)
{
    tt_params_t p;
    tt_defaults(&p);
    return build_params(&p);
}

UT_TEST(boot_image_accepted)
{
    const uint8_t *pl;
    uint32_t len = 0u;
    fsw_rd_t r;
    boot_good();
    UT_UEQ(g_t.state, FSW_TBL_S_IDLE);
    UT_UEQ(g_t.accepts, 1u);
    UT_UEQ(g_t.commits, 1u);
    UT_UEQ(g_t.rejects, 0u);
    pl = fsw_table_payload(&g_t, &len);
    UT_TRUE(pl != NULL);
    UT_UEQ(len, TT_PAYLOAD);
    fsw_rd_init(&r, pl, len);
    fsw_rd_seek(&r, 8u);
    UT_EQ(fsw_rd_i32(&r), -100);
    UT_UEQ(fsw_table_scrub(&g_t), FSW_OK);
}

UT_TEST(no_boot_image_means_no_active_table)
{
    uint32_t len = 7u;
    uint32_t why = 5u;
    UT_UEQ(fsw_table_init(&g_t, &tt_desc, NULL, 0u, &why), FSW_OK);
    UT_UEQ(why, FSW_TBL_R_NONE);
    UT_TRUE(fsw_table_payload(&g_t, &len) == NULL);
    UT_UEQ(len, 0u);
    UT_UEQ(fsw_table_revision(&g_t), 0u);
    UT_UEQ(fsw_table_scrub(&g_t), FSW_ERR_STATE);
}

UT_TEST(bad_boot_image_rejected)
{
    tt_params_t p;
    uint32_t n;
    uint32_t why = 0u;
    tt_defaults(&p);
    p.mode = 4u;
    n = tt_build(g_boot, sizeof g_boot, &p, (uint16_t)TT_ID, (uint16_t)TT_VERSION, 1u);
    UT_UEQ(fsw_table_init(&g_t, &tt_desc, g_boot, n, &why), FSW_ERR_RANGE);
    UT_UEQ(why, FSW_TBL_R_RANGE_HI);
    UT_TRUE(fsw_table_payload(&g_t, NULL) == NULL);
    UT_UEQ(g_t.rejects, 1u);
    UT_UEQ(fsw_table_init(&g_t, &tt_desc, g_boot, 8u, &why), FSW_ERR_CHUNK);
    UT_UEQ(why, FSW_TBL_R_OVERSIZE);
}

UT_TEST(malformed_descriptor_rejected)
{
    static const fsw_field_lim_t f_beyond[1] = {{22u, FSW_FT_U32, 0, 1}};
    static const fsw_field_lim_t f_type[1] = {{0u, 9u, 0, 1}};
    static const fsw_field_lim_t f_minmax[1] = {{0u, FSW_FT_U8, 2, 1}};
    static const fsw_field_lim_t f_ok[1] = {{0u, FSW_FT_U8, 0, 1}};
    static const fsw_field_rel_t r_bad[1] = {{0u, 1u, 0}};
    const fsw_table_desc_t d_beyond = {1u, 1u, 24u, f_beyond, 1u, NULL, 0u};
    const fsw_table_desc_t d_type = {1u, 1u, 24u, f_type, 1u, NULL, 0u};
    const fsw_table_desc_t d_minmax = {1u, 1u, 24u, f_minmax, 1u, NULL, 0u};
    const fsw_table_desc_t d_rel = {1u, 1u, 24u, f_ok, 1u, r_bad, 1u};
    const fsw_table_desc_t d_big = {1u, 1u, FSW_TABLE_CAP_BYTES, f_ok, 1u, NULL, 0u};
    const fsw_table_desc_t d_null = {1u, 1u, 24u, NULL, 1u, NULL, 0u};
    const fsw_table_desc_t d_ok = {1u, 1u, FSW_TABLE_CAP_BYTES - FSW_TABLE_HDR_BYTES, f_ok, 1u,
                                   NULL, 0u};
    fsw_table_chunk_t c = {1u, 1u, 20u, 0u, 4u, g_img};
    uint32_t why = 0u;
    UT_UEQ(fsw_table_init(&g_t, &d_beyond, NULL, 0u, NULL), FSW_ERR_ARG);
    UT_UEQ(fsw_table_init(&g_t, &d_type, NULL, 0u, NULL), FSW_ERR_ARG);
    UT_UEQ(fsw_table_init(&g_t, &d_minmax, NULL, 0u, NULL), FSW_ERR_ARG);
    UT_UEQ(fsw_table_init(&g_t, &d_rel, NULL, 0u, NULL), FSW_ERR_ARG);
    UT_UEQ(fsw_table_init(&g_t, &d_big, NULL, 0u, NULL), FSW_ERR_ARG);
    UT_UEQ(fsw_table_init(&g_t, &d_null, NULL, 0u, NULL), FSW_ERR_ARG);
    UT_UEQ(fsw_table_init(&g_t, NULL, NULL, 0u, NULL), FSW_ERR_ARG);
    UT_UEQ(fsw_table_init(NULL, &tt_desc, NULL, 0u, NULL), FSW_ERR_ARG);
    /* A table whose init failed refuses chunks instead of using a bad descriptor. */
    UT_UEQ(fsw_table_chunk(&g_t, &c, &why), FSW_ERR_ARG);
    UT_UEQ(why, FSW_TBL_R_CHUNK_LEN);
    UT_UEQ(fsw_table_init(&g_t, &d_ok, NULL, 0u, NULL), FSW_OK);
}

UT_TEST(upload_in_order_then_commit_swaps_only_at_commit)
{
    tt_params_t p;
    uint32_t n;
    uint32_t why = 0u;
    const uint8_t *pl;
    fsw_rd_t r;
    boot_good();
    snap_take();
    tt_defaults(&p);
    p.gain_q16 = 262144;   /* at max: inclusive */
    p.quant_q16 = 998;     /* quant + 2 == hyst: relation holds with equality */
    p.hyst_q16 = 1000;
    p.max_count = 4000000000u;
    n = build_params(&p);
    UT_UEQ(upload(g_img, n, 16u, 0, 2u, &why), FSW_OK);
    UT_UEQ(why, FSW_TBL_R_NONE);
    UT_UEQ(g_t.state, FSW_TBL_S_READY);
    UT_UEQ(g_t.accepts, 2u);
    /* Validated but not committed: the active table is still the old one. */
    UT_TRUE(snap_same());
    UT_UEQ(fsw_table_revision(&g_t), 1u);
    UT_UEQ(fsw_table_end(&g_t, &why), FSW_OK);
    UT_TRUE(snap_same());
    UT_TRUE(fsw_table_commit(&g_t));
    UT_UEQ(fsw_table_revision(&g_t), 2u);
    UT_UEQ(g_t.commits, 2u);
    UT_UEQ(g_t.state, FSW_TBL_S_IDLE);
    pl = fsw_table_payload(&g_t, NULL);
    UT_TRUE(pl != NULL);
    fsw_rd_init(&r, pl, TT_PAYLOAD);
    fsw_rd_seek(&r, 8u);
    UT_EQ(fsw_rd_i32(&r), 262144);
    UT_TRUE(!fsw_table_commit(&g_t));    /* nothing more to swap */
    UT_UEQ(fsw_table_scrub(&g_t), FSW_OK);
    UT_UEQ(g_t.rejects, 0u);
}

UT_TEST(chunks_out_of_order_and_duplicates_accepted)
{
    uint32_t n;
    uint32_t why = 0u;
    fsw_table_chunk_t c;
    boot_good();
    n = build_default();
    /* Reverse order, odd chunk size; then a re-sent identical chunk after a new upload. */
    UT_UEQ(upload(g_img, n, 7u, 1, 2u, &why), FSW_OK);
    UT_UEQ(g_t.state, FSW_TBL_S_READY);
    UT_TRUE(fsw_table_commit(&g_t));
    n = tt_build(g_img, sizeof g_img, &(tt_params_t){1u, 0u, 5u, 1u, 0, 0, 2, 10u},
                 (uint16_t)TT_ID, (uint16_t)TT_VERSION, 3u);
    c.table_id = (uint16_t)TT_ID;
    c.revision = 3u;
    c.total_len = n;
    c.offset = 10u;
    c.n = 20u;
    c.data = &g_img[10];
    UT_UEQ(fsw_table_chunk(&g_t, &c, &why), FSW_OK);
    UT_UEQ(fsw_table_chunk(&g_t, &c, &why), FSW_OK);    /* duplicate, identical */
    c.offset = 5u;                                      /* overlaps 10..14 consistently */
    c.n = 10u;
    c.data = &g_img[5];
    UT_UEQ(fsw_table_chunk(&g_t, &c, &why), FSW_OK);
    c.offset = 30u;
    c.n = n - 30u;
    c.data = &g_img[30];
    UT_UEQ(fsw_table_chunk(&g_t, &c, &why), FSW_OK);
    UT_UEQ(g_t.state, FSW_TBL_S_LOADING);
    c.offset = 0u;
    c.n = 5u;
    c.data = &g_img[0];
    UT_UEQ(fsw_table_chunk(&g_t, &c, &why), FSW_OK);
    UT_UEQ(g_t.state, FSW_TBL_S_READY);
    UT_TRUE(fsw_table_commit(&g_t));
    UT_UEQ(fsw_table_revision(&g_t), 3u);
    UT_UEQ(g_t.rejects, 0u);
}

UT_TEST(reject_bad_crc)
{
    uint32_t n = build_default();
    g_img[FSW_TABLE_HDR_BYTES + 5u] ^= 0x10u;   /* payload bit flip, header CRC left stale */
    expect_reject(n, FSW_ERR_CRC, FSW_TBL_R_CRC);
    n = build_default();
    g_img[12] ^= 0x01u;                         /* flip in the CRC field itself */
    expect_reject(n, FSW_ERR_CRC, FSW_TBL_R_CRC);
}

UT_TEST(reject_wrong_id)
{
    tt_params_t p;
    uint32_t n;
    tt_defaults(&p);
    n = tt_build(g_img, sizeof g_img, &p, 0x7E58u, (uint16_t)TT_VERSION, 2u);
    expect_reject(n, FSW_ERR_HEADER, FSW_TBL_R_ID);
}

UT_TEST(reject_chunk_for_other_table)
{
    uint32_t why = 0u;
    fsw_table_chunk_t c;
    uint32_t n = build_default();
    boot_good();
    snap_take();
    c.table_id = 0x1234u;
    c.revision = 2u;
    c.total_len = n;
    c.offset = 0u;
    c.n = n;
    c.data = g_img;
    UT_UEQ(fsw_table_chunk(&g_t, &c, &why), FSW_ERR_CHUNK);
    UT_UEQ(why, FSW_TBL_R_UPLOAD_ID);
    UT_TRUE(snap_same());
}

UT_TEST(reject_wrong_layout_version)
{
    tt_params_t p;
    uint32_t n;
    tt_defaults(&p);
    n = tt_build(g_img, sizeof g_img, &p, (uint16_t)TT_ID, (uint16_t)(TT_VERSION + 1u), 2u);
    expect_reject(n, FSW_ERR_HEADER, FSW_TBL_R_VERSION);
}

UT_TEST(reject_length_mismatch)
{
    fsw_wr_t w;
    uint32_t n = build_default();
    /* Header length disagrees with the bytes uploaded: a decode failure. */
    fsw_wr_init(&w, g_img, FSW_TABLE_HDR_BYTES);
    w.pos = 4u;
    fsw_wr_u32(&w, TT_PAYLOAD - 1u);
    tt_fix_crc(g_img, n);
    expect_reject(n, FSW_ERR_DECODE, FSW_TBL_R_DECODE);
    /* Consistent header and CRC, but 4 payload bytes more than the layout has. */
    n = build_default();
    g_img[n] = 0u;
    g_img[n + 1u] = 0u;
    g_img[n + 2u] = 0u;
    g_img[n + 3u] = 0u;
    fsw_wr_init(&w, g_img, FSW_TABLE_HDR_BYTES);
    w.pos = 4u;
    fsw_wr_u32(&w, TT_PAYLOAD + 4u);
    tt_fix_crc(g_img, n + 4u);
    expect_reject(n + 4u, FSW_ERR_HEADER, FSW_TBL_R_LENGTH);
    /* Shorter than a header. */
    n = build_default();
    expect_reject(FSW_TABLE_HDR_BYTES - 1u, FSW_ERR_CHUNK, FSW_TBL_R_OVERSIZE);
}

UT_TEST(reject_field_out_of_range)
{
    tt_params_t p;
    tt_defaults(&p);
    p.period_ms = 0u;                                   /* field 2 below min */
    expect_reject(build_params(&p), FSW_ERR_RANGE, FSW_TBL_R_RANGE_LO | (2u << 8));
    tt_defaults(&p);
    p.period_ms = 1001u;                                /* field 2 above max */
    expect_reject(build_params(&p), FSW_ERR_RANGE, FSW_TBL_R_RANGE_HI | (2u << 8));
    tt_defaults(&p);
    p.gain_q16 = -262145;                               /* signed field 4 below min */
    expect_reject(build_params(&p), FSW_ERR_RANGE, FSW_TBL_R_RANGE_LO | (4u << 8));
    tt_defaults(&p);
    p.gain_q16 = INT32_MIN;
    expect_reject(build_params(&p), FSW_ERR_RANGE, FSW_TBL_R_RANGE_LO | (4u << 8));
    tt_defaults(&p);
    p.max_count = UINT32_MAX;                           /* u32 above a max beyond INT32_MAX */
    expect_reject(build_params(&p), FSW_ERR_RANGE, FSW_TBL_R_RANGE_HI | (7u << 8));
    tt_defaults(&p);
    p.max_count = 9u;
    expect_reject(build_params(&p), FSW_ERR_RANGE, FSW_TBL_R_RANGE_LO | (7u << 8));
    /* Two bad fields: the lowest index is reported. */
    tt_defaults(&p);
    p.mode = 4u;
    p.hyst_q16 = -1;
    expect_reject(build_params(&p), FSW_ERR_RANGE, FSW_TBL_R_RANGE_HI | (0u << 8));
}

UT_TEST(reject_invariant_violated)
{
    tt_params_t p;
    tt_defaults(&p);
    p.quant_q16 = 999;                                  /* 999 + 2 > 1000 */
    p.hyst_q16 = 1000;
    expect_reject(build_params(&p), FSW_ERR_INVARIANT, FSW_TBL_R_INVARIANT | (0u << 8));
    tt_defaults(&p);
    p.stale_max = 1000u;                                /* 1000 + 1 > 1000 */
    p.max_count = 1000u;
    expect_reject(build_params(&p), FSW_ERR_INVARIANT, FSW_TBL_R_INVARIANT | (1u << 8));
    /* Ranges are checked before invariants. */
    tt_defaults(&p);
    p.quant_q16 = 1000;
    p.hyst_q16 = 0;
    p.period_ms = 0u;
    expect_reject(build_params(&p), FSW_ERR_RANGE, FSW_TBL_R_RANGE_LO | (2u << 8));
}

UT_TEST(validation_order_crc_before_header)
{
    tt_params_t p;
    uint32_t n;
    tt_defaults(&p);
    p.mode = 7u;
    n = tt_build(g_img, sizeof g_img, &p, 0x1111u, 9u, 2u);
    g_img[FSW_TABLE_HDR_BYTES] ^= 0x80u;
    expect_reject(n, FSW_ERR_CRC, FSW_TBL_R_CRC);
    n = tt_build(g_img, sizeof g_img, &p, 0x1111u, 9u, 2u);
    expect_reject(n, FSW_ERR_HEADER, FSW_TBL_R_ID);
    n = tt_build(g_img, sizeof g_img, &p, (uint16_t)TT_ID, 9u, 2u);
    expect_reject(n, FSW_ERR_HEADER, FSW_TBL_R_VERSION);
}

UT_TEST(reject_missing_chunk)
{
    uint32_t why = 0u;
    fsw_table_chunk_t c;
    uint32_t n = build_default();
    boot_good();
    snap_take();
    c.table_id = (uint16_t)TT_ID;
    c.revision = 2u;
    c.total_len = n;
    c.offset = 0u;
    c.n = 16u;
    c.data = g_img;
    UT_UEQ(fsw_table_chunk(&g_t, &c, &why), FSW_OK);
    c.offset = 24u;                                     /* bytes 16..23 never sent */
    c.n = n - 24u;
    c.data = &g_img[24];
    UT_UEQ(fsw_table_chunk(&g_t, &c, &why), FSW_OK);
    UT_UEQ(g_t.state, FSW_TBL_S_LOADING);
    UT_UEQ(fsw_table_end(&g_t, &why), FSW_ERR_INCOMPLETE);
    UT_UEQ(why, FSW_TBL_R_MISSING);
    UT_UEQ(g_t.rejects, 1u);
    UT_TRUE(snap_same());
    /* The upload is gone: another end reports "no upload" without counting again. */
    UT_UEQ(fsw_table_end(&g_t, &why), FSW_ERR_STATE);
    UT_UEQ(why, FSW_TBL_R_NO_UPLOAD);
    UT_UEQ(g_t.rejects, 1u);
    UT_UEQ(g_t.last_reason, FSW_TBL_R_MISSING);
}

/* Starts an upload of the default image with its first 16 bytes. */
static void start_upload(uint32_t n, fsw_table_chunk_t *c)
{
    uint32_t why = 0u;
    c->table_id = (uint16_t)TT_ID;
    c->revision = 2u;
    c->total_len = n;
    c->offset = 0u;
    c->n = 16u;
    c->data = g_img;
    UT_CHECK_UEQ(fsw_table_chunk(&g_t, c, &why), FSW_OK);
}

/* Sends c (expected to be refused with why_want) and checks the aftermath. */
static void expect_chunk_reject(const fsw_table_chunk_t *c, fsw_rc_t rc_want, uint32_t why_want)
{
    uint32_t why = 0u;
    UT_CHECK_UEQ(fsw_table_chunk(&g_t, c, &why), rc_want);
    UT_CHECK_UEQ(why, why_want);
    UT_CHECK_UEQ(g_t.rejects, 1u);
    UT_CHECK_UEQ(g_t.state, FSW_TBL_S_IDLE);
    UT_CHECK(snap_same());
}

UT_TEST(reject_overlap_inconsistent)
{
    fsw_table_chunk_t c;
    static uint8_t other[8];
    uint32_t n = build_default();
    uint32_t i;
    boot_good();
    snap_take();
    start_upload(n, &c);
    for (i = 0u; i < 8u; i++) {
        other[i] = g_img[12u + i];
    }
    other[3] ^= 0x01u;                                  /* image byte 15 differs */
    c.offset = 12u;
    c.n = 8u;
    c.data = other;
    expect_chunk_reject(&c, FSW_ERR_CHUNK, FSW_TBL_R_OVERLAP);
}

UT_TEST(reject_offset_beyond_capacity_or_image)
{
    fsw_table_chunk_t c;
    uint32_t n = build_default();
    boot_good();
    snap_take();
    start_upload(n, &c);
    c.offset = FSW_TABLE_CAP_BYTES + 100u;
    c.n = 4u;
    expect_chunk_reject(&c, FSW_ERR_CHUNK, FSW_TBL_R_OFFSET);
    boot_good();
    snap_take();
    start_upload(n, &c);
    c.offset = n - 3u;                                  /* last chunk runs past total_len */
    c.n = 4u;
    expect_chunk_reject(&c, FSW_ERR_CHUNK, FSW_TBL_R_OFFSET);
    boot_good();
    snap_take();
    start_upload(n, &c);
    c.offset = UINT32_MAX - 1u;                         /* offset + n would wrap */
    c.n = 4u;
    expect_chunk_reject(&c, FSW_ERR_CHUNK, FSW_TBL_R_OFFSET);
}

UT_TEST(reject_total_len_change_mid_upload)
{
    fsw_table_chunk_t c;
    uint32_t n = build_default();
    boot_good();
    snap_take();
    start_upload(n, &c);
    c.offset = 16u;
    c.total_len = n + 4u;
    c.data = &g_img[16];
    expect_chunk_reject(&c, FSW_ERR_CHUNK, FSW_TBL_R_TOTAL_CHANGED);
    boot_good();
    snap_take();
    start_upload(n, &c);
    c.offset = 16u;
    c.revision = 3u;
    c.data = &g_img[16];
    expect_chunk_reject(&c, FSW_ERR_CHUNK, FSW_TBL_R_REV_CHANGED);
}

UT_TEST(reject_oversize_and_bad_chunk)
{
    fsw_table_chunk_t c = {(uint16_t)TT_ID, 2u, FSW_TABLE_CAP_BYTES + 1u, 0u, 16u, g_img};
    boot_good();
    snap_take();
    expect_chunk_reject(&c, FSW_ERR_CHUNK, FSW_TBL_R_OVERSIZE);
    boot_good();
    c.total_len = TT_TOTAL;
    c.n = 0u;
    expect_chunk_reject(&c, FSW_ERR_ARG, FSW_TBL_R_CHUNK_LEN);
    boot_good();
    c.n = FSW_TABLE_CHUNK_MAX + 1u;
    expect_chunk_reject(&c, FSW_ERR_ARG, FSW_TBL_R_CHUNK_LEN);
    boot_good();
    c.n = 4u;
    c.data = NULL;
    expect_chunk_reject(&c, FSW_ERR_ARG, FSW_TBL_R_CHUNK_LEN);
    boot_good();
    expect_chunk_reject(NULL, FSW_ERR_ARG, FSW_TBL_R_CHUNK_LEN);
}

UT_TEST(busy_while_candidate_ready)
{
    uint32_t why = 0u;
    fsw_table_chunk_t c;
    uint32_t n = build_default();
    boot_good();
    UT_UEQ(upload(g_img, n, 64u, 0, 2u, &why), FSW_OK);
    UT_UEQ(g_t.state, FSW_TBL_S_READY);
    c.table_id = (uint16_t)TT_ID;
    c.revision = 3u;
    c.total_len = n;
    c.offset = 0u;
    c.n = 4u;
    c.data = g_img;
    /* A new upload must wait for the commit; the validated candidate survives. */
    UT_UEQ(fsw_table_chunk(&g_t, &c, &why), FSW_ERR_STATE);
    UT_UEQ(why, FSW_TBL_R_BUSY);
    UT_UEQ(g_t.rejects, 0u);
    UT_UEQ(g_t.state, FSW_TBL_S_READY);
    UT_TRUE(fsw_table_commit(&g_t));
    UT_UEQ(fsw_table_revision(&g_t), 2u);
    /* Abort drops a ready candidate without touching the active table or the counters. */
    n = tt_build(g_img, sizeof g_img, &(tt_params_t){0u, 0u, 1u, 1u, 0, 0, 2, 10u},
                 (uint16_t)TT_ID, (uint16_t)TT_VERSION, 4u);
    UT_UEQ(upload(g_img, n, 64u, 0, 4u, &why), FSW_OK);
    UT_UEQ(g_t.state, FSW_TBL_S_READY);
    fsw_table_abort(&g_t);
    UT_TRUE(!fsw_table_commit(&g_t));
    UT_UEQ(fsw_table_revision(&g_t), 2u);
    UT_UEQ(g_t.rejects, 0u);
}

UT_TEST(module_veto_drops_ready_candidate)
{
    uint32_t why = 0u;
    uint32_t len = 0u;
    const uint8_t *cand;
    fsw_rd_t r;
    tt_params_t p;
    uint32_t n;
    boot_good();
    snap_take();
    UT_TRUE(fsw_table_candidate(&g_t, &len) == NULL);   /* nothing validated yet */
    UT_UEQ(len, 0u);
    UT_UEQ(fsw_table_veto(&g_t, 3u, &why), FSW_ERR_STATE);
    UT_UEQ(why, FSW_TBL_R_NO_UPLOAD);
    UT_UEQ(g_t.rejects, 0u);
    tt_defaults(&p);
    p.period_ms = 250u;
    n = build_params(&p);
    UT_UEQ(upload(g_img, n, 32u, 0, 2u, &why), FSW_OK);
    UT_UEQ(g_t.state, FSW_TBL_S_READY);
    /* The executive decodes the candidate (here: one field) and its module check says no. */
    cand = fsw_table_candidate(&g_t, &len);
    UT_TRUE(cand != NULL);
    UT_UEQ(len, TT_PAYLOAD);
    fsw_rd_init(&r, cand, len);
    fsw_rd_seek(&r, 2u);
    UT_UEQ(fsw_rd_u16(&r), 250u);
    UT_UEQ(fsw_table_veto(&g_t, 0x1234u, &why), FSW_ERR_INVARIANT);
    UT_UEQ(why, FSW_TBL_R_MODULE | (0x34u << 8));
    UT_UEQ(g_t.last_reason, why);
    UT_UEQ(g_t.rejects, 1u);
    UT_UEQ(g_t.state, FSW_TBL_S_IDLE);
    UT_TRUE(!fsw_table_commit(&g_t));
    UT_TRUE(snap_same());
    UT_TRUE(fsw_table_candidate(&g_t, NULL) == NULL);
}

UT_TEST(recovery_after_reject_and_counter_saturates)
{
    uint32_t why = 0u;
    uint32_t n = build_default();
    boot_good();
    g_img[FSW_TABLE_HDR_BYTES] ^= 0xFFu;
    g_t.rejects = UINT32_MAX;
    UT_UEQ(upload(g_img, n, 16u, 0, 2u, &why), FSW_ERR_CRC);
    UT_UEQ(g_t.rejects, UINT32_MAX);                   /* saturating, never wraps */
    /* The next upload starts clean (no stale arrival bits from the rejected one). */
    n = build_default();
    UT_UEQ(upload(g_img, n, 16u, 1, 2u, &why), FSW_OK);
    UT_UEQ(g_t.state, FSW_TBL_S_READY);
    UT_TRUE(fsw_table_commit(&g_t));
    UT_UEQ(fsw_table_revision(&g_t), 2u);
}

UT_TEST(scrub_detects_flipped_bit)
{
    uint32_t k;
    uint32_t errs = 0u;
    boot_good();
    UT_UEQ(fsw_table_scrub(&g_t), FSW_OK);
    /* Every single-bit flip in the active image (header fields the loader relies on and the
       payload) is caught; the revision field is informative and not covered. */
    for (k = 0u; k < TT_TOTAL * 8u; k++) {
        uint32_t byte = k / 8u;
        uint8_t mask = (uint8_t)(1u << (k % 8u));
        if ((byte >= 8u) && (byte < 12u)) {
            continue;                                   /* revision */
        }
        g_t.img[g_t.active][byte] ^= mask;
        UT_CHECK_UEQ(fsw_table_scrub(&g_t), FSW_ERR_CRC);
        g_t.img[g_t.active][byte] ^= mask;
        errs++;
        UT_CHECK_UEQ(g_t.scrub_errs, errs);
        UT_CHECK_UEQ(fsw_table_scrub(&g_t), FSW_OK);
    }
    UT_UEQ(g_t.last_reason, FSW_TBL_R_SCRUB);
    UT_UEQ(g_t.scrub_errs, (TT_TOTAL - 4u) * 8u);
}

int main(void)
{
    UT_CASES(cases) = {
        UT_CASE(boot_image_accepted), UT_CASE(no_boot_image_means_no_active_table),
        UT_CASE(bad_boot_image_rejected), UT_CASE(malformed_descriptor_rejected),
        UT_CASE(upload_in_order_then_commit_swaps_only_at_commit),
        UT_CASE(chunks_out_of_order_and_duplicates_accepted), UT_CASE(reject_bad_crc),
        UT_CASE(reject_wrong_id), UT_CASE(reject_chunk_for_other_table),
        UT_CASE(reject_wrong_layout_version), UT_CASE(reject_length_mismatch),
        UT_CASE(reject_field_out_of_range), UT_CASE(reject_invariant_violated),
        UT_CASE(validation_order_crc_before_header), UT_CASE(reject_missing_chunk),
        UT_CASE(reject_overlap_inconsistent), UT_CASE(reject_offset_beyond_capacity_or_image),
        UT_CASE(reject_total_len_change_mid_upload), UT_CASE(reject_oversize_and_bad_chunk),
        UT_CASE(busy_while_candidate_ready), UT_CASE(module_veto_drops_ready_candidate),
        UT_CASE(recovery_after_reject_and_counter_saturates),
        UT_CASE(scrub_detects_flipped_bit),
    };
    return UT_RUN("fsw_table", cases);
}
