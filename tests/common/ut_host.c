/* Host side of ut.h: CMocka runs the cases; this file prints values and fails tests. */
#include "ut.h"

#include <inttypes.h>
#include <stdio.h>

static unsigned ut_fails_in_test;   /* harness state, host test binaries only */

void ut_puts(const char *s) { (void)fputs(s, stdout); }
void ut_put_u32hex(uint32_t v) { (void)printf("0x%08" PRIx32, v); }
void ut_put_i64(int64_t v) { (void)printf("%" PRId64, v); }
void ut_put_u64(uint64_t v) { (void)printf("%" PRIu64, v); }

void ut_record_fail(const char *file, int line, const char *expr, int64_t a, int64_t b)
{
    ut_fails_in_test++;
    print_error("%s:%d: check failed: %s (%" PRId64 " vs %" PRId64 ")\n", file, line, expr, a, b);
}

void ut_record_failu(const char *file, int line, const char *expr, uint64_t a, uint64_t b)
{
    ut_fails_in_test++;
    print_error("%s:%d: check failed: %s (%" PRIu64 " vs %" PRIu64 ")\n", file, line, expr, a, b);
}

unsigned ut_fail_count(void) { return ut_fails_in_test; }

void ut_begin_test(void) { ut_fails_in_test = 0u; }

void ut_end_test(void)
{
    if (ut_fails_in_test != 0u) {
        fail_msg("%u check(s) failed", ut_fails_in_test);
    }
}
