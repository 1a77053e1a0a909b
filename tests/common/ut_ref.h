/*
 * ut_ref.h — reference arithmetic for tests, built on C99 truncating division and remainder,
 * so it is independent of fx_core's magnitude-based rounding. Integer-only: usable on target.
 */
#ifndef TESTS_UT_REF_H
#define TESTS_UT_REF_H

#include <stdint.h>

/* round(p / 2^n), half away from zero, n in [0, 63]. */
static inline int64_t ut_ref_shr(int64_t p, uint32_t n)
{
    int64_t d;
    int64_t q;
    int64_t rem;
    if (n == 0u) {
        return p;
    }
    if (n == 63u) {
        /* |p| <= 2^63: |p| / 2^63 <= 1; the result is +-1 iff |p| >= 2^62. */
        return (p >= ((int64_t)1 << 62)) ? 1 : ((p <= -((int64_t)1 << 62)) ? -1 : 0);
    }
    d = (int64_t)1 << n;
    q = p / d;
    rem = p % d;
    rem = (rem < 0) ? -rem : rem;
    if (rem >= (d - rem)) {
        q += (p < 0) ? -1 : 1;
    }
    return q;
}

static inline int64_t ut_ref_clamp32(int64_t v)
{
    return (v > INT32_MAX) ? INT32_MAX : ((v < INT32_MIN) ? INT32_MIN : v);
}

#endif /* TESTS_UT_REF_H */
