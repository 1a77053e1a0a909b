/*
 * imp_mission.c — the impulse scheduler's adapter to the executive (RENDEZVOUS;
 * fsw/app/fsw_mission.h). The scheduler is initialised on every entry to its mode.
 *
 * Commit rule: the scheduler's state (timeline and burn log in valve-grid units, nav sample
 * converted with the count scales, calibration, a plan job) is only meaningful with the table it
 * was made with, and a swap must never touch a firing timeline. So a validated table is committed
 * only while the scheduler runs no mission — the executive is outside RENDEZVOUS, or the
 * scheduler is IDLE or terminal (DONE, INFEASIBLE, NO_SOLUTION, ABORTED, FAULT) — and otherwise
 * waits as a READY candidate (FSW_H_TBL_PENDING each step; ground can ABORT to force it). A commit
 * in RENDEZVOUS re-initialises the scheduler with the new table (IDLE, its telemetry carries the
 * new revision; like a mode re-entry, this clears its latched faults — the executive's sticky
 * health keeps the record).
 */
#include "imp_mission.h"

#define IMP_FAULT_BITS (IMP_H_STUCK_OFF | IMP_H_STUCK_ON | IMP_H_INTERLOCK | FX_ST_MASK)
#define IMP_SAMPLE_ALL 0x7Fu /* the seven nav channels */

/* The generated total is the header, the actuator counts, the health word and the block. */
FX_STATIC_ASSERT(imp_mis_sa_tlm, IMP_TLM_TOTAL_BYTES == (FSW_TLM_HEAD_BYTES + (4u * IMP_N_ACT) + 4u + IMP_TLM_BYTES));

static const int32_t IMP_SAFE_ACT[IMP_N_ACT] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};

const fsw_mis_desc_t IMP_MIS_DESC = {
    IMP_N_SENS, IMP_N_ACT, FSW_MIS_SAMPLE, IMP_FAULT_BITS, 0u, IMP_CMD_MAX,
    IMP_TLM_LAYOUT, IMP_TLM_TOTAL_BYTES,
    &IMP_TBL_DESC, IMP_SAFE_ACT,
};

void imp_mis_reset(imp_mis_t *b)
{
    static const imp_out_t out_zero = {0};   /* rodata: a struct copy without a stack temporary */
    b->o = out_zero;
}

/* imp_params_check and the same-period rule: 0 when p passes, else the veto detail. */
static uint32_t module_check(const imp_params_t *p, uint32_t period_us)
{
    uint32_t why = 0u;
    uint32_t d = 0u;
    if (imp_params_check(p, &why) != FSW_OK) {
        d = fsw_table_veto_detail(why);
    } else if (p->period_us != period_us) {
        d = fsw_table_veto_detail(IMP_WHY_PERIOD);
    } else {
        d = 0u;
    }
    return d;
}

uint32_t imp_mis_check(imp_mis_t *b, const uint8_t *pl, uint32_t len, uint32_t period_us)
{
    uint32_t d = FSW_VETO_UNDECODED;
    /* The revision is informative; the check does not depend on it. */
    if (imp_table_decode(pl, len, 0u, &b->cand) == FSW_OK) {
        d = module_check(&b->cand, period_us);
    }
    return d;
}

bool imp_mis_load(imp_mis_t *b, const uint8_t *pl, uint32_t len, uint32_t rev, bool in_mode)
{
    bool ok = false;
    if (imp_table_decode(pl, len, rev, &b->cand) == FSW_OK) {
        b->p = b->cand;
        ok = true;
        if (in_mode) {
            (void)imp_init(&b->s, &b->p, &b->o);
        }
    }
    return ok;
}

bool imp_mis_commit_ok(const imp_mis_t *b, bool in_mode)
{
    bool q = true;
    if (in_mode) {
        switch (b->o.tlm.mode) {
        case IMP_MODE_IDLE:
        case IMP_MODE_DONE:
        case IMP_MODE_INFEASIBLE:
        case IMP_MODE_NO_SOLUTION:
        case IMP_MODE_ABORTED:
        case IMP_MODE_FAULT:
            q = true;
            break;
        default:
            q = false;   /* PLANNING, ARMED, FIRING, FINAL: the commit waits */
            break;
        }
    }
    return q;
}

void imp_mis_ranges(const imp_mis_t *b, fsw_range_t *r)
{
    uint32_t i;
    (void)b;
    for (i = 0u; i < IMP_NAX; i++) {
        r[i].min = -IMP_NAV_POS_MAX_MM;
        r[i].max = IMP_NAV_POS_MAX_MM;
        r[IMP_NAX + i].min = -IMP_NAV_VEL_MAX_CNT;
        r[IMP_NAX + i].max = IMP_NAV_VEL_MAX_CNT;
    }
    r[IMP_CH_NAV_STEP].min = 0;
    r[IMP_CH_NAV_STEP].max = INT32_MAX;
}

void imp_mis_enter(imp_mis_t *b)
{
    (void)imp_init(&b->s, &b->p, &b->o);
}

/* Negative step arguments have no meaning: they become a time START refuses. */
static uint32_t step_arg(int32_t a)
{
    return (a < 0) ? 0u : (uint32_t)a;
}

uint32_t imp_mis_step(imp_mis_t *b, const fsw_acc_t *acc, int32_t *act)
{
    imp_in_t *ii = &b->in;
    uint32_t i;
    uint32_t j;
    bool ok = (acc->valid & IMP_SAMPLE_ALL) == IMP_SAMPLE_ALL;
    ii->step = (uint32_t)((uint64_t)acc->seq & 0xFFFFFFFFu);
    ii->nav_valid = ok ? 1u : 0u;
    for (i = 0u; i < IMP_NAX; i++) {
        ii->nav_pos_mm[i] = ok ? acc->cnt[i] : 0;
        ii->nav_vel_cnt[i] = ok ? acc->cnt[IMP_NAX + i] : 0;
        ii->cmd_tgt_pos_mm[i] = acc->tc_arg[2u + i];
        ii->cmd_tgt_vel_cnt[i] = acc->tc_arg[5u + i];
    }
    ii->nav_step = ok ? (uint32_t)acc->cnt[IMP_CH_NAV_STEP] : 0u;
    ii->avail_mask = (uint8_t)IMP_THR_ALL;
    /* acc->tc is a local id 1..IMP_CMD_MAX (the executive checked it) or IMP_CMD_NONE. */
    ii->cmd = (uint8_t)(acc->tc & 0xFFu);
    ii->cmd_t0_step = step_arg(acc->tc_arg[0]);
    ii->cmd_tf_step = step_arg(acc->tc_arg[1]);
    imp_step(&b->s, &b->p, ii, &b->o);
    for (j = 0u; j < IMP_NTHR; j++) {
        /* within one period (imp_step's invariant), so the int32 conversion is exact */
        uint32_t s0 = b->o.on_start_cnt[j] & 0x7FFFFFFFu;
        uint32_t l0 = b->o.on_len_cnt[j] & 0x7FFFFFFFu;
        act[j] = (int32_t)s0;
        act[IMP_NTHR + j] = (int32_t)l0;
    }
    act[IMP_ACT_MASK] = (int32_t)b->o.on_mask;
    return b->o.health;
}

const imp_tlm_t *imp_mis_tlm(const imp_mis_t *b)
{
    return &b->o.tlm;
}
