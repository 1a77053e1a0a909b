/*
 * Helpers of the impulse-table tests (test_imp_table, test_imp_table_image_host,
 * test_imp_mission): a field-by-field comparison of two imp_params_t, and a setter that writes one
 * descriptor field (by its index in IMP_TBL_DESC, see fsw/impulse/imp_table.c) through the
 * struct member it names, so a test that encodes the result proves that the encoder puts each
 * member where the descriptor checks it.
 */
#ifndef TESTS_IMPULSE_IMP_TBL_UTIL_H
#define TESTS_IMPULSE_IMP_TBL_UTIL_H

#include <stdint.h>
#include "imp.h"

#define IMP_TBL_N_FIELDS 56u   /* descriptor entries of layout 1 */

/* Number of imp_params_t fields (array entries counted one by one) that differ; with
   report != 0 each difference is recorded as a test failure naming the field. */
uint32_t imp_params_diff(const imp_params_t *a, const imp_params_t *b, int report);
/* Writes v into the member of descriptor field idx (0..55); returns 0 when idx is unknown. The
   caller keeps v within the member's C type (tests use imp_field_fits). */
int imp_field_set(imp_params_t *p, uint32_t idx, int64_t v);
/* True when v is representable in the member of field idx (u8, u32 or i32). */
int imp_field_fits(uint32_t idx, int64_t v);

#endif
