/*
 * Host-only dense sweeps of fx_mul, fx_div and the rounding shifts against an exact oracle.
 *
 * Oracle: __int128 integer arithmetic. Every quantity (a * b * 2^k, a * 2^k / b with its
 * remainder) is exact in 128 bits for formats in [0, 40], so "correctly rounded" means bitwise
 * equality with the oracle: the contract's 0.5 LSB bound with no slack. (The spec names x86-64
 * long double as the exact oracle for products; __int128 is exact for quotients too.)
 * Measured figures are printed so the README's accuracy table can quote them.
 */
#include "fx.h"
#include "ut.h"
#include "ut_oracle_host.h"

#include <stdio.h>


#define NELEM(a) (sizeof(a) / sizeof((a)[0]))
#define PAIRS_PER_TRIPLE (1u << 22)   /* spec 00 §1.6: 2^22 seeded random pairs per triple */
static int32_t o_clamp(i128 v, fx_status_t *st)
{
    if (v > INT32_MAX) {
        *st |= FX_ST_SAT_HI;
        return INT32_MAX;
    }
    if (v < INT32_MIN) {
        *st |= FX_ST_SAT_LO;
        return INT32_MIN;
    }
    return (int32_t)v;
}

static int32_t o_mul(int32_t a, uint32_t qa, int32_t b, uint32_t qb, uint32_t qr, fx_status_t *st)
{
    i128 p = (i128)a * b;
    uint32_t qp = qa + qb;
    return o_clamp((qp >= qr) ? o_shr(p, qp - qr) : p * ((i128)1 << (qr - qp)), st);
}

static int32_t o_div(int32_t a, uint32_t qa, int32_t b, uint32_t qb, uint32_t qr, fx_status_t *st)
{
    int32_t k = (int32_t)qr - (int32_t)qa + (int32_t)qb;
    i128 num = (i128)a;
    i128 den = (i128)b;
    i128 q;
    i128 r;
    if (k >= 0) {
        num *= (i128)1 << k;
    } else {
        den *= (i128)1 << (-k);
    }
    q = num / den;
    r = num % den;
    if (r < 0) {
        r = -r;
    }
    if (den < 0) {
        den = -den;
    }
    if (2 * r >= den) {
        q += ((num < 0) != (b < 0)) ? -1 : 1;
    }
    return o_clamp(q, st);
}

/* Edge set of spec 00 §1.6: extremes, +-2^k, +-2^k+-1. */
static size_t edge_set(int32_t *out)
{
    size_t n = 0u;
    uint32_t k;
    out[n++] = INT32_MIN;
    out[n++] = INT32_MIN + 1;
    out[n++] = -1;
    out[n++] = 0;
    out[n++] = 1;
    out[n++] = INT32_MAX - 1;
    out[n++] = INT32_MAX;
    for (k = 1u; k < 31u; k++) {
        int32_t p = (int32_t)1 << k;
        out[n++] = p;
        out[n++] = p - 1;
        out[n++] = p + 1;
        out[n++] = -p;
        out[n++] = -p - 1;
        out[n++] = -p + 1;
    }
    return n;
}

/* Random operand with a random bit length, so small values and ties are well represented. */
static int32_t rnd_operand(uint64_t *s)
{
    uint64_t r = ut_rng_next(s);
    uint32_t len = (uint32_t)(r % 33u);
    int64_t m = (len == 0u) ? 0 : (int64_t)((r >> 8) & ((UINT64_C(1) << (len - 1u)) - 1u)) | ((int64_t)1 << (len - 1u));
    int64_t v = ((r >> 7) & 1u) ? -m : m;
    if (v > INT32_MAX) {
        v = INT32_MAX;
    }
    if (v < INT32_MIN) {
        v = INT32_MIN;
    }
    return (int32_t)v;
}

/* Format triples in use by the module specs, plus the extremes of the legal range. */
static const uint32_t triples[][3] = {
    {29u, 29u, 29u}, {28u, 28u, 28u}, {30u, 30u, 30u}, {30u, 28u, 28u}, {28u, 30u, 28u},
    {29u, 28u, 29u}, {30u, 29u, 29u}, {24u, 24u, 24u}, {22u, 28u, 28u}, {32u, 29u, 30u},
    {0u, 0u, 0u}, {40u, 40u, 40u}, {0u, 40u, 20u}, {40u, 0u, 0u}, {0u, 0u, 40u}, {31u, 31u, 31u},
};

static void sweep(bool is_div)
{
    int32_t edges[200];
    size_t ne = edge_set(edges);
    size_t t;
    uint64_t seed = is_div ? 0xD1Fu : 0x3A1u;
    uint64_t checked = 0u;
    uint64_t ties = 0u;
    for (t = 0u; t < NELEM(triples); t++) {
        uint32_t qa = triples[t][0];
        uint32_t qb = triples[t][1];
        uint32_t qr = triples[t][2];
        size_t i;
        size_t j;
        uint32_t r;
        for (i = 0u; i < ne; i++) {
            for (j = 0u; j < ne; j++) {
                fx_status_t s1 = 0u;
                fx_status_t s2 = 0u;
                int32_t got = is_div ? fx_div(edges[i], qa, edges[j], qb, qr, &s1) : fx_mul(edges[i], qa, edges[j], qb, qr, &s1);
                int32_t want;
                if (is_div && edges[j] == 0) {
                    continue;
                }
                want = is_div ? o_div(edges[i], qa, edges[j], qb, qr, &s2) : o_mul(edges[i], qa, edges[j], qb, qr, &s2);
                UT_CHECK_EQ(got, want);
                UT_CHECK_UEQ(s1, s2);
                checked++;
            }
        }
        for (r = 0u; r < PAIRS_PER_TRIPLE; r++) {
            int32_t a = rnd_operand(&seed);
            int32_t b = rnd_operand(&seed);
            fx_status_t s1 = 0u;
            fx_status_t s2 = 0u;
            int32_t got;
            int32_t want;
            if (is_div && b == 0) {
                continue;
            }
            if (!is_div && (r & 3u) == 0u && qa + qb > qr) {
                /* Force an exact tie: a * b = odd * 2^(qa+qb-qr-1). */
                uint32_t sh = qa + qb - qr - 1u;
                if (sh < 31u) {
                    a = (int32_t)((((uint32_t)a & 0x3FFFu) | 1u) << sh) * (((r & 4u) != 0u) ? -1 : 1);
                    b = 1;
                }
            }
            got = is_div ? fx_div(a, qa, b, qb, qr, &s1) : fx_mul(a, qa, b, qb, qr, &s1);
            want = is_div ? o_div(a, qa, b, qb, qr, &s2) : o_mul(a, qa, b, qb, qr, &s2);
            if (got != want || s1 != s2) {
                UT_CHECK_EQ(got, want);
                UT_CHECK_UEQ(s1, s2);
                printf("  mismatch: a=%d qa=%u b=%d qb=%u qr=%u\n", a, qa, b, qb, qr);
                return;
            }
            checked++;
            ties += (!is_div && (r & 3u) == 0u) ? 1u : 0u;
        }
    }
    printf("fx_%s: %llu cases over %zu format triples, max error 0 LSB vs exact oracle "
           "(correctly rounded, <= 0.5 LSB), %llu forced ties\n",
           is_div ? "div" : "mul", (unsigned long long)checked, NELEM(triples), (unsigned long long)ties);
}

UT_TEST(mul_sweep) { sweep(false); }
UT_TEST(div_sweep) { sweep(true); }

UT_TEST(shift_convert_sweep)
{
    int32_t edges[200];
    size_t ne = edge_set(edges);
    uint32_t n;
    size_t i;
    uint64_t seed = 99u;
    uint64_t checked = 0u;
    /* Rounding shift: shifts 0..62 x edge set (int64 operands built from edges). */
    for (n = 0u; n <= 62u; n++) {
        for (i = 0u; i < ne; i++) {
            int64_t p = (int64_t)edges[i] * (int64_t)edges[(i * 7u) % ne];
            fx_status_t st = 0u;
            UT_CHECK_EQ(fx_shr_rnd64(p, n, &st), (int64_t)o_shr(p, n));
            p = (int64_t)ut_rng_next(&seed);
            UT_CHECK_EQ(fx_shr_rnd64(p, n, &st), (int64_t)o_shr(p, n));
            UT_CHECK_UEQ(st, 0u);
            checked += 2u;
        }
    }
    /* Conversions between every pair of formats. */
    for (n = 0u; n <= FX_Q_MAX; n++) {
        uint32_t m;
        for (m = 0u; m <= FX_Q_MAX; m++) {
            for (i = 0u; i < ne; i++) {
                fx_status_t s1 = 0u;
                fx_status_t s2 = 0u;
                i128 v = (n >= m) ? o_shr(edges[i], n - m) : (i128)edges[i] * ((i128)1 << (m - n));
                int32_t want = o_clamp(v, &s2);
                if (s2 != 0u) {
                    s2 |= FX_ST_CONV;
                }
                UT_CHECK_EQ(fx_convert(edges[i], n, m, &s1), want);
                UT_CHECK_UEQ(s1, s2);
                checked++;
            }
        }
    }
    printf("fx_shr_rnd64/fx_convert: %llu cases, all correctly rounded\n", (unsigned long long)checked);
}

static int64_t o_sat64(i128 v, fx_status_t *st)
{
    if (v > INT64_MAX) {
        *st |= FX_ST_SAT_HI;
        return INT64_MAX;
    }
    if (v < INT64_MIN) {
        *st |= FX_ST_SAT_LO;
        return INT64_MIN;
    }
    return (int64_t)v;
}

/* round(a 2^k / d) half away from zero, exact in 128 bits (|a| 2^k < 2^126). */
static i128 o_divk(int64_t a, uint32_t k, uint64_t d)
{
    u128 m = (u128)((a < 0) ? -(i128)a : (i128)a) << k;
    u128 q = m / d;
    u128 r = m % d;
    if (2u * r >= (u128)d) {
        q++;
    }
    return (a < 0) ? -(i128)q : (i128)q;
}

/* fx_mul64_shr and fx_div64_shl (the wide operations of the frequency estimator) against the 128-bit
   oracle: every shift, edge operands (int64 and int32 extremes, powers of two and their neighbours,
   exact ties) and seeded random ones; results and status bits must be identical. */
UT_TEST(wide_sweep)
{
    int32_t edges[200];
    size_t ne = edge_set(edges);
    int64_t a64[64];
    size_t na = 0u;
    uint64_t seed = 4242u;
    uint64_t checked = 0u;
    uint32_t n;
    size_t i;
    size_t j;
    a64[na++] = INT64_MIN;
    a64[na++] = INT64_MIN + 1;
    a64[na++] = INT64_MAX;
    a64[na++] = 0;
    for (n = 0u; n < 15u; n++) {
        int64_t p = (int64_t)1 << (4u * n + 2u);
        a64[na++] = p;
        a64[na++] = -p - 1;
        a64[na++] = p + 1;
        a64[na++] = -p;
    }
    for (n = 0u; n <= 62u; n++) {
        for (i = 0u; i < na + 200u; i++) {
            int64_t a = (i < na) ? a64[i] : (int64_t)ut_rng_next(&seed);
            if ((i >= na) && ((i & 1u) != 0u)) {
                a >>= (ut_rng_next(&seed) % 60u);  /* small magnitudes too */
            }
            for (j = 0u; j < ne; j += 3u) {
                fx_status_t s1 = 0u;
                fx_status_t s2 = 0u;
                int64_t got = fx_mul64_shr(a, edges[j], n, &s1);
                int64_t want = o_sat64(o_shr((i128)a * edges[j], n), &s2);
                if (got != want || s1 != s2) {
                    UT_CHECK_EQ(got, want);
                    UT_CHECK_UEQ(s1, s2);
                    printf("  mul64 mismatch: a=%lld b=%d n=%u\n", (long long)a, edges[j], n);
                    return;
                }
                if (edges[j] != 0) {
                    uint64_t d = (uint64_t)fx_uabs(edges[j]) * ((ut_rng_next(&seed) & 1u) ? 1u : 3u);
                    s1 = 0u;
                    s2 = 0u;
                    got = fx_div64_shl(a, n, d, &s1);
                    {
                        u128 ma = (u128)((a < 0) ? -(i128)a : (i128)a) << n;
                        want = (ma >= ((u128)1 << 63)) ? o_sat64((a < 0) ? -((i128)1 << 64) : ((i128)1 << 64), &s2)
                                                        : (int64_t)o_divk(a, n, d);
                    }
                    if (got != want || s1 != s2) {
                        UT_CHECK_EQ(got, want);
                        UT_CHECK_UEQ(s1, s2);
                        printf("  div64 mismatch: a=%lld n=%u d=%llu\n", (long long)a, n, (unsigned long long)d);
                        return;
                    }
                    checked++;
                }
                checked++;
            }
        }
    }
    {
        fx_status_t st = 0u;
        UT_CHECK_EQ(fx_mul64_shr(5, 7, 63u, &st), 0);
        UT_CHECK_UEQ(st, FX_ST_ARG);
        st = 0u;
        UT_CHECK_EQ(fx_div64_shl(5, 1u, 0u, &st), 0);
        UT_CHECK_UEQ(st, FX_ST_DIV0);
        st = 0u;
        UT_CHECK_EQ(fx_div64_shl(5, 63u, 1u, &st), 0);
        UT_CHECK_UEQ(st, FX_ST_ARG);
    }
    printf("fx_mul64_shr/fx_div64_shl: %llu cases, all identical to the 128-bit oracle\n",
           (unsigned long long)checked);
}

int main(void)
{
    UT_CASES(cases) = { UT_CASE(mul_sweep), UT_CASE(div_sweep), UT_CASE(shift_convert_sweep),
                         UT_CASE(wide_sweep) };
    return UT_RUN("fx_core_sweep", cases);
}
