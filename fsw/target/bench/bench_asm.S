/*
 * bench_asm.S — the SysTick brackets, NOP sleds and generic null functions shared by every
 * instruction-count image (fx_bench and each module's fsw/<m>/bench/<m>_bench.c; method in
 * fx_bench.c and tools/bench/README.md). Hand-written because the method depends on knowing
 * exactly which instructions execute between the two SysTick loads; compiled code could add or
 * move instructions there. Prototypes: bench_common.h.
 */
    .syntax unified
    .thumb
    .text

/*
 * uint32_t bench_bracket5(bench_fn_t fn, uint32_t arg)
 * SysTick ticks over: 5 x { mov r0, arg; blx fn } + 4 NOPs, i.e. 5 * (fn + 3) instructions
 * counted from one load to the other, so the result is exactly fn's instructions + 3.
 */
    .global bench_bracket5
    .type bench_bracket5, %function
    .thumb_func
bench_bracket5:
    push {r4, r5, r6, r7, lr}
    mov r6, r0
    mov r7, r1
    movw r5, #0xE018            /* SYST_CVR */
    movt r5, #0xE000
    ldr r4, [r5]
    mov r0, r7
    blx r6
    mov r0, r7
    blx r6
    mov r0, r7
    blx r6
    mov r0, r7
    blx r6
    mov r0, r7
    blx r6
    nop
    nop
    nop
    nop
    ldr r1, [r5]
    subs r0, r4, r1
    bic r0, r0, #0xFF000000     /* SysTick is 24 bits and counts down */
    pop {r4, r5, r6, r7, pc}
    .size bench_bracket5, . - bench_bracket5

/* uint32_t bench_bracket1(bench_fn_t fn, uint32_t arg): one call, raw ticks. */
    .global bench_bracket1
    .type bench_bracket1, %function
    .thumb_func
bench_bracket1:
    push {r4, r5, r6, r7, lr}
    mov r6, r0
    mov r7, r1
    movw r5, #0xE018
    movt r5, #0xE000
    ldr r4, [r5]
    mov r0, r7
    blx r6
    ldr r1, [r5]
    subs r0, r4, r1
    bic r0, r0, #0xFF000000
    pop {r4, r5, r6, r7, pc}
    .size bench_bracket1, . - bench_bracket1

/* void bench_sled_<n>(uint32_t): n NOPs and a return, n + 1 instructions. */
    .macro SLED n
    .global bench_sled_\n
    .type bench_sled_\n, %function
    .thumb_func
bench_sled_\n:
    .rept \n
    nop
    .endr
    bx lr
    .size bench_sled_\n, . - bench_sled_\n
    .endm

    SLED 0
    SLED 1
    SLED 2
    SLED 3
    SLED 4
    SLED 5
    SLED 7
    SLED 100
    SLED 1000
    SLED 10000
    SLED 50000

/*
 * Generic null twins for module benches: one `bx lr` each. A module bench declares the ones it
 * uses with the prototype of the function each stands in for (bench_common.h), calls it from a
 * twin of its wrapper, and gets kernel = w(kernel) - w(twin) + 1 (fx_bench.c). Whatever is in
 * r0 is "returned". tools/bench checks that every bench_null_* is a single 16-bit instruction.
 */
    .macro NULLFN name
    .global \name
    .type \name, %function
    .thumb_func
\name:
    bx lr
    .size \name, . - \name
    .endm

    NULLFN bench_null_0
    NULLFN bench_null_1
    NULLFN bench_null_2
    NULLFN bench_null_3
