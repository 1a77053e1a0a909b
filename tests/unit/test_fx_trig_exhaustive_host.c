/*
 * test_fx_trig_exhaustive_host.c — fx_sincos at all 2^32 BAM angles (label `exhaustive`,
 * excluded from the default suite; spec 00 §1.6, §7). Host only; takes a few minutes.
 *
 * Every angle a = q 2^30 + r (q = 0..3, 0 <= r < 2^30) has the reference angle
 * x = min(r, 2^30 - r) in [0, 2^29]: sin a and cos a are a signed permutation of
 * sin(x pi/2^31) and cos(x pi/2^31), by exact identities. The loop therefore runs over x, takes
 * the long double oracle once per x, and checks the up to 8 angles that share it. That visits
 * each of the 2^32 angles exactly once: (2^29 + 1) * 4 with r = x plus (2^29 - 1) * 4 with
 * r = 2^30 - x. It also checks s(-a) == -s(a), c(-a) == c(a) bit for bit (-a is in the same
 * group) and |s|, |c| <= 2^30.
 * Bound: contract 4 LSB of q30; design guard 1 LSB (see test_fx_trig_sweep_host.c).
 */
#include "ut.h"
#include "fx.h"

#include <inttypes.h>
#include <math.h>
#include <stdio.h>

static const long double PI_L = 3.14159265358979323846264338327950288L;

typedef struct {
    long double max;
    long double sum;
    uint32_t arg;
    int which;          /* 0 sin, 1 cos */
    uint64_t n;
    uint64_t sym_bad;
    uint64_t range_bad;
} ex_stat_t;

static void note(long double e, uint32_t a, int which, ex_stat_t *t)
{
    long double m = fabsl(e);
    t->sum += m;
    if (m > t->max) {
        t->max = m;
        t->arg = a;
        t->which = which;
    }
}

UT_TEST(t_sincos_all_angles)
{
    ex_stat_t t = { 0 };
    uint32_t x;
    const uint32_t half = UINT32_C(1) << 29;
    const uint32_t quarter = UINT32_C(1) << 30;
    for (x = 0u; x <= half; x++) {
        long double th = (long double)x * (PI_L / 2147483648.0L);
        long double so = sinl(th) * 1073741824.0L;
        long double co = cosl(th) * 1073741824.0L;
        int32_t s[8];
        int32_t c[8];
        uint32_t q;
        int nr = ((x > 0u) && (x < half)) ? 2 : 1;
        int j;
        for (j = 0; j < nr; j++) {
            /* j == 0: r = x, (sin phi, cos phi) = (so, co); j == 1: r = 2^30 - x, swapped */
            long double sp = (j == 0) ? so : co;
            long double cp = (j == 0) ? co : so;
            for (q = 0u; q < 4u; q++) {
                uint32_t a = q * quarter + ((j == 0) ? x : quarter - x);
                long double es;
                long double ec;
                int i = (int)(q * 2u) + j;
                fx_sincos(a, &s[i], &c[i]);
                switch (q) {
                case 0u: es = s[i] - sp; ec = c[i] - cp; break;
                case 1u: es = s[i] - cp; ec = c[i] + sp; break;
                case 2u: es = s[i] + sp; ec = c[i] + cp; break;
                default: es = s[i] + cp; ec = c[i] - sp; break;
                }
                note(es, a, 0, &t);
                note(ec, a, 1, &t);
                t.n++;
                t.range_bad += (s[i] > (1 << 30)) || (s[i] < -(1 << 30)) ||
                               (c[i] > (1 << 30)) || (c[i] < -(1 << 30));
            }
        }
        /* -(q 2^30 + r) = (3 - q) 2^30 + (2^30 - r) for r > 0; = (4 - q) 2^30 for r = 0 */
        for (q = 0u; q < 4u; q++) {
            int i = (int)(q * 2u);
            int k;
            if (x == 0u) {
                k = (int)(((4u - q) & 3u) * 2u);
            } else if (x == half) {
                k = (int)((3u - q) * 2u);
            } else {
                k = (int)((3u - q) * 2u) + 1;
            }
            t.sym_bad += (s[k] != -s[i]) || (c[k] != c[i]);
        }
    }
    (void)printf("fx_sincos exhaustive: %" PRIu64 " angles, max |err| %.4Lf LSB q30 (%s) at "
                 "a = 0x%08" PRIx32 ", mean |err| %.4Lf; symmetry violations %" PRIu64
                 ", range violations %" PRIu64 "\n",
                 t.n, t.max, (t.which == 0) ? "sin" : "cos", t.arg,
                 t.sum / (2.0L * (long double)t.n), t.sym_bad, t.range_bad);
    UT_UEQ(t.n, UINT64_C(1) << 32);
    UT_UEQ(t.sym_bad, 0u);
    UT_UEQ(t.range_bad, 0u);
    UT_TRUE(t.max <= 4.0L);
    UT_TRUE(t.max <= 1.0L);
}

int main(void)
{
    UT_CASES(cases) = {
        UT_CASE(t_sincos_all_angles),
    };
    return UT_RUN("fx_trig_exhaustive", cases);
}
