/*
 * fx golden digests: every fx function over fixed, seeded vector sets, with a CRC-32 digest of
 * the outputs (and status words) per set. The same source runs on the host and on the target;
 * the target's lines must equal the host's bit for bit (spec 00 §6.4, non-negotiable 7).
 *
 * Output: one line per set, "digest <set> <records> <crc>", then "N passed, N failed".
 * Build with -DFX_DIGEST_DUMP=<set index> to print that set's records for a diff.
 */
#include "fx.h"
#include "ut.h"
#include "gv_print.h"

/* gv_digest.h's word-wise CRC, plus the set index for FX_DIGEST_DUMP. */
typedef struct {
    gv_dg_t g;
    uint32_t set;
} dg_t;

static void dg_u32(dg_t *d, uint32_t v)
{
    gv_dg_u32(&d->g, v);
#if defined(FX_DIGEST_DUMP)
    if (d->set == (uint32_t)(FX_DIGEST_DUMP)) {
        ut_put_u32hex(v);
        ut_puts("\n");
    }
#endif
}

static void dg_i32(dg_t *d, int32_t v) { dg_u32(d, (uint32_t)v); }

/* Callers store the result in a local first: C leaves the order of argument evaluation
   unspecified, so passing `f(&st), st` could record the status from before the call. */
static void dg_rec(dg_t *d, int32_t v, fx_status_t st)
{
    dg_i32(d, v);
    dg_u32(d, st);
    d->g.n++;
}

static void dg_begin(dg_t *d, uint32_t set)
{
    gv_dg_begin(&d->g);
    d->set = set;
}

static void dg_end(const dg_t *d, const char *name)
{
    gv_dg_print(name, "", &d->g);
}

static const int32_t edges[] = {
    INT32_MIN, INT32_MIN + 1, -1073741824, -65536, -3, -2, -1, 0, 1, 2, 3, 65535, 65536,
    1073741823, 1073741824, INT32_MAX - 1, INT32_MAX,
};
#define NEDGE (sizeof(edges) / sizeof(edges[0]))
#define NRAND 4000u

/* Signed random value with `bits` magnitude bits (1..32), no shift of a negative value. */
static int32_t rndb(uint64_t *s, uint32_t bits)
{
    uint64_t r = ut_rng_next(s);
    uint32_t m = (uint32_t)(r >> (64u - bits));
    return (int32_t)m;
}
/* Full-range, 24- or 16-bit random operand. */
static int32_t rnd(uint64_t *s) { return rndb(s, 32u - ((uint32_t)(*s % 3u) * 8u)); }

static const uint32_t fm[][3] = {{28u, 28u, 28u}, {29u, 29u, 29u}, {30u, 30u, 30u}, {30u, 28u, 28u}, {0u, 40u, 20u}, {24u, 20u, 22u}};
#define NFM (sizeof(fm) / sizeof(fm[0]))

UT_TEST(digest_mul_div)
{
    dg_t dm;
    dg_t dd;
    uint64_t seed = 1u;
    uint32_t f;
    uint32_t i;
    uint32_t j;
    dg_begin(&dm, 0u);
    dg_begin(&dd, 1u);
    for (f = 0u; f < NFM; f++) {
        for (i = 0u; i < NEDGE + NRAND; i++) {
            for (j = 0u; j < ((i < NEDGE) ? NEDGE : 1u); j++) {
                int32_t a = (i < NEDGE) ? edges[i] : rnd(&seed);
                int32_t b = (i < NEDGE) ? edges[j] : rnd(&seed);
                fx_status_t s1 = 0u;
                fx_status_t s2 = 0u;
                { int32_t r_ = fx_mul(a, fm[f][0], b, fm[f][1], fm[f][2], &s1); dg_rec(&dm, r_, s1); }
                { int32_t r_ = fx_div(a, fm[f][0], b, fm[f][1], fm[f][2], &s2); dg_rec(&dd, r_, s2); }
            }
        }
    }
    dg_end(&dm, "fx_mul");
    dg_end(&dd, "fx_div");
}

UT_TEST(digest_shift_convert_counts)
{
    dg_t d;
    uint64_t seed = 2u;
    uint32_t n;
    uint32_t i;
    dg_begin(&d, 2u);
    for (n = 0u; n < 64u; n++) {
        for (i = 0u; i < 200u; i++) {
            fx_status_t st = 0u;
            int64_t p = (int64_t)(ut_rng_next(&seed) >> (1u + (i % 40u))) * (((i & 1u) != 0u) ? -1 : 1);
            int64_t r = fx_shr_rnd64(p, n, &st);
            dg_u32(&d, (uint32_t)(uint64_t)r);
            dg_rec(&d, (int32_t)(uint32_t)((uint64_t)r >> 32), st);
            st = 0u;
            { int32_t x1 = rnd(&seed); int32_t r_ = fx_convert(x1, n % 41u, (n * 7u) % 41u, &st); dg_rec(&d, r_, st); }
            st = 0u;
            { int32_t r_ = fx_shl_sat(rndb(&seed, 24u), n % 32u, &st); dg_rec(&d, r_, st); }
            st = 0u;
            {
                /* Operands drawn in separate statements: argument evaluation order is unspecified. */
                int32_t c = rnd(&seed);
                int32_t m = rndb(&seed, 16u);
                int32_t bias = rndb(&seed, 28u);
                int32_t r_ = fx_from_count(c, m, n % 40u, bias, &st);
                dg_rec(&d, r_, st);
            }
            st = 0u;
            {
                int32_t v = rnd(&seed);
                int32_t m = rndb(&seed, 16u);
                int32_t r_ = fx_to_count(v, m, n % 40u, -1048575, 1048575, &st);
                dg_rec(&d, r_, st);
            }
            st = 0u;
            {
                int32_t x1 = rnd(&seed);
                int32_t x2 = rnd(&seed);
                int32_t r_ = fx_add_sat(x1, x2, &st);
                dg_rec(&d, r_, st);
            }
        }
    }
    dg_end(&d, "fx_shift_convert");
}

UT_TEST(digest_roots)
{
    dg_t d;
    uint64_t seed = 3u;
    uint32_t i;
    dg_begin(&d, 3u);
    for (i = 0u; i < 20000u; i++) {
        fx_status_t st = 0u;
        uint64_t x = ut_rng_next(&seed) >> (i % 64u);
        int32_t v[3];
        dg_rec(&d, (int32_t)fx_isqrt64(x), 0u);
        { int32_t r_ = fx_sqrt(rnd(&seed), 30u - (i % 3u), 30u - (i % 5u), &st); dg_rec(&d, r_, st); }
        v[0] = rnd(&seed);
        v[1] = rnd(&seed);
        v[2] = rnd(&seed);
        st = 0u;
        { int32_t r_ = fx_norm3(v, &st); dg_rec(&d, r_, st); }
    }
    dg_end(&d, "fx_roots");
}

UT_TEST(digest_trig)
{
    dg_t d;
    uint64_t seed = 4u;
    uint32_t i;
    dg_begin(&d, 4u);
    for (i = 0u; i < 40000u; i++) {
        int32_t s;
        int32_t c;
        fx_status_t st = 0u;
        uint32_t a = (i < 8192u) ? ((i / 16u) * 0x20000000u / 64u + (i % 16u) - 8u) : (uint32_t)ut_rng_next(&seed);
        fx_sincos(a, &s, &c);
        dg_rec(&d, s, 0u);
        dg_rec(&d, c, 0u);
        {
            int32_t y = rnd(&seed);
            int32_t x = rnd(&seed);
            dg_u32(&d, fx_atan2_bam(y, x, &st));
        }
        { int32_t r_ = fx_bam_to_rad_q29(a); dg_rec(&d, r_, st); }
        dg_u32(&d, fx_rad_q29_to_bam(rnd(&seed)));
    }
    dg_end(&d, "fx_trig");
}

UT_TEST(digest_kernels_solve)
{
    dg_t dk;
    dg_t ds;
    uint64_t seed = 5u;
    uint32_t it;
    dg_begin(&dk, 5u);
    dg_begin(&ds, 6u);
    for (it = 0u; it < 3000u; it++) {
        int32_t a[64];
        int32_t b[64];
        int32_t y[64];
        uint32_t n = 1u + (it % 8u);
        uint32_t m = 1u + ((it / 8u) % 8u);
        uint32_t i;
        fx_status_t st = 0u;
        fx_solve_ws_t ws;
        for (i = 0u; i < 64u; i++) {
            a[i] = rndb(&seed, 32u - (it % 5u));
            b[i] = rndb(&seed, 32u - (it % 3u));
        }
        { int32_t r_ = fx_dot(a, 30u, b, 29u, n, 28u, &st); dg_rec(&dk, r_, st); }
        st = 0u;
        fx_matvec(a, 28u, b, 28u, n, m, y, 28u, &st);
        for (i = 0u; i < n; i++) {
            dg_rec(&dk, y[i], st);
        }
        st = 0u;
        fx_matmul(a, 30u, b, 30u, n, m, n, y, 31u, &st);
        for (i = 0u; i < n * n; i++) {
            dg_rec(&dk, y[i], st);
        }
        /* Solve: diagonally weighted random systems, n = 1..4, q28 -> q29. */
        {
            uint32_t ns = 1u + (it % 4u);
            for (i = 0u; i < ns * ns; i++) {
                a[i] = rndb(&seed, 27u);
            }
            for (i = 0u; i < ns; i++) {
                a[i * ns + i] = (a[i * ns + i] / 2) + ((((it + i) & 1u) != 0u) ? (1 << 28) : -(1 << 28));
                b[i] = rndb(&seed, 28u);
            }
            st = 0u;
            fx_solve(&ws, a, 28u, b, 28u, ns, y, 29u, 1 << 18, &st);
            for (i = 0u; i < ns; i++) {
                dg_rec(&ds, y[i], st);
            }
        }
    }
    dg_end(&dk, "fx_kernels");
    dg_end(&ds, "fx_solve");
}

UT_TEST(digest_crc)
{
    dg_t d;
    uint64_t seed = 6u;
    uint8_t buf[256];
    uint32_t i;
    uint32_t crc = 0u;
    dg_begin(&d, 7u);
    for (i = 0u; i < 256u; i++) {
        buf[i] = (uint8_t)(ut_rng_next(&seed) & 0xFFu);
    }
    for (i = 0u; i <= 256u; i++) {
        crc = fx_crc32(crc, buf, i);
        dg_rec(&d, (int32_t)crc, 0u);
    }
    dg_end(&d, "fx_crc32");
}

int main(void)
{
    UT_CASES(cases) = {
        UT_CASE(digest_mul_div), UT_CASE(digest_shift_convert_counts), UT_CASE(digest_roots),
        UT_CASE(digest_trig), UT_CASE(digest_kernels_solve), UT_CASE(digest_crc),
    };
    return UT_RUN("fx_digest", cases);
}
