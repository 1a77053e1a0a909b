/*
 * rly_bench.c — instructions per rly_step on the emulated Cortex-M (spec 00 §6.4, §9; spec 20).
 * Built by fsw/target/CMakeLists.txt as relay_bench (the loop over the mission modules), run by
 * `python -m tools.bench.module_insn <BUILD_DIR>... --module relay` under QEMU -icount shift=3.
 *
 * Closed loop: a rigid axis (x'' = m, spec 20 §2.1 without the elastic modes) integrated exactly
 * per tick in int64 (angle 2^-60 rad, rate 2^-60 rad/tick, m h^2 in 2^-60 rad: the ZOH step
 * x += x' + m/2, x' += m), from the published start x(0) = 4.5e-4 rad, x'(0) = 2.2e-5 rad/s,
 * driven by the module's own commanded level (m_u 4e-5, m_eps 1e-6 rad/s^2) and sampled as q24
 * counts (round half away from zero), so the law runs its real two-sided cycle through every
 * state. The table is RLY_TBL_DEFAULT (IMPROVED_UP adaptation) with the window shortened to
 * RLY_B_WIN ticks, so that many windows close; rly_params_check must accept it. One sensor
 * outage of RLY_B_OUT_LEN ticks (> lost_ticks) late in the run adds COAST and its exit.
 *
 * Exact counts although rly_step mutates its state: every tick first runs one step on a copy
 * (s_work = s_live) to classify it; a tick to be measured is then bracketed with bench_bracket5
 * by a wrapper that restores the copy before each call, so the five calls are identical (rly has
 * no globals: the step is a function of state, table and input), and by its twin, which does the
 * same copy and calls a null function instead:
 *   insns = bracket5(wrapper) - bracket5(twin) + 1   from rly_step's entry through its return.
 * Measured: every window-boundary tick, every state-transition tick, and every RLY_B_EVERY-th
 * other (ordinary) tick. Each measured tick is also bracketed once with bench_bracket1 (a single
 * call, +-4 instructions whatever the tick phase): an err line if it disagrees with bracket5.
 *
 * Output (the module bench protocol of tools/bench/module_insn.py, see bench_common.h):
 *   bench relay 1 cpuid <hex>
 *   cal ... / tick ...            calibration (bench_common.c)
 *   class <name> <text>           the sample classes, in report order
 *   twin <value> 0                bracket5 of the twin (constant, else an err line)
 *   m <class> <sub> <insns> <tick>   one measured rly_step; class ordinary (sub: the state),
 *                                 window (the window closed: sub = adaptation phase/event after
 *                                 the decision), transition (the law changed state: sub =
 *                                 from>to; the brake end's chained W test shows as one step),
 *                                 window+transition (both: sub = from>to,phase/event);
 *                                 "/invalid" is appended to sub for an invalid sample
 *   sum <key> <value>             closed-loop summary
 *   err <text>                    a check failed (table refused, twin not constant)
 *   end
 */
#include <stdint.h>
#include <stdbool.h>
#include <stddef.h>
#include "board.h"
#include "bench_common.h"
#include "fx.h"
#include "rly.h"
#include "rly_tables.h"

#define BENCH_CPUID    0xE000ED00u

#define RLY_B_TICKS    2000000u       /* 2000 s at 1 ms: about 45 two-sided cycles of ~44 s */
#define RLY_B_WIN      4000u          /* 4-s windows: 500 boundaries */
#define RLY_B_EVERY    97u            /* ordinary ticks measured: one in 97 */
#define RLY_B_OUT_AT   1900000u       /* sensor outage: start tick ... */
#define RLY_B_OUT_LEN  150u           /* ... and length (lost_ticks = 100: COAST for 50 ticks) */

/* Plant constants in 2^-60 rad (per tick, per tick^2 at h = 1 ms); accelerations even so that
   m/2 is exact. */
#define RLY_B_A_FULL   INT64_C(46116860)          /* 4e-5 rad/s^2 h^2 2^60 = 46116860.18 */
#define RLY_B_A_WEAK   INT64_C(1152922)           /* 1e-6 rad/s^2 h^2 2^60 = 1152921.50 */
#define RLY_B_X0       INT64_C(518814677073081)   /* 4.5e-4 rad */
#define RLY_B_V0       INT64_C(25364273101)       /* 2.2e-5 rad/s = 2.2e-8 rad/tick */
#define RLY_B_SH_Q24   36u                        /* 2^-60 -> 2^-24 rad */

#define RLY_B_F_WIN    1u
#define RLY_B_F_TRANS  2u

static rly_params_t s_p;
static rly_state_t s_live;            /* the loop's state */
static rly_state_t s_work;            /* one step ahead of s_live */
static rly_in_t s_in;
static rly_out_t s_out;

/* Null twin (bench_asm.S): a lone `bx lr`, with rly_step's prototype. */
void bench_null_0(rly_state_t *s, const rly_params_t *p, const rly_in_t *in, rly_out_t *out);

static void bk_step(uint32_t i)
{
    (void)i;
    s_work = s_live;
    rly_step(&s_work, &s_p, &s_in, &s_out);
}

static void bn_step(uint32_t i)
{
    (void)i;
    s_work = s_live;
    bench_null_0(&s_work, &s_p, &s_in, &s_out);
}

/* The commanded level's acceleration, 2^-60 rad per tick^2 (an unknown code applies 0). */
static int64_t plant_accel(uint8_t lvl)
{
    int64_t a = 0;
    if (lvl == RLY_LVL_FULL_POS) {
        a = RLY_B_A_FULL;
    } else if (lvl == RLY_LVL_FULL_NEG) {
        a = -RLY_B_A_FULL;
    } else if (lvl == RLY_LVL_WEAK_POS) {
        a = RLY_B_A_WEAK;
    } else if (lvl == RLY_LVL_WEAK_NEG) {
        a = -RLY_B_A_WEAK;
    } else {
        a = 0;
    }
    return a;
}

static const char *name_of(const char *const *names, uint32_t n, uint32_t i)
{
    return (i < n) ? names[i] : "?";
}

/* "m <class> <sub> <insns> <tick>" for the step s_live -> s_work. */
static void put_sample(uint32_t k, uint32_t flags, int32_t insns)
{
    static const char *const st_name[7] = {
        "W_POS", "R_MAIN", "R_BRAKE", "W_NEG", "L_MAIN", "L_BRAKE", "COAST"
    };
    static const char *const ph_name[3] = { "SEARCH", "PROBE", "FROZEN" };
    static const char *const ev_name[7] = {
        "NONE", "STEP", "PROBE_START", "FREEZE_SETTLED", "FREEZE_CLIFF", "UNFREEZE", "SKIPPED"
    };
    static const char *const class_name[4] = { "ordinary", "window", "transition", "window+transition" };

    board_console_write("m ");
    board_console_write(class_name[flags & 3u]);
    board_console_write(" ");
    if ((flags & RLY_B_F_TRANS) != 0u) {
        board_console_write(name_of(st_name, 7u, s_live.st));
        board_console_write(">");
        board_console_write(name_of(st_name, 7u, s_work.st));
    }
    if (flags == (RLY_B_F_WIN | RLY_B_F_TRANS)) {
        board_console_write(",");
    }
    if ((flags & RLY_B_F_WIN) != 0u) {
        board_console_write(name_of(ph_name, 3u, s_work.tlm.win.phase));
        board_console_write("/");
        board_console_write(name_of(ev_name, 7u, s_work.tlm.win.event));
    }
    if (flags == 0u) {
        board_console_write(name_of(st_name, 7u, s_work.st));
    }
    if (!s_in.valid) {
        board_console_write("/invalid");
    }
    board_console_write(" ");
    bench_put_i32(insns);
    board_console_write(" ");
    bench_put_u32(k);
    board_console_write("\n");
}

static void put_sum(const char *key, uint32_t v)
{
    board_console_write("sum ");
    board_console_write(key);
    board_console_write(" ");
    bench_put_u32(v);
    board_console_write("\n");
}

static void put_classes(void)
{
    board_console_write("class ordinary neither a window boundary nor a state change (every 97th such tick)\n");
    board_console_write("class window the window closes: window packet and rly_adapt_window\n");
    board_console_write("class transition the law changes state (and the copy is re-anchored)\n");
    board_console_write("class window+transition both in the same tick\n");
}

int main(void)
{
    int64_t x = RLY_B_X0;
    int64_t v = RLY_B_V0;
    uint32_t xmax = 0u;
    uint32_t states = 0u;
    uint32_t phases = 0u;
    uint32_t events = 0u;
    uint32_t n_ord = 0u;
    uint32_t twin = 0u;
    uint32_t why = 0u;
    uint32_t k;
    fsw_rc_t rc;
    fx_status_t st = 0u;

    s_p = RLY_TBL_DEFAULT;
    s_p.win_ticks = RLY_B_WIN;
    rc = rly_params_check(&s_p, &why);

    board_console_write("bench relay 1 cpuid ");
    board_console_hex(*board_reg32(BENCH_CPUID));
    board_console_write("\n");
    if (rc != FSW_OK) {
        bench_put_kv("err table refused: rc why", rc, why);
    }
    bench_calibrate();
    put_classes();

    rly_init(&s_live, &s_p);
    s_in.valid = true;
    s_in.reinit = false;
    for (k = 0u; k < RLY_B_TICKS; k++) {
        uint32_t flags = 0u;
        int64_t a;
        /* the sample of tick k, then the command of tick k over [t_k, t_k + h) */
        s_in.x_q24 = fx_rshift_sat(x, RLY_B_SH_Q24, &st);
        s_in.valid = (k < RLY_B_OUT_AT) || (k >= (RLY_B_OUT_AT + RLY_B_OUT_LEN));
        bk_step(k);   /* classify: s_work = the step from s_live */
        if (s_work.tlm.n_windows != s_live.tlm.n_windows) {
            flags |= RLY_B_F_WIN;
            phases |= 1u << (s_work.tlm.win.phase & 31u);
            events |= 1u << (s_work.tlm.win.event & 31u);
        }
        if (s_work.st != s_live.st) {
            flags |= RLY_B_F_TRANS;
        }
        if (flags == 0u) {
            n_ord++;
        }
        if ((flags != 0u) || ((n_ord % RLY_B_EVERY) == 1u)) {
            uint32_t t1 = bench_bracket1(bk_step, k);   /* one call: wrapper + 3 = 5 t1 +- 4 */
            uint32_t wn = bench_bracket5(bn_step, k);   /* leaves s_work = s_live */
            uint32_t wk = bench_bracket5(bk_step, k);   /* leaves s_work one step ahead again */
            uint32_t t5 = 5u * t1;
            if (twin == 0u) {
                twin = wn;
                bench_put_kv("twin", wn, 0u);
            } else if (wn != twin) {
                board_console_write("err twin not constant\n");
            } else {
                /* the twin's count is constant */
            }
            if (((t5 > wk) ? (t5 - wk) : (wk - t5)) > 4u) {
                bench_put_kv("err bracket1 disagrees with bracket5: tick ticks", k, t1);
            }
            put_sample(k, flags, (int32_t)wk - (int32_t)wn + 1);
        }
        s_live = s_work;
        states |= 1u << (s_live.st & 31u);
        if (fx_uabs(s_in.x_q24) > xmax) {
            xmax = fx_uabs(s_in.x_q24);
        }
        a = plant_accel(s_out.cmd);
        x += v + (a / 2);   /* |x| stays far below 2^63 (0.5 rad is 2^59) */
        v += a;
    }

    put_sum("ticks", RLY_B_TICKS);
    put_sum("win_ticks", s_p.win_ticks);
    put_sum("windows", s_live.tlm.n_windows);
    put_sum("r_main", s_live.tlm.n_r_main);
    put_sum("l_main", s_live.tlm.n_l_main);
    put_sum("lost", s_live.tlm.n_lost);
    put_sum("kt_q16", s_live.kt_q16);
    put_sum("xmax_q24", xmax);
    put_sum("states_mask", states);
    put_sum("phases_mask", phases);
    put_sum("events_mask", events);
    put_sum("health_sticky", s_live.tlm.health_sticky);
    if (st != 0u) {
        bench_put_kv("err plant sample status", st, 0u);
    }
    board_console_write("end\n");
    return 0;
}
