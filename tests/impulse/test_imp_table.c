/*
 * The impulse table on the wire (fsw/impulse/imp_table.c; spec 00 §3.2, 50-impulse §5.7): the
 * three generated boot tables encode, load through the loader's checks and decode bit-identical;
 * the descriptor covers the payload byte for byte; every field's [min, max] is enforced with the
 * reason word and field index (and the encoder writes each imp_params_t member where the
 * descriptor checks it); the relations; CRC, header and length errors; argument checks; a
 * decoded table passes imp_params_check. Host and target.
 */
#include "imp_mission.h"
#include "app/fsw_codec.h"
#include "imp_tables.h"
#include "imp_tbl_util.h"
#include "fx.h"
#include "ut.h"

#define CODE(why)   ((why) & 0xFFu)
#define DETAIL(why) (((why) >> FSW_TBL_DETAIL_SHIFT) & 0xFFu)
#define IMG_BYTES   (FSW_TABLE_HDR_BYTES + IMP_TBL_PAYLOAD)

/* Large objects live in static storage: the target test stack is small. */
static fsw_table_t g_t;
static uint8_t g_img[FSW_TABLE_CAP_BYTES];
static uint8_t g_img2[FSW_TABLE_CAP_BYTES];
static imp_params_t g_p;
static imp_params_t g_q;

static const imp_params_t *const BOOT[3] = {&IMP_TBL_DEFAULT, &IMP_TBL_1S, &IMP_TBL_SUB1MS};

static void fix_crc(uint8_t *img, uint32_t payload_len)
{
    fsw_wr_t w;
    fsw_wr_init(&w, &img[12], 4u);
    fsw_wr_u32(&w, fx_crc32(0u, &img[FSW_TABLE_HDR_BYTES], payload_len));
}

/* Loads img[0..n) as a boot image of a fresh loader; returns the reason word. */
static uint32_t load(const uint8_t *img, uint32_t n)
{
    uint32_t why = 0xFFFFFFFFu;
    (void)fsw_table_init(&g_t, &IMP_TBL_DESC, img, n, &why);
    return why;
}

/* Encodes p (revision 9) and loads it; returns the reason word. */
static uint32_t load_params(const imp_params_t *p)
{
    uint32_t n = imp_table_encode(p, 9u, g_img, sizeof(g_img));
    UT_CHECK_UEQ(n, IMG_BYTES);
    return load(g_img, n);
}

UT_TEST(boot_tables_round_trip_bit_identical)
{
    uint32_t k;
    for (k = 0u; k < 3u; k++) {
        fsw_rd_t r;
        uint32_t len = 0u;
        uint32_t why = 0u;
        uint32_t i;
        const uint8_t *pl;
        UT_CHECK_UEQ(imp_table_encode(BOOT[k], 0x01020304u, g_img, sizeof(g_img)), IMG_BYTES);
        fsw_rd_init(&r, g_img, FSW_TABLE_HDR_BYTES);
        UT_CHECK_UEQ(fsw_rd_u16(&r), IMP_TBL_ID);
        UT_CHECK_UEQ(fsw_rd_u16(&r), IMP_TBL_LAYOUT);
        UT_CHECK_UEQ(fsw_rd_u32(&r), IMP_TBL_PAYLOAD);
        UT_CHECK_UEQ(fsw_rd_u32(&r), 0x01020304u);
        UT_CHECK_UEQ(fsw_rd_u32(&r), fx_crc32(0u, &g_img[FSW_TABLE_HDR_BYTES], IMP_TBL_PAYLOAD));
        /* through the loader's checks */
        UT_CHECK_UEQ(fsw_table_init(&g_t, &IMP_TBL_DESC, g_img, IMG_BYTES, &why), FSW_OK);
        UT_CHECK_UEQ(why, FSW_TBL_R_NONE);
        UT_CHECK_UEQ(fsw_table_revision(&g_t), 0x01020304u);
        pl = fsw_table_payload(&g_t, &len);
        UT_CHECK(pl != NULL);
        UT_CHECK_UEQ(len, IMP_TBL_PAYLOAD);
        /* decode: every field, and the whole struct byte for byte (imp_params_t has no padding) */
        UT_CHECK_UEQ(imp_table_decode(pl, len, 1u, &g_p), FSW_OK);
        UT_CHECK_UEQ(imp_params_diff(&g_p, BOOT[k], 1), 0u);
        for (i = 0u; i < (uint32_t)sizeof(imp_params_t); i++) {
            UT_CHECK_UEQ(((const uint8_t *)&g_p)[i], ((const uint8_t *)BOOT[k])[i]);
        }
        /* a decoded table passes the module check */
        UT_CHECK_UEQ(imp_params_check(&g_p, &why), FSW_OK);
        UT_CHECK_UEQ(why, 0u);
        /* re-encoding the decoded table gives the same image */
        UT_CHECK_UEQ(imp_table_encode(&g_p, 0x01020304u, g_img2, sizeof(g_img2)), IMG_BYTES);
        for (i = 0u; i < IMG_BYTES; i++) {
            UT_CHECK_UEQ(g_img2[i], g_img[i]);
        }
    }
}

UT_TEST(decoded_revision_comes_from_the_header)
{
    uint32_t len = 0u;
    const uint8_t *pl;
    g_p = IMP_TBL_DEFAULT;
    g_p.revision = 55u;                              /* not on the wire */
    UT_UEQ(load_params(&g_p), FSW_TBL_R_NONE);
    pl = fsw_table_payload(&g_t, &len);
    UT_UEQ(imp_table_decode(pl, len, fsw_table_revision(&g_t), &g_q), FSW_OK);
    UT_UEQ(g_q.revision, 9u);
    g_q.revision = 55u;
    UT_UEQ(imp_params_diff(&g_q, &g_p, 1), 0u);
}

UT_TEST(descriptor_covers_the_payload_byte_for_byte)
{
    uint32_t i;
    uint32_t off = 0u;
    const fsw_table_desc_t *d = &IMP_TBL_DESC;
    UT_UEQ(d->table_id, IMP_TBL_ID);
    UT_UEQ(d->layout_version, IMP_TBL_LAYOUT);
    UT_UEQ(d->payload_len, IMP_TBL_PAYLOAD);
    UT_UEQ(d->n_fields, IMP_TBL_N_FIELDS);
    UT_UEQ(d->n_rels, 5u);
    for (i = 0u; i < d->n_fields; i++) {
        uint32_t w = (d->fields[i].type == FSW_FT_U8) ? 1u : 4u;
        UT_CHECK_UEQ(d->fields[i].offset, off);      /* contiguous, in index order */
        UT_CHECK(d->fields[i].type != FSW_FT_U16);   /* the layout has no u16 */
        UT_CHECK_LE(d->fields[i].min, d->fields[i].max);
        off += w;
    }
    UT_UEQ(off, IMP_TBL_PAYLOAD);
    /* bounds that repeat imp_params_check / spec 50 exactly */
    UT_EQ(d->fields[7].max, IMP_ITER_CAP);                     /* max_iter */
    UT_EQ(d->fields[8].min, IMP_ROUND_UNITS);                  /* plan_iter_per_step */
    UT_EQ(d->fields[16].min, 107374182);                       /* tau_f >= 0.2 rad */
    UT_EQ(d->fields[17].max, 1073741824);                      /* tau_f <= 2.0 rad */
    UT_EQ(d->fields[19].min, 858993459);                       /* alpha >= 0.8 */
    UT_EQ(d->fields[24].max, 1288490189);                      /* alpha <= 1.2 */
    UT_EQ(d->fields[29].max, 0);                               /* spare: zero */
    UT_EQ(d->fields[51].max, 0);                               /* spare2[2]: zero */
    /* and a fresh loader accepts the descriptor */
    UT_UEQ(fsw_table_init(&g_t, &IMP_TBL_DESC, NULL, 0u, NULL), FSW_OK);
}

/* For every field: one below min and one above max (when the member can hold them) are refused
   with RANGE_LO / RANGE_HI and the field index; min and max themselves pass the range check. */
UT_TEST(every_field_range_is_enforced_with_its_index)
{
    uint32_t i;
    uint32_t tried = 0u;
    const fsw_table_desc_t *d = &IMP_TBL_DESC;
    for (i = 0u; i < d->n_fields; i++) {
        int64_t lo = d->fields[i].min;
        int64_t hi = d->fields[i].max;
        uint32_t why;
        if (imp_field_fits(i, lo - 1)) {
            g_p = IMP_TBL_DEFAULT;
            UT_CHECK(imp_field_set(&g_p, i, lo - 1));
            why = load_params(&g_p);
            UT_CHECK_UEQ(why, FSW_TBL_R_RANGE_LO | (i << FSW_TBL_DETAIL_SHIFT));
            UT_CHECK_UEQ(fsw_table_payload(&g_t, NULL) == NULL, 1u);
            tried++;
        }
        if (imp_field_fits(i, hi + 1)) {
            g_p = IMP_TBL_DEFAULT;
            UT_CHECK(imp_field_set(&g_p, i, hi + 1));
            why = load_params(&g_p);
            UT_CHECK_UEQ(why, FSW_TBL_R_RANGE_HI | (i << FSW_TBL_DETAIL_SHIFT));
            tried++;
        }
        g_p = IMP_TBL_DEFAULT;
        UT_CHECK(imp_field_set(&g_p, i, lo));
        why = load_params(&g_p);
        UT_CHECK((CODE(why) != FSW_TBL_R_RANGE_LO) && (CODE(why) != FSW_TBL_R_RANGE_HI));
        g_p = IMP_TBL_DEFAULT;
        UT_CHECK(imp_field_set(&g_p, i, hi));
        why = load_params(&g_p);
        UT_CHECK((CODE(why) != FSW_TBL_R_RANGE_LO) && (CODE(why) != FSW_TBL_R_RANGE_HI));
    }
    UT_LE(80, tried);
    /* the first failing field is reported (index order) */
    g_p = IMP_TBL_DEFAULT;
    g_p.nav_gate_pos_q28 = 0;
    g_p.max_iter = 17u;
    UT_UEQ(load_params(&g_p), FSW_TBL_R_RANGE_HI | (7u << FSW_TBL_DETAIL_SHIFT));
}

UT_TEST(relations_are_enforced_with_their_index)
{
    /* 0: t_min_us <= period_us */
    g_p = IMP_TBL_DEFAULT;
    g_p.t_min_us = g_p.period_us + 1u;
    UT_UEQ(load_params(&g_p), FSW_TBL_R_INVARIANT | (0u << FSW_TBL_DETAIL_SHIFT));
    g_p.t_min_us = g_p.period_us;                     /* equality holds */
    UT_UEQ(load_params(&g_p), FSW_TBL_R_NONE);
    /* 1: subtick_us <= period_us */
    g_p = IMP_TBL_SUB1MS;
    g_p.subtick_us = g_p.period_us + 1u;
    UT_UEQ(load_params(&g_p), FSW_TBL_R_INVARIANT | (1u << FSW_TBL_DETAIL_SHIFT));
    /* 2: rho_warn <= rho_reject */
    g_p = IMP_TBL_DEFAULT;
    g_p.rho_warn_q28 = g_p.rho_reject_q28 + 1;
    UT_UEQ(load_params(&g_p), FSW_TBL_R_INVARIANT | (2u << FSW_TBL_DETAIL_SHIFT));
    g_p.rho_warn_q28 = g_p.rho_reject_q28;
    UT_UEQ(load_params(&g_p), FSW_TBL_R_NONE);
    /* 3: tauf_min <= tauf_max */
    g_p = IMP_TBL_DEFAULT;
    g_p.tauf_max_q29 = 200000000;
    g_p.tauf_min_q29 = 200000001;
    UT_UEQ(load_params(&g_p), FSW_TBL_R_INVARIANT | (3u << FSW_TBL_DETAIL_SHIFT));
    /* 4: u_cal <= u_uncal */
    g_p = IMP_TBL_DEFAULT;
    g_p.u_cal_q30 = g_p.u_uncal_q30 + 1;
    UT_UEQ(load_params(&g_p), FSW_TBL_R_INVARIANT | (4u << FSW_TBL_DETAIL_SHIFT));
    /* the relation failures are also what imp_params_check refuses */
    {
        uint32_t why = 0u;
        UT_TRUE(imp_params_check(&g_p, &why) != FSW_OK);
        UT_TRUE((why & IMP_WHY_CAL) != 0u);
    }
}

UT_TEST(crc_header_and_length_errors)
{
    fsw_wr_t w;
    uint32_t i;
    /* CRC: every payload byte, one bit each */
    for (i = 0u; i < IMP_TBL_PAYLOAD; i++) {
        (void)imp_table_encode(&IMP_TBL_DEFAULT, 1u, g_img, sizeof(g_img));
        g_img[FSW_TABLE_HDR_BYTES + i] ^= (uint8_t)(1u << (i & 7u));
        UT_CHECK_UEQ(load(g_img, IMG_BYTES), FSW_TBL_R_CRC);
    }
    /* header table_id (CRC still right: it covers the payload only) */
    (void)imp_table_encode(&IMP_TBL_DEFAULT, 1u, g_img, sizeof(g_img));
    fsw_wr_init(&w, g_img, 2u);
    fsw_wr_u16(&w, (uint16_t)0x0B01u);   /* the observer table's id */
    UT_UEQ(load(g_img, IMG_BYTES), FSW_TBL_R_ID);
    /* layout version */
    (void)imp_table_encode(&IMP_TBL_DEFAULT, 1u, g_img, sizeof(g_img));
    fsw_wr_init(&w, &g_img[2], 2u);
    fsw_wr_u16(&w, (uint16_t)2u);
    UT_UEQ(load(g_img, IMG_BYTES), FSW_TBL_R_VERSION);
    /* payload one byte short, header consistent and CRC right: LENGTH */
    (void)imp_table_encode(&IMP_TBL_DEFAULT, 1u, g_img, sizeof(g_img));
    fsw_wr_init(&w, &g_img[4], 4u);
    fsw_wr_u32(&w, IMP_TBL_PAYLOAD - 1u);
    fix_crc(g_img, IMP_TBL_PAYLOAD - 1u);
    UT_UEQ(load(g_img, IMG_BYTES - 1u), FSW_TBL_R_LENGTH);
    /* header length disagrees with the image: DECODE */
    (void)imp_table_encode(&IMP_TBL_DEFAULT, 1u, g_img, sizeof(g_img));
    UT_UEQ(load(g_img, IMG_BYTES - 1u), FSW_TBL_R_DECODE);
    /* a byte too many */
    (void)imp_table_encode(&IMP_TBL_DEFAULT, 1u, g_img, sizeof(g_img));
    g_img[IMG_BYTES] = 0u;
    fsw_wr_init(&w, &g_img[4], 4u);
    fsw_wr_u32(&w, IMP_TBL_PAYLOAD + 1u);
    fix_crc(g_img, IMP_TBL_PAYLOAD + 1u);
    UT_UEQ(load(g_img, IMG_BYTES + 1u), FSW_TBL_R_LENGTH);
}

UT_TEST(encode_and_decode_check_their_arguments)
{
    uint32_t i;
    for (i = 0u; i < sizeof(g_img); i++) {
        g_img[i] = 0xA5u;
    }
    UT_UEQ(imp_table_encode(&IMP_TBL_DEFAULT, 1u, g_img, IMG_BYTES - 1u), 0u);
    UT_UEQ(imp_table_encode(NULL, 1u, g_img, sizeof(g_img)), 0u);
    UT_UEQ(imp_table_encode(&IMP_TBL_DEFAULT, 1u, NULL, sizeof(g_img)), 0u);
    for (i = 0u; i < sizeof(g_img); i++) {
        UT_CHECK_UEQ(g_img[i], 0xA5u);               /* nothing written */
    }
    UT_UEQ(imp_table_encode(&IMP_TBL_DEFAULT, 1u, g_img, IMG_BYTES), IMG_BYTES);
    UT_UEQ(g_img[IMG_BYTES], 0xA5u);                 /* not one byte beyond */
    UT_UEQ(imp_table_decode(&g_img[FSW_TABLE_HDR_BYTES], IMP_TBL_PAYLOAD - 1u, 1u, &g_p), FSW_ERR_ARG);
    UT_UEQ(imp_table_decode(&g_img[FSW_TABLE_HDR_BYTES], IMP_TBL_PAYLOAD + 1u, 1u, &g_p), FSW_ERR_ARG);
    UT_UEQ(imp_table_decode(NULL, IMP_TBL_PAYLOAD, 1u, &g_p), FSW_ERR_ARG);
    UT_UEQ(imp_table_decode(&g_img[FSW_TABLE_HDR_BYTES], IMP_TBL_PAYLOAD, 1u, NULL), FSW_ERR_ARG);
}

/* A chunked upload (13-byte chunks, in reverse order) commits a payload byte-identical to the
   encoder's, and the decoded candidate equals the source table. */
UT_TEST(chunked_upload_commits_the_encoded_table)
{
    uint32_t why = 0u;
    uint32_t off;
    uint32_t len = 0u;
    uint32_t i;
    const uint8_t *pl;
    (void)imp_table_encode(&IMP_TBL_DEFAULT, 1u, g_img2, sizeof(g_img2));
    UT_UEQ(fsw_table_init(&g_t, &IMP_TBL_DESC, g_img2, IMG_BYTES, &why), FSW_OK);
    g_p = IMP_TBL_DEFAULT;
    g_p.miss_flag_q28 = 2 * g_p.miss_flag_q28;
    g_p.alpha_q30[3] = 1100000000;
    (void)imp_table_encode(&g_p, 2u, g_img, sizeof(g_img));
    for (off = ((IMG_BYTES - 1u) / 13u) * 13u;; off -= 13u) {
        fsw_table_chunk_t c;
        c.table_id = (uint16_t)IMP_TBL_ID;
        c.revision = 2u;
        c.total_len = IMG_BYTES;
        c.offset = off;
        c.n = ((IMG_BYTES - off) < 13u) ? (IMG_BYTES - off) : 13u;
        c.data = &g_img[off];
        UT_CHECK_UEQ(fsw_table_chunk(&g_t, &c, &why), FSW_OK);
        if (off == 0u) {
            break;
        }
    }
    UT_UEQ(g_t.state, FSW_TBL_S_READY);
    pl = fsw_table_candidate(&g_t, &len);
    UT_UEQ(imp_table_decode(pl, len, 2u, &g_q), FSW_OK);
    g_p.revision = 2u;
    UT_UEQ(imp_params_diff(&g_q, &g_p, 1), 0u);
    UT_TRUE(fsw_table_commit(&g_t));
    pl = fsw_table_payload(&g_t, &len);
    UT_UEQ(len, IMP_TBL_PAYLOAD);
    for (i = 0u; i < len; i++) {
        UT_CHECK_UEQ(pl[i], g_img[FSW_TABLE_HDR_BYTES + i]);
    }
    UT_UEQ(fsw_table_scrub(&g_t), FSW_OK);
}

int main(void)
{
    UT_CASES(cases) = {
        UT_CASE(boot_tables_round_trip_bit_identical),
        UT_CASE(decoded_revision_comes_from_the_header),
        UT_CASE(descriptor_covers_the_payload_byte_for_byte),
        UT_CASE(every_field_range_is_enforced_with_its_index),
        UT_CASE(relations_are_enforced_with_their_index),
        UT_CASE(crc_header_and_length_errors),
        UT_CASE(encode_and_decode_check_their_arguments),
        UT_CASE(chunked_upload_commits_the_encoded_table),
    };
    return UT_RUN("fsw_imp_table", cases);
}
