/*
 * pd_table.c — the pd parameter table on the wire (spec 00 §3.2, spec 40 §4.1 item 5).
 *
 * table_id PD_TBL_ID, layout_version PD_TBL_LAYOUT (3), payload PD_TBL_PAYLOAD (3068) bytes,
 * little-endian, field by field (never a struct copy). The header revision becomes
 * pd_common_t.revision.
 *
 *   off  type  field           loader limits (the loader refuses anything outside, naming the field)
 *     0  u32   period_us       [1000, 1000000]
 *     4  u32   inv_ty_q22      [1, 2^32 - 1]
 *     8  u8    law             [0, 2]       PD_LAW_*
 *     9  u8    src             [0, 2]       PD_SRC_* (ADAPTIVE: pd_params_check asks pd_fest_check)
 *    10  u8    sched_law       [0, 2]
 *    11  u8    ch_mask         [0, 7]
 *    12  u8    n_y             [2, 64]
 *    13  u8    n_bad_max       [0, 63]
 *    14  u16   n_div           [1, 64]
 *    16  u16   n_hold          [0, 1000]
 *    18  u16   n_frozen        [2, 65535]
 *    20  i32   y_lim_q30       [1, 2^29]
 *    24  i32   dy_max_q30      [1, 2^24]
 *    28  i32   m_max_q28       [1, 2^30]
 *    32  i32   m_frozen_q28    [0, 2^30]
 *    36  i32   beta_warn_q24   [1, pi 2^24]
 *    40  i32   beta_lim_q24    [1, pi 2^24]
 *    44  u32   f0_q32          [0, 2^31 - 1]
 *    48  u32   df_inv_q16      [1, 2^31 - 1]
 *    52  u32   f_ground_q32    [0, 2^31 - 1]
 *    56  3 x 1004 B, channel yaw at 56, roll at 1060, pitch at 2064; offsets within a channel:
 *       0  u32 k0_q22, k1_q22, k2_nom_q22, k2_cold_q22, k2_min_q22, k2_max_q22   [0, 1023 2^22]
 *      24  u32 k2_node_q22[19]   (range, order and cap: pd_params_check)
 *     100  the estimator block (pd_fest_params_t, 904 B; pd_fest_check judges what the limits cannot):
 *     100  u8  n_sec           [1, 2]   (2: yaw's cascade)
 *     101  u8  n_reg           [0, 2]   (0 or 2: pd_fest_check)
 *     102  u8  reserved0, reserved1: 0 (else the decoder fails: FSW_ERR_DECODE)
 *     104  u32 inv_m_q30, alpha_hp_q30, f_hp_min_q32, beta_kappa_q30, kappa_hi_q30, sigma_y_q40
 *     128  i32 ad_m[4][4] (row-major)          192  u8 ad_sh[4]
 *     196  i32 bd_m[4]                         212  u8 bd_sh[4]
 *     216  i32 l_m[4]                          232  u8 l_sh[4]
 *     236  i32 dad_m[2][4][4]                  364  u8 dad_sh[2][4]
 *     372  i32 dbd_m[2][4]                     404  u8 dbd_sh[2][4]
 *     412  i32 aa_b_q29[3]                     424  i32 aa_a_q29[2]
 *     432  u32 cinv_q30[13][11] (row-major; 572 B, to 1004)
 *   3068  end
 *
 * pd_params_check (the executive's module check on every candidate, per channel) checks the
 * invariants the limits cannot: 1/Ty against period_us, gain order, the accumulator bounds, the
 * monotone schedule, n_y a power of two, the law the schedule was made for, and with ADAPTIVE the
 * channel's estimator block (pd_fest_check); the adapter adds the roll cap.
 */
#include "pd_mission.h"

#define K_MAX ((int64_t)PD_K_MAX_Q22)
#define U31   ((int64_t)0x7FFFFFFF)
#define PI_Q24 ((int64_t)52707179)   /* pi 2^24, rounded up: beta limits at most one turn / 2 */

static const fsw_field_lim_t PD_LIMS[] = {
    {0u, FSW_FT_U32, 1000, 1000000},          /* 0 period_us */
    {4u, FSW_FT_U32, 1, (int64_t)UINT32_MAX},  /* 1 inv_ty_q22 */
    {8u, FSW_FT_U8, 0, 2},                    /* 2 law */
    {9u, FSW_FT_U8, 0, 2},                    /* 3 src */
    {10u, FSW_FT_U8, 0, 2},                   /* 4 sched_law */
    {11u, FSW_FT_U8, 0, 7},                   /* 5 ch_mask */
    {12u, FSW_FT_U8, 2, 64},                  /* 6 n_y */
    {13u, FSW_FT_U8, 0, 63},                  /* 7 n_bad_max */
    {14u, FSW_FT_U16, 1, 64},                 /* 8 n_div */
    {16u, FSW_FT_U16, 0, 1000},               /* 9 n_hold */
    {18u, FSW_FT_U16, 2, 65535},              /* 10 n_frozen */
    {20u, FSW_FT_I32, 1, (int64_t)PD_Y_MAX_Q30},    /* 11 y_lim_q30 */
    {24u, FSW_FT_I32, 1, (int64_t)PD_DY_MAX_Q30},   /* 12 dy_max_q30 */
    {28u, FSW_FT_I32, 1, (int64_t)PD_M_MAX_Q28},    /* 13 m_max_q28 */
    {32u, FSW_FT_I32, 0, (int64_t)PD_M_MAX_Q28},    /* 14 m_frozen_q28 */
    {36u, FSW_FT_I32, 1, PI_Q24},             /* 15 beta_warn_q24 */
    {40u, FSW_FT_I32, 1, PI_Q24},             /* 16 beta_lim_q24 */
    {44u, FSW_FT_U32, 0, U31},                /* 17 f0_q32 */
    {48u, FSW_FT_U32, 1, U31},                /* 18 df_inv_q16 */
    {52u, FSW_FT_U32, 0, U31},                /* 19 f_ground_q32 */
    {56u, FSW_FT_U32, 0, K_MAX}, {60u, FSW_FT_U32, 0, K_MAX}, {64u, FSW_FT_U32, 0, K_MAX},         /* yaw */
    {68u, FSW_FT_U32, 0, K_MAX}, {72u, FSW_FT_U32, 0, K_MAX}, {76u, FSW_FT_U32, 0, K_MAX},
    {156u, FSW_FT_U8, 1, 2}, {157u, FSW_FT_U8, 0, 2},                         /* 26, 27 yaw fest n_sec, n_reg */
    {1060u, FSW_FT_U32, 0, K_MAX}, {1064u, FSW_FT_U32, 0, K_MAX}, {1068u, FSW_FT_U32, 0, K_MAX},   /* roll */
    {1072u, FSW_FT_U32, 0, K_MAX}, {1076u, FSW_FT_U32, 0, K_MAX}, {1080u, FSW_FT_U32, 0, K_MAX},
    {1160u, FSW_FT_U8, 1, 2}, {1161u, FSW_FT_U8, 0, 2},                      /* 34, 35 roll fest n_sec, n_reg */
    {2064u, FSW_FT_U32, 0, K_MAX}, {2068u, FSW_FT_U32, 0, K_MAX}, {2072u, FSW_FT_U32, 0, K_MAX},   /* pitch */
    {2076u, FSW_FT_U32, 0, K_MAX}, {2080u, FSW_FT_U32, 0, K_MAX}, {2084u, FSW_FT_U32, 0, K_MAX},
    {2164u, FSW_FT_U8, 1, 2}, {2165u, FSW_FT_U8, 0, 2},                      /* 42, 43 pitch fest n_sec, n_reg */
};

/* One channel's record on the wire: gains and nodes (100 B), then the estimator block. */
#define PD_TBL_CH0       56u
#define PD_TBL_CH_BYTES  1004u
#define PD_TBL_FEST_OFF  100u
#define PD_TBL_FEST_BYTES 904u
FX_STATIC_ASSERT(pd_tbl_sa_len, PD_TBL_PAYLOAD == (PD_TBL_CH0 + (PD_N_CH * PD_TBL_CH_BYTES)));
FX_STATIC_ASSERT(pd_tbl_sa_ch, PD_TBL_CH_BYTES == (PD_TBL_FEST_OFF + PD_TBL_FEST_BYTES));
FX_STATIC_ASSERT(pd_tbl_sa_cap, (FSW_TABLE_HDR_BYTES + PD_TBL_PAYLOAD) <= FSW_TABLE_CAP_BYTES);
FX_STATIC_ASSERT(pd_tbl_sa_dims, (PD_FEST_NX == 4u) && (PD_FEST_NR == 2u) && (PD_FEST_CF == 13u) &&
                                 (PD_FEST_CK == 11u));

/* n unsigned values in a row (the estimator block's shifts and its 1/c rows). */
static void pdt_wr_u8n(fsw_wr_t *w, const uint8_t *v, uint32_t n)
{
    uint32_t i;
    for (i = 0u; i < n; i++) {
        fsw_wr_u8(w, v[i]);
    }
}

static void pdt_rd_u8n(fsw_rd_t *r, uint8_t *v, uint32_t n)
{
    uint32_t i;
    for (i = 0u; i < n; i++) {
        v[i] = fsw_rd_u8(r);
    }
}

static void pdt_wr_u32n(fsw_wr_t *w, const uint32_t *v, uint32_t n)
{
    uint32_t i;
    for (i = 0u; i < n; i++) {
        fsw_wr_u32(w, v[i]);
    }
}

static void pdt_rd_u32n(fsw_rd_t *r, uint32_t *v, uint32_t n)
{
    uint32_t i;
    for (i = 0u; i < n; i++) {
        v[i] = fsw_rd_u32(r);
    }
}

/* The estimator block, in the field order of pd_fest.h; every matrix row by row (the rows are the
   arrays the codec walks, so no access crosses an inner array's bound). */
static void pdt_fest_wr(fsw_wr_t *w, const pd_fest_params_t *f)
{
    uint32_t i;
    uint32_t r;
    fsw_wr_u8(w, f->n_sec);
    fsw_wr_u8(w, f->n_reg);
    fsw_wr_u8(w, 0u);   /* reserved0: keeps the u32 fields 4-byte aligned in the record */
    fsw_wr_u8(w, 0u);   /* reserved1 */
    fsw_wr_u32(w, f->inv_m_q30);
    fsw_wr_u32(w, f->alpha_hp_q30);
    fsw_wr_u32(w, f->f_hp_min_q32);
    fsw_wr_u32(w, f->beta_kappa_q30);
    fsw_wr_u32(w, f->kappa_hi_q30);
    fsw_wr_u32(w, f->sigma_y_q40);
    for (i = 0u; i < PD_FEST_NX; i++) {
        fsw_wr_i32n(w, f->ad_m[i], PD_FEST_NX);
    }
    pdt_wr_u8n(w, f->ad_sh, PD_FEST_NX);
    fsw_wr_i32n(w, f->bd_m, PD_FEST_NX);
    pdt_wr_u8n(w, f->bd_sh, PD_FEST_NX);
    fsw_wr_i32n(w, f->l_m, PD_FEST_NX);
    pdt_wr_u8n(w, f->l_sh, PD_FEST_NX);
    for (r = 0u; r < PD_FEST_NR; r++) {
        for (i = 0u; i < PD_FEST_NX; i++) {
            fsw_wr_i32n(w, f->dad_m[r][i], PD_FEST_NX);
        }
    }
    for (r = 0u; r < PD_FEST_NR; r++) {
        pdt_wr_u8n(w, f->dad_sh[r], PD_FEST_NX);
    }
    for (r = 0u; r < PD_FEST_NR; r++) {
        fsw_wr_i32n(w, f->dbd_m[r], PD_FEST_NX);
    }
    for (r = 0u; r < PD_FEST_NR; r++) {
        pdt_wr_u8n(w, f->dbd_sh[r], PD_FEST_NX);
    }
    fsw_wr_i32n(w, f->aa_b_q29, 3u);
    fsw_wr_i32n(w, f->aa_a_q29, 2u);
    for (i = 0u; i < PD_FEST_CF; i++) {
        pdt_wr_u32n(w, f->cinv_q30[i], PD_FEST_CK);
    }
}

/* Reads the block; false when a reserved byte is not 0 (a table of another layout, or a corrupted
   one that still passed its CRC: nothing reserved may carry meaning unnoticed). */
static bool pdt_fest_rd(fsw_rd_t *rd, pd_fest_params_t *f)
{
    uint32_t i;
    uint32_t r;
    uint8_t res0;
    uint8_t res1;
    f->n_sec = fsw_rd_u8(rd);
    f->n_reg = fsw_rd_u8(rd);
    res0 = fsw_rd_u8(rd);
    res1 = fsw_rd_u8(rd);
    f->inv_m_q30 = fsw_rd_u32(rd);
    f->alpha_hp_q30 = fsw_rd_u32(rd);
    f->f_hp_min_q32 = fsw_rd_u32(rd);
    f->beta_kappa_q30 = fsw_rd_u32(rd);
    f->kappa_hi_q30 = fsw_rd_u32(rd);
    f->sigma_y_q40 = fsw_rd_u32(rd);
    for (i = 0u; i < PD_FEST_NX; i++) {
        fsw_rd_i32n(rd, f->ad_m[i], PD_FEST_NX);
    }
    pdt_rd_u8n(rd, f->ad_sh, PD_FEST_NX);
    fsw_rd_i32n(rd, f->bd_m, PD_FEST_NX);
    pdt_rd_u8n(rd, f->bd_sh, PD_FEST_NX);
    fsw_rd_i32n(rd, f->l_m, PD_FEST_NX);
    pdt_rd_u8n(rd, f->l_sh, PD_FEST_NX);
    for (r = 0u; r < PD_FEST_NR; r++) {
        for (i = 0u; i < PD_FEST_NX; i++) {
            fsw_rd_i32n(rd, f->dad_m[r][i], PD_FEST_NX);
        }
    }
    for (r = 0u; r < PD_FEST_NR; r++) {
        pdt_rd_u8n(rd, f->dad_sh[r], PD_FEST_NX);
    }
    for (r = 0u; r < PD_FEST_NR; r++) {
        fsw_rd_i32n(rd, f->dbd_m[r], PD_FEST_NX);
    }
    for (r = 0u; r < PD_FEST_NR; r++) {
        pdt_rd_u8n(rd, f->dbd_sh[r], PD_FEST_NX);
    }
    fsw_rd_i32n(rd, f->aa_b_q29, 3u);
    fsw_rd_i32n(rd, f->aa_a_q29, 2u);
    for (i = 0u; i < PD_FEST_CF; i++) {
        pdt_rd_u32n(rd, f->cinv_q30[i], PD_FEST_CK);
    }
    return (res0 == 0u) && (res1 == 0u);
}

const fsw_table_desc_t PD_TBL_DESC = {
    (uint16_t)PD_TBL_ID, (uint16_t)PD_TBL_LAYOUT, PD_TBL_PAYLOAD,
    PD_LIMS, (uint32_t)(sizeof(PD_LIMS) / sizeof(PD_LIMS[0])),
    NULL, 0u,
};

uint32_t pd_table_encode(const pd_table_t *t, uint32_t revision, uint8_t *img, uint32_t cap)
{
    uint32_t n = 0u;
    if ((t != NULL) && (img != NULL) && (cap >= (FSW_TABLE_HDR_BYTES + PD_TBL_PAYLOAD))) {
        const pd_common_t *c = &t->c;
        fsw_wr_t w;
        uint32_t k;
        uint32_t i;
        fsw_wr_init(&w, &img[FSW_TABLE_HDR_BYTES], PD_TBL_PAYLOAD);
        fsw_wr_u32(&w, c->period_us);
        fsw_wr_u32(&w, c->inv_ty_q22);
        fsw_wr_u8(&w, c->law);
        fsw_wr_u8(&w, c->src);
        fsw_wr_u8(&w, c->sched_law);
        fsw_wr_u8(&w, c->ch_mask);
        fsw_wr_u8(&w, c->n_y);
        fsw_wr_u8(&w, c->n_bad_max);
        fsw_wr_u16(&w, c->n_div);
        fsw_wr_u16(&w, c->n_hold);
        fsw_wr_u16(&w, c->n_frozen);
        fsw_wr_i32(&w, c->y_lim_q30);
        fsw_wr_i32(&w, c->dy_max_q30);
        fsw_wr_i32(&w, c->m_max_q28);
        fsw_wr_i32(&w, c->m_frozen_q28);
        fsw_wr_i32(&w, c->beta_warn_q24);
        fsw_wr_i32(&w, c->beta_lim_q24);
        fsw_wr_u32(&w, c->f0_q32);
        fsw_wr_u32(&w, c->df_inv_q16);
        fsw_wr_u32(&w, c->f_ground_q32);
        for (k = 0u; k < PD_N_CH; k++) {
            const pd_gains_t *g = &t->ch[k];
            fsw_wr_u32(&w, g->k0_q22);
            fsw_wr_u32(&w, g->k1_q22);
            fsw_wr_u32(&w, g->k2_nom_q22);
            fsw_wr_u32(&w, g->k2_cold_q22);
            fsw_wr_u32(&w, g->k2_min_q22);
            fsw_wr_u32(&w, g->k2_max_q22);
            for (i = 0u; i < PD_N_NODES; i++) {
                fsw_wr_u32(&w, g->k2_node_q22[i]);
            }
            pdt_fest_wr(&w, &g->fest);
        }
        if ((!w.err) && (w.pos == PD_TBL_PAYLOAD)) {
            fsw_table_write_header(img, (uint16_t)PD_TBL_ID, (uint16_t)PD_TBL_LAYOUT,
                                   PD_TBL_PAYLOAD, revision);
            n = FSW_TABLE_HDR_BYTES + PD_TBL_PAYLOAD;
        }
    }
    return n;
}

fsw_rc_t pd_table_decode(const uint8_t *payload, uint32_t len, uint32_t revision, pd_table_t *t)
{
    fsw_rc_t rc = FSW_ERR_ARG;
    if ((payload != NULL) && (t != NULL) && (len == PD_TBL_PAYLOAD)) {
        pd_common_t *c = &t->c;
        fsw_rd_t r;
        uint32_t k;
        uint32_t i;
        bool res_ok = true;
        fsw_rd_init(&r, payload, len);
        c->period_us = fsw_rd_u32(&r);
        c->inv_ty_q22 = fsw_rd_u32(&r);
        c->law = fsw_rd_u8(&r);
        c->src = fsw_rd_u8(&r);
        c->sched_law = fsw_rd_u8(&r);
        c->ch_mask = fsw_rd_u8(&r);
        c->n_y = fsw_rd_u8(&r);
        c->n_bad_max = fsw_rd_u8(&r);
        c->n_div = fsw_rd_u16(&r);
        c->n_hold = fsw_rd_u16(&r);
        c->n_frozen = fsw_rd_u16(&r);
        c->y_lim_q30 = fsw_rd_i32(&r);
        c->dy_max_q30 = fsw_rd_i32(&r);
        c->m_max_q28 = fsw_rd_i32(&r);
        c->m_frozen_q28 = fsw_rd_i32(&r);
        c->beta_warn_q24 = fsw_rd_i32(&r);
        c->beta_lim_q24 = fsw_rd_i32(&r);
        c->f0_q32 = fsw_rd_u32(&r);
        c->df_inv_q16 = fsw_rd_u32(&r);
        c->f_ground_q32 = fsw_rd_u32(&r);
        c->revision = revision;
        for (k = 0u; k < PD_N_CH; k++) {
            pd_gains_t *g = &t->ch[k];
            g->k0_q22 = fsw_rd_u32(&r);
            g->k1_q22 = fsw_rd_u32(&r);
            g->k2_nom_q22 = fsw_rd_u32(&r);
            g->k2_cold_q22 = fsw_rd_u32(&r);
            g->k2_min_q22 = fsw_rd_u32(&r);
            g->k2_max_q22 = fsw_rd_u32(&r);
            for (i = 0u; i < PD_N_NODES; i++) {
                g->k2_node_q22[i] = fsw_rd_u32(&r);
            }
            if (!pdt_fest_rd(&r, &g->fest)) {
                res_ok = false;
            }
        }
        if ((!r.err) && (r.pos == len) && res_ok) {
            rc = FSW_OK;
        } else {
            rc = FSW_ERR_DECODE;
        }
    }
    return rc;
}
