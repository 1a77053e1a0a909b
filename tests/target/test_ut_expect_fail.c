/*
 * test_ut_expect_fail.c — a group with deliberate failures. tests/target/CMakeLists.txt runs
 * it through expect_run.cmake and requires exit status 2, the report lines of each failed
 * check (file:line, expression, both values) and "1 passed, 2 failed".
 */
#include "ut.h"

UT_TEST(passes)
{
    UT_EQ(1, 1);
}

UT_TEST(fatal_check_ends_the_body)
{
    UT_EQ(2 + 2, 5);
    ut_puts("must not run: the fatal check returns\n");
}

UT_TEST(nonfatal_checks_carry_on)
{
    UT_CHECK_EQ(INT64_MIN, 0);
    UT_CHECK_UEQ(UINT64_MAX, 0u);
    UT_CHECK_LE(5, -5);
    UT_CHECK(1 == 2);
    ut_puts("after 4 non-fatal failures: count ");
    ut_put_u64(ut_fail_count());
    ut_puts("\n");
}

UT_CASES(ut_fail_cases) = {
    UT_CASE(passes),
    UT_CASE(fatal_check_ends_the_body),
    UT_CASE(nonfatal_checks_carry_on),
};

int main(void)
{
    return UT_RUN("ut_expect_fail", ut_fail_cases);
}
