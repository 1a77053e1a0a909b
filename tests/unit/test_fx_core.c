/*
 * fx core: saturation, shifts, conversions, multiply, divide, counters, CRC, constants.
 * Runs on the host (CMocka) and on the Cortex-M3 under QEMU, so every oracle here is an
 * independent integer computation (C division and remainder instead of the core's magnitude
 * shifts); the host-only sweeps in test_fx_core_sweep_host.c use an exact __int128 oracle.
 */
#include "fx.h"
#include "ut.h"
#include "ut_ref.h"

#define NELEM(a) (sizeof(a) / sizeof((a)[0]))

static const int32_t edge32[] = {
    INT32_MIN, INT32_MIN + 1, -1073741825, -1073741824, -65537, -65536, -65535, -3, -2, -1, 0,
    1, 2, 3, 65535, 65536, 65537, 1073741823, 1073741824, INT32_MAX - 1, INT32_MAX,
};

UT_TEST(sat_and_add)
{
    fx_status_t st = 0u;
    UT_EQ(fx_sat32((int64_t)INT32_MAX + 1, &st), INT32_MAX);
    UT_UEQ(st, FX_ST_SAT_HI);
    st = 0u;
    UT_EQ(fx_sat32((int64_t)INT32_MIN - 1, &st), INT32_MIN);
    UT_UEQ(st, FX_ST_SAT_LO);
    st = 0u;
    UT_EQ(fx_sat32(INT32_MIN, &st), INT32_MIN);
    UT_EQ(fx_sat32(INT32_MAX, &st), INT32_MAX);
    UT_UEQ(st, 0u);
}

UT_TEST(sat16_u32)
{
    fx_status_t st = 0u;
    UT_EQ(fx_sat16(32767, &st), 32767);
    UT_EQ(fx_sat16(-32768, &st), -32768);
    UT_UEQ(st, 0u);
    UT_EQ(fx_sat16(32768, &st), 32767);
    UT_UEQ(st, FX_ST_SAT_HI);
    st = 0u;
    UT_EQ(fx_sat16(-32769, &st), -32768);
    UT_UEQ(st, FX_ST_SAT_LO);
    st = 0u;
    UT_UEQ(fx_satu32(-1, &st), 0u);
    UT_UEQ(st, FX_ST_SAT_LO);
    st = 0u;
    UT_UEQ(fx_satu32((int64_t)UINT32_MAX + 1, &st), UINT32_MAX);
    UT_UEQ(st, FX_ST_SAT_HI);
    st = 0u;
    UT_UEQ(fx_satu32(UINT32_MAX, &st), UINT32_MAX);
    UT_UEQ(st, 0u);
}

UT_TEST(add_sub_neg_abs_edges)
{
    size_t i;
    size_t j;
    for (i = 0u; i < NELEM(edge32); i++) {
        for (j = 0u; j < NELEM(edge32); j++) {
            int64_t a = edge32[i];
            int64_t b = edge32[j];
            fx_status_t st = 0u;
            int64_t s = a + b;
            fx_status_t want = (s > INT32_MAX) ? FX_ST_SAT_HI : ((s < INT32_MIN) ? FX_ST_SAT_LO : 0u);
            UT_CHECK_EQ(fx_add_sat(edge32[i], edge32[j], &st), ut_ref_clamp32(s));
            UT_CHECK_UEQ(st, want);
            st = 0u;
            s = a - b;
            want = (s > INT32_MAX) ? FX_ST_SAT_HI : ((s < INT32_MIN) ? FX_ST_SAT_LO : 0u);
            UT_CHECK_EQ(fx_sub_sat(edge32[i], edge32[j], &st), ut_ref_clamp32(s));
            UT_CHECK_UEQ(st, want);
        }
    }
    {
        fx_status_t st = 0u;
        UT_EQ(fx_neg(INT32_MIN, &st), INT32_MAX);
        UT_UEQ(st, FX_ST_SAT_HI);
        st = 0u;
        UT_EQ(fx_abs(INT32_MIN, &st), INT32_MAX);
        UT_UEQ(st, FX_ST_SAT_HI);
        st = 0u;
        UT_EQ(fx_neg(INT32_MAX, &st), -INT32_MAX);
        UT_EQ(fx_abs(-5, &st), 5);
        UT_EQ(fx_neg(0, &st), 0);
        UT_UEQ(st, 0u);
        UT_UEQ(fx_uabs(INT32_MIN), (uint32_t)1 << 31);
        UT_UEQ(fx_uabs(-7), 7u);
    }
}

UT_TEST(add64_overflow)
{
    fx_status_t st = 0u;
    UT_EQ(fx_add64_sat(INT64_MAX, 1, &st), INT64_MAX);
    UT_UEQ(st, FX_ST_ACC_OVF);
    st = 0u;
    UT_EQ(fx_add64_sat(INT64_MIN, -1, &st), INT64_MIN);
    UT_UEQ(st, FX_ST_ACC_OVF);
    st = 0u;
    UT_EQ(fx_add64_sat(INT64_MAX, INT64_MIN, &st), -1);
    UT_EQ(fx_add64_sat(INT64_MIN + 1, -1, &st), INT64_MIN);
    UT_UEQ(st, 0u);
}

UT_TEST(shl_sat_all_shifts)
{
    size_t i;
    uint32_t n;
    for (n = 0u; n < 32u; n++) {
        for (i = 0u; i < NELEM(edge32); i++) {
            fx_status_t st = 0u;
            int64_t exact = (int64_t)edge32[i] * ((int64_t)1 << n);
            fx_status_t want = (exact > INT32_MAX) ? FX_ST_SAT_HI : ((exact < INT32_MIN) ? FX_ST_SAT_LO : 0u);
            UT_CHECK_EQ(fx_shl_sat(edge32[i], n, &st), ut_ref_clamp32(exact));
            UT_CHECK_UEQ(st, want);
        }
    }
    {
        fx_status_t st = 0u;
        UT_EQ(fx_shl_sat(1, 32u, &st), 0);
        UT_UEQ(st, FX_ST_ARG);
    }
}

UT_TEST(shr_rnd_ties_and_sweep)
{
    fx_status_t st = 0u;
    uint64_t seed = 1u;
    uint32_t n;
    uint32_t i;
    /* Ties go away from zero, and the rule is odd-symmetric. */
    UT_EQ(fx_shr_rnd64(3, 1u, &st), 2);
    UT_EQ(fx_shr_rnd64(-3, 1u, &st), -2);
    UT_EQ(fx_shr_rnd64(1, 1u, &st), 1);
    UT_EQ(fx_shr_rnd64(-1, 1u, &st), -1);
    UT_EQ(fx_shr_rnd64(5, 2u, &st), 1);     /* 1.25 */
    UT_EQ(fx_shr_rnd64(-5, 2u, &st), -1);
    UT_EQ(fx_shr_rnd64(6, 2u, &st), 2);     /* 1.5 */
    UT_EQ(fx_shr_rnd64(-6, 2u, &st), -2);
    UT_EQ(fx_shr_rnd64(INT64_MIN, 63u, &st), -1);
    UT_EQ(fx_shr_rnd64(INT64_MAX, 63u, &st), 1);
    UT_EQ(fx_shr_rnd64(INT64_MIN, 1u, &st), -((int64_t)1 << 62));
    UT_EQ(fx_shr_rnd(INT32_MIN, 31u, &st), -1);
    UT_EQ(fx_shr_rnd(INT32_MAX, 31u, &st), 1);
    UT_EQ(fx_shr_rnd(-1, 0u, &st), -1);
    UT_UEQ(st, 0u);
    UT_EQ(fx_shr_rnd64(1, 64u, &st), 0);
    UT_UEQ(st, FX_ST_ARG);
    st = 0u;
    UT_EQ(fx_shr_rnd(1, 32u, &st), 0);
    UT_UEQ(st, FX_ST_ARG);
    for (n = 0u; n < 64u; n++) {
        for (i = 0u; i < 2000u; i++) {
            int64_t p = (int64_t)ut_rng_next(&seed);
            /* Mix magnitudes so small shifts see small values and ties appear. */
            uint32_t drop = (uint32_t)(ut_rng_next(&seed) % 63u);
            fx_status_t s2 = 0u;
            if (drop > 0u) {
                p = ((p < 0) ? -1 : 1) * (int64_t)(((uint64_t)p & (UINT64_MAX >> 1)) >> drop);
            }
            if ((i & 7u) == 0u && n > 0u && n < 63u) {
                /* exact tie: odd multiple of 2^(n-1) */
                p = (((int64_t)(i | 1u)) * ((int64_t)1 << (n - 1u))) * (((i & 8u) != 0u) ? -1 : 1);
            }
            UT_CHECK_EQ(fx_shr_rnd64(p, n, &s2), ut_ref_shr(p, n));
            UT_CHECK_EQ(fx_shr_rnd64(-p, n, &s2), -ut_ref_shr(p, n));
            UT_CHECK_UEQ(s2, 0u);
        }
    }
}

UT_TEST(convert_edges)
{
    uint32_t qf;
    uint32_t qt;
    size_t i;
    for (qf = 0u; qf <= FX_Q_MAX; qf += 4u) {
        for (qt = 0u; qt <= FX_Q_MAX; qt += 3u) {
            for (i = 0u; i < NELEM(edge32); i++) {
                fx_status_t st = 0u;
                int64_t want;
                int32_t got = fx_convert(edge32[i], qf, qt, &st);
                if (qf >= qt) {
                    want = ut_ref_shr(edge32[i], qf - qt);
                    UT_CHECK_UEQ(st, 0u);
                } else {
                    uint32_t sh = qt - qf;
                    int64_t e = (sh > 32u) ? ((edge32[i] > 0) ? INT64_MAX : ((edge32[i] < 0) ? INT64_MIN : 0))
                                           : (int64_t)edge32[i] * ((int64_t)1 << sh);
                    want = ut_ref_clamp32(e);
                    UT_CHECK_UEQ(st, (want != e) ? (((e > 0) ? FX_ST_SAT_HI : FX_ST_SAT_LO) | FX_ST_CONV) : 0u);
                }
                UT_CHECK_EQ(got, want);
            }
        }
    }
    {
        fx_status_t st = 0u;
        UT_EQ(fx_convert(1, 41u, 0u, &st), 0);
        UT_UEQ(st, FX_ST_ARG);
        st = 0u;
        /* q24 -> q20 rounds: 0.5 LSB of q20 is 8 LSB of q24 */
        UT_EQ(fx_convert(8, 24u, 20u, &st), 1);
        UT_EQ(fx_convert(-8, 24u, 20u, &st), -1);
        UT_EQ(fx_convert(7, 24u, 20u, &st), 0);
        UT_EQ(fx_convert64(INT64_MAX, 62u, 29u, &st), 1073741824);  /* (2^63-1)/2^62 = 2.0 - 2^-62 -> 2.0 in q29 */
        UT_UEQ(st, 0u);
    }
}

UT_TEST(counts)
{
    fx_status_t st = 0u;
    uint32_t c = UINT32_MAX - 1u;
    /* A 2^-20 rad/s gyro count into q29: scale 2^9. */
    UT_EQ(fx_from_count(1048575, 512, 0u, 0, &st), 1048575 * 512);
    UT_EQ(fx_from_count(-1048575, 512, 0u, 0, &st), -1048575 * 512);
    /* Counts of LSB 3/8 in q0 with a bias of 2: 5*3/8 = 1.875 -> 2, minus 2 = 0. */
    UT_EQ(fx_from_count(5, 3, 3u, 2, &st), 0);
    UT_EQ(fx_from_count(-5, 3, 3u, 0, &st), -2);
    UT_UEQ(st, 0u);
    UT_EQ(fx_from_count(INT32_MAX, INT32_MAX, 0u, 0, &st), INT32_MAX);
    UT_UEQ(st, FX_ST_SAT_HI);
    st = 0u;
    UT_EQ(fx_from_count(1, 1, 63u, 0, &st), 0);
    UT_UEQ(st, FX_ST_ARG);
    st = 0u;
    /* q29 rad/s -> 2^-20 counts: inv 1 / 2^9, clamp to +-(2^20 - 1). */
    UT_EQ(fx_to_count(512 * 1000 + 256, 1, 9u, -1048575, 1048575, &st), 1001);
    UT_EQ(fx_to_count(-(512 * 1000 + 256), 1, 9u, -1048575, 1048575, &st), -1001);
    UT_UEQ(st, 0u);
    UT_EQ(fx_to_count(INT32_MAX, 1, 9u, -1048575, 1048575, &st), 1048575);
    UT_UEQ(st, FX_ST_SAT_HI);
    st = 0u;
    UT_EQ(fx_to_count(INT32_MIN, 1, 9u, -1048575, 1048575, &st), -1048575);
    UT_UEQ(st, FX_ST_SAT_LO);
    st = 0u;
    UT_EQ(fx_to_count(5, 1, 0u, 3, 2, &st), 0);
    UT_UEQ(st, FX_ST_ARG);
    fx_cnt_inc(&c);
    UT_UEQ(c, UINT32_MAX);
    fx_cnt_inc(&c);
    UT_UEQ(c, UINT32_MAX);
}

/* fx_mul against an exact int64 product and the reference shift (shift <= 62 here). */
UT_TEST(mul_edges_and_random)
{
    static const uint32_t fm[][3] = {
        {29u, 29u, 29u}, {28u, 28u, 28u}, {30u, 30u, 30u}, {30u, 28u, 28u}, {24u, 20u, 22u},
        {0u, 0u, 0u}, {31u, 31u, 31u}, {40u, 20u, 30u}, {0u, 30u, 31u}, {10u, 10u, 30u},
    };
    uint64_t seed = 7u;
    size_t f;
    size_t i;
    size_t j;
    for (f = 0u; f < NELEM(fm); f++) {
        uint32_t qa = fm[f][0];
        uint32_t qb = fm[f][1];
        uint32_t qr = fm[f][2];
        for (i = 0u; i < NELEM(edge32) + 3000u; i++) {
            for (j = 0u; j < ((i < NELEM(edge32)) ? NELEM(edge32) : 1u); j++) {
                int32_t a = (i < NELEM(edge32)) ? edge32[i] : (int32_t)(uint32_t)ut_rng_next(&seed);
                int32_t b = (i < NELEM(edge32)) ? edge32[j] : (int32_t)(uint32_t)ut_rng_next(&seed);
                fx_status_t st = 0u;
                int64_t p = (int64_t)a * (int64_t)b;
                int64_t want;
                int32_t got = fx_mul(a, qa, b, qb, qr, &st);
                if (qa + qb >= qr) {
                    want = ut_ref_shr(p, qa + qb - qr);
                } else {
                    uint32_t sh = qr - qa - qb;
                    int64_t lim = (int64_t)1 << (62u - sh);
                    want = (p >= lim) ? INT64_MAX : ((p <= -lim) ? INT64_MIN : p * ((int64_t)1 << sh));
                }
                UT_CHECK_EQ(got, ut_ref_clamp32(want));
                UT_CHECK_UEQ(st, (want > INT32_MAX) ? FX_ST_SAT_HI : ((want < INT32_MIN) ? FX_ST_SAT_LO : 0u));
            }
        }
    }
    {
        fx_status_t st = 0u;
        /* Ties: 0.5 * 1 LSB -> away from zero. 1 (q1) * 1 (q0) -> q0: 0.5 -> 1. */
        UT_EQ(fx_mul(1, 1u, 1, 0u, 0u, &st), 1);
        UT_EQ(fx_mul(-1, 1u, 1, 0u, 0u, &st), -1);
        UT_EQ(fx_mul(3, 1u, 1, 0u, 0u, &st), 2);    /* 1.5 -> 2 */
        UT_EQ(fx_mul(-3, 1u, 1, 0u, 0u, &st), -2);
        UT_EQ(fx_mul(INT32_MIN, 31u, INT32_MIN, 31u, 31u, &st), INT32_MAX);  /* (-1)(-1) = 1 */
        UT_UEQ(st, FX_ST_SAT_HI);
        st = 0u;
        UT_EQ(fx_mul(1, 41u, 1, 0u, 0u, &st), 0);
        UT_UEQ(st, FX_ST_ARG);
    }
}

/* fx_div against int64 arithmetic where a * 2^k fits (k <= 31). */
UT_TEST(div_edges_and_random)
{
    static const uint32_t fm[][3] = {
        {28u, 28u, 28u}, {29u, 29u, 29u}, {30u, 30u, 30u}, {28u, 30u, 28u}, {0u, 0u, 0u}, {20u, 10u, 21u},
    };
    static const int32_t dv[] = {INT32_MIN, -1, 1, 2, 3, INT32_MAX, 1073741824, -1073741824};
    uint64_t seed = 11u;
    size_t f;
    size_t i;
    for (f = 0u; f < NELEM(fm); f++) {
        uint32_t qa = fm[f][0];
        uint32_t qb = fm[f][1];
        uint32_t qr = fm[f][2];
        uint32_t k = qr + qb - qa;
        for (i = 0u; i < 4000u; i++) {
            int32_t a = (i < NELEM(edge32)) ? edge32[i] : (int32_t)(uint32_t)ut_rng_next(&seed);
            int32_t b = (i < NELEM(dv) * 3u) ? dv[i % NELEM(dv)] : (int32_t)(uint32_t)ut_rng_next(&seed);
            fx_status_t st = 0u;
            int64_t num;
            int64_t q;
            int64_t rem;
            int64_t babs;
            if (b == 0) {
                continue;
            }
            num = (int64_t)a * ((int64_t)1 << k);
            q = num / b;
            rem = num % b;
            rem = (rem < 0) ? -rem : rem;
            babs = (b < 0) ? -(int64_t)b : (int64_t)b;
            if (rem >= (babs - rem)) {
                q += ((num < 0) != (b < 0)) ? -1 : 1;
            }
            UT_CHECK_EQ(fx_div(a, qa, b, qb, qr, &st), ut_ref_clamp32(q));
            UT_CHECK_UEQ(st, (q > INT32_MAX) ? FX_ST_SAT_HI : ((q < INT32_MIN) ? FX_ST_SAT_LO : 0u));
        }
    }
    {
        fx_status_t st = 0u;
        UT_EQ(fx_div(5, 0u, 0, 0u, 0u, &st), INT32_MAX);
        UT_UEQ(st, FX_ST_DIV0);
        st = 0u;
        UT_EQ(fx_div(-5, 0u, 0, 0u, 0u, &st), -INT32_MAX);
        UT_UEQ(st, FX_ST_DIV0);
        st = 0u;
        UT_EQ(fx_div(0, 0u, 0, 0u, 0u, &st), 0);
        UT_UEQ(st, FX_ST_DIV0);
        st = 0u;
        /* Saturation at the extreme k = 80 and underflow at k = -40. */
        UT_EQ(fx_div(1, 0u, INT32_MAX, 40u, 40u, &st), INT32_MAX);
        UT_UEQ(st, FX_ST_SAT_HI);
        st = 0u;
        UT_EQ(fx_div(INT32_MAX, 40u, 1, 0u, 0u, &st), 0);
        UT_EQ(fx_div(INT32_MIN, 31u, INT32_MIN, 31u, 30u, &st), 1073741824);
        UT_EQ(fx_div(INT32_MIN, 0u, -1, 0u, 0u, &st), INT32_MAX);
        UT_UEQ(st, FX_ST_SAT_HI);
        st = 0u;
        UT_EQ(fx_div(INT32_MIN, 0u, 1, 0u, 0u, &st), INT32_MIN);
        UT_UEQ(st, 0u);
    }
}

/* FX_STATIC_ASSERT is used at file scope (spec 00 §1.2); these would stop the build if wrong. */
FX_STATIC_ASSERT(ut_sa_fits, FX_Q_RAT_FITS(1, 3, 30));
FX_STATIC_ASSERT(ut_sa_nofit, !FX_Q_RAT_FITS(2, 1, 30));
FX_STATIC_ASSERT(ut_sa_min, FX_Q_RAT_FITS(-2, 1, 30));

UT_TEST(q_constants)
{
    /* Values checked by hand: 1/3 * 2^30 = 357913941.33; -1/3 rounds to -357913941. */
    UT_EQ(FX_Q_RAT(1, 3, 30), 357913941);
    UT_EQ(FX_Q_RAT(-1, 3, 30), -357913941);
    UT_EQ(FX_Q_RAT(1, 2, 0), 1);      /* tie 0.5 -> 1 */
    UT_EQ(FX_Q_RAT(-1, 2, 0), -1);    /* tie -0.5 -> -1 */
    UT_EQ(FX_Q_RAT(7853982, 10000000, 30), 843314896);  /* 0.7853982 * 2^30 = 843314895.83 */
    UT_EQ(FX_Q_INT(-2, 29), -1073741824);
    UT_EQ(FX_Q_INT(1, 30), 1073741824);
}

UT_TEST(crc32_check_values)
{
    static const uint8_t check[] = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};
    static const uint8_t zeros[4] = {0u, 0u, 0u, 0u};
    UT_UEQ(fx_crc32(0u, check, sizeof check), 0xCBF43926u);
    /* Chaining equals one pass. */
    UT_UEQ(fx_crc32(fx_crc32(0u, check, 4u), &check[4], 5u), 0xCBF43926u);
    UT_UEQ(fx_crc32(0u, zeros, 4u), 0x2144DF1Cu);   /* zlib.crc32(b"\0" * 4) */
    UT_UEQ(fx_crc32(0u, check, 0u), 0u);
}

int main(void)
{
    UT_CASES(cases) = {
        UT_CASE(sat16_u32), UT_CASE(add_sub_neg_abs_edges), UT_CASE(add64_overflow),
        UT_CASE(shl_sat_all_shifts), UT_CASE(shr_rnd_ties_and_sweep), UT_CASE(convert_edges),
        UT_CASE(counts), UT_CASE(mul_edges_and_random), UT_CASE(div_edges_and_random),
        UT_CASE(q_constants), UT_CASE(crc32_check_values), UT_CASE(sat_and_add),
    };
    return UT_RUN("fx_core", cases);
}
