/*
 * pd_mission.c — pd's adapter to the executive (HOLD; fsw/app/fsw_mission.h).
 *
 * The law runs only in the mission mode and restarts on every entry (outside it the actuator
 * holds its safe value, zero torque). CMD_LIMIT_PERSIST is a module fault (FSW_H_MODULE in the
 * executive's health), not a SAFE trigger: the damper keeps commanding its limit. Commit rule: a
 * validated table becomes active at the next step boundary; the law has no state that depends on
 * the table, so nothing restarts. Telecommand RESET_COUNTERS clears the module's counters.
 */
#include "pd_mission.h"

#define PD_FAULT_BITS (PD_H_CMD_LIMIT_PERSIST | FX_ST_MASK)

/* The generated total is the header, the actuator counts, the health word and the block. */
FX_STATIC_ASSERT(pd_mis_sa_tlm,
                 PD_TLM_TOTAL_BYTES == (FSW_TLM_HEAD_BYTES + (4u * PD_N_ACT) + 4u + PD_TLM_BYTES));

static const int32_t PD_SAFE_ACT[PD_N_ACT] = {0};

const fsw_mis_desc_t PD_MIS_DESC = {
    PD_N_SENS, PD_N_ACT, FSW_MIS_STALE_SAFE | FSW_MIS_SAT_SAFE, PD_FAULT_BITS,
    0u,   /* safe_bits: the module health bits its own persistence rule raises, which send the executive to SAFE */
    PD_CMD_MAX,
    PD_TLM_LAYOUT, PD_TLM_TOTAL_BYTES,
    &PD_TBL_DESC, PD_SAFE_ACT,
};

void pd_mis_reset(pd_mis_t *b)
{
    static const pd_out_t out_zero = {0};   /* rodata: a struct copy without a stack temporary */
    b->have_p = false;
    b->o = out_zero;
}

uint32_t pd_mis_check(pd_mis_t *b, const uint8_t *pl, uint32_t len, uint32_t period_us)
{
    uint32_t why = 0u;
    uint32_t d = FSW_VETO_UNDECODED;
    /* The revision is informative; the check does not depend on it. */
    if (pd_table_decode(pl, len, 0u, &b->cand) == FSW_OK) {
        if (pd_params_check(&b->cand, &why) != FSW_OK) {
            d = fsw_table_veto_detail(why);
        } else if (b->cand.period_us != period_us) {
            d = fsw_table_veto_detail(PD_WHY_PERIOD);
        } else {
            d = 0u;
        }
    }
    return d;
}

bool pd_mis_load(pd_mis_t *b, const uint8_t *pl, uint32_t len, uint32_t rev, bool in_mode)
{
    bool ok = false;
    (void)in_mode;   /* nothing in the state depends on the table */
    if (pd_table_decode(pl, len, rev, &b->cand) == FSW_OK) {
        b->p = b->cand;
        b->have_p = true;
        ok = true;
    }
    return ok;
}

bool pd_mis_commit_ok(const pd_mis_t *b, bool in_mode)
{
    (void)b;
    (void)in_mode;
    return true;
}

void pd_mis_ranges(const pd_mis_t *b, fsw_range_t *r)
{
    /* |count| >= rate_max_cnt is full scale, i.e. invalid; the loader guarantees >= 1. */
    int32_t m = (b->p.rate_max_cnt > 0) ? (b->p.rate_max_cnt - 1) : -1;
    r[0].min = (m >= 0) ? -m : 1;
    r[0].max = m;
}

void pd_mis_enter(pd_mis_t *b)
{
    pd_init(&b->s, &b->p);
}

uint32_t pd_mis_step(pd_mis_t *b, const fsw_acc_t *acc, int32_t *act)
{
    pd_in_t in;
    if (acc->tc == PD_CMD_RESET_COUNTERS) {
        b->s.tlm.n_skip = 0u;
        b->s.tlm.n_limited = 0u;
        b->s.tlm.health_sticky = 0u;
    }
    in.rate_cnt = acc->cnt[0];
    in.valid = (acc->valid & 1u) != 0u;
    pd_step(&b->s, &b->p, &in, &b->o);
    act[0] = b->o.u_cnt;
    return b->o.health;
}

const pd_tlm_t *pd_mis_tlm(const pd_mis_t *b)
{
    return &b->s.tlm;
}
