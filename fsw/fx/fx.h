/*
 * fx.h — fixed-point core of the flight software (spec 00-platform §1).
 *
 * Conventions (see fsw/fx/README.md for the full contract and measured accuracy):
 *  - Storage int32_t, intermediates int64_t; operands are widened before a product.
 *  - qN: signed int32 with N fraction bits, 0 <= N <= FX_Q_MAX (40). Angles that wrap are
 *    BAM (uint32_t, 2^32 = one turn).
 *  - One rounding rule everywhere: round half away from zero, so rnd(-x) == -rnd(x).
 *  - Every operation that can clip or fail ORs bits into a caller-owned sticky status word
 *    (fx_status_t). Results are always defined values, never in-band sentinels.
 *  - Pure functions: no globals, no statics holding state, no I/O, bounded loops.
 */
#ifndef FSW_FX_H
#define FSW_FX_H

#include <stdint.h>
#include <stdbool.h>
#include <stddef.h>
#include "fx_rc.h"

typedef uint32_t fx_status_t;

#define FX_ST_SAT_HI    (1u << 0)  /* result clipped to INT32_MAX (UINT32_MAX) */
#define FX_ST_SAT_LO    (1u << 1)  /* result clipped to INT32_MIN (0 for unsigned) */
#define FX_ST_DIV0      (1u << 2)  /* divisor 0; result +-INT32_MAX with the dividend's sign, 0 for 0/0 */
#define FX_ST_DOMAIN    (1u << 3)  /* sqrt of a negative value, atan2(0,0); result 0 */
#define FX_ST_ACC_OVF   (1u << 4)  /* 64-bit accumulator overflow in a kernel; result saturated */
#define FX_ST_SINGULAR  (1u << 5)  /* |pivot| < pivot_min in fx_solve; x zeroed */
#define FX_ST_CONV      (1u << 6)  /* narrowing or format conversion out of range */
#define FX_ST_ARG       (1u << 7)  /* dimension > FX_NMAX, or a format/shift out of range */
#define FX_ST_MASK      0xFFu      /* bits 0..7 of a module health word */

#define FX_Q_MAX   40u   /* largest legal number of fraction bits */
#define FX_NMAX    8u    /* largest vector/matrix dimension of the kernels */
#define FX_SOLVE_NMAX 4u /* largest system fx_solve accepts */

/*
 * Compile-time assertion usable at file scope under C99 -Wpedantic -Werror and the
 * cppcheck misra addon (spec 00 §1.2). `name` must be unique in the translation unit.
 */
#define FX_STATIC_ASSERT(name, c) extern char (name)[(c) ? 1 : -1]

/*
 * Q constant from an exact rational num/den (den > 0), rounded half away from zero, as an
 * integer constant expression: FX_Q_RAT(1, 3, 30) == 357913941 (0.3333 in q30).
 * Floating literals are forbidden in fsw/, so real values are written as ratios; tools that
 * emit tables write the integer and the real value in a comment instead.
 * The caller guards the range with FX_STATIC_ASSERT(.., FX_Q_RAT_FITS(num, den, q)).
 * num * 2^q must fit int64: |num| < 2^(63-q).
 */
/* 2^q as int64 (0 <= q <= 62), shifted on an unsigned operand (MISRA 10.1). The shift of two
   constants is a constant expression, not a composite one, so rule 10.8 does not apply to its
   cast; the inner (uint64_t) keeps cppcheck's misra addon, which does not tell the two apart,
   from reporting it. */
#define FX_POW2_64_(q) ((int64_t)(uint64_t)(UINT64_C(1) << (uint32_t)(q)))
#define FX_Q_RAT64_(num, den, q) \
    ((((num) < 0) ? -1 : 1) * \
     (((((num) < 0) ? -(int64_t)(num) : (int64_t)(num)) * FX_POW2_64_(q) + ((int64_t)(den) / 2)) / (int64_t)(den)))
#define FX_Q_RAT_FITS(num, den, q) \
    ((FX_Q_RAT64_(num, den, q) <= (int64_t)INT32_MAX) && (FX_Q_RAT64_(num, den, q) >= (int64_t)INT32_MIN))
#define FX_Q_RAT(num, den, q) ((int32_t)FX_Q_RAT64_(num, den, q))
/* Integer value v in qN (v * 2^q), for small exact constants such as 1.0 or -2.0. */
#define FX_Q_INT(v, q) FX_Q_RAT((v), 1, (q))

/* ---------------------------------------------------------------- saturation, conversion */
int32_t  fx_sat32(int64_t v, fx_status_t *st);               /* clamp to int32, SAT_HI/SAT_LO */
int16_t  fx_sat16(int32_t v, fx_status_t *st);               /* clamp to int16, SAT_HI/SAT_LO */
uint32_t fx_satu32(int64_t v, fx_status_t *st);              /* clamp to [0, UINT32_MAX] */
int32_t  fx_add_sat(int32_t a, int32_t b, fx_status_t *st);
int32_t  fx_sub_sat(int32_t a, int32_t b, fx_status_t *st);
int32_t  fx_neg(int32_t a, fx_status_t *st);                 /* -INT32_MIN -> INT32_MAX, SAT_HI */
int32_t  fx_abs(int32_t a, fx_status_t *st);                 /* |INT32_MIN| -> INT32_MAX, SAT_HI */
uint32_t fx_uabs(int32_t a);                                 /* |a| exactly, as unsigned */
int64_t  fx_add64_sat(int64_t a, int64_t b, fx_status_t *st); /* ACC_OVF on overflow */

/* Left shift with saturation; n in [0, 31] else ARG and 0. Never shifts a negative value. */
int32_t  fx_shl_sat(int32_t a, uint32_t n, fx_status_t *st);
/* Rounding right shift (half away from zero) of an int64; n in [0, 63] else ARG and 0. */
int64_t  fx_shr_rnd64(int64_t p, uint32_t n, fx_status_t *st);
/* Rounding right shift of int64 to a saturated int32: fx_sat32(fx_shr_rnd64(p, n)). */
int32_t  fx_rshift_sat(int64_t p, uint32_t n, fx_status_t *st);
/* Rounding right shift of an int32; n in [0, 31] else ARG. */
int32_t  fx_shr_rnd(int32_t a, uint32_t n, fx_status_t *st);
/* Re-express a in another Q: rounds when dropping fraction bits, saturates when adding. */
int32_t  fx_convert(int32_t a, uint32_t q_from, uint32_t q_to, fx_status_t *st);
/* Scale a 64-bit value with q_from fraction bits to q_to (round or saturate), result int32. */
int32_t  fx_convert64(int64_t a, uint32_t q_from, uint32_t q_to, fx_status_t *st);

/*
 * Sensor counts -> Q value: v = rnd(count * scale_m / 2^scale_sh) - bias, where
 * scale_m / 2^scale_sh is one count's LSB expressed in the destination Q (e.g. a 2^-20 rad/s
 * count into q29: scale_m = 512, scale_sh = 0). scale_sh in [0, 62].
 */
int32_t  fx_from_count(int32_t count, int32_t scale_m, uint32_t scale_sh, int32_t bias,
                       fx_status_t *st);
/*
 * Q value -> actuator counts: c = rnd(v * inv_m / 2^inv_sh), clamped to [cmin, cmax].
 * A clamp sets SAT_HI/SAT_LO; callers that clamp on purpose (actuator limits are designated
 * saturating points) pass their own scratch status word.
 */
int32_t  fx_to_count(int32_t v, int32_t inv_m, uint32_t inv_sh, int32_t cmin, int32_t cmax,
                     fx_status_t *st);

/* 2^n as int64 for n in [0, 62] (built by an unsigned shift); ARG and 0 otherwise. */
int64_t  fx_pow2_64(uint32_t n, fx_status_t *st);

/* Saturating counter increment: counters never wrap. */
void     fx_cnt_inc(uint32_t *c);

/* ---------------------------------------------------------------- multiply, divide */
/* a (qa) * b (qb) -> qr, one rounding, saturating. Formats in [0, 40] else ARG and 0. */
int32_t  fx_mul(int32_t a, uint32_t qa, int32_t b, uint32_t qb, uint32_t qr, fx_status_t *st);
/* a (qa) / b (qb) -> qr, correctly rounded; b == 0 -> DIV0. Formats in [0, 40] else ARG. */
int32_t  fx_div(int32_t a, uint32_t qa, int32_t b, uint32_t qb, uint32_t qr, fx_status_t *st);
/* round(num / den) half away from zero on unsigned magnitudes; den > 0 (den == 0 -> UINT64_MAX). */
uint64_t fx_udiv_rnd64(uint64_t num, uint64_t den);
/* round(a b / 2^n) half away from zero for an int64 a; n in [0, 62] else ARG and 0; results beyond
 * int64 saturate (SAT_HI / SAT_LO). Exact for every a, b. */
int64_t  fx_mul64_shr(int64_t a, int32_t b, uint32_t n, fx_status_t *st);
/* round(a 2^k / d) half away from zero, d > 0; |a| 2^k >= 2^63 saturates (SAT_HI / SAT_LO),
 * d == 0 -> DIV0 and 0, k > 62 -> ARG and 0. */
int64_t  fx_div64_shl(int64_t a, uint32_t k, uint64_t d, fx_status_t *st);

/*
 * Reciprocal for repeated division by one divisor: made with one 64/32 divide, then each
 * division is multiplies plus an exact integer fix-up, so results are correctly rounded.
 * 1/d = m * 2^(sh - 60) with d as an integer, |d| << sh in [2^30, 2^31], |m| in [2^29, 2^30]
 * (|d| << sh = 2^31 only at d = INT32_MIN, where m = -2^29; d = +-INT32_MAX also gives |m| = 2^29).
 */
typedef struct {
    int32_t  d;    /* the divisor, in its own Q (integer LSBs) */
    int32_t  m;    /* reciprocal mantissa */
    uint32_t sh;   /* normalisation shift, [0, 30] */
} fx_recip_t;
/* d == 0 -> DIV0; later divisions then behave as fx_div by zero. */
void     fx_recip_init(fx_recip_t *r, int32_t d, fx_status_t *st);
/* round(a * 2^k / d), half away from zero, saturated to int32; k in [0, 62] (ARG otherwise).
 * With a in qa and d in qd the result is in qa - qd + k. */
int32_t  fx_recip_div(int64_t a, const fx_recip_t *r, uint32_t k, fx_status_t *st);

/* ---------------------------------------------------------------- roots */
/* Exact floor square root: r*r <= x < (r+1)*(r+1). 32 fixed iterations. */
uint32_t fx_isqrt64(uint64_t x);
/* sqrt(a) with a in qa, result in qr, <= 0.5 LSB. 2*qr - qa must lie in [0, 33] else ARG.
 * a < 0 -> DOMAIN and 0. Results above INT32_MAX saturate (SAT_HI). */
int32_t  fx_sqrt(int32_t a, uint32_t qa, uint32_t qr, fx_status_t *st);
/* Euclidean norm of a 3-vector, result in the vector's own Q, <= 0.5 LSB; SAT_HI above range. */
int32_t  fx_norm3(const int32_t v[3], fx_status_t *st);

/* ---------------------------------------------------------------- trigonometry */
/* sin and cos of a BAM angle in q30; |err| <= 2^-28; s(-a) == -s(a), c(-a) == c(a) exactly. */
void     fx_sincos(uint32_t a_bam, int32_t *s_q30, int32_t *c_q30);
/* Angle of (x, y) as BAM (y, x in the same Q). |err| <= 2^-27 rad. (0,0) -> DOMAIN and 0. */
uint32_t fx_atan2_bam(int32_t y, int32_t x, fx_status_t *st);
/* BAM <-> radians. Signed BAM interpretation, (-pi, pi] rad in q29. */
int32_t  fx_bam_to_rad_q29(uint32_t a_bam);
uint32_t fx_rad_q29_to_bam(int32_t a_rad_q29);

/* ---------------------------------------------------------------- vectors and matrices */
/*
 * All kernels accumulate exact int64 products with overflow-checked adds and round once.
 * Result Q is qr; the accumulator has qa + qb fraction bits, and qa + qb - qr must lie in
 * [0, 62] (ARG otherwise). An accumulator overflow sets ACC_OVF and saturates the result.
 * Matrices are row-major; dimensions are 1..FX_NMAX (ARG and zeroed outputs otherwise).
 * Outputs must not alias inputs.
 */
int32_t  fx_dot(const int32_t *a, uint32_t qa, const int32_t *b, uint32_t qb, uint32_t n,
                uint32_t qr, fx_status_t *st);
void     fx_matvec(const int32_t *m, uint32_t qm, const int32_t *x, uint32_t qx,
                   uint32_t rows, uint32_t cols, int32_t *y, uint32_t qy, fx_status_t *st);
void     fx_matmul(const int32_t *a, uint32_t qa, const int32_t *b, uint32_t qb,
                   uint32_t n, uint32_t k, uint32_t m, int32_t *c, uint32_t qc, fx_status_t *st);
/* Exact int64 sum of a[i] * b[i], i < n (n <= FX_NMAX); on overflow ACC_OVF and the int64
 * extreme in that direction. For callers that align several sums and round once. */
int64_t  fx_dot_acc(const int32_t *a, const int32_t *b, uint32_t n, fx_status_t *st);
/* round(sum_{i<n} a[i] b[i*sb] + w v) by `shift` (<= 62) to a saturated int32, one rounding: a dot
 * product with one wide term, for a column whose values outgrow int32 while its products still fit
 * the exact int64 sum (obs: the regressor column of F_s). Overflow as in fx_dot: ACC_OVF and the
 * int32 extreme. Bit-identical to fx_dot over n + 1 terms whenever w fits int32. */
int32_t  fx_dot_wide(const int32_t *a, const int32_t *b, uint32_t sb, uint32_t n, int64_t w, int32_t v,
                     uint32_t shift, fx_status_t *st);
/* v * 2^n exactly (n <= 62); ACC_OVF and the int64 extreme if it does not fit. */
int64_t  fx_shl64_chk(int64_t v, uint32_t n, fx_status_t *st);
/* y = a + b, y = a - b element-wise (same Q), saturating. */
void     fx_vadd(const int32_t *a, const int32_t *b, uint32_t n, int32_t *y, fx_status_t *st);
void     fx_vsub(const int32_t *a, const int32_t *b, uint32_t n, int32_t *y, fx_status_t *st);

/* Caller-owned workspace of fx_solve (no hidden state). A and b are worked on as int64, each scaled
   by a power of two so that its largest entry has 31 bits, plus 24 guard bits (fsw/fx/README.md). */
typedef struct {
    int64_t a[FX_SOLVE_NMAX * FX_SOLVE_NMAX];  /* eliminated matrix U (upper triangle), q(qa + sa) */
    int64_t b[FX_SOLVE_NMAX];                  /* eliminated right-hand side, q(qb + sb) */
    fx_recip_t rec[FX_SOLVE_NMAX];             /* pivot k rounded to qa (rec[k].d) and its reciprocal */
    int32_t pm[FX_SOLVE_NMAX];                 /* round(2^60 / P_k), P_k: the 31 leading bits of pivot k */
    int32_t pe[FX_SOLVE_NMAX];                 /* |pivot k| (in units of q(qa + sa)) ~= P_k 2^pe[k] */
    uint8_t perm[FX_SOLVE_NMAX];               /* perm[k]: original row used at step k */
    uint8_t sa;                                /* fraction bits of a[] beyond qa */
    uint8_t sb;                                /* fraction bits of b[] beyond qb */
} fx_solve_ws_t;

/*
 * Solve A x = b (n <= FX_SOLVE_NMAX) by Gaussian elimination with partial pivoting; one
 * reciprocal (one divide) per pivot, then multiplies. A in qa, b in qb, x in qx; qb <= qa + qx.
 * A and b are each scaled exactly by a power of two to 31 significant bits and carried in int64
 * with 24 guard bits; the multipliers are exact to 2^-58 (a second term from the exact residual),
 * and each x_i is correctly rounded for its triangular system from an exact 128-bit numerator.
 * Headroom: partial pivoting bounds growth by 2^(n-1); an eliminated entry that leaves int32 in
 * qa (A without n-1 spare bits) sets SAT_HI/SAT_LO (the solve itself stays exact). |pivot| <
 * pivot_min (qa, exact pivot) or a pivot below 1/2 LSB of qa -> SINGULAR and x zeroed.
 * Error bound (derived in fsw/fx/README.md, tested for any |x| against an exact reference):
 * |x - x_exact|inf <= ((2^n - 1)/2 + 2^-10) kappa_inf(A) <= 2 n kappa_inf(A) LSB of qx.
 */
void     fx_solve(fx_solve_ws_t *ws, const int32_t *a, uint32_t qa, const int32_t *b, uint32_t qb,
                  uint32_t n, int32_t *x, uint32_t qx, int32_t pivot_min, fx_status_t *st);

/* Caller-owned workspace of fx_solve_fast: the eliminated system kept in int32 in the caller's
   own formats (no scaling, no guard bits), so its elimination is one 32 x 32 product per update. */
typedef struct {
    int32_t a[FX_SOLVE_NMAX * FX_SOLVE_NMAX];  /* eliminated matrix U (upper triangle), qa */
    int32_t b[FX_SOLVE_NMAX];                  /* eliminated right-hand side, qb */
    fx_recip_t rec[FX_SOLVE_NMAX];             /* pivot k (rec[k].d, qa) and its reciprocal */
    uint8_t perm[FX_SOLVE_NMAX];               /* perm[k]: original row used at step k */
} fx_solve_fast_ws_t;

/*
 * Fast solve for iterations that only need a step of small *relative* error (Newton steps): the
 * same arguments, argument checks, pivoting (ties to the lowest row), SINGULAR rule and x zeroing
 * as fx_solve, but its own int32 elimination: the multiplier l = a_ik / a_kk is taken in q30 from
 * the pivot's reciprocal (|l^ - l| <= 1.5 2^-30), every updated a_ij and b_i is rounded to one
 * LSB of qa / qb, and x_i = s_i / u_ii is one product with the reciprocal and one rounding
 * (relative error <= 1.5 2^-30 + 2^-61, plus 1/2 LSB). An updated entry or an x_i outside int32,
 * or an int64 overflow of the back substitution's sum, raises SAT_HI/SAT_LO or ACC_OVF.
 * Error bound (derived in fsw/fx/README.md, "fx_solve_fast"; tested over mixed scales), with no
 * status flag raised, x the returned solution, N = |A|inf in LSB of qa, e = qa + qx - qb and
 * kappa = kappa_inf(A):
 *   |x - x_exact|inf <= kappa (2 n (1 + 2^-27 |x|inf) + (n (n-1)/4 |x|inf + (n-1)/2 2^e + n^3/8) / N)
 * LSB of qx. The |x|/N term is the rounding of U to one LSB of qa: it grows with |x| in LSB of
 * qx over |A| in LSB of qa, so use fx_solve wherever the solution itself is the answer.
 */
void     fx_solve_fast(fx_solve_fast_ws_t *ws, const int32_t *a, uint32_t qa, const int32_t *b, uint32_t qb,
                       uint32_t n, int32_t *x, uint32_t qx, int32_t pivot_min, fx_status_t *st);

/* ---------------------------------------------------------------- integrity */
/* CRC-32 (zlib/IEEE, reflected, poly 0xEDB88320); crc = 0 to start, chain by passing back. */
uint32_t fx_crc32(uint32_t crc, const uint8_t *data, size_t len);

#endif /* FSW_FX_H */
