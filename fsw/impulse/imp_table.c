/*
 * imp_table.c — the impulse-scheduler parameter table on the wire (spec 00 §3.2,
 * 50-impulse §5.7).
 *
 * table_id IMP_TBL_ID (0x0B04), layout_version IMP_TBL_LAYOUT (1), payload IMP_TBL_PAYLOAD (176) bytes, little-endian, field
 * by field (never a struct copy), in the declaration order of imp_params_t. Every field is on
 * the wire except `revision`, which comes from the header (as for the observer). The spare
 * bytes are reserved: on the wire, and required to be zero. Field index (idx) is the detail of
 * a RANGE_LO / RANGE_HI reason word.
 *
 *   idx  off  type    field                  idx  off  type    field
 *     0    0  u32     period_us               30   96  i32     k_vel_m
 *     1    4  u32     subtick_us              31  100  i32     k_tau_m
 *     2    8  u32     t_min_us                32  104  i32     k_tick_m
 *     3   12  u32     plan_lead               33  108  u32     omega_nradps
 *     4   16  u32     replan_period           34  112  u32     a_nom_umps2
 *     5   20  u32     t_stop                  35  116  i32     k_gtau_m
 *     6   24  u32     nav_timeout             36  120  i32     k_gtick_m
 *     7   28  u8      max_iter                37  124  u8      k_gtau_sh
 *     8   29  u8      plan_iter_per_step      38  125  u8      k_gtick_sh
 *     9   30  u8      pivot_ratio_sh          39  126  u8      cal_enable
 *    10   31  u8      k_tau_sh                40  127  u8      cal_pool
 *    11   32  i32     r_tol_lsb               41  128  i32     dv_cal_min_q28
 *    12   36  i32     pivot_min_q26           42  132  i32     cal_gate_q30
 *    13   40  i32     rho_warn_q28            43  136  i32     u_uncal_q30
 *    14   44  i32     rho_reject_q28          44  140  i32     u_cal_q30
 *    15   48  i32     dv_tie_q28              45  144  i32     miss_flag_q28
 *    16   52  i32     tauf_min_q29            46  148  u32     fd_window
 *    17   56  i32     tauf_max_q29            47  152  i32     fd_frac_q30
 *    18   60  i32     w_v_q28                 48  156  u8      fd_persist
 *  19-24  64  i32[6]  alpha_q30            49-51  157  u8[3]   spare2 (zero)
 *    25   88  i32     k_pos_m                 52  160  i32     nav_gate_pos_q28
 *    26   92  u8      k_pos_sh                53  164  i32     nav_gate_vel_q28
 *    27   93  u8      k_vel_sh                54  168  i32     nav_gate_acc_q28
 *    28   94  u8      k_tick_sh               55  172  i32     replan_gain_q30
 *    29   95  u8      spare (zero)                                          (176 = end)
 *
 * The limits descriptor range-checks every field. Where imp_params_check holds the exact rule
 * (fraction ranges, alpha band, tau_f band, shift limits) the descriptor repeats it; where the
 * rule needs code (reciprocal scale pairs, shifts summing to 60, plan_lead against the worst
 * plan, the sub-tick grid dividing the period, fd_window x period <= 60 s, re-plan timing that
 * applies only when replan_period != 0) the descriptor is a plausibility range and
 * imp_params_check, run by the executive on the candidate, is the real invariant. Relations
 * give the orderings the loader can check on raw values of one format.
 */
#include "imp_mission.h"

/* The wire layout is imp_params_t's declaration order without `revision`: a field added to the
   struct must be added to the layout (and layout_version bumped) before this builds again. */
FX_STATIC_ASSERT(imp_tbl_sa_fields, sizeof(imp_params_t) == (IMP_TBL_PAYLOAD + 4u));

/* Offsets of the fields listed by a macro, as uint16_t so that offset + k stays essentially
   uint16_t (MISRA 10.8 forbids casting the composite sum). */
#define OFF_ALPHA   ((uint16_t)64u)
#define OFF_SPARE2  ((uint16_t)157u)

#define I32MAX ((int64_t)INT32_MAX)

/* Raw bounds (the same constants as fsw/impulse/imp.c, spec 50 §5.7), from the core's exact
   constant builders. */
#define ALPHA_MIN   FX_Q_RAT(4, 5, 30)   /* 0.8 in q30 */
#define ALPHA_MAX   FX_Q_RAT(6, 5, 30)   /* 1.2 in q30 */
#define TAU_LO      FX_Q_RAT(1, 5, 29)   /* 0.2 rad in q29 */
#define TAU_HI      FX_Q_INT(2, 29)      /* 2.0 rad in q29 */
#define US_MAX      10000000             /* 10 s: imp_params_check's longest period */
#define STEPS_MAX   10000000             /* step counts: 10^4 s at a 1 ms period */
#define A_NOM_MAX   10000000             /* 10 m/s^2 in um/s^2 */

/* Field indices used by the relations below. */
#define F_PERIOD     0u
#define F_SUBTICK    1u
#define F_T_MIN      2u
#define F_RHO_WARN   13u
#define F_RHO_REJECT 14u
#define F_TAUF_MIN   16u
#define F_TAUF_MAX   17u
#define F_U_UNCAL    43u
#define F_U_CAL      44u

#define LIM_VEC6_I32(off, lo, hi) \
    {(off), FSW_FT_I32, (lo), (hi)}, {(off) + (uint16_t)4u, FSW_FT_I32, (lo), (hi)}, \
    {(off) + (uint16_t)8u, FSW_FT_I32, (lo), (hi)}, {(off) + (uint16_t)12u, FSW_FT_I32, (lo), (hi)}, \
    {(off) + (uint16_t)16u, FSW_FT_I32, (lo), (hi)}, {(off) + (uint16_t)20u, FSW_FT_I32, (lo), (hi)}

#define LIM_VEC3_ZERO(off) \
    {(off), FSW_FT_U8, 0, 0}, {(off) + (uint16_t)1u, FSW_FT_U8, 0, 0}, {(off) + (uint16_t)2u, FSW_FT_U8, 0, 0}

static const fsw_field_lim_t IMP_LIMS[] = {
    {0u, FSW_FT_U32, 1000, US_MAX},              /* 0 period_us: 1 ms .. 10 s */
    {4u, FSW_FT_U32, 0, US_MAX},                 /* 1 subtick_us: 0 = whole steps (divides: check) */
    {8u, FSW_FT_U32, 0, US_MAX},                 /* 2 t_min_us (<= period: relation 0) */
    {12u, FSW_FT_U32, 2, STEPS_MAX},             /* 3 plan_lead (worst plan: check) */
    {16u, FSW_FT_U32, 0, STEPS_MAX},             /* 4 replan_period: 0 = never */
    {20u, FSW_FT_U32, 0, STEPS_MAX},             /* 5 t_stop */
    {24u, FSW_FT_U32, 1, STEPS_MAX},             /* 6 nav_timeout */
    {28u, FSW_FT_U8, 1, 16},                     /* 7 max_iter <= IMP_ITER_CAP */
    {29u, FSW_FT_U8, 4, 255},                    /* 8 plan_iter_per_step >= IMP_ROUND_UNITS */
    {30u, FSW_FT_U8, 0, 30},                     /* 9 pivot_ratio_sh */
    {31u, FSW_FT_U8, 0, 60},                     /* 10 k_tau_sh (sums to 60 with k_tick_sh: check) */
    {32u, FSW_FT_I32, 1, 65536},                 /* 11 r_tol_lsb: <= 2^-12 (7.6 m) */
    {36u, FSW_FT_I32, 1, 67108864},              /* 12 pivot_min_q26: (0, 1] */
    {40u, FSW_FT_I32, 1, FX_Q_INT(1, 28)},               /* 13 rho_warn_q28: (0, 1] */
    {44u, FSW_FT_I32, 1, FX_Q_INT(1, 28)},               /* 14 rho_reject_q28: (0, 1] */
    {48u, FSW_FT_I32, 0, FX_Q_INT(1, 28)},               /* 15 dv_tie_q28 */
    {52u, FSW_FT_I32, TAU_LO, TAU_HI},           /* 16 tauf_min_q29: [0.2, 2.0] rad */
    {56u, FSW_FT_I32, TAU_LO, TAU_HI},           /* 17 tauf_max_q29 */
    {60u, FSW_FT_I32, 1, FX_Q_INT(1, 30)},               /* 18 w_v_q28: (0, 4] (t_w <= 3500 s at 400 km) */
    LIM_VEC6_I32(OFF_ALPHA, ALPHA_MIN, ALPHA_MAX), /* 19..24 alpha_q30: [0.8, 1.2] */
    {88u, FSW_FT_I32, 1, I32MAX},                /* 25 k_pos_m */
    {92u, FSW_FT_U8, 0, 62},                     /* 26 k_pos_sh */
    {93u, FSW_FT_U8, 0, 62},                     /* 27 k_vel_sh */
    {94u, FSW_FT_U8, 1, 60},                     /* 28 k_tick_sh */
    {95u, FSW_FT_U8, 0, 0},                      /* 29 spare: reserved, zero */
    {96u, FSW_FT_I32, 1, I32MAX},                /* 30 k_vel_m */
    {100u, FSW_FT_I32, 1, I32MAX},               /* 31 k_tau_m (reciprocal pair: check) */
    {104u, FSW_FT_I32, 1, I32MAX},               /* 32 k_tick_m */
    {108u, FSW_FT_U32, 1000, 2000000},           /* 33 omega_nradps: 1 urad/s .. 2 mrad/s */
    {112u, FSW_FT_U32, 1, A_NOM_MAX},            /* 34 a_nom_umps2: up to 10 m/s^2 */
    {116u, FSW_FT_I32, 1, I32MAX},               /* 35 k_gtau_m */
    {120u, FSW_FT_I32, 1, I32MAX},               /* 36 k_gtick_m */
    {124u, FSW_FT_U8, 0, 60},                    /* 37 k_gtau_sh */
    {125u, FSW_FT_U8, 0, 60},                    /* 38 k_gtick_sh */
    {126u, FSW_FT_U8, 0, 1},                     /* 39 cal_enable */
    {127u, FSW_FT_U8, 0, 1},                     /* 40 cal_pool */
    {128u, FSW_FT_I32, 0, FX_Q_INT(1, 28)},              /* 41 dv_cal_min_q28: [0, 35 m/s] */
    {132u, FSW_FT_I32, 1, FX_Q_RAT(1, 2, 30)},             /* 42 cal_gate_q30: (0, 0.5] */
    {136u, FSW_FT_I32, 0, FX_Q_RAT(1, 2, 30)},             /* 43 u_uncal_q30: [0, 0.5] */
    {140u, FSW_FT_I32, 0, FX_Q_RAT(1, 2, 30)},             /* 44 u_cal_q30 (<= u_uncal: relation 4) */
    {144u, FSW_FT_I32, 1, I32MAX},               /* 45 miss_flag_q28 */
    {148u, FSW_FT_U32, 1, 60000},                /* 46 fd_window (x period <= 60 s: check) */
    {152u, FSW_FT_I32, 1, FX_Q_INT(1, 30) - 1},          /* 47 fd_frac_q30: (0, 1) */
    {156u, FSW_FT_U8, 1, 255},                   /* 48 fd_persist */
    LIM_VEC3_ZERO(OFF_SPARE2),                   /* 49..51 spare2: reserved, zero */
    {160u, FSW_FT_I32, 1, I32MAX},               /* 52 nav_gate_pos_q28 */
    {164u, FSW_FT_I32, 1, I32MAX},               /* 53 nav_gate_vel_q28 */
    {168u, FSW_FT_I32, 0, I32MAX},               /* 54 nav_gate_acc_q28 */
    {172u, FSW_FT_I32, 0, FX_Q_INT(1, 30) - 1},          /* 55 replan_gain_q30: [0, 1) */
};

/* value[a] + margin <= value[b] */
static const fsw_field_rel_t IMP_RELS[] = {
    {(uint8_t)F_T_MIN, (uint8_t)F_PERIOD, 0},         /* 0 minimum on-time within one step */
    {(uint8_t)F_SUBTICK, (uint8_t)F_PERIOD, 0},       /* 1 sub-tick no longer than the step */
    {(uint8_t)F_RHO_WARN, (uint8_t)F_RHO_REJECT, 0},  /* 2 warn <= reject */
    {(uint8_t)F_TAUF_MIN, (uint8_t)F_TAUF_MAX, 0},    /* 3 tau_f band */
    {(uint8_t)F_U_CAL, (uint8_t)F_U_UNCAL, 0},        /* 4 calibrated <= uncalibrated */
};

const fsw_table_desc_t IMP_TBL_DESC = {
    IMP_TBL_ID, IMP_TBL_LAYOUT, IMP_TBL_PAYLOAD,
    IMP_LIMS, (uint32_t)(sizeof(IMP_LIMS) / sizeof(IMP_LIMS[0])),
    IMP_RELS, (uint32_t)(sizeof(IMP_RELS) / sizeof(IMP_RELS[0])),
};

uint32_t imp_table_encode(const imp_params_t *p, uint32_t revision, uint8_t *img, uint32_t cap)
{
    uint32_t n = 0u;
    if ((p != NULL) && (img != NULL) && (cap >= (FSW_TABLE_HDR_BYTES + IMP_TBL_PAYLOAD))) {
        fsw_wr_t w;
        uint32_t i;
        uint8_t *pl = &img[FSW_TABLE_HDR_BYTES];
        fsw_wr_init(&w, pl, IMP_TBL_PAYLOAD);
        fsw_wr_u32(&w, p->period_us);
        fsw_wr_u32(&w, p->subtick_us);
        fsw_wr_u32(&w, p->t_min_us);
        fsw_wr_u32(&w, p->plan_lead);
        fsw_wr_u32(&w, p->replan_period);
        fsw_wr_u32(&w, p->t_stop);
        fsw_wr_u32(&w, p->nav_timeout);
        fsw_wr_u8(&w, p->max_iter);
        fsw_wr_u8(&w, p->plan_iter_per_step);
        fsw_wr_u8(&w, p->pivot_ratio_sh);
        fsw_wr_u8(&w, p->k_tau_sh);
        fsw_wr_i32(&w, p->r_tol_lsb);
        fsw_wr_i32(&w, p->pivot_min_q26);
        fsw_wr_i32(&w, p->rho_warn_q28);
        fsw_wr_i32(&w, p->rho_reject_q28);
        fsw_wr_i32(&w, p->dv_tie_q28);
        fsw_wr_i32(&w, p->tauf_min_q29);
        fsw_wr_i32(&w, p->tauf_max_q29);
        fsw_wr_i32(&w, p->w_v_q28);
        fsw_wr_i32n(&w, p->alpha_q30, IMP_NTHR);
        fsw_wr_i32(&w, p->k_pos_m);
        fsw_wr_u8(&w, p->k_pos_sh);
        fsw_wr_u8(&w, p->k_vel_sh);
        fsw_wr_u8(&w, p->k_tick_sh);
        fsw_wr_u8(&w, p->spare);
        fsw_wr_i32(&w, p->k_vel_m);
        fsw_wr_i32(&w, p->k_tau_m);
        fsw_wr_i32(&w, p->k_tick_m);
        fsw_wr_u32(&w, p->omega_nradps);
        fsw_wr_u32(&w, p->a_nom_umps2);
        fsw_wr_i32(&w, p->k_gtau_m);
        fsw_wr_i32(&w, p->k_gtick_m);
        fsw_wr_u8(&w, p->k_gtau_sh);
        fsw_wr_u8(&w, p->k_gtick_sh);
        fsw_wr_u8(&w, p->cal_enable);
        fsw_wr_u8(&w, p->cal_pool);
        fsw_wr_i32(&w, p->dv_cal_min_q28);
        fsw_wr_i32(&w, p->cal_gate_q30);
        fsw_wr_i32(&w, p->u_uncal_q30);
        fsw_wr_i32(&w, p->u_cal_q30);
        fsw_wr_i32(&w, p->miss_flag_q28);
        fsw_wr_u32(&w, p->fd_window);
        fsw_wr_i32(&w, p->fd_frac_q30);
        fsw_wr_u8(&w, p->fd_persist);
        for (i = 0u; i < (uint32_t)sizeof(p->spare2); i++) {
            fsw_wr_u8(&w, p->spare2[i]);
        }
        fsw_wr_i32(&w, p->nav_gate_pos_q28);
        fsw_wr_i32(&w, p->nav_gate_vel_q28);
        fsw_wr_i32(&w, p->nav_gate_acc_q28);
        fsw_wr_i32(&w, p->replan_gain_q30);
        if ((!w.err) && (w.pos == IMP_TBL_PAYLOAD)) {
            fsw_table_write_header(img, (uint16_t)IMP_TBL_ID, (uint16_t)IMP_TBL_LAYOUT, IMP_TBL_PAYLOAD,
                                   revision);
            n = FSW_TABLE_HDR_BYTES + IMP_TBL_PAYLOAD;
        }
    }
    return n;
}

fsw_rc_t imp_table_decode(const uint8_t *payload, uint32_t len, uint32_t revision,
                              imp_params_t *p)
{
    fsw_rc_t rc = FSW_ERR_ARG;
    if ((payload != NULL) && (p != NULL) && (len == IMP_TBL_PAYLOAD)) {
        fsw_rd_t r;
        uint32_t i;
        imp_params_t *q = p;   /* decoded in place, as the observer table (no stack copy) */
        fsw_rd_init(&r, payload, len);
        q->period_us = fsw_rd_u32(&r);
        q->subtick_us = fsw_rd_u32(&r);
        q->t_min_us = fsw_rd_u32(&r);
        q->plan_lead = fsw_rd_u32(&r);
        q->replan_period = fsw_rd_u32(&r);
        q->t_stop = fsw_rd_u32(&r);
        q->nav_timeout = fsw_rd_u32(&r);
        q->max_iter = fsw_rd_u8(&r);
        q->plan_iter_per_step = fsw_rd_u8(&r);
        q->pivot_ratio_sh = fsw_rd_u8(&r);
        q->k_tau_sh = fsw_rd_u8(&r);
        q->r_tol_lsb = fsw_rd_i32(&r);
        q->pivot_min_q26 = fsw_rd_i32(&r);
        q->rho_warn_q28 = fsw_rd_i32(&r);
        q->rho_reject_q28 = fsw_rd_i32(&r);
        q->dv_tie_q28 = fsw_rd_i32(&r);
        q->tauf_min_q29 = fsw_rd_i32(&r);
        q->tauf_max_q29 = fsw_rd_i32(&r);
        q->w_v_q28 = fsw_rd_i32(&r);
        fsw_rd_i32n(&r, q->alpha_q30, IMP_NTHR);
        q->k_pos_m = fsw_rd_i32(&r);
        q->k_pos_sh = fsw_rd_u8(&r);
        q->k_vel_sh = fsw_rd_u8(&r);
        q->k_tick_sh = fsw_rd_u8(&r);
        q->spare = fsw_rd_u8(&r);
        q->k_vel_m = fsw_rd_i32(&r);
        q->k_tau_m = fsw_rd_i32(&r);
        q->k_tick_m = fsw_rd_i32(&r);
        q->omega_nradps = fsw_rd_u32(&r);
        q->a_nom_umps2 = fsw_rd_u32(&r);
        q->k_gtau_m = fsw_rd_i32(&r);
        q->k_gtick_m = fsw_rd_i32(&r);
        q->k_gtau_sh = fsw_rd_u8(&r);
        q->k_gtick_sh = fsw_rd_u8(&r);
        q->cal_enable = fsw_rd_u8(&r);
        q->cal_pool = fsw_rd_u8(&r);
        q->dv_cal_min_q28 = fsw_rd_i32(&r);
        q->cal_gate_q30 = fsw_rd_i32(&r);
        q->u_uncal_q30 = fsw_rd_i32(&r);
        q->u_cal_q30 = fsw_rd_i32(&r);
        q->miss_flag_q28 = fsw_rd_i32(&r);
        q->fd_window = fsw_rd_u32(&r);
        q->fd_frac_q30 = fsw_rd_i32(&r);
        q->fd_persist = fsw_rd_u8(&r);
        for (i = 0u; i < (uint32_t)sizeof(q->spare2); i++) {
            q->spare2[i] = fsw_rd_u8(&r);
        }
        q->nav_gate_pos_q28 = fsw_rd_i32(&r);
        q->nav_gate_vel_q28 = fsw_rd_i32(&r);
        q->nav_gate_acc_q28 = fsw_rd_i32(&r);
        q->replan_gain_q30 = fsw_rd_i32(&r);
        q->revision = revision;
        if ((!r.err) && (r.pos == len)) {
            rc = FSW_OK;
        } else {
            rc = FSW_ERR_DECODE;
        }
    }
    return rc;
}
