/*
 * fx_bench_asm.S — the null twins of fx_bench.c's kernels (the brackets and NOP sleds are
 * shared: bench_asm.S).
 */
    .syntax unified
    .thumb
    .text

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
