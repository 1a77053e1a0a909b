/*
 * rly_mission.c — relay's adapter to the executive (RELAY; fsw/app/fsw_mission.h).
 *
 * The law runs only in the mission mode and restarts (rly_init) on every entry; outside it the
 * actuator holds RLY_LVL_OFF. Faults that raise FSW_H_MODULE: SENSOR_LOST, ENV_SAT and any fx
 * status; none sends the executive to SAFE (COAST is the module's own safe state, spec 20 §8 F2).
 * Commit rule (spec 20 §8): a validated table becomes active at a window boundary (or at once
 * outside the mission mode); in the mode the copy is re-anchored under the new constants at its
 * current state and k_t is held inside the new limits (rly_retable), the law's state is kept.
 * A table whose geometry (epsilon, gamma, the modes) differs also waits for the law to be in W+,
 * W- or COAST (level off, left through W) at a window boundary, so no pulse or brake ever runs
 * across a moved deadband edge. The
 * table is applied whole (one revision in force, no second 384-B parameter set held back);
 * fsw/relay/README.md says why this replaces the spec's "geometry at the next W entry".
 * Telecommand RESET_COUNTERS clears the module's counters and sticky health.
 */
#include "rly_mission.h"

#define RLY_FAULT_BITS (RLY_H_SENSOR_LOST | RLY_H_ENV_SAT | FX_ST_MASK)

FX_STATIC_ASSERT(rly_mis_sa_tlm,
                 RLY_TLM_TOTAL_BYTES == (FSW_TLM_HEAD_BYTES + (4u * RLY_N_ACT) + 4u + RLY_TLM_BYTES));

static const int32_t RLY_SAFE_ACT[RLY_N_ACT] = {(int32_t)RLY_LVL_OFF};

const fsw_mis_desc_t RLY_MIS_DESC = {
    RLY_N_SENS, RLY_N_ACT, 0u, RLY_FAULT_BITS,
    0u,   /* safe_bits: none (COAST is the module's safe state) */
    RLY_CMD_MAX,
    RLY_TLM_LAYOUT, RLY_TLM_TOTAL_BYTES,
    &RLY_TBL_DESC, RLY_SAFE_ACT,
};

void rly_mis_reset(rly_mis_t *b)
{
    static const rly_out_t out_zero = {0};
    b->have_p = false;
    b->o = out_zero;
}

uint32_t rly_mis_check(rly_mis_t *b, const uint8_t *pl, uint32_t len, uint32_t period_us)
{
    uint32_t why = 0u;
    uint32_t d = FSW_VETO_UNDECODED;
    if (rly_table_decode(pl, len, 0u, &b->cand) == FSW_OK) {
        if (rly_params_check(&b->cand, &why) != FSW_OK) {
            d = fsw_table_veto_detail(why);
        } else if (b->cand.period_us != period_us) {
            d = fsw_table_veto_detail(RLY_WHY_PERIOD);
        } else {
            d = 0u;
        }
    }
    return d;
}

bool rly_mis_load(rly_mis_t *b, const uint8_t *pl, uint32_t len, uint32_t rev, bool in_mode)
{
    bool ok = false;
    if (rly_table_decode(pl, len, rev, &b->cand) == FSW_OK) {
        if (in_mode && b->have_p) {
            rly_retable(&b->s, &b->p, &b->cand);
        }
        b->p = b->cand;
        b->have_p = true;
        ok = true;
    }
    return ok;
}

/* Same deadband edges and the same modal copy (the constants rly_step's tests and the envelope
   copy use; q0/p0 only seed a run and f_q64 only checks dphi). */
static bool same_geometry(const rly_params_t *a, const rly_params_t *c)
{
    bool same = (a->eps_q24 == c->eps_q24) && (a->gamma_q24 == c->gamma_q24) && (a->n_modes == c->n_modes);
    uint32_t i;
    for (i = 0u; i < RLY_MAX_MODES; i++) {
        same = same && (a->dphi_bam64[i] == c->dphi_bam64[i]) && (a->cu_q40[i] == c->cu_q40[i]) &&
               (a->ce_q40[i] == c->ce_q40[i]);
    }
    return same;
}

bool rly_mis_commit_ok(const rly_mis_t *b, bool in_mode)
{
    /* b->cand: the candidate the executive holds READY (rly_mis_check decoded it; nothing else
       writes it until the commit's rly_mis_load). w_n == 0: the last step closed a window. */
    bool ok = (!in_mode) || (!b->have_p);
    if ((!ok) && (b->s.w_n == 0u)) {
        ok = same_geometry(&b->p, &b->cand) || (b->s.st == RLY_ST_W_POS) || (b->s.st == RLY_ST_W_NEG) ||
             (b->s.st == RLY_ST_COAST);
    }
    return ok;
}

void rly_mis_ranges(const rly_mis_t *b, fsw_range_t *r)
{
    (void)b;   /* the sensor's whole range; the module refuses |x| > x_max itself (X_RANGE, counted) */
    r[0].min = -RLY_X_FULL_Q24;
    r[0].max = RLY_X_FULL_Q24;
}

void rly_mis_enter(rly_mis_t *b)
{
    rly_init(&b->s, &b->p);
}

uint32_t rly_mis_step(rly_mis_t *b, const fsw_acc_t *acc, int32_t *act)
{
    static const rly_in_t in_zero = {0};
    rly_in_t in = in_zero;
    if (acc->tc == RLY_CMD_RESET_COUNTERS) {
        rly_tlm_t *t = &b->s.tlm;
        t->n_x_invalid = 0u;
        t->n_x_range = 0u;
        t->n_lost = 0u;
        t->n_tau_sat = 0u;
        t->n_kt_clamped = 0u;
        t->n_env_sat = 0u;
        t->n_reinit = 0u;
        t->n_env_high = 0u;
        t->health_sticky = 0u;
    }
    in.x_q24 = acc->cnt[0];
    in.valid = ((acc->valid & 1u) != 0u) && ((acc->sat & 1u) == 0u);
    rly_step(&b->s, &b->p, &in, &b->o);
    act[0] = (int32_t)b->o.cmd;
    return b->o.health;
}

const rly_tlm_t *rly_mis_tlm(const rly_mis_t *b)
{
    return &b->s.tlm;
}
