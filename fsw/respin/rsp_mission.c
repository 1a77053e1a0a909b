/*
 * rsp_mission.c — respin's adapter to the executive (RESPIN; fsw/app/fsw_mission.h).
 *
 * The law runs only in the mission mode and restarts on every entry (outside it the actuator
 * holds its safe value, zero torque). CMD_LIMIT_PERSIST is a module fault (FSW_H_MODULE in the
 * executive's health), not a SAFE trigger: the damper keeps commanding its limit. Commit rule: a
 * validated table becomes active at the next step boundary; the law has no state that depends on
 * the table, so nothing restarts. Telecommand RESET_COUNTERS clears the module's counters.
 */
#include "rsp_mission.h"

#define RSP_FAULT_BITS (RSP_H_CMD_LIMIT_PERSIST | FX_ST_MASK)

/* The generated total is the header, the actuator counts, the health word and the block. */
FX_STATIC_ASSERT(rsp_mis_sa_tlm,
                 RSP_TLM_TOTAL_BYTES == (FSW_TLM_HEAD_BYTES + (4u * RSP_N_ACT) + 4u + RSP_TLM_BYTES));

static const int32_t RSP_SAFE_ACT[RSP_N_ACT] = {0};

const fsw_mis_desc_t RSP_MIS_DESC = {
    RSP_N_SENS, RSP_N_ACT, FSW_MIS_STALE_SAFE | FSW_MIS_SAT_SAFE, RSP_FAULT_BITS,
    0u,   /* safe_bits: the module health bits its own persistence rule raises, which send the executive to SAFE */
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
    (void)in_mode;   /* nothing in the state depends on the table */
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
    /* |count| >= rate_max_cnt is full scale, i.e. invalid; the loader guarantees >= 1. */
    int32_t m = (b->p.rate_max_cnt > 0) ? (b->p.rate_max_cnt - 1) : -1;
    r[0].min = (m >= 0) ? -m : 1;
    r[0].max = m;
}

void rsp_mis_enter(rsp_mis_t *b)
{
    rsp_init(&b->s, &b->p);
}

uint32_t rsp_mis_step(rsp_mis_t *b, const fsw_acc_t *acc, int32_t *act)
{
    rsp_in_t in;
    if (acc->tc == RSP_CMD_RESET_COUNTERS) {
        b->s.tlm.n_skip = 0u;
        b->s.tlm.n_limited = 0u;
        b->s.tlm.health_sticky = 0u;
    }
    in.rate_cnt = acc->cnt[0];
    in.valid = (acc->valid & 1u) != 0u;
    rsp_step(&b->s, &b->p, &in, &b->o);
    act[0] = b->o.u_cnt;
    return b->o.health;
}

const rsp_tlm_t *rsp_mis_tlm(const rsp_mis_t *b)
{
    return &b->s.tlm;
}
