/* Test table 0x7E57 (see tbl_test_desc.h). */
#include "tbl_test_desc.h"
#include "app/fsw_codec.h"
#include "fx.h"

static const fsw_field_lim_t tt_fields[8] = {
    {0u, FSW_FT_U8, 0, 3},
    {1u, FSW_FT_U8, 0, 1},
    {2u, FSW_FT_U16, 1, 1000},
    {4u, FSW_FT_U32, 1, 1000},
    {8u, FSW_FT_I32, -262144, 262144},
    {12u, FSW_FT_I32, 0, 1000},
    {16u, FSW_FT_I32, 0, 100000},
    {20u, FSW_FT_U32, 10, INT64_C(4000000000)},
};

static const fsw_field_rel_t tt_rels[2] = {
    {5u, 6u, 2},
    {3u, 7u, 1},
};

const fsw_table_desc_t tt_desc = {
    TT_ID, TT_VERSION, TT_PAYLOAD, tt_fields, 8u, tt_rels, 2u,
};

void tt_defaults(tt_params_t *p)
{
    p->mode = 2u;
    p->enable = 1u;
    p->period_ms = 200u;
    p->stale_max = 16u;
    p->gain_q16 = -100;
    p->quant_q16 = 64;
    p->hyst_q16 = 1000;
    p->max_count = 1234u;
}

uint32_t tt_build(uint8_t *img, uint32_t cap, const tt_params_t *p, uint16_t id,
                  uint16_t version, uint32_t revision)
{
    fsw_wr_t w;
    uint32_t total = 0u;
    if (cap >= TT_TOTAL) {
        fsw_wr_init(&w, &img[FSW_TABLE_HDR_BYTES], TT_PAYLOAD);
        fsw_wr_u8(&w, p->mode);
        fsw_wr_u8(&w, p->enable);
        fsw_wr_u16(&w, p->period_ms);
        fsw_wr_u32(&w, p->stale_max);
        fsw_wr_i32(&w, p->gain_q16);
        fsw_wr_i32(&w, p->quant_q16);
        fsw_wr_i32(&w, p->hyst_q16);
        fsw_wr_u32(&w, p->max_count);
        fsw_wr_init(&w, img, FSW_TABLE_HDR_BYTES);
        fsw_wr_u16(&w, id);
        fsw_wr_u16(&w, version);
        fsw_wr_u32(&w, TT_PAYLOAD);
        fsw_wr_u32(&w, revision);
        fsw_wr_u32(&w, fx_crc32(0u, &img[FSW_TABLE_HDR_BYTES], TT_PAYLOAD));
        total = TT_TOTAL;
    }
    return total;
}

void tt_fix_crc(uint8_t *img, uint32_t total)
{
    fsw_rd_t r;
    fsw_wr_t w;
    uint32_t len;
    fsw_rd_init(&r, img, total);
    fsw_rd_seek(&r, 4u);
    len = fsw_rd_u32(&r);
    if (len > (total - FSW_TABLE_HDR_BYTES)) {
        len = total - FSW_TABLE_HDR_BYTES;
    }
    fsw_wr_init(&w, img, FSW_TABLE_HDR_BYTES);
    w.pos = 12u;
    fsw_wr_u32(&w, fx_crc32(0u, &img[FSW_TABLE_HDR_BYTES], len));
}
