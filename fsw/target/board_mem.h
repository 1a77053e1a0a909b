/*
 * board_mem.h — the four C library names the flight library may reference (spec 00 §4).
 * GCC emits calls to them for struct copies and clears even under -ffreestanding, and newlib
 * never enters the image, so the BSP provides them. Defining standard-library names is MISRA
 * C:2012 21.2 (required); the deviation is confined to these four, in fsw/target only.
 * `restrict` is left out of memcpy (MISRA 8.14); the type is still compatible with <string.h>.
 */
#ifndef FSW_TARGET_BOARD_MEM_H
#define FSW_TARGET_BOARD_MEM_H

#include <stddef.h>

/* cppcheck-suppress misra-c2012-21.2 ; the BSP is the C library for these four names */
void *memcpy(void *dst, const void *src, size_t n);
/* cppcheck-suppress misra-c2012-21.2 */
void *memmove(void *dst, const void *src, size_t n);
/* cppcheck-suppress misra-c2012-21.2 */
void *memset(void *dst, int c, size_t n);
/* cppcheck-suppress misra-c2012-21.2 */
int   memcmp(const void *a, const void *b, size_t n);

#endif /* FSW_TARGET_BOARD_MEM_H */
