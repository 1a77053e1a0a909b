/*
 * ut_target.c — target side of tests/common/ut.h (spec 00 §6.3): the project's own runner for
 * Cortex-M images under QEMU. CMocka is packaged for the host only and no third-party source
 * is vendored, and the image has no libc, so integers are formatted here without printf.
 *
 * Output goes to the board console (semihosting → QEMU → CTest). A run ends with exactly one
 * line "N passed, N failed"; main returns the failed-test count, which becomes QEMU's exit
 * status through the board's exit path.
 */
#include "ut.h"
#include "ut_target.h"
#include "board.h"

/* Harness state of the test image (one runner per image). */
static unsigned ut_fails_in_test;

/* ------------------------------------------------------------------ formatting */

/* Powers of ten instead of division: no 64-bit divide (libgcc call) on the reporting path. */
static const uint64_t ut_pow10[20] = {
    UINT64_C(10000000000000000000), UINT64_C(1000000000000000000), UINT64_C(100000000000000000),
    UINT64_C(10000000000000000), UINT64_C(1000000000000000), UINT64_C(100000000000000),
    UINT64_C(10000000000000), UINT64_C(1000000000000), UINT64_C(100000000000),
    UINT64_C(10000000000), UINT64_C(1000000000), UINT64_C(100000000), UINT64_C(10000000),
    UINT64_C(1000000), UINT64_C(100000), UINT64_C(10000), UINT64_C(1000), UINT64_C(100),
    UINT64_C(10), UINT64_C(1)
};

static size_t ut_fmt_mag(char *buf, uint64_t v)
{
    size_t n = 0u;
    size_t i;
    uint64_t r = v;

    for (i = 0u; i < 20u; i++) {
        unsigned d = 0u;
        while (r >= ut_pow10[i]) {
            r -= ut_pow10[i];
            d++;
        }
        if ((d != 0u) || (n != 0u) || (i == 19u)) {
            buf[n] = (char)('0' + (int)d);
            n++;
        }
    }
    buf[n] = '\0';
    return n;
}

size_t ut_fmt_u64(char buf[UT_FMT_DEC_MAX], uint64_t v)
{
    return ut_fmt_mag(buf, v);
}

size_t ut_fmt_i64(char buf[UT_FMT_DEC_MAX], int64_t v)
{
    size_t n;

    if (v < 0) {
        buf[0] = '-';
        /* Unsigned negation: |INT64_MIN| is representable only as uint64_t. */
        n = 1u + ut_fmt_mag(&buf[1], UINT64_C(0) - (uint64_t)v);
    } else {
        n = ut_fmt_mag(buf, (uint64_t)v);
    }
    return n;
}

size_t ut_fmt_u32hex(char buf[UT_FMT_HEX_MAX], uint32_t v)
{
    static const char digits[16] = {
        '0', '1', '2', '3', '4', '5', '6', '7', '8', '9', 'a', 'b', 'c', 'd', 'e', 'f'
    };
    size_t i;

    buf[0] = '0';
    buf[1] = 'x';
    for (i = 0u; i < 8u; i++) {
        buf[2u + i] = digits[(v >> (28u - (4u * (uint32_t)i))) & 0xFu];
    }
    buf[10] = '\0';
    return 10u;
}

/* ------------------------------------------------------------------ output */

void ut_puts(const char *s)
{
    board_console_write(s);
}

void ut_put_u32hex(uint32_t v)
{
    char b[UT_FMT_HEX_MAX];
    (void)ut_fmt_u32hex(b, v);
    ut_puts(b);
}

void ut_put_i64(int64_t v)
{
    char b[UT_FMT_DEC_MAX];
    (void)ut_fmt_i64(b, v);
    ut_puts(b);
}

void ut_put_u64(uint64_t v)
{
    char b[UT_FMT_DEC_MAX];
    (void)ut_fmt_u64(b, v);
    ut_puts(b);
}

/* ------------------------------------------------------------------ failures */

static void ut_fail_head(const char *file, int line, const char *expr)
{
    ut_fails_in_test++;
    ut_puts(file);
    ut_puts(":");
    ut_put_i64((int64_t)line);
    ut_puts(": check failed: ");
    ut_puts(expr);
    ut_puts(" (");
}

void ut_record_fail(const char *file, int line, const char *expr, int64_t a, int64_t b)
{
    ut_fail_head(file, line, expr);
    ut_put_i64(a);
    ut_puts(" vs ");
    ut_put_i64(b);
    ut_puts(")\n");
}

void ut_record_failu(const char *file, int line, const char *expr, uint64_t a, uint64_t b)
{
    ut_fail_head(file, line, expr);
    ut_put_u64(a);
    ut_puts(" vs ");
    ut_put_u64(b);
    ut_puts(")\n");
}

unsigned ut_fail_count(void)
{
    return ut_fails_in_test;
}

void ut_begin_test(void)
{
    ut_fails_in_test = 0u;
}

void ut_end_test(void)
{
    /* The runner reads ut_fails_in_test after the case returns; nothing to unwind here. */
}

/* ------------------------------------------------------------------ runner */

int ut_run_cases(const char *group, const ut_case_t *cases, size_t n)
{
    size_t passed = 0u;
    size_t failed = 0u;
    size_t i;

    ut_puts("[==========] ");
    ut_puts(group);
    ut_puts(": ");
    ut_put_u64((uint64_t)n);
    ut_puts(" test(s)\n");
    for (i = 0u; i < n; i++) {
        void *state = NULL;

        ut_puts("[ RUN      ] ");
        ut_puts(cases[i].name);
        ut_puts("\n");
        /* Also reset here: a case that bypasses UT_TEST must not inherit earlier failures. */
        ut_fails_in_test = 0u;
        cases[i].fn(&state);
        if (ut_fails_in_test == 0u) {
            passed++;
            ut_puts("[       OK ] ");
        } else {
            failed++;
            ut_puts("[  FAILED  ] ");
        }
        ut_puts(cases[i].name);
        ut_puts("\n");
    }
    ut_puts("[==========] stack used ");
    ut_put_u64((uint64_t)board_stack_used());
    ut_puts(" of ");
    ut_put_u64((uint64_t)board_stack_size());
    ut_puts(" bytes\n");
    ut_put_u64((uint64_t)passed);
    ut_puts(" passed, ");
    ut_put_u64((uint64_t)failed);
    ut_puts(" failed\n");
    /* The exact count; board_exit() clamps it to 127 so it never collides with 236/238. */
    return (failed > (size_t)INT32_MAX) ? (int)INT32_MAX : (int)failed;
}
