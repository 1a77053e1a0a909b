/*
 * board_mem.c — memcpy, memmove, memset, memcmp.
 *
 * Built with -fno-tree-loop-distribute-patterns (see CMakeLists.txt): otherwise GCC turns these
 * very loops back into calls to themselves. Word copies are used when both pointers are
 * word-aligned, because fsw_step's struct copies fall inside the measured instruction budget.
 * The void * parameters are the standard interface, so converting them to byte and word
 * pointers is inherent (MISRA 11.5, advisory, suppressed line by line below).
 */
#include <stdbool.h>
#include <stdint.h>
#include "board_mem.h"
#include "board_internal.h"

/* may_alias: these words overlay objects of any type. */
typedef uint32_t __attribute__((may_alias)) board_word_t;

static bool board_aligned(const void *p)
{
    return (board_addr(p) & 3u) == 0u;
}

void *memcpy(void *dst, const void *src, size_t n)
{
    /* cppcheck-suppress misra-c2012-11.5 */
    unsigned char *d = (unsigned char *)dst;
    /* cppcheck-suppress misra-c2012-11.5 */
    const unsigned char *s = (const unsigned char *)src;
    size_t i = 0u;

    if (board_aligned(dst) && board_aligned(src)) {
        /* cppcheck-suppress misra-c2012-11.5 */
        board_word_t *dw = (board_word_t *)dst;
        /* cppcheck-suppress misra-c2012-11.5 */
        const board_word_t *sw = (const board_word_t *)src;
        size_t nw = n / 4u;
        size_t n4 = nw - (nw % 4u);
        size_t k;
        /* Four words per pass: the loop test and increment cost as much as a word's load and
           store, and telemetry blocks of a few hundred bytes are copied every step. */
        for (k = 0u; k < n4; k += 4u) {
            dw[k] = sw[k];
            dw[k + 1u] = sw[k + 1u];
            dw[k + 2u] = sw[k + 2u];
            dw[k + 3u] = sw[k + 3u];
        }
        for (k = n4; k < nw; k++) {
            dw[k] = sw[k];
        }
        i = nw * 4u;
    }
    for (; i < n; i++) {
        d[i] = s[i];
    }
    return dst;
}

void *memmove(void *dst, const void *src, size_t n)
{
    /* cppcheck-suppress misra-c2012-11.5 */
    unsigned char *d = (unsigned char *)dst;
    /* cppcheck-suppress misra-c2012-11.5 */
    const unsigned char *s = (const unsigned char *)src;
    size_t i;

    /* Integer compare: the buffers may be unrelated objects (MISRA 18.3 forbids the pointer one). */
    if (board_addr(dst) <= board_addr(src)) {
        for (i = 0u; i < n; i++) {
            d[i] = s[i];
        }
    } else {
        for (i = n; i > 0u; i--) {
            d[i - 1u] = s[i - 1u];
        }
    }
    return dst;
}

void *memset(void *dst, int c, size_t n)
{
    /* cppcheck-suppress misra-c2012-11.5 */
    unsigned char *d = (unsigned char *)dst;
    unsigned char b = (unsigned char)((unsigned int)c & 0xFFu);
    size_t i = 0u;

    if (board_aligned(dst)) {
        /* cppcheck-suppress misra-c2012-11.5 */
        board_word_t *dw = (board_word_t *)dst;
        board_word_t w = (board_word_t)b * 0x01010101u;
        size_t nw = n / 4u;
        for (i = 0u; i < nw; i++) {
            dw[i] = w;
        }
        i = nw * 4u;
    }
    for (; i < n; i++) {
        d[i] = b;
    }
    return dst;
}

int memcmp(const void *a, const void *b, size_t n)
{
    /* cppcheck-suppress misra-c2012-11.5 */
    const unsigned char *pa = (const unsigned char *)a;
    /* cppcheck-suppress misra-c2012-11.5 */
    const unsigned char *pb = (const unsigned char *)b;
    int r = 0;
    size_t i;

    for (i = 0u; (i < n) && (r == 0); i++) {
        r = (int)pa[i] - (int)pb[i];
    }
    return r;
}
