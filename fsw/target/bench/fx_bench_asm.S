/*
 * fx_bench_asm.S — the SysTick brackets and NOP sleds of fx_bench.c. Hand-written because the
 * method depends on knowing exactly which instructions execute between the two SysTick loads
 * (see fx_bench.c); compiled code could add or move instructions there.
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
 * Null twins of the kernels: one `bx lr` each, called with the kernel's own prototype (see
 * fx_bench.c). Whatever is in r0 is "returned"; the wrappers only store it to a sink.
 */
    .macro NULLFN name
    .global \name
    .type \name, %function
    .thumb_func
\name:
    bx lr
    .size \name, . - \name
    .endm

    NULLFN bench_null_muldiv
    NULLFN bench_null_sqrt
    NULLFN bench_null_isqrt
    NULLFN bench_null_norm3
    NULLFN bench_null_sincos
    NULLFN bench_null_atan2
    NULLFN bench_null_dot
    NULLFN bench_null_matvec
    NULLFN bench_null_matmul
    NULLFN bench_null_solve
    NULLFN bench_null_fsolve
    NULLFN bench_null_crc
    NULLFN bench_null_obs
    NULLFN bench_null_imp_solve
    NULLFN bench_null_imp_attempt
    NULLFN bench_null_imp_trig
    NULLFN bench_null_imp_round
    NULLFN bench_null_imp_vec
    NULLFN bench_null_imp_step
