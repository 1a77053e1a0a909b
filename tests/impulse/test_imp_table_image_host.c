/*
 * The C impulse-table encoder/decoder against the independent Python writer (host only).
 * tools/impulse/image.py (`python -m tools.impulse image`), which shares no code with fsw/
 * (integers from tools/impulse/ctable.py's own computation, Python struct, zlib.crc32), writes
 * the images into IMP_IMG_DIR at test time (CTest fixture imp_table_images). For each boot table
 * the file must equal the C encoder's image of the C initialiser byte for byte, and the C
 * decoder's result must equal the C initialiser field for field; images with one defect each
 * must be refused by the loader with the expected reason word; and uploaded into a RENDEZVOUS
 * executive a good image is committed and a vetoed one refused with the module's detail.
 */
#include <stdio.h>

#include "fsw_exec.h"
#include "imp_tables.h"
#include "imp_tbl_util.h"
#include "ut.h"

#ifndef IMP_IMG_DIR
#error "IMP_IMG_DIR must name the directory tools/impulse/image.py writes"
#endif

#define IMG_BYTES (FSW_TABLE_HDR_BYTES + IMP_TBL_PAYLOAD)

static fsw_table_t g_t;
static fsw_t g_f;
static fsw_out_t g_o;
static uint8_t g_file[FSW_TABLE_CAP_BYTES + 1u];
static uint8_t g_c[FSW_TABLE_CAP_BYTES];
static imp_params_t g_p;
static imp_params_t g_want;

static uint32_t read_image(const char *name)
{
    char path[512];
    FILE *f;
    size_t n = 0u;
    (void)snprintf(path, sizeof path, "%s/%s.bin", IMP_IMG_DIR, name);
    f = fopen(path, "rb");
    if (f == NULL) {
        ut_puts("cannot open ");
        ut_puts(path);
        ut_puts("\n");
        UT_CHECK(f != NULL);
        return 0u;
    }
    n = fread(g_file, 1u, sizeof g_file, f);
    (void)fclose(f);
    UT_CHECK(n <= FSW_TABLE_CAP_BYTES);
    return (uint32_t)n;
}

static fsw_rc_t upload(fsw_t *f, const uint8_t *img, uint32_t n, uint32_t *why)
{
    fsw_rc_t rc = FSW_OK;
    uint32_t off;
    for (off = 0u; off < n; off += 50u) {
        fsw_table_chunk_t c;
        c.table_id = (uint16_t)IMP_TBL_ID;
        c.revision = 1234u;
        c.total_len = n;
        c.offset = off;
        c.n = ((n - off) < 50u) ? (n - off) : 50u;
        c.data = &img[off];
        rc = fsw_table_upload(f, &c, why);
    }
    return rc;
}

typedef struct {
    const char *file;
    const imp_params_t *table;
    uint32_t revision;
} good_t;

static const good_t GOOD[3] = {
    {"imp_default_r7", &IMP_TBL_DEFAULT, 7u},
    {"imp_1s_r8", &IMP_TBL_1S, 8u},
    {"imp_sub1ms_r9", &IMP_TBL_SUB1MS, 9u},
};

UT_TEST(python_images_equal_the_c_encoder_and_decode_to_the_c_tables)
{
    uint32_t k;
    for (k = 0u; k < 3u; k++) {
        uint32_t n = read_image(GOOD[k].file);
        uint32_t why = 0u;
        uint32_t len = 0u;
        uint32_t i;
        uint32_t diff = 0u;
        const uint8_t *pl;
        UT_CHECK_UEQ(n, IMG_BYTES);
        /* byte for byte the C encoder's image of the C initialiser */
        UT_CHECK_UEQ(imp_table_encode(GOOD[k].table, GOOD[k].revision, g_c, sizeof(g_c)), IMG_BYTES);
        for (i = 0u; i < IMG_BYTES; i++) {
            diff += (g_c[i] != g_file[i]) ? 1u : 0u;
        }
        UT_CHECK_UEQ(diff, 0u);
        /* through the loader, then the C decoder: the C initialiser field for field */
        UT_CHECK_UEQ(fsw_table_init(&g_t, &IMP_TBL_DESC, g_file, n, &why), FSW_OK);
        UT_CHECK_UEQ(why, FSW_TBL_R_NONE);
        UT_CHECK_UEQ(fsw_table_revision(&g_t), GOOD[k].revision);
        pl = fsw_table_payload(&g_t, &len);
        UT_CHECK(pl != NULL);
        UT_CHECK_UEQ(imp_table_decode(pl, len, fsw_table_revision(&g_t), &g_p), FSW_OK);
        g_want = *GOOD[k].table;
        g_want.revision = GOOD[k].revision;
        UT_CHECK_UEQ(imp_params_diff(&g_p, &g_want, 1), 0u);
        UT_CHECK_UEQ(imp_params_check(&g_p, &why), FSW_OK);
    }
}

typedef struct {
    const char *file;
    uint32_t why;             /* loader verdict */
} bad_t;

#define RW(code, detail) ((code) | ((uint32_t)(detail) << FSW_TBL_DETAIL_SHIFT))

static const bad_t BAD[] = {
    {"imp_default_bad_crc", RW(FSW_TBL_R_CRC, 0u)},
    {"imp_default_table_id_obs", RW(FSW_TBL_R_ID, 0u)},
    {"imp_default_layout_2", RW(FSW_TBL_R_VERSION, 0u)},
    {"imp_default_length_175", RW(FSW_TBL_R_DECODE, 0u)},
    {"imp_default_max_iter_17", RW(FSW_TBL_R_RANGE_HI, 7u)},
    {"imp_default_pips_3", RW(FSW_TBL_R_RANGE_LO, 8u)},
    {"imp_default_alpha3_low", RW(FSW_TBL_R_RANGE_LO, 22u)},
    {"imp_default_spare_1", RW(FSW_TBL_R_RANGE_HI, 29u)},
    {"imp_default_spare2_1", RW(FSW_TBL_R_RANGE_HI, 50u)},
    {"imp_default_gain_1", RW(FSW_TBL_R_RANGE_HI, 55u)},
    {"imp_default_t_min_gt_period", RW(FSW_TBL_R_INVARIANT, 0u)},
    {"imp_default_rho_warn_gt_reject", RW(FSW_TBL_R_INVARIANT, 2u)},
    {"imp_default_u_cal_gt_u_uncal", RW(FSW_TBL_R_INVARIANT, 4u)},
    {"imp_default_lead_5", RW(FSW_TBL_R_NONE, 0u)},   /* the loader passes it: imp_params_check vetoes */
};

UT_TEST(python_defect_images_get_the_expected_reason)
{
    uint32_t k;
    for (k = 0u; k < (uint32_t)(sizeof BAD / sizeof BAD[0]); k++) {
        uint32_t n = read_image(BAD[k].file);
        uint32_t why = 0xFFFFFFFFu;
        (void)fsw_table_init(&g_t, &IMP_TBL_DESC, g_file, n, &why);
        if (why != BAD[k].why) {
            ut_puts(BAD[k].file);
            ut_puts(": reason word ");
            ut_put_u32hex(why);
            ut_puts(" expected ");
            ut_put_u32hex(BAD[k].why);
            ut_puts("\n");
        }
        UT_CHECK_UEQ(why, BAD[k].why);
    }
}

static fsw_in_t idle_frame(int64_t k)
{
    fsw_in_t in;
    uint32_t i;
    in.utime_us = k * 100000;
    in.seq = k;
    in.n_counts = 0u;
    for (i = 0u; i < FSW_IN_MAX; i++) {
        in.counts[i] = 0;
        in.status[i] = 0u;
    }
    in.mode_cmd = FSW_CMD_NONE;
    in.host_missed = 0u;
    in.host_rejected = 0u;
    in.tc = FSW_TC_NONE;
    for (i = 0u; i < 8u; i++) {
        in.tc_arg[i] = 0;
    }
    return in;
}

UT_TEST(python_images_uploaded_into_the_rendezvous_executive)
{
    fsw_cfg_t c = {100000u, 5u, FSW_MODE_RENDEZVOUS, FSW_MISSION_RENDEZVOUS};
    fsw_in_t in = idle_frame(1);
    uint32_t why = 0u;
    uint32_t n;
    n = imp_table_encode(&IMP_TBL_DEFAULT, 1u, g_c, (uint32_t)sizeof(g_c));
    UT_UEQ(fsw_init(&g_f, &c, g_c, n), FSW_OK);
    fsw_step(&g_f, &in, &g_o);
    /* a good image of another table (sub-tick grid): committed at the next step */
    n = read_image("imp_sub1ms_r9");
    UT_UEQ(upload(&g_f, g_file, n, &why), FSW_OK);
    UT_UEQ(why, FSW_TBL_R_NONE);
    in = idle_frame(2);
    fsw_step(&g_f, &in, &g_o);
    UT_UEQ(g_o.tlm.tbl_revision, 9u);
    UT_UEQ(g_o.tlm.n_tbl_acc, 1u);
    UT_UEQ(g_o.tlm.m.rendezvous.revision, 9u);
    g_want = IMP_TBL_SUB1MS;
    g_want.revision = 9u;
    UT_UEQ(imp_params_diff(&g_f.m.rendezvous.p, &g_want, 1), 0u);
    /* within the loader's ranges, but plan_lead below the worst plan: vetoed (LEAD, detail 8) */
    n = read_image("imp_default_lead_5");
    UT_UEQ(upload(&g_f, g_file, n, &why), FSW_ERR_INVARIANT);
    UT_UEQ(why, RW(FSW_TBL_R_MODULE, 8u));
    /* the 1 s table is valid, but not for this executive's 0.1 s period (detail 1, PERIOD) */
    n = read_image("imp_1s_r8");
    UT_UEQ(upload(&g_f, g_file, n, &why), FSW_ERR_INVARIANT);
    UT_UEQ(why, RW(FSW_TBL_R_MODULE, 1u));
    /* a bad CRC */
    n = read_image("imp_default_bad_crc");
    UT_UEQ(upload(&g_f, g_file, n, &why), FSW_ERR_CRC);
    in = idle_frame(3);
    fsw_step(&g_f, &in, &g_o);
    UT_UEQ(g_o.tlm.n_tbl_rej, 3u);
    UT_UEQ(g_o.tlm.tbl_reason, RW(FSW_TBL_R_CRC, 0u));
    UT_UEQ(g_o.tlm.tbl_revision, 9u);
    UT_UEQ(imp_params_diff(&g_f.m.rendezvous.p, &g_want, 1), 0u);
    UT_UEQ(g_o.mode, FSW_MODE_RENDEZVOUS);
}

int main(void)
{
    UT_CASES(cases) = {
        UT_CASE(python_images_equal_the_c_encoder_and_decode_to_the_c_tables),
        UT_CASE(python_defect_images_get_the_expected_reason),
        UT_CASE(python_images_uploaded_into_the_rendezvous_executive),
    };
    return UT_RUN("fsw_imp_table_image", cases);
}
