/*
 * imp_cw.c — Clohessy-Wiltshire kernels and valve-grid units of the impulse scheduler (spec
 * 50-impulse §4, §5.2): the derived trig of sigma, Psi_r, Phi e_r and Phi X (the exact kernels of
 * the solve, the rounding and the nav prediction), the grid units per step and their length, grid
 * units -> tau, and the commanded response of one burn. The bottom of the module: it calls fsw/fx
 * alone.
 *
 * Grid positions are absolute uint64 counts of grid units (step * G + sub-tick), so no
 * arithmetic on them can overflow over any mission; differences fed to the trig kernels are
 * bounded by the horizon (<= 2 rad).
 */
#include "imp.h"
#include "imp_int.h"
#include "fx_inline.h"

#define TWO_OVER_PI_UQ32 UINT64_C(2734261102)         /* 0.6366197724 (2/pi), uq32 */
/* sigma/2 as BAM = sigma_q29 * 2/pi: the product of a q29 magnitude (< 2^31) and the uq32
   constant stays below 2^63, and one rounding shift of 32 gives the BAM. */
#define K_INV72_Q32  INT64_C(59652324)                /* 0.013888889 (1/72) */
#define K_INV42_Q32  INT64_C(102261126)               /* 0.023809524 (1/42) */
#define K_INV20_Q32  INT64_C(214748365)               /* 0.05 (1/20) */
#define K_INV6_Q32   INT64_C(715827883)               /* 0.166666667 (1/6) */
/* Shifts between formats (spec 00 §1.2: named, checked). */
#define SH_T_TO_TRIG   1u   /* q29 -> q30: x 2 */
#define SH_TRIG_TO_M   2u   /* q30 -> q28 */
#define SH_ACC_TO_X    30u  /* q58 -> q28 */
FX_STATIC_ASSERT(imp_sa_t, (IMP_T_Q + SH_T_TO_TRIG) == IMP_TRIG_Q);
FX_STATIC_ASSERT(imp_sa_m, (IMP_TRIG_Q - SH_TRIG_TO_M) == IMP_M_Q);
FX_STATIC_ASSERT(imp_sa_sq, (IMP_T_Q + IMP_T_Q) == (IMP_M_Q + SH_ACC_TO_X));
FX_STATIC_ASSERT(imp_cw_sa_one30, FX_Q_RAT_FITS(1, 1, 30));
FX_STATIC_ASSERT(imp_cw_sa_half29, FX_Q_RAT_FITS(1, 2, 29));

/* ------------------------------------------------------------------ kernels */

/* sigma - sin sigma for |sigma| < 0.5 (m = |sigma| in q30, >= 0):
   sigma^3/6 (1 - sigma^2/20 (1 - sigma^2/42 (1 - sigma^2/72))); truncation < 1e-11. */
static int64_t tms_series(int64_t m_q30, fx_status_t *st)
{
    int64_t u = fx_shr_rnd64_i(m_q30 * m_q30, 30u, st);                         /* sigma^2 */
    int64_t a = (int64_t)FX_Q_INT(1, 30) - fx_shr_rnd64_i(u * K_INV72_Q32, 32u, st);
    int64_t cube;
    a = (int64_t)FX_Q_INT(1, 30) - fx_shr_rnd64_i(fx_shr_rnd64_i(u * a, 30u, st) * K_INV42_Q32, 32u, st);
    a = (int64_t)FX_Q_INT(1, 30) - fx_shr_rnd64_i(fx_shr_rnd64_i(u * a, 30u, st) * K_INV20_Q32, 32u, st);
    cube = fx_shr_rnd64_i(m_q30 * u, 30u, st);
    return fx_shr_rnd64_i(fx_shr_rnd64_i(cube * K_INV6_Q32, 32u, st) * a, 30u, st);
}

void imp_trig(int32_t sig_q29, imp_trig_t *t, fx_status_t *st)
{
    uint32_t m = fx_uabs(sig_q29);
    uint64_t prod = ((uint64_t)m * TWO_OVER_PI_UQ32) + (UINT64_C(1) << 31u);
    uint32_t bh = (uint32_t)(prod >> 32u);
    uint32_t bam_h = (sig_q29 < 0) ? (0u - bh) : bh;
    int32_t sh_q30 = 0;
    int32_t ch_q30 = 0;
    int64_t tms;
    fx_sincos(bam_h, &sh_q30, &ch_q30);
    /* sin = 2 sh ch, 1 - cos = 2 sh^2 (q60 products, one rounding to q30), cos = 1 - (1 - cos). */
    t->s_q30 = fx_rshift_sat_i((int64_t)sh_q30 * (int64_t)ch_q30, 29u, st);
    t->omc_q30 = fx_rshift_sat_i((int64_t)sh_q30 * (int64_t)sh_q30, 29u, st);
    t->c_q30 = fx_sat32_i((int64_t)FX_Q_INT(1, 30) - (int64_t)t->omc_q30, st);
    if (m < (uint32_t)FX_Q_RAT(1, 2, 29)) {
        tms = tms_series((int64_t)m * 2, st);
        if (sig_q29 < 0) {
            tms = -tms;
        }
    } else {
        tms = ((int64_t)sig_q29 * 2) - (int64_t)t->s_q30;
    }
    t->tms_q30 = fx_sat32_i(tms, st);
}

/* q30 (int64) -> q28 with one rounding: v / 4. */
FX_INLINE int32_t m28(int64_t v_q30, fx_status_t *st)
{
    return fx_rshift_sat_i(v_q30, SH_TRIG_TO_M, st);
}

void imp_psi(uint32_t axis, int32_t sig_q29, const imp_trig_t *t, int32_t *psi_q28, fx_status_t *st)
{
    int64_t sg = (int64_t)sig_q29 * 2;              /* q30 */
    int64_t omc = (int64_t)t->omc_q30;
    int64_t tms = (int64_t)t->tms_q30;
    int64_t s = (int64_t)t->s_q30;
    if (axis == 0u) {
        /* 4(1 - c) - 1.5 sigma^2 in q58: 4 omc = omc_q30 * 2^30; sigma^2 exact from q29. */
        int64_t sq = (int64_t)sig_q29 * (int64_t)sig_q29;
        int64_t a = fx_shl64_chk(omc, 30u, st) - (sq + fx_shr_rnd64_i(sq, 1u, st));
        psi_q28[0] = fx_rshift_sat_i(a, SH_ACC_TO_X, st);
        psi_q28[1] = m28(sg - (4 * tms), st);       /* 4 s - 3 sigma = sigma - 4 (sigma - s) */
        psi_q28[2] = m28(-2 * tms, st);
        psi_q28[3] = m28(-2 * omc, st);
    } else if (axis == 1u) {
        psi_q28[0] = m28(2 * tms, st);
        psi_q28[1] = m28(2 * omc, st);
        psi_q28[2] = m28(omc, st);
        psi_q28[3] = m28(s, st);
    } else {
        psi_q28[0] = m28(omc, st);
        psi_q28[1] = m28(s, st);
    }
}

void imp_phie(uint32_t axis, int32_t sig_q29, const imp_trig_t *t, int32_t *col_q28, fx_status_t *st)
{
    int64_t sg = (int64_t)sig_q29 * 2;
    int64_t omc = (int64_t)t->omc_q30;
    int64_t tms = (int64_t)t->tms_q30;
    int64_t s = (int64_t)t->s_q30;
    int64_t c = (int64_t)t->c_q30;
    if (axis == 0u) {
        col_q28[0] = m28(sg - (4 * tms), st);       /* 4 s - 3 sigma */
        col_q28[1] = m28((int64_t)FX_Q_INT(1, 30) - (4 * omc), st);  /* 4 c - 3 */
        col_q28[2] = m28(-2 * omc, st);
        col_q28[3] = m28(-2 * s, st);
    } else if (axis == 1u) {
        col_q28[0] = m28(2 * omc, st);
        col_q28[1] = m28(2 * s, st);
        col_q28[2] = m28(s, st);
        col_q28[3] = m28(c, st);
    } else {
        col_q28[0] = m28(s, st);
        col_q28[1] = m28(c, st);
    }
}

/* Entry v (q30, int64) as q28 in int64: rounded once, never saturated. */
FX_INLINE int64_t e28(int64_t v_q30, fx_status_t *st)
{
    return fx_shr_rnd64_i(v_q30, SH_TRIG_TO_M, st);
}

/* Exact int64 dot product of q28 entries held in int64 (|e| < 2^32: the largest Phi entry over
   sigma <= 2 is 6 (1 - cos 2) = 8.5) with an int32 vector: each product is below 2^63. */
static int64_t row_dot(const int64_t *e_q28, const int32_t *x, uint32_t n, fx_status_t *st)
{
    int64_t acc = 0;
    uint32_t i;
    for (i = 0u; i < n; i++) {
        acc = fx_add64_sat_i(acc, e_q28[i] * (int64_t)x[i], st);
    }
    return acc;
}

void imp_phi_apply(int32_t sig_q29, const imp_trig_t *t, const int32_t *x_q28, int64_t *y_q56, fx_status_t *st)
{
    int64_t sg = (int64_t)sig_q29 * 2;
    int64_t omc = (int64_t)t->omc_q30;
    int64_t tms = (int64_t)t->tms_q30;
    int64_t s = (int64_t)t->s_q30;
    int64_t c = (int64_t)t->c_q30;
    int64_t row[4];
    row[0] = e28((int64_t)FX_Q_INT(1, 30), st);
    row[1] = e28(sg - (4 * tms), st);
    row[2] = e28(6 * tms, st);
    row[3] = e28(2 * omc, st);
    y_q56[0] = row_dot(row, x_q28, 4u, st);
    row[0] = 0;
    row[1] = e28((int64_t)FX_Q_INT(1, 30) - (4 * omc), st);
    row[2] = e28(6 * omc, st);            /* reaches 8.5 at sigma = 2: beyond q28 as int32 */
    row[3] = e28(2 * s, st);
    y_q56[1] = row_dot(row, x_q28, 4u, st);
    row[1] = e28(-2 * omc, st);
    row[2] = e28((int64_t)FX_Q_INT(1, 30) + (3 * omc), st);
    row[3] = e28(s, st);
    y_q56[2] = row_dot(row, x_q28, 4u, st);
    row[1] = e28(-2 * s, st);
    row[2] = e28(3 * s, st);
    row[3] = e28(c, st);
    y_q56[3] = row_dot(row, x_q28, 4u, st);
    row[0] = e28(c, st);
    row[1] = e28(s, st);
    y_q56[4] = row_dot(row, &x_q28[4], 2u, st);
    row[0] = e28(-s, st);
    row[1] = e28(c, st);
    y_q56[5] = row_dot(row, &x_q28[4], 2u, st);
}
/* ------------------------------------------------------------------ valve grid */

uint32_t imp_grid(const imp_params_t *p)
{
    uint32_t g = 1u;
    if ((p->subtick_us != 0u) && (p->subtick_us <= p->period_us)) {
        g = p->period_us / p->subtick_us;
    }
    return g;
}

uint32_t imp_grid_us(const imp_params_t *p)
{
    return (p->subtick_us != 0u) ? p->subtick_us : p->period_us;
}

int32_t imp_g2tau(const imp_params_t *p, uint64_t n, fx_status_t *st)
{
    int32_t t = INT32_MAX;
    if (n > (uint64_t)INT32_MAX) {
        *st |= FX_ST_CONV;
    } else {
        t = fx_rshift_sat((int64_t)n * (int64_t)p->k_gtau_m, p->k_gtau_sh, st);
    }
    return t;
}
void imp_burn_response(imp_state_t *s, const imp_params_t *p, uint32_t j, uint64_t bs, uint64_t be, uint64_t k1g,
                          uint64_t k2g, uint64_t teg, fx_status_t *st)
{
    uint64_t a = (bs > k1g) ? bs : k1g;
    uint64_t b = (be < k2g) ? be : k2g;
    if ((a < b) && (b <= teg)) {
        imp_trig_t t;
        int32_t va[4] = {0, 0, 0, 0};
        int32_t vb[4] = {0, 0, 0, 0};
        uint32_t r = j / 2u;
        uint32_t row0 = 0u;                   /* first state row of the axis's subsystem ... */
        uint32_t nrow = 4u;                   /* ... and its rows */
        if (r == 2u) {
            row0 = 4u;
            nrow = 2u;
        }
        int32_t sa = imp_g2tau(p, teg - a, st);
        int32_t sb = imp_g2tau(p, teg - b, st);
        uint32_t i;
        imp_trig(sa, &t, st);
        imp_psi(r, sa, &t, va, st);
        imp_trig(sb, &t, st);
        imp_psi(r, sb, &t, vb, st);
        for (i = 0u; i < nrow; i++) {
            int64_t d = (int64_t)va[i] - (int64_t)vb[i];
            s->win.r_q28[j][row0 + i] += ((j & 1u) != 0u) ? -d : d;
        }
        s->win.on_g[j] += b - a;
    }
}
