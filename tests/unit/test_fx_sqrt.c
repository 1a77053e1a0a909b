/*
 * fx_isqrt64, fx_sqrt, fx_norm3: integer-exact properties, on host and target.
 * The oracle is the defining inequality checked in integers, never a float root:
 *   floor root r:    r^2 <= x < (r+1)^2
 *   rounded root s:  (2s-1)^2 <= 4x < (2s+1)^2   (no ties: (s+1/2)^2 is never an integer)
 */
#include "fx.h"
#include "ut.h"

static void check_floor(uint64_t x)
{
    uint64_t r = fx_isqrt64(x);
    UT_CHECK(r * r <= x);
    /* (r+1)^2 overflows only for r = 2^32-1, where x < 2^64 = (r+1)^2 holds trivially. */
    if (r < UINT32_MAX) {
        UT_CHECK((r + 1u) * (r + 1u) > x);
    }
}

/* x < 2^62 so 4x fits: the rounded-root inequality in uint64. */
static void check_round(uint64_t x, uint64_t s)
{
    UT_CHECK(s == 0u || ((2u * s - 1u) * (2u * s - 1u)) <= 4u * x);
    UT_CHECK(((2u * s + 1u) * (2u * s + 1u)) > 4u * x);
}

UT_TEST(isqrt_small_exhaustive)
{
    uint64_t x;
    for (x = 0u; x < (1u << 16); x++) {
        check_floor(x);
    }
}

UT_TEST(isqrt_around_squares)
{
    uint64_t seed = 5u;
    uint32_t i;
    static const uint32_t ks[] = {1u, 2u, 3u, 65535u, 65536u, 0x7FFFFFFFu, 0x80000000u, 0xFFFFFFFEu, 0xFFFFFFFFu};
    for (i = 0u; i < (sizeof ks / sizeof ks[0]) + 4000u; i++) {
        uint64_t k = (i < (sizeof ks / sizeof ks[0])) ? ks[i] : (ut_rng_next(&seed) >> 32);
        uint64_t k2 = k * k;
        UT_CHECK_UEQ(fx_isqrt64(k2), k);
        UT_CHECK_UEQ(fx_isqrt64(k2 - 1u), (k == 0u) ? 0u : k - 1u);
        UT_CHECK_UEQ(fx_isqrt64(k2 + 2u * k), k);     /* (k+1)^2 - 1 */
    }
    UT_UEQ(fx_isqrt64(UINT64_MAX), 0xFFFFFFFFu);
    UT_UEQ(fx_isqrt64(0u), 0u);
    for (i = 0u; i < 20000u; i++) {
        check_floor(ut_rng_next(&seed) >> (i % 64u));
    }
}

UT_TEST(sqrt_formats)
{
    static const uint32_t fm[][2] = {{30u, 30u}, {29u, 29u}, {28u, 28u}, {24u, 24u}, {30u, 15u}, {20u, 26u}, {0u, 0u}, {2u, 16u}};
    uint64_t seed = 77u;
    uint32_t f;
    uint32_t i;
    for (f = 0u; f < (sizeof fm / sizeof fm[0]); f++) {
        uint32_t qa = fm[f][0];
        uint32_t qr = fm[f][1];
        uint32_t sh = 2u * qr - qa;
        for (i = 0u; i < 3000u; i++) {
            fx_status_t st = 0u;
            int32_t a = (int32_t)(ut_rng_next(&seed) >> (33u + (i % 31u)));
            uint64_t x = (uint64_t)a << sh;
            int32_t s = fx_sqrt(a, qa, qr, &st);
            /* round(sqrt(x)) > M = INT32_MAX  <=>  x > M (M + 1): only then may it saturate. */
            if (x > (uint64_t)INT32_MAX * ((uint64_t)INT32_MAX + 1u)) {
                UT_CHECK_UEQ(st, FX_ST_SAT_HI);
                UT_CHECK_EQ(s, INT32_MAX);
            } else {
                UT_CHECK_UEQ(st, 0u);
                if (x < ((uint64_t)1 << 62)) {
                    check_round(x, (uint64_t)s);
                }
            }
        }
    }
    {
        fx_status_t st = 0u;
        UT_EQ(fx_sqrt(1 << 30, 30u, 30u, &st), 1 << 30);          /* sqrt(1) = 1 */
        UT_EQ(fx_sqrt(1 << 28, 30u, 30u, &st), 1 << 29);          /* sqrt(1/4) = 1/2 */
        UT_EQ(fx_sqrt(4, 0u, 0u, &st), 2);
        UT_EQ(fx_sqrt(2, 0u, 0u, &st), 1);                        /* 1.414 -> 1 */
        UT_EQ(fx_sqrt(3, 0u, 0u, &st), 2);                        /* 1.732 -> 2 */
        UT_UEQ(st, 0u);
        UT_EQ(fx_sqrt(-1, 30u, 30u, &st), 0);
        UT_UEQ(st, FX_ST_DOMAIN);
        st = 0u;
        UT_EQ(fx_sqrt(1, 30u, 10u, &st), 0);                      /* 2*10-30 < 0 */
        UT_UEQ(st, FX_ST_ARG);
        st = 0u;
        UT_EQ(fx_sqrt(1, 0u, 17u, &st), 0);                       /* shift 34 > 33 */
        UT_UEQ(st, FX_ST_ARG);
        st = 0u;
        /* sqrt(INT32_MAX in q0) into q16: 46340.95 * 65536 = 3037000499.97 > INT32_MAX. */
        UT_EQ(fx_sqrt(INT32_MAX, 0u, 16u, &st), INT32_MAX);
        UT_UEQ(st, FX_ST_SAT_HI);
    }
}

UT_TEST(norm3)
{
    uint64_t seed = 3u;
    uint32_t i;
    fx_status_t st = 0u;
    static const int32_t v345[3] = {3, -4, 12};
    static const int32_t vmin[3] = {INT32_MIN, INT32_MIN, INT32_MIN};
    static const int32_t vone[3] = {INT32_MIN, 0, 0};
    UT_EQ(fx_norm3(v345, &st), 13);
    UT_UEQ(st, 0u);
    UT_EQ(fx_norm3(vmin, &st), INT32_MAX);       /* sqrt(3) * 2^31 is out of range */
    UT_UEQ(st, FX_ST_SAT_HI);
    st = 0u;
    UT_EQ(fx_norm3(vone, &st), INT32_MAX);       /* exactly 2^31, one above INT32_MAX */
    UT_UEQ(st, FX_ST_SAT_HI);
    for (i = 0u; i < 5000u; i++) {
        int32_t v[3];
        uint64_t s2;
        int32_t n;
        uint32_t j;
        st = 0u;
        for (j = 0u; j < 3u; j++) {
            v[j] = (int32_t)(ut_rng_next(&seed) >> 35);   /* |v| < 2^28: sum of squares < 2^58 */
        }
        n = fx_norm3(v, &st);
        s2 = 0u;
        for (j = 0u; j < 3u; j++) {
            s2 += (uint64_t)((int64_t)v[j] * v[j]);
        }
        check_round(s2, (uint64_t)n);
        UT_CHECK_UEQ(st, 0u);
    }
}

int main(void)
{
    UT_CASES(cases) = {
        UT_CASE(isqrt_small_exhaustive), UT_CASE(isqrt_around_squares), UT_CASE(sqrt_formats), UT_CASE(norm3),
    };
    return UT_RUN("fx_sqrt", cases);
}
