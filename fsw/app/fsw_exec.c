/*
 * fsw_exec.c — the executive (spec 00 §3.3). See fsw_exec.h for the step order; the missions
 * are reached only through the generated dispatch (fsw_missions_gen.h).
 *
 * Mode rules (fsw/app/README.md "Executive"):
 *   BOOT     -> cfg.boot_mode at the first step when the table is valid, else SAFE
 *   STANDBY <-> the mission mode by command; any mode -> SAFE by command
 *   SAFE     -> STANDBY by command only; entered automatically on a channel invalid (or at full
 *              scale) for stale_max steps where the mission declares it a SAFE trigger, a failed
 *              scrub, or no valid table
 * Module faults raise FSW_H_MODULE and are reported, not SAFE triggers (README "Executive").
 */
#include "fsw_exec.h"

/* The state every mission starts from: BOOT, no table, counters zero. */
static void reset_common(fsw_t *f, const fsw_cfg_t *cfg)
{
    /* Read-only zero image (rodata, no state) so the reset is a struct copy without a large
       stack temporary. */
    static const fsw_tlm_t tlm_zero = {0};
    uint32_t i;
    f->cfg = *cfg;
    f->init_ok = false;
    f->have_p = false;
    f->tbl_rej_pending = false;
    f->mode = FSW_MODE_BOOT;
    f->step = 0u;
    for (i = 0u; i < FSW_IN_MAX; i++) {
        f->last_good[i] = 0;
        f->stale_run[i] = 0u;
        f->sat_run[i] = 0u;
    }
    f->tlm = tlm_zero;
    f->tlm.mission = cfg->mission;
    fsw_mis_reset(cfg->mission, &f->m);
}

static bool cfg_ok(const fsw_cfg_t *cfg)
{
    bool ok = false;
    if ((cfg != NULL) && (fsw_mis_desc(cfg->mission) != NULL)) {
        ok = (cfg->period_us > 0u) && (cfg->stale_max >= 1u) &&
             ((cfg->boot_mode == FSW_MODE_STANDBY) || (cfg->boot_mode == fsw_mis_mode(cfg->mission)));
    }
    return ok;
}

fsw_rc_t fsw_init(fsw_t *f, const fsw_cfg_t *cfg, const uint8_t *boot, uint32_t boot_len)
{
    fsw_rc_t rc = FSW_ERR_ARG;
    /* boot == NULL with boot_len == 0: no table in the image; one arrives by upload. */
    bool tableless = (boot == NULL) && (boot_len == 0u);
    if ((f != NULL) && ((boot != NULL) || tableless) && cfg_ok(cfg)) {
        const fsw_mis_desc_t *d = fsw_mis_desc(cfg->mission);
        uint32_t why = 0u;
        uint32_t len = 0u;
        const uint8_t *pl = NULL;
        reset_common(f, cfg);
        rc = fsw_table_init(&f->tbl, d->table, boot, boot_len, &why);
        if (rc == FSW_OK) {
            pl = fsw_table_payload(&f->tbl, &len);
        }
        if (tableless) {
            /* nothing refused: NO_TABLE (and SAFE) until an upload commits */
        } else if (pl != NULL) {
            uint32_t v = fsw_mis_check(cfg->mission, &f->m, pl, len, cfg->period_us);
            if ((v == 0u) &&
                fsw_mis_load(cfg->mission, &f->m, pl, len, fsw_table_revision(&f->tbl), false)) {
                f->init_ok = true;
                f->have_p = true;
                /* The module starts from its table: its telemetry is meaningful from step 1. */
                fsw_mis_enter(cfg->mission, &f->m);
            } else {
                f->tlm.tbl_reason = FSW_TBL_R_MODULE | (v << FSW_TBL_DETAIL_SHIFT);
                rc = FSW_ERR_INVARIANT;
            }
        } else {
            f->tlm.tbl_reason = why;
            if (rc == FSW_OK) {
                rc = FSW_ERR_INVARIANT;
            }
        }
        if ((!f->init_ok) && (!tableless)) {
            fx_cnt_inc(&f->tlm.n_tbl_rej);
        }
        f->tlm.tbl_revision = fsw_table_revision(&f->tbl);
    }
    return rc;
}

const fsw_table_t *fsw_mission_table(const fsw_t *f)
{
    return (f != NULL) ? &f->tbl : NULL;
}

fsw_rc_t fsw_table_upload(fsw_t *f, const fsw_table_chunk_t *c, uint32_t *why)
{
    fsw_rc_t rc = FSW_ERR_ARG;
    uint32_t w = 0u;
    if ((f != NULL) && (c != NULL)) {
        /* The mission's table: a chunk for another table id is refused by its loader (UPLOAD_ID). */
        fsw_table_t *t = &f->tbl;
        uint32_t before = t->rejects;
        rc = fsw_table_chunk(t, c, &w);
        if ((rc == FSW_OK) && (t->state == FSW_TBL_S_READY)) {
            uint32_t len = 0u;
            const uint8_t *pl = fsw_table_candidate(t, &len);
            uint32_t d = fsw_mis_check(f->cfg.mission, &f->m, pl, len, f->cfg.period_us);
            if (d != 0u) {
                rc = fsw_table_veto(t, d, &w);
                if (rc == FSW_OK) {
                    rc = FSW_ERR_INVARIANT;
                }
            }
        }
        if (t->rejects != before) {
            f->tbl_rej_pending = true;
            f->tlm.tbl_reason = w;
            fx_cnt_inc(&f->tlm.n_tbl_rej);
        }
    } else {
        /* null arguments: FSW_ERR_ARG */
    }
    if (why != NULL) {
        *why = w;
    }
    return rc;
}

/* The mission's channel ranges under the active table; without one nothing is accepted. */
static void ranges(const fsw_t *f, uint32_t n, fsw_range_t *r)
{
    if (f->have_p) {
        fsw_mis_ranges(f->cfg.mission, &f->m, r);
    } else {
        uint32_t i;
        for (i = 0u; i < n; i++) {
            r[i].min = 1;
            r[i].max = -1;
        }
    }
}

void fsw_sensor_ranges(const fsw_t *f, fsw_range_t *r, uint32_t *n)
{
    if ((f != NULL) && (r != NULL) && (n != NULL)) {
        const fsw_mis_desc_t *d = fsw_mis_desc(f->cfg.mission);
        *n = (d != NULL) ? d->n_sens : 0u;
        ranges(f, *n, r);
    }
}

static void zero_out(const fsw_mis_desc_t *d, fsw_out_t *out)
{
    uint32_t i;
    out->n_act = (d != NULL) ? d->n_act : 0u;
    for (i = 0u; i < FSW_ACT_MAX; i++) {
        out->act_cnt[i] = ((d != NULL) && (i < d->n_act)) ? d->safe_act[i] : 0;
    }
    out->mode = FSW_MODE_BOOT;
    out->health = 0u;
}

/* Step 1: the mission's table at the step boundary (commit when the mission allows it, scrub)
   and a refusal since the last step. Returns the executive health bits of this part. */
static uint32_t tables_at_boundary(fsw_t *f)
{
    uint32_t hx = 0u;
    uint32_t mission = f->cfg.mission;
    if (f->tbl.state == FSW_TBL_S_READY) {
        bool in_mode = f->mode == fsw_mis_mode(mission);
        if (!fsw_mis_commit_ok(mission, &f->m, in_mode)) {
            hx |= FSW_H_TBL_PENDING;
        } else if (fsw_table_commit(&f->tbl)) {
            uint32_t len = 0u;
            const uint8_t *pl = fsw_table_payload(&f->tbl, &len);
            f->have_p = (pl != NULL) && fsw_mis_load(mission, &f->m, pl, len, fsw_table_revision(&f->tbl), in_mode);
            if (f->have_p) {
                f->init_ok = true;
                hx |= FSW_H_TBL_NEW;
                fx_cnt_inc(&f->tlm.n_tbl_acc);
            }
        } else {
            /* not reached: a READY candidate always commits */
        }
    }
    if (!f->have_p) {
        hx |= FSW_H_NO_TABLE;
    }
    if ((f->mode != FSW_MODE_BOOT) && (fsw_table_scrub(&f->tbl) != FSW_OK)) {
        hx |= FSW_H_SCRUB;
    }
    if (f->tbl_rej_pending) {
        hx |= FSW_H_TBL_REJ;
        f->tbl_rej_pending = false;
    }
    return hx;
}

/* Steps 2-3, validity: channel i is accepted when the frame carries it, its STALE bit is clear
   and its count lies in the mission's range. A FSW_MIS_SAMPLE mission's channels are valid only
   together. Returns the mask of accepted channels. */
static uint32_t valid_mask(fsw_t *f, const fsw_mis_desc_t *d, const fsw_in_t *in, uint32_t all)
{
    uint32_t i;
    uint32_t valid = 0u;
    ranges(f, d->n_sens, f->rng);
    for (i = 0u; i < d->n_sens; i++) {
        int32_t c = in->counts[i];
        bool ok = (i < in->n_counts) && ((in->status[i] & FSW_ST_STALE) == 0u);
        if (ok && (c >= f->rng[i].min) && (c <= f->rng[i].max)) {
            valid |= (uint32_t)1u << i;
        }
    }
    if (((d->flags & FSW_MIS_SAMPLE) != 0u) && (valid != all)) {
        valid = 0u;
    }
    return valid;
}

/* Steps 2-3, bookkeeping: an accepted channel updates its last good value, an invalid one keeps
   it and is counted (a FSW_MIS_SAMPLE mission's refused sample counts once); persistence for
   stale_max steps raises the SAFE triggers the mission declares. */
static void accept_inputs(fsw_t *f, const fsw_mis_desc_t *d, const fsw_in_t *in, uint32_t *hx)
{
    uint32_t i;
    uint32_t n = d->n_sens;
    uint32_t all = (n >= 32u) ? 0xFFFFFFFFu : (((uint32_t)1u << n) - 1u);
    bool sample = (d->flags & FSW_MIS_SAMPLE) != 0u;
    fsw_acc_t *acc = &f->acc;
    acc->seq = in->seq;
    acc->valid = valid_mask(f, d, in, all);
    acc->sat = 0u;
    if (in->n_counts < n) {
        fx_cnt_inc(&f->tlm.n_in_bad);
    }
    for (i = 0u; i < n; i++) {
        uint32_t bit = (uint32_t)1u << i;
        bool ok = (acc->valid & bit) != 0u;
        if (ok) {
            f->last_good[i] = in->counts[i];
            f->stale_run[i] = 0u;
        } else {
            fx_cnt_inc(&f->stale_run[i]);
            if (!sample) {
                fx_cnt_inc(&f->tlm.n_chan_rej);
            }
        }
        if (ok && ((in->status[i] & FSW_ST_SAT) != 0u)) {
            acc->sat |= bit;
            fx_cnt_inc(&f->sat_run[i]);
        } else {
            f->sat_run[i] = 0u;
        }
        acc->cnt[i] = f->last_good[i];
        if (((d->flags & FSW_MIS_STALE_SAFE) != 0u) && (f->stale_run[i] >= (uint32_t)f->cfg.stale_max)) {
            *hx |= FSW_H_STALE_PERSIST;
        }
        if (((d->flags & FSW_MIS_SAT_SAFE) != 0u) && (f->sat_run[i] >= (uint32_t)f->cfg.stale_max)) {
            *hx |= FSW_H_SAT_PERSIST;
        }
    }
    if (acc->valid != all) {
        *hx |= FSW_H_STALE;
        fx_cnt_inc(&f->tlm.n_stale_steps);
        if (sample) {
            fx_cnt_inc(&f->tlm.n_chan_rej);
        }
    }
}

static bool cmd_allowed(uint32_t mm, uint32_t from, uint32_t to)
{
    bool ok = false;
    if (from == FSW_MODE_STANDBY) {
        ok = (to == mm) || (to == FSW_MODE_SAFE) || (to == FSW_MODE_STANDBY);
    } else if (from == FSW_MODE_SAFE) {
        ok = (to == FSW_MODE_STANDBY) || (to == FSW_MODE_SAFE);
    } else if (from == mm) {
        ok = (to == FSW_MODE_STANDBY) || (to == FSW_MODE_SAFE) || (to == mm);
    } else {
        ok = false;   /* BOOT is not commandable */
    }
    return ok;
}

/* Step 4: returns the mode of this step. */
static uint32_t next_mode(fsw_t *f, uint32_t mm, const fsw_in_t *in, uint32_t *hx)
{
    uint32_t m = f->mode;
    if (m == FSW_MODE_BOOT) {
        m = f->init_ok ? f->cfg.boot_mode : FSW_MODE_SAFE;
    } else if (in->mode_cmd != FSW_CMD_NONE) {
        if (cmd_allowed(mm, m, in->mode_cmd)) {
            m = in->mode_cmd;
        } else {
            *hx |= FSW_H_MODE_REJ;
            fx_cnt_inc(&f->tlm.n_mode_rej);
        }
    } else {
        /* no command: keep */
    }
    if ((*hx & (FSW_H_STALE_PERSIST | FSW_H_SAT_PERSIST | FSW_H_SCRUB | FSW_H_NO_TABLE)) != 0u) {
        m = FSW_MODE_SAFE;
    }
    return m;
}

/* Step 5: this step's telecommand. Taken when its namespace is this mission's, its local id
   exists and the mission mode flies; anything else is refused and counted. */
static void take_tc(fsw_t *f, const fsw_mis_desc_t *d, const fsw_in_t *in, bool in_mode, uint32_t *hx)
{
    uint32_t i;
    fsw_acc_t *acc = &f->acc;
    acc->tc = 0u;
    for (i = 0u; i < FSW_TC_ARGS; i++) {
        acc->tc_arg[i] = in->tc_arg[i];
    }
    if (in->tc != FSW_TC_NONE) {
        uint32_t ns = FSW_TC_ID(f->cfg.mission, 0u);
        uint32_t local = in->tc & FSW_TC_LOCAL_MASK;
        bool known = ((in->tc & ~FSW_TC_LOCAL_MASK) == ns) && (local >= 1u) && (local <= d->tc_max);
        if (known && in_mode) {
            acc->tc = local;
            fx_cnt_inc(&f->tlm.n_tc);
        } else {
            *hx |= FSW_H_TC_REJ;
            fx_cnt_inc(&f->tlm.n_tc_rej);
        }
    }
}

/* Step 7: health aggregation and telemetry. */
static void fill_tlm(fsw_t *f, const fsw_mis_desc_t *d, const fsw_in_t *in, uint32_t mod_h, fsw_out_t *out)
{
    uint32_t i;
    const fsw_table_t *t = &f->tbl;
    f->tlm.utime_us = in->utime_us;
    f->tlm.seq = in->seq;
    f->tlm.step = f->step;
    f->tlm.mode = out->mode;
    f->tlm.health = out->health;
    f->tlm.health_sticky |= out->health;
    if (t->rejects != 0u) {
        f->tlm.tbl_reason = t->last_reason;
    }
    f->tlm.tbl_revision = fsw_table_revision(t);
    f->tlm.n_scrub_err = t->scrub_errs;
    f->tlm.host_missed = in->host_missed;
    f->tlm.host_rejected = in->host_rejected;
    for (i = 0u; i < FSW_ACT_MAX; i++) {
        f->tlm.act_cnt[i] = (i < d->n_act) ? out->act_cnt[i] : 0;
    }
    f->tlm.mod_health = mod_h;
    fsw_mis_tlm(f->cfg.mission, &f->m, &f->tlm.m);
    out->tlm = f->tlm;
}

void fsw_step(fsw_t *f, const fsw_in_t *in, fsw_out_t *out)
{
    const fsw_mis_desc_t *d = fsw_mis_desc(f->cfg.mission);
    zero_out(d, out);
    fx_cnt_inc(&f->step);
    if (d == NULL) {
        /* Never initialised for a mission of this build (fsw_init refused the cfg): nothing can
           fly; report it and command nothing. */
        out->mode = FSW_MODE_SAFE;
        out->health = FSW_H_NO_TABLE | FSW_H_SAFE;
        f->tlm.step = f->step;
        f->tlm.mode = out->mode;
        f->tlm.health = out->health;
        f->tlm.health_sticky |= out->health;
        out->tlm = f->tlm;
    } else {
        uint32_t mm = fsw_mis_mode(f->cfg.mission);
        uint32_t hx = tables_at_boundary(f);
        uint32_t mode;
        uint32_t mod_h = 0u;
        accept_inputs(f, d, in, &hx);
        mode = next_mode(f, mm, in, &hx);
        if ((mode == FSW_MODE_SAFE) && (f->mode != FSW_MODE_SAFE)) {
            fx_cnt_inc(&f->tlm.n_safe);
        }
        if ((mode == mm) && (f->mode != mm)) {
            fsw_mis_enter(f->cfg.mission, &f->m);
        }
        take_tc(f, d, in, mode == mm, &hx);
        f->mode = mode;
        if (mode == mm) {
            mod_h = fsw_mis_step(f->cfg.mission, &f->m, &f->acc, out->act_cnt);
            if ((mod_h & d->fault_bits) != 0u) {
                hx |= FSW_H_MODULE;
            }
            if ((mod_h & d->safe_bits) != 0u) {
                /* The module's own persistence rule fired: its output is not to be flown. SAFE
                   from this step on (left only by command; re-entering the mission mode
                   re-initialises the module), and this step already commands the safe values. */
                uint32_t i;
                for (i = 0u; i < d->n_act; i++) {
                    out->act_cnt[i] = d->safe_act[i];
                }
                mode = FSW_MODE_SAFE;
                f->mode = mode;
                fx_cnt_inc(&f->tlm.n_safe);
                hx |= FSW_H_MODULE_SAFE | FSW_H_SAFE;
            }
        } else if (mode == FSW_MODE_SAFE) {
            hx |= FSW_H_SAFE;
        } else {
            /* STANDBY: no module runs, actuators hold their safe values */
        }
        out->mode = mode;
        out->health = hx | (mod_h & FX_ST_MASK);
        fill_tlm(f, d, in, mod_h, out);
    }
}
