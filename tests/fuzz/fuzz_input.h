/*
 * fuzz_input.h — what every fuzz harness here shares: the invariant check (a violation traps,
 * so libFuzzer and the GCC replay both report it as a crash) and the input reader (every byte
 * string is a valid input: reads past the end give 0).
 */
#ifndef TESTS_FUZZ_INPUT_H
#define TESTS_FUZZ_INPUT_H

#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#if defined(__GNUC__) || defined(__clang__)
#define FZ_TRAP() __builtin_trap()
#else
#define FZ_TRAP() abort()
#endif
#define FZ_CHECK(cond) \
    do { \
        if (!(cond)) { \
            FZ_TRAP(); \
        } \
    } while (0)

typedef struct {
    const uint8_t *d;
    size_t n;
    size_t pos;
} fz_in_t;

static inline uint32_t fz_u8(fz_in_t *in)
{
    uint32_t v = 0u;
    if (in->pos < in->n) {
        v = in->d[in->pos];
        in->pos++;
    }
    return v;
}

static inline uint32_t fz_u16(fz_in_t *in)
{
    uint32_t lo = fz_u8(in);
    return lo | (fz_u8(in) << 8);
}

#endif /* TESTS_FUZZ_INPUT_H */
