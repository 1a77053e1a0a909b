/*
 * obs_mission.c — the observer's adapter to the executive (DETUMBLE; fsw/app/fsw_mission.h).
 *
 * The observer runs only in its mission mode and is re-initialised on every entry: outside it the
 * actuators hold their safe value (zero rate), which the observer's model would not know.
 * CMD_LIMIT_PERSIST is reported, not a SAFE trigger: with insufficient authority the spec's
 * scenario (10-observer S0-9) expects the loop to keep commanding and the plant to end DIVERGED.
 * INNOV_PERSIST (a gyro channel failing the innovation gate n_rej_safe times in a row) is a fault
 * bit and the mission's safe_bits: the observer latches its own safe output (zero command, kappa
 * frozen), and the executive goes to SAFE at that step (FSW_H_MODULE_SAFE), left only by command;
 * re-entering DETUMBLE re-initialises the observer and clears the latch.
 * Commit rule: a validated table becomes active at the next step boundary; the covariance lives in
 * the table's scaled coordinates, so a new scale vector restarts the observer when it is flying.
 */
#include "obs_mission.h"

#define OBS_FAULT_BITS (OBS_H_MEAS_LOST | OBS_H_CMD_LIMIT_PERSIST | OBS_H_COV_CLIP | OBS_H_INNOV_PERSIST | FX_ST_MASK)

/* The generated total is the header, the actuator counts, the health word and the block. */
FX_STATIC_ASSERT(obs_mis_sa_tlm, OBS_TLM_TOTAL_BYTES == (FSW_TLM_HEAD_BYTES + (4u * OBS_N_ACT) + 4u + OBS_TLM_BYTES));

static const int32_t OBS_SAFE_ACT[OBS_N_ACT] = {0, 0};

const fsw_mis_desc_t OBS_MIS_DESC = {
    OBS_N_SENS, OBS_N_ACT, FSW_MIS_STALE_SAFE | FSW_MIS_SAT_SAFE, OBS_FAULT_BITS, OBS_H_INNOV_PERSIST, OBS_CMD_MAX,
    OBS_TLM_LAYOUT, OBS_TLM_TOTAL_BYTES,
    &OBS_TBL_DESC, OBS_SAFE_ACT,
};

void obs_mis_reset(obs_mis_t *b)
{
    static const obs_out_t out_zero = {0};   /* rodata: a struct copy without a stack temporary */
    b->have_p = false;
    b->o = out_zero;
}

uint32_t obs_mis_check(obs_mis_t *b, const uint8_t *pl, uint32_t len, uint32_t period_us)
{
    uint32_t why = 0u;
    uint32_t d = FSW_VETO_UNDECODED;
    /* The revision is informative; the check does not depend on it. */
    if (obs_table_decode(pl, len, 0u, &b->cand) == FSW_OK) {
        if (obs_params_check(&b->cand, &why) != FSW_OK) {
            d = fsw_table_veto_detail(why);
        } else if (b->cand.period_us != period_us) {
            d = fsw_table_veto_detail(OBS_WHY_PERIOD);
        } else {
            d = 0u;
        }
    }
    return d;
}

bool obs_mis_load(obs_mis_t *b, const uint8_t *pl, uint32_t len, uint32_t rev, bool in_mode)
{
    bool ok = false;
    if (obs_table_decode(pl, len, rev, &b->cand) == FSW_OK) {
        uint32_t i;
        bool same_scale = b->have_p;
        for (i = 0u; i < OBS_NZ; i++) {
            same_scale = same_scale && (b->p.ls[i] == b->cand.ls[i]);
        }
        b->p = b->cand;
        b->have_p = true;
        ok = true;
        if (in_mode && !same_scale) {
            (void)obs_init(&b->s, &b->p, &b->o);
        }
    }
    return ok;
}

bool obs_mis_commit_ok(const obs_mis_t *b, bool in_mode)
{
    (void)b;
    (void)in_mode;
    return true;
}

void obs_mis_ranges(const obs_mis_t *b, fsw_range_t *r)
{
    uint32_t i;
    /* |count| >= gyro_max_cnt is full scale, i.e. invalid; the loader guarantees >= 1. */
    int32_t m = (b->p.gyro_max_cnt > 0) ? (b->p.gyro_max_cnt - 1) : -1;
    for (i = 0u; i < OBS_N_SENS; i++) {
        r[i].min = (m >= 0) ? -m : 1;
        r[i].max = m;
    }
}

void obs_mis_enter(obs_mis_t *b)
{
    (void)obs_init(&b->s, &b->p, &b->o);
}

uint32_t obs_mis_step(obs_mis_t *b, const fsw_acc_t *acc, int32_t *act)
{
    uint32_t i;
    obs_in_t oi;
    oi.seq = (uint32_t)((uint64_t)acc->seq & 0xFFFFFFFFu);
    oi.stale = 0u;
    oi.sat = 0u;
    for (i = 0u; i < OBS_NY; i++) {
        uint32_t bit = (uint32_t)1u << i;
        oi.gyro_cnt[i] = acc->cnt[i];
        if ((acc->valid & bit) == 0u) {
            oi.stale = (uint8_t)(oi.stale | bit);
        }
        if ((acc->sat & bit) != 0u) {
            oi.sat = (uint8_t)(oi.sat | bit);
        }
    }
    obs_step(&b->s, &b->p, &oi, &b->o);
    for (i = 0u; i < OBS_N_ACT; i++) {
        act[i] = b->o.bdot_cmd_cnt[i];
    }
    return b->o.health;
}

const obs_tlm_t *obs_mis_tlm(const obs_mis_t *b)
{
    return &b->o.tlm;
}
