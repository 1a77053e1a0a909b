/*
 * pd_table.c — the pd parameter table on the wire (spec 00 §3.2).
 *
 * table_id PD_TBL_ID, layout_version PD_TBL_LAYOUT, payload PD_TBL_PAYLOAD
 * (20) bytes, little-endian, field by field (never a struct copy). The header revision becomes
 * pd_params_t.revision.
 *
 *   off  type  field           limits (the loader refuses anything outside, naming the field)
 *     0  u32   period_us       [1000, 1000000]
 *     4  i32   rate_max_cnt    [1, INT32_MAX]
 *     8  i32   gain_q16        [1, 2^24]
 *    12  i32   u_max_cnt       [1, 2^24]
 *    16  u16   n_sat           [1, 65535]
 *    18  u16   spare           [0, 0]
 *
 * pd_params_check (the executive's module check on every candidate) repeats the ranges for
 * tables that never went through the loader, and checks the period against the executive's.
 */
#include "pd_mission.h"

#define I32MAX ((int64_t)INT32_MAX)

static const fsw_field_lim_t PD_LIMS[] = {
    {0u, FSW_FT_U32, 1000, 1000000},                    /* 0 period_us */
    {4u, FSW_FT_I32, 1, I32MAX},                        /* 1 rate_max_cnt */
    {8u, FSW_FT_I32, 1, (int64_t)PD_GAIN_MAX_Q16},    /* 2 gain_q16 */
    {12u, FSW_FT_I32, 1, (int64_t)PD_U_MAX_CNT},      /* 3 u_max_cnt */
    {16u, FSW_FT_U16, 1, 65535},                        /* 4 n_sat */
    {18u, FSW_FT_U16, 0, 0},                            /* 5 spare */
};

const fsw_table_desc_t PD_TBL_DESC = {
    (uint16_t)PD_TBL_ID, (uint16_t)PD_TBL_LAYOUT, PD_TBL_PAYLOAD,
    PD_LIMS, (uint32_t)(sizeof(PD_LIMS) / sizeof(PD_LIMS[0])),
    NULL, 0u,
};

uint32_t pd_table_encode(const pd_params_t *p, uint32_t revision, uint8_t *img, uint32_t cap)
{
    uint32_t n = 0u;
    if ((p != NULL) && (img != NULL) && (cap >= (FSW_TABLE_HDR_BYTES + PD_TBL_PAYLOAD))) {
        fsw_wr_t w;
        fsw_wr_init(&w, &img[FSW_TABLE_HDR_BYTES], PD_TBL_PAYLOAD);
        fsw_wr_u32(&w, p->period_us);
        fsw_wr_i32(&w, p->rate_max_cnt);
        fsw_wr_i32(&w, p->gain_q16);
        fsw_wr_i32(&w, p->u_max_cnt);
        fsw_wr_u16(&w, p->n_sat);
        fsw_wr_u16(&w, 0u);
        if ((!w.err) && (w.pos == PD_TBL_PAYLOAD)) {
            fsw_table_write_header(img, (uint16_t)PD_TBL_ID, (uint16_t)PD_TBL_LAYOUT,
                                   PD_TBL_PAYLOAD, revision);
            n = FSW_TABLE_HDR_BYTES + PD_TBL_PAYLOAD;
        }
    }
    return n;
}

fsw_rc_t pd_table_decode(const uint8_t *payload, uint32_t len, uint32_t revision, pd_params_t *p)
{
    fsw_rc_t rc = FSW_ERR_ARG;
    if ((payload != NULL) && (p != NULL) && (len == PD_TBL_PAYLOAD)) {
        fsw_rd_t r;
        fsw_rd_init(&r, payload, len);
        p->period_us = fsw_rd_u32(&r);
        p->rate_max_cnt = fsw_rd_i32(&r);
        p->gain_q16 = fsw_rd_i32(&r);
        p->u_max_cnt = fsw_rd_i32(&r);
        p->n_sat = fsw_rd_u16(&r);
        (void)fsw_rd_u16(&r);   /* spare */
        p->revision = revision;
        if ((!r.err) && (r.pos == len)) {
            rc = FSW_OK;
        } else {
            rc = FSW_ERR_DECODE;
        }
    }
    return rc;
}
