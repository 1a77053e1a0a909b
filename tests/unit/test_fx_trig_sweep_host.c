/*
 * test_fx_trig_sweep_host.c — accuracy sweeps of the fx trigonometry against libm long double
 * (host only; spec 00 §1.6). Prints the measured figures.
 *
 * Bounds:
 *  - sincos: contract |err| <= 2^-28 = 4 LSB of q30. Design bound, asserted as a regression
 *    guard: the final rounding contributes <= 0.5 LSB and everything before it (minimax error,
 *    coefficient quantisation, the roundings of u and of each Horner stage) <= 0.25 LSB on the
 *    generator's model (gen_poly.py prints it), so <= 0.75; the guard is 1 LSB.
 *  - atan2: contract |err| <= 2^-27 rad = 5.09 BAM LSB. Design: final rounding 0.5 BAM LSB,
 *    polynomial model <= 0.14, the rounded uq32 divide <= 2^-33 rad = 0.09: <= 0.73 BAM LSB;
 *    the guard is 1 BAM LSB (1.46e-9 rad).
 *  - bam <-> rad: correctly rounded (half away from zero). The long double oracle decides
 *    wherever the exact value is more than 2^-24 from a tie (its own error is < 1e-10 LSB);
 *    closer cases are decided by an exact 32 x 128-bit integer product with 128-bit constants.
 * Oracle error: th = a * (pi/2^31) in long double is within 4e-19 rad of the BAM angle, and
 * sinl/cosl/atan2l are accurate to about 1 ulp (1e-19): negligible against 2^-30.
 */
#include "ut.h"
#include "fx.h"

#include <inttypes.h>
#include <math.h>
#include <stdio.h>

#define SC_N        (1u << 24)
#define EDGE_D      4096
#define SC_GUARD    1.0L     /* LSB q30 */
#define SC_CONTRACT 4.0L
#define AT_GUARD_BAM 1.0L    /* BAM LSB */

static const long double PI_L = 3.14159265358979323846264338327950288L;

static long double bam_lsb_rad(void)
{
    return PI_L / 2147483648.0L;
}

/* Angle of a BAM in (-pi, pi]. */
static long double bam_to_radl(uint32_t a)
{
    long double v = (a > UINT32_C(0x80000000)) ? -(long double)(0u - a) : (long double)a;
    return v * bam_lsb_rad();
}

static int32_t i32_of(uint32_t u)
{
    return (u <= (uint32_t)INT32_MAX) ? (int32_t)u : ((int32_t)(u - UINT32_C(0x80000000)) - INT32_MAX - 1);
}

/* ------------------------------------------------------------------ sincos */
typedef struct {
    long double max_s, max_c, sum_s, sum_c, bias_s, bias_c;
    uint32_t arg_s, arg_c;
    uint64_t n;
} sc_stat_t;

static void sc_one(uint32_t a, sc_stat_t *t)
{
    int32_t s;
    int32_t c;
    long double th = bam_to_radl(a);
    long double es;
    long double ec;
    fx_sincos(a, &s, &c);
    es = (long double)s - sinl(th) * 1073741824.0L;
    ec = (long double)c - cosl(th) * 1073741824.0L;
    t->sum_s += fabsl(es);
    t->sum_c += fabsl(ec);
    t->bias_s += es;
    t->bias_c += ec;
    t->n++;
    if (fabsl(es) > t->max_s) {
        t->max_s = fabsl(es);
        t->arg_s = a;
    }
    if (fabsl(ec) > t->max_c) {
        t->max_c = fabsl(ec);
        t->arg_c = a;
    }
}

UT_TEST(t_sincos_sweep)
{
    sc_stat_t t = { 0 };
    uint64_t seed = UINT64_C(0x5357454550534331);
    uint32_t i;
    uint32_t k;
    int32_t d;
    for (i = 0u; i < SC_N; i++) {
        sc_one((uint32_t)(ut_rng_next(&seed) >> 32), &t);
    }
    /* every octant edge +-4096 */
    for (k = 0u; k < 8u; k++) {
        for (d = -EDGE_D; d <= EDGE_D; d++) {
            sc_one((k << 29) + (uint32_t)d, &t);
        }
    }
    /* powers of two, their neighbours and negatives */
    for (k = 0u; k < 32u; k++) {
        uint32_t p = (uint32_t)1 << k;
        sc_one(p, &t);
        sc_one(p + 1u, &t);
        sc_one(p - 1u, &t);
        sc_one(0u - p, &t);
        sc_one(0u - p + 1u, &t);
        sc_one(0u - p - 1u, &t);
    }
    (void)printf("fx_sincos: %" PRIu64 " angles (2^24 uniform + octant edges +-4096 + powers of two)\n", t.n);
    (void)printf("  sin: max |err| %.4Lf LSB q30 at a = 0x%08" PRIx32 ", mean |err| %.4Lf, mean err %+.2Le\n",
                 t.max_s, t.arg_s, t.sum_s / (long double)t.n, t.bias_s / (long double)t.n);
    (void)printf("  cos: max |err| %.4Lf LSB q30 at a = 0x%08" PRIx32 ", mean |err| %.4Lf, mean err %+.2Le\n",
                 t.max_c, t.arg_c, t.sum_c / (long double)t.n, t.bias_c / (long double)t.n);
    UT_TRUE(t.max_s <= SC_CONTRACT);
    UT_TRUE(t.max_c <= SC_CONTRACT);
    UT_TRUE(t.max_s <= SC_GUARD);
    UT_TRUE(t.max_c <= SC_GUARD);
}

/* ------------------------------------------------------------------ atan2 */
typedef struct {
    long double max;
    int32_t arg_y, arg_x;
    uint64_t n;
    fx_status_t st;
} at_stat_t;

static void at_one(int32_t y, int32_t x, at_stat_t *t)
{
    uint32_t r;
    long double e;
    if ((y == 0) && (x == 0)) {
        return;
    }
    r = fx_atan2_bam(y, x, &t->st);
    e = bam_to_radl(r) - atan2l((long double)y, (long double)x);
    if (e > PI_L) {
        e -= 2.0L * PI_L;
    } else if (e <= -PI_L) {
        e += 2.0L * PI_L;
    } else {
        /* in range */
    }
    e = fabsl(e);
    t->n++;
    if (e > t->max) {
        t->max = e;
        t->arg_y = y;
        t->arg_x = x;
    }
}

/* All 8 sign/swap images of (a, b) with a, b >= 0 magnitudes (INT32_MIN handled apart). */
static void at_images(int32_t a, int32_t b, at_stat_t *t)
{
    at_one(a, b, t);
    at_one(b, a, t);
    at_one(-a, b, t);
    at_one(-b, a, t);
    at_one(a, -b, t);
    at_one(b, -a, t);
    at_one(-a, -b, t);
    at_one(-b, -a, t);
}

UT_TEST(t_atan2_sweep)
{
    at_stat_t t = { 0 };
    uint64_t seed = UINT64_C(0x4154414E32535750);
    uint32_t i;
    uint32_t j;
    int32_t d;
    size_t m;
    static const int32_t mags[] = { 4097, 65536, 1000003, 123456789, 1073741824, INT32_MAX - 4096 };
    /* regular grid over the full int32 square, 1024 x 1024 */
    for (i = 0u; i < 1024u; i++) {
        for (j = 0u; j < 1024u; j++) {
            at_one(i32_of((i << 22) + 12345u), i32_of((j << 22) + 54321u), &t);
        }
    }
    /* small operands: every pair in [-64, 64]^2 */
    for (d = -64; d <= 64; d++) {
        int32_t e;
        for (e = -64; e <= 64; e++) {
            at_one(d, e, &t);
        }
    }
    /* random pairs, magnitudes spread over all scales */
    for (i = 0u; i < (1u << 22); i++) {
        uint64_t r = ut_rng_next(&seed);
        uint32_t sh = (uint32_t)(r & 31u);
        at_one(i32_of((uint32_t)(r >> 32) >> (sh & 15u)), i32_of((uint32_t)r >> (sh >> 1)), &t);
    }
    /* axes, the diagonals (octant edges) and the tan(pi/8) branch switch, +-4096 */
    for (m = 0u; m < sizeof(mags) / sizeof(mags[0]); m++) {
        int32_t k = mags[m];
        int32_t kt = (int32_t)lroundl((long double)k * tanl(PI_L / 8.0L));
        for (d = -EDGE_D; d <= EDGE_D; d++) {
            if (d >= 0) {
                at_images(d, k, &t);                 /* near the axes */
            }
            at_images(k + d, k, &t);                 /* near the diagonals */
            if (kt + d >= 0) {
                at_images(kt + d, k, &t);            /* near the branch switch */
            }
        }
    }
    /* INT32_MIN operands */
    for (d = -EDGE_D; d <= EDGE_D; d++) {
        at_one(INT32_MIN, d, &t);
        at_one(d, INT32_MIN, &t);
        at_one(INT32_MIN, INT32_MAX - EDGE_D - d, &t);
        at_one(INT32_MIN, INT32_MIN + EDGE_D + d, &t);
        at_one(INT32_MAX - EDGE_D - d, INT32_MIN, &t);
        at_one(INT32_MIN + EDGE_D + d, INT32_MIN, &t);
    }
    at_one(INT32_MIN, INT32_MIN, &t);
    (void)printf("fx_atan2_bam: %" PRIu64 " operand pairs (grid, small, random, axes, diagonals, "
                 "tan(pi/8) switch, INT32_MIN)\n", t.n);
    (void)printf("  max |err| %.4Le rad = %.4Lf BAM LSB (contract 2^-27 = %.4Le rad) at (y, x) = "
                 "(%" PRId32 ", %" PRId32 ")\n",
                 t.max, t.max / bam_lsb_rad(), ldexpl(1.0L, -27), t.arg_y, t.arg_x);
    UT_UEQ(t.st, 0u);
    UT_TRUE(t.max <= ldexpl(1.0L, -27));
    UT_TRUE(t.max <= AT_GUARD_BAM * bam_lsb_rad());
}

/* ------------------------------------------------------------------ bam <-> rad */
__extension__ typedef unsigned __int128 u128;

/* round(m * K / 2^(64 + sh)) for K = khi:klo (128 bits), ties up; K truncated (error < 2^-96). */
static uint64_t exact_mul_rnd(uint32_t m, uint64_t khi, uint64_t klo, unsigned sh)
{
    u128 h = (u128)m * khi + (((u128)m * klo) >> 64);   /* floor(m K / 2^64) */
    return (uint64_t)((h + ((u128)1 << (sh - 1u))) >> sh);
}

/* pi/4 * 2^128 and 4/pi * 2^127, truncated (hex expansions of pi and 2/pi). */
#define PI4_HI UINT64_C(0xC90FDAA22168C234)
#define PI4_LO UINT64_C(0xC4C6628B80DC1CD1)
#define FPI_HI UINT64_C(0xA2F9836E4E441529)
#define FPI_LO UINT64_C(0xFC2757D1F534DDC0)

static int32_t exact_b2r(uint32_t a)
{
    int neg = a > UINT32_C(0x80000000);
    uint32_t m = neg ? 0u - a : a;
    int32_t r = (int32_t)exact_mul_rnd(m, PI4_HI, PI4_LO, 64u);
    return neg ? -r : r;
}

static uint32_t exact_r2b(int32_t q)
{
    uint32_t m = (q < 0) ? 0u - (uint32_t)q : (uint32_t)q;
    uint32_t r = (uint32_t)exact_mul_rnd(m, FPI_HI, FPI_LO, 63u);
    return (q < 0) ? 0u - r : r;
}

typedef struct {
    uint64_t n, near_ties, ld_used, bad;
} cv_stat_t;

/* Half away from zero with long double; *near set if within 2^-24 of a tie. */
static long double rnd_ld(long double v, int *near)
{
    long double f = fabsl(v) - floorl(fabsl(v));
    *near = fabsl(f - 0.5L) < ldexpl(1.0L, -24);
    return roundl(v);
}

static void cv_one(uint32_t a, int32_t q, cv_stat_t *t)
{
    int near;
    int32_t r = fx_bam_to_rad_q29(a);
    uint32_t b = fx_rad_q29_to_bam(q);
    long double va = (a > UINT32_C(0x80000000)) ? -(long double)(0u - a) : (long double)a;
    long double ea = rnd_ld(va * (PI_L / 4.0L), &near);
    t->n += 2u;
    if (near) {
        t->near_ties++;
    } else {
        t->ld_used++;
        t->bad += ((int64_t)r != (int64_t)ea);
    }
    t->bad += (r != exact_b2r(a));
    {
        long double eq = rnd_ld((long double)q * (4.0L / PI_L), &near);
        /* reduce mod 2^32 exactly: eq is an integer of magnitude < 2^32 */
        uint32_t eb = (eq < 0.0L) ? 0u - (uint32_t)(-eq) : (uint32_t)eq;
        if (near) {
            t->near_ties++;
        } else {
            t->ld_used++;
            t->bad += (b != eb);
        }
        t->bad += (b != exact_r2b(q));
    }
}

UT_TEST(t_bam_rad_correct_rounding)
{
    cv_stat_t t = { 0 };
    uint64_t seed = UINT64_C(0x4342414D52414432);
    uint32_t i;
    int32_t d;
    for (i = 0u; i < (1u << 24); i++) {
        uint64_t r = ut_rng_next(&seed);
        cv_one((uint32_t)(r >> 32), i32_of((uint32_t)r), &t);
    }
    for (d = -65536; d <= 65536; d++) {
        cv_one((uint32_t)d, d, &t);
        cv_one(UINT32_C(0x80000000) + (uint32_t)d, INT32_MAX - 65536 + (d < 0 ? -d : d), &t);
        cv_one(UINT32_C(0x40000000) + (uint32_t)d, INT32_MIN + 65536 + d, &t);
    }
    /* the closest approaches to a tie for |a|, |q| <= 2^31 (continued fractions of pi/2, 8/pi) */
    cv_one(1963319607u, 133620862, &t);
    cv_one(0u - 1963319607u, -133620862, &t);
    UT_UEQ(exact_b2r(1963319607u), 1541987614u);
    UT_UEQ(exact_r2b(133620862), 170131365u);
    (void)printf("fx_bam_to_rad_q29 / fx_rad_q29_to_bam: %" PRIu64 " conversions, %" PRIu64
                 " decided by long double, %" PRIu64 " near-ties decided exactly, %" PRIu64 " wrong\n",
                 t.n, t.ld_used, t.near_ties, t.bad);
    UT_UEQ(t.bad, 0u);
}

int main(void)
{
    UT_CASES(cases) = {
        UT_CASE(t_sincos_sweep),
        UT_CASE(t_atan2_sweep),
        UT_CASE(t_bam_rad_correct_rounding),
    };
    return UT_RUN("fx_trig_sweep", cases);
}
