/*
 * rly_table.c — the relay parameter table on the wire (spec 00 §3.2, spec 20 §5.7, §8 F5).
 *
 * table_id RLY_TBL_ID, layout RLY_TBL_LAYOUT, payload RLY_TBL_PAYLOAD (188) bytes, little-endian,
 * field by field. The header revision becomes rly_params_t.revision. Field index: limits below;
 * rly_params_check adds the cross-field rules (gamma < eps <= x_max, k_t order, dphi against the
 * period, ratios) for tables that never went through the loader.
 *
 *   off  type      field                      off  type      field
 *     0  u32       period_us                   44  u8        n_modes
 *     4  i32       x_max_q24                   45  u8        adapt_mode
 *     8  i32       eps_q24                     46  u8 x 2    delta0_num, delta0_den
 *    12  i32       gamma_q24                   48  u8        n_small
 *    16  u32       tau_max_ticks               49  u8        n_ignore
 *    20  u32       win_ticks                   50  u8 x 2    count_before_tmin, learn_after_tmin
 *    24  u32       seed                        52  u8        gate_dk
 *    28  u32       env_alarm_q40               53  u8        probe_settle
 *    32  u16       lost_ticks                  54  u8 x 2    cliff_num, cliff_den
 *    34  u16       tmin_windows                56  u8        retreat_dk
 *    36  u16       dk_q16                      57  u8 x 2    unfreeze_num, unfreeze_den
 *    38  u16 x 3   kt0, kt_min, kt_max (q16)   59  u8        unfreeze_windows
 *    60  u32 x 4   dphi low words              76  u32 x 4   dphi high words (< 2^30)
 *    92  u32 x 4   f low words (Q0.64 turns/s) 108 u32 x 4   f high words
 *   124  i32 x 4   cu_q40                      140 i32 x 4   ce_q40
 *   156  i32 x 4   q0_q40                      172 i32 x 4   p0_q40
 */
#include "rly_mission.h"

#define I32MAX ((int64_t)INT32_MAX)
#define U32MAX ((int64_t)UINT32_MAX)
#define X_FULL ((int64_t)RLY_X_FULL_Q24)
#define C_MAX  ((int64_t)RLY_C_MAX)
#define A_MAX  ((int64_t)RLY_ANCHOR_MAX)

#define LIM4(off, t, lo, hi) \
    {(off), (t), (lo), (hi)}, {(off) + (uint16_t)4u, (t), (lo), (hi)}, \
    {(off) + (uint16_t)8u, (t), (lo), (hi)}, {(off) + (uint16_t)12u, (t), (lo), (hi)}

static const fsw_field_lim_t RLY_LIMS[] = {
    {0u, FSW_FT_U32, 1000, 1000000},            /* 0 period_us */
    {4u, FSW_FT_I32, 1, X_FULL},                /* 1 x_max_q24 */
    {8u, FSW_FT_I32, 1, X_FULL},                /* 2 eps_q24 */
    {12u, FSW_FT_I32, 2, X_FULL},               /* 3 gamma_q24: >= 2 sensor LSB */
    {16u, FSW_FT_U32, 1, 16777216},             /* 4 tau_max_ticks */
    {20u, FSW_FT_U32, 1, (int64_t)RLY_WIN_MAX}, /* 5 win_ticks */
    {24u, FSW_FT_U32, 1, U32MAX},               /* 6 seed: nonzero */
    {28u, FSW_FT_U32, 1, U32MAX},               /* 7 env_alarm_q40 */
    {32u, FSW_FT_U16, 1, 65535},                /* 8 lost_ticks */
    {34u, FSW_FT_U16, 1, 65535},                /* 9 tmin_windows */
    {36u, FSW_FT_U16, 1, 65535},                /* 10 dk_q16 */
    {38u, FSW_FT_U16, 1, 65535},                /* 11 kt0_q16 */
    {40u, FSW_FT_U16, 1, 65535},                /* 12 kt_min_q16 */
    {42u, FSW_FT_U16, 1, 65535},                /* 13 kt_max_q16 */
    {44u, FSW_FT_U8, 0, (int64_t)RLY_MAX_MODES}, /* 14 n_modes */
    {45u, FSW_FT_U8, 0, 3},                     /* 15 adapt_mode */
    {46u, FSW_FT_U8, 1, 255},                   /* 16 delta0_num */
    {47u, FSW_FT_U8, 1, 255},                   /* 17 delta0_den */
    {48u, FSW_FT_U8, 1, 255},                   /* 18 n_small */
    {49u, FSW_FT_U8, 0, 255},                   /* 19 n_ignore */
    {50u, FSW_FT_U8, 0, 1},                     /* 20 count_before_tmin */
    {51u, FSW_FT_U8, 0, 1},                     /* 21 learn_after_tmin */
    {52u, FSW_FT_U8, 1, 255},                   /* 22 gate_dk */
    {53u, FSW_FT_U8, 0, 15},                    /* 23 probe_settle */
    {54u, FSW_FT_U8, 1, 255},                   /* 24 cliff_num */
    {55u, FSW_FT_U8, 1, 255},                   /* 25 cliff_den */
    {56u, FSW_FT_U8, 0, 255},                   /* 26 retreat_dk */
    {57u, FSW_FT_U8, 1, 255},                   /* 27 unfreeze_num */
    {58u, FSW_FT_U8, 1, 255},                   /* 28 unfreeze_den */
    {59u, FSW_FT_U8, 1, 255},                   /* 29 unfreeze_windows */
    LIM4(60u, FSW_FT_U32, 0, U32MAX),           /* 30..33 dphi_lo */
    LIM4(76u, FSW_FT_U32, 0, (int64_t)RLY_DPHI_HI_MAX), /* 34..37 dphi_hi: dphi < 2^62 */
    LIM4(92u, FSW_FT_U32, 0, U32MAX),           /* 38..41 f_lo */
    LIM4(108u, FSW_FT_U32, 0, U32MAX),          /* 42..45 f_hi */
    LIM4(124u, FSW_FT_I32, -C_MAX, C_MAX),      /* 46..49 cu_q40 */
    LIM4(140u, FSW_FT_I32, -C_MAX, C_MAX),      /* 50..53 ce_q40 */
    LIM4(156u, FSW_FT_I32, -A_MAX, A_MAX),      /* 54..57 q0_q40 */
    LIM4(172u, FSW_FT_I32, -A_MAX, A_MAX),      /* 58..61 p0_q40 */
};

/* value[a] + margin <= value[b]: gamma < eps <= x_max, kt_min <= kt0 <= kt_max. */
static const fsw_field_rel_t RLY_RELS[] = {
    {3u, 2u, 1}, {2u, 1u, 0}, {12u, 11u, 0}, {11u, 13u, 0},
};

const fsw_table_desc_t RLY_TBL_DESC = {
    (uint16_t)RLY_TBL_ID, (uint16_t)RLY_TBL_LAYOUT, RLY_TBL_PAYLOAD,
    RLY_LIMS, (uint32_t)(sizeof(RLY_LIMS) / sizeof(RLY_LIMS[0])),
    RLY_RELS, (uint32_t)(sizeof(RLY_RELS) / sizeof(RLY_RELS[0])),
};

static void wr_u64_halves(fsw_wr_t *w, const uint64_t *v, uint32_t hi)
{
    uint32_t i;
    for (i = 0u; i < RLY_MAX_MODES; i++) {
        fsw_wr_u32(w, (uint32_t)((hi != 0u) ? (v[i] >> 32) : (v[i] & 0xFFFFFFFFu)));
    }
}

uint32_t rly_table_encode(const rly_params_t *p, uint32_t revision, uint8_t *img, uint32_t cap)
{
    uint32_t n = 0u;
    if ((p != NULL) && (img != NULL) && (cap >= (FSW_TABLE_HDR_BYTES + RLY_TBL_PAYLOAD))) {
        fsw_wr_t w;
        fsw_wr_init(&w, &img[FSW_TABLE_HDR_BYTES], RLY_TBL_PAYLOAD);
        fsw_wr_u32(&w, p->period_us);
        fsw_wr_i32(&w, p->x_max_q24);
        fsw_wr_i32(&w, p->eps_q24);
        fsw_wr_i32(&w, p->gamma_q24);
        fsw_wr_u32(&w, p->tau_max_ticks);
        fsw_wr_u32(&w, p->win_ticks);
        fsw_wr_u32(&w, p->seed);
        fsw_wr_u32(&w, p->env_alarm_q40);
        fsw_wr_u16(&w, p->lost_ticks);
        fsw_wr_u16(&w, p->tmin_windows);
        fsw_wr_u16(&w, p->dk_q16);
        fsw_wr_u16(&w, p->kt0_q16);
        fsw_wr_u16(&w, p->kt_min_q16);
        fsw_wr_u16(&w, p->kt_max_q16);
        fsw_wr_u8(&w, p->n_modes);
        fsw_wr_u8(&w, p->adapt_mode);
        fsw_wr_u8(&w, p->delta0_num);
        fsw_wr_u8(&w, p->delta0_den);
        fsw_wr_u8(&w, p->n_small);
        fsw_wr_u8(&w, p->n_ignore);
        fsw_wr_u8(&w, p->count_before_tmin);
        fsw_wr_u8(&w, p->learn_after_tmin);
        fsw_wr_u8(&w, p->gate_dk);
        fsw_wr_u8(&w, p->probe_settle);
        fsw_wr_u8(&w, p->cliff_num);
        fsw_wr_u8(&w, p->cliff_den);
        fsw_wr_u8(&w, p->retreat_dk);
        fsw_wr_u8(&w, p->unfreeze_num);
        fsw_wr_u8(&w, p->unfreeze_den);
        fsw_wr_u8(&w, p->unfreeze_windows);
        wr_u64_halves(&w, p->dphi_bam64, 0u);
        wr_u64_halves(&w, p->dphi_bam64, 1u);
        wr_u64_halves(&w, p->f_q64, 0u);
        wr_u64_halves(&w, p->f_q64, 1u);
        fsw_wr_i32n(&w, p->cu_q40, RLY_MAX_MODES);
        fsw_wr_i32n(&w, p->ce_q40, RLY_MAX_MODES);
        fsw_wr_i32n(&w, p->q0_q40, RLY_MAX_MODES);
        fsw_wr_i32n(&w, p->p0_q40, RLY_MAX_MODES);
        if ((!w.err) && (w.pos == RLY_TBL_PAYLOAD)) {
            fsw_table_write_header(img, (uint16_t)RLY_TBL_ID, (uint16_t)RLY_TBL_LAYOUT, RLY_TBL_PAYLOAD, revision);
            n = FSW_TABLE_HDR_BYTES + RLY_TBL_PAYLOAD;
        }
    }
    return n;
}

static void rd_u64_halves(fsw_rd_t *r, uint64_t *v, uint32_t hi)
{
    uint32_t i;
    for (i = 0u; i < RLY_MAX_MODES; i++) {
        uint64_t x = (uint64_t)fsw_rd_u32(r);
        v[i] = (hi != 0u) ? (v[i] | (x << 32)) : x;
    }
}

fsw_rc_t rly_table_decode(const uint8_t *payload, uint32_t len, uint32_t revision, rly_params_t *p)
{
    fsw_rc_t rc = FSW_ERR_ARG;
    if ((payload != NULL) && (p != NULL) && (len == RLY_TBL_PAYLOAD)) {
        fsw_rd_t r;
        fsw_rd_init(&r, payload, len);
        p->period_us = fsw_rd_u32(&r);
        p->x_max_q24 = fsw_rd_i32(&r);
        p->eps_q24 = fsw_rd_i32(&r);
        p->gamma_q24 = fsw_rd_i32(&r);
        p->tau_max_ticks = fsw_rd_u32(&r);
        p->win_ticks = fsw_rd_u32(&r);
        p->seed = fsw_rd_u32(&r);
        p->env_alarm_q40 = fsw_rd_u32(&r);
        p->lost_ticks = fsw_rd_u16(&r);
        p->tmin_windows = fsw_rd_u16(&r);
        p->dk_q16 = fsw_rd_u16(&r);
        p->kt0_q16 = fsw_rd_u16(&r);
        p->kt_min_q16 = fsw_rd_u16(&r);
        p->kt_max_q16 = fsw_rd_u16(&r);
        p->n_modes = fsw_rd_u8(&r);
        p->adapt_mode = fsw_rd_u8(&r);
        p->delta0_num = fsw_rd_u8(&r);
        p->delta0_den = fsw_rd_u8(&r);
        p->n_small = fsw_rd_u8(&r);
        p->n_ignore = fsw_rd_u8(&r);
        p->count_before_tmin = fsw_rd_u8(&r);
        p->learn_after_tmin = fsw_rd_u8(&r);
        p->gate_dk = fsw_rd_u8(&r);
        p->probe_settle = fsw_rd_u8(&r);
        p->cliff_num = fsw_rd_u8(&r);
        p->cliff_den = fsw_rd_u8(&r);
        p->retreat_dk = fsw_rd_u8(&r);
        p->unfreeze_num = fsw_rd_u8(&r);
        p->unfreeze_den = fsw_rd_u8(&r);
        p->unfreeze_windows = fsw_rd_u8(&r);
        rd_u64_halves(&r, p->dphi_bam64, 0u);
        rd_u64_halves(&r, p->dphi_bam64, 1u);
        rd_u64_halves(&r, p->f_q64, 0u);
        rd_u64_halves(&r, p->f_q64, 1u);
        fsw_rd_i32n(&r, p->cu_q40, RLY_MAX_MODES);
        fsw_rd_i32n(&r, p->ce_q40, RLY_MAX_MODES);
        fsw_rd_i32n(&r, p->q0_q40, RLY_MAX_MODES);
        fsw_rd_i32n(&r, p->p0_q40, RLY_MAX_MODES);
        p->revision = revision;
        if ((!r.err) && (r.pos == len)) {
            rc = FSW_OK;
        } else {
            rc = FSW_ERR_DECODE;
        }
    }
    return rc;
}
