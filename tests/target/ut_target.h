/*
 * ut_target.h — pieces of the target runner (ut_target.c) exposed to its own self-test.
 * Test sources use tests/common/ut.h only.
 */
#ifndef TESTS_UT_TARGET_H
#define TESTS_UT_TARGET_H

#include <stdint.h>
#include <stddef.h>

#define UT_FMT_DEC_MAX 21u   /* "-9223372036854775808" + NUL */
#define UT_FMT_HEX_MAX 11u   /* "0x" + 8 digits + NUL */

/* Each writes a NUL-terminated string into buf and returns its length (without the NUL). */
size_t ut_fmt_u64(char buf[UT_FMT_DEC_MAX], uint64_t v);
size_t ut_fmt_i64(char buf[UT_FMT_DEC_MAX], int64_t v);
size_t ut_fmt_u32hex(char buf[UT_FMT_HEX_MAX], uint32_t v);

#endif /* TESTS_UT_TARGET_H */
