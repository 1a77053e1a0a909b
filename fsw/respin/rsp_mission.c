/*
 * rsp_mission.c — respin's adapter to the executive (RESPIN; fsw/app/fsw_mission.h).
 *
 * Channel map: sensors 0..2 gyro x, y, z (2^-22 rad/s), 3..5 wheel speed x, y, z (2^-10 rad/s),
 * 6..9 gimbal angle 1..4 (2 pi / 2^20 rad, [0, 2^20)), 10..13 rotor speed 1..4 (2^-8 rad/s);
 * actuators 0..2 wheel motor torque x, y, z (2^-17 N m), 3..6 gimbal rate 1..4 (2^-16 rad/s), safe
 * value 0 (a held cluster). The table's act_kind says which set flies; the other set's channels are
 * read and ignored (the plant publishes the superset).
 *
 * The law runs only in the mission mode and restarts (rsp_init: g0 averaged again) on every
 * entry; outside it the wheels hold zero torque. The module judges its inputs itself (spec 30 §8:
 * an invalid tick commands zero and keeps region, a_f and latch), so no channel condition sends
 * the executive to SAFE: a 10 s gyro dropout in FAR must not restart a respin hours into its far
 * phase (spec 30 §7 A12). INPUT_FAULT, WHEEL_FAULT, ROTOR_FAULT, ENERGY_ALARM, ENERGY_LOW,
 * HBOUND_STUCK, OVERFLOW and any fx status raise FSW_H_MODULE.
 * Commit rule: a validated table becomes active at the next step boundary and the law's state
 * (g0, region, a_f, energy) is kept: every table field is a gain, a limit or a threshold read
 * afresh each tick, and g0 is a measurement, not a table value. Telecommand RESET_COUNTERS clears
 * the module's counters and sticky health.
 */
#include "rsp_mission.h"

#define RSP_FAULT_BITS (RSP_H_INPUT_FAULT | RSP_H_WHEEL_FAULT | RSP_H_ROTOR_FAULT | RSP_H_ENERGY_ALARM | \
                        RSP_H_ENERGY_LOW | RSP_H_HBOUND_STUCK | RSP_H_OVERFLOW | FX_ST_MASK)
#define RSP_ENC_MAX    ((int32_t)1048575)    /* gimbal encoder: 2^20 counts per turn */
#define RSP_ROTOR_MAX  ((int32_t)16777216)   /* rotor speed: 2^24 counts = 65 536 rad/s, far above any rotor */

/* The generated total is the header, the actuator counts, the health word and the block. */
FX_STATIC_ASSERT(rsp_mis_sa_tlm,
                 RSP_TLM_TOTAL_BYTES == (FSW_TLM_HEAD_BYTES + (4u * RSP_N_ACT) + 4u + RSP_TLM_BYTES));

static const int32_t RSP_SAFE_ACT[RSP_N_ACT] = {0, 0, 0, 0, 0, 0, 0};

const fsw_mis_desc_t RSP_MIS_DESC = {
    RSP_N_SENS, RSP_N_ACT, 0u, RSP_FAULT_BITS,
    0u,   /* safe_bits: none (zero torque is the module's own safe action) */
    RSP_CMD_MAX,
    RSP_TLM_LAYOUT, RSP_TLM_TOTAL_BYTES,
    &RSP_TBL_DESC, RSP_SAFE_ACT,
};

void rsp_mis_reset(rsp_mis_t *b)
{
    static const rsp_out_t out_zero = {0};   /* rodata: a struct copy without a stack temporary */
    b->have_p = false;
    b->o = out_zero;
}

uint32_t rsp_mis_check(rsp_mis_t *b, const uint8_t *pl, uint32_t len, uint32_t period_us)
{
    uint32_t why = 0u;
    uint32_t d = FSW_VETO_UNDECODED;
    /* The revision is informative; the check does not depend on it. */
    if (rsp_table_decode(pl, len, 0u, &b->cand) == FSW_OK) {
        if (rsp_params_check(&b->cand, &why) != FSW_OK) {
            d = fsw_table_veto_detail(why);
        } else if (b->cand.period_us != period_us) {
            d = fsw_table_veto_detail(RSP_WHY_PERIOD);
        } else {
            d = 0u;
        }
    }
    return d;
}

bool rsp_mis_load(rsp_mis_t *b, const uint8_t *pl, uint32_t len, uint32_t rev, bool in_mode)
{
    bool ok = false;
    (void)in_mode;   /* the law keeps its state across a commit (header comment) */
    if (rsp_table_decode(pl, len, rev, &b->cand) == FSW_OK) {
        b->p = b->cand;
        b->have_p = true;
        ok = true;
    }
    return ok;
}

bool rsp_mis_commit_ok(const rsp_mis_t *b, bool in_mode)
{
    (void)b;
    (void)in_mode;
    return true;
}

void rsp_mis_ranges(const rsp_mis_t *b, fsw_range_t *r)
{
    uint32_t i;
    /* |gyro count| >= gyro_max_cnt is full scale, i.e. invalid; the loader guarantees >= 1.
       Before a table is loaded (limits 0) every channel is refused. */
    int32_t g = (b->p.gyro_max_cnt > 0) ? (b->p.gyro_max_cnt - 1) : -1;
    int32_t w = (b->p.whl_max_cnt > 0) ? b->p.whl_max_cnt : -1;
    for (i = 0u; i < 3u; i++) {
        r[i].min = (g >= 0) ? -g : 1;
        r[i].max = g;
        r[3u + i].min = (w >= 0) ? -w : 1;
        r[3u + i].max = w;
    }
    for (i = 0u; i < 4u; i++) {
        r[6u + i].min = 0;
        r[6u + i].max = RSP_ENC_MAX;
        r[10u + i].min = 0;
        r[10u + i].max = RSP_ROTOR_MAX;
    }
}

void rsp_mis_enter(rsp_mis_t *b)
{
    rsp_init(&b->s, &b->p);
}

static void rsp_reset_counters(rsp_tlm_t *t)
{
    t->n_switch = 0u;
    t->n_lin = 0u;
    t->n_mid = 0u;
    t->n_far = 0u;
    t->n_gyro_bad = 0u;
    t->n_gyro_stale = 0u;
    t->n_whl_bad = 0u;
    t->n_whl_est = 0u;
    t->n_outlier = 0u;
    t->n_overflow = 0u;
    t->n_clip = 0u;
    t->n_hbound = 0u;
    t->n_singular = 0u;
    t->n_rate_limited = 0u;
    t->health_sticky = 0u;
}

uint32_t rsp_mis_step(rsp_mis_t *b, const fsw_acc_t *acc, int32_t *act)
{
    rsp_in_t in;
    uint32_t i;
    if (acc->tc == RSP_CMD_RESET_COUNTERS) {
        rsp_reset_counters(&b->s.tlm);
    }
    for (i = 0u; i < 3u; i++) {
        in.omega_BN_B_cnt[i] = acc->cnt[i];
        in.whl_speed_cnt[i] = acc->cnt[3u + i];
    }
    for (i = 0u; i < 4u; i++) {
        in.gimbal_enc_cnt[i] = acc->cnt[6u + i];
        in.rotor_cnt[i] = acc->cnt[10u + i];
    }
    in.valid = acc->valid & 0x3FFFu;
    in.sat = acc->sat & 0x3FFFu;
    rsp_step(&b->s, &b->p, &in, &b->o);
    for (i = 0u; i < 3u; i++) {
        act[i] = (int32_t)b->o.whl_torque_cnt[i];
    }
    for (i = 0u; i < 4u; i++) {
        act[3u + i] = (int32_t)b->o.gimbal_rate_cnt[i];
    }
    return b->o.health;
}

const rsp_tlm_t *rsp_mis_tlm(const rsp_mis_t *b)
{
    return &b->s.tlm;
}
