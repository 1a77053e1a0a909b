/*
 * rsp_table.c — the respin parameter table on the wire (spec 00 §3.2, spec 30 §3.4, §8).
 *
 * table_id RSP_TBL_ID, layout RSP_TBL_LAYOUT, payload RSP_TBL_PAYLOAD (156) bytes, little-endian,
 * field by field, every field 4 bytes. The header revision becomes rsp_params_t.revision.
 *
 *   off  type     field              off  type  field
 *     0  u32      period_us           72  u32   n_g0            [1, 1024]
 *     4  u32      mode     [0, 1]     76  i32   gyro_max_cnt    [1, 2^22]
 *     8  u32      act_kind [0, 1]     80  i32   whl_max_cnt
 *    12  i32 x 3  j_q19               84  u32   n_fault
 *    24  i32      iw_q30              88  u32   n_stale
 *    28  i32      eps1_q30 (< eps2)   92  u32   n_whl_est
 *    32  i32      eps2_q30            96  i32   outlier_q20
 *    36  i32      heps_q30           100  u32   outlier_rel_q16 [1, 2^16]
 *    40  i32      m_q24              104  i32   drift_q30
 *    44  i32      k_q30              108  u32   drift_sh        [1, 20]
 *    48  i32      mstar_q24          112  u32   ealarm_q32 (at most 1 J)
 *    52  i32      mmax_q24           116  i32   done_xi_q30
 *    56  i32      hlim_q20           120  i32   done_h_q20
 *    60  i32      inv_ts_q16         124  u32   done_ticks      [1, 2^24]
 *    64  i32      gguard_q20 (>= gmin) 128  i32   gfilt_alpha_q30 [0, 0.5]  (0: G filter off)
 *    68  i32      gmin_q20            132  i32   hg_q20
 *                                     136  i32   lambda_q28      [., 1.0]
 *                                     140  i32   umax_cnt        [1, 32767]
 *                                     144  i32   ms_sing_q28     [., 4.0]
 *                                     148  i32   rotor_nom_cnt
 *                                     152  u32   rotor_tol_q16   [1, 2^16]
 * Layout 2 added the last seven (the G filter and the gyrodine cluster): a layout-1 image is refused.
 *
 * Every value must be positive (limits below, naming the field); rsp_params_check adds the
 * cross-field rules (thresholds and hysteresis, m = M_max / eps1, 1/Ts against the period,
 * J_y the largest) for tables that never went through the loader.
 */
#include "rsp_mission.h"

#define I32MAX ((int64_t)INT32_MAX)
#define U32MAX ((int64_t)UINT32_MAX)
#define Q30ONE ((int64_t)1073741824)

static const fsw_field_lim_t RSP_LIMS[] = {
    {0u, FSW_FT_U32, 1000, 1000000},     /* 0 period_us */
    {4u, FSW_FT_U32, 0, 1},              /* 1 mode */
    {8u, FSW_FT_U32, 0, 1},              /* 2 act_kind */
    {12u, FSW_FT_I32, 1, I32MAX},        /* 3 j_q19[0] */
    {16u, FSW_FT_I32, 1, I32MAX},        /* 4 j_q19[1] */
    {20u, FSW_FT_I32, 1, I32MAX},        /* 5 j_q19[2] */
    {24u, FSW_FT_I32, 1, I32MAX},        /* 6 iw_q30 */
    {28u, FSW_FT_I32, 1, Q30ONE},        /* 7 eps1_q30 */
    {32u, FSW_FT_I32, 1, Q30ONE},        /* 8 eps2_q30 */
    {36u, FSW_FT_I32, 1, Q30ONE},        /* 9 heps_q30 */
    {40u, FSW_FT_I32, 1, I32MAX},        /* 10 m_q24 */
    {44u, FSW_FT_I32, 1, I32MAX},        /* 11 k_q30 */
    {48u, FSW_FT_I32, 1, I32MAX},        /* 12 mstar_q24 */
    {52u, FSW_FT_I32, 1, I32MAX},        /* 13 mmax_q24 */
    {56u, FSW_FT_I32, 1, I32MAX},        /* 14 hlim_q20 */
    {60u, FSW_FT_I32, 1, I32MAX},        /* 15 inv_ts_q16 */
    {64u, FSW_FT_I32, 1, I32MAX},        /* 16 gguard_q20 */
    {68u, FSW_FT_I32, 1, I32MAX},        /* 17 gmin_q20 */
    {72u, FSW_FT_U32, 1, 1024},          /* 18 n_g0 (RSP_G0_TICKS_MAX) */
    {76u, FSW_FT_I32, 1, 4194304},       /* 19 gyro_max_cnt: << 6 stays in int32 */
    {80u, FSW_FT_I32, 1, I32MAX},        /* 20 whl_max_cnt */
    {84u, FSW_FT_U32, 1, 65535},         /* 21 n_fault */
    {88u, FSW_FT_U32, 1, 65535},         /* 22 n_stale */
    {92u, FSW_FT_U32, 1, 65535},         /* 23 n_whl_est */
    {96u, FSW_FT_I32, 1, I32MAX},        /* 24 outlier_q20 */
    {100u, FSW_FT_U32, 1, 65536},        /* 25 outlier_rel_q16 */
    {104u, FSW_FT_I32, 1, Q30ONE},       /* 26 drift_q30 */
    {108u, FSW_FT_U32, 1, 20},           /* 27 drift_sh */
    {112u, FSW_FT_U32, 1, U32MAX},       /* 28 ealarm_q32 */
    {116u, FSW_FT_I32, 1, Q30ONE},       /* 29 done_xi_q30 */
    {120u, FSW_FT_I32, 1, I32MAX},       /* 30 done_h_q20 */
    {124u, FSW_FT_U32, 1, 16777216},     /* 31 done_ticks */
    {128u, FSW_FT_I32, 0, 536870912},    /* 32 gfilt_alpha_q30 (0 = off; at most 0.5) */
    {132u, FSW_FT_I32, 1, I32MAX},       /* 33 hg_q20 */
    {136u, FSW_FT_I32, 1, 268435456},    /* 34 lambda_q28 */
    {140u, FSW_FT_I32, 1, 32767},        /* 35 umax_cnt (int16 command) */
    {144u, FSW_FT_I32, 1, Q30ONE},       /* 36 ms_sing_q28 */
    {148u, FSW_FT_I32, 1, I32MAX},       /* 37 rotor_nom_cnt */
    {152u, FSW_FT_U32, 1, 65536},        /* 38 rotor_tol_q16 */
};

/* value[a] + margin <= value[b]: eps1 < eps2, g_min <= g_guard */
static const fsw_field_rel_t RSP_RELS[] = {
    {7u, 8u, 1}, {17u, 16u, 0},
};

const fsw_table_desc_t RSP_TBL_DESC = {
    (uint16_t)RSP_TBL_ID, (uint16_t)RSP_TBL_LAYOUT, RSP_TBL_PAYLOAD,
    RSP_LIMS, (uint32_t)(sizeof(RSP_LIMS) / sizeof(RSP_LIMS[0])),
    RSP_RELS, (uint32_t)(sizeof(RSP_RELS) / sizeof(RSP_RELS[0])),
};

uint32_t rsp_table_encode(const rsp_params_t *p, uint32_t revision, uint8_t *img, uint32_t cap)
{
    uint32_t n = 0u;
    if ((p != NULL) && (img != NULL) && (cap >= (FSW_TABLE_HDR_BYTES + RSP_TBL_PAYLOAD)) &&
        (p->ealarm_q32 >= 0) && (p->ealarm_q32 <= (int64_t)UINT32_MAX)) {
        fsw_wr_t w;
        fsw_wr_init(&w, &img[FSW_TABLE_HDR_BYTES], RSP_TBL_PAYLOAD);
        fsw_wr_u32(&w, p->period_us);
        fsw_wr_u32(&w, p->mode);
        fsw_wr_u32(&w, p->act_kind);
        fsw_wr_i32n(&w, p->j_q19, 3u);
        fsw_wr_i32(&w, p->iw_q30);
        fsw_wr_i32(&w, p->eps1_q30);
        fsw_wr_i32(&w, p->eps2_q30);
        fsw_wr_i32(&w, p->heps_q30);
        fsw_wr_i32(&w, p->m_q24);
        fsw_wr_i32(&w, p->k_q30);
        fsw_wr_i32(&w, p->mstar_q24);
        fsw_wr_i32(&w, p->mmax_q24);
        fsw_wr_i32(&w, p->hlim_q20);
        fsw_wr_i32(&w, p->inv_ts_q16);
        fsw_wr_i32(&w, p->gguard_q20);
        fsw_wr_i32(&w, p->gmin_q20);
        fsw_wr_u32(&w, p->n_g0);
        fsw_wr_i32(&w, p->gyro_max_cnt);
        fsw_wr_i32(&w, p->whl_max_cnt);
        fsw_wr_u32(&w, p->n_fault);
        fsw_wr_u32(&w, p->n_stale);
        fsw_wr_u32(&w, p->n_whl_est);
        fsw_wr_i32(&w, p->outlier_q20);
        fsw_wr_u32(&w, p->outlier_rel_q16);
        fsw_wr_i32(&w, p->drift_q30);
        fsw_wr_u32(&w, p->drift_sh);
        fsw_wr_u32(&w, (uint32_t)p->ealarm_q32);   /* range checked above */
        fsw_wr_i32(&w, p->done_xi_q30);
        fsw_wr_i32(&w, p->done_h_q20);
        fsw_wr_u32(&w, p->done_ticks);
        fsw_wr_i32(&w, p->gfilt_alpha_q30);
        fsw_wr_i32(&w, p->hg_q20);
        fsw_wr_i32(&w, p->lambda_q28);
        fsw_wr_i32(&w, p->umax_cnt);
        fsw_wr_i32(&w, p->ms_sing_q28);
        fsw_wr_i32(&w, p->rotor_nom_cnt);
        fsw_wr_u32(&w, p->rotor_tol_q16);
        if ((!w.err) && (w.pos == RSP_TBL_PAYLOAD)) {
            fsw_table_write_header(img, (uint16_t)RSP_TBL_ID, (uint16_t)RSP_TBL_LAYOUT,
                                   RSP_TBL_PAYLOAD, revision);
            n = FSW_TABLE_HDR_BYTES + RSP_TBL_PAYLOAD;
        }
    }
    return n;
}

fsw_rc_t rsp_table_decode(const uint8_t *payload, uint32_t len, uint32_t revision, rsp_params_t *p)
{
    fsw_rc_t rc = FSW_ERR_ARG;
    if ((payload != NULL) && (p != NULL) && (len == RSP_TBL_PAYLOAD)) {
        fsw_rd_t r;
        fsw_rd_init(&r, payload, len);
        p->period_us = fsw_rd_u32(&r);
        p->mode = fsw_rd_u32(&r);
        p->act_kind = fsw_rd_u32(&r);
        fsw_rd_i32n(&r, p->j_q19, 3u);
        p->iw_q30 = fsw_rd_i32(&r);
        p->eps1_q30 = fsw_rd_i32(&r);
        p->eps2_q30 = fsw_rd_i32(&r);
        p->heps_q30 = fsw_rd_i32(&r);
        p->m_q24 = fsw_rd_i32(&r);
        p->k_q30 = fsw_rd_i32(&r);
        p->mstar_q24 = fsw_rd_i32(&r);
        p->mmax_q24 = fsw_rd_i32(&r);
        p->hlim_q20 = fsw_rd_i32(&r);
        p->inv_ts_q16 = fsw_rd_i32(&r);
        p->gguard_q20 = fsw_rd_i32(&r);
        p->gmin_q20 = fsw_rd_i32(&r);
        p->n_g0 = fsw_rd_u32(&r);
        p->gyro_max_cnt = fsw_rd_i32(&r);
        p->whl_max_cnt = fsw_rd_i32(&r);
        p->n_fault = fsw_rd_u32(&r);
        p->n_stale = fsw_rd_u32(&r);
        p->n_whl_est = fsw_rd_u32(&r);
        p->outlier_q20 = fsw_rd_i32(&r);
        p->outlier_rel_q16 = fsw_rd_u32(&r);
        p->drift_q30 = fsw_rd_i32(&r);
        p->drift_sh = fsw_rd_u32(&r);
        p->ealarm_q32 = (int64_t)fsw_rd_u32(&r);
        p->done_xi_q30 = fsw_rd_i32(&r);
        p->done_h_q20 = fsw_rd_i32(&r);
        p->done_ticks = fsw_rd_u32(&r);
        p->gfilt_alpha_q30 = fsw_rd_i32(&r);
        p->hg_q20 = fsw_rd_i32(&r);
        p->lambda_q28 = fsw_rd_i32(&r);
        p->umax_cnt = fsw_rd_i32(&r);
        p->ms_sing_q28 = fsw_rd_i32(&r);
        p->rotor_nom_cnt = fsw_rd_i32(&r);
        p->rotor_tol_q16 = fsw_rd_u32(&r);
        p->revision = revision;
        if ((!r.err) && (r.pos == len)) {
            rc = FSW_OK;
        } else {
            rc = FSW_ERR_DECODE;
        }
    }
    return rc;
}
