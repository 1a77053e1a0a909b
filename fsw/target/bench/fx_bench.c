/*
 * fx_bench.c — instruction counts of the fx kernels on the emulated Cortex-M (spec 00 §6.4, §9).
 * Run by tools/bench/fx_insn.py under QEMU -icount shift=3: virtual time advances 8 ns per
 * instruction and MPS2's SysTick counts the 25 MHz processor clock, so one tick = 5
 * instructions.
 *
 * Exact counts despite the 5-instruction tick. The bracket (bench_bracket5 in bench_asm.S,
 * hand-written so its instructions are known) reads SYST_CVR, calls the function five times
 * with the same argument, executes 4 NOPs and reads SYST_CVR again. Between the two reads
 * exactly 5 * (f + 3) instructions execute, f being the callee's, so the tick difference is
 * exactly f + 3 whatever the phase p of the tick: floor((p + 5k) / 5) - floor(p / 5) = k.
 * The calibration section (bench_calibrate in bench_common.c, shared with the module benches)
 * checks this with NOP sleds of known length at all five phases.
 *
 * Per sample the kernel is called from a wrapper that loads its arguments from the sample
 * arrays and stores its results to volatile sinks. Each wrapper has a twin that calls a null
 * function of the same prototype instead (a lone `bx lr` in fx_bench_asm.S), so
 *   kernel = w(kernel) - w(null) + 1   instructions from the kernel's entry through its return
 *   call   = w(kernel) - w(empty)      the same plus argument setup and result stores
 * where w() is the bracket value and `empty` is a wrapper that only returns.
 *
 * Output (parsed by tools/bench/fx_insn.py):
 *   fx_bench 1 cpuid <hex>
 *   cal <N> <phase> <value>        value must equal N + 4 (an N-NOP sled is N + 1 instructions)
 *   tick <N> <ticks>               one plain bracket around an N-NOP sled: ticks ~ N / 5
 *   empty <value>                  must be 4
 *   k <kernel> <sample> <kernel insns> <call insns>
 *   imp <kernel> <sample> <iters_total> <outcome> <how_xy> <how_z> <pattern>   (imp_solve entries)
 *   end
 *
 * Impulse scheduler entries (spec 50 §4.7; fx_insn.py compares them with the budgets): one full
 * imp_solve on the paper's example, on 32 random states of the nominal box, and on 8 hard states
 * of the wide box where every polarity pattern of both subsystems is tried; the same 8 with
 * r_tol = 0 (every attempt that does not fail early runs to max_iter, the closest real path to
 * the spec's worst case); imp_attempt from (0, tau_f) with max_iter 0 and 1, whose difference per
 * sample is exactly one Newton iteration (solve, update, trig of every switch, residual and
 * Jacobian); imp_trig; imp_psi and imp_phie of axis x on precomputed trig (prep); imp_round_best
 * after an imp_solve done outside the bracket (prep).
 * The inputs are nav counts (1 mm, 10 um/s) converted with the flight table as imp.c does, so the
 * image holds no floating point.
 */
#include <stdint.h>
#include <stddef.h>
#include "board.h"
#include "bench_common.h"
#include "fx.h"
#include "obs.h"
#include "obs_tables.h"
#include "imp.h"
#include "imp_tables.h"

#define BENCH_SAMPLES 32u
#define BENCH_CPUID   0xE000ED00u

/* ------------------------------------------------------------------ inputs */

static uint64_t bench_rng(void)
{
    static uint64_t state = UINT64_C(0x5EED00F1BE7C4A11);   /* splitmix64, fixed seed */
    uint64_t z;

    state += UINT64_C(0x9E3779B97F4A7C15);
    z = state;
    z = (z ^ (z >> 30)) * UINT64_C(0xBF58476D1CE4E5B9);
    z = (z ^ (z >> 27)) * UINT64_C(0x94D049BB133111EB);
    return z ^ (z >> 31);
}

static uint32_t bench_u32(void)
{
    return (uint32_t)(bench_rng() >> 32);
}

static int32_t bench_signed(uint32_t m)
{
    return ((bench_u32() & 1u) != 0u) ? -(int32_t)m : (int32_t)m;
}

/* Random int32 of random magnitude: |v| < 2^b, b uniform in [1, 31]. */
static int32_t bench_i32_mag(void)
{
    uint32_t shift = 1u + (bench_u32() % 31u);   /* 1..31 */
    return bench_signed(bench_u32() >> shift);
}

/* Uniform in (-2^(32 - shift), 2^(32 - shift)), shift in [1, 31]. */
static int32_t bench_i32_range(uint32_t shift)
{
    return bench_signed(bench_u32() >> shift);
}

#define Q24_ONE       16777216   /* 1.0 in q24 */
#define PIVOT_MIN_Q24 16777      /* 0.001 in q24 */
#define SH_Q24_1      8u         /* bench_i32_range(8u): (-1, 1) in q24 */
#define SH_Q24_2      7u         /* (-2, 2) in q24 */
#define SH_Q24_4      6u         /* (-4, 4) in q24 */
#define SH_Q24_8      5u         /* (-8, 8) in q24 */

typedef struct { int32_t a; int32_t b; uint32_t qa; uint32_t qb; uint32_t qr; } s_muldiv_t;
typedef struct { int32_t a[16]; int32_t b[4]; uint32_t n; } s_solve_t;

static s_muldiv_t s_mul[BENCH_SAMPLES];
static s_muldiv_t s_div[BENCH_SAMPLES];
static int32_t    s_sqrt[BENCH_SAMPLES];
static uint32_t   s_sqrt_q[BENCH_SAMPLES];
static uint64_t   s_isqrt[BENCH_SAMPLES];
static int32_t    s_norm3[BENCH_SAMPLES][3];
static uint32_t   s_sincos[BENCH_SAMPLES];
static int32_t    s_atan2[BENCH_SAMPLES][2];
static int32_t    s_dot[BENCH_SAMPLES][2][6];
static int32_t    s_matvec_m[BENCH_SAMPLES][36];
static int32_t    s_matvec_x[BENCH_SAMPLES][6];
static int32_t    s_matmul[BENCH_SAMPLES][2][16];
static s_solve_t  s_solve4[BENCH_SAMPLES];
static s_solve_t  s_solve2[BENCH_SAMPLES];
static uint8_t    s_crc[BENCH_SAMPLES][64];

static void bench_fill_solve(s_solve_t *s, uint32_t n)
{
    uint32_t i;
    uint32_t j;
    uint32_t rot = bench_u32() % n;

    /* Diagonally dominant (small kappa), rows rotated so partial pivoting has to swap. */
    for (i = 0u; i < n; i++) {
        uint32_t r = (i + rot) % n;
        for (j = 0u; j < n; j++) {
            int32_t v = bench_i32_range(SH_Q24_1);
            if (j == i) {
                int32_t d = ((int32_t)n * Q24_ONE) + ((v < 0) ? -v : v);
                v = bench_signed((uint32_t)d);
            }
            s->a[(r * n) + j] = v;
        }
        s->b[i] = bench_i32_range(SH_Q24_4);
    }
    s->n = n;
}

static void bench_fill_edges(void)
{
    uint32_t j;

    /* Saturation, divide by zero, domain errors, a singular system. */
    s_mul[0].a = INT32_MIN;
    s_mul[0].b = INT32_MIN;
    s_mul[1].a = 0;
    s_div[0].b = 0;
    s_div[1].a = INT32_MIN;
    s_div[1].b = -1;
    s_sqrt[0] = -1;
    s_sqrt[1] = 0;
    s_sqrt[2] = INT32_MAX;
    s_isqrt[0] = 0u;
    s_isqrt[1] = UINT64_MAX;
    for (j = 0u; j < 3u; j++) {
        s_norm3[0][j] = INT32_MIN;
    }
    s_sincos[0] = 0u;
    s_sincos[1] = 0x20000000u;   /* an octant edge */
    s_atan2[0][0] = 0;
    s_atan2[0][1] = 0;
    s_atan2[1][0] = INT32_MIN;
    s_atan2[1][1] = INT32_MIN;
    for (j = 0u; j < 4u; j++) {
        s_solve4[0].a[4u + j] = s_solve4[0].a[j];   /* two equal rows */
    }
}

static void bench_fill(void)
{
    /* Format triples of the kind the modules use (spec 00 §2: signals sit around q14..q30). */
    static const uint32_t fmt[4][3] = {
        { 24u, 24u, 24u }, { 30u, 24u, 24u }, { 29u, 14u, 20u }, { 16u, 20u, 24u }
    };
    uint32_t i;
    uint32_t j;

    for (i = 0u; i < BENCH_SAMPLES; i++) {
        const uint32_t *f = fmt[i % 4u];
        s_mul[i].a = bench_i32_mag();
        s_mul[i].b = bench_i32_mag();
        s_mul[i].qa = f[0];
        s_mul[i].qb = f[1];
        s_mul[i].qr = f[2];
        s_div[i].a = bench_i32_mag();
        s_div[i].b = bench_i32_mag();
        s_div[i].qa = f[0];
        s_div[i].qb = f[1];
        s_div[i].qr = f[2];
        s_sqrt[i] = bench_i32_mag();
        s_sqrt[i] = (s_sqrt[i] < 0) ? -s_sqrt[i] : s_sqrt[i];
        s_sqrt_q[i] = f[1];
        s_isqrt[i] = bench_rng() >> (bench_u32() % 64u);
        for (j = 0u; j < 3u; j++) {
            s_norm3[i][j] = bench_i32_mag();
        }
        s_sincos[i] = bench_u32();
        s_atan2[i][0] = bench_i32_mag();
        s_atan2[i][1] = bench_i32_mag();
        for (j = 0u; j < 6u; j++) {
            s_dot[i][0][j] = bench_i32_range(SH_Q24_8);
            s_dot[i][1][j] = bench_i32_range(SH_Q24_8);
            s_matvec_x[i][j] = bench_i32_range(SH_Q24_4);
        }
        for (j = 0u; j < 36u; j++) {
            s_matvec_m[i][j] = bench_i32_range(SH_Q24_4);
        }
        for (j = 0u; j < 16u; j++) {
            s_matmul[i][0][j] = bench_i32_range(SH_Q24_2);
            s_matmul[i][1][j] = bench_i32_range(SH_Q24_2);
        }
        bench_fill_solve(&s_solve4[i], 4u);
        bench_fill_solve(&s_solve2[i], 2u);
        for (j = 0u; j < 64u; j++) {
            s_crc[i][j] = (uint8_t)(bench_u32() & 0xFFu);
        }
    }
    bench_fill_edges();
}

/* ------------------------------------------------------------------ wrappers and null twins */

static volatile int32_t bench_sink_i;
static volatile uint32_t bench_sink_u;
static fx_status_t bench_st;   /* a static, not a local: keeps the wrappers' frames identical */
static int32_t bench_out[FX_NMAX * FX_NMAX];
static fx_solve_ws_t bench_ws;
static fx_solve_fast_ws_t bench_fws;

/* Null twins (fx_bench_asm.S): a lone `bx lr` each, with the kernels' prototypes. */
int32_t  bench_null_muldiv(int32_t a, uint32_t qa, int32_t b, uint32_t qb, uint32_t qr, fx_status_t *st);
int32_t  bench_null_sqrt(int32_t a, uint32_t qa, uint32_t qr, fx_status_t *st);
uint32_t bench_null_isqrt(uint64_t x);
int32_t  bench_null_norm3(const int32_t v[3], fx_status_t *st);
void     bench_null_sincos(uint32_t a_bam, int32_t *s_q30, int32_t *c_q30);
uint32_t bench_null_atan2(int32_t y, int32_t x, fx_status_t *st);
int32_t  bench_null_dot(const int32_t *a, uint32_t qa, const int32_t *b, uint32_t qb, uint32_t n,
                        uint32_t qr, fx_status_t *st);
void     bench_null_matvec(const int32_t *m, uint32_t qm, const int32_t *x, uint32_t qx,
                           uint32_t rows, uint32_t cols, int32_t *y, uint32_t qy, fx_status_t *st);
void     bench_null_matmul(const int32_t *a, uint32_t qa, const int32_t *b, uint32_t qb,
                           uint32_t n, uint32_t k, uint32_t m, int32_t *c, uint32_t qc, fx_status_t *st);
void     bench_null_solve(fx_solve_ws_t *ws, const int32_t *a, uint32_t qa, const int32_t *b, uint32_t qb,
                          uint32_t n, int32_t *x, uint32_t qx, int32_t pivot_min, fx_status_t *st);
void     bench_null_fsolve(fx_solve_fast_ws_t *ws, const int32_t *a, uint32_t qa, const int32_t *b, uint32_t qb,
                           uint32_t n, int32_t *x, uint32_t qx, int32_t pivot_min, fx_status_t *st);
uint32_t bench_null_crc(uint32_t crc, const uint8_t *data, size_t len);

/* One body per kernel, two callees: a twin differs from its wrapper only in the call target. */
#define W_MULDIV(F, S, i) do { bench_st = 0u; \
        bench_sink_i = (F)((S)[i].a, (S)[i].qa, (S)[i].b, (S)[i].qb, (S)[i].qr, &bench_st); \
        bench_sink_u = bench_st; } while (0)
#define W_SQRT(F, i) do { bench_st = 0u; \
        bench_sink_i = (F)(s_sqrt[i], s_sqrt_q[i], s_sqrt_q[i], &bench_st); bench_sink_u = bench_st; } while (0)
#define W_NORM3(F, i) do { bench_st = 0u; \
        bench_sink_i = (F)(s_norm3[i], &bench_st); bench_sink_u = bench_st; } while (0)
#define W_ATAN2(F, i) do { bench_st = 0u; \
        bench_sink_u = (F)(s_atan2[i][0], s_atan2[i][1], &bench_st); bench_sink_i = (int32_t)bench_st; } while (0)
#define W_DOT(F, i) do { bench_st = 0u; \
        bench_sink_i = (F)(s_dot[i][0], 24u, s_dot[i][1], 24u, 6u, 24u, &bench_st); bench_sink_u = bench_st; } while (0)
#define W_MATVEC(F, i) do { bench_st = 0u; \
        (F)(s_matvec_m[i], 24u, s_matvec_x[i], 24u, 6u, 6u, bench_out, 24u, &bench_st); \
        bench_sink_u = bench_st; } while (0)
#define W_MATMUL(F, i) do { bench_st = 0u; \
        (F)(s_matmul[i][0], 24u, s_matmul[i][1], 24u, 4u, 4u, 4u, bench_out, 24u, &bench_st); \
        bench_sink_u = bench_st; } while (0)
#define W_SOLVE(F, S, i) do { bench_st = 0u; \
        (F)(&bench_ws, (S)[i].a, 24u, (S)[i].b, 24u, (S)[i].n, bench_out, 24u, PIVOT_MIN_Q24, &bench_st); \
        bench_sink_u = bench_st; } while (0)
#define W_FSOLVE(F, S, i) do { bench_st = 0u; \
        (F)(&bench_fws, (S)[i].a, 24u, (S)[i].b, 24u, (S)[i].n, bench_out, 24u, PIVOT_MIN_Q24, &bench_st); \
        bench_sink_u = bench_st; } while (0)

static void bk_mul(uint32_t i)      { W_MULDIV(fx_mul, s_mul, i); }
static void bn_mul(uint32_t i)      { W_MULDIV(bench_null_muldiv, s_mul, i); }
static void bk_div(uint32_t i)      { W_MULDIV(fx_div, s_div, i); }
static void bn_div(uint32_t i)      { W_MULDIV(bench_null_muldiv, s_div, i); }
static void bk_sqrt(uint32_t i)     { W_SQRT(fx_sqrt, i); }
static void bn_sqrt(uint32_t i)     { W_SQRT(bench_null_sqrt, i); }
static void bk_isqrt(uint32_t i)    { bench_sink_u = fx_isqrt64(s_isqrt[i]); }
static void bn_isqrt(uint32_t i)    { bench_sink_u = bench_null_isqrt(s_isqrt[i]); }
static void bk_norm3(uint32_t i)    { W_NORM3(fx_norm3, i); }
static void bn_norm3(uint32_t i)    { W_NORM3(bench_null_norm3, i); }
static void bk_sincos(uint32_t i)   { fx_sincos(s_sincos[i], &bench_out[0], &bench_out[1]); }
static void bn_sincos(uint32_t i)   { bench_null_sincos(s_sincos[i], &bench_out[0], &bench_out[1]); }
static void bk_atan2(uint32_t i)    { W_ATAN2(fx_atan2_bam, i); }
static void bn_atan2(uint32_t i)    { W_ATAN2(bench_null_atan2, i); }
static void bk_dot(uint32_t i)      { W_DOT(fx_dot, i); }
static void bn_dot(uint32_t i)      { W_DOT(bench_null_dot, i); }
static void bk_matvec(uint32_t i)   { W_MATVEC(fx_matvec, i); }
static void bn_matvec(uint32_t i)   { W_MATVEC(bench_null_matvec, i); }
static void bk_matmul(uint32_t i)   { W_MATMUL(fx_matmul, i); }
static void bn_matmul(uint32_t i)   { W_MATMUL(bench_null_matmul, i); }
static void bk_solve4(uint32_t i)   { W_SOLVE(fx_solve, s_solve4, i); }
static void bn_solve4(uint32_t i)   { W_SOLVE(bench_null_solve, s_solve4, i); }
static void bk_solve2(uint32_t i)   { W_SOLVE(fx_solve, s_solve2, i); }
static void bn_solve2(uint32_t i)   { W_SOLVE(bench_null_solve, s_solve2, i); }
static void bk_fsolve4(uint32_t i)  { W_FSOLVE(fx_solve_fast, s_solve4, i); }
static void bn_fsolve4(uint32_t i)  { W_FSOLVE(bench_null_fsolve, s_solve4, i); }
static void bk_fsolve2(uint32_t i)  { W_FSOLVE(fx_solve_fast, s_solve2, i); }
static void bn_fsolve2(uint32_t i)  { W_FSOLVE(bench_null_fsolve, s_solve2, i); }
static void bk_crc(uint32_t i)      { bench_sink_u = fx_crc32(0u, s_crc[i], 64u); }
static void bn_crc(uint32_t i)      { bench_sink_u = bench_null_crc(0u, s_crc[i], 64u); }

/* Observer step on the flight table. Input: a 1 deg/s rate vector turning at the platform
   nutation frequency (50.98 rad/s, 1.0196 rad = 696952218 BAM per 20 ms step), i.e. gyro
   counts a real detumbling start looks like; both wrappers build it, so the difference is
   obs_step alone. Each bracket runs 5 consecutive steps (mean per step).
   The twin builds the same five inputs from its own copy of the stream clock (bp_obs sets it
   before each sample): when the twin advanced the filter's clock, every kernel bracket began
   with a 6-frame sequence gap, i.e. 5 predict-only steps (n_gap_max = 10), and the figure
   (82 415, then 67 203) was a mean over a gap recovery, not the nominal step. */
void bench_null_obs(obs_state_t *s, const obs_params_t *p, const obs_in_t *in, obs_out_t *out);
static obs_state_t s_obs;
static obs_out_t s_obs_out;
static uint32_t s_obs_seq;        /* the synthetic stream's clock (the filter sees this one) */
static uint32_t s_obs_seq_twin;   /* the twin's copy, reset to s_obs_seq by bp_obs */
static obs_in_t obs_next(uint32_t *clk)
{
    obs_in_t in;
    int32_t sn;
    int32_t cs;
    fx_status_t st = 0u;
    (*clk)++;
    fx_sincos(*clk * 696952218u, &sn, &cs);
    in.seq = *clk;
    in.gyro_cnt[0] = (int32_t)fx_shr_rnd64((int64_t)18301 * cs, 30u, &st);   /* 1 deg/s in 2^-20 rad/s */
    in.gyro_cnt[1] = (int32_t)fx_shr_rnd64((int64_t)18301 * sn, 30u, &st);
    in.stale = 0u;
    in.sat = 0u;
    return in;
}
static void bk_obs(uint32_t i)
{
    obs_in_t in = obs_next(&s_obs_seq);
    (void)i;
    obs_step(&s_obs, &OBS_TBL_50HZ_PHYS, &in, &s_obs_out);
}
static void bn_obs(uint32_t i)
{
    obs_in_t in = obs_next(&s_obs_seq_twin);
    (void)i;
    bench_null_obs(&s_obs, &OBS_TBL_50HZ_PHYS, &in, &s_obs_out);
}
static void bp_obs(uint32_t i)
{
    (void)i;
    s_obs_seq_twin = s_obs_seq;
}

/* ------------------------------------------------------------------ impulse scheduler (spec 50) */

#define IMP_B_STEPS    10550u        /* T = 1055 s at the table's 0.1 s tick (the example's horizon) */
#define IMP_B_NHARD    8u
#define IMP_B_POS_HALF 5000000u      /* nominal box: +-5 km in 1 mm counts */
#define IMP_B_VEL_HALF 100000u       /* +-1 m/s in 10 um/s counts */
#define IMP_B_SIG_MAX  1181116006u   /* 2.2 rad in q29 (trig inputs) */

static imp_ws_t s_imp_ws;
static imp_solution_t s_imp_sol;
static imp_round_t s_imp_rd;
static imp_problem_t s_imp_ex;
static imp_problem_t s_imp_nom[BENCH_SAMPLES];
static imp_problem_t s_imp_hard[IMP_B_NHARD];
static uint8_t s_imp_pat[BENCH_SAMPLES][IMP_NSUB];   /* accepted pattern per subsystem (local bits) */
static int32_t s_imp_sig[BENCH_SAMPLES];
static int32_t s_imp_t1[2];                          /* attempt start (0, tau_f) */
static int32_t s_imp_t2[2];
static imp_params_t s_imp_p0;                        /* table with max_iter 0 */
static imp_params_t s_imp_p1;                        /* table with max_iter 1 */
static imp_params_t s_imp_pr0;                       /* table with r_tol 0 */
static uint32_t s_imp_iters;
static uint32_t s_imp_fres;
static imp_trig_t s_imp_trig;

/* Nav counts -> problem, with the table's scales (as imp.c's counts_to_state / steps_to_tau).
   Every field starts from zero (a START plan: no warm start, not a re-plan, all thrusters, and
   whatever fields imp.h adds later), then horizon, state and the table's thrust factors. */
static void imp_b_problem(imp_problem_t *pr, const int32_t *cnt)
{
    static const imp_problem_t zero = {0};   /* zero-initialised */
    const imp_params_t *p = &IMP_TBL_DEFAULT;
    fx_status_t st = 0u;
    uint32_t i;

    *pr = zero;
    pr->tauf_q29 = fx_rshift_sat((int64_t)IMP_B_STEPS * (int64_t)p->k_tau_m, p->k_tau_sh, &st);
    for (i = 0u; i < IMP_NX; i++) {
        pr->x0_q28[i] = ((i % 2u) == 0u) ? fx_from_count(cnt[i], p->k_pos_m, p->k_pos_sh, 0, &st)
                                         : fx_from_count(cnt[i], p->k_vel_m, p->k_vel_sh, 0, &st);
        pr->alpha_q30[i] = p->alpha_q30[i];
    }
    bench_sink_u = st;
}

static void imp_b_fill(void)
{
    /* The paper's example (spec 50 §3.4): (5000 m, -1 m/s, 4000 m, -1 m/s, 4000 m, -1 m/s). */
    static const int32_t imp_ex_cnt[6] = { 5000000, -100000, 4000000, -100000, 4000000, -100000 };

    /* Hard states (x mm, x' 10 um/s, y, y', z, z'): the 8 wide-box samples with the most Newton
       iterations in `python -m tools.impulse mc --box wide --n 20000 --seed 1` (indices 10833, 11903,
       17514, 18632, 18279, 14510, 3352, 639). Each tries all 16 x-y and all 4 z patterns; all end
       NO_SOLUTION except 3352 (z by search); 115-131 iterations per plan. */
    static const int32_t imp_hard_cnt[IMP_B_NHARD][6] = {
        { -12181513, -185765, 8838026, -430571, 14990051, -362879 },
        { -11333225, -263614, 7623191, -298395, -15244169, 419758 },
        { 5519283, -192526, -8797119, -415941, -15158082, 432694 },
        { -5388079, -69182, 9872606, 186689, -13467093, 60167 },
        { -11051604, -306469, 8736599, -482792, 13821770, -192210 },
        { -7194759, -393804, 7649026, -20424, -15622763, 316625 },
        { -13579218, -384520, 76533, 392088, -10288477, 465371 },
        { -3550354, 182274, 9608917, 227431, 12268150, 138981 },
    };
    int32_t cnt[6];
    uint32_t i;
    uint32_t j;

    s_imp_p0 = IMP_TBL_DEFAULT;
    s_imp_p0.max_iter = 0u;
    s_imp_p1 = IMP_TBL_DEFAULT;
    s_imp_p1.max_iter = 1u;
    s_imp_pr0 = IMP_TBL_DEFAULT;
    s_imp_pr0.r_tol_lsb = 0;
    imp_b_problem(&s_imp_ex, imp_ex_cnt);
    for (i = 0u; i < IMP_B_NHARD; i++) {
        imp_b_problem(&s_imp_hard[i], imp_hard_cnt[i]);
    }
    for (i = 0u; i < BENCH_SAMPLES; i++) {
        for (j = 0u; j < IMP_NX; j++) {
            uint32_t half = ((j % 2u) == 0u) ? IMP_B_POS_HALF : IMP_B_VEL_HALF;
            uint32_t r = bench_u32() % ((2u * half) + 1u);
            cnt[j] = (int32_t)r - (int32_t)half;
        }
        imp_b_problem(&s_imp_nom[i], cnt);
        /* the accepted polarities (every nominal state is solved, spec 50 §3.5) */
        imp_solve(&s_imp_ws, &IMP_TBL_DEFAULT, &s_imp_nom[i], &s_imp_sol);
        s_imp_pat[i][IMP_SUB_XY] = (uint8_t)(s_imp_sol.pattern & 0x0Fu);
        {
            uint32_t zpat = ((uint32_t)s_imp_sol.pattern >> 4) & 0x03u;
            s_imp_pat[i][IMP_SUB_Z] = (uint8_t)zpat;
        }
        {
            uint32_t sig = bench_u32() % IMP_B_SIG_MAX;
            s_imp_sig[i] = (int32_t)sig;
        }
    }
    s_imp_t1[0] = 0;
    s_imp_t1[1] = 0;
    s_imp_t2[0] = s_imp_ex.tauf_q29;
    s_imp_t2[1] = s_imp_ex.tauf_q29;
}

void bench_null_imp_solve(imp_ws_t *ws, const imp_params_t *p, const imp_problem_t *pr, imp_solution_t *sol);
uint32_t bench_null_imp_attempt(imp_ws_t *ws, const imp_params_t *p, const imp_problem_t *pr, uint32_t sub,
                                uint32_t pat, const int32_t *t1_q29, const int32_t *t2_q29, uint32_t *iters,
                                uint32_t *fres_lsb, fx_status_t *ast);
void bench_null_imp_trig(int32_t sig_q29, imp_trig_t *t, fx_status_t *st);
void bench_null_imp_vec(uint32_t axis, int32_t sig_q29, const imp_trig_t *t, int32_t *v_q28, fx_status_t *st);
void bench_null_imp_round(imp_ws_t *ws, const imp_params_t *p, const imp_problem_t *pr, const imp_solution_t *sol,
                          uint32_t n_total, imp_round_t *rd, fx_status_t *st);

#define W_IMP_SOLVE(F, P, PR) do { (F)(&s_imp_ws, (P), (PR), &s_imp_sol); \
        bench_sink_u = s_imp_sol.iters_total; } while (0)
#define W_IMP_ATT(F, P, SUB, i) do { bench_st = 0u; \
        bench_sink_u = (F)(&s_imp_ws, (P), &s_imp_nom[i], (SUB), s_imp_pat[i][SUB], s_imp_t1, s_imp_t2, \
                           &s_imp_iters, &s_imp_fres, &bench_st); } while (0)
#define W_IMP_TRIG(F, i) do { bench_st = 0u; \
        (F)(s_imp_sig[i], &s_imp_trig, &bench_st); bench_sink_u = bench_st; } while (0)
#define W_IMP_ROUND(F, i) do { bench_st = 0u; \
        (F)(&s_imp_ws, &IMP_TBL_DEFAULT, &s_imp_nom[i], &s_imp_sol, IMP_B_STEPS, &s_imp_rd, &bench_st); \
        bench_sink_u = bench_st; } while (0)

static void bk_imp_ex(uint32_t i)     { (void)i; W_IMP_SOLVE(imp_solve, &IMP_TBL_DEFAULT, &s_imp_ex); }
static void bn_imp_ex(uint32_t i)     { (void)i; W_IMP_SOLVE(bench_null_imp_solve, &IMP_TBL_DEFAULT, &s_imp_ex); }
static void bk_imp_nom(uint32_t i)    { W_IMP_SOLVE(imp_solve, &IMP_TBL_DEFAULT, &s_imp_nom[i]); }
static void bn_imp_nom(uint32_t i)    { W_IMP_SOLVE(bench_null_imp_solve, &IMP_TBL_DEFAULT, &s_imp_nom[i]); }
static void bk_imp_hard(uint32_t i)   { W_IMP_SOLVE(imp_solve, &IMP_TBL_DEFAULT, &s_imp_hard[i]); }
static void bn_imp_hard(uint32_t i)   { W_IMP_SOLVE(bench_null_imp_solve, &IMP_TBL_DEFAULT, &s_imp_hard[i]); }
static void bk_imp_hard0(uint32_t i)  { W_IMP_SOLVE(imp_solve, &s_imp_pr0, &s_imp_hard[i]); }
static void bn_imp_hard0(uint32_t i)  { W_IMP_SOLVE(bench_null_imp_solve, &s_imp_pr0, &s_imp_hard[i]); }
static void bk_imp_xy0(uint32_t i)    { W_IMP_ATT(imp_attempt, &s_imp_p0, IMP_SUB_XY, i); }
static void bn_imp_xy0(uint32_t i)    { W_IMP_ATT(bench_null_imp_attempt, &s_imp_p0, IMP_SUB_XY, i); }
static void bk_imp_xy1(uint32_t i)    { W_IMP_ATT(imp_attempt, &s_imp_p1, IMP_SUB_XY, i); }
static void bn_imp_xy1(uint32_t i)    { W_IMP_ATT(bench_null_imp_attempt, &s_imp_p1, IMP_SUB_XY, i); }
static void bk_imp_z0(uint32_t i)     { W_IMP_ATT(imp_attempt, &s_imp_p0, IMP_SUB_Z, i); }
static void bn_imp_z0(uint32_t i)     { W_IMP_ATT(bench_null_imp_attempt, &s_imp_p0, IMP_SUB_Z, i); }
static void bk_imp_z1(uint32_t i)     { W_IMP_ATT(imp_attempt, &s_imp_p1, IMP_SUB_Z, i); }
static void bn_imp_z1(uint32_t i)     { W_IMP_ATT(bench_null_imp_attempt, &s_imp_p1, IMP_SUB_Z, i); }
static void bk_imp_trig(uint32_t i)   { W_IMP_TRIG(imp_trig, i); }
static void bn_imp_trig(uint32_t i)   { W_IMP_TRIG(bench_null_imp_trig, i); }
static void bk_imp_round(uint32_t i)  { W_IMP_ROUND(imp_round_best, i); }
static void bn_imp_round(uint32_t i)  { W_IMP_ROUND(bench_null_imp_round, i); }
#define W_IMP_VEC(F, i) do { bench_st = 0u; \
        (F)(0u, s_imp_sig[i], &s_imp_trig, bench_out, &bench_st); bench_sink_u = bench_st; } while (0)
static void bk_imp_psi(uint32_t i)    { W_IMP_VEC(imp_psi, i); }
static void bk_imp_phie(uint32_t i)   { W_IMP_VEC(imp_phie, i); }
static void bn_imp_vec(uint32_t i)    { W_IMP_VEC(bench_null_imp_vec, i); }
/* Outside the bracket: the derived trig that imp_psi / imp_phie take. */
static void bp_imp_trig(uint32_t i)   { fx_status_t st = 0u; imp_trig(s_imp_sig[i], &s_imp_trig, &st); }
/* Outside the bracket: the solve whose workspace imp_round_best needs. */
static void bp_imp_round(uint32_t i)  { imp_solve(&s_imp_ws, &IMP_TBL_DEFAULT, &s_imp_nom[i], &s_imp_sol); }

/* imp_step (spec 50 §4.7: a step with no planning work <= 1 500). Prep (outside every bracket):
   START at step 0 on the paper's example with t0 = IMP_B_T0 (the earliest START allows) and
   t_f = t0 + IMP_B_STEPS, then steps up to IMP_B_K - 1 with a nav sample every 10 steps (1 Hz at
   the 0.1 s tick). The samples repeat the START counts: each passes the outlier gate (the 1 s drift
   and burn are ~1 m / 40 mm/s, inside the gate plus allowance) and none reaches a monitor
   window's end, so the measured step sees an accepted history, the plan done long before
   (mode FIRING, 2.6 s into the first burns, 3 logged burn segments) and no re-plan epoch. Each
   bracketed call restores that state first (the twin does the same copy), so all five calls
   run the same step IMP_B_K: `imp_step_idle` without a new sample (timeline, windows, gates,
   monitor bookkeeping), `imp_step_nav` with a new sample (prediction through the logged burns,
   outlier gate, acceptance, monitor window). */
#define IMP_B_T0       50u            /* START at step 0: t0 >= plan_lead */
#define IMP_B_K        76u            /* the measured step */

static imp_state_t s_imp_st0;         /* state after step IMP_B_K - 1 */
static imp_state_t s_imp_st;
static imp_out_t s_imp_out;
static imp_in_t s_imp_in_idle;
static imp_in_t s_imp_in_nav;

void bench_null_imp_step(imp_state_t *s, const imp_params_t *p, const imp_in_t *in, imp_out_t *out);

static void imp_b_step_fill(void)
{
    static const int32_t imp_ex_cnt[6] = { 5000000, -100000, 4000000, -100000, 4000000, -100000 };
    static const imp_in_t zero = {0};
    imp_in_t in = zero;
    uint32_t r;
    uint32_t k;

    (void)imp_init(&s_imp_st0, &IMP_TBL_DEFAULT, &s_imp_out);
    in.cmd = IMP_CMD_START;
    in.cmd_t0_step = IMP_B_T0;
    in.cmd_tf_step = IMP_B_T0 + IMP_B_STEPS;
    in.nav_valid = 1u;
    in.avail_mask = 0x3Fu;
    for (r = 0u; r < IMP_NAX; r++) {
        in.nav_pos_mm[r] = imp_ex_cnt[2u * r];
        in.nav_vel_cnt[r] = imp_ex_cnt[(2u * r) + 1u];
    }
    for (k = 0u; k < IMP_B_K; k++) {
        in.step = k;
        in.nav_step = (k / 10u) * 10u;
        imp_step(&s_imp_st0, &IMP_TBL_DEFAULT, &in, &s_imp_out);
        in.cmd = IMP_CMD_NONE;
    }
    in.step = IMP_B_K;
    s_imp_in_idle = in;               /* latest sample already seen */
    in.nav_step = IMP_B_K;
    s_imp_in_nav = in;                /* a new sample */
}

#define W_IMP_STEP(F, IN) do { s_imp_st = s_imp_st0; (F)(&s_imp_st, &IMP_TBL_DEFAULT, (IN), &s_imp_out); \
        bench_sink_u = s_imp_out.health; } while (0)
static void bk_imp_step0(uint32_t i)  { (void)i; W_IMP_STEP(imp_step, &s_imp_in_idle); }
static void bn_imp_step0(uint32_t i)  { (void)i; W_IMP_STEP(bench_null_imp_step, &s_imp_in_idle); }
static void bk_imp_step1(uint32_t i)  { (void)i; W_IMP_STEP(imp_step, &s_imp_in_nav); }
static void bn_imp_step1(uint32_t i)  { (void)i; W_IMP_STEP(bench_null_imp_step, &s_imp_in_nav); }

static void bench_empty(uint32_t i)
{
    (void)i;
}

typedef struct {
    const char *name;
    bench_fn_t kernel;
    bench_fn_t twin;
    bench_fn_t prep;      /* run before each sample's brackets (not measured), or NULL */
    uint32_t samples;     /* samples 0..samples-1 (<= BENCH_SAMPLES) */
    uint32_t imp_info;    /* 1: print the imp_solve solution summary after the sample */
} bench_kernel_t;

/* ------------------------------------------------------------------ main */

int main(void)
{
    static const bench_kernel_t kernels[] = {
        { "fx_mul", bk_mul, bn_mul, NULL, BENCH_SAMPLES, 0u },
        { "fx_div", bk_div, bn_div, NULL, BENCH_SAMPLES, 0u },
        { "fx_sqrt", bk_sqrt, bn_sqrt, NULL, BENCH_SAMPLES, 0u },
        { "fx_isqrt64", bk_isqrt, bn_isqrt, NULL, BENCH_SAMPLES, 0u },
        { "fx_norm3", bk_norm3, bn_norm3, NULL, BENCH_SAMPLES, 0u },
        { "fx_sincos", bk_sincos, bn_sincos, NULL, BENCH_SAMPLES, 0u },
        { "fx_atan2_bam", bk_atan2, bn_atan2, NULL, BENCH_SAMPLES, 0u },
        { "fx_dot_n6", bk_dot, bn_dot, NULL, BENCH_SAMPLES, 0u },
        { "fx_matvec_6x6", bk_matvec, bn_matvec, NULL, BENCH_SAMPLES, 0u },
        { "fx_matmul_4x4", bk_matmul, bn_matmul, NULL, BENCH_SAMPLES, 0u },
        { "fx_solve_n4", bk_solve4, bn_solve4, NULL, BENCH_SAMPLES, 0u },
        { "fx_solve_n2", bk_solve2, bn_solve2, NULL, BENCH_SAMPLES, 0u },
        { "fx_solve_fast_n4", bk_fsolve4, bn_fsolve4, NULL, BENCH_SAMPLES, 0u },
        { "fx_solve_fast_n2", bk_fsolve2, bn_fsolve2, NULL, BENCH_SAMPLES, 0u },
        { "fx_crc32_64B", bk_crc, bn_crc, NULL, BENCH_SAMPLES, 0u },
        { "obs_step_50hz_phys", bk_obs, bn_obs, bp_obs, BENCH_SAMPLES, 0u },
        { "imp_trig", bk_imp_trig, bn_imp_trig, NULL, BENCH_SAMPLES, 0u },
        { "imp_psi_x", bk_imp_psi, bn_imp_vec, bp_imp_trig, BENCH_SAMPLES, 0u },
        { "imp_phie_x", bk_imp_phie, bn_imp_vec, bp_imp_trig, BENCH_SAMPLES, 0u },
        { "imp_attempt_xy_max0", bk_imp_xy0, bn_imp_xy0, NULL, BENCH_SAMPLES, 0u },
        { "imp_attempt_xy_max1", bk_imp_xy1, bn_imp_xy1, NULL, BENCH_SAMPLES, 0u },
        { "imp_attempt_z_max0", bk_imp_z0, bn_imp_z0, NULL, BENCH_SAMPLES, 0u },
        { "imp_attempt_z_max1", bk_imp_z1, bn_imp_z1, NULL, BENCH_SAMPLES, 0u },
        { "imp_solve_example", bk_imp_ex, bn_imp_ex, NULL, 4u, 1u },
        { "imp_solve_nominal", bk_imp_nom, bn_imp_nom, NULL, BENCH_SAMPLES, 1u },
        { "imp_round_best_nominal", bk_imp_round, bn_imp_round, bp_imp_round, BENCH_SAMPLES, 0u },
        { "imp_solve_search_all", bk_imp_hard, bn_imp_hard, NULL, IMP_B_NHARD, 1u },
        { "imp_solve_search_all_rtol0", bk_imp_hard0, bn_imp_hard0, NULL, IMP_B_NHARD, 1u },
        { "imp_step_idle", bk_imp_step0, bn_imp_step0, NULL, 1u, 0u },
        { "imp_step_nav", bk_imp_step1, bn_imp_step1, NULL, 1u, 0u },
    };
    size_t k;
    uint32_t i;
    uint32_t empty = bench_bracket5(bench_empty, 0u);

    board_console_write("fx_bench 1 cpuid ");
    board_console_hex(*board_reg32(BENCH_CPUID));
    board_console_write("\n");
    bench_calibrate();
    board_console_write("empty ");
    bench_put_u32(empty);
    board_console_write("\n");
    bench_fill();
    imp_b_fill();
    imp_b_step_fill();
    (void)obs_init(&s_obs, &OBS_TBL_50HZ_PHYS, &s_obs_out);
    for (i = 0u; i < 10u; i++) {
        bk_obs(i);   /* initialise the filter; measure steady-state steps */
    }
    for (k = 0u; k < (sizeof(kernels) / sizeof(kernels[0])); k++) {
        const bench_kernel_t *bk = &kernels[k];
        for (i = 0u; i < bk->samples; i++) {
            bench_fn_t fk = bk->kernel;
            bench_fn_t fn = bk->twin;
            uint32_t wk;
            uint32_t wn;
            if (bk->prep != NULL) {
                bk->prep(i);
            }
            wk = bench_bracket5(fk, i);
            wn = bench_bracket5(fn, i);
            board_console_write("k ");
            board_console_write(bk->name);
            board_console_write(" ");
            bench_put_u32(i);
            board_console_write(" ");
            bench_put_i32((int32_t)wk - (int32_t)wn + 1);
            board_console_write(" ");
            bench_put_i32((int32_t)wk - (int32_t)empty);
            board_console_write("\n");
            if (bk->imp_info != 0u) {
                /* s_imp_sol is the kernel's (the twin calls a null function) */
                board_console_write("imp ");
                board_console_write(bk->name);
                board_console_write(" ");
                bench_put_u32(i);
                board_console_write(" ");
                bench_put_u32(s_imp_sol.iters_total);
                board_console_write(" ");
                bench_put_u32(s_imp_sol.outcome);
                board_console_write(" ");
                bench_put_u32(s_imp_sol.how[IMP_SUB_XY]);
                board_console_write(" ");
                bench_put_u32(s_imp_sol.how[IMP_SUB_Z]);
                board_console_write(" ");
                bench_put_u32(s_imp_sol.pattern);
                board_console_write("\n");
            }
        }
    }
    board_console_write("end\n");
    return 0;
}
