/*
 * test_ut_selftest.c — the target runner and the BSP services it relies on, tested on the
 * target itself: integer formatting, the check macros on edge values, the PRNG, the mem*
 * implementations, SysTick and the stack canary. Needs nothing from fsw/.
 */
#include "ut.h"
#include "ut_target.h"
#include "board.h"
#include "board_mem.h"
#include "uart_cmsdk.h"

static int ut_streq(const char *a, const char *b)
{
    size_t i = 0u;
    while ((a[i] != '\0') && (a[i] == b[i])) {
        i++;
    }
    return a[i] == b[i];
}

#define CHECK_FMT(fn, v, expect) do { char b_[UT_FMT_DEC_MAX]; size_t n_ = fn(b_, (v)); \
    UT_CHECK(ut_streq(b_, (expect))); UT_CHECK_EQ(n_, sizeof(expect) - 1u); \
    if (!ut_streq(b_, (expect))) { ut_puts("  got \""); ut_puts(b_); ut_puts("\"\n"); } } while (0)

UT_TEST(format_decimal)
{
    CHECK_FMT(ut_fmt_u64, 0u, "0");
    CHECK_FMT(ut_fmt_u64, 9u, "9");
    CHECK_FMT(ut_fmt_u64, 10u, "10");
    CHECK_FMT(ut_fmt_u64, 1000000007u, "1000000007");
    CHECK_FMT(ut_fmt_u64, UINT64_C(10000000000000000000), "10000000000000000000");
    CHECK_FMT(ut_fmt_u64, UINT64_MAX, "18446744073709551615");
    CHECK_FMT(ut_fmt_i64, 0, "0");
    CHECK_FMT(ut_fmt_i64, -1, "-1");
    CHECK_FMT(ut_fmt_i64, INT32_MIN, "-2147483648");
    CHECK_FMT(ut_fmt_i64, INT64_MAX, "9223372036854775807");
    CHECK_FMT(ut_fmt_i64, INT64_MIN, "-9223372036854775808");
    CHECK_FMT(ut_fmt_i64, INT64_MIN + 1, "-9223372036854775807");
}

UT_TEST(format_hex)
{
    CHECK_FMT(ut_fmt_u32hex, 0u, "0x00000000");
    CHECK_FMT(ut_fmt_u32hex, 0xDEADBEEFu, "0xdeadbeef");
    CHECK_FMT(ut_fmt_u32hex, UINT32_MAX, "0xffffffff");
}

UT_TEST(check_macros_pass_on_edges)
{
    UT_EQ(INT64_MIN, INT64_MIN);
    UT_UEQ(UINT64_MAX, UINT64_MAX);
    UT_LE(INT64_MIN, INT64_MAX);
    UT_LE(-1, 0);
    UT_TRUE(1 == 1);
    UT_CHECK_EQ(INT32_MIN, (int64_t)INT32_MIN);
    UT_EQ(ut_fail_count(), 0u);
}

UT_TEST(output_helpers)
{
    /* Visible in the log; formatting itself is checked above. */
    ut_puts("  i64 ");
    ut_put_i64(INT64_MIN);
    ut_puts(" u64 ");
    ut_put_u64(UINT64_MAX);
    ut_puts(" hex ");
    ut_put_u32hex(0x0123ABCDu);
    ut_puts("\n");
    UT_EQ(ut_fail_count(), 0u);
}

UT_TEST(prng_matches_reference)
{
    uint64_t s = 0u;
    /* splitmix64 from state 0: the published first outputs. */
    UT_UEQ(ut_rng_next(&s), UINT64_C(0xE220A8397B1DCDAF));
    UT_UEQ(ut_rng_next(&s), UINT64_C(0x6E789E6AA1B965F4));
}

UT_TEST(mem_functions)
{
    uint8_t a[40];
    uint8_t b[40];
    size_t i;
    size_t off;

    for (off = 0u; off < 4u; off++) {
        for (i = 0u; i < sizeof(a); i++) {
            a[i] = (uint8_t)(i + 1u);
            b[i] = 0u;
        }
        UT_TRUE(memcpy(&b[off], &a[1], 33u) == &b[off]);
        for (i = 0u; i < 33u; i++) {
            UT_EQ(b[off + i], a[1u + i]);
        }
        UT_EQ(b[off + 33u], 0);
        UT_EQ(memcmp(&b[off], &a[1], 33u), 0);
        b[off + 20u] = 0xFFu;
        UT_LE(1, memcmp(&b[off], &a[1], 33u));
        UT_LE(memcmp(&a[1], &b[off], 33u), -1);
        UT_TRUE(memset(&b[off], 0x5A, 29u) == &b[off]);
        for (i = 0u; i < 29u; i++) {
            UT_EQ(b[off + i], 0x5A);
        }
        UT_EQ(b[off + 29u], a[30]);
    }
    /* Overlapping moves in both directions. */
    for (i = 0u; i < sizeof(a); i++) {
        a[i] = (uint8_t)i;
    }
    (void)memmove(&a[3], &a[0], 30u);
    for (i = 0u; i < 30u; i++) {
        UT_EQ(a[3u + i], i);
    }
    for (i = 0u; i < sizeof(a); i++) {
        a[i] = (uint8_t)i;
    }
    (void)memmove(&a[0], &a[5], 30u);
    for (i = 0u; i < 30u; i++) {
        UT_EQ(a[i], i + 5u);
    }
    UT_EQ(memcmp(a, b, 0u), 0);
}

UT_TEST(systick_counts_down)
{
    /* Without -icount QEMU reloads SysTick from a host timer, so the first reads after reset
     * may all return 0: wait (bounded) for a change rather than timing a fixed loop. */
    uint32_t t0 = board_systick_read();
    uint32_t t1 = t0;
    uint32_t i;

    for (i = 0u; (i < 50000000u) && (t1 == t0); i++) {
        t1 = board_systick_read();
    }
    UT_TRUE(t1 != t0);
    UT_LE(1, board_systick_elapsed(t0, t1));
    UT_LE(board_systick_elapsed(t0, t1), 0x7FFFFF);   /* went down, not up */
    UT_UEQ(board_systick_elapsed(0x000005u, 0xFFFFFEu), 7u);   /* modular across reload */
}

UT_TEST(stack_canary_and_paint)
{
    UT_TRUE(board_stack_canary_ok());
    UT_LE(64, board_stack_used());
    UT_LE(board_stack_used(), board_stack_size() / 2u);
}

UT_TEST(uart_bauddiv)
{
    UT_UEQ(cmsdk_uart_bauddiv(25000000u, 115200u), 217u);
    UT_UEQ(cmsdk_uart_bauddiv(25000000u, 921600u), 27u);
    UT_UEQ(cmsdk_uart_bauddiv(25000000u, 25000000u), CMSDK_UART_BAUDDIV_MIN);
    UT_UEQ(cmsdk_uart_bauddiv(25000000u, 0u), CMSDK_UART_BAUDDIV_MIN);
}

UT_CASES(ut_selftest_cases) = {
    UT_CASE(format_decimal),
    UT_CASE(format_hex),
    UT_CASE(check_macros_pass_on_edges),
    UT_CASE(output_helpers),
    UT_CASE(prng_matches_reference),
    UT_CASE(mem_functions),
    UT_CASE(systick_counts_down),
    UT_CASE(stack_canary_and_paint),
    UT_CASE(uart_bauddiv),
};

int main(void)
{
    return UT_RUN("ut_selftest", ut_selftest_cases);
}
