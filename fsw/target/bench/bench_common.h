/*
 * bench_common.h — the shared pieces of the instruction-count images: fx_bench (fx_bench.c) and
 * every module's fsw/<m>/bench/<prefix or m>_bench.c, built by fsw/target/CMakeLists.txt and run
 * under QEMU -icount shift=3 by tools/bench (method: fx_bench.c, tools/bench/README.md).
 *
 *   bench_asm.S       the SysTick brackets, the NOP sleds, generic null twins (one `bx lr` each)
 *   bench_common.c    decimal console output and the calibration section
 *
 * Exact counts: bench_bracket5(fn, arg) returns exactly fn's instructions + 3 (five identical
 * calls between the SysTick loads), so kernel = bracket5(wrapper) - bracket5(twin) + 1 when the
 * twin is the wrapper with the kernel replaced by a null function of the same prototype.
 * bench_bracket1 (one call) gives raw ticks t: 5 t = fn + 3 within +-4 instructions.
 */
#ifndef FSW_TARGET_BENCH_COMMON_H
#define FSW_TARGET_BENCH_COMMON_H

#include <stdint.h>

typedef void (*bench_fn_t)(uint32_t sample);

/* bench_asm.S */
uint32_t bench_bracket5(bench_fn_t fn, uint32_t sample);
uint32_t bench_bracket1(bench_fn_t fn, uint32_t sample);
void bench_sled_0(uint32_t sample);
void bench_sled_1(uint32_t sample);
void bench_sled_2(uint32_t sample);
void bench_sled_3(uint32_t sample);
void bench_sled_4(uint32_t sample);
void bench_sled_5(uint32_t sample);
void bench_sled_7(uint32_t sample);
void bench_sled_100(uint32_t sample);
void bench_sled_1000(uint32_t sample);
void bench_sled_10000(uint32_t sample);
void bench_sled_50000(uint32_t sample);
/* The generic null twins bench_null_0 .. bench_null_3 are not declared here: a module bench
   declares each one it uses with the prototype of the function it stands in for. */

/* bench_common.c: console output, no libc */
void bench_put_u32(uint32_t v);
void bench_put_i32(int32_t v);
void bench_put_kv(const char *key, uint32_t a, uint32_t b);   /* "<key> <a> <b>\n" */

/* Calibration section (parsed by tools/bench):
 *   cal <N> <phase> <value>   bench_bracket5 around an N-NOP sled after a 0..4-NOP phase shift:
 *                             value must equal N + 4 at every phase
 *   tick <N> <ticks>          bench_bracket1 around an N-NOP sled, N = 0, 10000, 50000: ticks ~ N / 5 */
void bench_calibrate(void);

#endif /* FSW_TARGET_BENCH_COMMON_H */
