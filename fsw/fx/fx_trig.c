/*
 * fx_trig.c — sin/cos of a BAM angle, atan2 to a BAM angle, BAM <-> radians (spec 00 §1.6).
 *
 * Design (fsw/fx/README_trig.md has the measured accuracy):
 *  - Everything is unsigned integer arithmetic: uint32 operands, exact uint32 x uint32 ->
 *    uint64 products, and roundings of non-negative values only. Signs are applied last, to
 *    values of magnitude <= 2^30 (sincos) or as modular BAM negation (atan2). Nothing here
 *    shifts a negative value or can overflow a signed type.
 *  - The polynomial coefficients (tools/fx/gen_poly.py -> fx_trig_coef.h) alternate in sign,
 *    so they are stored as magnitudes and evaluated in the nested form
 *        P = M0 - z (M1 - z (M2 - ... (M(n-1) - z Mn)))
 *    where every stage is positive. Each stage is rounded half away from zero: the subtracted
 *    product is rounded with ties down (rnd_dn), so that M - rnd_dn(p) == round(M - p) with
 *    ties away from zero; a final positive product is rounded with ties up (rnd_up).
 *  - No loops, no tables beyond the coefficients: the cost is a fixed, short straight line.
 */
#include "fx.h"
#include "fx_trig_coef.h"

/* ------------------------------------------------------------------ formats and shifts */
#define OCT_BITS   29u                          /* BAM bits below the octant number */
#define OCT_ONE    ((uint32_t)1 << OCT_BITS)    /* pi/4 in BAM */
#define OCT_MASK   (OCT_ONE - 1u)
#define BAM_Q1     ((uint32_t)1 << 30u)          /* pi/2 */
#define BAM_HALF   ((uint32_t)1 << 31u)          /* pi */
#define ONE_Q30    ((uint32_t)1 << FX_TRIG_OUT_Q)

/* u = x^2 / 2^US in uq31 */
#define US         ((2u * FX_TRIG_X_Q) - FX_TRIG_U_Q)
/* Horner shifts: stage k holds coefficient k's Q, z * stage(k+1) is rounded into it. */
#define SIN_SH3    (FX_TRIG_U_Q + FX_TRIG_SIN_Q4 - FX_TRIG_SIN_Q3)
#define SIN_SH2    (FX_TRIG_U_Q + FX_TRIG_SIN_Q3 - FX_TRIG_SIN_Q2)
#define SIN_SH1    (FX_TRIG_U_Q + FX_TRIG_SIN_Q2 - FX_TRIG_SIN_Q1)
#define SIN_QP     (FX_TRIG_SIN_Q0 + 1u)        /* last stage P = S0 - u(...) in uq(Q0+1) */
#define SIN_SH0    (FX_TRIG_U_Q + FX_TRIG_SIN_Q1 - SIN_QP)
#define SIN_SHF    (FX_TRIG_X_Q + SIN_QP - FX_TRIG_OUT_Q)   /* x * P -> q30 */
#define COS_SH3    (FX_TRIG_U_Q + FX_TRIG_COS_Q4 - FX_TRIG_COS_Q3)
#define COS_SH2    (FX_TRIG_U_Q + FX_TRIG_COS_Q3 - FX_TRIG_COS_Q2)
#define COS_SH1    (FX_TRIG_U_Q + FX_TRIG_COS_Q2 - FX_TRIG_COS_Q1)
#define COS_SHF    (FX_TRIG_U_Q + FX_TRIG_COS_Q1 - FX_TRIG_OUT_Q)    /* 1 - u * stage1 */
#define WS         ((2u * FX_TRIG_V_Q) - FX_TRIG_W_Q)                  /* w = v^2 / 2^WS */
#define ATAN_SH4   (FX_TRIG_W_Q + FX_TRIG_ATAN_Q5 - FX_TRIG_ATAN_Q4)
#define ATAN_SH3   (FX_TRIG_W_Q + FX_TRIG_ATAN_Q4 - FX_TRIG_ATAN_Q3)
#define ATAN_SH2   (FX_TRIG_W_Q + FX_TRIG_ATAN_Q3 - FX_TRIG_ATAN_Q2)
#define ATAN_SH1   (FX_TRIG_W_Q + FX_TRIG_ATAN_Q2 - FX_TRIG_ATAN_Q1)
#define ATAN_QP    (FX_TRIG_ATAN_Q0 + 1u)
#define ATAN_SH0   (FX_TRIG_W_Q + FX_TRIG_ATAN_Q1 - ATAN_QP)
#define ATAN_SHF   (FX_TRIG_V_Q + ATAN_QP - 32u)    /* v * P -> turns * 2^32 (BAM) */

#define SH_OK(n) (((n) >= 1u) && ((n) <= 63u))
FX_STATIC_ASSERT(fx_trig_sa_us, (US >= 1u) && (US <= 31u));
FX_STATIC_ASSERT(fx_trig_sa_sin3, SH_OK(SIN_SH3));
FX_STATIC_ASSERT(fx_trig_sa_sin2, SH_OK(SIN_SH2));
FX_STATIC_ASSERT(fx_trig_sa_sin1, SH_OK(SIN_SH1));
FX_STATIC_ASSERT(fx_trig_sa_sin0, SH_OK(SIN_SH0));
FX_STATIC_ASSERT(fx_trig_sa_sinf, SH_OK(SIN_SHF));
FX_STATIC_ASSERT(fx_trig_sa_cos3, SH_OK(COS_SH3));
FX_STATIC_ASSERT(fx_trig_sa_cos2, SH_OK(COS_SH2));
FX_STATIC_ASSERT(fx_trig_sa_cos1, SH_OK(COS_SH1));
FX_STATIC_ASSERT(fx_trig_sa_cosf, SH_OK(COS_SHF));
FX_STATIC_ASSERT(fx_trig_sa_ws, SH_OK(WS));
FX_STATIC_ASSERT(fx_trig_sa_atan4, SH_OK(ATAN_SH4));
FX_STATIC_ASSERT(fx_trig_sa_atan3, SH_OK(ATAN_SH3));
FX_STATIC_ASSERT(fx_trig_sa_atan2, SH_OK(ATAN_SH2));
FX_STATIC_ASSERT(fx_trig_sa_atan1, SH_OK(ATAN_SH1));
FX_STATIC_ASSERT(fx_trig_sa_atan0, SH_OK(ATAN_SH0));
FX_STATIC_ASSERT(fx_trig_sa_atanf, SH_OK(ATAN_SHF));
/* The last sin/atan stage doubles a coefficient < 2^31 into a uint32; C0 is 1 in q30. */
FX_STATIC_ASSERT(fx_trig_sa_q0, (FX_TRIG_SIN_Q0 == 31u) && (FX_TRIG_ATAN_Q0 <= 33u));
FX_STATIC_ASSERT(fx_trig_sa_c0, FX_TRIG_COS_Q0 == FX_TRIG_OUT_Q);
/* Table lengths match the unrolled Horner forms below. */
FX_STATIC_ASSERT(fx_trig_sa_n, (FX_TRIG_SIN_N == 5u) && (FX_TRIG_COS_N == 5u) && (FX_TRIG_ATAN_N == 6u));
/* The atan2 reduction keeps v <= TAN_PI_8 + 1 (rounding), inside the fitted interval. */
FX_STATIC_ASSERT(fx_trig_sa_vmax, (FX_TRIG_TAN_PI_8 + 1u) <= FX_TRIG_V_MAX);

/* ------------------------------------------------------------------ unsigned helpers */
/*
 * Range argument (all operands unsigned): x <= 2^29, u <= 2^31, v < 2^31, w < 2^32, every
 * stage value < 2^32 (a magnitude < 2^31, or a doubled one < 2^32, minus a non-negative
 * term). Every product is therefore < 2^63, so adding a rounding constant < 2^62 never wraps.
 * gen_poly.py checks that no stage reaches 0 on its interval (stages decrease monotonically).
 */

/* round(p / 2^n), ties up: round half away from zero of a non-negative value; n in [1, 63]. */
static uint64_t rnd_up(uint64_t p, uint32_t n)
{
    const uint32_t k = n - 1u;
    const uint64_t half = (uint64_t)1 << k;
    return (p + half) >> n;
}

/* round(p / 2^n), ties down; c - rnd_dn(p, n) is round(c - p / 2^n) half away from zero. */
static uint64_t rnd_dn(uint64_t p, uint32_t n)
{
    const uint32_t k = n - 1u;
    const uint64_t half = (uint64_t)1 << k;
    return (p + (half - 1u)) >> n;
}

/* One Horner stage: m - z * s / 2^n, rounded half away from zero (result > 0 by design). */
static uint32_t stage(uint32_t m, uint32_t z, uint32_t s, uint32_t n)
{
    return m - (uint32_t)rnd_dn((uint64_t)z * (uint64_t)s, n);
}

/* Coefficient magnitude as unsigned (tables are int32_t, all entries positive). */
static uint32_t cf(int32_t c)
{
    return (uint32_t)c;
}

/* floor(m * K / 2^64) for K = k2:k1:k0 (96 bits): three exact 32x32 products. */
static uint64_t mul_u32_u96_hi(uint32_t m, uint32_t k2, uint32_t k1, uint32_t k0)
{
    uint64_t p = (uint64_t)m * (uint64_t)k0;
    p = ((uint64_t)m * (uint64_t)k1) + (p >> 32u);   /* < 2^64: (2^32-1)^2 + 2^32 - 1 */
    p = ((uint64_t)m * (uint64_t)k2) + (p >> 32u);
    return p;
}

/* ------------------------------------------------------------------ polynomials */
/* sin(pi/4 t) / t = P(u) = S0 - u (S1 - u (S2 - u (S3 - u S4))), in uq(SIN_Q0 + 1). */
static uint32_t sin_p(uint32_t u)
{
    static const int32_t mag[FX_TRIG_SIN_N] = FX_TRIG_SIN_MAG;
    uint32_t p = stage(cf(mag[3]), u, cf(mag[4]), SIN_SH3);
    p = stage(cf(mag[2]), u, p, SIN_SH2);
    p = stage(cf(mag[1]), u, p, SIN_SH1);
    return stage(cf(mag[0]) << 1u, u, p, SIN_SH0);
}

/* (1 - cos(pi/4 t)) / u = Q(u) = C1 - u (C2 - u (C3 - u C4)), in uq(COS_Q1); C0 = 1. */
static uint32_t cos_q(uint32_t u)
{
    static const int32_t mag[FX_TRIG_COS_N] = FX_TRIG_COS_MAG;
    uint32_t p = stage(cf(mag[3]), u, cf(mag[4]), COS_SH3);
    p = stage(cf(mag[2]), u, p, COS_SH2);
    return stage(cf(mag[1]), u, p, COS_SH1);
}

/* atan(v) / (2 pi v) = P(w) = A0 - w (A1 - w (A2 - w (A3 - w (A4 - w A5)))), uq(ATAN_Q0 + 1). */
static uint32_t atan_p(uint32_t w)
{
    static const int32_t mag[FX_TRIG_ATAN_N] = FX_TRIG_ATAN_MAG;
    uint32_t p = stage(cf(mag[4]), w, cf(mag[5]), ATAN_SH4);
    p = stage(cf(mag[3]), w, p, ATAN_SH3);
    p = stage(cf(mag[2]), w, p, ATAN_SH2);
    p = stage(cf(mag[1]), w, p, ATAN_SH1);
    return stage(cf(mag[0]) << 1u, w, p, ATAN_SH0);
}

/*
 * u = round(x^2 / 2^US) for x <= 2^29, ties up, assembled from the two 32-bit halves of x^2
 * (high half <= 2^26, so the shifted halves do not overlap): identical to
 * rnd_up(x * x, US), but GCC then knows u < 2^32 and multiplies by it with one UMULL instead
 * of UMULL + MLA per Horner stage.
 */
static uint32_t sq_rnd_us(uint32_t x)
{
    uint64_t xx = (uint64_t)x * (uint64_t)x;
    uint32_t hi = (uint32_t)(xx >> 32u);
    uint32_t lo = (uint32_t)xx;
    return (hi << (32u - US)) + (lo >> US) + ((lo >> (US - 1u)) & 1u);
}

/* ------------------------------------------------------------------ sin, cos */
/*
 * Octant reduction (exact): o = a >> 29, f = a mod 2^29, x = f for even o and 2^29 - f for
 * odd o, so x in [0, 2^29] is the distance to the nearest multiple of pi/2 in units of
 * pi/2^31 and t = x / 2^29 in [0, 1]. S = sin(pi/4 t) and C = cos(pi/4 t) are then mapped by
 * the octant: a signed permutation of (S, C). Since -a has the same x as a (its f is
 * 2^29 - f in the mirrored octant 7 - o), and the mapping is the exact one, s(-a) == -s(a)
 * and c(-a) == c(a) hold bit for bit, as do s(pi/2 - a) == c(a) and the quadrant shifts.
 *
 * Error (LSB of q30): the final rounding <= 0.5; before it, the integer model's error
 * (minimax + coefficient quantisation + u and stage roundings) measures <= 0.17 (sin) and
 * <= 0.25 (cos) on the generator's grid, so |err| <= 0.75 LSB against the <= 4 LSB contract.
 * Exact values: x = 0 gives S = 0, C = 2^30 (so 0, 90, 180, 270 deg are exact); S, C lie in
 * [0, 2^30].
 * Cost: 10 multiplies (32x32 -> 64), no divide, no loop, no branch except the octant selects
 * (74-76 instructions on Cortex-M3 at -Os, measured under QEMU).
 */
void fx_sincos(uint32_t a_bam, int32_t *s_q30, int32_t *c_q30)
{
    uint32_t oct = a_bam >> OCT_BITS;
    uint32_t f = a_bam & OCT_MASK;
    uint32_t x = ((oct & 1u) != 0u) ? (OCT_ONE - f) : f;
    uint32_t u = sq_rnd_us(x);
    uint32_t sv;
    uint32_t cv;
    uint32_t so;
    uint32_t co;
    bool swap;
    bool neg_s;
    bool neg_c;

    /* sin(pi/4 t) = t P(u), rounded once; cos(pi/4 t) = 1 - u Q(u), rounded once */
    sv = (uint32_t)rnd_up((uint64_t)x * (uint64_t)sin_p(u), SIN_SHF);
    cv = stage(ONE_Q30, u, cos_q(u), COS_SHF);

    /*
     * Octant map, with phi = a mod pi/2 and theta = pi/4 t:
     *  o:    0   1   2   3   4   5   6   7
     *  sin: +S  +C  +C  +S  -S  -C  -C  -S
     *  cos: +C  +S  -S  -C  -C  -S  +S  +C
     */
    swap = (((oct + 1u) >> 1u) & 1u) != 0u;
    neg_s = (oct >> 2u) != 0u;
    neg_c = (((oct + 2u) >> 2u) & 1u) != 0u;
    so = swap ? cv : sv;
    co = swap ? sv : cv;
    /* so, co <= 2^30: the conversions and negations are exact. */
    *s_q30 = neg_s ? -(int32_t)so : (int32_t)so;
    *c_q30 = neg_c ? -(int32_t)co : (int32_t)co;
}

/* ------------------------------------------------------------------ atan2 */
/*
 * Reduction: magnitudes |x|, |y| (exact uint32, also for INT32_MIN); mx = max, mn = min.
 * If mn / mx <= tan(pi/8): v = mn / mx, phi = atan(v); else v = (mx - mn) / (mx + mn),
 * phi = pi/4 - atan(v). Either way v in [0, tan(pi/8)], formed by ONE rounded 64/64 unsigned
 * divide in uq32 (error <= 2^-33, i.e. <= 2^-33 rad in atan). The quadrant and the swap of
 * x, y are then applied exactly in BAM: pi/2 - phi, pi - phi, -phi (mod 2^32).
 * Hence atan2(-y, x) == -atan2(y, x) and atan2(y, -x) == pi - atan2(y, x) exactly, the axes
 * and the diagonals are exact, and atan2(0, x < 0) == 0x80000000 (pi).
 * Error (BAM LSB, 1 LSB = 2 pi / 2^32 = 1.46e-9 rad): final rounding 0.5, polynomial model
 * <= 0.14, divide <= 0.09: <= 0.73 LSB = 1.1e-9 rad against the 2^-27 rad (5.1 LSB) contract.
 * Cost: 8 multiplies (32x32 -> 64) and one 64/64 divide (112-148 instructions on Cortex-M3
 * at -Os including __aeabi_uldivmod, measured under QEMU; 24 for (0, 0)).
 */
uint32_t fx_atan2_bam(int32_t y, int32_t x, fx_status_t *st)
{
    uint32_t ax = fx_uabs(x);
    uint32_t ay = fx_uabs(y);
    uint32_t r = 0u;

    if ((ax | ay) == 0u) {
        *st |= FX_ST_DOMAIN;
    } else {
        bool steep = ay > ax;
        uint32_t mx = steep ? ay : ax;   /* in [1, 2^31] */
        uint32_t mn = steep ? ax : ay;   /* in [0, mx] */
        /* mn / mx > tan(pi/8), compared exactly in uint64 */
        bool far = ((uint64_t)mn << 32u) > ((uint64_t)FX_TRIG_TAN_PI_8 * (uint64_t)mx);
        uint64_t num = far ? ((uint64_t)mx - (uint64_t)mn) : (uint64_t)mn;
        uint64_t den = far ? ((uint64_t)mx + (uint64_t)mn) : (uint64_t)mx;
        /*
         * v = round(num * 2^32 / den), ties up (num >= 0): num / den <= tan(pi/8) + 2^-32, so
         * num < 0.59 * 2^31 and num * 2^33 + den < 2^64; 2 den <= 2^33.
         */
        uint32_t v = (uint32_t)(((num << 33u) + den) / (den << 1u));
        uint32_t w = (uint32_t)rnd_up((uint64_t)v * (uint64_t)v, WS);
        /* atan(v) / 2 pi = v P(w), rounded once, in BAM: <= 2^28 */
        uint32_t phi = (uint32_t)rnd_up((uint64_t)v * (uint64_t)atan_p(w), ATAN_SHF);

        if (far) {
            phi = OCT_ONE - phi;
        }
        if (steep) {
            phi = BAM_Q1 - phi;
        }
        if (x < 0) {
            phi = BAM_HALF - phi;
        }
        if (y < 0) {
            phi = 0u - phi;
        }
        r = phi;
    }
    return r;
}

/* ------------------------------------------------------------------ BAM <-> radians */
/*
 * rad_q29 = a * pi / 4 with a the BAM read as an angle in (-pi, pi] (0x80000000 is +pi, as
 * atan2 returns it). |a| * (pi/4) with pi/4 to 96 bits: the product error is < 2^-65 LSB,
 * far below the smallest distance of |a| pi/4 from a half-integer for |a| <= 2^31 (3.7e-11,
 * from the continued fraction of pi/2), so the result is correctly rounded; ties cannot occur
 * (pi is irrational), so nearest == half away from zero.
 */
int32_t fx_bam_to_rad_q29(uint32_t a_bam)
{
    bool neg = a_bam > BAM_HALF;
    uint32_t m = neg ? (0u - a_bam) : a_bam;                 /* <= 2^31 */
    uint64_t hi = mul_u32_u96_hi(m, FX_TRIG_PI_4_W2, FX_TRIG_PI_4_W1, FX_TRIG_PI_4_W0);
    uint32_t r = (uint32_t)((hi + ((uint64_t)1 << 31u)) >> 32u);   /* <= 1686629713 */
    return neg ? -(int32_t)r : (int32_t)r;
}

/*
 * bam = a * 4 / pi (mod 2^32), correctly rounded: 4/pi to 96 bits (uq95), product error
 * < 2^-64 LSB, against a smallest distance of |a| 4/pi from a half-integer of 1.6e-10.
 * Negative angles are negated modulo 2^32 after rounding the magnitude (half away from zero).
 */
uint32_t fx_rad_q29_to_bam(int32_t a_rad_q29)
{
    uint32_t m = fx_uabs(a_rad_q29);                         /* <= 2^31 */
    uint64_t hi = mul_u32_u96_hi(m, FX_TRIG_4_PI_W2, FX_TRIG_4_PI_W1, FX_TRIG_4_PI_W0);
    uint32_t r = (uint32_t)((hi + ((uint64_t)1 << 30u)) >> 31u);   /* <= 2734261102 */
    return (a_rad_q29 < 0) ? (0u - r) : r;
}
