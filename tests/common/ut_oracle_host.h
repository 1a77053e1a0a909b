/*
 * ut_oracle_host.h — exact 128-bit oracle for host-only sweeps (x86-64 GCC/Clang __int128).
 * Every product, shifted product and quotient of the fx formats is exact in 128 bits, so
 * "correctly rounded" is tested as bitwise equality.
 */
#ifndef TESTS_UT_ORACLE_HOST_H
#define TESTS_UT_ORACLE_HOST_H

#include <stdint.h>

__extension__ typedef __int128 i128;
__extension__ typedef unsigned __int128 u128;

/* round(v / 2^n), half away from zero, exact. */
static inline i128 o_shr(i128 v, uint32_t n)
{
    i128 d;
    i128 q;
    i128 r;
    if (n == 0u) {
        return v;
    }
    d = (i128)1 << n;
    q = v / d;
    r = v % d;
    if (r < 0) {
        r = -r;
    }
    if (2 * r >= d) {
        q += (v < 0) ? -1 : 1;
    }
    return q;
}

#endif /* TESTS_UT_ORACLE_HOST_H */
