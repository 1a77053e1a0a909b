/*
 * Host-only sweeps of the roots (spec 00 §1.6): every x < 2^24; k^2-1, k^2, k^2+2k for 2^16
 * values of k including 2^32-1; 2^20 random; fx_sqrt per format in use; fx_norm3 random.
 * Oracle: the defining integer inequalities in __int128 (exact), so the contract "exact floor"
 * and "<= 0.5 LSB" have no slack.
 */
#include "fx.h"
#include "ut.h"
#include "ut_oracle_host.h"

#include <stdio.h>


static bool floor_ok(uint64_t x, uint32_t r)
{
    u128 rr = (u128)r * r;
    u128 r1 = ((u128)r + 1u) * ((u128)r + 1u);
    return rr <= x && r1 > x;
}

static bool round_ok(u128 x, uint64_t s)
{
    u128 lo = (s == 0u) ? 0u : ((u128)2u * s - 1u) * ((u128)2u * s - 1u);
    u128 hi = ((u128)2u * s + 1u) * ((u128)2u * s + 1u);
    return lo <= 4u * x && hi > 4u * x;
}

UT_TEST(isqrt_sweep)
{
    uint64_t x;
    uint64_t seed = 42u;
    uint32_t i;
    uint64_t n = 0u;
    for (x = 0u; x < (1u << 24); x++) {
        if (!floor_ok(x, fx_isqrt64(x))) {
            UT_CHECK_UEQ(x, UINT64_MAX);
            return;
        }
        n++;
    }
    for (i = 0u; i < (1u << 16); i++) {
        /* k spread over the whole 32-bit range, ending exactly at 2^32 - 1. */
        uint64_t k = (i == (1u << 16) - 1u) ? 0xFFFFFFFFu : ((uint64_t)i << 16) + (ut_rng_next(&seed) & 0xFFFFu);
        uint64_t k2 = k * k;
        UT_CHECK(floor_ok(k2, fx_isqrt64(k2)));
        UT_CHECK(k2 == 0u || floor_ok(k2 - 1u, fx_isqrt64(k2 - 1u)));
        UT_CHECK(floor_ok(k2 + 2u * k, fx_isqrt64(k2 + 2u * k)));
        n += 3u;
    }
    for (i = 0u; i < (1u << 20); i++) {
        uint64_t r = ut_rng_next(&seed) >> (i % 64u);
        UT_CHECK(floor_ok(r, fx_isqrt64(r)));
        n++;
    }
    printf("fx_isqrt64: %llu inputs, exact floor in every case\n", (unsigned long long)n);
}

UT_TEST(sqrt_sweep)
{
    static const uint32_t fm[][2] = {
        {30u, 30u}, {29u, 29u}, {28u, 28u}, {24u, 24u}, {30u, 15u}, {20u, 26u}, {0u, 0u}, {0u, 16u}, {31u, 32u}, {40u, 36u},
    };
    uint64_t seed = 4242u;
    uint32_t f;
    uint64_t n = 0u;
    for (f = 0u; f < (sizeof fm / sizeof fm[0]); f++) {
        uint32_t i;
        uint32_t sh = 2u * fm[f][1] - fm[f][0];
        for (i = 0u; i < (1u << 20); i++) {
            fx_status_t st = 0u;
            int32_t a = (int32_t)(ut_rng_next(&seed) >> (33u + (i % 31u)));
            int32_t s = fx_sqrt(a, fm[f][0], fm[f][1], &st);
            u128 x = (u128)(uint32_t)a << sh;
            if (st == FX_ST_SAT_HI) {
                UT_CHECK(!round_ok(x, INT32_MAX) || s == INT32_MAX);
                UT_CHECK(4u * x >= ((u128)2u * INT32_MAX + 1u) * ((u128)2u * INT32_MAX + 1u));
            } else {
                UT_CHECK_UEQ(st, 0u);
                UT_CHECK(round_ok(x, (uint64_t)s));
            }
            n++;
        }
    }
    printf("fx_sqrt: %llu inputs over %zu formats, all within 0.5 LSB (rounded to nearest)\n",
           (unsigned long long)n, sizeof fm / sizeof fm[0]);
}

UT_TEST(norm3_sweep)
{
    uint64_t seed = 17u;
    uint32_t i;
    uint32_t sat = 0u;
    for (i = 0u; i < (1u << 20); i++) {
        int32_t v[3];
        u128 s2 = 0u;
        uint32_t j;
        fx_status_t st = 0u;
        int32_t n;
        for (j = 0u; j < 3u; j++) {
            v[j] = (int32_t)(uint32_t)(ut_rng_next(&seed) >> (32u + (i % 8u)));
            s2 += (u128)(((i128)v[j]) * v[j]);
        }
        n = fx_norm3(v, &st);
        if (4u * s2 >= ((u128)2u * INT32_MAX + 1u) * ((u128)2u * INT32_MAX + 1u)) {
            UT_CHECK_UEQ(st, FX_ST_SAT_HI);
            UT_CHECK_EQ(n, INT32_MAX);
            sat++;
        } else {
            UT_CHECK_UEQ(st, 0u);
            UT_CHECK(round_ok(s2, (uint64_t)n));
        }
    }
    printf("fx_norm3: %u random vectors, <= 0.5 LSB, %u correctly saturated\n", 1u << 20, sat);
}

int main(void)
{
    UT_CASES(cases) = { UT_CASE(isqrt_sweep), UT_CASE(sqrt_sweep), UT_CASE(norm3_sweep) };
    return UT_RUN("fx_sqrt_sweep", cases);
}
