/*
 * fsw_exec.c — the executive (spec 00 §3.3). See fsw_exec.h for the step order.
 *
 * Mode rules (spec 00 §3.3; fsw/app/README.md "Executive"):
 *   BOOT     → cfg.boot_mode at the first step when the observer table is valid, else SAFE
 *   STANDBY  ↔ DETUMBLE by command; any mode → SAFE by command
 *   SAFE     → STANDBY by command only; entered automatically on a channel invalid for
 *              stale_max steps, a plant SAT bit held for stale_max steps, or a failed scrub
 * The observer runs only in DETUMBLE and is re-initialised on every entry: outside DETUMBLE the
 * actuators hold their safe value (zero rate), which the observer's model would not know.
 * CMD_LIMIT_PERSIST is reported, not a SAFE trigger: with insufficient authority the spec's
 * scenario (10-observer S0-9) expects the loop to keep commanding and the plant to end DIVERGED.
 */
#include "fsw_exec.h"
#include "fx.h"

#define OBS_FAULT_BITS (OBS_H_MEAS_LOST | OBS_H_CMD_LIMIT_PERSIST | OBS_H_COV_CLIP | 0xFFu)

static void zero_out(fsw_out_t *out)
{
    uint32_t i;
    out->n_act = FSW_N_ACT;
    for (i = 0u; i < FSW_ACT_MAX; i++) {
        out->act_cnt[i] = 0;
    }
    out->mode = FSW_MODE_BOOT;
    out->health = 0u;
}

/* Decodes the active observer image into f->obs_p. */
static bool load_active(fsw_t *f)
{
    uint32_t len = 0u;
    bool ok = false;
    const uint8_t *pl = fsw_table_payload(&f->obs_tbl, &len);
    if ((pl != NULL) &&
        (fsw_obs_table_decode(pl, len, fsw_table_revision(&f->obs_tbl), &f->obs_cand) == FSW_OK)) {
        f->obs_p = f->obs_cand;
        ok = true;
    }
    f->have_obs_p = ok;
    return ok;
}

/* Module check of a READY candidate: decode, obs_params_check, and the executive's own
   invariant (same period). A failure vetoes it with the module's why (low 8 bits). */
static fsw_rc_t check_candidate(fsw_t *f, uint32_t *why)
{
    fsw_rc_t rc = FSW_OK;
    uint32_t len = 0u;
    uint32_t mwhy = 0u;
    const uint8_t *pl = fsw_table_candidate(&f->obs_tbl, &len);
    if (pl == NULL) {
        rc = FSW_ERR_STATE;
    } else {
        /* The revision is informative; the check does not depend on it. */
        if (fsw_obs_table_decode(pl, len, 0u, &f->obs_cand) != FSW_OK) {
            mwhy = 0xFFu;
        } else if (obs_params_check(&f->obs_cand, &mwhy) != FSW_OK) {
            mwhy = (mwhy == 0u) ? 0xFFu : mwhy;
        } else if (f->obs_cand.period_us != f->cfg.period_us) {
            mwhy = OBS_WHY_PERIOD;
        } else {
            mwhy = 0u;
        }
        if (mwhy != 0u) {
            rc = fsw_table_veto(&f->obs_tbl, mwhy, why);
            if (rc == FSW_OK) {
                rc = FSW_ERR_INVARIANT;
            }
        }
    }
    return rc;
}

fsw_rc_t fsw_init(fsw_t *f, const fsw_cfg_t *cfg, const obs_params_t *boot_obs, uint32_t revision)
{
    fsw_rc_t rc = FSW_ERR_ARG;
    if ((f != NULL) && (cfg != NULL) && (boot_obs != NULL) && (cfg->period_us > 0u) &&
        (cfg->stale_max >= 1u) &&
        ((cfg->boot_mode == FSW_MODE_STANDBY) || (cfg->boot_mode == FSW_MODE_DETUMBLE))) {
        /* Read-only zero images (rodata, no state) so the reset is a struct copy without a
           large stack temporary. */
        static const fsw_tlm_t tlm_zero = {0};
        static const obs_out_t obs_out_zero = {0};
        uint8_t *img = f->boot_img;   /* fsw_table_init resets obs_tbl, then copies it */
        uint32_t n;
        uint32_t why = 0u;
        f->cfg = *cfg;
        f->init_ok = false;
        f->mode = FSW_MODE_BOOT;
        f->step = 0u;
        f->have_obs_p = false;
        f->tbl_rej_pending = false;
        f->last_good[0] = 0;
        f->last_good[1] = 0;
        f->stale_run[0] = 0u;
        f->stale_run[1] = 0u;
        f->sat_run[0] = 0u;
        f->sat_run[1] = 0u;
        f->tlm = tlm_zero;
        f->obs_o = obs_out_zero;
        n = fsw_obs_table_encode(boot_obs, revision, img, (uint32_t)sizeof(f->boot_img));
        rc = fsw_table_init(&f->obs_tbl, &FSW_TBL_DESC_OBS, img, n, &why);
        if ((rc == FSW_OK) && (fsw_table_payload(&f->obs_tbl, NULL) != NULL) && load_active(f)) {
            uint32_t mwhy = 0u;
            if ((obs_params_check(&f->obs_p, &mwhy) == FSW_OK) && (f->obs_p.period_us == cfg->period_us)) {
                f->init_ok = true;
            } else {
                f->have_obs_p = false;
                rc = FSW_ERR_INVARIANT;
            }
        } else {
            f->have_obs_p = false;
            f->tlm.tbl_reason = why;
            if (rc == FSW_OK) {
                rc = FSW_ERR_INVARIANT;
            }
        }
        if (!f->init_ok) {
            fx_cnt_inc(&f->tlm.n_tbl_rej);
        }
        f->tlm.tbl_revision = fsw_table_revision(&f->obs_tbl);
    }
    return rc;
}

fsw_rc_t fsw_table_upload(fsw_t *f, const fsw_table_chunk_t *c, uint32_t *why)
{
    fsw_rc_t rc = FSW_ERR_ARG;
    uint32_t w = 0u;
    if ((f != NULL) && (c != NULL)) {
        uint32_t before = f->obs_tbl.rejects;
        rc = fsw_table_chunk(&f->obs_tbl, c, &w);
        if ((rc == FSW_OK) && (f->obs_tbl.state == FSW_TBL_S_READY)) {
            rc = check_candidate(f, &w);
        }
        if (f->obs_tbl.rejects != before) {
            f->tbl_rej_pending = true;
            f->tlm.tbl_reason = w;
            fx_cnt_inc(&f->tlm.n_tbl_rej);
        }
    }
    if (why != NULL) {
        *why = w;
    }
    return rc;
}

/* Step 2: channel i is accepted when the frame carries it, its STALE bit is clear and its
   count lies in the observer table's valid range; otherwise the last good value is held and
   the channel is marked stale for the module. SAT is passed on (the observer skips the axis). */
static void accept_inputs(fsw_t *f, const fsw_in_t *in, obs_in_t *oi, uint32_t *hx)
{
    uint32_t i;
    bool any_bad = false;
    int32_t lim = f->have_obs_p ? f->obs_p.gyro_max_cnt : 0;
    oi->stale = 0u;
    oi->sat = 0u;
    oi->seq = (uint32_t)((uint64_t)in->seq & 0xFFFFFFFFu);
    if (in->n_counts < FSW_N_SENS) {
        fx_cnt_inc(&f->tlm.n_in_bad);
    }
    for (i = 0u; i < FSW_N_SENS; i++) {
        uint8_t bit = (uint8_t)(1u << i);
        bool ok = (i < in->n_counts) && ((in->status[i] & FSW_ST_STALE) == 0u);
        if (ok) {
            int32_t c = in->counts[i];
            ok = (c > -lim) && (c < lim);
        }
        if (ok) {
            f->last_good[i] = in->counts[i];
            f->stale_run[i] = 0u;
        } else {
            any_bad = true;
            fx_cnt_inc(&f->tlm.n_chan_rej);
            fx_cnt_inc(&f->stale_run[i]);
            oi->stale = (uint8_t)(oi->stale | bit);
        }
        if (ok && ((in->status[i] & FSW_ST_SAT) != 0u)) {
            oi->sat = (uint8_t)(oi->sat | bit);
            fx_cnt_inc(&f->sat_run[i]);
        } else {
            f->sat_run[i] = 0u;
        }
        oi->gyro_cnt[i] = f->last_good[i];
        if (f->stale_run[i] >= (uint32_t)f->cfg.stale_max) {
            *hx |= FSW_H_STALE_PERSIST;
        }
        if (f->sat_run[i] >= (uint32_t)f->cfg.stale_max) {
            *hx |= FSW_H_SAT_PERSIST;
        }
    }
    if (any_bad) {
        *hx |= FSW_H_STALE;
        fx_cnt_inc(&f->tlm.n_stale_steps);
    }
}

static bool cmd_allowed(uint32_t from, uint32_t to)
{
    bool ok = false;
    switch (from) {
    case FSW_MODE_STANDBY:
        ok = (to == FSW_MODE_DETUMBLE) || (to == FSW_MODE_SAFE) || (to == FSW_MODE_STANDBY);
        break;
    case FSW_MODE_DETUMBLE:
        ok = (to == FSW_MODE_STANDBY) || (to == FSW_MODE_SAFE) || (to == FSW_MODE_DETUMBLE);
        break;
    case FSW_MODE_SAFE:
        ok = (to == FSW_MODE_STANDBY) || (to == FSW_MODE_SAFE);
        break;
    default:
        ok = false;   /* BOOT is not commandable */
        break;
    }
    return ok;
}

/* Step 4: returns the mode of this step. */
static uint32_t next_mode(fsw_t *f, const fsw_in_t *in, uint32_t *hx)
{
    uint32_t m = f->mode;
    if (m == FSW_MODE_BOOT) {
        m = f->init_ok ? f->cfg.boot_mode : FSW_MODE_SAFE;
    } else if (in->mode_cmd != FSW_CMD_NONE) {
        if ((in->mode_cmd < FSW_MODE_COUNT) && cmd_allowed(m, in->mode_cmd)) {
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

/* Step 1: a READY candidate becomes active at the step boundary; then the active image's
   scrub. Returns the executive health bits of this part. */
static uint32_t tables_at_boundary(fsw_t *f)
{
    uint32_t hx = 0u;
    if (fsw_table_commit(&f->obs_tbl)) {
        uint32_t i;
        int8_t old_ls[OBS_NZ];
        bool same_scale = f->have_obs_p;
        for (i = 0u; i < OBS_NZ; i++) {
            old_ls[i] = f->obs_p.ls[i];
        }
        if (load_active(f)) {
            for (i = 0u; i < OBS_NZ; i++) {
                same_scale = same_scale && (old_ls[i] == f->obs_p.ls[i]);
            }
            f->init_ok = true;
            hx |= FSW_H_TBL_NEW;
            fx_cnt_inc(&f->tlm.n_tbl_acc);
            /* The covariance lives in the table's scaled coordinates: a new scale restarts. */
            if ((f->mode == FSW_MODE_DETUMBLE) && !same_scale) {
                (void)obs_init(&f->obs_s, &f->obs_p, &f->obs_o);
            }
        }
    }
    if (!f->have_obs_p) {
        hx |= FSW_H_NO_TABLE;
    }
    if ((f->mode != FSW_MODE_BOOT) && (fsw_table_scrub(&f->obs_tbl) != FSW_OK)) {
        hx |= FSW_H_SCRUB;
    }
    if (f->tbl_rej_pending) {
        hx |= FSW_H_TBL_REJ;
        f->tbl_rej_pending = false;
    }
    return hx;
}

/* Steps 5-6: the modules of this mode, and actuator counts (safe values outside DETUMBLE).
   Returns the observer health word (0 when it did not run). */
static uint32_t run_modules(fsw_t *f, uint32_t mode, const obs_in_t *oi, fsw_out_t *out, uint32_t *hx)
{
    uint32_t obs_h = 0u;
    if (mode == FSW_MODE_DETUMBLE) {
        uint32_t i;
        obs_step(&f->obs_s, &f->obs_p, oi, &f->obs_o);
        obs_h = f->obs_o.health;
        for (i = 0u; i < FSW_N_ACT; i++) {
            out->act_cnt[i] = f->obs_o.bdot_cmd_cnt[i];
        }
        if ((obs_h & OBS_FAULT_BITS) != 0u) {
            *hx |= FSW_H_MODULE;
        }
    }
    if (mode == FSW_MODE_SAFE) {
        *hx |= FSW_H_SAFE;
    }
    return obs_h;
}

/* Step 7: health aggregation and telemetry. */
static void fill_tlm(fsw_t *f, const fsw_in_t *in, uint32_t obs_h, fsw_out_t *out)
{
    uint32_t i;
    f->tlm.utime_us = in->utime_us;
    f->tlm.seq = in->seq;
    f->tlm.step = f->step;
    f->tlm.mode = out->mode;
    f->tlm.health = out->health;
    f->tlm.health_sticky |= out->health;
    if (f->obs_tbl.rejects != 0u) {
        f->tlm.tbl_reason = f->obs_tbl.last_reason;
    }
    f->tlm.tbl_revision = fsw_table_revision(&f->obs_tbl);
    f->tlm.n_scrub_err = f->obs_tbl.scrub_errs;
    f->tlm.host_missed = in->host_missed;
    f->tlm.host_rejected = in->host_rejected;
    for (i = 0u; i < FSW_N_ACT; i++) {
        f->tlm.act_cnt[i] = out->act_cnt[i];
    }
    f->tlm.obs_health = obs_h;
    f->tlm.obs = f->obs_o.tlm;
    out->tlm = f->tlm;
}

void fsw_step(fsw_t *f, const fsw_in_t *in, fsw_out_t *out)
{
    uint32_t hx;
    uint32_t mode;
    uint32_t obs_h;
    obs_in_t oi;
    zero_out(out);
    fx_cnt_inc(&f->step);
    hx = tables_at_boundary(f);
    /* 2-3. inputs (the observer converts counts with its table's shift) */
    accept_inputs(f, in, &oi, &hx);
    /* 4. modes; the observer restarts on every entry to DETUMBLE */
    mode = next_mode(f, in, &hx);
    if ((mode == FSW_MODE_SAFE) && (f->mode != FSW_MODE_SAFE)) {
        fx_cnt_inc(&f->tlm.n_safe);
    }
    if ((mode == FSW_MODE_DETUMBLE) && (f->mode != FSW_MODE_DETUMBLE)) {
        (void)obs_init(&f->obs_s, &f->obs_p, &f->obs_o);
    }
    f->mode = mode;
    obs_h = run_modules(f, mode, &oi, out, &hx);
    out->mode = mode;
    out->health = hx | (obs_h & 0xFFu);
    fill_tlm(f, in, obs_h, out);
}
