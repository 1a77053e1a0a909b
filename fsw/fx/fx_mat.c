/*
 * fx_mat.c — vector/matrix kernels with exact int64 accumulation, and a small linear solve.
 *
 * Kernels form exact int64 products, add them with an overflow check, and round once at the
 * end, so a result is correctly rounded whenever ACC_OVF stays clear (spec 00 §1.6).
 */
#include "fx.h"
#include "fx_inline.h"

/* Powers of two used as int64 scale factors (written out: no signed value is ever shifted). */
#define P2_30_I64 INT64_C(1073741824)       /* 2^30 */

/*
 * Exact sum of n products a[i*sa] * b[i*sb], rounded by `shift` to a saturated int32. On the
 * first int64 overflow the sum stops (it no longer means anything), ACC_OVF is raised and the
 * result is the int32 extreme in the direction of that overflow.
 */
static int32_t dot_rounded(const int32_t *a, uint32_t sa, const int32_t *b, uint32_t sb, uint32_t n,
                           uint32_t shift, fx_status_t *st)
{
    int64_t acc = 0;
    fx_status_t s = 0u;
    uint32_t i;
    int32_t r;
    for (i = 0u; (i < n) && (i < FX_NMAX) && (s == 0u); i++) {
        acc = fx_add64_sat(acc, (int64_t)a[(size_t)i * sa] * (int64_t)b[(size_t)i * sb], &s);
    }
    if (s != 0u) {
        *st |= FX_ST_ACC_OVF | ((acc > 0) ? FX_ST_SAT_HI : FX_ST_SAT_LO);
        r = (acc > 0) ? INT32_MAX : INT32_MIN;
    } else {
        r = fx_rshift_sat(acc, shift, st);
    }
    return r;
}

/* Shared argument check: dims 1..FX_NMAX, formats in range, qa+qb-qr in [0, 62]. */
static bool args_ok(uint32_t qa, uint32_t qb, uint32_t qr, uint32_t d1, uint32_t d2,
                    uint32_t d3, uint32_t *shift, fx_status_t *st)
{
    bool ok = (qa <= FX_Q_MAX) && (qb <= FX_Q_MAX) && (qr <= FX_Q_MAX) &&
              ((qa + qb) >= qr) && ((qa + qb - qr) <= 62u) &&
              (d1 >= 1u) && (d1 <= FX_NMAX) && (d2 >= 1u) && (d2 <= FX_NMAX) &&
              (d3 >= 1u) && (d3 <= FX_NMAX);
    if (ok) {
        *shift = qa + qb - qr;
    } else {
        *st |= FX_ST_ARG;
        *shift = 0u;
    }
    return ok;
}

int32_t fx_dot(const int32_t *a, uint32_t qa, const int32_t *b, uint32_t qb, uint32_t n,
               uint32_t qr, fx_status_t *st)
{
    uint32_t sh;
    int32_t r = 0;
    if (args_ok(qa, qb, qr, n, 1u, 1u, &sh, st)) {
        r = dot_rounded(a, 1u, b, 1u, n, sh, st);
    }
    return r;
}

void fx_matvec(const int32_t *m, uint32_t qm, const int32_t *x, uint32_t qx,
               uint32_t rows, uint32_t cols, int32_t *y, uint32_t qy, fx_status_t *st)
{
    uint32_t sh;
    uint32_t i;
    bool ok = args_ok(qm, qx, qy, rows, cols, 1u, &sh, st);
    for (i = 0u; (i < rows) && (i < FX_NMAX); i++) {
        y[i] = ok ? dot_rounded(&m[(size_t)i * cols], 1u, x, 1u, cols, sh, st) : 0;
    }
}

void fx_matmul(const int32_t *a, uint32_t qa, const int32_t *b, uint32_t qb,
               uint32_t n, uint32_t k, uint32_t m, int32_t *c, uint32_t qc, fx_status_t *st)
{
    uint32_t sh;
    uint32_t i;
    uint32_t j;
    bool ok = args_ok(qa, qb, qc, n, k, m, &sh, st);
    for (i = 0u; (i < n) && (i < FX_NMAX); i++) {
        for (j = 0u; (j < m) && (j < FX_NMAX); j++) {
            c[((size_t)i * m) + j] = ok ? dot_rounded(&a[(size_t)i * k], 1u, &b[j], m, k, sh, st) : 0;
        }
    }
}

int64_t fx_dot_acc(const int32_t *a, const int32_t *b, uint32_t n, fx_status_t *st)
{
    int64_t acc = 0;
    fx_status_t s = 0u;
    uint32_t i;
    if (n > FX_NMAX) {
        *st |= FX_ST_ARG;
    }
    for (i = 0u; (i < n) && (i < FX_NMAX) && (s == 0u); i++) {
        acc = fx_add64_sat(acc, (int64_t)a[i] * (int64_t)b[i], &s);
    }
    *st |= s;
    return acc;
}

int64_t fx_shl64_chk(int64_t v, uint32_t n, fx_status_t *st)
{
    int64_t r = 0;
    if (n > 62u) {
        *st |= FX_ST_ARG;
    } else if (n == 0u) {
        r = v;
    } else {
        /* v 2^n fits int64 iff -2^(63-n) <= v < 2^(63-n). */
        int64_t lim = fx_pow2_64(63u - n, st);
        if ((v >= lim) || (v < -lim)) {
            *st |= FX_ST_ACC_OVF;
            r = (v > 0) ? INT64_MAX : INT64_MIN;
        } else {
            r = v * fx_pow2_64(n, st);
        }
    }
    return r;
}

void fx_vadd(const int32_t *a, const int32_t *b, uint32_t n, int32_t *y, fx_status_t *st)
{
    uint32_t i;
    if (n > FX_NMAX) {
        *st |= FX_ST_ARG;
    }
    for (i = 0u; (i < n) && (i < FX_NMAX); i++) {
        y[i] = fx_add_sat(a[i], b[i], st);
    }
}

void fx_vsub(const int32_t *a, const int32_t *b, uint32_t n, int32_t *y, fx_status_t *st)
{
    uint32_t i;
    if (n > FX_NMAX) {
        *st |= FX_ST_ARG;
    }
    for (i = 0u; (i < n) && (i < FX_NMAX); i++) {
        y[i] = fx_sub_sat(a[i], b[i], st);
    }
}

/* ------------------------------------------------------------------------------ solve */

/* Partial pivoting for column k: swap the row with the largest |a_ik| (lowest index on ties)
   into row k. Returns that magnitude. */
static uint32_t pivot_rows(fx_solve_ws_t *ws, uint32_t n, uint32_t k)
{
    uint32_t p = k;
    uint32_t best = fx_uabs(ws->a[(k * n) + k]);
    uint32_t i;
    for (i = k + 1u; i < n; i++) {
        uint32_t v = fx_uabs(ws->a[(i * n) + k]);
        if (v > best) {
            best = v;
            p = i;
        }
    }
    if (p != k) {
        uint32_t j;
        for (j = 0u; j < n; j++) {
            int32_t t = ws->a[(k * n) + j];
            ws->a[(k * n) + j] = ws->a[(p * n) + j];
            ws->a[(p * n) + j] = t;
        }
        {
            int32_t t = ws->b[k];
            ws->b[k] = ws->b[p];
            ws->b[p] = t;
        }
    }
    ws->perm[k] = (uint8_t)p;
    return best;
}

/* Eliminate column k below the pivot using its reciprocal ws->rec[k]. The multiplier
   l = a_ik / a_kk in q30 comes straight from the reciprocal (relative error <= 2^-30, |l| <= 1 +
   2^-30 by pivoting): the elimination's rounding dominates, so the exact fix-up of fx_recip_div
   would buy nothing here. Each a_ij - l a_kj is formed exactly at 30 extra bits and rounded once;
   the inline rounding (fx_inline.h) keeps the hot loop free of calls. */
static void eliminate(fx_solve_ws_t *ws, uint32_t n, uint32_t k, fx_status_t *st)
{
    uint32_t i;
    uint32_t j;
    const int32_t *ak = &ws->a[(size_t)k * n];
    int32_t rm = ws->rec[k].m;
    uint32_t lsh = 30u - ws->rec[k].sh;
    for (i = k + 1u; i < n; i++) {
        int32_t *ai = &ws->a[(size_t)i * n];
        /* |l| <= 2^30 + 1 (|a_ik| <= |pivot|, m rounded): held in int32 so each product is one
           32 x 32 multiply */
        int32_t l = (int32_t)fx_shr_rnd64_i((int64_t)ai[k] * (int64_t)rm, lsh, st);
        ai[k] = 0;
        for (j = k + 1u; j < n; j++) {
            int64_t v = ((int64_t)ai[j] * P2_30_I64) - ((int64_t)l * (int64_t)ak[j]);
            ai[j] = fx_rshift_sat_i(v, 30u, st);
        }
        {
            int64_t v = ((int64_t)ws->b[i] * P2_30_I64) - ((int64_t)l * (int64_t)ws->b[k]);
            ws->b[i] = fx_rshift_sat_i(v, 30u, st);
        }
    }
}

/* x_i = (b_i - sum_{j>i} a_ij x_j) / a_ii, accumulated exactly in q(qa + qx), bottom up. */
static void back_substitute(const fx_solve_ws_t *ws, uint32_t n, uint32_t b_shift, int32_t *x,
                            fx_status_t *st)
{
    uint32_t k;
    for (k = 0u; k < n; k++) {
        uint32_t ii = n - 1u - k;
        uint32_t j;
        fx_status_t acc = 0u;
        int64_t s = (int64_t)ws->b[ii] * fx_pow2_64(b_shift, st);
        for (j = ii + 1u; j < n; j++) {
            s = fx_add64_sat(s, -((int64_t)ws->a[(ii * n) + j] * (int64_t)x[j]), &acc);
        }
        *st |= acc;
        x[ii] = fx_recip_div(s, &ws->rec[ii], 0u, st);
    }
}

/* fx_solve's and fx_solve_fast's shared part: argument checks, the copy into ws, pivoting and
   elimination; false (and x zeroed) on ARG or SINGULAR. Back substitution scales b from qb to
   qa + qx, so b * 2^e must stay inside int64 (e <= 31). */
static bool factor(fx_solve_ws_t *ws, const int32_t *a, uint32_t qa, const int32_t *b, uint32_t qb,
                   uint32_t n, int32_t *x, uint32_t qx, int32_t pivot_min, fx_status_t *st)
{
    uint32_t i;
    uint32_t k;
    bool fail = false;
    if ((n < 1u) || (n > FX_SOLVE_NMAX) || (qa > FX_Q_MAX) || (qb > FX_Q_MAX) || (qx > FX_Q_MAX) ||
        (qb > (qa + qx)) || ((qa + qx - qb) > 31u)) {
        *st |= FX_ST_ARG;
        fail = true;
    } else {
        for (i = 0u; i < (n * n); i++) {
            ws->a[i] = a[i];
        }
        for (i = 0u; i < n; i++) {
            ws->b[i] = b[i];
        }
    }
    for (k = 0u; (!fail) && (k < n); k++) {
        uint32_t best = pivot_rows(ws, n, k);
        if ((best == 0u) || ((int64_t)best < (int64_t)pivot_min)) {
            *st |= FX_ST_SINGULAR;
            ws->rec[k].d = ws->a[(k * n) + k];
            fail = true;
        } else {
            fx_recip_init(&ws->rec[k], ws->a[(k * n) + k], st);
            eliminate(ws, n, k, st);
        }
    }
    if (fail) {
        for (i = 0u; (i < n) && (i < FX_SOLVE_NMAX); i++) {
            x[i] = 0;
        }
    }
    return !fail;
}

void fx_solve(fx_solve_ws_t *ws, const int32_t *a, uint32_t qa, const int32_t *b, uint32_t qb,
              uint32_t n, int32_t *x, uint32_t qx, int32_t pivot_min, fx_status_t *st)
{
    if (factor(ws, a, qa, b, qb, n, x, qx, pivot_min, st)) {
        back_substitute(ws, n, (qa + qx) - qb, x, st);
    }
}

/* ------------------------------------------------------------------------- fast solve */

/*
 * fx_solve_fast: fx_solve's factor() (the same elimination), and a back substitution that takes
 * each x_i straight from the reciprocal: one product, one rounding, no correction step. Error
 * analysis in fx.h and fsw/fx/README.md.
 */

/* Number of bits of h (0 for 0), for h <= 2^33: 33 above 32 bits, else a bounded binary search
   on 32-bit words (a 64-bit variable shift costs ~15 instructions on Cortex-M3). */
static uint32_t bitlen34(uint64_t h)
{
    uint32_t t = 33u;
    if ((h >> 32) == 0u) {
        uint32_t v = (uint32_t)h;
        uint32_t step = 16u;
        uint32_t i;
        t = 0u;
        for (i = 0u; i < 5u; i++) {
            if ((v >> step) != 0u) {
                v >>= step;
                t += step;
            }
            step >>= 1;
        }
        t += v;
    }
    return t;
}

/*
 * x ~= s / d from the reciprocal r of d (1/d = m 2^(sh - 60)): s is rounded to 31 significant
 * bits (s_hi = rnd(s / 2^t), |s_hi| in [2^30, 2^31] when t > 0), then x = rnd(s_hi m / 2^(60 - sh
 * - t)). Relative error <= 2^-30 (m) + 2^-31 (s_hi) before the final rounding (1/2 LSB).
 * Saturates with SAT_HI / SAT_LO outside int32.
 */
static int32_t quot_fast(int64_t s, const fx_recip_t *r, fx_status_t *st)
{
    uint64_t u = (s < 0) ? ((uint64_t)0 - (uint64_t)s) : (uint64_t)s;
    uint32_t t = bitlen34(u >> 31);
    int32_t sh_r = 60 - (int32_t)r->sh - (int32_t)t;
    int32_t x;
    fx_status_t ignore = 0u;   /* t <= 33, sh_r in [28, 60] below: shifts in range */
    if ((t > 0u) && (sh_r < 28)) {
        /* |s_hi| >= 2^30 and |m| >= 2^29: |x| >= 2^59 / 2^27 = 2^32 */
        bool neg = (s < 0) != (r->m < 0);
        *st |= neg ? FX_ST_SAT_LO : FX_ST_SAT_HI;
        x = neg ? INT32_MIN : INT32_MAX;
    } else {
        int64_t s_hi = fx_shr_rnd64_i(s, t, &ignore);
        x = fx_rshift_sat_i(s_hi * (int64_t)r->m, (uint32_t)sh_r, st);
    }
    return x;
}

/* x_i = (b_i 2^e - sum_{j>i} a_ij x_j) / a_ii, the sum exact in int64, bottom up. */
static void back_substitute_fast(const fx_solve_ws_t *ws, uint32_t n, uint32_t b_shift, int32_t *x,
                                 fx_status_t *st)
{
    uint32_t k;
    int64_t scale = fx_pow2_64(b_shift, st);
    for (k = 0u; k < n; k++) {
        uint32_t ii = n - 1u - k;
        const int32_t *ai = &ws->a[(size_t)ii * n];
        uint32_t j;
        int64_t s = (int64_t)ws->b[ii] * scale;
        for (j = ii + 1u; j < n; j++) {
            s = fx_add64_sat_i(s, -((int64_t)ai[j] * (int64_t)x[j]), st);
        }
        x[ii] = quot_fast(s, &ws->rec[ii], st);
    }
}

void fx_solve_fast(fx_solve_ws_t *ws, const int32_t *a, uint32_t qa, const int32_t *b, uint32_t qb,
                   uint32_t n, int32_t *x, uint32_t qx, int32_t pivot_min, fx_status_t *st)
{
    if (factor(ws, a, qa, b, qb, n, x, qx, pivot_min, st)) {
        back_substitute_fast(ws, n, (qa + qx) - qb, x, st);
    }
}
