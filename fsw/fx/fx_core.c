/*
 * fx_core.c — saturation, shifts, conversions, multiply and divide (spec 00 §1.3–1.5).
 *
 * This file is the only place in fsw/ that decides how a value is widened, narrowed, shifted
 * or clipped. Rounding is half away from zero everywhere. It is implemented on the unsigned
 * magnitude, so no signed value is ever right-shifted (the implementation-defined case of C99)
 * and no signed expression can overflow: -x is formed only where |x| <= 2^63 - 1 is known.
 */
#include "fx.h"
#include "fx_inline.h"   /* the single implementation of the hot primitives (see there) */

/* Signed value from a magnitude known to be <= 2^63 - 1 and a sign. */
static int64_t signed_from_mag(uint64_t m, bool neg)
{
    return neg ? -(int64_t)m : (int64_t)m;
}

int32_t fx_sat32(int64_t v, fx_status_t *st)
{
    return fx_sat32_i(v, st);
}

int16_t fx_sat16(int32_t v, fx_status_t *st)
{
    int16_t r;
    if (v > (int32_t)INT16_MAX) {
        *st |= FX_ST_SAT_HI;
        r = INT16_MAX;
    } else if (v < (int32_t)INT16_MIN) {
        *st |= FX_ST_SAT_LO;
        r = INT16_MIN;
    } else {
        r = (int16_t)v;
    }
    return r;
}

uint32_t fx_satu32(int64_t v, fx_status_t *st)
{
    uint32_t r;
    if (v > (int64_t)UINT32_MAX) {
        *st |= FX_ST_SAT_HI;
        r = UINT32_MAX;
    } else if (v < 0) {
        *st |= FX_ST_SAT_LO;
        r = 0u;
    } else {
        r = (uint32_t)v;
    }
    return r;
}

int32_t fx_add_sat(int32_t a, int32_t b, fx_status_t *st)
{
    return fx_sat32((int64_t)a + (int64_t)b, st);
}

int32_t fx_sub_sat(int32_t a, int32_t b, fx_status_t *st)
{
    return fx_sat32((int64_t)a - (int64_t)b, st);
}

int32_t fx_neg(int32_t a, fx_status_t *st)
{
    return fx_sat32(-(int64_t)a, st);
}

int32_t fx_abs(int32_t a, fx_status_t *st)
{
    return fx_sat32((a < 0) ? -(int64_t)a : (int64_t)a, st);
}

uint32_t fx_uabs(int32_t a)
{
    return (a < 0) ? (0u - (uint32_t)a) : (uint32_t)a;
}

int64_t fx_add64_sat(int64_t a, int64_t b, fx_status_t *st)
{
    return fx_add64_sat_i(a, b, st);
}

int32_t fx_shl_sat(int32_t a, uint32_t n, fx_status_t *st)
{
    int32_t r;
    if (n > 31u) {
        *st |= FX_ST_ARG;
        r = 0;
    } else {
        /* |a| <= 2^31 and n <= 31: the exact product fits int64, then one saturation. */
        r = fx_sat32((int64_t)a * fx_pow2_64(n, st), st);
    }
    return r;
}

int64_t fx_shr_rnd64(int64_t p, uint32_t n, fx_status_t *st)
{
    return fx_shr_rnd64_i(p, n, st);
}

int32_t fx_rshift_sat(int64_t p, uint32_t n, fx_status_t *st)
{
    return fx_rshift_sat_i(p, n, st);
}

int32_t fx_shr_rnd(int32_t a, uint32_t n, fx_status_t *st)
{
    int32_t r;
    if (n > 31u) {
        *st |= FX_ST_ARG;
        r = 0;
    } else {
        /* |a| <= 2^31 and n >= 1 keep the result in range; n == 0 returns a. */
        r = (int32_t)fx_shr_rnd64((int64_t)a, n, st);
    }
    return r;
}

/* v * 2^n for an int64 v, saturated to int32; n in [0, 63]. */
static int32_t shl64_sat32(int64_t v, uint32_t n, fx_status_t *st)
{
    int32_t r;
    if (v == 0) {
        r = 0;
    } else if (n > 31u) {
        /* Any non-zero value times 2^32 or more is out of int32 range. */
        *st |= (v > 0) ? FX_ST_SAT_HI : FX_ST_SAT_LO;
        r = (v > 0) ? INT32_MAX : INT32_MIN;
    } else {
        /* In range iff -2^(31-n) <= v <= (2^31 - 1) >> n; then v * 2^n is exact. */
        uint32_t hi_u = (uint32_t)INT32_MAX >> n;
        int64_t lo = -fx_pow2_64(31u - n, st);
        if (v > (int64_t)hi_u) {
            *st |= FX_ST_SAT_HI;
            r = INT32_MAX;
        } else if (v < lo) {
            *st |= FX_ST_SAT_LO;
            r = INT32_MIN;
        } else {
            r = (int32_t)(v * fx_pow2_64(n, st));
        }
    }
    return r;
}

int32_t fx_convert64(int64_t a, uint32_t q_from, uint32_t q_to, fx_status_t *st)
{
    int32_t r;
    fx_status_t s = 0u;
    if ((q_from > 63u) || (q_to > 63u)) {
        s |= FX_ST_ARG;
        r = 0;
    } else if (q_from >= q_to) {
        r = fx_rshift_sat_i(a, q_from - q_to, &s);
    } else {
        r = shl64_sat32(a, q_to - q_from, &s);
    }
    /* A saturating format conversion is reported both as the direction and as CONV. */
    if ((s & (FX_ST_SAT_HI | FX_ST_SAT_LO)) != 0u) {
        s |= FX_ST_CONV;
    }
    *st |= s;
    return r;
}

int32_t fx_convert(int32_t a, uint32_t q_from, uint32_t q_to, fx_status_t *st)
{
    int32_t r;
    if ((q_from > FX_Q_MAX) || (q_to > FX_Q_MAX)) {
        *st |= FX_ST_ARG;
        r = 0;
    } else {
        r = fx_convert64((int64_t)a, q_from, q_to, st);
    }
    return r;
}

int32_t fx_from_count(int32_t count, int32_t scale_m, uint32_t scale_sh, int32_t bias,
                      fx_status_t *st)
{
    int32_t r;
    if (scale_sh > 62u) {
        *st |= FX_ST_ARG;
        r = 0;
    } else {
        /* |count * scale_m| <= 2^62; subtracting a 31-bit bias after rounding keeps int64. */
        int64_t v = fx_shr_rnd64((int64_t)count * (int64_t)scale_m, scale_sh, st);
        r = fx_sat32(v - (int64_t)bias, st);
    }
    return r;
}

int32_t fx_to_count(int32_t v, int32_t inv_m, uint32_t inv_sh, int32_t cmin, int32_t cmax,
                    fx_status_t *st)
{
    int32_t r;
    if ((inv_sh > 62u) || (cmin > cmax)) {
        *st |= FX_ST_ARG;
        r = 0;
    } else {
        int64_t c = fx_shr_rnd64((int64_t)v * (int64_t)inv_m, inv_sh, st);
        if (c > (int64_t)cmax) {
            *st |= FX_ST_SAT_HI;
            r = cmax;
        } else if (c < (int64_t)cmin) {
            *st |= FX_ST_SAT_LO;
            r = cmin;
        } else {
            r = (int32_t)c;
        }
    }
    return r;
}

int64_t fx_pow2_64(uint32_t n, fx_status_t *st)
{
    int64_t r = 0;
    if (n > 62u) {
        *st |= FX_ST_ARG;
    } else {
        /* Shifted as unsigned: no signed value is ever shifted. */
        uint64_t p = (uint64_t)1 << n;
        r = (int64_t)p;
    }
    return r;
}

void fx_cnt_inc(uint32_t *c)
{
    if (*c < UINT32_MAX) {
        *c += 1u;
    }
}

int32_t fx_mul(int32_t a, uint32_t qa, int32_t b, uint32_t qb, uint32_t qr, fx_status_t *st)
{
    int32_t r;
    if ((qa > FX_Q_MAX) || (qb > FX_Q_MAX) || (qr > FX_Q_MAX)) {
        *st |= FX_ST_ARG;
        r = 0;
    } else {
        /* Exact product, |p| <= 2^62, then exactly one rounding (or an exact left shift). */
        int64_t p = (int64_t)a * (int64_t)b;
        uint32_t qp = qa + qb;
        if (qp >= qr) {
            uint32_t n = qp - qr;
            /* n may reach 80; beyond 63 the rounded result is 0 since |p| < 2^63 / 2. */
            /* inlined twin: out of line, the shift cost two calls per multiply (fx_inline.h) */
            r = (n > 63u) ? 0 : fx_rshift_sat_i(p, n, st);
        } else {
            r = shl64_sat32(p, qr - qp, st);
        }
    }
    return r;
}

/*
 * One 64/64 unsigned divide (a libgcc __aeabi_uldivmod call on Cortex-M), then the rounding
 * decision on the remainder, so num + den/2 is never formed and cannot overflow.
 */
uint64_t fx_udiv_rnd64(uint64_t num, uint64_t den)
{
    uint64_t q;
    uint64_t rem;
    if (den == 0u) {
        return UINT64_MAX;
    }
    q = num / den;
    rem = num - (q * den);
    /* 2*rem >= den without overflow: rem >= den - rem. */
    if (rem >= (den - rem)) {
        q += 1u;
    }
    return q;
}

/* (hi 2^32 + lo + 2^(n-1)) >> n for n <= 32, lo < 2^32; *big when the quotient is >= 2^63 */
static uint64_t shr96_small(uint64_t hi, uint64_t lo, uint32_t n, bool *big)
{
    uint64_t h = hi;
    uint64_t l = lo;
    uint64_t q = 0u;
    if (n > 0u) {
        l += (uint64_t)1u << (n - 1u);
        h += l >> 32;
        l &= 0xFFFFFFFFu;
    }
    /* q = h 2^(32-n) + l 2^-n < 2^63 iff h < 2^(31+n); q = 2^63 exactly is reported as big too */
    *big = (h >> (31u + n)) != 0u;
    if (!*big) {
        q = (h << (32u - n)) | (l >> n);
    } else if ((h == ((uint64_t)1u << (31u + n))) && ((l >> n) == 0u)) {
        q = (uint64_t)1u << 63;   /* the caller accepts it as INT64_MIN */
    } else {
        q = 0u;
    }
    return q;
}

/*
 * round(a b / 2^n), half away from zero, for the 64 x 32 products of a wide state (an estimator's
 * int64 states times int32 coefficients): the 95-bit product is formed as two exact 64-bit partial
 * products, |a| <= 2^63 and |b| <= 2^31 keep each below 2^63, so nothing wraps.
 */
int64_t fx_mul64_shr(int64_t a, int32_t b, uint32_t n, fx_status_t *st)
{
    int64_t r = 0;
    if (n > 62u) {
        *st |= FX_ST_ARG;
    } else {
        const uint64_t ma = (a < 0) ? ((uint64_t)0 - (uint64_t)a) : (uint64_t)a;
        const uint64_t mb = (uint64_t)fx_uabs(b);
        const bool neg = (a < 0) != (b < 0);
        const uint64_t p_hi = (ma >> 32) * mb;              /* <= 2^31 2^31 */
        const uint64_t p_lo = (ma & 0xFFFFFFFFu) * mb;      /* < 2^63 */
        const uint64_t hi = p_hi + (p_lo >> 32);            /* |a b| = hi 2^32 + lo, hi < 2^62 + 2^31 */
        const uint64_t lo = p_lo & 0xFFFFFFFFu;
        bool big = false;
        /* n > 32: + 2^(n-1) lands in hi, and lo < 2^32 cannot carry into the quotient */
        const uint64_t q = (n > 32u) ? ((hi + ((uint64_t)1u << (n - 33u))) >> (n - 32u))
                                     : shr96_small(hi, lo, n, &big);
        if (big && neg && (q == ((uint64_t)1u << 63))) {
            r = INT64_MIN;
        } else if (big) {
            *st |= neg ? FX_ST_SAT_LO : FX_ST_SAT_HI;
            r = neg ? INT64_MIN : INT64_MAX;
        } else {
            r = neg ? -(int64_t)q : (int64_t)q;
        }
    }
    return r;
}

/*
 * round(a 2^k / d), half away from zero, d > 0, k in [0, 62]; |a| 2^k >= 2^63 saturates (SAT_HI /
 * SAT_LO), d == 0 is DIV0 and 0, k > 62 is ARG and 0.
 */
int64_t fx_div64_shl(int64_t a, uint32_t k, uint64_t d, fx_status_t *st)
{
    int64_t r = 0;
    if (k > 62u) {
        *st |= FX_ST_ARG;
    } else if (d == 0u) {
        *st |= FX_ST_DIV0;
    } else {
        const uint64_t ma = (a < 0) ? ((uint64_t)0 - (uint64_t)a) : (uint64_t)a;
        if ((ma >> (63u - k)) != 0u) {
            *st |= (a < 0) ? FX_ST_SAT_LO : FX_ST_SAT_HI;
            r = (a < 0) ? INT64_MIN : INT64_MAX;
        } else {
            const uint64_t q = fx_udiv_rnd64(ma << k, d);   /* <= ma 2^k < 2^63 */
            r = (a < 0) ? -(int64_t)q : (int64_t)q;
        }
    }
    return r;
}

/*
 * |a| / |b| * 2^k rounded, for magnitudes ua <= 2^31, 1 <= ub <= 2^31 and k in [-40, 80].
 * *big is set when the quotient is certainly >= 2^33 (it then saturates in the caller).
 */
static uint64_t div_mag(uint64_t ua, uint64_t ub, int32_t k, bool *big)
{
    uint64_t q = 0u;
    *big = false;
    if (k >= 0) {
        uint32_t uk = (uint32_t)k;
        /* ua * 2^k >= 2^64 with ub <= 2^31 means a quotient >= 2^33. */
        if ((uk > 63u) || (ua > (UINT64_MAX >> uk))) {
            *big = true;
        } else {
            q = fx_udiv_rnd64(ua << uk, ub);
        }
    } else {
        uint32_t uk = (uint32_t)(-k);
        /* ub * 2^-k >= 2^64 > 2 * ua means the quotient rounds to 0. */
        if ((uk <= 63u) && (ub <= (UINT64_MAX >> uk))) {
            q = fx_udiv_rnd64(ua, ub << uk);
        }
    }
    return q;
}

int32_t fx_div(int32_t a, uint32_t qa, int32_t b, uint32_t qb, uint32_t qr, fx_status_t *st)
{
    int32_t r = 0;
    if ((qa > FX_Q_MAX) || (qb > FX_Q_MAX) || (qr > FX_Q_MAX)) {
        *st |= FX_ST_ARG;
    } else if (b == 0) {
        *st |= FX_ST_DIV0;
        if (a != 0) {
            r = (a > 0) ? INT32_MAX : -INT32_MAX;
        }
    } else if (a != 0) {
        bool neg = (a < 0) != (b < 0);
        bool big = false;
        /* result = a/b * 2^k with k = qr - qa + qb in [-40, 80]. */
        int32_t k = ((int32_t)qr - (int32_t)qa) + (int32_t)qb;
        uint64_t q = div_mag((uint64_t)fx_uabs(a), (uint64_t)fx_uabs(b), k, &big);
        uint64_t lim = neg ? ((uint64_t)1 << 31) : (uint64_t)INT32_MAX;
        if (big || (q > lim)) {
            *st |= neg ? FX_ST_SAT_LO : FX_ST_SAT_HI;
            r = neg ? INT32_MIN : INT32_MAX;
        } else {
            r = (int32_t)signed_from_mag(q, neg);
        }
    } else {
        r = 0;
    }
    return r;
}
