/*
 * fx_inline.h — inlinable twins of the hottest fx_core primitives (spec 00 §1.3).
 *
 * These are the implementation of fx_sat32, fx_shr_rnd64, fx_rshift_sat and fx_add64_sat: the
 * out-of-line functions of fx.h (fx_core.c) are one-line wrappers around them, so the two forms
 * cannot drift apart and the oracle sweeps of tests/unit/test_fx_core*.c test both. They exist
 * because a call to the generic out-of-line shift costs ~50 instructions on Cortex-M3 (variable
 * 64-bit shift, the range checks, three calls), while the inlined form with a constant shift folds
 * to ~8. They keep fx_core.c's rules: rounding on the unsigned magnitude with the sign reapplied,
 * so no signed value is ever shifted, and overflow tests before the operation (or
 * __builtin_add_overflow under GCC; FX_PORTABLE_C, set by the asan-ubsan preset, builds and so
 * tests the portable path).
 *
 * For hot kernels of fsw/ modules; everything else calls the fx.h functions.
 */
#ifndef FSW_FX_INLINE_H
#define FSW_FX_INLINE_H

#include "fx.h"

/* -Os does not inline a multi-statement function of a header on its own, and a call is what these
   twins exist to avoid: GCC and Clang are told to inline always (a portable compiler may still
   choose; the results are the same either way). */
#if defined(__GNUC__)
#define FX_INLINE static inline __attribute__((always_inline))
#else
#define FX_INLINE static inline
#endif

/* fx_sat32: clamp to int32, SAT_HI / SAT_LO. */
FX_INLINE int32_t fx_sat32_i(int64_t v, fx_status_t *st)
{
    int32_t r;
    if (v > (int64_t)INT32_MAX) {
        *st |= FX_ST_SAT_HI;
        r = INT32_MAX;
    } else if (v < (int64_t)INT32_MIN) {
        *st |= FX_ST_SAT_LO;
        r = INT32_MIN;
    } else {
        r = (int32_t)v;
    }
    return r;
}

/* fx_shr_rnd64: round(p / 2^n) half away from zero; n == 0 returns p; n > 63 -> ARG and 0. */
FX_INLINE int64_t fx_shr_rnd64_i(int64_t p, uint32_t n, fx_status_t *st)
{
    int64_t r;
    if (n == 0u) {
        r = p;
    } else if (n > 63u) {
        *st |= FX_ST_ARG;
        r = 0;
    } else {
        /* |p| <= 2^63, so the rounded magnitude is <= 2^62 + 1 and the negation cannot overflow. */
        uint64_t m = (p < 0) ? ((uint64_t)0 - (uint64_t)p) : (uint64_t)p;
        uint64_t q = (m >> n) + ((m >> (n - 1u)) & 1u);
        r = (p < 0) ? -(int64_t)q : (int64_t)q;
    }
    return r;
}

/* fx_rshift_sat: fx_sat32(fx_shr_rnd64(p, n)). */
FX_INLINE int32_t fx_rshift_sat_i(int64_t p, uint32_t n, fx_status_t *st)
{
    return fx_sat32_i(fx_shr_rnd64_i(p, n, st), st);
}

/* fx_add64_sat: a + b; on overflow ACC_OVF and the int64 extreme in b's direction. */
FX_INLINE int64_t fx_add64_sat_i(int64_t a, int64_t b, fx_status_t *st)
{
    int64_t r;
#if defined(__GNUC__) && !defined(FX_PORTABLE_C)
    bool ovf = __builtin_add_overflow(a, b, &r);   /* ADDS/ADCS + a V-flag test */
    if (ovf) {
        *st |= FX_ST_ACC_OVF;
        r = (b > 0) ? INT64_MAX : INT64_MIN;
    }
#else
    if ((b > 0) && (a > (INT64_MAX - b))) {
        *st |= FX_ST_ACC_OVF;
        r = INT64_MAX;
    } else if ((b < 0) && (a < (INT64_MIN - b))) {
        *st |= FX_ST_ACC_OVF;
        r = INT64_MIN;
    } else {
        r = a + b;
    }
#endif
    return r;
}

#endif /* FSW_FX_INLINE_H */
