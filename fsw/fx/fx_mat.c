/*
 * fx_mat.c — vector/matrix kernels with exact int64 accumulation, and a small linear solve.
 *
 * Kernels form exact int64 products, add them with an overflow check, and round once at the
 * end, so a result is correctly rounded whenever ACC_OVF stays clear (spec 00 §1.6).
 */
#include "fx.h"
#include "fx_inline.h"

/* Powers of two used as int64 scale factors (written out: no signed value is ever shifted). */
#define P2_29_I64 INT64_C(536870912)        /* 2^29 */
#define P2_30_I64 INT64_C(1073741824)       /* 2^30 */
#define P2_60_I64 INT64_C(1152921504606846976)   /* 2^60 */

/* int64 with the value of u mod 2^64 (two's complement), without an implementation-defined
   conversion. */
static int64_t u2s64(uint64_t u)
{
    int64_t r;
    if (u <= (uint64_t)INT64_MAX) {
        r = (int64_t)u;
    } else {
        uint64_t c = UINT64_MAX - u;   /* < 2^63 */
        r = -(int64_t)c - 1;
    }
    return r;
}

static uint64_t mag64(int64_t v)
{
    return (v < 0) ? ((uint64_t)0 - (uint64_t)v) : (uint64_t)v;
}

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
    /* The inlined twins (fx_inline.h): out of line, the add and the final shift were calls costing
       more than the multiply-accumulate itself (obs_step spent a third of its time in them). */
    for (i = 0u; (i < n) && (i < FX_NMAX) && (s == 0u); i++) {
        acc = fx_add64_sat_i(acc, (int64_t)a[(size_t)i * sa] * (int64_t)b[(size_t)i * sb], &s);
    }
    if (s != 0u) {
        *st |= FX_ST_ACC_OVF | ((acc > 0) ? FX_ST_SAT_HI : FX_ST_SAT_LO);
        r = (acc > 0) ? INT32_MAX : INT32_MIN;
    } else {
        r = fx_rshift_sat_i(acc, shift, st);
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
        acc = fx_add64_sat_i(acc, (int64_t)a[i] * (int64_t)b[i], &s);
    }
    *st |= s;
    return acc;
}

/* w v exactly, or ACC_OVF and the int64 extreme of the product's sign when it does not fit. */
static int64_t mul_wide(int64_t w, int32_t v, fx_status_t *st)
{
    int64_t r;
    if ((w >= (int64_t)INT32_MIN) && (w <= (int64_t)INT32_MAX)) {
        r = w * (int64_t)v;   /* |r| <= 2^62: the common case, one 32 x 32 multiply */
    } else {
        bool neg = (w < 0) != (v < 0);
        uint64_t mw = mag64(w);
        uint64_t mv = mag64((int64_t)v);                 /* <= 2^31 */
        uint64_t hi = (mw >> 32) * mv;                   /* <= 2^62 */
        uint64_t lo = (mw & UINT64_C(0xFFFFFFFF)) * mv;  /* < 2^63 */
        uint64_t lim = neg ? ((uint64_t)INT64_MAX + 1u) : (uint64_t)INT64_MAX;
        /* hi <= 2^31: hi 2^32 <= 2^63 and + lo < 2^64, no wrap (hi = 2^31, lo = 0 is -2^63). */
        if ((hi > UINT64_C(0x80000000)) || (((hi << 32) + lo) > lim)) {
            *st |= FX_ST_ACC_OVF;
            r = neg ? INT64_MIN : INT64_MAX;
        } else {
            uint64_t m = (hi << 32) + lo;
            r = neg ? u2s64((uint64_t)0 - m) : (int64_t)m;
        }
    }
    return r;
}

int32_t fx_dot_wide(const int32_t *a, const int32_t *b, uint32_t sb, uint32_t n, int64_t w, int32_t v,
                    uint32_t shift, fx_status_t *st)
{
    fx_status_t s = 0u;
    int32_t r = 0;
    if ((n > FX_NMAX) || (shift > 62u)) {
        *st |= FX_ST_ARG;
    } else {
        int64_t acc = mul_wide(w, v, &s);
        uint32_t i;
        for (i = 0u; (i < n) && (i < FX_NMAX) && (s == 0u); i++) {
            acc = fx_add64_sat_i(acc, (int64_t)a[i] * (int64_t)b[(size_t)i * sb], &s);
        }
        if (s != 0u) {
            *st |= FX_ST_ACC_OVF | ((acc > 0) ? FX_ST_SAT_HI : FX_ST_SAT_LO);
            r = (acc > 0) ? INT32_MAX : INT32_MIN;
        } else {
            r = fx_rshift_sat_i(acc, shift, st);
        }
    }
    return r;
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

/*
 * Error model (fsw/fx/README.md, "fx_solve"). The old elimination rounded every updated entry to
 * one LSB of qa, a backward error of 1/2 LSB per entry and step; its effect on x grows with
 * kappa |x| / |A| and broke the 2 n kappa bound once |x| (LSB of qx) exceeded |A| (LSB of qa).
 * Here the working matrix W and right-hand side C are int64, each normalised so that its largest
 * input entry has 31 bits and then given SOLVE_G more fraction bits: a rounding costs 2^-55 of
 * max|a|, and the multipliers are exact to 2^-58 (two terms from an exact residual). What is left
 * is the back substitution's rounding of each x_i, which it does once and correctly from an exact
 * 128-bit sum.
 */
#define SOLVE_G 24u   /* guard bits below the normalised 31-bit scale; W < 2^55, < 2^58 after growth */

/* Unsigned 128-bit value as two words (only for the solve's exact sums and products). */
typedef struct {
    uint64_t hi;
    uint64_t lo;
} u128_t;

/* Bits of v (0 for 0): a bounded binary search. */
static uint32_t bitlen64(uint64_t v)
{
    uint64_t w = v;
    uint32_t t = 0u;
    uint32_t step = 32u;
    uint32_t i;
    for (i = 0u; i < 6u; i++) {
        if ((w >> step) != 0u) {
            w >>= step;
            t += step;
        }
        step >>= 1;
    }
    return t + (uint32_t)w;
}

/* u v exactly, u <= 2^63, v < 2^32: two 32 x 32 products. */
static u128_t umul64x32(uint64_t u, uint64_t v)
{
    u128_t r;
    uint64_t p0 = (u & UINT64_C(0xFFFFFFFF)) * v;   /* < 2^64 */
    uint64_t p1 = (u >> 32) * v;                    /* < 2^63 */
    r.lo = p0 + (p1 << 32);
    r.hi = (p1 >> 32) + ((r.lo < p0) ? 1u : 0u);
    return r;
}

/* round(x / 2^sh) on a magnitude, sh in [1, 127]; the caller guarantees a result below 2^63. */
static uint64_t shr128_rnd(u128_t x, uint32_t sh)
{
    uint64_t q;
    uint64_t rb;
    if (sh < 64u) {
        q = (x.lo >> sh) | (x.hi << (64u - sh));
        rb = (x.lo >> (sh - 1u)) & 1u;
    } else if (sh == 64u) {
        q = x.hi;
        rb = x.lo >> 63;
    } else {
        q = x.hi >> (sh - 64u);
        rb = (x.hi >> (sh - 65u)) & 1u;
    }
    return q + rb;
}

/* round(v f / 2^sh), half away from zero; |f| < 2^32, sh in [1, 127], result below 2^63 in
   magnitude (guaranteed by every caller's ranges, stated at the call). */
static int64_t mul_shr(int64_t v, int64_t f, uint32_t sh)
{
    uint64_t q = shr128_rnd(umul64x32(mag64(v), mag64(f)), sh);
    return ((v < 0) != (f < 0)) ? -(int64_t)q : (int64_t)q;
}

/* Two's complement 128-bit arithmetic for the back substitution's exact sum. */
static u128_t s128_from64(int64_t v)
{
    u128_t r;
    r.lo = (uint64_t)v;
    r.hi = (v < 0) ? UINT64_MAX : 0u;
    return r;
}

static u128_t add128(u128_t a, u128_t b)
{
    u128_t r;
    r.lo = a.lo + b.lo;
    r.hi = a.hi + b.hi + ((r.lo < a.lo) ? 1u : 0u);
    return r;
}

static u128_t neg128(u128_t a)
{
    u128_t r;
    u128_t one;
    r.hi = ~a.hi;
    r.lo = ~a.lo;
    one.hi = 0u;
    one.lo = 1u;
    return add128(r, one);
}

/* Partial pivoting for column k: swap the row with the largest |w_ik| (lowest index on ties)
   into row k. Returns that magnitude. */
static uint64_t pivot_rows(fx_solve_ws_t *ws, uint32_t n, uint32_t k)
{
    uint32_t p = k;
    uint64_t best = mag64(ws->a[(k * n) + k]);
    uint32_t i;
    for (i = k + 1u; i < n; i++) {
        uint64_t v = mag64(ws->a[(i * n) + k]);
        if (v > best) {
            best = v;
            p = i;
        }
    }
    if (p != k) {
        uint32_t j;
        for (j = 0u; j < n; j++) {
            int64_t t = ws->a[(k * n) + j];
            ws->a[(k * n) + j] = ws->a[(p * n) + j];
            ws->a[(p * n) + j] = t;
        }
        {
            int64_t t = ws->b[k];
            ws->b[k] = ws->b[p];
            ws->b[p] = t;
        }
    }
    ws->perm[k] = (uint8_t)p;
    return best;
}

/*
 * Reciprocal of the pivot's 31 leading bits P (|p| = P 2^e within 2^-31): pm = round(2^60 / P),
 * in [2^29, 2^30]. No divide: Newton's iteration m += m (2^60 - P m) / 2^60 squares the relative
 * error, started from the pivot's fx_recip_t (relative error <= 1/2 + 2^-29: the pivot rounded to
 * qa is >= 1 and within 1/2 of it), or from the chord (3 - P/2^30) 2^29 (<= 1/8) when that pivot
 * saturated. Six steps take 1/2 below 2^-32; the last loop settles the rounding exactly.
 */
static void pivot_recip(fx_solve_ws_t *ws, uint32_t k, uint64_t up, uint32_t sa, bool d_sat)
{
    int32_t e = (int32_t)bitlen64(up) - 31;   /* up in [2^23, 2^58]: e in [-8, 27] */
    int64_t pp;                                /* P in [2^30, 2^31] */
    int64_t m;
    int32_t z = (int32_t)ws->rec[k].sh + e - (int32_t)sa;
    fx_status_t ignore = 0u;                   /* shifts below are in range */
    uint32_t i;
    if (e > 0) {
        pp = (int64_t)shr128_rnd(umul64x32(up, 1u), (uint32_t)e);
    } else {
        uint64_t t = up << (uint32_t)(-e);
        pp = (int64_t)t;
    }
    if (d_sat || (z > 1) || (z < -1)) {
        m = (P2_29_I64 * 3) - fx_shr_rnd64_i(pp, 1u, &ignore);
    } else {
        uint64_t md = (uint64_t)fx_uabs(ws->rec[k].m);
        if (z >= 0) {
            uint64_t t = md << (uint32_t)z;
            m = (int64_t)t;
        } else {
            m = fx_shr_rnd64_i((int64_t)md, (uint32_t)(-z), &ignore);
        }
    }
    for (i = 0u; i < 6u; i++) {
        int64_t r = P2_60_I64 - (pp * m);   /* |r| <= 2^59 + 2^31: P m <= 1.5 2^60 */
        if ((r <= pp) && (r >= -pp)) {
            break;
        }
        m += mul_shr(r, m, 60u);                     /* m < 2^31 */
    }
    for (i = 0u; i < 4u; i++) {
        int64_t r = P2_60_I64 - (pp * m);
        if ((2 * r) > pp) {
            m++;
        } else if ((2 * r) < -pp) {
            m--;
        } else {
            break;
        }
    }
    ws->pm[k] = (int32_t)m;
    ws->pe[k] = e;
}

/*
 * Eliminate column k below the pivot p = w_kk. The multiplier l = w_ik / p is carried as
 * l1 2^-30 + l2 2^-58: l1 from the pivot's reciprocal (|l1 - l 2^30| <= 2: relative error
 * <= 1.5 2^-30 of pm and P, plus the rounding), then the exact residual N = w_ik 2^30 - l1 p
 * (|N| <= 2 |p| < 2^61, so its value mod 2^64 is the value) gives l2 = N 2^28 / p, |l2| <= 2^29.
 * |l1 2^-30 + l2 2^-58 - l| <= 2^-58 (1/2 + 2^-28), so the elimination's backward error at (i, k)
 * is <= 1 unit of W, and each update a_ij - l a_kj is rounded to <= 1 unit of W (two roundings).
 * An entry that leaves int32 in qa (A without its n - 1 headroom bits) raises SAT_HI / SAT_LO;
 * the elimination itself stays exact (W has the room).
 */
static void eliminate(fx_solve_ws_t *ws, uint32_t n, uint32_t k, fx_status_t *st)
{
    uint32_t i;
    uint32_t j;
    const int64_t *ak = &ws->a[(size_t)k * n];
    int64_t p = ak[k];
    int64_t m = (p < 0) ? -(int64_t)ws->pm[k] : (int64_t)ws->pm[k];
    uint32_t sh1 = (uint32_t)ws->pe[k] + 30u;      /* pe in [-7, 27]: unsigned wrap gives 30 + pe */
    uint32_t sh2 = sh1 + 2u;
    uint32_t qsh = (uint32_t)ws->sa + 31u;          /* |w| >= 2^qsh: outside int32 in qa */
    int64_t lim = (qsh <= 62u) ? fx_pow2_64(qsh, st) : INT64_MAX;
    for (i = k + 1u; i < n; i++) {
        int64_t *ai = &ws->a[(size_t)i * n];
        /* |w_ik| <= |p| < 2^59, pm <= 2^30: l1 <= 2^30 + 2 */
        int64_t l1 = mul_shr(ai[k], m, sh1);
        uint64_t nu = ((uint64_t)ai[k] << 30) - ((uint64_t)l1 * (uint64_t)p);
        int64_t l2 = mul_shr(u2s64(nu), m, sh2);
        ai[k] = 0;
        for (j = k + 1u; j < n; j++) {
            int64_t v = ai[j] - mul_shr(ak[j], l1, 30u) - mul_shr(ak[j], l2, 58u);
            if ((v >= lim) || (v <= -lim)) {
                *st |= (v > 0) ? FX_ST_SAT_HI : FX_ST_SAT_LO;
            }
            ai[j] = v;
        }
        ws->b[i] = ws->b[i] - mul_shr(ws->b[k], l1, 30u) - mul_shr(ws->b[k], l2, 58u);
    }
}

/* Left shift that brings the largest magnitude mx (> 0) to 31 bits, [0, 31]. */
static uint32_t norm_shift(uint32_t mx)
{
    uint32_t l = bitlen64((uint64_t)mx);
    return (l >= 31u) ? 0u : (31u - l);
}

/* Exact scalings W = A 2^sa, C = b 2^sb with |W|, |C| <= 2^(31 + SOLVE_G). */
static void scale_inputs(fx_solve_ws_t *ws, const int32_t *a, const int32_t *b, uint32_t n, fx_status_t *st)
{
    uint32_t mxa = 0u;
    uint32_t mxb = 0u;
    int64_t fa;
    int64_t fb;
    uint32_t i;
    for (i = 0u; i < (n * n); i++) {
        uint32_t v = fx_uabs(a[i]);
        mxa = (v > mxa) ? v : mxa;
    }
    for (i = 0u; i < n; i++) {
        uint32_t v = fx_uabs(b[i]);
        mxb = (v > mxb) ? v : mxb;
    }
    ws->sa = (uint8_t)(norm_shift(mxa) + SOLVE_G);
    ws->sb = (uint8_t)(norm_shift(mxb) + SOLVE_G);
    fa = fx_pow2_64(ws->sa, st);
    fb = fx_pow2_64(ws->sb, st);
    for (i = 0u; i < (n * n); i++) {
        ws->a[i] = (int64_t)a[i] * fa;
    }
    for (i = 0u; i < n; i++) {
        ws->b[i] = (int64_t)b[i] * fb;
    }
}

/* Step k: pivot, SINGULAR test, reciprocals, elimination. False on SINGULAR. */
static bool pivot_step(fx_solve_ws_t *ws, uint32_t n, uint32_t k, int32_t pivot_min, fx_status_t *st)
{
    uint64_t best = pivot_rows(ws, n, k);
    fx_status_t ds = 0u;
    bool ok = true;
    /* pivot in qa, rounded: the value callers see in rec[k].d */
    int32_t d = fx_rshift_sat_i(ws->a[(k * n) + k], ws->sa, &ds);
    ws->rec[k].d = d;
    ws->rec[k].m = 0;
    ws->rec[k].sh = 0u;
    /* |pivot| < pivot_min in qa, tested on the exact pivot: floor(|w| / 2^sa) < pivot_min */
    if ((d == 0) || ((pivot_min > 0) && ((best >> ws->sa) < (uint64_t)(uint32_t)pivot_min))) {
        *st |= FX_ST_SINGULAR;
        ok = false;
    } else {
        *st |= ds;
        fx_recip_init(&ws->rec[k], d, st);
        pivot_recip(ws, k, best, ws->sa, ds != 0u);
        eliminate(ws, n, k, st);
    }
    return ok;
}

/* fx_solve's argument checks, the normalised int64 copy into ws, pivoting and elimination;
   false (and x zeroed) on ARG or SINGULAR. */
static bool factor(fx_solve_ws_t *ws, const int32_t *a, uint32_t qa, const int32_t *b, uint32_t qb,
                   uint32_t n, int32_t *x, uint32_t qx, int32_t pivot_min, fx_status_t *st)
{
    uint32_t k;
    bool fail = false;
    if ((n < 1u) || (n > FX_SOLVE_NMAX) || (qa > FX_Q_MAX) || (qb > FX_Q_MAX) || (qx > FX_Q_MAX) ||
        (qb > (qa + qx)) || ((qa + qx - qb) > 31u)) {
        *st |= FX_ST_ARG;
        fail = true;
    } else {
        scale_inputs(ws, a, b, n, st);
    }
    for (k = 0u; (!fail) && (k < n); k++) {
        fail = !pivot_step(ws, n, k, pivot_min, st);
    }
    if (fail) {
        uint32_t i;
        for (i = 0u; (i < n) && (i < FX_SOLVE_NMAX); i++) {
            x[i] = 0;
        }
    }
    return !fail;
}

/* s_i = c_i 2^g - sum_{j>i} u_ij x_j exactly (two's complement, 128 bits). g = qa + qx - qb +
   sa - sb in [-31, 62] is the step from C's scale to W x's; g < 0 rounds c_i 2^g, an error of
   1/2 unit of W x. |c| < 2^59, |u_ij x_j| < 2^89: far inside 128 bits. */
static u128_t numerator(const fx_solve_ws_t *ws, uint32_t n, uint32_t ii, int32_t g, const int32_t *x)
{
    const int64_t *ai = &ws->a[(size_t)ii * n];
    fx_status_t ignore = 0u;   /* -g <= 31: in range */
    u128_t s;
    uint32_t j;
    if (g >= 0) {
        uint32_t ug = (uint32_t)g;
        s = s128_from64(ws->b[ii]);
        if (ug > 0u) {
            s.hi = (s.hi << ug) | (s.lo >> (64u - ug));
            s.lo <<= ug;
        }
    } else {
        s = s128_from64(fx_shr_rnd64_i(ws->b[ii], (uint32_t)(-g), &ignore));
    }
    for (j = ii + 1u; j < n; j++) {
        u128_t pr = umul64x32(mag64(ai[j]), (uint64_t)fx_uabs(x[j]));
        bool pneg = (ai[j] < 0) != (x[j] < 0);
        s = add128(s, pneg ? pr : neg128(pr));
    }
    return s;
}

/* Correct rounding from x0 (|x0 - ms / ud| < 7): R = ms - ud x0 (|R| < 2^61, so its value mod
   2^64 is the value), then X = round(ms / ud) half away from zero iff -ud <= 2 (ms - ud X) < ud. */
static uint64_t fix_quot(uint64_t ms_lo, uint64_t ud, uint64_t x0)
{
    int64_t r = u2s64(ms_lo - (ud * x0));
    int64_t sd = (int64_t)ud;
    uint64_t x = x0;
    uint32_t it;
    for (it = 0u; it < 8u; it++) {
        if ((2 * r) >= sd) {
            x++;
            r -= sd;
        } else if ((2 * r) < -sd) {
            x--;
            r += sd;
        } else {
            break;
        }
    }
    return x;
}

/* |s| / |u| for pivot ii: 0 below 1/2, UINT64_MAX at 2^32 or more (from bit lengths), else x0
   from the 62 leading bits of |s| and pm (relative error <= 1.5 2^-30 + 2^-61), corrected to the
   rounded quotient. */
static uint64_t quot_mag(const fx_solve_ws_t *ws, uint32_t ii, u128_t ms, uint64_t ud)
{
    uint32_t bd = bitlen64(ud);
    uint32_t bs = (ms.hi != 0u) ? (64u + bitlen64(ms.hi)) : bitlen64(ms.lo);
    uint64_t q;
    if ((bs + 1u) < bd) {
        q = 0u;                                      /* |s / u| < 2^(bs - bd + 1) <= 1/2 */
    } else if (bs > (bd + 32u)) {
        q = UINT64_MAX;                              /* |s / u| >= 2^(bs - 1 - bd) >= 2^32 */
    } else {
        /* sn = |s| 2^(62 - bs) in [2^61, 2^62]; |s| / |u| ~= sn 2^(bs - 62) pm 2^(-60 - pe):
           shift 122 + pe - bs, in [59, 93] since pe = bd - 31 and bd - 1 <= bs <= bd + 32 */
        uint64_t sn = (bs > 62u) ? shr128_rnd(ms, bs - 62u) : (ms.lo << (62u - bs));
        uint32_t shq = (122u + (uint32_t)ws->pe[ii]) - bs;
        q = shr128_rnd(umul64x32(sn, (uint64_t)(uint32_t)ws->pm[ii]), shq);
        if (q <= ((uint64_t)1 << 32)) {
            q = fix_quot(ms.lo, ud, q);               /* beyond 2^32: saturated either way */
        }
    }
    return q;
}

/* x_i = s_i / u_ii bottom up, saturated to int32 with SAT_HI / SAT_LO. */
static void back_substitute(const fx_solve_ws_t *ws, uint32_t n, uint32_t qa, uint32_t qb, uint32_t qx,
                            int32_t *x, fx_status_t *st)
{
    uint32_t k;
    int32_t g = ((int32_t)qa + (int32_t)qx) - (int32_t)qb + (int32_t)ws->sa - (int32_t)ws->sb;
    for (k = 0u; k < n; k++) {
        uint32_t ii = n - 1u - k;
        int64_t u = ws->a[((size_t)ii * n) + ii];
        u128_t s = numerator(ws, n, ii, g, x);
        bool sneg = (s.hi >> 63) != 0u;
        bool uneg = u < 0;
        bool neg = sneg != uneg;
        uint64_t q = quot_mag(ws, ii, sneg ? neg128(s) : s, mag64(u));
        uint64_t lim = neg ? ((uint64_t)INT32_MAX + 1u) : (uint64_t)INT32_MAX;
        if (q > lim) {
            *st |= neg ? FX_ST_SAT_LO : FX_ST_SAT_HI;
            x[ii] = neg ? INT32_MIN : INT32_MAX;
        } else {
            int64_t v = (int64_t)q;
            x[ii] = (int32_t)(neg ? -v : v);
        }
    }
}

void fx_solve(fx_solve_ws_t *ws, const int32_t *a, uint32_t qa, const int32_t *b, uint32_t qb,
              uint32_t n, int32_t *x, uint32_t qx, int32_t pivot_min, fx_status_t *st)
{
    if (factor(ws, a, qa, b, qb, n, x, qx, pivot_min, st)) {
        back_substitute(ws, n, qa, qb, qx, x, st);
    }
}

/* ------------------------------------------------------------------------- fast solve */

/*
 * fx_solve_fast: the int32 elimination and back substitution fx_solve used before its exact
 * elimination, on its own workspace. Its error grows with |x| (LSB of qx) over |A| (LSB of qa)
 * because every updated a_ij is rounded to one LSB of qa; the bound in fx.h, derived in
 * fsw/fx/README.md, states that. Newton needs only a step of small relative error, and this path
 * costs a quarter of the exact one at n = 4.
 */

/* Partial pivoting for column k: swap the row with the largest |a_ik| (lowest index on ties)
   into row k. Returns that magnitude. */
static uint32_t pivot_rows_fast(fx_solve_fast_ws_t *ws, uint32_t n, uint32_t k)
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
   l = a_ik / a_kk in q30 comes straight from the reciprocal (|l^ - l| <= 2^-30 |l| + 2^-31, |l| <= 1
   by pivoting): the rounding of the updates dominates, so an exact fix-up would buy nothing here.
   Each a_ij - l a_kj is formed exactly at 30 extra bits and rounded once (<= 1/2 LSB of qa, the
   backward error the README's bound counts); the inline rounding keeps the hot loop free of calls. */
static void eliminate_fast(fx_solve_fast_ws_t *ws, uint32_t n, uint32_t k, fx_status_t *st)
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

/* Argument checks, the copy into ws, pivoting and elimination; false (and x zeroed) on ARG or
   SINGULAR. The SINGULAR rule is fx_solve's: on int32 pivots "below 1/2 LSB" is "zero" and the
   exact pivot is the pivot. Back substitution scales b from qb to qa + qx, so e <= 31. */
static bool factor_fast(fx_solve_fast_ws_t *ws, const int32_t *a, uint32_t qa, const int32_t *b, uint32_t qb,
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
        uint32_t best = pivot_rows_fast(ws, n, k);
        if ((best == 0u) || ((int64_t)best < (int64_t)pivot_min)) {
            *st |= FX_ST_SINGULAR;
            ws->rec[k].d = ws->a[(k * n) + k];
            fail = true;
        } else {
            fx_recip_init(&ws->rec[k], ws->a[(k * n) + k], st);
            eliminate_fast(ws, n, k, st);
        }
    }
    if (fail) {
        for (i = 0u; (i < n) && (i < FX_SOLVE_NMAX); i++) {
            x[i] = 0;
        }
    }
    return !fail;
}

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
 * - t)). Relative error <= 2^-30 (m) + 2^-31 (s_hi) + 2^-61 before the final rounding (1/2 LSB).
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
static void back_substitute_fast(const fx_solve_fast_ws_t *ws, uint32_t n, uint32_t b_shift, int32_t *x,
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

void fx_solve_fast(fx_solve_fast_ws_t *ws, const int32_t *a, uint32_t qa, const int32_t *b, uint32_t qb,
                   uint32_t n, int32_t *x, uint32_t qx, int32_t pivot_min, fx_status_t *st)
{
    if (factor_fast(ws, a, qa, b, qb, n, x, qx, pivot_min, st)) {
        back_substitute_fast(ws, n, (qa + qx) - qb, x, st);
    }
}
