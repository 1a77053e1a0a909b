/*
 * fuzz_fsw_step — libFuzzer entry point for the executive and both missions (spec 00 §8
 * "Fuzzing": arbitrary fsw_in_t sequences; no UB, actuator counts within limits, no fx SAT
 * bit outside the designated points). Built like fuzz_table_loader: clang + libFuzzer in the
 * `fuzz` preset, corpus + seeded pseudo-random replay (fuzz_replay_main.c) elsewhere.
 *
 * Input format (every byte string is a valid input; missing operands read as 0):
 *   d[0]  cfg: bit0 mission (0 DETUMBLE, 1 RENDEZVOUS); bits1-2 boot table (DETUMBLE:
 *         50 Hz phys, 50 Hz paper, 5 Hz paper; RENDEZVOUS: 0.1 s, 1 s, 0.1 s with 1 ms
 *         sub-ticks; 3 selects the first); bit3 boot in STANDBY instead of the mission mode
 *   d[1]  stale_max - 1
 *   then records, one op byte each plus operands, each applied for 1 + u8 steps:
 *     op bits 0-1  sequence: 0 next, 1 repeat (duplicate), 2 back by u8 (reorder), 3 jump by
 *                  u16 (gap; > 1000 is the bridge's malformed case, here the flight code's)
 *     bit 2        add an i16 delta to every consumed channel (operands: i16 per channel)
 *     bit 3        raw channels: an i32 per channel replaces the value (extremes, junk)
 *     bit 4        status bytes: one per channel (STALE, SAT, and undefined bits)
 *     bit 5        mode command: u8 (values above the last mode included)
 *     bit 6        telecommand: u8 kind % 6: 0 none, 1..4 local id 0..3 in the mission's
 *                  namespace (RENDEZVOUS: 1 START, 2 ABORT, 3 CLEAR_FAULTS; 0 and the
 *                  observer's ids are unknown), 5 another mission's namespace; START with
 *                  u8 extra lead, u8 duration and i16 target offsets
 *     bit 7        n_counts: u8 % (FSW_IN_MAX + 2) (short frames and n_counts > FSW_IN_MAX)
 *   At most FZ_MAX_STEPS steps per input (an input's cost stays bounded).
 *
 * Checked after every step (a violation is __builtin_trap()):
 *   - out->n_act is the mission's count; the counts past it are 0;
 *   - the mode is BOOT, STANDBY, SAFE or the mission's own;
 *   - outside the mission mode every actuator count is the mission's safe value;
 *   - DETUMBLE: |gimbal rate count| <= the table's bdot_max in counts + 1 (error feedback);
 *   - RENDEZVOUS: on_mask within the six thrusters and never both of an axis; a thruster is
 *     on exactly when its window is non-empty, and every window lies inside the period;
 *   - fx status bits 0-7 are never silent: with any of them the health word has FSW_H_MODULE
 *     and the sticky word keeps them. Spec 00 §8 words this target's invariant as "no SAT bit
 *     outside designated points"; arbitrary inputs (a stuck gyro, a nav state that ignores the
 *     burns) drive an estimator out of its design range, where a saturation is the correct,
 *     flagged outcome (spec 10 §7 "fx saturation or overflow"), so the harness checks that it
 *     is reported and that the commands stay inside their limits regardless
 *     (tests/fuzz/README.md). The SIL and golden tests assert no SAT bit at all on physical
 *     inputs;
 *   - mode / health agree (SAFE <-> FSW_H_SAFE);
 *   - the step counter advances by one; every counter never decreases;
 *   - determinism: a second instance fed the same frames gives the same outputs.
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#if defined(FZ_STATS)
#include <stdio.h>
#endif
#include "fsw_exec.h"
#include "obs_tables.h"
#include "imp_tables.h"
#include "fuzz_input.h"

#define FZ_MAX_STEPS 1000u   /* keeps libFuzzer under ASan at several execs/s */

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static int32_t rd_i16(fz_in_t *r)
{
    return (int32_t)fz_u16(r) - 32768;
}

static int32_t rd_i32(fz_in_t *r)
{
    uint32_t v = fz_u16(r);
    v |= fz_u16(r) << 16;
    /* two's complement without the implementation-defined unsigned -> signed conversion */
    return (v <= (uint32_t)INT32_MAX) ? (int32_t)v : (-(int32_t)(~v) - 1);
}

/* Saturating add for the harness's channel values (the executive must refuse out-of-range). */
static int32_t add_sat(int32_t a, int32_t b)
{
    int64_t s = (int64_t)a + (int64_t)b;
    if (s > INT32_MAX) {
        s = INT32_MAX;
    } else if (s < INT32_MIN) {
        s = INT32_MIN;
    } else {
        /* in range */
    }
    return (int32_t)s;
}

/* Monotone counters of the telemetry. */
#define FZ_NCTR 11u
static void counters(const fsw_tlm_t *t, uint32_t *c)
{
    c[0] = t->n_chan_rej;
    c[1] = t->n_stale_steps;
    c[2] = t->n_in_bad;
    c[3] = t->n_tbl_acc;
    c[4] = t->n_tbl_rej;
    c[5] = t->n_scrub_err;
    c[6] = t->n_safe;
    c[7] = t->n_mode_rej;
    c[8] = t->n_tc;
    c[9] = t->n_tc_rej;
    c[10] = t->health_sticky;   /* OR-only: checked as a superset below */
}

typedef struct {
    bool rdv;
    uint32_t mission;
    uint32_t period_us;
    int32_t bdot_max_cnt;    /* DETUMBLE limit in counts (+1 for the error feedback) */
} fz_lim_t;

static void check_out(const fz_lim_t *lim, const fsw_out_t *o)
{
    const fsw_mis_desc_t *d = fsw_mis_desc(lim->mission);
    uint32_t n = d->n_act;
    uint32_t mission_mode = fsw_mis_mode(lim->mission);
    uint32_t i;
    FZ_CHECK(o->n_act == n);
    for (i = n; i < FSW_ACT_MAX; i++) {
        FZ_CHECK(o->act_cnt[i] == 0);
    }
    FZ_CHECK((o->mode == FSW_MODE_BOOT) || (o->mode == FSW_MODE_STANDBY) || (o->mode == FSW_MODE_SAFE) ||
             (o->mode == mission_mode));
    FZ_CHECK(o->mode == o->tlm.mode);
    FZ_CHECK(((o->health & 0xFFu) == 0u) || ((o->health & FSW_H_MODULE) != 0u));
    FZ_CHECK((o->mode == FSW_MODE_SAFE) == ((o->health & FSW_H_SAFE) != 0u));
    if (o->mode != mission_mode) {
        for (i = 0u; i < n; i++) {
            FZ_CHECK(o->act_cnt[i] == d->safe_act[i]);
        }
    } else if (!lim->rdv) {
        for (i = 0u; i < n; i++) {
            FZ_CHECK((o->act_cnt[i] <= lim->bdot_max_cnt) && (o->act_cnt[i] >= -lim->bdot_max_cnt));
        }
    } else {
        uint32_t mask = (uint32_t)o->act_cnt[IMP_ACT_MASK];
        uint32_t r;
        FZ_CHECK(o->act_cnt[IMP_ACT_MASK] >= 0);
        FZ_CHECK((mask & ~0x3Fu) == 0u);
        for (r = 0u; r < 3u; r++) {
            FZ_CHECK(((mask >> (2u * r)) & 3u) != 3u);
        }
        for (i = 0u; i < IMP_NTHR; i++) {
            int32_t s0 = o->act_cnt[i];
            int32_t l0 = o->act_cnt[IMP_NTHR + i];
            bool on = ((mask >> i) & 1u) != 0u;
            FZ_CHECK((s0 >= 0) && (l0 >= 0));
            FZ_CHECK(on == (l0 > 0));
            FZ_CHECK(on || (s0 == 0));
            FZ_CHECK(((uint64_t)(uint32_t)s0 + (uint64_t)(uint32_t)l0) <= (uint64_t)lim->period_us);
        }
    }
}

/* Everything an output step is judged by, folded into a running FNV-1a hash for the twin. */
static uint64_t fold(uint64_t h, const fsw_out_t *o)
{
    uint32_t w[FSW_ACT_MAX + 6u];
    uint32_t i;
    for (i = 0u; i < FSW_ACT_MAX; i++) {
        w[i] = (uint32_t)o->act_cnt[i];
    }
    w[FSW_ACT_MAX] = o->mode;
    w[FSW_ACT_MAX + 1u] = o->health;
    w[FSW_ACT_MAX + 2u] = o->tlm.n_chan_rej;
    w[FSW_ACT_MAX + 3u] = o->tlm.mod_health;
    w[FSW_ACT_MAX + 4u] = o->tlm.n_tc_rej;
    w[FSW_ACT_MAX + 5u] = (o->tlm.mission == FSW_MISSION_DETUMBLE) ? (uint32_t)o->tlm.m.detumble.kappa_q28
                                                                     : (uint32_t)o->tlm.m.rendezvous.mode;
    for (i = 0u; i < (FSW_ACT_MAX + 6u); i++) {
        uint32_t b;
        for (b = 0u; b < 4u; b++) {
            h ^= (w[i] >> (8u * b)) & 0xFFu;
            h *= UINT64_C(0x100000001B3);
        }
    }
    return h;
}

/* Nominal channel values: DETUMBLE 1 deg/s per axis (2^-20 rad/s counts); RENDEZVOUS the
   paper's example state (5 km, 4 km, 4 km; -1 m/s each) and the sample step in channel 6. */
static void nominal(bool rdv, int32_t *v)
{
    static const int32_t rdv0[IMP_N_SENS] = { 5000000, 4000000, 4000000, -100000, -100000, -100000, 0 };
    uint32_t i;
    for (i = 0u; i < FSW_IN_MAX; i++) {
        v[i] = 0;
    }
    if (rdv) {
        for (i = 0u; i < IMP_N_SENS; i++) {
            v[i] = rdv0[i];
        }
    } else {
        v[0] = 18301;   /* 1 deg/s = 0.0174533 rad/s = 18301.4 counts */
        v[1] = 18301;
    }
}

#if defined(FZ_STATS)
/* -DFZ_STATS: per input, how many steps each executive mode and impulse mode saw (how deep the
   corpus reaches). */
#define FZ_MODES 8u
#define FZ_STAT(o) do { s_st_mode[(o)->mode % FZ_MODES]++; s_st_imp[(o)->tlm.m.rendezvous.mode % 16u]++; \
                        s_st_fx += (((o)->health & 0xFFu) != 0u) ? 1u : 0u; } while (0)
static uint32_t s_st_mode[FZ_MODES];
static uint32_t s_st_imp[16];
static uint32_t s_st_fx;
#else
#define FZ_STAT(o) do { } while (0)
#endif

static fsw_t s_f[2];   /* 25 KB each: static, so the fuzzer's stack stays small */
static uint8_t s_boot[FSW_TABLE_CAP_BYTES];

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_in_t r = { data, size, 0u };
    uint32_t c0 = fz_u8(&r);
    bool rdv = (c0 & 1u) != 0u;
    uint32_t tsel = (c0 >> 1) & 3u;
    fsw_cfg_t cfg;
    fz_lim_t lim;
    fsw_in_t in;
    int32_t chan[FSW_IN_MAX];
    uint32_t nsens = rdv ? IMP_N_SENS : OBS_N_SENS;
    uint32_t k;
    uint32_t steps = 0u;
    int64_t seq = 1000;
    uint32_t prev_step = 0u;
    uint32_t prev_c[FZ_NCTR];
    bool first = true;
    uint64_t h[2] = { UINT64_C(0xCBF29CE484222325), UINT64_C(0xCBF29CE484222325) };

    memset(&cfg, 0, sizeof cfg);
    memset(&in, 0, sizeof in);
    memset(prev_c, 0, sizeof prev_c);
    cfg.stale_max = (uint16_t)(1u + fz_u8(&r));
    cfg.mission = rdv ? FSW_MISSION_RENDEZVOUS : FSW_MISSION_DETUMBLE;
    cfg.boot_mode = ((c0 & 8u) != 0u) ? FSW_MODE_STANDBY : (rdv ? FSW_MODE_RENDEZVOUS : FSW_MODE_DETUMBLE);
    lim.rdv = rdv;
    lim.mission = cfg.mission;
    if (rdv) {
        const imp_params_t *p = (tsel == 1u) ? &IMP_TBL_1S : ((tsel == 2u) ? &IMP_TBL_SUB1MS : &IMP_TBL_DEFAULT);
        cfg.period_us = p->period_us;
        lim.period_us = p->period_us;
        lim.bdot_max_cnt = 0;
        uint32_t n = imp_table_encode(p, 1u, s_boot, (uint32_t)sizeof s_boot);
        for (k = 0u; k < 2u; k++) {
            FZ_CHECK(fsw_init(&s_f[k], &cfg, s_boot, n) == FSW_OK);
        }
    } else {
        const obs_params_t *p = (tsel == 1u) ? &OBS_TBL_50HZ_PAPER : ((tsel == 2u) ? &OBS_TBL_5HZ_PAPER : &OBS_TBL_50HZ_PHYS);
        cfg.period_us = p->period_us;
        lim.period_us = p->period_us;
        lim.bdot_max_cnt = (int32_t)(((uint32_t)p->bdot_max_q29 >> p->act_cnt_shift) + 1u);
        uint32_t n = obs_table_encode(p, 1u, s_boot, (uint32_t)sizeof s_boot);
        for (k = 0u; k < 2u; k++) {
            FZ_CHECK(fsw_init(&s_f[k], &cfg, s_boot, n) == FSW_OK);
        }
    }
    nominal(rdv, chan);
    in.n_counts = nsens;
    in.mode_cmd = FSW_CMD_NONE;
    in.tc = FSW_TC_NONE;

    while ((r.pos < r.n) && (steps < FZ_MAX_STEPS)) {
        uint32_t op = fz_u8(&r);
        uint32_t reps = 1u + fz_u8(&r);
        uint32_t mode_cmd = FSW_CMD_NONE;
        uint32_t tc = FSW_TC_NONE;
        int32_t tc_arg[8] = { 0, 0, 0, 0, 0, 0, 0, 0 };
        uint8_t status[FSW_IN_MAX];
        int64_t seq_step = 1;
        uint32_t i;
        memset(status, 0, sizeof status);
        switch (op & 3u) {
        case 1u:
            seq_step = 0;
            break;
        case 2u:
            seq_step = -(int64_t)(1u + fz_u8(&r));
            break;
        case 3u:
            seq_step = (int64_t)(2u + fz_u16(&r));
            break;
        default:
            break;
        }
        if ((op & 4u) != 0u) {
            for (i = 0u; i < nsens; i++) {
                chan[i] = add_sat(chan[i], rd_i16(&r));
            }
        }
        if ((op & 8u) != 0u) {
            for (i = 0u; i < nsens; i++) {
                chan[i] = rd_i32(&r);
            }
        }
        if ((op & 16u) != 0u) {
            for (i = 0u; i < nsens; i++) {
                status[i] = (uint8_t)fz_u8(&r);
            }
        }
        if ((op & 32u) != 0u) {
            mode_cmd = fz_u8(&r) % 7u;   /* every mode number in use, and beyond */
        }
        if ((op & 64u) != 0u) {
            uint32_t kind = fz_u8(&r) % 6u;
            tc = (kind == 0u) ? FSW_TC_NONE
               : ((kind == 5u) ? FSW_TC_ID(cfg.mission + 1u, 1u) : FSW_TC_ID(cfg.mission, kind - 1u));
            if (kind == 2u) {   /* local id 1: RENDEZVOUS START */
                uint32_t lead = fz_u8(&r);
                uint32_t dur = fz_u8(&r);
                int64_t t0 = seq + 1 + (int64_t)lead;
                tc_arg[0] = (int32_t)(t0 & 0x7FFFFFFF);
                tc_arg[1] = (int32_t)((t0 + 100 + (16 * (int64_t)dur)) & 0x7FFFFFFF);
                for (i = 2u; i < 8u; i++) {
                    tc_arg[i] = rd_i16(&r) * 64;
                }
            }
        }
        if ((op & 128u) != 0u) {
            in.n_counts = fz_u8(&r) % (FSW_IN_MAX + 2u);
        }
        for (k = 0u; (k < reps) && (steps < FZ_MAX_STEPS); k++) {
            fsw_out_t out[2];
            uint32_t c[FZ_NCTR];
            uint32_t j;
            seq += (k == 0u) ? seq_step : 1;
            in.seq = seq;
            in.utime_us = seq * 1000;
            for (i = 0u; i < FSW_IN_MAX; i++) {
                in.counts[i] = chan[i];
                in.status[i] = status[i];
            }
            if (rdv) {
                in.counts[6] = (int32_t)(seq & 0x7FFFFFFF);   /* the sample's step: this frame */
            }
            /* mode commands and telecommands are one-shot: the first step of the record only */
            in.mode_cmd = (k == 0u) ? mode_cmd : FSW_CMD_NONE;
            in.tc = (k == 0u) ? tc : FSW_TC_NONE;
            for (i = 0u; i < 8u; i++) {
                in.tc_arg[i] = tc_arg[i];
            }
            for (j = 0u; j < 2u; j++) {
                memset(&out[j], 0, sizeof out[j]);
                fsw_step(&s_f[j], &in, &out[j]);
                h[j] = fold(h[j], &out[j]);
            }
            FZ_CHECK(h[0] == h[1]);
            check_out(&lim, &out[0]);
            FZ_STAT(&out[0]);
            counters(&out[0].tlm, c);
            FZ_CHECK((out[0].tlm.health_sticky & out[0].health) == out[0].health);
            if (!first) {
                FZ_CHECK(out[0].tlm.step == (prev_step + 1u));
                for (i = 0u; i < (FZ_NCTR - 1u); i++) {
                    FZ_CHECK(c[i] >= prev_c[i]);
                }
                FZ_CHECK((c[FZ_NCTR - 1u] & prev_c[FZ_NCTR - 1u]) == prev_c[FZ_NCTR - 1u]);
            }
            first = false;
            prev_step = out[0].tlm.step;
            memcpy(prev_c, c, sizeof c);
            steps++;
        }
    }
#if defined(FZ_STATS)
    printf("steps %u mission %u table %u: modes", steps, rdv ? 1u : 0u, tsel);
    for (k = 0u; k < FZ_MODES; k++) {
        printf(" %u", s_st_mode[k]);
        s_st_mode[k] = 0u;
    }
    printf("; imp modes");
    for (k = 0u; k < 16u; k++) {
        printf(" %u", s_st_imp[k]);
        s_st_imp[k] = 0u;
    }
    printf("; fx steps %u\n", s_st_fx);
    s_st_fx = 0u;
#endif
    return 0;
}
