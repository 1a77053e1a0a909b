/*
 * fsw_exec.h — the executive: fsw_t, fsw_step, modes, health, table upload, telemetry
 * (spec 00 §3.3). One caller-owned fsw_t holds everything (module states, the active and
 * candidate tables, mode, counters): a static object in a board image or a bridge member.
 * Two instances never interact.
 *
 * Step order (spec 00 §3.3): step counter → table commit at the step boundary (RENDEZVOUS: only
 * while the impulse scheduler is idle or terminal) → table scrub → accept inputs (range +
 * status; invalid channel keeps its last good value and is marked stale) → mode manager →
 * observer (DETUMBLE) or impulse scheduler (RENDEZVOUS) → actuator counts (safe values outside
 * the mission mode) → health aggregation → telemetry.
 *
 * Missions (fsw_cfg_t.mission) and their channel maps:
 *   DETUMBLE (sail platform, spec 10): the observer in mode DETUMBLE.
 *     sensor   counts[0] = gyro y, counts[1] = gyro z  (2^-20 rad/s LSB per the obs table)
 *     actuator counts[0] = gimbal rate y, counts[1] = gimbal rate z (obs table act_cnt_shift)
 *   RENDEZVOUS (chaser, spec 50): the impulse scheduler in mode RENDEZVOUS.
 *     sensor   counts[0..2] = nav position x, y, z [1 mm], counts[3..5] = nav velocity
 *              [10 um/s], counts[6] = the sample's step index (the plant's k); one sample,
 *              valid only when all 7 channels are
 *     actuator counts[0..5] = on_start_cnt, [6..11] = on_len_cnt [1 us within the step],
 *              [12] = on_mask (bit j: thruster +x, -x, +y, -y, +z, -z)
 * The impulse scheduler's time base is the frame's seq (the plant's step index k, as in its
 * commands and nav tags), not the executive's step counter, so lost frames do not shift it.
 */
#ifndef FSW_APP_EXEC_H
#define FSW_APP_EXEC_H

#include <stdint.h>
#include <stdbool.h>
#include "fsw_table.h"
#include "obs.h"
#include "imp.h"

#define FSW_IN_MAX   16u   /* sensor channels a frame can carry (sensor_frame_t.counts[16]) */
#define FSW_ACT_MAX  16u   /* actuator channels (actuator_cmd_t.counts[16]) */
#define FSW_N_SENS   2u    /* channels the DETUMBLE mission consumes */
#define FSW_N_ACT    2u    /* channels the DETUMBLE mission drives */
#define FSW_RDV_N_SENS 7u  /* RENDEZVOUS: nav position (3), velocity (3), sample step */
#define FSW_RDV_N_ACT  13u /* RENDEZVOUS: on_start (6), on_len (6), on_mask */
#define FSW_RDV_ACT_MASK 12u /* index of on_mask in the actuator counts */

/* Missions (fsw_cfg_t.mission). */
#define FSW_MISSION_DETUMBLE   0u
#define FSW_MISSION_RENDEZVOUS 1u

/* Nav counts accepted by the executive: +-200 km (1 mm) and +-250 m/s (10 um/s), inside the
   impulse scheduler's q28 state range (+-8 length units = +-250 km, +-283 m/s at 400 km). */
#define FSW_NAV_POS_MAX_MM   INT32_C(200000000)
#define FSW_NAV_VEL_MAX_CNT  INT32_C(25000000)

/* Per-channel status bits from the plant (sensor_frame_t.STATUS_*). */
#define FSW_ST_STALE 1u
#define FSW_ST_SAT   2u

/* Modes. BOOT exists only until the first step; SAFE is left only by command. */
#define FSW_MODE_BOOT     0u
#define FSW_MODE_STANDBY  1u
#define FSW_MODE_DETUMBLE 2u
#define FSW_MODE_SAFE     3u
#define FSW_MODE_RENDEZVOUS 4u
#define FSW_MODE_COUNT    5u

#define FSW_CMD_NONE      0xFFFFFFFFu   /* fsw_in_t.mode_cmd: no mode command this step */

/* Telecommands for a module (fsw_in_t.tc; gnc.fsw_cmd_t CMD_IMP_*). */
#define FSW_TC_NONE       0u
#define FSW_TC_IMP_START  2u   /* tc_arg: t0 step, tf step, target pos mm x y z, vel 10 um/s x y z */
#define FSW_TC_IMP_ABORT  3u
#define FSW_TC_IMP_CLEAR  4u

/* Executive health bits 8..19 (bits 0..7: OR of the modules' fx status this step). */
#define FSW_H_STALE          (0x00000100u)  /* a consumed channel is invalid this step */
#define FSW_H_STALE_PERSIST  (0x00000200u)  /* a channel invalid for >= stale_max steps */
#define FSW_H_SAT_PERSIST    (0x00000400u)  /* plant SAT bit on a channel for >= stale_max steps */
#define FSW_H_SCRUB          (0x00000800u)  /* active table failed its CRC scrub */
#define FSW_H_SAFE           (0x00001000u)  /* mode is SAFE */
#define FSW_H_MODE_REJ       (0x00002000u)  /* a mode command was refused this step */
#define FSW_H_TBL_REJ        (0x00004000u)  /* a table upload was refused since the last step */
#define FSW_H_TBL_NEW        (0x00008000u)  /* a new table became active at this step */
#define FSW_H_MODULE         (0x00010000u)  /* a module reports a fault bit (see obs_health) */
#define FSW_H_NO_TABLE       (0x00020000u)  /* no valid module table (boot table refused) */
#define FSW_H_TC_REJ         (0x00040000u)  /* a telecommand was refused this step (wrong mode) */
#define FSW_H_TBL_PENDING    (0x00080000u)  /* RENDEZVOUS: a validated impulse table waits for the
                                               scheduler to leave PLANNING/ARMED/FIRING/FINAL */

/* Table registry. */
#define FSW_TBL_ID_OBS       0x0B01u
#define FSW_TBL_OBS_LAYOUT   1u
#define FSW_TBL_OBS_PAYLOAD  646u          /* bytes; fsw_obs_table.c documents the layout */
#define FSW_TBL_ID_IMP       0x0B04u
#define FSW_TBL_IMP_LAYOUT   1u
#define FSW_TBL_IMP_PAYLOAD  176u          /* bytes; fsw_imp_table.c documents the layout */
/* Boot image staging: the larger of the two mission tables. */
#define FSW_BOOT_IMG_BYTES   (FSW_TABLE_HDR_BYTES + \
                              ((FSW_TBL_OBS_PAYLOAD > FSW_TBL_IMP_PAYLOAD) ? FSW_TBL_OBS_PAYLOAD : FSW_TBL_IMP_PAYLOAD))
/* Detail of a MODULE veto of the impulse table (reason word bits 8..15): imp_params_check's why
   word has 12 bits, so the detail is 1 + the index of its lowest set IMP_WHY_* bit (1 PERIOD,
   2 ITER, 3 TOL, 4 RHO, 5 ALPHA, 6 SCALE, 7 TAU, 8 LEAD, 9 GRID, 10 CAL, 11 FD, 12 NAV), the
   executive's own same-period check gives 1 (PERIOD), and 0xFF a candidate that did not decode
   (or a failure without a why bit). */
#define FSW_IMP_VETO_UNDECODED 0xFFu

/* Telemetry layout version carried beside the encoded bytes (fsw_tlm_frame_t). */
#define FSW_TLM_LAYOUT_VERSION  0x00010001u   /* DETUMBLE mission (fsw_tlm_formats.json) */
#define FSW_TLM_BYTES           192u       /* encoded size of fsw_tlm_t (fsw_tlm_encode) */
#define FSW_TLM_RDV_LAYOUT_VERSION 0x00020001u   /* RENDEZVOUS (fsw_tlm_formats_rdv.json) */
#define FSW_TLM_RDV_BYTES       502u       /* its encoded size (generated fsw_tlm_rdv.c) */

typedef struct {
    uint32_t period_us;      /* control period; every module table must agree */
    uint16_t stale_max;      /* consecutive invalid steps on a channel before SAFE (>= 1) */
    uint32_t boot_mode;      /* mode entered after BOOT: STANDBY or the mission mode */
    uint32_t mission;        /* FSW_MISSION_* */
} fsw_cfg_t;

typedef struct {
    int64_t  utime_us;       /* echoed, never computed with */
    int64_t  seq;            /* echoed; the observer sees the low 32 bits */
    uint32_t n_counts;       /* valid entries of counts[] (<= FSW_IN_MAX) */
    int32_t  counts[FSW_IN_MAX];
    uint8_t  status[FSW_IN_MAX];   /* FSW_ST_* per channel */
    uint32_t mode_cmd;       /* FSW_CMD_NONE or a target mode */
    uint32_t host_missed;    /* host-reported cumulative counters, copied into telemetry */
    uint32_t host_rejected;
    uint32_t tc;             /* FSW_TC_* telecommand this step, FSW_TC_NONE otherwise */
    int32_t  tc_arg[8];
} fsw_in_t;

typedef struct {
    int64_t  utime_us;
    int64_t  seq;
    uint32_t step;
    uint32_t mode;
    uint32_t health;         /* aggregate: executive bits 8..19, fx status 0..7 */
    uint32_t health_sticky;  /* OR of health since init */
    uint32_t n_chan_rej;     /* channel samples refused (range or STALE bit), saturating */
    uint32_t n_stale_steps;  /* steps with at least one invalid consumed channel */
    uint32_t n_in_bad;       /* frames with n_counts < FSW_N_SENS (all channels invalid) */
    uint32_t n_tbl_acc;      /* table candidates committed */
    uint32_t n_tbl_rej;      /* table uploads refused (loader or module veto) */
    uint32_t tbl_reason;     /* reason word of the latest refusal (fsw_table.h) */
    uint32_t tbl_revision;   /* active table revision (the mission's: observer or impulse) */
    uint32_t n_scrub_err;
    uint32_t n_safe;         /* SAFE entries */
    uint32_t n_mode_rej;     /* refused mode commands */
    uint32_t host_missed;
    uint32_t host_rejected;
    int32_t  act_cnt[FSW_RDV_N_ACT];   /* the mission's actuator counts (DETUMBLE: 2) */
    uint32_t obs_health;     /* observer health word of this step (0 when not run) */
    obs_tlm_t obs;           /* observer telemetry (last run) */
    uint32_t mission;
    uint32_t n_tc;           /* telecommands taken by a module */
    uint32_t n_tc_rej;       /* telecommands refused (wrong mode) */
    uint32_t imp_health;     /* impulse health word of this step (0 when not run) */
    imp_tlm_t imp;           /* impulse telemetry (last run) */
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
    bool         init_ok;
    uint32_t     mode;
    uint32_t     step;
    /* tables: the loader owns the images; obs_p is the decoded active table */
    fsw_table_t  obs_tbl;
    bool         have_obs_p;
    obs_params_t obs_p;
    obs_params_t obs_cand;           /* scratch: candidate decoded for its module check */
    bool         tbl_rej_pending;    /* a refusal since the last step (FSW_H_TBL_REJ) */
    uint8_t      boot_img[FSW_BOOT_IMG_BYTES];   /* boot image staging (either mission) */
    /* RENDEZVOUS: the impulse table (loader images; imp_p below is the decoded active table) */
    fsw_table_t  imp_tbl;
    bool         have_imp_p;
    imp_params_t imp_cand;           /* scratch: candidate decoded for its module check */
    /* modules */
    obs_state_t  obs_s;
    obs_out_t    obs_o;
    imp_params_t imp_p;              /* active impulse table (RENDEZVOUS) */
    imp_state_t  imp_s;
    imp_out_t    imp_o;
    imp_in_t     imp_i;
    /* input acceptance */
    int32_t      last_good[FSW_RDV_N_SENS];
    uint32_t     stale_run[FSW_RDV_N_SENS];
    uint32_t     sat_run[FSW_RDV_N_SENS];
    fsw_tlm_t    tlm;                /* counters live here */
} fsw_t;

/*
 * Validates cfg, encodes the boot observer table (boot_obs, e.g. &OBS_TBL_50HZ_PHYS) into an
 * image and loads it through the same checks as an upload. FSW_ERR_ARG on a bad cfg; a boot
 * table that fails its checks leaves the executive in BOOT → SAFE with FSW_H_NO_TABLE.
 */
fsw_rc_t fsw_init(fsw_t *f, const fsw_cfg_t *cfg, const obs_params_t *boot_obs, uint32_t revision);
/* The RENDEZVOUS mission (cfg->mission == FSW_MISSION_RENDEZVOUS): the impulse scheduler. Like
   fsw_init, the boot table (boot_imp, e.g. &IMP_TBL_DEFAULT) is encoded into an image and loaded
   through the loader's checks, then decoded and checked by imp_params_check and the same-period
   rule. A refusal leaves BOOT → SAFE with FSW_H_NO_TABLE and returns the loader's code
   (FSW_ERR_RANGE, ...) or FSW_ERR_INVARIANT for the module check; FSW_ERR_ARG on a bad cfg. */
fsw_rc_t fsw_init_rdv(fsw_t *f, const fsw_cfg_t *cfg, const imp_params_t *boot_imp, uint32_t revision);
void     fsw_step(fsw_t *f, const fsw_in_t *in, fsw_out_t *out);
/* One upload chunk for the mission's table (DETUMBLE: observer, RENDEZVOUS: impulse), between
   steps. A completed candidate is decoded and module-checked at once; *why gets the loader's
   reason word. DETUMBLE: active at the next fsw_step. RENDEZVOUS: active at the first step
   boundary at which the scheduler is not running a mission (executive outside RENDEZVOUS, or
   scheduler IDLE, DONE, INFEASIBLE, NO_SOLUTION, ABORTED, FAULT); until then the candidate waits
   (FSW_H_TBL_PENDING, further chunks BUSY). In RENDEZVOUS the commit re-initialises the
   scheduler with the new table (IDLE). */
fsw_rc_t fsw_table_upload(fsw_t *f, const fsw_table_chunk_t *c, uint32_t *why);
/* The loader of the mission's table (for acks: cand_got, state). Never NULL for a non-NULL f. */
const fsw_table_t *fsw_mission_table(const fsw_t *f);

/* Encodes t little-endian in its mission's layout (DETUMBLE: FSW_TLM_BYTES, fsw_tlm_formats.json;
   RENDEZVOUS: FSW_TLM_RDV_BYTES, fsw_tlm_formats_rdv.json). Returns the bytes written, 0 if cap
   is too small. fsw_tlm_layout() gives the layout version of t. */
uint32_t fsw_tlm_encode(const fsw_tlm_t *t, uint8_t *buf, uint32_t cap);
uint32_t fsw_tlm_layout(const fsw_tlm_t *t);
uint32_t fsw_tlm_rdv_encode(const fsw_tlm_t *t, uint8_t *buf, uint32_t cap);   /* generated */

/* Observer table image (fsw_obs_table.c). */
extern const fsw_table_desc_t FSW_TBL_DESC_OBS;
uint32_t fsw_obs_table_encode(const obs_params_t *p, uint32_t revision, uint8_t *img, uint32_t cap);
/* Decodes in place: on failure *p is partly written and must not be used (callers decode
   into a scratch struct and copy on success). */
fsw_rc_t fsw_obs_table_decode(const uint8_t *payload, uint32_t len, uint32_t revision,
                              obs_params_t *p);

/* Impulse table image (fsw_imp_table.c): every imp_params_t field but `revision`, which the
   header carries. Encode returns the image bytes (FSW_TABLE_HDR_BYTES + FSW_TBL_IMP_PAYLOAD), 0
   if cap is too small or p/img is NULL. Decode takes the payload only (FSW_ERR_ARG for a wrong
   length or NULL) and sets p->revision = revision; in place, so on failure *p is partly written
   and must not be used (callers decode into a scratch struct and copy on success). */
extern const fsw_table_desc_t FSW_TBL_DESC_IMP;
uint32_t fsw_imp_table_encode(const imp_params_t *p, uint32_t revision, uint8_t *img, uint32_t cap);
fsw_rc_t fsw_imp_table_decode(const uint8_t *payload, uint32_t len, uint32_t revision,
                              imp_params_t *p);

#endif /* FSW_APP_EXEC_H */
