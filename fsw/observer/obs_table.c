/*
 * obs_table.c — the observer parameter table on the wire (spec 00 §3.2, 10-observer §4.6).
 *
 * table_id OBS_TBL_ID (0x0B01), layout_version OBS_TBL_LAYOUT (2), payload OBS_TBL_PAYLOAD (652) bytes, little-endian, field
 * by field (never a struct copy). The header revision becomes obs_params_t.revision.
 *
 *   off  type      field                 off  type       field
 *     0  u32       period_us              42  i32        kappa0_q28
 *     4  u8        estimator              46  i32        kappa_init_q28
 *     5  u8        gyro_cnt_shift         50  i32        kappa_lo_q28
 *     6  u8        act_cnt_shift          54  i32        kappa_hi_q28
 *     7  u8        d2_reject              58  i32        r_q30
 *     8  i32       sigma                  62  i32        p_floor_q30
 *    12  i32       gyro_max_cnt           66  i32        p_ceil_q30
 *    16  i32       act_max_cnt            70  i32        d2_max_q16
 *    20  i32       bdot_max_q29           74  i32[7]     ls
 *    24  i32       bdot_hw_q29           102  i32[7]     p0_q30
 *    28  u8[6]     q_phi0 q_phik q_gam0  130  i32[7]     qd_q30
 *                  q_gamk q_d q_w        158  i32[36]    phi0
 *    34  u16       n_lost                302  i32[36]    phik
 *    36  u16       n_good                446  i32[12]    gam0
 *    38  u16       n_sat                 494  i32[12]    gamk
 *    40  u16       n_gap_max             542  i32[12]    d
 *                                        590  i32[14]    w
 *                                        646  u16        n_rej_safe
 *                                        648  u16        rej_leak_inc
 *                                        650  u16        rej_freeze_on  (652 = end)
 *
 * Layout 2 appended the three innovation-gate fields (layout 1 ended at 646).
 *
 * The limits descriptor range-checks every scalar and the ls/p0/qd vectors; matrix entries
 * span the whole int32 range and are not listed. Relations give the orderings the loader can
 * check on raw values; obs_params_check (run by the executive on the candidate) adds the
 * invariants that need code (formats, period, scales).
 */
#include "obs_mission.h"

/* Offsets of the range-checked vectors, as uint16_t so that offset + k stays essentially
   uint16_t (MISRA 10.8 forbids casting the composite sum). The matrix offsets are only in
   the layout comment above: the codec walks fields in order and needs none. */
#define OFF_LS    ((uint16_t)74u)
#define OFF_P0    ((uint16_t)102u)
#define OFF_QD    ((uint16_t)130u)

#define I32MAX ((int64_t)INT32_MAX)

/* Field indices used by the relations below. */
#define F_BDOT_MAX   8u
#define F_BDOT_HW    9u
#define F_KAPPA0     20u
#define F_KAPPA_INIT 21u
#define F_KAPPA_LO   22u
#define F_KAPPA_HI   23u
#define F_P_FLOOR    25u
#define F_P_CEIL     26u

#define LIM_VEC7(off, lo, hi) \
    {(off), FSW_FT_I32, (lo), (hi)}, {(off) + (uint16_t)4u, FSW_FT_I32, (lo), (hi)}, \
    {(off) + (uint16_t)8u, FSW_FT_I32, (lo), (hi)}, {(off) + (uint16_t)12u, FSW_FT_I32, (lo), (hi)}, \
    {(off) + (uint16_t)16u, FSW_FT_I32, (lo), (hi)}, {(off) + (uint16_t)20u, FSW_FT_I32, (lo), (hi)}, \
    {(off) + (uint16_t)24u, FSW_FT_I32, (lo), (hi)}

static const fsw_field_lim_t OBS_LIMS[] = {
    {0u, FSW_FT_U32, 1000, 1000000},          /* 0 period_us: 1 ms .. 1 s */
    {4u, FSW_FT_U8, 0, 2},                    /* 1 estimator (params_check refuses 1) */
    {5u, FSW_FT_U8, 0, 29},                   /* 2 gyro_cnt_shift */
    {6u, FSW_FT_U8, 0, 29},                   /* 3 act_cnt_shift */
    {7u, FSW_FT_U8, 0, 1},                    /* 4 d2_reject */
    {8u, FSW_FT_I32, -1, 1},                  /* 5 sigma (0 refused by params_check) */
    {12u, FSW_FT_I32, 1, I32MAX},             /* 6 gyro_max_cnt */
    {16u, FSW_FT_I32, 1, I32MAX},             /* 7 act_max_cnt */
    {20u, FSW_FT_I32, 1, I32MAX},             /* 8 bdot_max_q29 */
    {24u, FSW_FT_I32, 1, I32MAX},             /* 9 bdot_hw_q29 */
    {28u, FSW_FT_U8, 16, 40},                 /* 10 q_phi0 (spec 10 §4.5: >= 16 bits) */
    {29u, FSW_FT_U8, 16, 40},                 /* 11 q_phik */
    {30u, FSW_FT_U8, 16, 40},                 /* 12 q_gam0 */
    {31u, FSW_FT_U8, 16, 40},                 /* 13 q_gamk */
    {32u, FSW_FT_U8, 16, 40},                 /* 14 q_d */
    {33u, FSW_FT_U8, 16, 40},                 /* 15 q_w */
    {34u, FSW_FT_U16, 1, 65535},              /* 16 n_lost */
    {36u, FSW_FT_U16, 1, 65535},              /* 17 n_good */
    {38u, FSW_FT_U16, 1, 65535},              /* 18 n_sat */
    {40u, FSW_FT_U16, 1, 65535},              /* 19 n_gap_max */
    {42u, FSW_FT_I32, 1, I32MAX},             /* 20 kappa0_q28 */
    {46u, FSW_FT_I32, 1, I32MAX},             /* 21 kappa_init_q28 */
    {50u, FSW_FT_I32, 1, I32MAX},             /* 22 kappa_lo_q28 */
    {54u, FSW_FT_I32, 1, I32MAX},             /* 23 kappa_hi_q28 */
    {58u, FSW_FT_I32, 1, I32MAX},             /* 24 r_q30 */
    {62u, FSW_FT_I32, 1, I32MAX},             /* 25 p_floor_q30 */
    {66u, FSW_FT_I32, 1, I32MAX},             /* 26 p_ceil_q30 */
    {70u, FSW_FT_I32, 1, I32MAX},             /* 27 d2_max_q16 */
    LIM_VEC7(OFF_LS, -40, 40),                /* 28..34 ls */
    LIM_VEC7(OFF_P0, 1, I32MAX),              /* 35..41 p0_q30 */
    LIM_VEC7(OFF_QD, 4, I32MAX),              /* 42..48 qd_q30: >= 4 LSB (spec 10 §4.5) */
    {646u, FSW_FT_U16, 1, 65535},             /* 49 n_rej_safe */
    {648u, FSW_FT_U16, 1, 65535},             /* 50 rej_leak_inc */
    {650u, FSW_FT_U16, 1, 65535},             /* 51 rej_freeze_on */
};

/* value[a] + margin <= value[b] */
static const fsw_field_rel_t OBS_RELS[] = {
    {(uint8_t)F_BDOT_MAX, (uint8_t)F_BDOT_HW, 0},      /* 0 limit within the hardware */
    {(uint8_t)F_KAPPA_LO, (uint8_t)F_KAPPA_HI, 1},     /* 1 lo < hi */
    {(uint8_t)F_KAPPA_LO, (uint8_t)F_KAPPA0, 0},       /* 2 band holds kappa0 */
    {(uint8_t)F_KAPPA0, (uint8_t)F_KAPPA_HI, 0},       /* 3 */
    {(uint8_t)F_KAPPA_LO, (uint8_t)F_KAPPA_INIT, 0},   /* 4 band holds kappa_init */
    {(uint8_t)F_KAPPA_INIT, (uint8_t)F_KAPPA_HI, 0},   /* 5 */
    {(uint8_t)F_P_FLOOR, (uint8_t)F_P_CEIL, 1},        /* 6 floor < ceiling */
};

const fsw_table_desc_t OBS_TBL_DESC = {
    (uint16_t)OBS_TBL_ID, (uint16_t)OBS_TBL_LAYOUT, OBS_TBL_PAYLOAD,
    OBS_LIMS, (uint32_t)(sizeof(OBS_LIMS) / sizeof(OBS_LIMS[0])),
    OBS_RELS, (uint32_t)(sizeof(OBS_RELS) / sizeof(OBS_RELS[0])),
};

/* int8 <-> int32 without an implementation-defined narrowing (range is checked first). */
static int8_t i8_of(int32_t v)
{
    int8_t r = 0;
    if ((v >= -128) && (v <= 127)) {
        r = (int8_t)v;
    }
    return r;
}

uint32_t obs_table_encode(const obs_params_t *p, uint32_t revision, uint8_t *img, uint32_t cap)
{
    uint32_t n = 0u;
    if ((p != NULL) && (img != NULL) && (cap >= (FSW_TABLE_HDR_BYTES + OBS_TBL_PAYLOAD))) {
        fsw_wr_t w;
        uint32_t i;
        int32_t tmp[OBS_NZ];
        uint8_t *pl = &img[FSW_TABLE_HDR_BYTES];
        fsw_wr_init(&w, pl, OBS_TBL_PAYLOAD);
        fsw_wr_u32(&w, p->period_us);
        fsw_wr_u8(&w, p->estimator);
        fsw_wr_u8(&w, p->gyro_cnt_shift);
        fsw_wr_u8(&w, p->act_cnt_shift);
        fsw_wr_u8(&w, p->d2_reject);
        fsw_wr_i32(&w, (int32_t)p->sigma);
        fsw_wr_i32(&w, p->gyro_max_cnt);
        fsw_wr_i32(&w, p->act_max_cnt);
        fsw_wr_i32(&w, p->bdot_max_q29);
        fsw_wr_i32(&w, p->bdot_hw_q29);
        fsw_wr_u8(&w, p->q_phi0);
        fsw_wr_u8(&w, p->q_phik);
        fsw_wr_u8(&w, p->q_gam0);
        fsw_wr_u8(&w, p->q_gamk);
        fsw_wr_u8(&w, p->q_d);
        fsw_wr_u8(&w, p->q_w);
        fsw_wr_u16(&w, p->n_lost);
        fsw_wr_u16(&w, p->n_good);
        fsw_wr_u16(&w, p->n_sat);
        fsw_wr_u16(&w, p->n_gap_max);
        fsw_wr_i32(&w, p->kappa0_q28);
        fsw_wr_i32(&w, p->kappa_init_q28);
        fsw_wr_i32(&w, p->kappa_lo_q28);
        fsw_wr_i32(&w, p->kappa_hi_q28);
        fsw_wr_i32(&w, p->r_q30);
        fsw_wr_i32(&w, p->p_floor_q30);
        fsw_wr_i32(&w, p->p_ceil_q30);
        fsw_wr_i32(&w, p->d2_max_q16);
        for (i = 0u; i < OBS_NZ; i++) {
            tmp[i] = (int32_t)p->ls[i];
        }
        fsw_wr_i32n(&w, tmp, OBS_NZ);
        fsw_wr_i32n(&w, p->p0_q30, OBS_NZ);
        fsw_wr_i32n(&w, p->qd_q30, OBS_NZ);
        fsw_wr_i32n(&w, p->phi0, OBS_NX * OBS_NX);
        fsw_wr_i32n(&w, p->phik, OBS_NX * OBS_NX);
        fsw_wr_i32n(&w, p->gam0, OBS_NX * OBS_NU);
        fsw_wr_i32n(&w, p->gamk, OBS_NX * OBS_NU);
        fsw_wr_i32n(&w, p->d, OBS_NU * OBS_NX);
        fsw_wr_i32n(&w, p->w, OBS_NZ * OBS_NY);
        fsw_wr_u16(&w, p->n_rej_safe);
        fsw_wr_u16(&w, p->rej_leak_inc);
        fsw_wr_u16(&w, p->rej_freeze_on);
        if ((!w.err) && (w.pos == OBS_TBL_PAYLOAD)) {
            fsw_table_write_header(img, (uint16_t)OBS_TBL_ID, (uint16_t)OBS_TBL_LAYOUT, OBS_TBL_PAYLOAD,
                                   revision);
            n = FSW_TABLE_HDR_BYTES + OBS_TBL_PAYLOAD;
        }
    }
    return n;
}

fsw_rc_t obs_table_decode(const uint8_t *payload, uint32_t len, uint32_t revision,
                              obs_params_t *p)
{
    fsw_rc_t rc = FSW_ERR_ARG;
    if ((payload != NULL) && (p != NULL) && (len == OBS_TBL_PAYLOAD)) {
        fsw_rd_t r;
        uint32_t i;
        int32_t tmp[OBS_NZ];
        obs_params_t *q = p;   /* decoded in place: no 660-byte stack copy (-Wstack-usage) */
        fsw_rd_init(&r, payload, len);
        q->period_us = fsw_rd_u32(&r);
        q->estimator = fsw_rd_u8(&r);
        q->gyro_cnt_shift = fsw_rd_u8(&r);
        q->act_cnt_shift = fsw_rd_u8(&r);
        q->d2_reject = fsw_rd_u8(&r);
        q->sigma = i8_of(fsw_rd_i32(&r));
        q->gyro_max_cnt = fsw_rd_i32(&r);
        q->act_max_cnt = fsw_rd_i32(&r);
        q->bdot_max_q29 = fsw_rd_i32(&r);
        q->bdot_hw_q29 = fsw_rd_i32(&r);
        q->q_phi0 = fsw_rd_u8(&r);
        q->q_phik = fsw_rd_u8(&r);
        q->q_gam0 = fsw_rd_u8(&r);
        q->q_gamk = fsw_rd_u8(&r);
        q->q_d = fsw_rd_u8(&r);
        q->q_w = fsw_rd_u8(&r);
        q->n_lost = fsw_rd_u16(&r);
        q->n_good = fsw_rd_u16(&r);
        q->n_sat = fsw_rd_u16(&r);
        q->n_gap_max = fsw_rd_u16(&r);
        q->kappa0_q28 = fsw_rd_i32(&r);
        q->kappa_init_q28 = fsw_rd_i32(&r);
        q->kappa_lo_q28 = fsw_rd_i32(&r);
        q->kappa_hi_q28 = fsw_rd_i32(&r);
        q->r_q30 = fsw_rd_i32(&r);
        q->p_floor_q30 = fsw_rd_i32(&r);
        q->p_ceil_q30 = fsw_rd_i32(&r);
        q->d2_max_q16 = fsw_rd_i32(&r);
        fsw_rd_i32n(&r, tmp, OBS_NZ);
        for (i = 0u; i < OBS_NZ; i++) {
            q->ls[i] = i8_of(tmp[i]);
        }
        fsw_rd_i32n(&r, q->p0_q30, OBS_NZ);
        fsw_rd_i32n(&r, q->qd_q30, OBS_NZ);
        fsw_rd_i32n(&r, q->phi0, OBS_NX * OBS_NX);
        fsw_rd_i32n(&r, q->phik, OBS_NX * OBS_NX);
        fsw_rd_i32n(&r, q->gam0, OBS_NX * OBS_NU);
        fsw_rd_i32n(&r, q->gamk, OBS_NX * OBS_NU);
        fsw_rd_i32n(&r, q->d, OBS_NU * OBS_NX);
        fsw_rd_i32n(&r, q->w, OBS_NZ * OBS_NY);
        q->n_rej_safe = fsw_rd_u16(&r);
        q->rej_leak_inc = fsw_rd_u16(&r);
        q->rej_freeze_on = fsw_rd_u16(&r);
        q->revision = revision;
        if ((!r.err) && (r.pos == len)) {
            rc = FSW_OK;
        } else {
            rc = FSW_ERR_DECODE;
        }
    }
    return rc;
}
