/*
 * Vector/matrix kernels and fx_solve: exact integer properties, on host and target.
 * Reference sums are formed here in int64 with operands small enough (< 2^28) that the exact
 * sum of n <= 8 products cannot overflow, then rounded with C division (independent of fx).
 */
#include "fx.h"
#include "ut.h"
#include "ut_ref.h"

#define NELEM(a) (sizeof(a) / sizeof((a)[0]))

static int64_t abs64(int64_t v)
{
    return (v < 0) ? -v : v;
}

static int32_t small(uint64_t *s)
{
    return (int32_t)((int64_t)(ut_rng_next(s) >> 36) - ((int64_t)1 << 27));
}

UT_TEST(dot_matvec_matmul_random)
{
    uint64_t seed = 21u;
    uint32_t it;
    for (it = 0u; it < 300u; it++) {
        int32_t a[64];
        int32_t b[64];
        int32_t y[8];
        int32_t c[64];
        uint32_t n = 1u + (it % 8u);
        uint32_t k = 1u + ((it / 8u) % 8u);
        uint32_t m = 1u + ((it / 3u) % 8u);
        uint32_t i;
        uint32_t j;
        uint32_t l;
        fx_status_t st = 0u;
        for (i = 0u; i < 64u; i++) {
            a[i] = small(&seed);
            b[i] = small(&seed);
        }
        {
            int64_t s = 0;
            for (i = 0u; i < n; i++) {
                s += (int64_t)a[i] * b[i];
            }
            UT_CHECK_EQ(fx_dot(a, 28u, b, 29u, n, 30u, &st), ut_ref_shr(s, 27u));
        }
        fx_matvec(a, 28u, b, 28u, n, k, y, 28u, &st);
        for (i = 0u; i < n; i++) {
            int64_t s = 0;
            for (j = 0u; j < k; j++) {
                s += (int64_t)a[i * k + j] * b[j];
            }
            UT_CHECK_EQ(y[i], ut_ref_shr(s, 28u));
        }
        fx_matmul(a, 30u, b, 30u, n, k, m, c, 31u, &st);
        for (i = 0u; i < n; i++) {
            for (j = 0u; j < m; j++) {
                int64_t s = 0;
                for (l = 0u; l < k; l++) {
                    s += (int64_t)a[i * k + l] * b[l * m + j];
                }
                UT_CHECK_EQ(c[i * m + j], ut_ref_shr(s, 29u));
            }
        }
        UT_CHECK_UEQ(st, 0u);
    }
}

UT_TEST(accumulator_overflow)
{
    /* Two products of 2^62 already leave int64 (spec 00 §1.6 adversarial rows). */
    static const int32_t mn[4] = {INT32_MIN, INT32_MIN, INT32_MIN, INT32_MIN};
    static const int32_t mx[2] = {INT32_MAX, INT32_MAX};
    int32_t y[2];
    fx_status_t st = 0u;
    UT_EQ(fx_dot(mn, 31u, mn, 31u, 1u, 31u, &st), INT32_MAX);   /* (-1)(-1) = 1 saturates */
    UT_UEQ(st, FX_ST_SAT_HI);
    st = 0u;
    UT_EQ(fx_dot(mn, 0u, mn, 0u, 2u, 0u, &st), INT32_MAX);
    UT_TRUE((st & FX_ST_ACC_OVF) != 0u);
    st = 0u;
    /* 2 (-2^31)(2^31 - 1) = -2^63 + 2^32 fits int64: no ACC_OVF, only the int32 clamp. */
    UT_EQ(fx_dot(mn, 0u, mx, 0u, 2u, 0u, &st), INT32_MIN);
    UT_UEQ(st, FX_ST_SAT_LO);
    st = 0u;
    /* Same sum in q31 x q31 -> q31: -2 + 2^-30 is below -1, saturates LO. */
    UT_EQ(fx_dot(mn, 31u, mx, 31u, 2u, 31u, &st), INT32_MIN);
    UT_UEQ(st, FX_ST_SAT_LO);
    st = 0u;
    /* A request for more result bits than the product has is an argument error. */
    UT_EQ(fx_dot(mn, 0u, mx, 0u, 2u, 31u, &st), 0);
    UT_UEQ(st, FX_ST_ARG);
    st = 0u;
    fx_matvec(mn, 0u, mn, 0u, 2u, 2u, y, 0u, &st);
    UT_TRUE((st & FX_ST_ACC_OVF) != 0u);
    UT_EQ(y[0], INT32_MAX);
    UT_EQ(y[1], INT32_MAX);
}

UT_TEST(kernel_args)
{
    int32_t v[9] = {1, 2, 3, 4, 5, 6, 7, 8, 9};
    int32_t y[9] = {7, 7, 7, 7, 7, 7, 7, 7, 7};
    fx_status_t st = 0u;
    UT_EQ(fx_dot(v, 10u, v, 10u, 9u, 10u, &st), 0);     /* n > FX_NMAX */
    UT_UEQ(st, FX_ST_ARG);
    st = 0u;
    UT_EQ(fx_dot(v, 10u, v, 10u, 2u, 21u, &st), 0);     /* qr > qa + qb */
    UT_UEQ(st, FX_ST_ARG);
    st = 0u;
    fx_matvec(v, 0u, v, 0u, 2u, 0u, y, 0u, &st);         /* zero columns */
    UT_UEQ(st, FX_ST_ARG);
    UT_EQ(y[0], 0);
    UT_EQ(y[1], 0);
    UT_EQ(y[2], 7);                                      /* nothing beyond rows written */
    st = 0u;
    fx_vadd(v, v, 3u, y, &st);
    UT_EQ(y[2], 6);
    fx_vsub(v, y, 3u, y, &st);
    UT_EQ(y[2], -3);
    UT_UEQ(st, 0u);
}

UT_TEST(solve_exact_cases)
{
    fx_solve_ws_t ws;
    int32_t x[4];
    fx_status_t st = 0u;
    /* Permutation matrix (q28): x is b permuted, exactly. */
    static const int32_t p4[16] = {0, 0, 1 << 28, 0, 1 << 28, 0, 0, 0, 0, 0, 0, 1 << 28, 0, 1 << 28, 0, 0};
    static const int32_t b4[4] = {11, -22, 33, -44};
    /* [[2, 1], [1, 3]] x = [3, 5] -> x = [0.8, 1.4] */
    static const int32_t a2[4] = {2 << 28, 1 << 28, 1 << 28, 3 << 28};
    static const int32_t b2[2] = {3 << 28, 5 << 28};
    /* Singular: second row twice the first. */
    static const int32_t s2[4] = {1 << 27, 1 << 26, 1 << 28, 1 << 27};
    fx_solve(&ws, p4, 28u, b4, 28u, 4u, x, 28u, 1 << 18, &st);
    UT_UEQ(st, 0u);
    UT_EQ(x[0], -22);
    UT_EQ(x[1], -44);
    UT_EQ(x[2], 11);
    UT_EQ(x[3], 33);
    fx_solve(&ws, a2, 28u, b2, 28u, 2u, x, 29u, 1 << 18, &st);
    UT_UEQ(st, 0u);
    UT_EQ(x[0], 429496730);    /* 0.8 * 2^29 = 429496729.6 */
    UT_EQ(x[1], 751619277);    /* 1.4 * 2^29 = 751619276.8 */
    x[0] = 5;
    x[1] = 5;
    fx_solve(&ws, s2, 28u, b2, 28u, 2u, x, 28u, 1 << 18, &st);
    UT_UEQ(st, FX_ST_SINGULAR);
    UT_EQ(x[0], 0);
    UT_EQ(x[1], 0);
    st = 0u;
    fx_solve(&ws, a2, 28u, b2, 28u, 5u, x, 28u, 1, &st);
    UT_UEQ(st, FX_ST_ARG);
    st = 0u;
    /* Pivot threshold is exclusive below: |pivot| == pivot_min is accepted. */
    {
        static const int32_t one[1] = {1000};
        static const int32_t bb[1] = {3000};
        fx_solve(&ws, one, 0u, bb, 0u, 1u, x, 0u, 1000, &st);
        UT_UEQ(st, 0u);
        UT_EQ(x[0], 3);
        fx_solve(&ws, one, 0u, bb, 0u, 1u, x, 0u, 1001, &st);
        UT_UEQ(st, FX_ST_SINGULAR);
        UT_EQ(x[0], 0);
    }
}

/* Odd symmetry: solving with -b gives exactly -x (the rounding rule is odd). */
UT_TEST(solve_symmetry_and_determinism)
{
    uint64_t seed = 8u;
    uint32_t it;
    for (it = 0u; it < 500u; it++) {
        fx_solve_ws_t ws;
        int32_t a[16];
        int32_t b[4];
        int32_t nb[4];
        int32_t x1[4];
        int32_t x2[4];
        int32_t x3[4];
        uint32_t n = 1u + (it % 4u);
        uint32_t i;
        fx_status_t s1 = 0u;
        fx_status_t s2 = 0u;
        fx_status_t s3 = 0u;
        for (i = 0u; i < n * n; i++) {
            a[i] = small(&seed) / 8;   /* |off-diagonal| < 2^24: diagonally dominant, no saturation */
        }
        for (i = 0u; i < n; i++) {
            a[i * n + i] += (int32_t)1 << 28;   /* diagonally weighted, well conditioned */
            b[i] = small(&seed);
            nb[i] = -b[i];
        }
        fx_solve(&ws, a, 28u, b, 28u, n, x1, 28u, 1 << 18, &s1);
        fx_solve(&ws, a, 28u, nb, 28u, n, x2, 28u, 1 << 18, &s2);
        fx_solve(&ws, a, 28u, b, 28u, n, x3, 28u, 1 << 18, &s3);
        for (i = 0u; i < n; i++) {
            UT_CHECK_EQ(x2[i], -x1[i]);
            UT_CHECK_EQ(x3[i], x1[i]);
        }
        UT_CHECK_UEQ(s1, 0u);
        UT_CHECK_UEQ(s2, 0u);
    }
}

/* fx_recip_div against C division of exact int64 numerators (|a 2^k| < 2^62 here). */
UT_TEST(recip_div_exact)
{
    uint64_t seed = 99u;
    uint32_t it;
    static const int32_t dv[] = {1, -1, 2, 3, -3, 7, 1073741824, -1073741824, INT32_MAX, INT32_MIN, 46341};
    for (it = 0u; it < 20000u; it++) {
        fx_recip_t r;
        fx_status_t st = 0u;
        int32_t d = (it < 11u * 50u) ? dv[it % 11u] : (int32_t)(uint32_t)ut_rng_next(&seed);
        uint32_t k = (uint32_t)(ut_rng_next(&seed) % 31u);
        int64_t a = (int64_t)(ut_rng_next(&seed) >> (33u + k)) * (((it & 1u) != 0u) ? -1 : 1);
        int64_t num = a * ((int64_t)1 << k);
        int64_t q;
        int64_t rem;
        int64_t ud;
        if (d == 0) {
            continue;
        }
        if ((it % 5u) == 0u) {
            /* exact tie: num = (2j + 1) d / 2 needs an even d */
            d = (d / 2) * 2;
            if (d == 0) {
                d = 2;
            }
            num = ((int64_t)(it % 1000u) * 2 + 1) * (d / 2);
            a = num;
            k = 0u;
        }
        q = num / d;
        rem = num % d;
        rem = (rem < 0) ? -rem : rem;
        ud = (d < 0) ? -(int64_t)d : (int64_t)d;
        if (rem >= ud - rem) {
            q += ((num < 0) != (d < 0)) ? -1 : 1;
        }
        fx_recip_init(&r, d, &st);
        UT_CHECK_EQ(fx_recip_div(a, &r, k, &st), ut_ref_clamp32(q));
        UT_CHECK_UEQ(st, (q > INT32_MAX) ? FX_ST_SAT_HI : ((q < INT32_MIN) ? FX_ST_SAT_LO : 0u));
    }
    {
        fx_recip_t r;
        fx_status_t st = 0u;
        fx_recip_init(&r, 0, &st);
        UT_UEQ(st, FX_ST_DIV0);
        UT_EQ(fx_recip_div(5, &r, 0u, &st), INT32_MAX);
        UT_EQ(fx_recip_div(-5, &r, 0u, &st), -INT32_MAX);
        st = 0u;
        fx_recip_init(&r, 3, &st);
        UT_EQ(fx_recip_div(1, &r, 63u, &st), 0);
        UT_UEQ(st, FX_ST_ARG);
        st = 0u;
        /* -2^62 / 2^31 = -2^31 exactly: INT32_MIN without saturation. */
        fx_recip_init(&r, INT32_MIN, &st);
        UT_EQ(fx_recip_div(INT64_C(1) << 62, &r, 0u, &st), INT32_MIN);
        UT_UEQ(st, 0u);
        UT_EQ(fx_recip_div(INT64_MIN, &r, 0u, &st), INT32_MAX);
        UT_UEQ(st, FX_ST_SAT_HI);
    }
}

/* fx_dot_wide: exact wide products, the int32 fast path equal to fx_dot, overflow and arguments. */
UT_TEST(dot_wide_cases)
{
    static const int32_t a[3] = {3, -5, 7};
    static const int32_t b[6] = {11, 99, 13, 99, -17, 99};   /* stride 2: 11, 13, -17 */
    static const int32_t aw[4] = {3, -5, 7, 123456789};
    static const int32_t bw[4] = {11, 13, -17, -987654};
    fx_status_t st = 0u;
    fx_status_t s2 = 0u;
    /* w fits int32: the same as fx_dot over four terms (3 * 11 - 5 * 13 - 7 * 17 + w v). */
    UT_EQ(fx_dot_wide(a, b, 2u, 3u, 123456789, -987654, 20u, &st), fx_dot(aw, 20u, bw, 0u, 4u, 0u, &s2));
    UT_UEQ(st, 0u);
    UT_UEQ(s2, 0u);
    /* w = 2^40 + 3 (beyond int32) times -2^20: -2^60 - 3 2^20, plus 33 - 65 - 119 = -151; shifted by
       40: -2^20 - 3 2^-20 - 151 2^-40, rounded half away from zero: -2^20. One more: 2^40 + 2^39
       times 3 = 2^41 + 2^40 + 2^39 (exact), by 40: 3.5 -> 4. */
    UT_EQ(fx_dot_wide(a, b, 2u, 3u, ((int64_t)1 << 40) + 3, -(1 << 20), 40u, &st), -(1 << 20));
    UT_EQ(fx_dot_wide(a, b, 2u, 0u, ((int64_t)1 << 40) + ((int64_t)1 << 39), 3, 40u, &st), 5);
    UT_UEQ(st, 0u);
    /* (2^33 - 1) (2^30 - 1) + 0: exact, 2^63 - 2^33 - 2^30 + 1 < 2^63; by 33: 2^30 - 1 after rounding. */
    UT_EQ(fx_dot_wide(a, b, 2u, 0u, ((int64_t)1 << 33) - 1, (1 << 30) - 1, 33u, &st), (1 << 30) - 1);
    UT_UEQ(st, 0u);
    /* INT64_MIN * -1 = 2^63: does not fit; INT64_MIN * 1 fits, with a term that takes it out. */
    UT_EQ(fx_dot_wide(a, b, 2u, 0u, INT64_MIN, -1, 62u, &st), INT32_MAX);
    UT_UEQ(st, FX_ST_ACC_OVF | FX_ST_SAT_HI);
    st = 0u;
    UT_EQ(fx_dot_wide(a, b, 2u, 0u, INT64_MIN, 1, 62u, &st), -2);
    UT_UEQ(st, 0u);
    UT_EQ(fx_dot_wide(&a[1], b, 2u, 1u, INT64_MIN, 1, 62u, &st), INT32_MIN);   /* -2^63 - 55 */
    UT_UEQ(st, FX_ST_ACC_OVF | FX_ST_SAT_LO);
    st = 0u;
    /* 2^34 * 2^31 - 1 ... the wide product itself overflows: 2^34 * (-2^31) = -2^65. */
    UT_EQ(fx_dot_wide(a, b, 2u, 3u, (int64_t)1 << 34, INT32_MIN, 40u, &st), INT32_MIN);
    UT_UEQ(st, FX_ST_ACC_OVF | FX_ST_SAT_LO);
    st = 0u;
    /* w = 0 and v = 0: the plain dot (33 - 65 - 119 = -151). */
    UT_EQ(fx_dot_wide(a, b, 2u, 3u, 0, 0, 0u, &st), -151);
    UT_EQ(fx_dot_wide(a, b, 2u, 3u, -((int64_t)1 << 50), 0, 0u, &st), -151);
    UT_UEQ(st, 0u);
    UT_EQ(fx_dot_wide(a, b, 2u, FX_NMAX + 1u, 0, 0, 0u, &st), 0);
    UT_UEQ(st, FX_ST_ARG);
    st = 0u;
    UT_EQ(fx_dot_wide(a, b, 2u, 3u, 0, 0, 63u, &st), 0);
    UT_UEQ(st, FX_ST_ARG);
}

UT_TEST(dot_acc_and_shl64)
{
    static const int32_t a[3] = {INT32_MIN, 3, -5};
    static const int32_t b[3] = {INT32_MIN, 7, 11};
    static const int32_t mn[2] = {INT32_MIN, INT32_MIN};
    fx_status_t st = 0u;
    UT_EQ(fx_dot_acc(a, b, 3u, &st), ((int64_t)1 << 62) + 21 - 55);
    UT_UEQ(st, 0u);
    UT_EQ(fx_dot_acc(mn, mn, 2u, &st), INT64_MAX);
    UT_UEQ(st, FX_ST_ACC_OVF);
    st = 0u;
    UT_EQ(fx_shl64_chk(-9, 60u, &st), INT64_MIN);   /* -9 * 2^60 < -2^63 */
    UT_UEQ(st, FX_ST_ACC_OVF);
    st = 0u;
    UT_EQ(fx_shl64_chk(4, 61u, &st), INT64_MAX);    /* 2^63 does not fit */
    UT_UEQ(st, FX_ST_ACC_OVF);
    st = 0u;
    UT_EQ(fx_shl64_chk(-4, 61u, &st), INT64_MIN);   /* -2^63 fits exactly */
    UT_EQ(fx_shl64_chk(-3, 60u, &st), -3 * ((int64_t)1 << 60));
    UT_EQ(fx_shl64_chk(3, 61u, &st), 3 * ((int64_t)1 << 61));
    UT_EQ(fx_shl64_chk(5, 0u, &st), 5);
    UT_UEQ(st, 0u);
    UT_EQ(fx_shl64_chk(1, 63u, &st), 0);
    UT_UEQ(st, FX_ST_ARG);
}

/* fx_solve_fast: exact cases, guards and argument checks as fx_solve. */
UT_TEST(solve_fast_exact_cases)
{
    fx_solve_fast_ws_t ws;
    fx_solve_ws_t wse;
    int32_t x[4];
    fx_status_t st = 0u;
    static const int32_t p4[16] = {0, 0, 1 << 28, 0, 1 << 28, 0, 0, 0, 0, 0, 0, 1 << 28, 0, 1 << 28, 0, 0};
    static const int32_t b4[4] = {11, -22, 33, -44};
    static const int32_t a2[4] = {2 << 28, 1 << 28, 1 << 28, 3 << 28};
    static const int32_t b2[2] = {3 << 28, 5 << 28};
    static const int32_t s2[4] = {1 << 27, 1 << 26, 1 << 28, 1 << 27};
    fx_solve_fast(&ws, p4, 28u, b4, 28u, 4u, x, 28u, 1 << 18, &st);
    UT_UEQ(st, 0u);
    UT_EQ(x[0], -22);
    UT_EQ(x[1], -44);
    UT_EQ(x[2], 11);
    UT_EQ(x[3], 33);
    fx_solve_fast(&ws, a2, 28u, b2, 28u, 2u, x, 29u, 1 << 18, &st);
    UT_UEQ(st, 0u);
    UT_CHECK_LE(abs64((int64_t)x[0] - 429496730), 1);   /* 0.8 * 2^29 */
    UT_CHECK_LE(abs64((int64_t)x[1] - 751619277), 1);   /* 1.4 * 2^29 */
    x[0] = 5;
    x[1] = 5;
    fx_solve_fast(&ws, s2, 28u, b2, 28u, 2u, x, 28u, 1 << 18, &st);
    UT_UEQ(st, FX_ST_SINGULAR);
    UT_EQ(x[0], 0);
    UT_EQ(x[1], 0);
    st = 0u;
    fx_solve_fast(&ws, a2, 28u, b2, 28u, 5u, x, 28u, 1, &st);
    UT_UEQ(st, FX_ST_ARG);
    st = 0u;
    fx_solve_fast(&ws, a2, 28u, b2, 29u, 2u, x, 0u, 1, &st);   /* qb > qa + qx */
    UT_UEQ(st, FX_ST_ARG);
    st = 0u;
    {
        static const int32_t one[1] = {1000};
        static const int32_t bb[1] = {3000};
        static const int32_t tiny[1] = {1 << 18};
        static const int32_t big[1] = {INT32_MAX};
        static const int32_t nbig[1] = {-INT32_MAX};
        fx_solve_fast(&ws, one, 0u, bb, 0u, 1u, x, 0u, 1000, &st);
        UT_UEQ(st, 0u);
        UT_EQ(x[0], 3);
        fx_solve_fast(&ws, one, 0u, bb, 0u, 1u, x, 0u, 1001, &st);
        UT_UEQ(st, FX_ST_SINGULAR);
        UT_EQ(x[0], 0);
        /* Quotients outside int32 saturate with the sign, as fx_solve's. */
        st = 0u;
        fx_solve_fast(&ws, tiny, 28u, big, 28u, 1u, x, 28u, 1 << 18, &st);
        UT_UEQ(st, FX_ST_SAT_HI);
        UT_EQ(x[0], INT32_MAX);
        st = 0u;
        fx_solve_fast(&ws, tiny, 28u, nbig, 28u, 1u, x, 28u, 1 << 18, &st);
        UT_UEQ(st, FX_ST_SAT_LO);
        UT_EQ(x[0], INT32_MIN);
        st = 0u;
        fx_solve(&wse, tiny, 28u, nbig, 28u, 1u, x, 28u, 1 << 18, &st);
        UT_UEQ(st, FX_ST_SAT_LO);
    }
}

/* fx_solve_fast has its own int32 elimination; on diagonally dominant systems with |x| below
   |A| (both ~2^28 LSB) its x stays within a few LSB of fx_solve's: there |u_ij / u_ii| is small and
   the roundings of U (1/2 LSB of qa each) and of x_i (1.5 2^-30 relative) hardly propagate. It is
   odd (-b gives -x and mirrored saturation flags) and deterministic, and flags SINGULAR and ARG as
   fx_solve does on these systems (no pivot near pivot_min). */
UT_TEST(solve_fast_vs_solve)
{
    uint64_t seed = 99u;
    uint32_t it;
    int64_t worst = 0;
    for (it = 0u; it < 600u; it++) {
        fx_solve_ws_t w1;
        fx_solve_fast_ws_t w2;
        int32_t a[16];
        int32_t b[4];
        int32_t nb[4];
        int32_t x1[4];
        int32_t x2[4];
        int32_t x3[4];
        int32_t x4[4];
        uint32_t n = 1u + (it % 4u);
        uint32_t i;
        fx_status_t s1 = 0u;
        fx_status_t s2 = 0u;
        fx_status_t s3 = 0u;
        bool dominant = (it % 3u) != 0u;
        for (i = 0u; i < n * n; i++) {
            a[i] = dominant ? (small(&seed) / 8) : (small(&seed) / 2);   /* |a| < 2^26: 2 headroom bits */
        }
        for (i = 0u; i < n; i++) {
            if (dominant) {
                a[(((i + it) % n) * n) + i] += ((i % 2u) != 0u) ? -((int32_t)1 << 28) : ((int32_t)1 << 28);
            }
            b[i] = small(&seed) * (int32_t)((it % 5u) + 1u);
            nb[i] = -b[i];
        }
        fx_solve(&w1, a, 28u, b, 28u, n, x1, 28u, 1 << 18, &s1);
        fx_solve_fast(&w2, a, 28u, b, 28u, n, x2, 28u, 1 << 18, &s2);
        fx_solve_fast(&w2, a, 28u, nb, 28u, n, x4, 28u, 1 << 18, &s3);
        /* odd: -b saturates the other way */
        UT_CHECK_UEQ(s3, (s2 & (fx_status_t)~(FX_ST_SAT_HI | FX_ST_SAT_LO)) | ((s2 & FX_ST_SAT_HI) << 1) |
                             ((s2 & FX_ST_SAT_LO) >> 1));
        UT_CHECK_UEQ(s2 & (FX_ST_SINGULAR | FX_ST_ARG), s1 & (FX_ST_SINGULAR | FX_ST_ARG));
        fx_solve_fast(&w2, a, 28u, b, 28u, n, x3, 28u, 1 << 18, &s3);
        for (i = 0u; (i < n) && ((s1 & FX_ST_SINGULAR) == 0u); i++) {
            int64_t d = abs64((int64_t)x2[i] - (int64_t)x1[i]);
            UT_CHECK_EQ(x3[i], x2[i]);
            if (s2 == 0u) {
                UT_CHECK_EQ(x4[i], -x2[i]);
            }
            if ((s1 == 0u) && (s2 == 0u) && dominant) {
                UT_CHECK_LE(d, 2 + (abs64((int64_t)x1[i]) / ((int64_t)1 << 27)));
                worst = (d > worst) ? d : worst;
            }
        }
    }
    UT_CHECK_LE(worst, 40);
}

/* Odd symmetry of fx_solve_fast: -b gives exactly -x. */
UT_TEST(solve_fast_symmetry)
{
    uint64_t seed = 17u;
    uint32_t it;
    for (it = 0u; it < 300u; it++) {
        fx_solve_fast_ws_t ws;
        int32_t a[16];
        int32_t b[4];
        int32_t nb[4];
        int32_t x1[4];
        int32_t x2[4];
        uint32_t n = 1u + (it % 4u);
        uint32_t i;
        fx_status_t s1 = 0u;
        fx_status_t s2 = 0u;
        for (i = 0u; i < n * n; i++) {
            a[i] = small(&seed) / 8;
        }
        for (i = 0u; i < n; i++) {
            a[i * n + i] += (int32_t)1 << 28;
            b[i] = small(&seed);
            nb[i] = -b[i];
        }
        fx_solve_fast(&ws, a, 28u, b, 28u, n, x1, 27u, 1 << 18, &s1);
        fx_solve_fast(&ws, a, 28u, nb, 28u, n, x2, 27u, 1 << 18, &s2);
        for (i = 0u; i < n; i++) {
            UT_CHECK_EQ(x2[i], -x1[i]);
        }
        UT_CHECK_UEQ(s1, 0u);
        UT_CHECK_UEQ(s2, 0u);
    }
}

/*
 * Audit reproducer (fx_solve broke its bound with no flag raised): |x| in LSB of qx far above
 * max|a_ij| in LSB of qa, where the old elimination's rounding of each a_ij to one LSB of qa
 * cost kappa |x| / |A| LSB. The old code returned x[3] = -344437253 (34.3 LSB off, bound 17.3).
 * Exact values with Python fractions.Fraction (Gaussian elimination on the integers, b scaled
 * by 2^(qa + qx - qb) = 2^31):
 *   x * 1000 = [844307884606.47, -31838663931.48, -1014009875859.61, -344437218739.71]
 *   kappa_inf(A) = |A|inf |A^-1|inf = 2.15689530168..., 2 n kappa = 17.2551630... LSB
 * fx_solve: |x_i - x_exact,i| <= 2 n kappa; 1000 |x - x_exact| <= 17255 is checked against the
 * rounded 1000 x_exact (itself within 0.5), hence the 17254.
 * fx_solve_fast (its own int32 elimination, the old one): the fx.h bound with n = 4, e = 31,
 * N = |A|inf = 122845580 (row 1), and X = |x|inf of the returned x (<= 1014009876 + bound < 2^30):
 *   kappa (8 (1 + 2^-27 X) + (3 X + 1.5 2^31 + 8) / N) <= 2.156896 (8 + 64 + 26.2218 + 26.2218) = 268.41 LSB
 * (with X = 2^30, a value above the returned |x|, so the number is a constant). Asserted as
 * 1000 |x - x_exact| <= 268000 (the rounded 1000 x_exact is itself within 0.5). The old header's
 * 2 n kappa (1 + 2^-29 |x|) = 49.8 LSB was false for this path (the mixed-scale sweep counts its
 * violations).
 */
UT_TEST(solve_bound_large_x_reproducer)
{
    static const int32_t a[16] = {-101006476, 4848859, -1500227, -15490018, -9971092, 89364658, -15706927, 727701,
                                  -7814389, 3797064, -73312023, 11573623, -2333061, -2548668, -12415896, 95501512};
    static const int32_t b[4] = {-36590901, 2054688, 29631930, -10334472};
    static const int64_t x1000[4] = {INT64_C(844307884606), INT64_C(-31838663931), INT64_C(-1014009875860),
                                     INT64_C(-344437218740)};
    fx_solve_ws_t ws;
    fx_solve_fast_ws_t wsf;
    int32_t x[4];
    fx_status_t st = 0u;
    uint32_t i;
    int64_t worst_fast = 0;
    fx_solve(&ws, a, 28u, b, 27u, 4u, x, 30u, 1, &st);
    UT_UEQ(st, 0u);
    for (i = 0u; i < 4u; i++) {
        UT_CHECK_LE(abs64(((int64_t)x[i] * 1000) - x1000[i]), 17254);
    }
    fx_solve_fast(&wsf, a, 28u, b, 27u, 4u, x, 30u, 1, &st);
    UT_UEQ(st, 0u);
    for (i = 0u; i < 4u; i++) {
        int64_t d = abs64(((int64_t)x[i] * 1000) - x1000[i]);
        UT_CHECK_LE(d, 268000);
        UT_CHECK_LE(abs64((int64_t)x[i]), (int64_t)1 << 30);   /* the X used above */
        worst_fast = (d > worst_fast) ? d : worst_fast;
    }
    /* the old path's error is still there (it is what the new bound has to cover) */
    UT_CHECK(worst_fast > 17255);
}

/*
 * fx_recip_div at d = INT32_MIN with |a| 2^k just above 2^62: the quotient -|a| 2^(k - 31) lies in
 * (-2^31 - 1/2, -2^31), which rounds to INT32_MIN, a representable result (the old code flagged
 * SAT_LO). Exact values (Python Fraction(a * 2**k, -2**31), rounded half away from zero):
 *   a = 2^61 + 1,            k = 1:  -2147483648.000000000931 -> -2147483648, no flag
 *   a = 2^61 + 2^29 - 1,     k = 1:  -2147483648.49999999907  -> -2147483648, no flag
 *   a = 2^61 + 2^29,         k = 1:  -2147483648.5 (tie)      -> -2147483649: SAT_LO, INT32_MIN
 *   a = 2^32 + 1,            k = 30: -2147483648.5 (tie)      -> SAT_LO
 *   a = 2^32,                k = 30: -2147483648 exactly      -> no flag (|a| 2^k = 2^62)
 *   a = 2^31 + 1,            k = 31: -2147483649 exactly      -> SAT_LO
 *   a = -(2^61 + 1),         k = 1:  +2147483648.000000000931 -> SAT_HI, INT32_MAX
 */
UT_TEST(recip_div_int32_min_edge)
{
    fx_recip_t r;
    fx_status_t st = 0u;
    fx_recip_init(&r, INT32_MIN, &st);
    UT_UEQ(st, 0u);
    UT_EQ(fx_recip_div(INT64_C(2305843009213693953), &r, 1u, &st), INT32_MIN);   /* 2^61 + 1 */
    UT_UEQ(st, 0u);
    UT_EQ(fx_recip_div(INT64_C(2305843009750564863), &r, 1u, &st), INT32_MIN);   /* 2^61 + 2^29 - 1 */
    UT_UEQ(st, 0u);
    UT_EQ(fx_recip_div(INT64_C(4294967296), &r, 30u, &st), INT32_MIN);           /* 2^32 */
    UT_UEQ(st, 0u);
    UT_EQ(fx_recip_div(INT64_C(2305843009750564864), &r, 1u, &st), INT32_MIN);   /* 2^61 + 2^29: tie */
    UT_UEQ(st, FX_ST_SAT_LO);
    st = 0u;
    UT_EQ(fx_recip_div(INT64_C(4294967297), &r, 30u, &st), INT32_MIN);           /* 2^32 + 1: tie */
    UT_UEQ(st, FX_ST_SAT_LO);
    st = 0u;
    UT_EQ(fx_recip_div(INT64_C(2147483649), &r, 31u, &st), INT32_MIN);           /* 2^31 + 1 */
    UT_UEQ(st, FX_ST_SAT_LO);
    st = 0u;
    UT_EQ(fx_recip_div(INT64_C(-2305843009213693953), &r, 1u, &st), INT32_MAX);  /* -(2^61 + 1) */
    UT_UEQ(st, FX_ST_SAT_HI);
}

/*
 * fx_recip_t ranges (fx.h): |d| << sh in [2^30, 2^31] and |m| in [2^29, 2^30]. The ends are
 * reached at d = INT32_MIN (|d| = 2^31, sh = 0, m = -2^60 / 2^31 = -2^29 exactly) and at
 * d = +-INT32_MAX (m = round(2^60 / (2^31 - 1)) = round(2^29 + 0.25) = 2^29), and |m| = 2^30
 * at |d| = 2^k (|d| << sh = 2^30).
 */
UT_TEST(recip_ranges)
{
    static const int32_t dv[] = {INT32_MIN, INT32_MAX, -INT32_MAX, 1, -1, 3, 1073741824, 1073741825, -1073741823,
                                 46341, 2147483646};
    uint64_t seed = 5u;
    uint32_t it;
    fx_recip_t r;
    fx_status_t st = 0u;
    fx_recip_init(&r, INT32_MIN, &st);
    UT_EQ(r.m, -536870912);
    UT_UEQ(r.sh, 0u);
    fx_recip_init(&r, INT32_MAX, &st);
    UT_EQ(r.m, 536870912);
    UT_UEQ(r.sh, 0u);
    fx_recip_init(&r, -INT32_MAX, &st);
    UT_EQ(r.m, -536870912);
    fx_recip_init(&r, -4, &st);
    UT_EQ(r.m, -1073741824);
    UT_UEQ(r.sh, 28u);
    UT_UEQ(st, 0u);
    for (it = 0u; it < 20000u; it++) {
        int32_t d = (it < 11u) ? dv[it] : (int32_t)(uint32_t)(ut_rng_next(&seed) >> (32u + (it % 31u)));
        uint64_t nd;
        uint32_t um;
        if (d == 0) {
            continue;
        }
        fx_recip_init(&r, d, &st);
        nd = (uint64_t)fx_uabs(d) << r.sh;
        um = fx_uabs(r.m);
        UT_CHECK(nd >= (UINT64_C(1) << 30));
        UT_CHECK(nd <= (UINT64_C(1) << 31));
        UT_CHECK(um >= (1u << 29));
        UT_CHECK(um <= (1u << 30));
        UT_CHECK((r.m < 0) == (d < 0));
    }
    UT_UEQ(st, 0u);
}

int main(void)
{
    UT_CASES(cases) = {
        UT_CASE(dot_matvec_matmul_random), UT_CASE(accumulator_overflow), UT_CASE(kernel_args),
        UT_CASE(solve_exact_cases), UT_CASE(solve_symmetry_and_determinism), UT_CASE(recip_div_exact), UT_CASE(dot_acc_and_shl64), UT_CASE(dot_wide_cases),
        UT_CASE(solve_fast_exact_cases), UT_CASE(solve_fast_vs_solve), UT_CASE(solve_fast_symmetry),
        UT_CASE(solve_bound_large_x_reproducer), UT_CASE(recip_div_int32_min_edge), UT_CASE(recip_ranges),
    };
    return UT_RUN("fx_mat", cases);
}
