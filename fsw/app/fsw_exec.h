/*
 * fsw_exec.h — the executive: fsw_t, fsw_init, fsw_step, table upload, telemetry (spec 00 §3.3).
 * Mission-agnostic: it names no mission. The missions of a build and their dispatch are generated
 * from missions.json (fsw_missions_gen.h in the build tree); each mission's facts live in its
 * adapter, fsw/<module>/<p>_mission.c (contract: fsw_mission.h).
 *
 * One caller-owned fsw_t holds the executive's state and the flying mission's block (a union
 * over the configured missions): a static object in a board image or a bridge member. Two
 * instances never interact.
 *
 * Step order, written once (spec 00 §3.3):
 *   1. step counter; the mission's table at the step boundary: a validated candidate is committed
 *      when the mission's commit rule allows (else FSW_H_TBL_PENDING), then the active image's
 *      CRC scrub (a failure is FSW_H_SCRUB, a SAFE trigger);
 *   2-3. input acceptance: consumed channel i is accepted when the frame carries it, its STALE bit
 *      is clear and its count lies in the mission's range under the active table; otherwise its
 *      last good value is held and it is marked invalid (the mission may declare its channels one
 *      sample, valid only together); persistence for stale_max steps is a SAFE trigger where the
 *      mission says so;
 *   4. mode manager: BOOT -> cfg.boot_mode (or SAFE without a valid table); STANDBY <-> the
 *      mission mode and any mode -> SAFE by command; SAFE -> STANDBY only by command; SAFE on
 *      the triggers above; the mission is (re)initialised on every entry to its mode;
 *   5. this step's telecommand: taken when it belongs to this mission, exists and the mission
 *      mode flies, else refused and counted (FSW_H_TC_REJ);
 *   6. the mission step in its mode (module faults raise FSW_H_MODULE); actuator counts: the
 *      mission's, or its safe values outside its mode;
 *   7. health aggregation and telemetry.
 */
#ifndef FSW_APP_EXEC_H
#define FSW_APP_EXEC_H

#include <stdint.h>
#include <stdbool.h>
#include "fsw_ids.h"
#include "fsw_mission.h"
#include "fsw_missions_gen.h"

#define FSW_CMD_NONE 0xFFFFFFFFu   /* fsw_in_t.mode_cmd: no mode command this step */
#define FSW_TC_NONE  0u            /* fsw_in_t.tc: no telecommand this step */

typedef struct {
    uint32_t period_us;      /* control period; the mission's table must agree */
    uint16_t stale_max;      /* consecutive invalid steps on a channel before SAFE (>= 1) */
    uint32_t boot_mode;      /* mode entered after BOOT: STANDBY or the mission mode */
    uint32_t mission;        /* FSW_MISSION_* of this build */
} fsw_cfg_t;

typedef struct {
    int64_t  utime_us;       /* echoed, never computed with */
    int64_t  seq;            /* echoed; the mission sees it as its step index */
    uint32_t n_counts;       /* valid entries of counts[] (<= FSW_IN_MAX) */
    int32_t  counts[FSW_IN_MAX];
    uint8_t  status[FSW_IN_MAX];   /* FSW_ST_* per channel */
    uint32_t mode_cmd;       /* FSW_CMD_NONE or a target mode */
    uint32_t host_missed;    /* host-reported cumulative counters, copied into telemetry */
    uint32_t host_rejected;
    uint32_t tc;             /* FSW_TC_NONE, or a telecommand: mission namespace | local id */
    int32_t  tc_arg[FSW_TC_ARGS];
} fsw_in_t;

typedef struct {
    int64_t  utime_us;
    int64_t  seq;
    uint32_t step;
    uint32_t mode;
    uint32_t health;         /* aggregate: executive bits 8..19, the module's fx status 0..7 */
    uint32_t health_sticky;  /* OR of health since init */
    uint32_t n_chan_rej;     /* channel samples refused (range or STALE bit), saturating */
    uint32_t n_stale_steps;  /* steps with at least one invalid consumed channel */
    uint32_t n_in_bad;       /* frames carrying fewer channels than the mission consumes */
    uint32_t n_tbl_acc;      /* table candidates committed */
    uint32_t n_tbl_rej;      /* table uploads refused (loader or module veto) */
    uint32_t tbl_reason;     /* reason word of the latest refusal (fsw_table.h) */
    uint32_t tbl_revision;   /* active table revision */
    uint32_t n_scrub_err;
    uint32_t n_safe;         /* SAFE entries */
    uint32_t n_mode_rej;     /* refused mode commands */
    uint32_t host_missed;
    uint32_t host_rejected;
    uint32_t n_tc;           /* telecommands taken by the module */
    uint32_t n_tc_rej;       /* telecommands refused */
    uint32_t mission;        /* FSW_MISSION_* (selects the layout; not on the wire) */
    int32_t  act_cnt[FSW_ACT_MAX];   /* the mission's actuator counts (n_act of them) */
    uint32_t mod_health;     /* the module's health word of this step (0 when not run) */
    fsw_mis_tlm_u m;         /* the module's telemetry block (last run) */
} fsw_tlm_t;

typedef struct {
    uint32_t n_act;                  /* valid entries of act_cnt[] */
    int32_t  act_cnt[FSW_ACT_MAX];
    uint32_t mode;
    uint32_t health;
    fsw_tlm_t tlm;
} fsw_out_t;

typedef struct {
    fsw_cfg_t    cfg;
    bool         init_ok;            /* a valid table has been active since init */
    bool         have_p;             /* the active table decoded into the mission's parameters */
    bool         tbl_rej_pending;    /* a refusal since the last step (FSW_H_TBL_REJ) */
    uint32_t     mode;
    uint32_t     step;
    fsw_table_t  tbl;                /* the mission's table: active image and upload candidate */
    /* input acceptance */
    int32_t      last_good[FSW_IN_MAX];
    uint32_t     stale_run[FSW_IN_MAX];
    uint32_t     sat_run[FSW_IN_MAX];
    fsw_range_t  rng[FSW_IN_MAX];    /* scratch: this step's channel ranges */
    fsw_acc_t    acc;                /* scratch: this step's accepted inputs for the mission */
    fsw_tlm_t    tlm;                /* counters live here */
    fsw_mis_u    m;                  /* the flying mission (cfg.mission) */
} fsw_t;

/*
 * Validates cfg (a mission of this build, period > 0, stale_max >= 1, boot_mode STANDBY or the
 * mission mode) and loads the boot table image boot[0..boot_len) through the same checks as an
 * upload, plus the mission's module check. FSW_ERR_ARG on a bad cfg or NULL (f untouched); a boot
 * image that fails its checks returns the loader's code or FSW_ERR_INVARIANT and leaves the
 * executive to go SAFE at its first step with FSW_H_NO_TABLE. Images come from the mission's
 * encoder (<prefix>_table_encode) or from the ground tools. boot == NULL with boot_len == 0 boots
 * without a table (a generic image, the table is loaded on the ground or in orbit): FSW_OK,
 * nothing counted as refused, FSW_H_NO_TABLE until an upload commits; one committed at the
 * boundary of the first step lets the executive enter its boot mode directly.
 */
fsw_rc_t fsw_init(fsw_t *f, const fsw_cfg_t *cfg, const uint8_t *boot, uint32_t boot_len);
void     fsw_step(fsw_t *f, const fsw_in_t *in, fsw_out_t *out);
/* One upload chunk for the mission's table, between steps. A completed candidate is decoded and
   module-checked at once; *why gets the loader's reason word. It becomes active at the first
   step boundary at which the mission's commit rule allows it (until then FSW_H_TBL_PENDING, and
   further chunks are refused BUSY). */
fsw_rc_t fsw_table_upload(fsw_t *f, const fsw_table_chunk_t *c, uint32_t *why);
/* The loader of the mission's table (for acks: cand_got, state). Never NULL for a non-NULL f. */
const fsw_table_t *fsw_mission_table(const fsw_t *f);
/* The mission's sensor channel ranges under the active table: r[0..*n) (capacity FSW_IN_MAX);
   the host's frame validator uses them, so the channel map is written once. */
void     fsw_sensor_ranges(const fsw_t *f, fsw_range_t *r, uint32_t *n);

/* Encodes t little-endian in its mission's layout (the header of fsw_iface.py, the actuator
   counts, the module health word, the module block of <p>_iface.py). Returns the bytes written,
   0 if cap is too small or the mission is not in this build. fsw_tlm_layout() gives the layout
   version of t (0 for a mission not in this build). */
uint32_t fsw_tlm_encode(const fsw_tlm_t *t, uint8_t *buf, uint32_t cap);
uint32_t fsw_tlm_layout(const fsw_tlm_t *t);
void     fsw_tlm_wr_head(fsw_wr_t *w, const fsw_tlm_t *t);   /* generated: fsw_tlm_head.c */

#endif /* FSW_APP_EXEC_H */
