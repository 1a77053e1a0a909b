/*
 * fsw_exec.c — the executive (spec 00 §3.3). See fsw_exec.h for the step order.
 *
 * Mode rules (spec 00 §3.3; fsw/app/README.md "Executive"):
 *   BOOT     → cfg.boot_mode at the first step when the module table is valid, else SAFE
 *   STANDBY  ↔ the mission mode (DETUMBLE or RENDEZVOUS) by command; any mode → SAFE by command
 *   SAFE     → STANDBY by command only; entered automatically on a channel invalid for
 *              stale_max steps, a plant SAT bit held for stale_max steps, or a failed scrub
 * The observer runs only in DETUMBLE and is re-initialised on every entry: outside DETUMBLE the
 * actuators hold their safe value (zero rate), which the observer's model would not know.
 * CMD_LIMIT_PERSIST is reported, not a SAFE trigger: with insufficient authority the spec's
 * scenario (10-observer S0-9) expects the loop to keep commanding and the plant to end DIVERGED.
 * RENDEZVOUS: the impulse scheduler runs in its mode (initialised on entry); a stale nav sample
 * is never a SAFE trigger, because the scheduler flies a dropout open loop by design (spec 50 §8
 * "nav dropout in FIRING"); its own faults (STUCK_*, INTERLOCK) raise FSW_H_MODULE.
 *
 * Tables: each mission has one fsw_table_t (DETUMBLE obs_tbl, RENDEZVOUS imp_tbl), booted from
 * the C initialiser through the loader's checks and the module check, uploaded by
 * fsw_table_upload (module check at once, veto on failure), committed at a step boundary and
 * scrubbed every step (failure → SAFE). Impulse commit policy: the scheduler's state (timeline
 * and burn log in valve-grid units, nav sample converted with the count scales, calibration,
 * a plan job) is only meaningful with the table it was made with, and a swap must never touch a
 * firing timeline. So a validated impulse table is committed only while the scheduler is not
 * running a mission — the executive is outside RENDEZVOUS, or the scheduler is IDLE or terminal
 * (DONE, INFEASIBLE, NO_SOLUTION, ABORTED, FAULT) — and otherwise waits as a READY candidate
 * (FSW_H_TBL_PENDING each step; ground can ABORT to force it). A commit in RENDEZVOUS
 * re-initialises the scheduler with the new table (IDLE, its telemetry carries the new revision;
 * like a mode re-entry, this clears its latched faults — the executive's sticky health keeps the
 * record).
 */
#include "fsw_exec.h"
#include "fx.h"

#define OBS_FAULT_BITS (OBS_H_MEAS_LOST | OBS_H_CMD_LIMIT_PERSIST | OBS_H_COV_CLIP | 0xFFu)
#define IMP_FAULT_BITS (IMP_H_STUCK_OFF | IMP_H_STUCK_ON | IMP_H_INTERLOCK | 0xFFu)
#define IMP_ALL_THRUSTERS 0x3Fu
#define IMP_WHY_BITS      12u     /* IMP_WHY_PERIOD .. IMP_WHY_NAV */

FX_STATIC_ASSERT(exec_sa_boot_obs, FSW_BOOT_IMG_BYTES >= (FSW_TABLE_HDR_BYTES + FSW_TBL_OBS_PAYLOAD));
FX_STATIC_ASSERT(exec_sa_boot_imp, FSW_BOOT_IMG_BYTES >= (FSW_TABLE_HDR_BYTES + FSW_TBL_IMP_PAYLOAD));

static bool rdv(const fsw_t *f)
{
    return f->cfg.mission == FSW_MISSION_RENDEZVOUS;
}

static uint32_t n_act(const fsw_t *f)
{
    return rdv(f) ? FSW_RDV_N_ACT : FSW_N_ACT;
}

static uint32_t mission_mode(const fsw_t *f)
{
    return rdv(f) ? FSW_MODE_RENDEZVOUS : FSW_MODE_DETUMBLE;
}

static void zero_out(const fsw_t *f, fsw_out_t *out)
{
    uint32_t i;
    out->n_act = n_act(f);
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

/* Decodes the active impulse image into f->imp_p. */
static bool load_imp_active(fsw_t *f)
{
    uint32_t len = 0u;
    bool ok = false;
    const uint8_t *pl = fsw_table_payload(&f->imp_tbl, &len);
    if ((pl != NULL) &&
        (fsw_imp_table_decode(pl, len, fsw_table_revision(&f->imp_tbl), &f->imp_cand) == FSW_OK)) {
        f->imp_p = f->imp_cand;
        ok = true;
    }
    f->have_imp_p = ok;
    return ok;
}

/* The 8-bit veto detail of an imp_params_check why word (fsw_exec.h FSW_IMP_VETO_UNDECODED). */
static uint32_t imp_veto_detail(uint32_t mwhy)
{
    uint32_t d = FSW_IMP_VETO_UNDECODED;
    uint32_t bit = 1u;
    uint32_t i;
    for (i = 0u; (i < IMP_WHY_BITS) && (d == FSW_IMP_VETO_UNDECODED); i++) {
        if ((mwhy & bit) != 0u) {
            d = i + 1u;
        }
        bit <<= 1u;
    }
    return d;
}

/* The impulse table's module check: imp_params_check and the same-period rule. Returns the veto
   detail, 0 when p passes. */
static uint32_t imp_module_check(const fsw_t *f, const imp_params_t *p)
{
    uint32_t mwhy = 0u;
    uint32_t d = 0u;
    if (imp_params_check(p, &mwhy) != FSW_OK) {
        d = imp_veto_detail(mwhy);
    } else if (p->period_us != f->cfg.period_us) {
        d = imp_veto_detail(IMP_WHY_PERIOD);
    } else {
        d = 0u;
    }
    return d;
}

/* Module check of a READY impulse candidate: decode, then imp_module_check; a failure vetoes it. */
static fsw_rc_t check_imp_candidate(fsw_t *f, uint32_t *why)
{
    fsw_rc_t rc = FSW_OK;
    uint32_t len = 0u;
    const uint8_t *pl = fsw_table_candidate(&f->imp_tbl, &len);
    if (pl == NULL) {
        rc = FSW_ERR_STATE;
    } else {
        uint32_t d = FSW_IMP_VETO_UNDECODED;
        /* The revision is informative; the check does not depend on it. */
        if (fsw_imp_table_decode(pl, len, 0u, &f->imp_cand) == FSW_OK) {
            d = imp_module_check(f, &f->imp_cand);
        }
        if (d != 0u) {
            rc = fsw_table_veto(&f->imp_tbl, d, why);
            if (rc == FSW_OK) {
                rc = FSW_ERR_INVARIANT;
            }
        }
    }
    return rc;
}

/* The state every mission starts from: BOOT, no table, counters zero. */
static void reset_common(fsw_t *f, const fsw_cfg_t *cfg)
{
    /* Read-only zero images (rodata, no state) so the reset is a struct copy without a large
       stack temporary. */
    static const fsw_tlm_t tlm_zero = {0};
    static const obs_out_t obs_out_zero = {0};
    static const imp_out_t imp_out_zero = {0};
    uint32_t i;
    f->cfg = *cfg;
    f->init_ok = false;
    f->mode = FSW_MODE_BOOT;
    f->step = 0u;
    f->have_obs_p = false;
    f->have_imp_p = false;
    f->tbl_rej_pending = false;
    for (i = 0u; i < FSW_RDV_N_SENS; i++) {
        f->last_good[i] = 0;
        f->stale_run[i] = 0u;
        f->sat_run[i] = 0u;
    }
    f->tlm = tlm_zero;
    f->tlm.mission = cfg->mission;
    f->obs_o = obs_out_zero;
    f->imp_o = imp_out_zero;
}

static bool cfg_ok(const fsw_cfg_t *cfg, uint32_t mission, uint32_t mode)
{
    return (cfg != NULL) && (cfg->mission == mission) && (cfg->period_us > 0u) && (cfg->stale_max >= 1u) &&
           ((cfg->boot_mode == FSW_MODE_STANDBY) || (cfg->boot_mode == mode));
}

fsw_rc_t fsw_init_rdv(fsw_t *f, const fsw_cfg_t *cfg, const imp_params_t *boot_imp, uint32_t revision)
{
    fsw_rc_t rc = FSW_ERR_ARG;
    if ((f != NULL) && (boot_imp != NULL) && cfg_ok(cfg, FSW_MISSION_RENDEZVOUS, FSW_MODE_RENDEZVOUS)) {
        uint8_t *img = f->boot_img;   /* fsw_table_init resets imp_tbl, then copies it */
        uint32_t n;
        uint32_t why = 0u;
        reset_common(f, cfg);
        n = fsw_imp_table_encode(boot_imp, revision, img, (uint32_t)sizeof(f->boot_img));
        rc = fsw_table_init(&f->imp_tbl, &FSW_TBL_DESC_IMP, img, n, &why);
        if ((rc == FSW_OK) && (fsw_table_payload(&f->imp_tbl, NULL) != NULL) && load_imp_active(f)) {
            uint32_t d = imp_module_check(f, &f->imp_p);
            if (d == 0u) {
                f->init_ok = true;
                (void)imp_init(&f->imp_s, &f->imp_p, &f->imp_o);
            } else {
                f->have_imp_p = false;
                f->tlm.tbl_reason = FSW_TBL_R_MODULE | (d << FSW_TBL_DETAIL_SHIFT);
                rc = FSW_ERR_INVARIANT;
            }
        } else {
            f->have_imp_p = false;
            f->tlm.tbl_reason = why;
            if (rc == FSW_OK) {
                rc = FSW_ERR_INVARIANT;
            }
        }
        if (!f->init_ok) {
            fx_cnt_inc(&f->tlm.n_tbl_rej);
        }
        f->tlm.tbl_revision = fsw_table_revision(&f->imp_tbl);
    }
    return rc;
}

fsw_rc_t fsw_init(fsw_t *f, const fsw_cfg_t *cfg, const obs_params_t *boot_obs, uint32_t revision)
{
    fsw_rc_t rc = FSW_ERR_ARG;
    if ((f != NULL) && (boot_obs != NULL) && cfg_ok(cfg, FSW_MISSION_DETUMBLE, FSW_MODE_DETUMBLE)) {
        uint8_t *img = f->boot_img;   /* fsw_table_init resets obs_tbl, then copies it */
        uint32_t n;
        uint32_t why = 0u;
        reset_common(f, cfg);
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

const fsw_table_t *fsw_mission_table(const fsw_t *f)
{
    const fsw_table_t *t = NULL;
    if (f != NULL) {
        t = rdv(f) ? &f->imp_tbl : &f->obs_tbl;
    }
    return t;
}

fsw_rc_t fsw_table_upload(fsw_t *f, const fsw_table_chunk_t *c, uint32_t *why)
{
    fsw_rc_t rc = FSW_ERR_ARG;
    uint32_t w = 0u;
    if ((f != NULL) && (c != NULL)) {
        /* The mission's table: a chunk for another table id is refused by its loader (UPLOAD_ID). */
        fsw_table_t *t = rdv(f) ? &f->imp_tbl : &f->obs_tbl;
        uint32_t before = t->rejects;
        rc = fsw_table_chunk(t, c, &w);
        if ((rc == FSW_OK) && (t->state == FSW_TBL_S_READY)) {
            rc = rdv(f) ? check_imp_candidate(f, &w) : check_candidate(f, &w);
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

/* RENDEZVOUS steps 2-3: the nav sample is one unit, valid only when all 7 channels are present,
   not STALE and inside the accepted ranges; an invalid sample is passed on as invalid (the
   module keeps its last accepted one and flies on), counted, and never a SAFE trigger. */
static void accept_nav(fsw_t *f, const fsw_in_t *in, uint32_t *hx)
{
    uint32_t i;
    bool ok = in->n_counts >= FSW_RDV_N_SENS;
    imp_in_t *ii = &f->imp_i;
    if (!ok) {
        fx_cnt_inc(&f->tlm.n_in_bad);
    }
    for (i = 0u; ok && (i < FSW_RDV_N_SENS); i++) {
        int32_t c = in->counts[i];
        int32_t hi = (i < 3u) ? FSW_NAV_POS_MAX_MM : ((i < 6u) ? FSW_NAV_VEL_MAX_CNT : INT32_MAX);
        int32_t lo = (i < 6u) ? (-hi) : 0;
        ok = ((in->status[i] & FSW_ST_STALE) == 0u) && (c >= lo) && (c <= hi);
    }
    ii->nav_valid = ok ? 1u : 0u;
    for (i = 0u; i < IMP_NAX; i++) {
        ii->nav_pos_mm[i] = ok ? in->counts[i] : 0;
        ii->nav_vel_cnt[i] = ok ? in->counts[3u + i] : 0;
    }
    ii->nav_step = ok ? (uint32_t)in->counts[6] : 0u;
    if (!ok) {
        *hx |= FSW_H_STALE;
        fx_cnt_inc(&f->tlm.n_chan_rej);
        fx_cnt_inc(&f->tlm.n_stale_steps);
    }
}

/* RENDEZVOUS: the step index and this step's telecommand for the impulse scheduler. A module
   telecommand outside the mission mode is refused and counted here. */
static void rdv_command(fsw_t *f, const fsw_in_t *in, uint32_t mode, uint32_t *hx)
{
    imp_in_t *ii = &f->imp_i;
    uint32_t i;
    ii->step = (uint32_t)((uint64_t)in->seq & 0xFFFFFFFFu);
    ii->avail_mask = IMP_ALL_THRUSTERS;
    ii->cmd = IMP_CMD_NONE;
    if (in->tc != FSW_TC_NONE) {
        bool known = (in->tc == FSW_TC_IMP_START) || (in->tc == FSW_TC_IMP_ABORT) || (in->tc == FSW_TC_IMP_CLEAR);
        if (known && (mode == FSW_MODE_RENDEZVOUS)) {
            ii->cmd = (in->tc == FSW_TC_IMP_START) ? IMP_CMD_START
                    : ((in->tc == FSW_TC_IMP_ABORT) ? IMP_CMD_ABORT : IMP_CMD_CLEAR_FAULTS);
            fx_cnt_inc(&f->tlm.n_tc);
        } else {
            *hx |= FSW_H_TC_REJ;
            fx_cnt_inc(&f->tlm.n_tc_rej);
        }
    }
    /* Negative step arguments have no meaning: they become a time START refuses. */
    ii->cmd_t0_step = (in->tc_arg[0] < 0) ? 0u : (uint32_t)in->tc_arg[0];
    ii->cmd_tf_step = (in->tc_arg[1] < 0) ? 0u : (uint32_t)in->tc_arg[1];
    for (i = 0u; i < IMP_NAX; i++) {
        ii->cmd_tgt_pos_mm[i] = in->tc_arg[2u + i];
        ii->cmd_tgt_vel_cnt[i] = in->tc_arg[5u + i];
    }
}

static bool cmd_allowed(const fsw_t *f, uint32_t from, uint32_t to)
{
    bool ok = false;
    uint32_t mm = mission_mode(f);
    switch (from) {
    case FSW_MODE_STANDBY:
        ok = (to == mm) || (to == FSW_MODE_SAFE) || (to == FSW_MODE_STANDBY);
        break;
    case FSW_MODE_DETUMBLE:
    case FSW_MODE_RENDEZVOUS:
        ok = (from == mm) && ((to == FSW_MODE_STANDBY) || (to == FSW_MODE_SAFE) || (to == from));
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
        if ((in->mode_cmd < FSW_MODE_COUNT) && cmd_allowed(f, m, in->mode_cmd)) {
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

/* True when the impulse scheduler runs no mission that a table swap could disturb: the
   executive is outside RENDEZVOUS (the scheduler is re-initialised on entry), or the scheduler
   (its last output) is IDLE or in a terminal mode. */
static bool imp_quiescent(const fsw_t *f)
{
    bool q = true;
    if (f->mode == FSW_MODE_RENDEZVOUS) {
        switch (f->imp_o.tlm.mode) {
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

/* RENDEZVOUS step 1: a READY impulse candidate is committed when the scheduler is quiescent
   (re-initialised with it in RENDEZVOUS), else it waits; then the active image's scrub. */
static uint32_t imp_tables_at_boundary(fsw_t *f)
{
    uint32_t hx = 0u;
    if (f->imp_tbl.state == FSW_TBL_S_READY) {
        if (!imp_quiescent(f)) {
            hx |= FSW_H_TBL_PENDING;
        } else if (fsw_table_commit(&f->imp_tbl) && load_imp_active(f)) {
            f->init_ok = true;
            hx |= FSW_H_TBL_NEW;
            fx_cnt_inc(&f->tlm.n_tbl_acc);
            if (f->mode == FSW_MODE_RENDEZVOUS) {
                (void)imp_init(&f->imp_s, &f->imp_p, &f->imp_o);
            }
        } else {
            /* not reached: a READY candidate always commits and decodes (checked at upload) */
        }
    }
    if (!f->have_imp_p) {
        hx |= FSW_H_NO_TABLE;
    }
    if ((f->mode != FSW_MODE_BOOT) && (fsw_table_scrub(&f->imp_tbl) != FSW_OK)) {
        hx |= FSW_H_SCRUB;
    }
    return hx;
}

/* DETUMBLE step 1: a READY observer candidate becomes active at the step boundary; then the
   active image's scrub. */
static uint32_t obs_tables_at_boundary(fsw_t *f)
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
    return hx;
}

/* Step 1: the mission's table at the step boundary (commit, scrub) and a refusal since the last
   step. Returns the executive health bits of this part. */
static uint32_t tables_at_boundary(fsw_t *f)
{
    uint32_t hx = rdv(f) ? imp_tables_at_boundary(f) : obs_tables_at_boundary(f);
    if (f->tbl_rej_pending) {
        hx |= FSW_H_TBL_REJ;
        f->tbl_rej_pending = false;
    }
    return hx;
}

/* Steps 5-6: the modules of this mode, and actuator counts (safe values outside the mission
   mode). Returns the health word of the module that ran (0 when none did). */
static uint32_t run_rdv(fsw_t *f, uint32_t mode, fsw_out_t *out, uint32_t *hx)
{
    uint32_t h = 0u;
    if (mode == FSW_MODE_RENDEZVOUS) {
        uint32_t j;
        imp_step(&f->imp_s, &f->imp_p, &f->imp_i, &f->imp_o);
        h = f->imp_o.health;
        for (j = 0u; j < IMP_NTHR; j++) {
            /* within one period (imp_step's invariant), so the int32 conversion is exact */
            uint32_t s0 = f->imp_o.on_start_cnt[j] & 0x7FFFFFFFu;
            uint32_t l0 = f->imp_o.on_len_cnt[j] & 0x7FFFFFFFu;
            out->act_cnt[j] = (int32_t)s0;
            out->act_cnt[IMP_NTHR + j] = (int32_t)l0;
        }
        out->act_cnt[FSW_RDV_ACT_MASK] = (int32_t)f->imp_o.on_mask;
        if ((h & IMP_FAULT_BITS) != 0u) {
            *hx |= FSW_H_MODULE;
        }
    }
    return h;
}

static uint32_t run_modules(fsw_t *f, uint32_t mode, const obs_in_t *oi, fsw_out_t *out, uint32_t *hx)
{
    uint32_t obs_h = 0u;
    if (rdv(f)) {
        obs_h = run_rdv(f, mode, out, hx);
    } else if (mode == FSW_MODE_DETUMBLE) {
        uint32_t i;
        obs_step(&f->obs_s, &f->obs_p, oi, &f->obs_o);
        obs_h = f->obs_o.health;
        for (i = 0u; i < FSW_N_ACT; i++) {
            out->act_cnt[i] = f->obs_o.bdot_cmd_cnt[i];
        }
        if ((obs_h & OBS_FAULT_BITS) != 0u) {
            *hx |= FSW_H_MODULE;
        }
    } else {
        /* STANDBY, SAFE: no module runs, actuators hold their safe values */
    }
    if (mode == FSW_MODE_SAFE) {
        *hx |= FSW_H_SAFE;
    }
    return obs_h;
}

/* Step 7: health aggregation and telemetry. */
static void fill_tlm(fsw_t *f, const fsw_in_t *in, uint32_t mod_h, fsw_out_t *out)
{
    uint32_t i;
    f->tlm.utime_us = in->utime_us;
    f->tlm.seq = in->seq;
    f->tlm.step = f->step;
    f->tlm.mode = out->mode;
    f->tlm.health = out->health;
    f->tlm.health_sticky |= out->health;
    {
        const fsw_table_t *t = rdv(f) ? &f->imp_tbl : &f->obs_tbl;
        if (t->rejects != 0u) {
            f->tlm.tbl_reason = t->last_reason;
        }
        f->tlm.tbl_revision = fsw_table_revision(t);
        f->tlm.n_scrub_err = t->scrub_errs;
    }
    f->tlm.host_missed = in->host_missed;
    f->tlm.host_rejected = in->host_rejected;
    for (i = 0u; i < FSW_RDV_N_ACT; i++) {
        f->tlm.act_cnt[i] = (i < n_act(f)) ? out->act_cnt[i] : 0;
    }
    if (rdv(f)) {
        f->tlm.imp_health = mod_h;
        f->tlm.imp = f->imp_o.tlm;
    } else {
        f->tlm.obs_health = mod_h;
        f->tlm.obs = f->obs_o.tlm;
    }
    out->tlm = f->tlm;
}

void fsw_step(fsw_t *f, const fsw_in_t *in, fsw_out_t *out)
{
    uint32_t hx;
    uint32_t mode;
    uint32_t mod_h;
    obs_in_t oi = {0u, {0, 0}, 0u, 0u};
    zero_out(f, out);
    fx_cnt_inc(&f->step);
    hx = tables_at_boundary(f);
    /* 2-3. inputs (the observer converts counts with its table's shift; so does the impulse
       scheduler with its count scales) */
    if (rdv(f)) {
        accept_nav(f, in, &hx);
    } else {
        accept_inputs(f, in, &oi, &hx);
    }
    /* 4. modes; a module restarts on every entry to its mode */
    mode = next_mode(f, in, &hx);
    if ((mode == FSW_MODE_SAFE) && (f->mode != FSW_MODE_SAFE)) {
        fx_cnt_inc(&f->tlm.n_safe);
    }
    if ((mode == FSW_MODE_DETUMBLE) && (f->mode != FSW_MODE_DETUMBLE)) {
        (void)obs_init(&f->obs_s, &f->obs_p, &f->obs_o);
    }
    if ((mode == FSW_MODE_RENDEZVOUS) && (f->mode != FSW_MODE_RENDEZVOUS)) {
        (void)imp_init(&f->imp_s, &f->imp_p, &f->imp_o);
    }
    if (rdv(f)) {
        rdv_command(f, in, mode, &hx);
    }
    f->mode = mode;
    mod_h = run_modules(f, mode, &oi, out, &hx);
    out->mode = mode;
    out->health = hx | (mod_h & 0xFFu);
    fill_tlm(f, in, mod_h, out);
}
