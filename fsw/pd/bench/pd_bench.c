/*
 * pd_bench.c — instructions per pd_step, pd_mis_step and pd_sched_k2 on the emulated Cortex-M
 * (spec 00 §6.4, §9; spec 40). Built by fsw/target/CMakeLists.txt as pd_bench (the loop over the
 * mission modules), run by `python -m tools.bench.module_insn <BUILD_DIR>... --module pd` under
 * QEMU -icount shift=3.
 *
 * Open loop: the attitude is synthetic, y = 0.017 rad (the §4.1 step, the largest |y| of §5's value
 * ranges) + a triangle of +-4.9e-4 rad over 1024 samples + uniform noise of +-3.1e-5 rad (xorshift32,
 * fixed seed), as counts of 2^-26 rad; the gimbal encoder 0.2 rad +-3.9e-3 rad (below beta_warn), as
 * counts of 2^-24 rad. No floating point: every input is an integer count, every f a uq32 Hz. The
 * channel is pitch (pd_params_of(&tbl, 2u, &p)) of the boot tables PD_TBL_DEFAULT (FAST),
 * PD_TBL_LITERAL and PD_TBL_AVGP; pd_params_check must accept each.
 *   FAST       PD_B_FAST_N samples. The first half flies the boot source FIXED; in every block of 64
 *              samples one missing sample (hold), a run of three (hold, coast, coast), a rate spike
 *              (+2^-5 rad), an out-of-range count (0.6 rad) and a count with the sensor's saturation
 *              bit are refused or missing (at most 3 invalid per control period: no period is bad).
 *              The second half flies GROUND: every 16th sample first gets a new commanded f (uq32,
 *              uniform in [0, 0.125) Hz, redrawn until the scheduled k2 differs from the one in use),
 *              as SET_F does (pd_set_f_ground + pd_set_source outside the bracket), so that sample
 *              re-tunes (schedule lookup + gains); the others keep f (GROUND still looks the
 *              schedule up on every sample: class fast_ground).
 *   LITERAL, FAST_AVGP   PD_B_AVG_N valid samples each: ordinary and period-boundary samples.
 *   mission    pd_mis_step of a pd_mis_t loaded with the encoded PD_TBL_DEFAULT through
 *              pd_mis_check / pd_mis_load and entered (pd_mis_enter): three valid channels per step,
 *              seq + 1 each step (n_div 1: every step is a sample), no telecommand. Then, from the
 *              run's last state (not advanced), one step whose seq jumped by 1 + G for each gap G of
 *              PD_B_GAPS: pd_note_gap on every channel before its sample (class mis_gap, sub G).
 *   schedule   pd_sched_k2 alone (pitch, PD_TBL_DEFAULT) at PD_B_SCHED_N + 1 f on a uniform grid
 *              over [0, 0.2] Hz.
 *
 * Exact counts although the steps mutate their state (relay bench, fsw/relay/bench/rly_bench.c):
 * every sample first runs one step on a copy (s_swork = s_slive) to classify it; a sample to be
 * measured is then bracketed with bench_bracket5 by a wrapper that restores the copy before each
 * call, so the five calls are identical (pd has no globals: a step is a function of state, params
 * and input), and by its twin, which does the same copy and calls a null function instead:
 *   insns = bracket5(wrapper) - bracket5(twin) + 1   from the function's entry through its return.
 * pd_sched_k2 is pure: its wrapper only stores the result. Each measured sample is also bracketed
 * once with bench_bracket1 (a single call, +-4 instructions whatever the tick phase): an err line if
 * it disagrees with bracket5.
 * Each sample's class is intended by the generator and checked on the classification step (its
 * health word, counters and state): a sample that is not of its class prints an err line and is
 * not measured.
 *
 * Output (the module bench protocol of tools/bench/module_insn.py, see bench_common.h):
 *   bench pd 1 cpuid <hex>
 *   cal ... / tick ...            calibration (bench_common.c)
 *   class <name> <text>           the sample classes, in report order
 *   twin <value> 0                bracket5 of pd_step's twin (constant, else an err line); the
 *                                 twins of pd_sched_k2 and pd_mis_step are the sums twin_sched, twin_mis
 *   m <class> <sub> <insns> <k>   one measured call, k the sample (or grid) index of its run
 *   sum <key> <value>             sizes of the pd types, run summaries
 *   err <text>                    a check failed (table refused, sample not of its class, twin not
 *                                 constant, bracket1 disagrees)
 *   end
 */
#include <stdint.h>
#include <stdbool.h>
#include <stddef.h>
#include "board.h"
#include "bench_common.h"
#include "fx.h"
#include "pd.h"
#include "pd_mission.h"
#include "pd_tables.h"

#define BENCH_CPUID     0xE000ED00u

#define PD_B_CH         2u            /* pitch */
#define PD_B_FAST_N     4096u         /* FAST samples (17 min at Ty = 0.25 s) ... */
#define PD_B_GROUND_AT  2048u         /* ... GROUND from this one on */
#define PD_B_BLOCK      64u           /* FIXED half: the fault pattern repeats every 4 periods */
#define PD_B_RETUNE_PER 16u           /* GROUND half: a new f every 16 samples */
#define PD_B_AVG_N      1024u         /* LITERAL, FAST_AVGP: 64 control periods of 16 */
#define PD_B_AD_N       1024u         /* ADAPTIVE: 64 control periods of 16 */
#define PD_B_MIS_N      512u          /* mission steps */
#define PD_B_SCHED_N    256u          /* pd_sched_k2 grid intervals over [0, 0.2] Hz */
#define PD_B_EVERY      3u            /* ordinary samples measured: one in 3 */

#define PD_B_Y0         1140851       /* 0.017 rad in 2^-26 rad (1140850.7) */
#define PD_B_Y_RANGE    40265318      /* 0.6 rad: above y_lim 0.5 rad */
#define PD_B_Y_SPIKE    2097152       /* 2^-5 rad: |dy| above dy_max 2^-6 rad */
#define PD_B_BETA0      3355443       /* 0.2 rad in 2^-24 rad */
#define PD_B_F_SPAN     536870911u    /* retune f: [0, 0.125) Hz uq32 (mask) */
#define PD_B_F_STEP     134217728u    /* 0.03125 Hz: the redraw step */
#define PD_B_F_HI       429496730u    /* 0.1 Hz uq32: the last node (from here on k2 is clamped) */
#define PD_B_F_MAX      858993459u    /* 0.2 Hz uq32 */
#define PD_B_TRIES      4u
#define PD_B_N_GAPS     11u

/* intended sample kinds */
#define PD_B_EV_ORD     0u
#define PD_B_EV_RETUNE  1u
#define PD_B_EV_MISS    2u
#define PD_B_EV_RATE    3u
#define PD_B_EV_RANGE   4u
#define PD_B_EV_SAT     5u

/* bracket kinds (twins) */
#define PD_B_K_STEP     0u
#define PD_B_K_SCHED    1u
#define PD_B_K_MIS      2u

/* Health bits that an ordinary sample must not raise (FALLBACK_GAIN and TABLE_DEFAULT may be set:
   the boot table flies k2_cold). */
#define PD_B_H_ABN (PD_H_STALE | PD_H_FROZEN | PD_H_TRQ_SAT | PD_H_BETA_WARN | PD_H_BETA_LIM | \
                    PD_H_RETUNE | PD_H_REJECT | PD_H_COAST | PD_H_PERIOD_BAD | FX_ST_MASK)

/* File-scope names differ from rly_bench.c's: cppcheck's MISRA proof sees fsw/ as one program
   (rule 5.9: internal identifiers unique; D10 covers only the several mains). */
static pd_params_t s_par;
static pd_state_t s_slive;            /* the run's state */
static pd_state_t s_swork;            /* one step ahead of s_slive */
static pd_in_t s_sin;
static pd_out_t s_sout;

static pd_mis_t s_mlive;
static pd_mis_t s_mwork;
static fsw_acc_t s_acc;
static int32_t s_act[PD_N_ACT];
static uint32_t s_mh;

static uint32_t s_f;                  /* pd_sched_k2's argument */
static uint32_t s_k2;                 /* and its result */

/* Null twins (bench_asm.S): a lone `bx lr` each, with the prototype of the function it replaces.
   Not bench_null_0: rly_bench.c declares it with rly_step's prototype, and two declarations of one
   external in two files break rule 8.5 of the whole-fsw/ MISRA proof. */
void bench_null_1(pd_state_t *s, const pd_params_t *p, const pd_in_t *in, pd_out_t *out);
uint32_t bench_null_2(const pd_params_t *p, uint32_t f_q32);
uint32_t bench_null_3(pd_mis_t *b, const fsw_acc_t *acc, int32_t *act);

static void bk_pd_step(uint32_t i)
{
    (void)i;
    s_swork = s_slive;
    pd_step(&s_swork, &s_par, &s_sin, &s_sout);
}

static void bn_pd_step(uint32_t i)
{
    (void)i;
    s_swork = s_slive;
    bench_null_1(&s_swork, &s_par, &s_sin, &s_sout);
}

static void bk_sched(uint32_t i)
{
    (void)i;
    s_k2 = pd_sched_k2(&s_par, s_f);
}

static void bn_sched(uint32_t i)
{
    (void)i;
    s_k2 = bench_null_2(&s_par, s_f);
}

static void bk_mis(uint32_t i)
{
    (void)i;
    s_mwork = s_mlive;
    s_mh = pd_mis_step(&s_mwork, &s_acc, s_act);
}

static void bn_mis(uint32_t i)
{
    (void)i;
    s_mwork = s_mlive;
    s_mh = bench_null_3(&s_mwork, &s_acc, s_act);
}

/* xorshift32 */
static uint32_t rnd(void)
{
    static uint32_t s_rng = 0x2545F491u;
    uint32_t x = s_rng;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    s_rng = x;
    return x;
}

/* Uniform in [-2048, 2047]. */
static int32_t noise(void)
{
    const uint32_t r = rnd() & 0xFFFu;
    return (int32_t)r - 2048;
}

/* Triangle of +-32768 counts over 1024 samples. */
static int32_t tri(uint32_t k)
{
    const uint32_t ph = k & 1023u;
    const uint32_t t = (ph < 512u) ? ph : (1024u - ph);
    const int32_t ts = (int32_t)t;
    return (ts * 128) - 32768;
}

static int32_t y_of(uint32_t k)
{
    return PD_B_Y0 + tri(k) + noise();
}

static int32_t beta_of(void)
{
    return PD_B_BETA0 + (noise() * 32);
}

static void pdb_put_sum(const char *key, uint32_t v)
{
    board_console_write("sum ");
    board_console_write(key);
    board_console_write(" ");
    bench_put_u32(v);
    board_console_write("\n");
}

/* "err <what> <k> health <hex>" */
static void pdb_put_err(const char *what, uint32_t k, uint32_t h)
{
    board_console_write("err ");
    board_console_write(what);
    board_console_write(" ");
    bench_put_u32(k);
    board_console_write(" health ");
    board_console_hex(h);
    board_console_write("\n");
}

/* "m <class> <sub> <insns> <k>" */
static void pdb_put_sample(const char *cls, const char *sub, int32_t insns, uint32_t k)
{
    board_console_write("m ");
    board_console_write(cls);
    board_console_write(" ");
    board_console_write(sub);
    board_console_write(" ");
    bench_put_i32(insns);
    board_console_write(" ");
    bench_put_u32(k);
    board_console_write("\n");
}

static void pdb_put_classes(void)
{
    board_console_write("class fast_ordinary FAST valid sample, source FIXED, no gain change (every 3rd)\n");
    board_console_write("class fast_retune FAST valid sample, GROUND with a new commanded f: schedule lookup and gains (sub: f below the first node, between nodes, beyond the last)\n");
    board_console_write("class fast_missing FAST y_valid false, source FIXED: hold (first) or coast (later)\n");
    board_console_write("class fast_refused FAST sample refused, source FIXED: rate spike, range, sensor saturation bit\n");
    board_console_write("class fast_ground FAST valid sample, GROUND with f unchanged: the lookup runs but k2 stays (every 3rd)\n");
    board_console_write("class lit_ordinary LITERAL valid sample inside a control period: the held torque (every 3rd)\n");
    board_console_write("class lit_boundary LITERAL 16th sample of a period: mean and torque formation\n");
    board_console_write("class avgp_ordinary FAST_AVGP valid sample inside a period: P on the held mean, D (every 3rd)\n");
    board_console_write("class avgp_boundary FAST_AVGP 16th sample of a period: the period closes, then P on the new mean\n");
    board_console_write("class mis_ordinary pd_mis_step, three valid channels (FAST boot table), no telecommand (every 2nd)\n");
    board_console_write("class mis_gap pd_mis_step after G lost frames (seq jumped by G + 1): pd_note_gap on each channel, then the sample (sub: G)\n");
    board_console_write("class sched_k2 pd_sched_k2 alone, pitch, f on a uniform grid over [0, 0.2] Hz\n");
    board_console_write("class ad_sample ADAPTIVE (pd_adaptive, pitch) valid sample inside a Td block: law + estimator predictor, regressors, noise, anti-alias (every 3rd; sub: estimator state)\n");
    board_console_write("class ad_td ADAPTIVE 4th sample of a Td block, not a period end: + high-pass, gate, notch and RLS, theta RLS, frequency (sub: estimator state)\n");
    board_console_write("class ad_period ADAPTIVE 16th sample: + the estimator's period logic and the re-tune rule (sub: estimator state after it)\n");
    board_console_write("class ady_sample ADAPTIVE yaw (two notch sections) valid sample inside a Td block (every 3rd; sub: estimator state)\n");
    board_console_write("class ady_td ADAPTIVE yaw 4th sample of a Td block: + the two-section cascade and the line logic\n");
    board_console_write("class ady_period ADAPTIVE yaw 16th sample: + the period logic with the pair / single-line proofs\n");
}

/* bracket1, twin and wrapper of kind kd: the instructions of one call (the wrapper leaves the state
   of the classification behind). */
static int32_t measure(bench_fn_t fk, bench_fn_t fn, uint32_t kd, uint32_t k)
{
    static const char *const twin_key[3] = { "twin", "twin_sched", "twin_mis" };
    static uint32_t s_twin[3];
    const uint32_t t1 = bench_bracket1(fk, k);   /* one call: wrapper + 3 = 5 t1 +- 4 */
    const uint32_t wn = bench_bracket5(fn, k);
    const uint32_t wk = bench_bracket5(fk, k);
    const uint32_t t5 = 5u * t1;
    if (s_twin[kd] == 0u) {
        s_twin[kd] = wn;
        if (kd == PD_B_K_STEP) {
            bench_put_kv("twin", wn, 0u);
        } else {
            pdb_put_sum(twin_key[kd], wn);
        }
    } else if (wn != s_twin[kd]) {
        pdb_put_err(twin_key[kd], k, wn);
    } else {
        /* the twin's count is constant */
    }
    if (((t5 > wk) ? (t5 - wk) : (wk - t5)) > 4u) {
        pdb_put_err("bracket1_disagrees_with_bracket5", k, t1);
    }
    return (int32_t)wk - (int32_t)wn + 1;
}

/* The input of sample k of kind ev. */
static void make_input(uint32_t k, uint32_t ev)
{
    const int32_t y = y_of(k);
    s_sin.y_cnt = y;
    s_sin.y_valid = ev != PD_B_EV_MISS;
    s_sin.y_sat = ev == PD_B_EV_SAT;
    s_sin.beta_cnt = beta_of();
    s_sin.beta_valid = true;
    if (ev == PD_B_EV_RATE) {
        s_sin.y_cnt = y + PD_B_Y_SPIKE;
    } else if (ev == PD_B_EV_RANGE) {
        s_sin.y_cnt = PD_B_Y_RANGE + noise();
    } else {
        /* y as drawn */
    }
}

/* FAST: the kind of sample k. */
static uint32_t fast_event(uint32_t k)
{
    const uint32_t o = k % PD_B_BLOCK;
    uint32_t ev = PD_B_EV_ORD;
    if (k >= PD_B_GROUND_AT) {
        if ((k % PD_B_RETUNE_PER) == 0u) {
            ev = PD_B_EV_RETUNE;
        }
    } else if ((o == 20u) || (o == 36u) || (o == 37u) || (o == 38u)) {
        ev = PD_B_EV_MISS;
    } else if (o == 52u) {
        ev = PD_B_EV_RATE;
    } else if (o == 58u) {
        ev = PD_B_EV_RANGE;
    } else if (o == 61u) {
        ev = PD_B_EV_SAT;
    } else {
        /* ordinary */
    }
    return ev;
}

static const char *f_region(uint32_t f)
{
    const char *r = "mid";
    if (f <= s_par.c.f0_q32) {
        r = "lo";
    } else if (f >= PD_B_F_HI) {
        r = "hi";
    } else {
        /* between the nodes */
    }
    return r;
}

/* A commanded f whose scheduled k2 differs from the one in use (0 tries left: the last draw). */
static uint32_t retune_f(void)
{
    uint32_t f = rnd() & PD_B_F_SPAN;
    uint32_t i;
    for (i = 0u; i < PD_B_TRIES; i++) {
        if (pd_sched_k2(&s_par, f) == s_slive.k2_q22) {
            f = (f + PD_B_F_STEP) & PD_B_F_SPAN;
        }
    }
    return f;
}

/* Sub-class of an ordinary FAST sample: first after a restart of the difference, and/or the
   period's last sample. */
static const char *ord_sub(void)
{
    static const char *const sub[4] = { "plain", "restart", "pend", "pend+restart" };
    uint32_t i = 0u;
    if (!s_slive.have_prev) {
        i |= 1u;
    }
    if (s_swork.nu == 0u) {
        i |= 2u;
    }
    return sub[i];
}

/* Class and sub-class of the FAST step s_slive -> s_swork of kind ev; false if it is not of it. */
static bool classify_fast(uint32_t ev, const char **cls, const char **sub)
{
    const uint32_t h = s_sout.health;
    const uint32_t a = h & PD_B_H_ABN;
    const bool ground = s_slive.src == (uint8_t)PD_SRC_GROUND;
    bool ok = false;
    if (ev == PD_B_EV_ORD) {
        *cls = ground ? "fast_ground" : "fast_ordinary";
        *sub = ord_sub();
        ok = (a == 0u) && (s_swork.k2_q22 == s_slive.k2_q22);
    } else if (ev == PD_B_EV_RETUNE) {
        *cls = "fast_retune";
        *sub = f_region(s_slive.f_ground_q32);
        ok = ground && (a == PD_H_RETUNE) && (s_swork.k2_q22 != s_slive.k2_q22);
    } else if (ev == PD_B_EV_MISS) {
        *cls = "fast_missing";
        if ((h & PD_H_COAST) != 0u) {
            *sub = "coast";
            ok = (a == (PD_H_STALE | PD_H_COAST)) && (s_sout.m_q28 == 0);
        } else {
            *sub = "hold";
            ok = (a == PD_H_STALE) && (s_sout.m_q28 == s_slive.m_last_q28);
        }
        ok = ok && (s_swork.tlm.miss_cnt == (s_slive.tlm.miss_cnt + 1u));
    } else {
        *cls = "fast_refused";
        if (ev == PD_B_EV_RATE) {
            *sub = "rate";
            ok = s_swork.tlm.rate_rej == (s_slive.tlm.rate_rej + 1u);
        } else {
            *sub = (ev == PD_B_EV_SAT) ? "sat" : "range";
            ok = s_swork.tlm.range_rej == (s_slive.tlm.range_rej + 1u);
        }
        ok = ok && (a == (PD_H_STALE | PD_H_REJECT));
    }
    return ok;
}

/* Class and sub-class of an averaged-mode step (law LITERAL or FAST_AVGP) at sample k. */
static bool classify_avg(uint32_t k, const char **cls, const char **sub)
{
    const bool lit = s_par.c.law == (uint8_t)PD_LAW_LITERAL;
    const bool bound = (k % (uint32_t)s_par.c.n_y) == ((uint32_t)s_par.c.n_y - 1u);
    const uint32_t a = s_sout.health & PD_B_H_ABN;
    bool ok = a == 0u;
    if (bound) {
        *cls = lit ? "lit_boundary" : "avgp_boundary";
        *sub = s_slive.have_xbar ? "next" : "first";
        ok = ok && (s_slive.nu == ((uint32_t)s_par.c.n_y - 1u)) && (s_swork.nu == 0u) && s_swork.have_xbar;
    } else {
        *cls = lit ? "lit_ordinary" : "avgp_ordinary";
        *sub = s_slive.have_xbar ? "mean" : "nomean";
        ok = ok && (s_swork.nu != 0u);
        if (lit) {
            ok = ok && (s_swork.m_held_q28 == s_slive.m_held_q28);
        }
    }
    return ok;
}

/* One pitch channel of tbl; err if pd_params_check refuses it. */
static void load_params_ch(const pd_table_t *tbl, uint32_t ch, const char *name)
{
    uint32_t why = 0u;
    pd_params_of(tbl, ch, &s_par);
    if (pd_params_check(&s_par, &why) != FSW_OK) {
        pdb_put_err(name, 0u, why);
    }
    pd_init(&s_slive, &s_par);
}

static void load_params(const pd_table_t *tbl, const char *name)
{
    load_params_ch(tbl, PD_B_CH, name);
}

static void run_fast(void)
{
    uint32_t n_ord = 0u;
    uint32_t n_ret = 0u;
    uint32_t k;
    load_params(&PD_TBL_DEFAULT, "table_refused_default");
    for (k = 0u; k < PD_B_FAST_N; k++) {
        const uint32_t ev = fast_event(k);
        const char *cls = "?";
        const char *sub = "?";
        if (ev == PD_B_EV_RETUNE) {
            /* SET_F's effect, before the sample (outside the bracket) */
            pd_set_f_ground(&s_slive, retune_f());
            if (!pd_set_source(&s_slive, &s_par, (uint8_t)PD_SRC_GROUND)) {
                pdb_put_err("set_source_refused", k, 0u);
            }
        }
        make_input(k, ev);
        bk_pd_step(k);   /* classify: s_swork = the step from s_slive */
        if (!classify_fast(ev, &cls, &sub)) {
            pdb_put_err(cls, k, s_sout.health);
        } else {
            if (ev == PD_B_EV_ORD) {
                n_ord++;
            } else if (ev == PD_B_EV_RETUNE) {
                n_ret++;
            } else {
                /* missing or refused */
            }
            if ((ev != PD_B_EV_ORD) || ((n_ord % PD_B_EVERY) == 1u)) {
                pdb_put_sample(cls, sub, measure(bk_pd_step, bn_pd_step, PD_B_K_STEP, k), k);
            }
        }
        s_slive = s_swork;
    }
    pdb_put_sum("fast_samples", PD_B_FAST_N);
    pdb_put_sum("fast_retunes", n_ret);
    pdb_put_sum("fast_k2_q22", s_slive.k2_q22);
    pdb_put_sum("fast_miss_cnt", s_slive.tlm.miss_cnt);
    pdb_put_sum("fast_range_rej", s_slive.tlm.range_rej);
    pdb_put_sum("fast_rate_rej", s_slive.tlm.rate_rej);
    pdb_put_sum("fast_period_rej", s_slive.tlm.period_rej);
    pdb_put_sum("fast_health_sticky", s_slive.tlm.health_sticky);
}

static void run_avg(const pd_table_t *tbl, const char *name)
{
    uint32_t n_ord = 0u;
    uint32_t k;
    load_params(tbl, name);
    for (k = 0u; k < PD_B_AVG_N; k++) {
        const char *cls = "?";
        const char *sub = "?";
        make_input(k, PD_B_EV_ORD);
        bk_pd_step(k);
        if (!classify_avg(k, &cls, &sub)) {
            pdb_put_err(cls, k, s_sout.health);
        } else {
            const bool bound = s_swork.nu == 0u;
            if (!bound) {
                n_ord++;
            }
            if (bound || ((n_ord % PD_B_EVERY) == 1u)) {
                pdb_put_sample(cls, sub, measure(bk_pd_step, bn_pd_step, PD_B_K_STEP, k), k);
            }
        }
        s_slive = s_swork;
    }
}

/* ADAPTIVE on the pitch channel of PD_TBL_ADAPTIVE, the FAST input pattern without faults. The input is
   synthetic and open loop (not the plant's response to the torque), so the estimator's states are not
   those of a flight; its arithmetic per sample does not depend on the data except in the FAULT / reset
   branches, which the sub-class (the state) separates. Class by the estimator's phase. */
static const char *ad_state(void)
{
    static const char *const names[4] = { "ACQUIRE", "TRACK", "HOLD", "FAULT" };
    return names[s_swork.fest.state & 3u];
}

/* ch: pitch (one notch section) or yaw (two sections and the line logic; its source in PD_TBL_ADAPTIVE is
   ADAPTIVE too, masked off by ch_mask in flight, which pd_params_check of the channel does not see);
   cls[3]: the class names of a sample, a Td sample and a period end */
static void run_adaptive(uint32_t ch, const char *const *cls3)
{
    uint32_t n_ord = 0u;
    uint32_t k;
    load_params_ch(&PD_TBL_ADAPTIVE, ch, "table_refused_adaptive");
    if (s_slive.src != (uint8_t)PD_SRC_ADAPTIVE) {
        pdb_put_err("adaptive_not_selected", 0u, s_slive.src);
    }
    for (k = 0u; k < PD_B_AD_N; k++) {
        const char *cls;
        bool measured;
        make_input(k, PD_B_EV_ORD);
        bk_pd_step(k);   /* classify: s_swork = the step from s_slive */
        if (s_swork.fest.period_end) {
            cls = cls3[2];
            measured = true;
        } else if (s_swork.fest.blk_n == 0u) {
            cls = cls3[1];
            measured = true;
        } else {
            cls = cls3[0];
            n_ord++;
            measured = (n_ord % PD_B_EVERY) == 1u;
        }
        if (measured) {
            pdb_put_sample(cls, ad_state(), measure(bk_pd_step, bn_pd_step, PD_B_K_STEP, k), k);
        }
        s_slive = s_swork;
    }
    if (ch == PD_B_CH) {
        pdb_put_sum("ad_samples", PD_B_AD_N);
        pdb_put_sum("ad_fest_resets", s_slive.fest.resets);
        pdb_put_sum("ad_fest_state", (uint32_t)s_slive.fest.state);
        pdb_put_sum("ad_k2_q22", s_slive.k2_q22);
    }
}

/* The mission block: the boot table encoded, checked, loaded and entered. */
static void mis_setup(void)
{
    static uint8_t s_img[FSW_TABLE_HDR_BYTES + PD_TBL_PAYLOAD];
    const uint32_t n = pd_table_encode(&PD_TBL_DEFAULT, 1u, s_img, (uint32_t)sizeof(s_img));
    const uint8_t *pl = &s_img[FSW_TABLE_HDR_BYTES];
    uint32_t i;
    pd_mis_reset(&s_mlive);
    if (n != (uint32_t)sizeof(s_img)) {
        pdb_put_err("table_encode", 0u, n);
    } else if (pd_mis_check(&s_mlive, pl, PD_TBL_PAYLOAD, PD_TBL_DEFAULT.c.period_us) != 0u) {
        pdb_put_err("table_check", 0u, 0u);
    } else if (!pd_mis_load(&s_mlive, pl, PD_TBL_PAYLOAD, 1u, false)) {
        pdb_put_err("table_load", 0u, 0u);
    } else {
        pd_mis_enter(&s_mlive);
    }
    s_acc.valid = (1u << (2u * PD_N_CH)) - 1u;
    s_acc.sat = 0u;
    s_acc.tc = PD_CMD_NONE;
    for (i = 0u; i < FSW_TC_ARGS; i++) {
        s_acc.tc_arg[i] = 0;
    }
    for (i = 0u; i < FSW_IN_MAX; i++) {
        s_acc.cnt[i] = 0;
    }
}

static void run_mis(void)
{
    uint32_t k;
    uint32_t c;
    uint32_t sticky = 0u;
    mis_setup();
    for (k = 0u; k < PD_B_MIS_N; k++) {
        s_acc.seq = (int64_t)k + 1;
        for (c = 0u; c < PD_N_CH; c++) {
            s_acc.cnt[c] = y_of(k + (341u * c));
            s_acc.cnt[c + PD_N_CH] = beta_of();
        }
        bk_mis(k);   /* classify: s_mwork = the step from s_mlive */
        sticky |= s_mh;
        if (((s_mh & PD_B_H_ABN) != 0u) || ((s_mh & PD_H_TABLE_DEFAULT) == 0u)) {
            pdb_put_err("mis_ordinary", k, s_mh);
        } else if ((k % 2u) == 1u) {
            pdb_put_sample("mis_ordinary", "-", measure(bk_mis, bn_mis, PD_B_K_MIS, k), k);
        } else {
            /* not measured */
        }
        s_mlive = s_mwork;
    }
    pdb_put_sum("mis_steps", PD_B_MIS_N);
    pdb_put_sum("mis_health_or", sticky);
    pdb_put_sum("mis_n_loads", s_mlive.n_loads);
}

/* One step after each gap of PD_B_GAPS lost frames, from the last state of run_mis (the live
   block is not advanced: every gap starts from the same state). */
static void run_mis_gap(void)
{
    static const uint32_t gaps[PD_B_N_GAPS] = { 1u, 2u, 3u, 4u, 8u, 15u, 16u, 63u, 64u, 1000u, 1000000u };
    const int64_t seq1 = s_mlive.last_seq + 1;
    uint32_t j;
    uint32_t c;
    for (j = 0u; j < PD_B_N_GAPS; j++) {
        bool ok;
        s_acc.seq = seq1 + (int64_t)gaps[j];
        for (c = 0u; c < PD_N_CH; c++) {
            s_acc.cnt[c] = y_of(PD_B_MIS_N + (341u * c));
            s_acc.cnt[c + PD_N_CH] = beta_of();
        }
        bk_mis(j);   /* classify */
        ok = (s_mh & (PD_B_H_ABN & ~PD_H_PERIOD_BAD)) == 0u;
        for (c = 0u; c < PD_N_CH; c++) {
            ok = ok && (s_mwork.s[c].tlm.miss_cnt == (s_mlive.s[c].tlm.miss_cnt + gaps[j]));
        }
        if (!ok) {
            pdb_put_err("mis_gap", gaps[j], s_mh);
        } else {
            const int32_t insns = measure(bk_mis, bn_mis, PD_B_K_MIS, j);
            board_console_write("m mis_gap ");
            bench_put_u32(gaps[j]);
            board_console_write(" ");
            bench_put_i32(insns);
            board_console_write(" ");
            bench_put_u32(j);
            board_console_write("\n");
        }
    }
}

static void run_sched(void)
{
    uint32_t i;
    load_params(&PD_TBL_DEFAULT, "table_refused_sched");
    for (i = 0u; i <= PD_B_SCHED_N; i++) {
        const uint64_t f = ((uint64_t)i * (uint64_t)PD_B_F_MAX) / PD_B_SCHED_N;
        const char *sub;
        bool ok;
        s_f = (uint32_t)f;
        sub = f_region(s_f);
        bk_sched(i);
        if (s_f <= s_par.c.f0_q32) {
            ok = s_k2 == s_par.g.k2_node_q22[0];
        } else if (s_f >= PD_B_F_HI) {
            ok = s_k2 == s_par.g.k2_node_q22[PD_N_NODES - 1u];
        } else {
            ok = (s_k2 <= s_par.g.k2_node_q22[0]) && (s_k2 >= s_par.g.k2_node_q22[PD_N_NODES - 1u]);
        }
        if (!ok) {
            pdb_put_err("sched_k2", i, s_k2);
        } else {
            pdb_put_sample("sched_k2", sub, measure(bk_sched, bn_sched, PD_B_K_SCHED, i), i);
        }
    }
}

int main(void)
{
    board_console_write("bench pd 1 cpuid ");
    board_console_hex(*board_reg32(BENCH_CPUID));
    board_console_write("\n");
    bench_calibrate();
    pdb_put_classes();

    pdb_put_sum("sizeof_pd_mis_t", (uint32_t)sizeof(pd_mis_t));
    pdb_put_sum("sizeof_pd_state_t", (uint32_t)sizeof(pd_state_t));
    pdb_put_sum("sizeof_pd_params_t", (uint32_t)sizeof(pd_params_t));
    pdb_put_sum("sizeof_pd_table_t", (uint32_t)sizeof(pd_table_t));

    run_fast();
    run_avg(&PD_TBL_LITERAL, "table_refused_literal");
    run_avg(&PD_TBL_AVGP, "table_refused_avgp");
    {
        static const char *const s_pitch[3] = { "ad_sample", "ad_td", "ad_period" };
        static const char *const s_yaw[3] = { "ady_sample", "ady_td", "ady_period" };
        run_adaptive(PD_B_CH, s_pitch);
        run_adaptive(0u, s_yaw);
    }
    run_mis();
    run_mis_gap();
    run_sched();

    board_console_write("end\n");
    return 0;
}
