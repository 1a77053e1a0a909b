/*
 * gv_print.h — the digest line of every golden replay and of fx_digest.c,
 *     digest <name><suffix> <records> <crc>
 * which tests/golden/digest.cmake keeps and compares. Separate from gv_digest.h because the
 * host generator includes that one and has no ut.h.
 */
#ifndef TESTS_GOLDEN_GV_PRINT_H
#define TESTS_GOLDEN_GV_PRINT_H

#include "ut.h"
#include "gv_digest.h"

static inline void gv_dg_print(const char *name, const char *suffix, const gv_dg_t *d)
{
    ut_puts("digest ");
    ut_puts(name);
    ut_puts(suffix);
    ut_puts(" ");
    ut_put_u64(d->n);
    ut_puts(" ");
    ut_put_u32hex(d->crc);
    ut_puts("\n");
}

#endif /* TESTS_GOLDEN_GV_PRINT_H */
