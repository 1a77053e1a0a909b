/*
 * Gyrodine steering of the respin (fsw/respin/rsp_cmg.c, spec 30 §2, §4, §5) on hand-derived cases.
 * Host and target, integer only.
 *
 * Every expected number is worked out from the spec's equations (stated next to it) with
 * lambda0 = 13421773 2^-28 (the table's value, 0.05 + 7.5e-10), h_g = 7.5 N m s, M_cmd as the q24
 * integer passed in; never read back from the code. Values with a fraction are written times 100
 * (suffix _x100) and compared with near().
 *
 * Error budget of the flight arithmetic, in LSB of the stated format (used by every tolerance):
 *   e_A   Ahat entry: fx_sincos <= 0.751 LSB q30 = 0.19 LSB q28, plus the rounding to q28: 0.69.
 *         Exact (0) at multiples of pi/2; 0.25 at +-pi/4 (759250125 / 4 vs sqrt(1/2) 2^28 =
 *         189812531.2485).
 *   P_ii  one rounding of the exact sum of n squared entries: n (2 e_A + e_A^2) + 1/2
 *         = 1.86 n + 1/2 LSB q28 (4.2 for n = 2, 7.9 for n = 4; 0 when the entries are exact).
 *   b     -M / h_g rounded to Q1.30: 1/8 LSB q28.
 *   y     diagonal P (L = 0: y_i = w_i = round(b_i / D_i) in Q5.26): 1/2 LSB q26 = 2 LSB q28, plus
 *         (1/8 + |y_i| dP_ii) / P_ii.
 *   beta_dot_p = round(sum_i Ahat_ip y_i): 1/2 + sum_i (|Ahat_ip| dy_i + e_A |y_i|) LSB q28.
 *   counts: beta_dot 2^-12 (or, scaled, u_max / max times it): an error of a few LSB q28 is
 *         < 0.002 count, so a count is exact whenever the hand value is farther than that from a
 *         rounding boundary (every case below: the hand values' fractions are given).
 *   M_del = round(-h_g round(Ahat cnt, q30) 2^-26): 1/2 + h_g 2^-31 2^24 (0.06) + e_A sum|cnt| 7.5
 *         2^-20 (<= 0.23 at 4 u_max) = 0.79 LSB q24, against the moment of the same counts with
 *         the exact Ahat.
 *   m_s   a minor (one nonzero first-row entry here, two-term cofactors): 2 (2 e_A) + e_A + 1/2
 *         (cofactor rounding) + 1/2 <= 4.5 LSB; m_s is the norm of the four minors, so
 *         |dm_s| <= |dminors|_2 + 1/2 (root rounding) <= 2 4.5 + 1/2 -> 10 LSB q28.
 *   s     |ds| <= d(max beta_dot) / u_max: a few LSB q28 are < 0.01 LSB q16; with the rounding,
 *         1 LSB q16.
 */
#include "rsp_cmg.h"
#include "ut.h"

#define HG_Q20      7864320    /* 7.5 N m s */
#define LAMBDA_Q28  13421773   /* 0.05 */
#define UMAX_CNT    11437      /* 0.1745 rad/s */
#define MS_SING_Q28 13421773   /* 0.05 */
#define BAM_P4      0x20000000u   /* pi/4 */
#define BAM_P2      0x40000000u   /* pi/2 */
#define BAM_M4      0xE0000000u   /* -pi/4 */
#define Q28         268435456
#define H_Q28       189812531     /* Ahat entry at +-pi/4: round(759250125 / 4) */

static rsp_cmg_params_t params(void)
{
    rsp_cmg_params_t p;
    p.hg_q20 = HG_Q20;
    p.lambda_q28 = LAMBDA_Q28;
    p.umax_cnt = UMAX_CNT;
    p.ms_sing_q28 = MS_SING_Q28;
    return p;
}

static int64_t iabs64(int64_t v)
{
    return (v < 0) ? -v : v;
}

/* |v - exp_x100 / 100| <= tol_x100 / 100, in integers */
static void near(int64_t v, int64_t exp_x100, int64_t tol_x100)
{
    UT_CHECK_LE(iabs64((v * 100) - exp_x100), tol_x100);
}

static void geom4(uint32_t b1, uint32_t b2, uint32_t b3, uint32_t b4, rsp_cmg_geom_t *g, fx_status_t *st)
{
    uint32_t beta[4];
    beta[0] = b1;
    beta[1] = b2;
    beta[2] = b3;
    beta[3] = b4;
    rsp_cmg_geom(beta, HG_Q20, g, st);
}

static void steer3(const rsp_cmg_geom_t *g, int32_t mx, int32_t my, int32_t mz, rsp_cmg_out_t *o, fx_status_t *st)
{
    const rsp_cmg_params_t p = params();
    int32_t m[3];
    m[0] = mx;
    m[1] = my;
    m[2] = mz;
    rsp_cmg_steer(&p, g, m, o, st);
}

static void check_counts(const rsp_cmg_out_t *o, int32_t c1, int32_t c2, int32_t c3, int32_t c4)
{
    UT_CHECK_EQ(o->rate_cnt[0], c1);
    UT_CHECK_EQ(o->rate_cnt[1], c2);
    UT_CHECK_EQ(o->rate_cnt[2], c3);
    UT_CHECK_EQ(o->rate_cnt[3], c4);
}

static void check_limits(const rsp_cmg_out_t *o)
{
    uint32_t k;
    for (k = 0u; k < 4u; k++) {
        UT_CHECK_LE(iabs64(o->rate_cnt[k]), UMAX_CNT);
    }
}

/* q56 entry (i, j) of Ahat Ahat^T, formed here from the geometry's Ahat */
static int64_t aat_q56(const rsp_cmg_geom_t *g, uint32_t i, uint32_t j)
{
    int64_t s = 0;
    uint32_t k;
    for (k = 0u; k < 4u; k++) {
        s += (int64_t)g->ahat_q28[i][k] * g->ahat_q28[j][k];
    }
    return s;
}

/* ------------------------------------------------------------------ geometry */

/* Null configuration beta = (pi/4, pi/4, -pi/4, -pi/4): H = h_g (c3 - c4, c1 - c2, s1 + s2 + s3 + s4)
   = 0: the bound is 1/2 (rounding) + 4 h_g 0.751 2^-30 2^20 (0.022) = 0.52 LSB, so the integer is 0.
   Ahat: columns (0, -h, h), (0, h, h), (h, 0, h), (-h, 0, h), h = sqrt(1/2); each within e_A = 0.25
   of 189812531.2485, i.e. exactly H_Q28. Ahat Ahat^T = diag(1, 1, 2) within n (2 e_A + e_A^2) 2^28
   (n = 2: 1.1 LSB q28, n = 4: 2.3): tolerance 3 LSB q28 = 3 2^28 in q56 for every entry.
   m_s = sqrt 2 = 379625062.497 LSB q28, tolerance 10 LSB. */
UT_TEST(null_configuration)
{
    rsp_cmg_geom_t g;
    fx_status_t st = 0u;
    const int64_t tol = (int64_t)3 * Q28;
    geom4(BAM_P4, BAM_P4, BAM_M4, BAM_M4, &g, &st);
    UT_UEQ(st, 0u);
    UT_EQ(g.h_q20[0], 0);
    UT_EQ(g.h_q20[1], 0);
    UT_EQ(g.h_q20[2], 0);
    UT_CHECK_EQ(g.ahat_q28[0][0], 0);
    UT_CHECK_EQ(g.ahat_q28[0][1], 0);
    UT_CHECK_EQ(g.ahat_q28[0][2], H_Q28);    /* -s3 = -sin(-pi/4) */
    UT_CHECK_EQ(g.ahat_q28[0][3], -H_Q28);   /* s4 */
    UT_CHECK_EQ(g.ahat_q28[1][0], -H_Q28);   /* -s1 */
    UT_CHECK_EQ(g.ahat_q28[1][1], H_Q28);    /* s2 */
    UT_CHECK_EQ(g.ahat_q28[1][2], 0);
    UT_CHECK_EQ(g.ahat_q28[1][3], 0);
    UT_CHECK_EQ(g.ahat_q28[2][0], H_Q28);
    UT_CHECK_EQ(g.ahat_q28[2][3], H_Q28);
    UT_CHECK_LE(iabs64(aat_q56(&g, 0u, 0u) - ((int64_t)1 << 56)), tol);
    UT_CHECK_LE(iabs64(aat_q56(&g, 1u, 1u) - ((int64_t)1 << 56)), tol);
    UT_CHECK_LE(iabs64(aat_q56(&g, 2u, 2u) - ((int64_t)2 << 56)), tol);
    UT_CHECK_LE(iabs64(aat_q56(&g, 0u, 1u)), tol);
    UT_CHECK_LE(iabs64(aat_q56(&g, 0u, 2u)), tol);
    UT_CHECK_LE(iabs64(aat_q56(&g, 1u, 2u)), tol);
    near(rsp_cmg_ms_q28(&g, &st), 37962506250, 1000);
    UT_UEQ(st, 0u);
}

/* Saturation beta = (pi/2, ...): sin = 2^30 and cos = 0 exactly (fx_sincos), so H = (0, 0, 4 h_g) =
   30 N m s = 31457280 exactly; Ahat columns (0, -1, 0), (0, 1, 0), (-1, 0, 0), (1, 0, 0): row z is
   zero, every 3x3 minor contains it, m_s = 0 exactly. */
UT_TEST(saturation_geometry)
{
    rsp_cmg_geom_t g;
    fx_status_t st = 0u;
    geom4(BAM_P2, BAM_P2, BAM_P2, BAM_P2, &g, &st);
    UT_UEQ(st, 0u);
    UT_EQ(g.h_q20[0], 0);
    UT_EQ(g.h_q20[1], 0);
    UT_EQ(g.h_q20[2], 4 * HG_Q20);
    UT_CHECK_EQ(g.ahat_q28[0][2], -Q28);
    UT_CHECK_EQ(g.ahat_q28[0][3], Q28);
    UT_CHECK_EQ(g.ahat_q28[1][0], -Q28);
    UT_CHECK_EQ(g.ahat_q28[1][1], Q28);
    UT_CHECK_EQ(g.ahat_q28[2][0], 0);
    UT_CHECK_EQ(g.ahat_q28[2][3], 0);
    UT_EQ(rsp_cmg_ms_q28(&g, &st), 0);
    UT_UEQ(st, 0u);
}

/* beta = (pi/4, pi/2, 0, -pi/4): s = (h, 1, 0, -h), c = (h, 0, 1, h).
   H = h_g (1 - h, h, h + 1 + 0 - h) = (2303405.999, 5560914.001, 7864320) LSB q20: H_x, H_y within
   1/2 + 2 0.0055 of the exact value, H_z exact (s1 + s4 cancel bit for bit, s2 = 1, s3 = 0).
   Cauchy-Binet in closed form (the four minors are s3 sin(b1 + b2), -s4 sin(b1 + b2), -s1 sin(b3 + b4),
   s2 sin(b3 + b4)): m_s^2 = (s3^2 + s4^2) sin^2(b1 + b2) + (s1^2 + s2^2) sin^2(b3 + b4)
   = (1/2)(1/2) + (3/2)(1/2) = 1, m_s = 1.0 = 2^28 (tolerance 10 LSB). */
UT_TEST(general_geometry_and_cauchy_binet)
{
    rsp_cmg_geom_t g;
    fx_status_t st = 0u;
    geom4(BAM_P4, BAM_P2, 0u, BAM_M4, &g, &st);
    UT_UEQ(st, 0u);
    near(g.h_q20[0], 230340599, 52);
    near(g.h_q20[1], 556091400, 52);
    UT_CHECK_EQ(g.h_q20[2], HG_Q20);
    near(rsp_cmg_ms_q28(&g, &st), (int64_t)Q28 * 100, 1000);
    /* beta = (pi/2, 0, pi/4, pi/4): (1 + 1) 1 + (1 + 0) sin^2(pi/2) ... = (s3^2 + s4^2) sin^2(pi/2)
       + (s1^2 + s2^2) sin^2(pi/2) = 1 + 1 = 2: m_s = sqrt 2 */
    geom4(BAM_P2, 0u, BAM_P4, BAM_P4, &g, &st);
    near(rsp_cmg_ms_q28(&g, &st), 37962506250, 1000);
    UT_UEQ(st, 0u);
}

/* Binary angles wrap: an encoder count c and c + 2^20 (one more turn) give the same word c << 12,
   and a BAM beta and beta + 2^32 are the same uint32. Across the wrap: beta = -eps (0xFFFFF000, one
   encoder count below 2 pi) is the mirror of +eps: cos equal, sin negated bit for bit, so H_x, H_y and
   the cos row agree and H_z, the sin rows change sign. Hand value: H_z = 4 h_g sin(2 pi 2^-20)
   = 188.4956 LSB q20 (bound 0.52 LSB: 188 or 189). */
UT_TEST(binary_angle_wrap)
{
    rsp_cmg_geom_t ga;
    rsp_cmg_geom_t gb;
    fx_status_t st = 0u;
    const uint32_t enc = 917504u;   /* -pi/4 as an encoder count, 7/8 of a turn */
    uint32_t beta[4];
    uint32_t k;
    uint32_t i;
    for (k = 0u; k < 4u; k++) {
        beta[k] = enc << 12;
    }
    rsp_cmg_geom(beta, HG_Q20, &ga, &st);
    for (k = 0u; k < 4u; k++) {
        beta[k] = (uint32_t)(((uint64_t)enc + 1048576u) << 12);             /* one turn more */
    }
    rsp_cmg_geom(beta, HG_Q20, &gb, &st);
    for (i = 0u; i < 3u; i++) {
        UT_CHECK_EQ(ga.h_q20[i], gb.h_q20[i]);
    }
    for (k = 0u; k < 4u; k++) {
        beta[k] = (uint32_t)((uint64_t)BAM_M4 + ((uint64_t)1 << 32));       /* beta + 2^32 */
    }
    rsp_cmg_geom(beta, HG_Q20, &gb, &st);
    for (i = 0u; i < 3u; i++) {
        UT_CHECK_EQ(ga.h_q20[i], gb.h_q20[i]);
        for (k = 0u; k < 4u; k++) {
            UT_CHECK_EQ(ga.ahat_q28[i][k], gb.ahat_q28[i][k]);
        }
    }
    geom4(0xFFFFF000u, 0xFFFFF000u, 0xFFFFF000u, 0xFFFFF000u, &ga, &st);
    geom4(0x00001000u, 0x00001000u, 0x00001000u, 0x00001000u, &gb, &st);
    UT_CHECK_EQ(ga.h_q20[0], 0);
    UT_CHECK_EQ(ga.h_q20[1], 0);
    UT_CHECK_EQ(ga.h_q20[2], -gb.h_q20[2]);
    UT_CHECK((gb.h_q20[2] == 188) || (gb.h_q20[2] == 189));
    UT_CHECK_EQ(ga.ahat_q28[0][2], -gb.ahat_q28[0][2]);
    UT_CHECK_EQ(ga.ahat_q28[1][0], -gb.ahat_q28[1][0]);
    for (k = 0u; k < 4u; k++) {
        UT_CHECK_EQ(ga.ahat_q28[2][k], gb.ahat_q28[2][k]);
    }
    UT_UEQ(st, 0u);
}

/* ------------------------------------------------------------------ steering */

/* Null configuration, M_cmd = (0, 0, -1.5) N m: Hdot_c / h_g = (0, 0, 0.2); P = diag(1 + l, 1 + l,
   2 + l) (the off-diagonal sums cancel exactly); y = (0, 0, 0.2 / 2.05); beta_dot_p = h y_z
   = 0.0689860274 rad/s = 18518295.72 LSB q28 for all four (budget: dy_z <= 2 + (1/8 + 0.1 7.9) / 2.05
   = 2.45, dbeta_dot <= 1/2 + h 2.45 + e_A 0.1 = 2.3: tolerance 3 LSB q28). Counts 4521.07 -> 4521.
   s = 0.0689860274 / (11437 2^-16) = 25906.51 LSB q16 (tolerance 1). M_del = -h_g Ahat cnt 2^-16:
   x and y cancel exactly (equal counts, entries +-H_Q28), z = -15 sqrt 2 4521 2^-16 N m
   = -24551652.54 LSB q24 (tolerance 0.79 -> 1). Not singular, not limited. */
UT_TEST(steer_null_configuration)
{
    rsp_cmg_geom_t g;
    rsp_cmg_out_t o;
    fx_status_t st = 0u;
    uint32_t k;
    geom4(BAM_P4, BAM_P4, BAM_M4, BAM_M4, &g, &st);
    steer3(&g, 0, 0, -25165824, &o, &st);
    UT_UEQ(st, 0u);
    for (k = 0u; k < 4u; k++) {
        near(o.rate_q28[k], 1851829572, 300);
    }
    check_counts(&o, 4521, 4521, 4521, 4521);
    UT_CHECK_EQ(o.mdel_q24[0], 0);
    UT_CHECK_EQ(o.mdel_q24[1], 0);
    near(o.mdel_q24[2], -2455165254, 100);
    near(o.s_q16, 2590650, 100);
    near(o.ms_q28, 37962506250, 1000);
    UT_UEQ(o.flags, 0u);
}

/* Saturation (beta = pi/2), M_cmd = (1.2, -0.9, 2) N m = (20132659, -15099494, 33554432) LSB q24:
   b = -M / h_g; P = diag(2 + l, 2 + l, l) (entries exact); y = (b_x / 2.05, b_y / 2.05, b_z / 0.05)
   = (-0.0780488, 0.0585366, -5.33); beta_dot = (-y_y, y_y, -y_x, y_x)
   = (-15713294.56, 15713294.56, 20951059.76, -20951059.76) LSB q28 (tolerance 3: dy <= 2.06);
   counts (-3836.25, 3836.25, 5115.005, -5115.005) -> (-3836, 3836, 5115, -5115).
   M_del = -h_g Ahat cnt 2^-16 with exact entries: x = -7.5 (-5115 - 5115) 2^-16 = 19641600 LSB q24,
   y = -7.5 (3836 + 3836) 2^-16 = -14730240, z = 0, all exact (bound 0.56 < 1 around an integer).
   m_s = 0: SINGULAR; the damped inverse still steers (y_z = -5.33 fits Q5.26), no fx status. */
UT_TEST(steer_through_saturation)
{
    rsp_cmg_geom_t g;
    rsp_cmg_out_t o;
    fx_status_t st = 0u;
    geom4(BAM_P2, BAM_P2, BAM_P2, BAM_P2, &g, &st);
    steer3(&g, 20132659, -15099494, 33554432, &o, &st);
    UT_UEQ(st, 0u);
    near(o.rate_q28[0], -1571329456, 300);
    near(o.rate_q28[1], 1571329456, 300);
    near(o.rate_q28[2], 2095105976, 300);
    near(o.rate_q28[3], -2095105976, 300);
    check_counts(&o, -3836, 3836, 5115, -5115);
    UT_CHECK_EQ(o.mdel_q24[0], 19641600);
    UT_CHECK_EQ(o.mdel_q24[1], -14730240);
    UT_CHECK_EQ(o.mdel_q24[2], 0);
    UT_CHECK_EQ(o.ms_q28, 0);
    UT_UEQ(o.flags, RSP_CMG_F_SINGULAR);
    check_limits(&o);
}

/* Internal singularity beta = 0: s = 0, c = 1 exactly; H = h_g (1 - 1, 1 - 1, 0) = 0; Ahat has the
   single non-zero row z = (1, 1, 1, 1): rank 1, m_s = 0. M_cmd = (0.5, -0.5, -2) N m:
   P = diag(l, l, 4 + l); y = (-1.33, 1.33, (2 / 7.5) / 4.05 = 0.0658436) (y_x, y_y large and
   invisible: Ahat^T has no x, y columns); beta_dot_p = y_z = 17674762.53 LSB q28 (tolerance 3);
   counts 4315.13 -> 4315; M_del = (0, 0, -7.5 4 4315 2^-16) = (0, 0, -33139200) exactly: the
   x, y moments cannot be delivered at this singularity. */
UT_TEST(steer_at_internal_singularity)
{
    rsp_cmg_geom_t g;
    rsp_cmg_out_t o;
    fx_status_t st = 0u;
    uint32_t k;
    geom4(0u, 0u, 0u, 0u, &g, &st);
    UT_EQ(g.h_q20[0], 0);
    UT_EQ(g.h_q20[1], 0);
    UT_EQ(g.h_q20[2], 0);
    UT_EQ(rsp_cmg_ms_q28(&g, &st), 0);
    steer3(&g, 8388608, -8388608, -33554432, &o, &st);
    UT_UEQ(st, 0u);
    for (k = 0u; k < 4u; k++) {
        near(o.rate_q28[k], 1767476253, 300);
    }
    check_counts(&o, 4315, 4315, 4315, 4315);
    UT_CHECK_EQ(o.mdel_q24[0], 0);
    UT_CHECK_EQ(o.mdel_q24[1], 0);
    UT_CHECK_EQ(o.mdel_q24[2], -33139200);
    UT_UEQ(o.flags, RSP_CMG_F_SINGULAR);
}

/* General geometry beta = (pi/4, pi/2, 0, -pi/4) (P not diagonal: d = e = -1/2, so L is exercised):
   P = [[0.55, 0, -0.5], [0, 1.55, -0.5], [-0.5, -0.5, 2.05]] (+ 7.5e-10 on the diagonal),
   M_cmd = (0.6, -1.2, 0.9) N m = (10066330, -20132659, 15099494) LSB q24, b = -M / h_g, y = P^-1 b
   (solved by hand in rationals) = (-0.2349044, 0.0714855, -0.0983948), beta_dot = Ahat^T y
   = (-32245424.80, 19189251.41, -26412665.67, 25911226.04) LSB q28.
   Tolerance, from the backward error of the LDL^T solve: the computed y solves (P + E) y = b + f with
   |E|_2 <= 3 (P: 1.6, factor: 1.8) = 10 LSB q28 and the w, y roundings (2 LSB q28 each, through
   L^-T, |L^-T|_2 = 1.59); |Ahat^T P^-1|_2 = 1.51, |Ahat|_2 = 1.55, |y| = 0.27:
   1/2 + 1.51 10 0.27 + 1.55 1.59 (2 + 2) sqrt 3 + 1.51 0.22 + e_A |y|_1 = 22.3 -> 23 LSB q28.
   Counts (-7872.42, 4684.88, -6448.40, 6325.98) -> (-7872, 4685, -6448, 6326); s = 45110.33 LSB q16;
   M_del of these counts with the exact Ahat (8588462.40, -19682581.60, 14479079.20) LSB q24 (tol 1). */
UT_TEST(steer_general_geometry)
{
    rsp_cmg_geom_t g;
    rsp_cmg_out_t o;
    fx_status_t st = 0u;
    geom4(BAM_P4, BAM_P2, 0u, BAM_M4, &g, &st);
    steer3(&g, 10066330, -20132659, 15099494, &o, &st);
    UT_UEQ(st, 0u);
    near(o.rate_q28[0], -3224542480, 2300);
    near(o.rate_q28[1], 1918925141, 2300);
    near(o.rate_q28[2], -2641266567, 2300);
    near(o.rate_q28[3], 2591122604, 2300);
    check_counts(&o, -7872, 4685, -6448, 6326);
    near(o.s_q16, 4511033, 100);
    near(o.mdel_q24[0], 858846240, 100);
    near(o.mdel_q24[1], -1968258160, 100);
    near(o.mdel_q24[2], 1447907920, 100);
    UT_UEQ(o.flags, 0u);
}

/* Zero command: b = 0, so y, beta_dot, the counts, s and M_del are exactly zero at any geometry. */
UT_TEST(zero_command_zero_rates)
{
    rsp_cmg_geom_t g;
    rsp_cmg_out_t o;
    fx_status_t st = 0u;
    uint32_t k;
    geom4(0x12345678u, 0x9ABCDEF0u, 0x0F1E2D3Cu, 0xC0FFEE00u, &g, &st);
    steer3(&g, 0, 0, 0, &o, &st);
    UT_UEQ(st, 0u);
    for (k = 0u; k < 4u; k++) {
        UT_CHECK_EQ(o.rate_q28[k], 0);
        UT_CHECK_EQ(o.rate_cnt[k], 0);
    }
    UT_CHECK_EQ(o.mdel_q24[0], 0);
    UT_CHECK_EQ(o.mdel_q24[1], 0);
    UT_CHECK_EQ(o.mdel_q24[2], 0);
    UT_CHECK_EQ(o.s_q16, 0);
    UT_CHECK((o.flags & RSP_CMG_F_RATE_LIMITED) == 0u);
}

/* Rate limit at the null configuration, M_cmd = (3, -2.5, -4) N m: y = (b_x / 1.05, b_y / 1.05,
   b_z / 2.05) = (-0.380952, 0.317460, 0.260163); beta_dot = h (-y_y + y_z, y_y + y_z, y_x + y_z,
   -y_x + y_z) = (-10875824.45, 109640068.32, -22927413.73, 121691657.60) LSB q28 (budget: dy <= 3.64,
   3.39, 3.07, so 1/2 + h (3.64 + 3.07) + e_A 0.64 = 5.4: tolerance 6); max 0.4533 rad/s, s = 2.5977
   = 170242.77 LSB q16 > 1: RATE_LIMITED. Scaled counts u_max beta_dot / max = (-1022.15, 10304.35,
   -2155 (-2154.80), 11437) -> (-1022, 10304, -2155, 11437): the largest exactly at the limit, the
   ratios those of beta_dot. M_del of these counts with the exact Ahat = (18453111.11,
   -15376687.50, -25203322.15) LSB q24 (tolerance 1). */
UT_TEST(rate_limit_preserves_direction)
{
    rsp_cmg_geom_t g;
    rsp_cmg_out_t o;
    fx_status_t st = 0u;
    int64_t mx = 0;
    uint32_t k;
    geom4(BAM_P4, BAM_P4, BAM_M4, BAM_M4, &g, &st);
    steer3(&g, 50331648, -41943040, -67108864, &o, &st);
    UT_UEQ(st, 0u);
    near(o.rate_q28[0], -1087582445, 600);
    near(o.rate_q28[1], 10964006832, 600);
    near(o.rate_q28[2], -2292741373, 600);
    near(o.rate_q28[3], 12169165760, 600);
    UT_UEQ(o.flags, RSP_CMG_F_RATE_LIMITED);
    near(o.s_q16, 17024277, 100);
    check_counts(&o, -1022, 10304, -2155, 11437);
    check_limits(&o);
    /* direction: each count is the correctly rounded u_max rate / max of the reported rates */
    for (k = 0u; k < 4u; k++) {
        mx = (iabs64(o.rate_q28[k]) > mx) ? iabs64(o.rate_q28[k]) : mx;
    }
    for (k = 0u; k < 4u; k++) {
        UT_CHECK_LE(iabs64(((int64_t)o.rate_cnt[k] * mx) - ((int64_t)o.rate_q28[k] * UMAX_CNT)), mx / 2);
    }
    near(o.mdel_q24[0], 1845311111, 100);
    near(o.mdel_q24[1], -1537668750, 100);
    near(o.mdel_q24[2], -2520332215, 100);
}

/* M_del is the moment of the counts actually commanded: recomputed here from the counts with the
   entries' exact values (sqrt(1/2) 2^30 = 759250124.994 -> 759250125, error 0.006 LSB q30) in two
   integer steps: a = sum Ahat cnt (q46) rounded to q30 (1/2 LSB), M = -h_g a 2^-26 (1/2 LSB q24).
   Against the flight: 0.79 + 0.5 + 0.06 -> tolerance 2 LSB q24. Also a command far beyond u_max (all
   four rates limited) keeps every count within +-umax_cnt. */
static int64_t mdel_of(const int32_t arow_q30[4], const int16_t cnt[4])
{
    int64_t a = 0;
    int64_t m;
    uint32_t k;
    for (k = 0u; k < 4u; k++) {
        a += (int64_t)arow_q30[k] * cnt[k];
    }
    a = (a >= 0) ? ((a + 32768) / 65536) : -((-a + 32768) / 65536);
    m = -(int64_t)HG_Q20 * a;
    return (m >= 0) ? ((m + 33554432) / 67108864) : -((-m + 33554432) / 67108864);
}

UT_TEST(mdel_follows_the_commanded_counts)
{
    static const int32_t row_x[4] = {0, 0, 759250125, -759250125};
    static const int32_t row_y[4] = {-759250125, 759250125, 0, 0};
    static const int32_t row_z[4] = {759250125, 759250125, 759250125, 759250125};
    rsp_cmg_geom_t g;
    rsp_cmg_out_t o;
    fx_status_t st = 0u;
    geom4(BAM_P4, BAM_P4, BAM_M4, BAM_M4, &g, &st);
    steer3(&g, 50331648, -41943040, -67108864, &o, &st);
    UT_CHECK_LE(iabs64(o.mdel_q24[0] - mdel_of(row_x, o.rate_cnt)), 2);
    UT_CHECK_LE(iabs64(o.mdel_q24[1] - mdel_of(row_y, o.rate_cnt)), 2);
    UT_CHECK_LE(iabs64(o.mdel_q24[2] - mdel_of(row_z, o.rate_cnt)), 2);
    /* 4.7 N m along -z: beta_dot_p = h (4.7 / 7.5) / 2.05 = 0.2162 rad/s > u_max for all four:
       each count exactly u_max */
    steer3(&g, 0, 0, -78852915, &o, &st);
    check_counts(&o, UMAX_CNT, UMAX_CNT, UMAX_CNT, UMAX_CNT);
    UT_CHECK_LE(iabs64(o.mdel_q24[2] - mdel_of(row_z, o.rate_cnt)), 2);
    UT_UEQ(o.flags, RSP_CMG_F_RATE_LIMITED);
    UT_UEQ(st, 0u);
}

/* Inputs beyond every range saturate through fx and raise the status (never undefined behaviour;
   the asan-ubsan build runs this): the command is then zero and within the limits. */
UT_TEST(extreme_inputs_raise_status)
{
    rsp_cmg_geom_t g;
    rsp_cmg_geom_t bad;
    rsp_cmg_out_t o;
    rsp_cmg_params_t p = params();
    fx_status_t st = 0u;
    int32_t m[3] = {INT32_MAX, INT32_MIN, INT32_MAX};
    uint32_t beta[4] = {BAM_P2, BAM_P2, BAM_P2, BAM_P2};
    uint32_t i;
    uint32_t k;
    geom4(BAM_P4, BAM_P4, BAM_M4, BAM_M4, &g, &st);
    UT_UEQ(st, 0u);
    /* |M| = 128 N m: -M / h_g = 17 does not fit Q1.30 */
    rsp_cmg_steer(&p, &g, m, &o, &st);
    UT_TRUE((st & (FX_ST_SAT_HI | FX_ST_SAT_LO)) != 0u);
    check_counts(&o, 0, 0, 0, 0);
    UT_CHECK_EQ(o.mdel_q24[0], 0);
    /* beta = 0, M_x = 13 N m: y_x = -(13 / 7.5) / 0.05 = -34.7 does not fit Q5.26 (even though
       Ahat^T y has no x part) */
    st = 0u;
    geom4(0u, 0u, 0u, 0u, &g, &st);
    steer3(&g, 218103808, 0, 0, &o, &st);
    UT_TRUE((st & FX_ST_SAT_LO) != 0u);
    check_counts(&o, 0, 0, 0, 0);
    /* an Ahat not made by rsp_cmg_geom: every entry INT32_MIN */
    st = 0u;
    for (i = 0u; i < 3u; i++) {
        bad.h_q20[i] = 0;
        for (k = 0u; k < 4u; k++) {
            bad.ahat_q28[i][k] = INT32_MIN;
        }
    }
    m[0] = 16777216;
    m[1] = 0;
    m[2] = 0;
    rsp_cmg_steer(&p, &bad, m, &o, &st);
    UT_TRUE(st != 0u);
    check_limits(&o);
    check_counts(&o, 0, 0, 0, 0);
    /* h_g at INT32_MAX: H_z = 4 h_g at saturation is beyond int32 */
    st = 0u;
    rsp_cmg_geom(beta, INT32_MAX, &g, &st);
    UT_CHECK_UEQ(st, FX_ST_SAT_HI);
    UT_CHECK_EQ(g.h_q20[2], INT32_MAX);
    /* tables the steering cannot use: FX_ST_ARG, every output zero */
    geom4(BAM_P4, BAM_P4, BAM_M4, BAM_M4, &g, &st);
    m[2] = 16777216;
    p.hg_q20 = 0;
    st = 0u;
    rsp_cmg_steer(&p, &g, m, &o, &st);
    UT_CHECK_UEQ(st, FX_ST_ARG);
    UT_CHECK_EQ(o.ms_q28, 0);
    p = params();
    p.lambda_q28 = 0;
    st = 0u;
    rsp_cmg_steer(&p, &g, m, &o, &st);
    UT_CHECK_UEQ(st, FX_ST_ARG);
    p = params();
    p.umax_cnt = 32768;
    st = 0u;
    rsp_cmg_steer(&p, &g, m, &o, &st);
    UT_CHECK_UEQ(st, FX_ST_ARG);
    check_counts(&o, 0, 0, 0, 0);
    /* the same command with the table restored flies */
    p = params();
    st = 0u;
    rsp_cmg_steer(&p, &g, m, &o, &st);
    UT_UEQ(st, 0u);
    UT_TRUE(o.rate_cnt[0] != 0);
}

int main(void)
{
    UT_CASES(cases) = {
        UT_CASE(null_configuration),
        UT_CASE(saturation_geometry),
        UT_CASE(general_geometry_and_cauchy_binet),
        UT_CASE(binary_angle_wrap),
        UT_CASE(steer_null_configuration),
        UT_CASE(steer_through_saturation),
        UT_CASE(steer_at_internal_singularity),
        UT_CASE(steer_general_geometry),
        UT_CASE(zero_command_zero_rates),
        UT_CASE(rate_limit_preserves_direction),
        UT_CASE(mdel_follows_the_commanded_counts),
        UT_CASE(extreme_inputs_raise_status),
    };
    return UT_RUN("rsp_cmg", cases);
}
