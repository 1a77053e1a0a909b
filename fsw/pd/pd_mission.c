/*
 * pd_mission.c — pd's adapter to the executive (HOLD; fsw/app/fsw_mission.h).
 *
 * The three channel laws run only in the mission mode and restart on every entry (outside it the
 * actuators hold their safe value, zero torque). A channel whose ch_mask bit is clear commands zero.
 * No channel fault is a SAFE trigger: the law's own rules (hold, coast, refuse) are the response of
 * spec 40 §8, and the executive's stale-frame rule still applies to the whole frame. Commit rule: a
 * validated table becomes active at the next step boundary and, in the mode, restarts the channels
 * (their period, derivative and telecommanded overrides follow the new table).
 * Telecommands: RESET_COUNTERS, SET_SOURCE (0 FIXED, 1 GROUND, 2 ADAPTIVE: taken by the channels with
 * a usable estimator block, all three with the committed tables), SET_F (1e-6 Hz; selects GROUND),
 * SET_K2 (three words, 2^-8 s; selects FIXED): one command sets a whole gain source.
 */
#include "pd_mission.h"

/* Fault bits: the step's fx status (the law has no designed fx saturation). */
#define PD_FAULT_BITS (FX_ST_MASK)

FX_STATIC_ASSERT(pd_mis_sa_tlm,
                 PD_TLM_TOTAL_BYTES == (FSW_TLM_HEAD_BYTES + (4u * PD_N_ACT) + 4u + PD_TLM_BYTES));
FX_STATIC_ASSERT(pd_mis_sa_ch, (PD_N_ACT == PD_N_CH) && (PD_N_SENS == (2u * PD_N_CH)));

static const int32_t PD_SAFE_ACT[PD_N_ACT] = {0};

const fsw_mis_desc_t PD_MIS_DESC = {
    PD_N_SENS, PD_N_ACT, FSW_MIS_STALE_SAFE, PD_FAULT_BITS,
    0u,   /* safe_bits: none; the law coasts on its own */
    PD_CMD_MAX,
    PD_TLM_LAYOUT, PD_TLM_TOTAL_BYTES,
    &PD_TBL_DESC, PD_SAFE_ACT,
};

void pd_params_of(const pd_table_t *t, uint32_t k, pd_params_t *p)
{
    p->c = t->c;
    p->g = t->ch[(k < PD_N_CH) ? k : 0u];
}

uint32_t pd_table_check(const pd_table_t *t, pd_params_t *p, uint32_t *why)
{
    uint32_t w = 0u;
    uint32_t k;
    for (k = 0u; k < PD_N_CH; k++) {
        uint32_t wk = 0u;
        pd_params_of(t, k, p);
        if ((((uint32_t)t->c.ch_mask >> k) & 1u) == 0u) {
            /* a channel that does not fly needs no gain source (yaw's estimator block is refused:
               an ADAPTIVE table flies pitch and roll with ch_mask 6) */
            p->c.src = (uint8_t)PD_SRC_FIXED;
        }
        (void)pd_params_check(p, &wk);
        w |= wk;
    }
    if (t->ch[1].k2_max_q22 > PD_ROLL_K2_CAP_Q22) {
        w |= PD_WHY_CAP;
    }
    if (why != NULL) {
        *why = w;
    }
    return w;
}

void pd_mis_reset(pd_mis_t *b)
{
    static const pd_out_t out_zero = {0};   /* rodata: a struct copy without a stack temporary */
    uint32_t k;
    b->have_p = false;
    b->n_loads = 0u;
    b->have_seq = false;
    b->health = 0u;
    for (k = 0u; k < PD_N_CH; k++) {
        b->o[k] = out_zero;
    }
}

uint32_t pd_mis_check(pd_mis_t *b, const uint8_t *pl, uint32_t len, uint32_t period_us)
{
    uint32_t why = 0u;
    uint32_t d = FSW_VETO_UNDECODED;
    /* The revision is informative; the check does not depend on it. */
    if (pd_table_decode(pl, len, 0u, &b->cand) == FSW_OK) {
        if (pd_table_check(&b->cand, &b->chk, &why) != 0u) {
            d = fsw_table_veto_detail(why);
        } else if (b->cand.c.period_us != period_us) {
            d = fsw_table_veto_detail(PD_WHY_PERIOD);
        } else {
            d = 0u;
        }
    }
    return d;
}

static void restart(pd_mis_t *b)
{
    uint32_t k;
    for (k = 0u; k < PD_N_CH; k++) {
        pd_init(&b->s[k], &b->p[k]);
    }
    b->have_seq = false;
}

bool pd_mis_load(pd_mis_t *b, const uint8_t *pl, uint32_t len, uint32_t rev, bool in_mode)
{
    bool ok = false;
    if (pd_table_decode(pl, len, rev, &b->cand) == FSW_OK) {
        uint32_t k;
        b->t = b->cand;
        for (k = 0u; k < PD_N_CH; k++) {
            pd_params_of(&b->t, k, &b->p[k]);
        }
        b->have_p = true;
        fx_cnt_inc(&b->n_loads);
        if (in_mode) {
            restart(b);
        }
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
    uint32_t i;
    (void)b;
    for (i = 0u; i < PD_N_SENS; i++) {
        r[i].min = INT32_MIN;   /* the law refuses out-of-range samples itself (range_rej) */
        r[i].max = INT32_MAX;
    }
}

void pd_mis_enter(pd_mis_t *b)
{
    restart(b);
}

static void telecommand(pd_mis_t *b, const fsw_acc_t *acc)
{
    uint32_t k;
    for (k = 0u; k < PD_N_CH; k++) {
        pd_state_t *s = &b->s[k];
        const pd_params_t *p = &b->p[k];
        if (acc->tc == PD_CMD_RESET_COUNTERS) {
            pd_reset_counters(s);
        } else if (acc->tc == PD_CMD_SET_SOURCE) {
            if ((acc->tc_arg[0] >= 0) && (acc->tc_arg[0] <= (int32_t)PD_SRC_ADAPTIVE)) {
                (void)pd_set_source(s, p, (uint8_t)acc->tc_arg[0]);   /* refused: the source stays */
            }
        } else if (acc->tc == PD_CMD_SET_F) {
            if ((acc->tc_arg[0] >= 0) && (acc->tc_arg[0] < 500000)) {
                /* 1e-6 Hz -> uq32 Hz: round(u 2^32 / 10^6), u < 5e5 so u 2^32 < 2^51 */
                const uint32_t uhz = (uint32_t)acc->tc_arg[0];
                const uint64_t f = fx_udiv_rnd64((uint64_t)uhz << 32, 1000000u);
                pd_set_f_ground(s, (uint32_t)f);
                (void)pd_set_source(s, p, (uint8_t)PD_SRC_GROUND);
            }
        } else if (acc->tc == PD_CMD_SET_K2) {
            const int32_t a = acc->tc_arg[k];
            if ((a >= 0) && (a < (1023 * 256))) {
                const uint32_t k2 = (uint32_t)a;
                pd_set_k2_fixed(s, p, k2 << 14);   /* 2^-8 s -> uq22 */
                (void)pd_set_source(s, p, (uint8_t)PD_SRC_FIXED);
            }
        } else {
            /* no telecommand this step */
        }
    }
}

/* The sample instants are every n_div-th frame counted by seq from the mode entry, so a frame lost on
   the link (it never reaches fsw_step) neither shifts the phase nor goes unnoticed: the next sample
   frame finds its index more than one past the last and notes the gap (pd_note_gap). A frame whose
   seq did not advance is stale: at a sample instant the channels see it as missing. */
static void run_channels(pd_mis_t *b, const fsw_acc_t *acc, bool fresh, uint32_t gap)
{
    uint32_t h = 0u;
    uint32_t k;
    for (k = 0u; k < PD_N_CH; k++) {
        if (((uint32_t)b->t.c.ch_mask & (1u << k)) != 0u) {
            pd_in_t in;
            const uint32_t ys = 1u << k;
            const uint32_t bs = 1u << (k + PD_N_CH);
            if (gap > 0u) {
                pd_note_gap(&b->s[k], &b->p[k], gap);
            }
            in.y_cnt = acc->cnt[k];
            in.y_valid = fresh && ((acc->valid & ys) != 0u);
            in.y_sat = (acc->sat & ys) != 0u;
            in.beta_cnt = acc->cnt[k + PD_N_CH];
            in.beta_valid = fresh && ((acc->valid & bs) != 0u) && ((acc->sat & bs) == 0u);
            pd_step(&b->s[k], &b->p[k], &in, &b->o[k]);
            h |= b->o[k].health;
        } else {
            b->o[k].m_q28 = 0;
            b->o[k].m_cnt = 0;
            b->o[k].health = 0u;
        }
        b->tlm.ch[k] = b->s[k].tlm;
    }
    if (b->n_loads == 1u) {
        h |= PD_H_TABLE_DEFAULT;
    }
    b->health = h;
}

uint32_t pd_mis_step(pd_mis_t *b, const fsw_acc_t *acc, int32_t *act)
{
    uint32_t k;
    const int64_t nd = (int64_t)b->t.c.n_div;   /* >= 1 (loader limits) */
    if (!b->have_seq) {
        b->seq0 = acc->seq;
        b->last_idx = -1;
        b->last_seq = acc->seq - 1;
        b->have_seq = true;
    }
    if (acc->tc != PD_CMD_NONE) {
        telecommand(b, acc);
    }
    if (acc->seq >= b->seq0) {
        const int64_t rel = acc->seq - b->seq0;
        const bool fresh = acc->seq != b->last_seq;
        if ((rel % nd) == 0) {
            const int64_t idx = rel / nd;
            const int64_t g = (idx > b->last_idx) ? (idx - b->last_idx - 1) : 0;
            const uint32_t gap = (g > 1000000) ? 1000000u : (uint32_t)g;
            run_channels(b, acc, fresh, (b->last_idx >= 0) ? gap : 0u);
            b->last_idx = (idx > b->last_idx) ? idx : b->last_idx;
        }
        b->last_seq = acc->seq;
    }
    for (k = 0u; k < PD_N_CH; k++) {
        act[k] = b->o[k].m_cnt;
    }
    b->tlm.revision = b->t.c.revision;
    return b->health;
}

const pd_tlm_t *pd_mis_tlm(const pd_mis_t *b)
{
    return &b->tlm;
}
