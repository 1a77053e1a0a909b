/*
 * fx_sqrt.c — exact integer square root and the rounded fixed-point roots built on it.
 * The bitwise method runs exactly 32 iterations whatever the input, so its cost is fixed.
 */
#include "fx.h"

uint32_t fx_isqrt64(uint64_t x)
{
    uint64_t rem = x;
    uint64_t root = 0u;
    uint64_t bit = (uint64_t)1 << 62;
    uint32_t i;
    /* Classic digit-by-digit method, one result bit per iteration: invariant
       root^2 + rem == x for the bits decided so far (root scaled by the current bit). */
    for (i = 0u; i < 32u; i++) {
        uint64_t trial = root + bit;
        if (rem >= trial) {
            rem -= trial;
            root = (root >> 1) + bit;
        } else {
            root >>= 1;
        }
        bit >>= 2;
    }
    return (uint32_t)root;
}

/* round(sqrt(x)) from the floor root r: sqrt(x) >= r + 1/2  <=>  x - r^2 > r (integers). */
static uint64_t isqrt_rnd(uint64_t x)
{
    uint64_t r = (uint64_t)fx_isqrt64(x);
    return ((x - (r * r)) > r) ? (r + 1u) : r;
}

int32_t fx_sqrt(int32_t a, uint32_t qa, uint32_t qr, fx_status_t *st)
{
    int32_t r = 0;
    /* x = a * 2^(2 qr - qa) holds 2 qr fraction bits, so sqrt(x) holds qr. Shift <= 33 keeps
       x below 2^64 for a < 2^31. */
    int32_t sh = (2 * (int32_t)qr) - (int32_t)qa;
    if ((qa > FX_Q_MAX) || (qr > FX_Q_MAX) || (sh < 0) || (sh > 33)) {
        *st |= FX_ST_ARG;
    } else if (a < 0) {
        *st |= FX_ST_DOMAIN;
    } else {
        uint64_t x = (uint64_t)(uint32_t)a << (uint32_t)sh;
        uint64_t s = isqrt_rnd(x);
        if (s > (uint64_t)INT32_MAX) {
            *st |= FX_ST_SAT_HI;
            r = INT32_MAX;
        } else {
            r = (int32_t)s;
        }
    }
    return r;
}

int32_t fx_norm3(const int32_t v[3], fx_status_t *st)
{
    int32_t r;
    uint64_t s = 0u;
    uint32_t i;
    /* Each square is <= 2^62 and 3 * 2^62 < 2^64: the sum is exact with no prescaling. */
    for (i = 0u; i < 3u; i++) {
        uint64_t m = (uint64_t)fx_uabs(v[i]);
        s += m * m;
    }
    {
        uint64_t n = isqrt_rnd(s);
        if (n > (uint64_t)INT32_MAX) {
            *st |= FX_ST_SAT_HI;
            r = INT32_MAX;
        } else {
            r = (int32_t)n;
        }
    }
    return r;
}
