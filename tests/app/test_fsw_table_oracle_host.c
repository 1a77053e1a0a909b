/*
 * Independent oracle for the table loader (host only). tools/table/mktable.py, which shares no
 * code with fsw/ (Python struct + zlib.crc32), writes good and corrupted images and its own
 * verdict for each into TBL_ORACLE_DIR/manifest.txt at test time (CTest fixture). This test
 * uploads every image in odd-sized chunks, in reverse order for every other image, and checks
 * the loader's reason word against that verdict, plus the double-buffer guarantees: on
 * rejection the active image is bit-identical; on acceptance the committed payload equals the
 * file's payload byte for byte.
 */
#include <stdio.h>
#include <string.h>

#include "app/fsw_table.h"
#include "tbl_test_desc.h"
#include "ut.h"

#ifndef TBL_ORACLE_DIR
#error "TBL_ORACLE_DIR must name the directory mktable.py writes"
#endif

typedef struct {
    const char *name;
    uint32_t code;
} reason_name_t;

static const reason_name_t reasons[] = {
    {"OK", FSW_TBL_R_NONE},           {"OVERSIZE", FSW_TBL_R_OVERSIZE},
    {"DECODE", FSW_TBL_R_DECODE},     {"CRC", FSW_TBL_R_CRC},
    {"ID", FSW_TBL_R_ID},             {"VERSION", FSW_TBL_R_VERSION},
    {"LENGTH", FSW_TBL_R_LENGTH},     {"RANGE_LO", FSW_TBL_R_RANGE_LO},
    {"RANGE_HI", FSW_TBL_R_RANGE_HI}, {"INVARIANT", FSW_TBL_R_INVARIANT},
};

static fsw_table_t g_t;
static uint8_t g_boot[FSW_TABLE_CAP_BYTES];
static uint8_t g_file[FSW_TABLE_CAP_BYTES + 1u];
static uint8_t g_snap[FSW_TABLE_CAP_BYTES];

static int reason_code(const char *name, uint32_t *code)
{
    size_t i;
    for (i = 0u; i < sizeof reasons / sizeof reasons[0]; i++) {
        if (strcmp(name, reasons[i].name) == 0) {
            *code = reasons[i].code;
            return 1;
        }
    }
    return 0;
}

/* Uploads img in chunks of `step`, reverse order if asked; returns the first failure or the
   end-of-upload result. */
static fsw_rc_t upload_all(const uint8_t *img, uint32_t total, uint32_t step, int reverse,
                           uint32_t *why)
{
    uint32_t nchunks = (total + step - 1u) / step;
    uint32_t k;
    fsw_rc_t rc = FSW_OK;
    for (k = 0u; (k < nchunks) && (rc == FSW_OK); k++) {
        uint32_t idx = reverse ? (nchunks - 1u - k) : k;
        fsw_table_chunk_t c;
        c.table_id = (uint16_t)TT_ID;
        c.revision = 77u;
        c.total_len = total;
        c.offset = idx * step;
        c.n = ((total - c.offset) < step) ? (total - c.offset) : step;
        c.data = &img[c.offset];
        rc = fsw_table_chunk(&g_t, &c, why);
    }
    if (rc == FSW_OK) {
        rc = fsw_table_end(&g_t, why);
    }
    return rc;
}

static void check_one(const char *name, uint32_t want, int reverse)
{
    char path[512];
    FILE *f;
    size_t n;
    uint32_t why = 0xFFFFFFFFu;
    tt_params_t p;
    uint32_t boot_len;
    fsw_rc_t rc;
    const uint8_t *pl;
    uint32_t plen = 0u;

    (void)snprintf(path, sizeof path, "%s/%s.bin", TBL_ORACLE_DIR, name);
    f = fopen(path, "rb");
    UT_CHECK(f != NULL);
    if (f == NULL) {
        return;
    }
    n = fread(g_file, 1u, sizeof g_file, f);
    (void)fclose(f);
    UT_CHECK(n <= FSW_TABLE_CAP_BYTES);

    tt_defaults(&p);
    boot_len = tt_build(g_boot, sizeof g_boot, &p, (uint16_t)TT_ID, (uint16_t)TT_VERSION, 1u);
    UT_CHECK_UEQ(fsw_table_init(&g_t, &tt_desc, g_boot, boot_len, NULL), FSW_OK);
    (void)memcpy(g_snap, g_t.img[g_t.active], sizeof g_snap);

    rc = upload_all(g_file, (uint32_t)n, 13u, reverse, &why);
    if (why != want) {
        ut_puts(name);
        ut_puts(": reason word ");
        ut_put_u32hex(why);
        ut_puts(" expected ");
        ut_put_u32hex(want);
        ut_puts("\n");
    }
    UT_CHECK_UEQ(why, want);
    if (want == FSW_TBL_R_NONE) {
        UT_CHECK_UEQ(rc, FSW_OK);
        UT_CHECK(fsw_table_commit(&g_t));
        pl = fsw_table_payload(&g_t, &plen);
        UT_CHECK(pl != NULL);
        UT_CHECK_UEQ(plen, n - FSW_TABLE_HDR_BYTES);
        UT_CHECK(pl != NULL && memcmp(pl, &g_file[FSW_TABLE_HDR_BYTES], plen) == 0);
        UT_CHECK_UEQ(fsw_table_scrub(&g_t), FSW_OK);
        UT_CHECK_UEQ(g_t.rejects, 0u);
    } else {
        UT_CHECK(rc != FSW_OK);
        UT_CHECK_UEQ(g_t.rejects, 1u);
        UT_CHECK(!fsw_table_commit(&g_t));
        UT_CHECK_UEQ(fsw_table_revision(&g_t), 1u);
        UT_CHECK(memcmp(g_snap, g_t.img[g_t.active], sizeof g_snap) == 0);
        UT_CHECK_UEQ(g_t.active_len, boot_len);
    }
}

UT_TEST(oracle_images_match_verdicts)
{
    char line[256];
    char name[128];
    char reason[32];
    unsigned detail;
    unsigned count = 0u;
    unsigned accepted = 0u;
    FILE *m = fopen(TBL_ORACLE_DIR "/manifest.txt", "r");
    UT_TRUE(m != NULL);
    while (fgets(line, sizeof line, m) != NULL) {
        uint32_t code = 0u;
        UT_CHECK(sscanf(line, "%127s %31s %u", name, reason, &detail) == 3);
        UT_CHECK(reason_code(reason, &code));
        check_one(name, code | ((uint32_t)detail << FSW_TBL_DETAIL_SHIFT), (int)(count & 1u));
        count++;
        if (code == FSW_TBL_R_NONE) {
            accepted++;
        }
    }
    (void)fclose(m);
    ut_puts("oracle: ");
    ut_put_u64(count);
    ut_puts(" images, ");
    ut_put_u64(accepted);
    ut_puts(" accepted\n");
    /* The suite must exercise both outcomes and every reason class it names. */
    UT_LE(40, count);
    UT_LE(3, accepted);
}

int main(void)
{
    UT_CASES(cases) = {
        UT_CASE(oracle_images_match_verdicts),
    };
    return UT_RUN("fsw_table_oracle", cases);
}
