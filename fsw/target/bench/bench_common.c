/*
 * bench_common.c — console output and calibration shared by the instruction-count images
 * (bench_common.h).
 */
#include <stdint.h>
#include <stddef.h>
#include "board.h"
#include "bench_common.h"

#define BENCH_PHASES 5u

void bench_put_u32(uint32_t v)
{
    static const char digits[10] = { '0', '1', '2', '3', '4', '5', '6', '7', '8', '9' };
    char buf[11];
    uint32_t i = 10u;
    uint32_t r = v;

    buf[10] = '\0';
    do {
        i--;
        buf[i] = digits[r % 10u];
        r /= 10u;
    } while ((r != 0u) && (i > 0u));
    board_console_write(&buf[i]);
}

void bench_put_i32(int32_t v)
{
    if (v < 0) {
        board_console_write("-");
        bench_put_u32(0u - (uint32_t)v);
    } else {
        bench_put_u32((uint32_t)v);
    }
}

void bench_put_kv(const char *key, uint32_t a, uint32_t b)
{
    board_console_write(key);
    board_console_write(" ");
    bench_put_u32(a);
    board_console_write(" ");
    bench_put_u32(b);
    board_console_write("\n");
}

typedef struct {
    bench_fn_t fn;
    uint32_t n;
} bench_sled_t;

void bench_calibrate(void)
{
    static const bench_sled_t sleds[] = {
        { bench_sled_0, 0u }, { bench_sled_1, 1u }, { bench_sled_2, 2u }, { bench_sled_3, 3u },
        { bench_sled_4, 4u }, { bench_sled_5, 5u }, { bench_sled_7, 7u }, { bench_sled_100, 100u },
        { bench_sled_1000, 1000u },
    };
    /* Run just before a bracket, they shift the tick phase by 0..4 instructions. */
    static const bench_fn_t phase[BENCH_PHASES] = {
        bench_sled_0, bench_sled_1, bench_sled_2, bench_sled_3, bench_sled_4
    };
    size_t i;
    uint32_t ph;

    for (i = 0u; i < (sizeof(sleds) / sizeof(sleds[0])); i++) {
        for (ph = 0u; ph < BENCH_PHASES; ph++) {
            bench_fn_t fn = sleds[i].fn;
            uint32_t v;
            phase[ph](0u);
            v = bench_bracket5(fn, 0u);
            board_console_write("cal ");
            bench_put_u32(sleds[i].n);
            board_console_write(" ");
            bench_put_u32(ph);
            board_console_write(" ");
            bench_put_u32(v);
            board_console_write("\n");
        }
    }
    for (ph = 0u; ph < BENCH_PHASES; ph++) {
        uint32_t t0;
        uint32_t t1;
        uint32_t t2;
        phase[ph](0u);
        t0 = bench_bracket1(bench_sled_0, 0u);
        t1 = bench_bracket1(bench_sled_10000, 0u);
        t2 = bench_bracket1(bench_sled_50000, 0u);
        bench_put_kv("tick", 0u, t0);
        bench_put_kv("tick", 10000u, t1);
        bench_put_kv("tick", 50000u, t2);
    }
}
