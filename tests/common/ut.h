/*
 * ut.h — thin test macro layer (spec 00 §6.3). Test sources are written once against these
 * macros; on the host they map to CMocka, on the Cortex-M target to the project's own runner
 * (tests/target/ut_target.c), because CMocka is packaged for the host only and no third-party
 * source is vendored.
 *
 * Failures print file, line, the expression and both values (as 64-bit integers). UT_EQ & co
 * record the failure and return from the test body; UT_CHECK_* record it and carry on (use
 * them in helpers). Either way the test is failed when its body ends.
 *
 *   UT_TEST(name) { ... }            define a test
 *   UT_CASE(name)                     entry of the case table
 *   return UT_RUN("group", cases);   run, print "N passed, N failed", return failure count
 */
#ifndef TESTS_UT_H
#define TESTS_UT_H

#include <stdint.h>
#include <stddef.h>

/* Output helpers without printf (the target image has no libc). */
void ut_puts(const char *s);            /* writes s, no newline added */
void ut_put_u32hex(uint32_t v);         /* 0x%08x */
void ut_put_i64(int64_t v);             /* decimal */
void ut_put_u64(uint64_t v);            /* decimal */

/* Records a failure; returns nothing. Used by all macros. */
void ut_record_fail(const char *file, int line, const char *expr, int64_t a, int64_t b);
void ut_record_failu(const char *file, int line, const char *expr, uint64_t a, uint64_t b);
/* Number of failures recorded in the current test so far. */
unsigned ut_fail_count(void);

/* Bracket every test: failures recorded in a test body fail that test, on both platforms. */
void ut_begin_test(void);
void ut_end_test(void);    /* host: CMocka fail() if the body recorded a failure */

#define UT_TEST(name) \
    static void name##_body(void); \
    static void name(void **ut_state_) { (void)ut_state_; ut_begin_test(); name##_body(); ut_end_test(); } \
    static void name##_body(void)

#if defined(UT_TARGET)
/* ------------------------------------------------------------------ target runner */
typedef struct {
    const char *name;
    void (*fn)(void **state);
} ut_case_t;
int ut_run_cases(const char *group, const ut_case_t *cases, size_t n);
#define UT_CASE(name) { #name, name }
#define UT_CASES(var) static const ut_case_t var[]
#define UT_RUN(group, cases) ut_run_cases((group), (cases), sizeof(cases) / sizeof((cases)[0]))
#else
/* ------------------------------------------------------------------ host: CMocka */
#include <stdarg.h>
#include <setjmp.h>
#include <cmocka.h>
#define UT_CASE(name) cmocka_unit_test(name)
#define UT_CASES(var) static const struct CMUnitTest var[]
#define UT_RUN(group, cases) _cmocka_run_group_tests((group), (cases), \
                                 sizeof(cases) / sizeof((cases)[0]), NULL, NULL)
#endif
#define UT_END_TEST_ return

/* Record-only checks (usable anywhere, continue after failure). */
#define UT_CHECK_EQ(a, b) do { int64_t ut_a_ = (int64_t)(a), ut_b_ = (int64_t)(b); \
    if (ut_a_ != ut_b_) { ut_record_fail(__FILE__, __LINE__, #a " == " #b, ut_a_, ut_b_); } } while (0)
#define UT_CHECK_UEQ(a, b) do { uint64_t ut_a_ = (uint64_t)(a), ut_b_ = (uint64_t)(b); \
    if (ut_a_ != ut_b_) { ut_record_failu(__FILE__, __LINE__, #a " == " #b, ut_a_, ut_b_); } } while (0)
#define UT_CHECK_LE(a, b) do { int64_t ut_a_ = (int64_t)(a), ut_b_ = (int64_t)(b); \
    if (!(ut_a_ <= ut_b_)) { ut_record_fail(__FILE__, __LINE__, #a " <= " #b, ut_a_, ut_b_); } } while (0)
#define UT_CHECK(c) do { if (!(c)) { ut_record_fail(__FILE__, __LINE__, #c, 0, 1); } } while (0)

/* Fatal checks: end the test body on failure (only in the test function itself). */
#define UT_EQ(a, b)  do { int64_t ut_a_ = (int64_t)(a), ut_b_ = (int64_t)(b); \
    if (ut_a_ != ut_b_) { ut_record_fail(__FILE__, __LINE__, #a " == " #b, ut_a_, ut_b_); UT_END_TEST_; } } while (0)
#define UT_UEQ(a, b) do { uint64_t ut_a_ = (uint64_t)(a), ut_b_ = (uint64_t)(b); \
    if (ut_a_ != ut_b_) { ut_record_failu(__FILE__, __LINE__, #a " == " #b, ut_a_, ut_b_); UT_END_TEST_; } } while (0)
#define UT_LE(a, b)  do { int64_t ut_a_ = (int64_t)(a), ut_b_ = (int64_t)(b); \
    if (!(ut_a_ <= ut_b_)) { ut_record_fail(__FILE__, __LINE__, #a " <= " #b, ut_a_, ut_b_); UT_END_TEST_; } } while (0)
#define UT_TRUE(c)   do { if (!(c)) { ut_record_fail(__FILE__, __LINE__, #c, 0, 1); UT_END_TEST_; } } while (0)

/* Deterministic integer PRNG for sweeps (splitmix64): identical on host and target. */
static inline uint64_t ut_rng_next(uint64_t *s)
{
    uint64_t z = (*s += UINT64_C(0x9E3779B97F4A7C15));
    z = (z ^ (z >> 30)) * UINT64_C(0xBF58476D1CE4E5B9);
    z = (z ^ (z >> 27)) * UINT64_C(0x94D049BB133111EB);
    return z ^ (z >> 31);
}

#endif /* TESTS_UT_H */
