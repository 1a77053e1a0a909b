/*
 * rsp_cmg.c — gyrodine steering of the respin (rsp_cmg.h; spec 30 §2, §4, §5).
 *
 * Ranges, worst case over every geometry and |Hdot_c| <= 4.65 N m (the law's bound m (1 + k 30),
 * spec 30 §5), h_g = 7.5 N m s, lambda0 = 0.05; the margin is the format's range over the bound:
 *   sin, cos      Q1.30 from fx_sincos (|err| <= 0.751 LSB, README), exact at multiples of pi/2
 *   Ahat          entries +-s_p, c_p: |.| <= 1                          Q3.28 (margin 8)
 *   P = Ahat Ahat^T + lambda0 I: with the structure of Ahat
 *                 P = [[s3^2 + s4^2, 0, d], [0, s1^2 + s2^2, e], [d, e, sum c_p^2]] + lambda0 I,
 *                 d = -s3 c3 + s4 c4, e = -s1 c1 + s2 c2: diagonal <= 2.05, 2.05, 4.05, |d|, |e| <= 1
 *                                                                     Q3.28 (margin 1.97)
 *   eigenvalues of P in [lambda0, 4.05], so every LDL^T pivot D_i = det P_i / det P_(i-1) lies in
 *                 [lambda0, 4.05] (interlacing): the reciprocals never see a divisor below 0.05
 *   u_ij = L_ij D_j (the unscaled factor): u_10 = 0, u_20 = d, u_21 = e: |u| <= 1     Q3.28
 *   L_20 = d / (s3^2 + s4^2 + lambda0), with |d| <= sqrt(2) r, r^2 = s3^2 + s4^2:
 *                 |L| <= sqrt(2) r / (r^2 + lambda0) <= 1 / sqrt(2 lambda0) = 3.17; L_21 alike,
 *                 L_10 = 0                                            Q3.28 (margin 2.5)
 *   b = Hdot_c / h_g: |b| <= 4.65 / 7.5 = 0.62                        Q1.30 (margin 3.2)
 *   w = D^-1 L^-1 b: w^T D w = b^T P^-1 b <= |b|^2 / lambda0, so |w_i| <= |b| / sqrt(D_i lambda0)
 *                 <= |b| / lambda0 = 12.4                             Q5.26 (margin 2.6)
 *   y = P^-1 b:   |y| <= |b| / lambda0 = 12.4                         Q5.26 (margin 2.6)
 *   beta_dot = Ahat^T P^-1 b: the singular values of Ahat^T P^-1 are sigma / (sigma^2 + lambda0)
 *                 <= 1 / (2 sqrt(lambda0)), so |beta_dot| <= |b| / (2 sqrt(lambda0)) = 1.39 rad/s
 *                                                                     Q3.28 (margin 5.8)
 *   beta_dot in counts before the scaling: <= 1.39 2^16 = 91 000 (int32; int16 only after it)
 *   Ahat beta_dot_cmd: |beta_dot_cmd_p| <= u_max = 0.1745: row z <= 4 u_max = 0.70 rad/s
 *                                                                     Q1.30 (margin 2.9)
 *   M_del = -h_g Ahat beta_dot_cmd: <= 7.5 0.70 = 5.2 N m            2^-24 N m (margin 24)
 *   minors of Ahat (Cauchy-Binet): s3 sin(b1 + b2), -s4 sin(b1 + b2), -s1 sin(b3 + b4),
 *                 s2 sin(b3 + b4): |.| <= 1; m_s <= 1.54 (spec 30 §4)  Q3.28 (margin 5.2)
 * Intermediates are exact int64 sums of int32 products (each < 2^62), added with overflow checks.
 * Inputs outside these ranges (a table beyond its limits, M_cmd beyond 15 N m, an Ahat not made by
 * rsp_cmg_geom) saturate and raise the fx status; nothing is undefined.
 *
 * Rounding: half away from zero (fx), once per value from an exact int64 sum: H, u, D, the L formed
 * inside the factorisation, b, w, y, beta_dot and the counts (no quantity is rounded twice on its way;
 * P is never rounded on its own: u and D take its exact q56 sums). Two exceptions, both far below
 * their golden bounds: a 3x3 minor rounds its three 2x2 cofactors first (q84 does not fit), and M_del
 * rounds Ahat beta_dot_cmd to Q1.30 before the product with h_g (the exact sum is q44 and times h_g
 * q20 would need 96 bits); error <= h_g 2^-31 + 2^-25 N m.
 * Cost (spec 30 §4 "no division near zero"): three reciprocals of the pivots (each >= lambda0), one of
 * h_g, one of max |beta_dot| when the rate is scaled, and multiplies; fx_div once for the reported s.
 */
#include "rsp_cmg.h"

#define CMG_AX        3u                       /* body axes */
#define CMG_NLOW      3u                       /* strict lower entries of a 3x3 factor */
#define CMG_Q28_ONE   ((int32_t)268435456)     /* 1.0 in Q3.28: the largest lambda0 accepted */
#define CMG_CNT_MAX   ((int32_t)32767)         /* int16 command range */
#define CMG_Q28_TO_CNT 12u                     /* Q3.28 rad/s -> counts of 2^-16 rad/s */

/* The factor P = L D L^T (unit lower L), kept as the pivots D_i with their reciprocals and the
   unscaled lower part u_ij = L_ij D_j (no division in it). L itself is formed only where the
   factorisation needs it (L_ij = u_ij / D_j); the solve works with u and D.
   Lower index of (i, j), i > j: (1,0) -> 0, (2,0) -> 1, (2,1) -> 2. */
typedef struct {
    fx_recip_t d[CMG_AX];      /* pivot D_i (Q3.28, >= lambda0) and its reciprocal */
    int32_t u_q28[CMG_NLOW];   /* u_ij = L_ij D_j */
} cmg_ldl_t;

static uint32_t low_idx(uint32_t i, uint32_t j)
{
    return (((i * (i - 1u)) / 2u) + j);
}

/* ------------------------------------------------------------------ geometry */

void rsp_cmg_geom(const uint32_t beta_bam[4], int32_t hg_q20, rsp_cmg_geom_t *g, fx_status_t *st)
{
    int32_t s_q30[RSP_CMG_N];
    int32_t c_q30[RSP_CMG_N];
    int32_t s_q28[RSP_CMG_N];
    int32_t c_q28[RSP_CMG_N];
    int64_t hz_q50 = 0;
    uint32_t p;
    for (p = 0u; p < RSP_CMG_N; p++) {
        /* binary angles wrap by construction: beta and beta + 2^32 are the same word */
        fx_sincos(beta_bam[p], &s_q30[p], &c_q30[p]);
        s_q28[p] = fx_shr_rnd(s_q30[p], 2u, st);   /* |.| <= 2^28: rounds, never saturates */
        c_q28[p] = fx_shr_rnd(c_q30[p], 2u, st);
        hz_q50 = fx_add64_sat(hz_q50, (int64_t)hg_q20 * (int64_t)s_q30[p], st);
    }
    /* H = h_g (c3 - c4, c1 - c2, sum s_p): exact q50 (|c3 - c4| <= 2^31, times h_g < 2^62), one
       rounding each. At the null configuration the sines and cosines cancel bit for bit (fx_sincos
       is exactly odd and even), so H = 0 exactly there. */
    g->h_q20[0] = fx_rshift_sat((int64_t)hg_q20 * ((int64_t)c_q30[2] - (int64_t)c_q30[3]), 30u, st);
    g->h_q20[1] = fx_rshift_sat((int64_t)hg_q20 * ((int64_t)c_q30[0] - (int64_t)c_q30[1]), 30u, st);
    g->h_q20[2] = fx_rshift_sat(hz_q50, 30u, st);
    /* Ahat: columns (0, -s1, c1), (0, s2, c2), (-s3, 0, c3), (s4, 0, c4); a negated rounded value
       is the rounded negated value (half away from zero is odd) */
    g->ahat_q28[0][0] = 0;
    g->ahat_q28[0][1] = 0;
    g->ahat_q28[0][2] = -s_q28[2];
    g->ahat_q28[0][3] = s_q28[3];
    g->ahat_q28[1][0] = -s_q28[0];
    g->ahat_q28[1][1] = s_q28[1];
    g->ahat_q28[1][2] = 0;
    g->ahat_q28[1][3] = 0;
    for (p = 0u; p < RSP_CMG_N; p++) {
        g->ahat_q28[2][p] = c_q28[p];
    }
}

/* ------------------------------------------------------------------ singularity measure */

/* a b - c d exactly (each product <= 2^62 in magnitude; ACC_OVF only for the int64 extreme). */
static int64_t cross64(int32_t a, int32_t b, int32_t c, int32_t d, fx_status_t *st)
{
    return fx_add64_sat((int64_t)a * (int64_t)b, -((int64_t)c * (int64_t)d), st);
}

/* Determinant of the 3x3 minor of Ahat without column `skip`, Q3.28: cofactor expansion along the
   first row over the kept columns k0 < k1 < k2 taken cyclically, det = sum_r A0(kr) (A1(kr+1)
   A2(kr+2) - A1(kr+2) A2(kr+1)); each cofactor is rounded to Q3.28 (q56 times q28 would not fit),
   the sum of the three q56 products once. Error <= 3 |A0| 1/2 + 1/2 <= 2 LSB. */
static int32_t minor_q28(const rsp_cmg_geom_t *g, uint32_t skip, fx_status_t *st)
{
    uint32_t col[CMG_AX] = {0u, 0u, 0u};
    uint32_t n = 0u;
    uint32_t j;
    uint32_t r;
    int64_t acc = 0;
    for (j = 0u; j < RSP_CMG_N; j++) {
        if ((j != skip) && (n < CMG_AX)) {
            col[n] = j;
            n++;
        }
    }
    for (r = 0u; r < CMG_AX; r++) {
        uint32_t a = col[r];
        uint32_t b = col[(r + 1u) % CMG_AX];
        uint32_t c = col[(r + 2u) % CMG_AX];
        int64_t cof_q56 = cross64(g->ahat_q28[1][b], g->ahat_q28[2][c], g->ahat_q28[1][c], g->ahat_q28[2][b], st);
        int32_t cof_q28 = fx_rshift_sat(cof_q56, 28u, st);
        acc = fx_add64_sat(acc, (int64_t)g->ahat_q28[0][a] * (int64_t)cof_q28, st);
    }
    return fx_rshift_sat(acc, 28u, st);
}

/* m_s (rsp_cmg_ms_q28 and the steering's telemetry) */
static int32_t ms_q28(const rsp_cmg_geom_t *g, fx_status_t *st)
{
    uint64_t sum_q56 = 0u;
    uint64_t r;
    uint32_t k;
    for (k = 0u; k < RSP_CMG_N; k++) {
        uint64_t m = (uint64_t)fx_uabs(minor_q28(g, k, st));
        uint64_t sq = m * m;   /* <= 2^62 */
        if (sq > (UINT64_MAX - sum_q56)) {
            /* four minors at the int32 extreme only: not a geometry of rsp_cmg_geom */
            *st |= FX_ST_ACC_OVF;
            sum_q56 = UINT64_MAX;
        } else {
            sum_q56 += sq;
        }
    }
    /* m_s = sqrt(sum) in Q3.28, rounded to nearest: the floor root r, plus one when
       sum >= (r + 1/2)^2, i.e. sum - r^2 > r (integers) */
    r = (uint64_t)fx_isqrt64(sum_q56);
    if ((sum_q56 - (r * r)) > r) {
        r++;
    }
    return fx_sat32((int64_t)r, st);   /* r <= 2^32 */
}

int32_t rsp_cmg_ms_q28(const rsp_cmg_geom_t *g, fx_status_t *st)
{
    return ms_q28(g, st);
}

/* ------------------------------------------------------------------ the damped solve */

/* round((A_i . A_j + extra) / 2^28): one rounding of an exact q56 sum (A_i: row i of Ahat). */
static int32_t ldl_entry(const rsp_cmg_geom_t *g, uint32_t i, uint32_t j, int64_t extra_q56, fx_status_t *st)
{
    int64_t acc = fx_dot_acc(g->ahat_q28[i], g->ahat_q28[j], RSP_CMG_N, st);
    return fx_rshift_sat(fx_add64_sat(acc, extra_q56, st), 28u, st);
}

/* LDL^T of P = Ahat Ahat^T + lambda0 I (3x3, written out). Each entry of the factor is one rounding
   of an exact q56 sum: P_ij 2^28 (the q56 dot product of rows i and j of Ahat, lambda0 2^28 added on
   the diagonal) minus the q56 products of the factor so far:
     D_0 = P_00
     u_10 = P_10                      L_10 = u_10 / D_0
     D_1 = P_11 - u_10 L_10
     u_20 = P_20                      L_20 = u_20 / D_0
     u_21 = P_21 - u_20 L_10          L_21 = u_21 / D_1
     D_2 = P_22 - u_20 L_20 - u_21 L_21
   L (Q3.28) is one correctly rounded quotient each, used here only (the solve needs u and D). For this
   cluster P_10 = 0 (rows x and y of Ahat have disjoint support), so u_10 = L_10 = 0, u_20 = d, u_21 = e.
   Each product is < 2^62 and lambda0 2^28 <= 2^56: the first difference cannot overflow int64, the
   second sum of D_2 is checked. A pivot below lambda0 / 2 cannot come from a geometry of rsp_cmg_geom
   (D_i >= lambda0 up to a few LSB): it raises FX_ST_SINGULAR, and a zero pivot DIV0 (fx_recip_init). */
static void ldl_factor(const rsp_cmg_params_t *p, const rsp_cmg_geom_t *g, cmg_ldl_t *f, fx_status_t *st)
{
    int64_t lam_q56 = (int64_t)p->lambda_q28 * (int64_t)CMG_Q28_ONE;
    int64_t d2_q56;
    int32_t l10_q28;
    int32_t l20_q28;
    int32_t l21_q28;
    uint32_t i;
    fx_recip_init(&f->d[0], ldl_entry(g, 0u, 0u, lam_q56, st), st);
    f->u_q28[0] = ldl_entry(g, 1u, 0u, 0, st);
    l10_q28 = fx_recip_div((int64_t)f->u_q28[0], &f->d[0], 28u, st);
    fx_recip_init(&f->d[1], ldl_entry(g, 1u, 1u, lam_q56 - ((int64_t)f->u_q28[0] * (int64_t)l10_q28), st), st);
    f->u_q28[1] = ldl_entry(g, 2u, 0u, 0, st);
    l20_q28 = fx_recip_div((int64_t)f->u_q28[1], &f->d[0], 28u, st);
    f->u_q28[2] = ldl_entry(g, 2u, 1u, -((int64_t)f->u_q28[1] * (int64_t)l10_q28), st);
    l21_q28 = fx_recip_div((int64_t)f->u_q28[2], &f->d[1], 28u, st);
    d2_q56 = fx_add64_sat(lam_q56 - ((int64_t)f->u_q28[1] * (int64_t)l20_q28),
                          -((int64_t)f->u_q28[2] * (int64_t)l21_q28), st);
    fx_recip_init(&f->d[2], ldl_entry(g, 2u, 2u, d2_q56, st), st);
    for (i = 0u; i < CMG_AX; i++) {
        if (f->d[i].d < (p->lambda_q28 / 2)) {
            *st |= FX_ST_SINGULAR;
        }
    }
}

/* Solve L D L^T y = b in place (v: b in Q1.30 in, y in Q5.26 out), with U = D L^T (U_ij = u_ji):
     forward   w_i = (b_i - sum_{k<i} u_ik w_k) / D_i           (L z = b, z_k = D_k w_k)
     backward  y_i = (D_i w_i - sum_{j>i} u_ji y_j) / D_i        (U y = z)
   Each numerator is an exact q54 sum (Q1.30 2^24, Q3.28 times Q5.26), divided once by D_i (Q3.28)
   through its reciprocal: one correctly rounded Q5.26 value each, no L rounding in the solve. */
static void ldl_solve(const cmg_ldl_t *f, int32_t v[3], fx_status_t *st)
{
    uint32_t i;
    uint32_t k;
    for (i = 0u; i < CMG_AX; i++) {
        int64_t acc = fx_shl64_chk((int64_t)v[i], 24u, st);   /* Q1.30 -> q54, exact (< 2^55) */
        for (k = 0u; k < i; k++) {
            acc = fx_add64_sat(acc, -((int64_t)f->u_q28[low_idx(i, k)] * (int64_t)v[k]), st);
        }
        v[i] = fx_recip_div(acc, &f->d[i], 0u, st);
    }
    for (i = CMG_AX; i > 0u; i--) {
        uint32_t r = i - 1u;
        int64_t acc = (int64_t)f->d[r].d * (int64_t)v[r];   /* D_r w_r: q54, < 2^62 */
        for (k = i; k < CMG_AX; k++) {
            acc = fx_add64_sat(acc, -((int64_t)f->u_q28[low_idx(k, r)] * (int64_t)v[k]), st);
        }
        v[r] = fx_recip_div(acc, &f->d[r], 0u, st);
    }
}

/* ------------------------------------------------------------------ command */

/* Gimbal-rate counts from beta_dot (Q3.28): round(beta_dot 2^16), or, when max |beta_dot| exceeds
   u_max (s > 1, decided exactly in Q3.28), round(beta_dot u_max / max |beta_dot|) per component:
   one correctly rounded quotient each (fx_recip), the largest component lands on +-umax_cnt and
   the ratios are those of beta_dot up to 1/2 count. The final clamp holds the limit in counts
   whatever came before (a no-op here: |quotient| <= umax_cnt). Returns true when scaled. */
static bool rate_counts(const rsp_cmg_params_t *p, rsp_cmg_out_t *o, fx_status_t *st)
{
    uint32_t max_q28 = 0u;
    int64_t lim_q28 = (int64_t)p->umax_cnt * (int64_t)4096;   /* umax_cnt 2^12 */
    bool scaled;
    fx_status_t tlm = 0u;   /* s is telemetry: its Q16.16 clip must not zero the command */
    fx_recip_t r;
    uint32_t k;
    for (k = 0u; k < RSP_CMG_N; k++) {
        uint32_t a = fx_uabs(o->rate_q28[k]);
        if (a > max_q28) {
            max_q28 = a;
        }
    }
    /* s = max / u_max with u_max = umax_cnt in Q16 rad/s */
    o->s_q16 = fx_div(fx_sat32((int64_t)max_q28, &tlm), 28u, p->umax_cnt, 16u, 16u, &tlm);
    scaled = (int64_t)max_q28 > lim_q28;
    if (scaled) {
        fx_recip_init(&r, fx_sat32((int64_t)max_q28, st), st);   /* 2^31 only if a rate saturated */
    }
    for (k = 0u; k < RSP_CMG_N; k++) {
        int32_t c;
        if (scaled) {
            c = fx_recip_div((int64_t)o->rate_q28[k] * (int64_t)p->umax_cnt, &r, 0u, st);
        } else {
            c = fx_rshift_sat((int64_t)o->rate_q28[k], CMG_Q28_TO_CNT, st);
        }
        if (c > p->umax_cnt) {
            c = p->umax_cnt;
        } else if (c < -p->umax_cnt) {
            c = -p->umax_cnt;
        } else {
            /* inside the limit */
        }
        o->rate_cnt[k] = (int16_t)c;   /* |c| <= umax_cnt <= 32767 */
    }
    return scaled;
}

/* M_del = -h_g Ahat beta_dot_cmd: the exact q44 sum of Ahat (Q3.28) times counts (2^-16 rad/s),
   |.| < 4 2^31 2^15 = 2^48 (no overflow), rounded to Q1.30, times h_g (q50), rounded to 2^-24 N m. */
static void delivered(const rsp_cmg_params_t *p, const rsp_cmg_geom_t *g, rsp_cmg_out_t *o, fx_status_t *st)
{
    uint32_t i;
    uint32_t k;
    for (i = 0u; i < CMG_AX; i++) {
        int64_t a_q44 = 0;
        int32_t a_q30;
        for (k = 0u; k < RSP_CMG_N; k++) {
            a_q44 += (int64_t)g->ahat_q28[i][k] * (int64_t)o->rate_cnt[k];
        }
        a_q30 = fx_rshift_sat(a_q44, 14u, st);
        o->mdel_q24[i] = fx_rshift_sat(-((int64_t)p->hg_q20 * (int64_t)a_q30), 26u, st);   /* |.| <= 2^62 */
    }
}

/* b = Hdot_c / h_g = -M_cmd / h_g: round(-M_q24 2^26 / h_g_q20) is Q1.30 (one reciprocal of h_g). */
static void rhs(const rsp_cmg_params_t *p, const int32_t mcmd_q24[3], int32_t b_q30[3], fx_status_t *st)
{
    fx_recip_t rhg;
    uint32_t i;
    fx_recip_init(&rhg, p->hg_q20, st);
    for (i = 0u; i < CMG_AX; i++) {
        b_q30[i] = fx_recip_div(-(int64_t)mcmd_q24[i], &rhg, 26u, st);
    }
}

/* beta_dot_k = sum_i Ahat_ik y_i: q54, one rounding to Q3.28. */
static void rates(const rsp_cmg_geom_t *g, const int32_t y_q26[3], rsp_cmg_out_t *o, fx_status_t *st)
{
    uint32_t i;
    uint32_t k;
    for (k = 0u; k < RSP_CMG_N; k++) {
        int64_t acc = 0;
        for (i = 0u; i < CMG_AX; i++) {
            acc = fx_add64_sat(acc, (int64_t)g->ahat_q28[i][k] * (int64_t)y_q26[i], st);
        }
        o->rate_q28[k] = fx_rshift_sat(acc, 26u, st);
    }
}

static bool params_ok(const rsp_cmg_params_t *p)
{
    return (p->hg_q20 > 0) && (p->lambda_q28 > 0) && (p->lambda_q28 <= CMG_Q28_ONE) && (p->umax_cnt >= 1) &&
           (p->umax_cnt <= CMG_CNT_MAX);
}

void rsp_cmg_steer(const rsp_cmg_params_t *p, const rsp_cmg_geom_t *g, const int32_t mcmd_q24[3],
                   rsp_cmg_out_t *o, fx_status_t *st)
{
    static const rsp_cmg_out_t out_zero = {0};   /* rodata: a struct copy without a stack temporary */
    fx_status_t s = 0u;   /* this call's status: a bit here zeroes the command */
    *o = out_zero;
    if (!params_ok(p)) {
        s |= FX_ST_ARG;
    } else {
        o->ms_q28 = ms_q28(g, &s);
        if (o->ms_q28 < p->ms_sing_q28) {
            o->flags |= RSP_CMG_F_SINGULAR;
        }
        {
            /* the factor and the solve vector end here: their stack is reused below (frame budget) */
            cmg_ldl_t f;
            int32_t v[CMG_AX];   /* b (Q1.30), then w and y (Q5.26), in place */
            rhs(p, mcmd_q24, v, &s);
            ldl_factor(p, g, &f, &s);
            ldl_solve(&f, v, &s);
            rates(g, v, o, &s);
        }
        if (rate_counts(p, o, &s)) {
            o->flags |= RSP_CMG_F_RATE_LIMITED;
        }
        delivered(p, g, o, &s);
        if (s != 0u) {
            /* spec 30 §5: a status in the step zeroes its command; M_del = 0 is then what the
               cluster delivers */
            uint32_t i;
            for (i = 0u; i < RSP_CMG_N; i++) {
                o->rate_cnt[i] = 0;
            }
            for (i = 0u; i < CMG_AX; i++) {
                o->mdel_q24[i] = 0;
            }
        }
    }
    *st |= s;
}
