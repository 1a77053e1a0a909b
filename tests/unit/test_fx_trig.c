/*
 * test_fx_trig.c — exact properties of fx_sincos, fx_atan2_bam and the BAM <-> radian
 * conversions (spec 00 §1.6). Runs on the host (CMocka) and on the target (QEMU): integer
 * only, no floating point, no libm. The libm/long double accuracy sweeps are in
 * test_fx_trig_sweep_host.c.
 *
 * Contract bounds used below (q30 LSB = 2^-30; BAM LSB = 2 pi / 2^32 rad):
 *   sincos |err| <= 4 LSB (2^-28); atan2 |err| <= 2^-27 rad = 5.09 BAM LSB.
 */
#include "ut.h"
#include "fx.h"

#define ONE_Q30   ((int32_t)1 << 30)
#define BAM_45    UINT32_C(0x20000000)
#define BAM_90    UINT32_C(0x40000000)
#define BAM_180   UINT32_C(0x80000000)
#define BAM_270   UINT32_C(0xC0000000)
#define SWEEP_N   65536u    /* seeded sweep length (about 0.2 s under QEMU) */
#define EDGE_D    4096

/*
 * s^2 + c^2 - 2^60 with s = S + e1, c = C + e2, S^2 + C^2 = 2^60, |e| <= 4:
 *   |2 (S e1 + C e2) + e1^2 + e2^2| <= 2 * 2^30 * 4 * sqrt(2) + 32 < 6 * 2^31.
 */
#define PYTH_BOUND   ((int64_t)6 << 31)
/*
 * Double angle: s(2a) 2^30 - 2 s(a) c(a) = 2^30 e3 - 2 (S e2 + C e1) - 2 e1 e2 (same notation,
 * 2 S C = 2^30 S2): |.| <= 2^30 4 + 2 2^30 4 sqrt(2) + 32 < 16 * 2^30.
 */
#define DBL_BOUND    ((int64_t)16 << 30)
/*
 * Round trip atan2(sincos(a)) - a: the vector (s, c) deviates from the exact one by at most
 * 4 sqrt(2) LSB at radius 2^30, i.e. by an angle <= 4 sqrt(2) 2^-30 (1 + 1e-8) rad = 5.27e-9
 * rad; atan2 adds <= 2^-27 rad = 7.45e-9 rad. Sum 1.272e-8 rad = 8.70 BAM LSB -> 9.
 */
#define ROUNDTRIP_BAM 9u

static uint32_t bam_dist(uint32_t a, uint32_t b)
{
    uint32_t d = a - b;
    uint32_t e = b - a;
    return (d < e) ? d : e;
}

/* Two's-complement reinterpretation without implementation-defined conversions. */
static int32_t i32_of(uint32_t u)
{
    return (u <= (uint32_t)INT32_MAX) ? (int32_t)u : ((int32_t)(u - UINT32_C(0x80000000)) - INT32_MAX - 1);
}

static int64_t iabs64(int64_t v)
{
    return (v < 0) ? -v : v;
}

/* Every property that must hold exactly at one angle; failures are recorded, not fatal. */
static void check_angle(uint32_t a)
{
    int32_t s;
    int32_t c;
    int32_t sn;
    int32_t cn;
    int32_t s2;
    int32_t c2;
    fx_sincos(a, &s, &c);
    /* bounds */
    UT_CHECK_LE(iabs64(s), ONE_Q30);
    UT_CHECK_LE(iabs64(c), ONE_Q30);
    /* exact symmetry */
    fx_sincos(0u - a, &sn, &cn);
    UT_CHECK_EQ(sn, -(int64_t)s);
    UT_CHECK_EQ(cn, c);
    /* exact complement and quadrant shifts (the octant map is a signed permutation) */
    fx_sincos(BAM_90 - a, &s2, &c2);
    UT_CHECK_EQ(s2, c);
    UT_CHECK_EQ(c2, s);
    fx_sincos(a + BAM_90, &s2, &c2);
    UT_CHECK_EQ(s2, c);
    UT_CHECK_EQ(c2, -(int64_t)s);
    fx_sincos(a + BAM_180, &s2, &c2);
    UT_CHECK_EQ(s2, -(int64_t)s);
    UT_CHECK_EQ(c2, -(int64_t)c);
    /* sin^2 + cos^2 */
    UT_CHECK_LE(iabs64((int64_t)s * s + (int64_t)c * c - ((int64_t)1 << 60)), PYTH_BOUND);
    /* double angle: an accuracy check that needs no oracle */
    fx_sincos(a * 2u, &s2, &c2);
    UT_CHECK_LE(iabs64((int64_t)s2 * ((int64_t)1 << 30) - 2 * (int64_t)s * c), DBL_BOUND);
    UT_CHECK_LE(iabs64((int64_t)c2 * ((int64_t)1 << 30) - ((int64_t)c * c - (int64_t)s * s)), DBL_BOUND);
}

UT_TEST(t_sincos_exact_values)
{
    int32_t s;
    int32_t c;
    fx_sincos(0u, &s, &c);
    UT_EQ(s, 0);
    UT_EQ(c, ONE_Q30);
    fx_sincos(BAM_90, &s, &c);
    UT_EQ(s, ONE_Q30);
    UT_EQ(c, 0);
    fx_sincos(BAM_180, &s, &c);
    UT_EQ(s, 0);
    UT_EQ(c, -ONE_Q30);
    fx_sincos(BAM_270, &s, &c);
    UT_EQ(s, -ONE_Q30);
    UT_EQ(c, 0);
    /* 45 deg: sqrt(2)/2 2^30 = 759250124.99; sin and cos agree bit for bit there. */
    fx_sincos(BAM_45, &s, &c);
    UT_EQ(s, 759250125);
    UT_EQ(c, 759250125);
    /* One BAM LSB is 1.57 q30 LSB of sin near 0, and cos stays at 2^30 to within 4 LSB. */
    fx_sincos(1u, &s, &c);
    UT_TRUE((s >= 1) && (s <= 2));
    UT_EQ(c, ONE_Q30);
    fx_sincos(UINT32_MAX, &s, &c);
    UT_TRUE((s >= -2) && (s <= -1));
    UT_EQ(c, ONE_Q30);
}

UT_TEST(t_sincos_symmetry_sweep)
{
    uint64_t seed = UINT64_C(0x7452494753574550);   /* fixed seed */
    uint32_t i;
    check_angle(0u);
    check_angle(BAM_180);
    for (i = 0u; i < SWEEP_N; i++) {
        check_angle((uint32_t)(ut_rng_next(&seed) >> 32));
        if (ut_fail_count() != 0u) {
            break;
        }
    }
    UT_EQ(ut_fail_count(), 0);
}

UT_TEST(t_sincos_octant_edges)
{
    uint32_t k;
    int32_t d;
    for (k = 0u; k < 8u; k++) {
        for (d = -EDGE_D; d <= EDGE_D; d++) {
            check_angle((k << 29) + (uint32_t)d);
        }
        UT_EQ(ut_fail_count(), 0);
    }
    /* powers of two and their neighbours */
    for (k = 0u; k < 32u; k++) {
        check_angle((uint32_t)1 << k);
        check_angle(((uint32_t)1 << k) + 1u);
        check_angle(((uint32_t)1 << k) - 1u);
    }
    UT_EQ(ut_fail_count(), 0);
}

UT_TEST(t_atan2_axes_and_diagonals)
{
    static const int32_t mags[] = { 1, 2, 3, 1000, 65536, 123456789, INT32_MAX - 1, INT32_MAX };
    fx_status_t st = 0u;
    size_t i;
    for (i = 0u; i < sizeof(mags) / sizeof(mags[0]); i++) {
        int32_t k = mags[i];
        UT_UEQ(fx_atan2_bam(0, k, &st), 0u);
        UT_UEQ(fx_atan2_bam(k, 0, &st), BAM_90);
        UT_UEQ(fx_atan2_bam(0, -k, &st), BAM_180);
        UT_UEQ(fx_atan2_bam(-k, 0, &st), BAM_270);
        UT_UEQ(fx_atan2_bam(k, k, &st), BAM_45);
        UT_UEQ(fx_atan2_bam(k, -k, &st), 3u * BAM_45);
        UT_UEQ(fx_atan2_bam(-k, -k, &st), 5u * BAM_45);
        UT_UEQ(fx_atan2_bam(-k, k, &st), 7u * BAM_45);
    }
    UT_UEQ(st, 0u);
}

/*
 * Near the axes and the diagonals the exact angle is linear to far below one LSB:
 * atan2(d, k) = d/k - (d/k)^3/3 and atan2(k + d, k) = pi/4 + atan(d / (2k + d)), with
 * |d| <= 4096 and k = 2^30, so the cubic terms are < 2^-54 rad. The expected offset
 * e = round(z 2^31 / pi), z = d/k or d/(2k + d), uses pi ~ 355/113 (relative error 8.5e-8, i.e.
 * < 1e-3 LSB on |e| <= 2608). Bound: contract 2^-27 rad = 5.09 LSB + 0.5 (rounding of e)
 * + 0.01 -> 6 BAM LSB. Also monotone in d.
 */
static int64_t lin_offset(int64_t d, int64_t den)
{
    int64_t num = d * ((int64_t)1 << 31) * 113;
    int64_t q = den * 355;
    int64_t m = (num < 0) ? -num : num;
    int64_t r = (m + (q / 2)) / q;
    return (num < 0) ? -r : r;
}

UT_TEST(t_atan2_octant_edges)
{
    const int32_t k = (int32_t)1 << 30;
    fx_status_t st = 0u;
    uint32_t prev_axis = 0u;
    uint32_t prev_diag = 0u;
    int32_t d;
    for (d = -EDGE_D; d <= EDGE_D; d++) {
        uint32_t ra = fx_atan2_bam(d, k, &st);
        uint32_t rd = fx_atan2_bam(k + d, k, &st);
        uint32_t ea = (uint32_t)lin_offset(d, k);                    /* mod 2^32 */
        uint32_t ed = BAM_45 + (uint32_t)lin_offset(d, 2 * (int64_t)k + d);
        UT_CHECK_LE(bam_dist(ra, ea), 6u);
        UT_CHECK_LE(bam_dist(rd, ed), 6u);
        if (d > -EDGE_D) {
            /* non-decreasing modulo 2^32: the step is a small non-negative BAM difference */
            UT_CHECK_LE(ra - prev_axis, 16u);
            UT_CHECK_LE(rd - prev_diag, 16u);
        }
        prev_axis = ra;
        prev_diag = rd;
    }
    UT_UEQ(st, 0u);
    UT_EQ(ut_fail_count(), 0);
}

UT_TEST(t_atan2_int32_min)
{
    fx_status_t st = 0u;
    UT_UEQ(fx_atan2_bam(INT32_MIN, 0, &st), BAM_270);
    UT_UEQ(fx_atan2_bam(0, INT32_MIN, &st), BAM_180);
    UT_UEQ(fx_atan2_bam(INT32_MIN, INT32_MIN, &st), 5u * BAM_45);
    /* atan2(-2^31, 2^31 - 1) = -pi/4 - 2.3e-10 rad: BAM 0xE0000000 - 0.16 */
    UT_LE(bam_dist(fx_atan2_bam(INT32_MIN, INT32_MAX, &st), 7u * BAM_45), 1u);
    UT_LE(bam_dist(fx_atan2_bam(INT32_MAX, INT32_MIN, &st), 3u * BAM_45), 1u);
    UT_LE(bam_dist(fx_atan2_bam(INT32_MIN, -INT32_MAX, &st), 5u * BAM_45), 1u);
    /* atan2(-2^31, 1): 2^-31 rad past -pi/2 = 0.33 BAM LSB */
    UT_LE(bam_dist(fx_atan2_bam(INT32_MIN, 1, &st), BAM_270), 1u);
    UT_LE(bam_dist(fx_atan2_bam(1, INT32_MIN, &st), BAM_180), 1u);
    UT_LE(bam_dist(fx_atan2_bam(-1, INT32_MIN, &st), BAM_180), 1u);
    UT_UEQ(st, 0u);
}

UT_TEST(t_atan2_domain)
{
    fx_status_t st = 0u;
    UT_UEQ(fx_atan2_bam(0, 0, &st), 0u);
    UT_UEQ(st, FX_ST_DOMAIN);
    /* sticky: ORs, never clears */
    st = FX_ST_SAT_HI;
    UT_UEQ(fx_atan2_bam(0, 0, &st), 0u);
    UT_UEQ(st, FX_ST_SAT_HI | FX_ST_DOMAIN);
    UT_UEQ(fx_atan2_bam(1, 0, &st), BAM_90);
    UT_UEQ(st, FX_ST_SAT_HI | FX_ST_DOMAIN);
}

/* Exact mirror identities of the reduction, on a seeded sweep of operands. */
UT_TEST(t_atan2_symmetry_sweep)
{
    uint64_t seed = UINT64_C(0x41544E3253594D4D);
    fx_status_t st = 0u;
    uint32_t i;
    for (i = 0u; i < SWEEP_N; i++) {
        uint64_t r = ut_rng_next(&seed);
        /* mix full-range operands with small ones (every fourth draw shrinks both) */
        uint32_t sh = ((i & 3u) == 0u) ? (uint32_t)(r & 31u) : 0u;
        int32_t y = i32_of((uint32_t)(r >> 32) >> sh);
        int32_t x = i32_of((uint32_t)r >> sh);
        uint32_t t;
        if ((x == INT32_MIN) || (y == INT32_MIN) || ((x == 0) && (y == 0))) {
            continue;
        }
        t = fx_atan2_bam(y, x, &st);
        UT_CHECK_UEQ(fx_atan2_bam(-y, x, &st), 0u - t);
        UT_CHECK_UEQ(fx_atan2_bam(y, -x, &st), BAM_180 - t);
        UT_CHECK_UEQ(fx_atan2_bam(x, y, &st), BAM_90 - t);
        if (ut_fail_count() != 0u) {
            break;
        }
    }
    UT_UEQ(st, 0u);
}

/* atan2(sincos(a)) == a within the bound derived from both contracts. */
UT_TEST(t_atan2_sincos_roundtrip)
{
    uint64_t seed = UINT64_C(0x524F554E44545249);
    fx_status_t st = 0u;
    uint32_t worst = 0u;
    uint32_t i;
    int32_t d;
    uint32_t k;
    for (i = 0u; i < SWEEP_N; i++) {
        uint32_t a = (uint32_t)(ut_rng_next(&seed) >> 32);
        int32_t s;
        int32_t c;
        uint32_t e;
        fx_sincos(a, &s, &c);
        e = bam_dist(fx_atan2_bam(s, c, &st), a);
        worst = (e > worst) ? e : worst;
    }
    for (k = 0u; k < 8u; k++) {
        for (d = -EDGE_D; d <= EDGE_D; d += 7) {
            uint32_t a = (k << 29) + (uint32_t)d;
            int32_t s;
            int32_t c;
            uint32_t e;
            fx_sincos(a, &s, &c);
            e = bam_dist(fx_atan2_bam(s, c, &st), a);
            worst = (e > worst) ? e : worst;
        }
    }
    UT_LE(worst, ROUNDTRIP_BAM);
    UT_UEQ(st, 0u);
}

UT_TEST(t_bam_rad_values)
{
    /* Expected values from exact rational arithmetic (100-digit pi), not from the code. */
    UT_EQ(fx_bam_to_rad_q29(0u), 0);
    UT_EQ(fx_bam_to_rad_q29(1u), 1);                      /* 0.785 */
    UT_EQ(fx_bam_to_rad_q29(UINT32_MAX), -1);
    UT_EQ(fx_bam_to_rad_q29(BAM_45), 421657428);          /* pi/4 2^29 = ...428.27 */
    UT_EQ(fx_bam_to_rad_q29(BAM_90), 843314857);          /* ...856.53 */
    UT_EQ(fx_bam_to_rad_q29(BAM_270), -843314857);
    UT_EQ(fx_bam_to_rad_q29(BAM_180), 1686629713);        /* +pi: range is (-pi, pi] */
    UT_EQ(fx_bam_to_rad_q29(BAM_180 + 1u), -1686629712);
    UT_EQ(fx_bam_to_rad_q29(12345678u), 9696273);
    /* hardest case for |a| <= 2^31: a pi/4 = 1541987613.5 + 3.7e-11 */
    UT_EQ(fx_bam_to_rad_q29(1963319607u), 1541987614);
    UT_EQ(fx_bam_to_rad_q29(0u - 1963319607u), -1541987614);

    UT_UEQ(fx_rad_q29_to_bam(0), 0u);
    UT_UEQ(fx_rad_q29_to_bam(1), 1u);
    UT_UEQ(fx_rad_q29_to_bam(-1), UINT32_MAX);
    UT_UEQ(fx_rad_q29_to_bam(1686629713), BAM_180);
    UT_UEQ(fx_rad_q29_to_bam(-1686629712), BAM_180 + 1u);
    UT_UEQ(fx_rad_q29_to_bam(843314857), BAM_90 + 1u);    /* 2^30 + 0.595 */
    UT_UEQ(fx_rad_q29_to_bam(INT32_MAX), 2734261101u);
    UT_UEQ(fx_rad_q29_to_bam(INT32_MIN), 1560706194u);    /* -4 rad wraps */
    /* hardest case for |r| <= 2^31: r 4/pi = 170131365.5 - 1.7e-10 */
    UT_UEQ(fx_rad_q29_to_bam(133620862), 170131365u);
    UT_UEQ(fx_rad_q29_to_bam(-133620862), 0u - 170131365u);
}

/*
 * Round trips. rad -> bam -> rad is exact on (-pi, pi]: the BAM error <= 0.5 LSB becomes
 * <= 0.5 pi/4 = 0.39 LSB of q29 < 0.5. bam -> rad -> bam is within 1 LSB: 0.5 (4/pi) + 0.5
 * = 1.14 and the result is an integer.
 */
UT_TEST(t_bam_rad_roundtrip)
{
    uint64_t seed = UINT64_C(0x42414D5241443239);
    const int32_t rmax = 1686629713;    /* round(pi 2^29) */
    uint32_t i;
    int32_t d;
    for (i = 0u; i < SWEEP_N; i++) {
        uint64_t r = ut_rng_next(&seed);
        uint32_t a = (uint32_t)(r >> 32);
        int32_t q = i32_of((uint32_t)r);
        UT_CHECK_LE(bam_dist(fx_rad_q29_to_bam(fx_bam_to_rad_q29(a)), a), 1u);
        if ((q <= rmax) && (q > -rmax)) {
            UT_CHECK_EQ(fx_bam_to_rad_q29(fx_rad_q29_to_bam(q)), q);
        }
        /* odd symmetry of both conversions */
        if (a != BAM_180) {
            UT_CHECK_EQ(fx_bam_to_rad_q29(0u - a), -(int64_t)fx_bam_to_rad_q29(a));
        }
        if (q != INT32_MIN) {
            UT_CHECK_UEQ(fx_rad_q29_to_bam(-q), 0u - fx_rad_q29_to_bam(q));
        }
        if (ut_fail_count() != 0u) {
            break;
        }
    }
    for (d = -EDGE_D; d <= EDGE_D; d++) {
        UT_CHECK_EQ(fx_bam_to_rad_q29(fx_rad_q29_to_bam(d)), d);
        UT_CHECK_EQ(fx_bam_to_rad_q29(fx_rad_q29_to_bam(rmax - EDGE_D - d)), rmax - EDGE_D - d);
        UT_CHECK_LE(bam_dist(fx_rad_q29_to_bam(fx_bam_to_rad_q29(BAM_180 + (uint32_t)d)),
                             BAM_180 + (uint32_t)d), 1u);
    }
    UT_EQ(ut_fail_count(), 0);
}

int main(void)
{
    UT_CASES(cases) = {
        UT_CASE(t_sincos_exact_values),
        UT_CASE(t_sincos_symmetry_sweep),
        UT_CASE(t_sincos_octant_edges),
        UT_CASE(t_atan2_axes_and_diagonals),
        UT_CASE(t_atan2_octant_edges),
        UT_CASE(t_atan2_int32_min),
        UT_CASE(t_atan2_domain),
        UT_CASE(t_atan2_symmetry_sweep),
        UT_CASE(t_atan2_sincos_roundtrip),
        UT_CASE(t_bam_rad_values),
        UT_CASE(t_bam_rad_roundtrip),
    };
    return UT_RUN("fx_trig", cases);
}
