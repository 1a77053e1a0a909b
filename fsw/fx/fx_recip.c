/*
 * fx_recip.c — division through a reciprocal: one divide per divisor, then multiplies.
 *
 * On Cortex-M3 a 64/32 divide is a ~70-instruction libgcc call against ~16 for a multiply,
 * so kernels that divide several values by one divisor (pivots of fx_solve, the innovation
 * variance of a Kalman update) make the reciprocal once. Each division then takes an
 * approximate quotient from the reciprocal, one correction from the exact residual, and an
 * exact integer fix-up of the rounding decision, so the result equals the correctly rounded
 * quotient (half away from zero) bit for bit.
 */
#include "fx.h"

/* Approximate quotients beyond 2^31 + 2^20 saturate before any residual is formed: far outside
   int32 given the approximation error (a few LSB), and small enough that |d x| < 2^63. */
#define RECIP_X_LIMIT INT64_C(2148532224)   /* 2^31 + 2^20 */

void fx_recip_init(fx_recip_t *r, int32_t d, fx_status_t *st)
{
    r->d = d;
    r->m = 0;
    r->sh = 0u;
    if (d == 0) {
        *st |= FX_ST_DIV0;
    } else {
        uint32_t m = fx_uabs(d);
        uint32_t s = 0u;
        uint32_t i;
        uint64_t rec;
        /* Bounded normalisation: at most 30 doublings bring m into [2^30, 2^31]; only
           d = INT32_MIN gives 2^31 (no doubling). */
        for (i = 0u; (i < 31u) && (m < ((uint32_t)1 << 30)); i++) {
            m <<= 1;
            s++;
        }
        /* 2^60 / m in [2^29, 2^30], correctly rounded: relative error <= 2^-30. The low end is
           reached at |d| = 2^31 (exactly 2^29) and at |d| = 2^31 - 1 (2^29 + 0.25, rounded down). */
        rec = fx_udiv_rnd64((uint64_t)1 << 60, (uint64_t)m);
        r->m = (d < 0) ? -(int32_t)rec : (int32_t)rec;
        r->sh = s;
    }
}

/*
 * q ~= a / d from the reciprocal: a is first rounded to 31 significant bits (a / 2^e), so
 * the product with m fits int64. Relative error <= 2^-30 + 2^-31 plus 1/2 absolute.
 * Returns false when |q| would exceed 2^40.
 */
static bool approx_quot(int64_t a, const fx_recip_t *r, int64_t *q)
{
    uint64_t m = (a < 0) ? ((uint64_t)0 - (uint64_t)a) : (uint64_t)a;
    uint32_t e = 0u;
    uint32_t i;
    int32_t t;
    bool ok = true;
    fx_status_t ignore = 0u;  /* shifts below are in range by construction */
    for (i = 0u; (i < 33u) && (m >= ((uint64_t)1 << 31)); i++) {
        m >>= 1;
        e++;
    }
    t = 60 - (int32_t)r->sh - (int32_t)e;
    /* With e > 0, |a_hi| >= 2^30 and |m| >= 2^29, so |q| >= 2^(59 - t): t < 19 means > 2^40. */
    if ((e > 0u) && (t < 19)) {
        ok = false;
        *q = 0;
    } else {
        int64_t a_hi = fx_shr_rnd64(a, e, &ignore);
        *q = fx_shr_rnd64(a_hi * (int64_t)r->m, (uint32_t)t, &ignore);
    }
    return ok;
}

/*
 * Exact rounding decision on magnitudes: X = round(A / D) half away from zero iff
 * -D <= 2 (A - D X) < D. x is within a few LSB of the answer here, so a bounded number of
 * unit steps settles it.
 */
static int64_t fix_rounding(int64_t a, int32_t d, int64_t x)
{
    uint64_t ua = (a < 0) ? ((uint64_t)0 - (uint64_t)a) : (uint64_t)a;
    int64_t ud = (int64_t)fx_uabs(d);
    int64_t ux = (x < 0) ? -x : x;                       /* |x| < 2^31 + 2^20 + 8 */
    bool neg = (a < 0) != (d < 0);
    uint32_t i;
    /* A and D X both lie below 2^63 here; their difference is a few D. */
    int64_t rem = (int64_t)ua - (ud * ux);
    if (((x < 0) && !neg) || ((x > 0) && neg)) {
        /* x has the wrong sign (|quotient| < 1): start from 0. */
        ux = 0;
        rem = (int64_t)ua;
    }
    for (i = 0u; i < 8u; i++) {
        if ((2 * rem) >= ud) {
            ux++;
            rem -= ud;
        } else if ((2 * rem) < -ud) {
            ux--;
            rem += ud;
        } else {
            break;
        }
    }
    return neg ? -ux : ux;
}

/*
 * Correctly rounded a 2^k / d for a != 0, d != 0, k <= 62, into *x; returns false when the
 * quotient is certainly outside int32 (the caller saturates).
 */
static bool quot_nonzero(int64_t a, const fx_recip_t *r, uint32_t k, int64_t *x, fx_status_t *st)
{
    uint64_t ua = (a < 0) ? ((uint64_t)0 - (uint64_t)a) : (uint64_t)a;
    bool ok = false;
    /* |a| 2^k > 2^62 means |quotient| > 2^31 (|d| <= 2^31), which saturates, except for
       d = INT32_MIN, a > 0 and |a| 2^k in (2^62, 2^62 + 2^30): -|a| 2^(k - 31) in (-2^31 - 1/2, -2^31)
       rounds to INT32_MIN. k >= 31 has no such a (|a| 2^(k - 31) is then an integer > 2^31). */
    if ((k > 0u) && (ua > ((uint64_t)1 << (62u - k)))) {
        if ((r->d == INT32_MIN) && (a > 0) && (k <= 30u) &&
            ((ua - ((uint64_t)1 << (62u - k))) < ((uint64_t)1 << (30u - k)))) {
            *x = (int64_t)INT32_MIN;
            ok = true;
        }
    } else {
        int64_t ak = a * fx_pow2_64(k, st);             /* exact: |a 2^k| <= 2^62 */
        int64_t x0 = 0;
        if (approx_quot(ak, r, &x0) && (x0 < RECIP_X_LIMIT) && (x0 > -RECIP_X_LIMIT)) {
            /* One correction from the exact residual brings x within 1 of the answer. */
            int64_t c = 0;
            int64_t resid = ak - ((int64_t)r->d * x0);
            (void)approx_quot(resid, r, &c);
            *x = fix_rounding(ak, r->d, x0 + c);
            ok = (*x <= (int64_t)INT32_MAX) && (*x >= (int64_t)INT32_MIN);
        }
    }
    return ok;
}

int32_t fx_recip_div(int64_t a, const fx_recip_t *r, uint32_t k, fx_status_t *st)
{
    int32_t res = 0;
    int64_t x = 0;
    if (k > 62u) {
        *st |= FX_ST_ARG;
    } else if (r->d == 0) {
        *st |= FX_ST_DIV0;
        res = (a > 0) ? INT32_MAX : ((a < 0) ? -INT32_MAX : 0);
    } else if (a == 0) {
        res = 0;
    } else if (quot_nonzero(a, r, k, &x, st)) {
        res = (int32_t)x;
    } else {
        bool neg = (a < 0) != (r->d < 0);
        *st |= neg ? FX_ST_SAT_LO : FX_ST_SAT_HI;
        res = neg ? INT32_MIN : INT32_MAX;
    }
    return res;
}
