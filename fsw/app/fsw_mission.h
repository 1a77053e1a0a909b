/*
 * fsw_mission.h — the contract between the executive and a mission adapter (spec 00 §3;
 * README "Design: one module, one folder").
 *
 * A mission is a flight module plus everything the executive needs to fly it. Its adapter,
 * fsw/<module>/<p>_mission.{h,c}, owns every per-mission fact: the channel map (which counts it
 * consumes and drives, with ranges), its telecommands, its parameter table (codec, descriptor,
 * module check, the commit-at-boundary rule), its SAFE triggers, its safe actuator values and its
 * telemetry block. The executive (fsw_exec.c) writes the step order once and reaches a mission
 * only through the dispatch generated from missions.json (build tree: fsw_missions_gen.{h,c}),
 * a switch over the configured missions: no function pointers, so the static stack proof sees
 * every path.
 *
 * An adapter with prefix p defines (all on a caller-owned block p_mis_t, no globals):
 *   extern const fsw_mis_desc_t P_MIS_DESC;        the data below
 *   void     p_mis_reset(p_mis_t *b);               BOOT: no table, module outputs safe
 *   uint32_t p_mis_check(p_mis_t *b, const uint8_t *pl, uint32_t len, uint32_t period_us);
 *            module check of a candidate payload: 0 = passes, else the veto detail
 *            (fsw_table_veto_detail of the module's why word, FSW_VETO_UNDECODED when it does
 *            not decode)
 *   bool     p_mis_load(p_mis_t *b, const uint8_t *pl, uint32_t len, uint32_t rev, bool in_mode);
 *            makes a (checked) payload the active parameters; in_mode: the mission mode is
 *            flying, restart the module if the new table requires it. false: did not decode.
 *   bool     p_mis_commit_ok(const p_mis_t *b, bool in_mode);   commit-at-boundary rule
 *   void     p_mis_ranges(const p_mis_t *b, fsw_range_t *r);    valid count range per sensor
 *            channel under the active table (r[0..n_sens))
 *   void     p_mis_enter(p_mis_t *b);               mission mode entered: (re)initialise
 *   uint32_t p_mis_step(p_mis_t *b, const fsw_acc_t *acc, int32_t *act);
 *            one step in the mission mode: act[0..n_act) and the module health word
 *   const p_tlm_t *p_mis_tlm(const p_mis_t *b);     the module's telemetry block (last run)
 *   void     p_tlm_wr(fsw_wr_t *w, const p_tlm_t *t);  generated from <p>_iface.py
 */
#ifndef FSW_APP_MISSION_H
#define FSW_APP_MISSION_H

#include <stdint.h>
#include <stdbool.h>
#include "fx.h"
#include "fsw_table.h"
#include "fsw_codec.h"

#define FSW_IN_MAX   16u   /* sensor channels a frame can carry (sensor_frame_v2_t.counts[16]) */
#define FSW_ACT_MAX  16u   /* actuator channels (actuator_cmd_v2_t.counts[16]) */
#define FSW_TC_ARGS  8u    /* telecommand argument words (fsw_cmd_v2_t.args[8]) */

/* Telecommand ids on the wire: (mission id + 1) << FSW_TC_NS_SHIFT | local id (1..255), so one
   mission's command can never be taken for another's (fsw_in_t.tc, gnc.fsw_cmd_v2_t.cmd). */
#define FSW_TC_NS_SHIFT 8u
#define FSW_TC_LOCAL_MASK 0xFFu
#define FSW_TC_ID(mission, local) ((((uint32_t)(mission) + 1u) << FSW_TC_NS_SHIFT) | (uint32_t)(local))

/* fsw_mis_desc_t.flags: the mission's input policy and SAFE triggers. */
#define FSW_MIS_STALE_SAFE 0x1u  /* a consumed channel invalid for stale_max steps -> SAFE */
#define FSW_MIS_SAT_SAFE   0x2u  /* the plant's SAT bit on a channel for stale_max steps -> SAFE */
#define FSW_MIS_SAMPLE     0x4u  /* the channels form one sample: valid only all together, and a
                                    refused sample counts once (not once per channel) */

typedef struct {
    int32_t min;             /* inclusive raw counts; min > max: never valid */
    int32_t max;
} fsw_range_t;

typedef struct {
    uint32_t n_sens;                 /* sensor channels consumed, counts[0..n_sens) */
    uint32_t n_act;                  /* actuator channels driven, counts[0..n_act) */
    uint32_t flags;                  /* FSW_MIS_* */
    uint32_t fault_bits;             /* module health bits that raise FSW_H_MODULE */
    uint32_t safe_bits;              /* module health bits that send the executive to SAFE: faults the
                                        module itself judged persistent (its own persistence rule),
                                        so the step that reports one already flies safe_act */
    uint32_t tc_max;                 /* telecommand local ids 1..tc_max exist */
    uint32_t tlm_layout;             /* telemetry layout version */
    uint32_t tlm_bytes;              /* bytes of the whole encoded telemetry */
    const fsw_table_desc_t *table;   /* the mission's parameter table */
    const int32_t *safe_act;         /* n_act safe actuator values (outside the mission mode) */
} fsw_mis_desc_t;

/* A step's inputs as the executive accepted them (spec 00 §3.3 steps 2-3). */
typedef struct {
    int64_t  seq;                    /* the frame's seq (the plant's step index k) */
    int32_t  cnt[FSW_IN_MAX];        /* consumed channel i: this step's count, or its last good one */
    uint32_t valid;                  /* bit i: channel i accepted this step */
    uint32_t sat;                    /* bit i: accepted, with the plant's SAT bit */
    uint32_t tc;                     /* telecommand local id accepted for this step (0: none) */
    int32_t  tc_arg[FSW_TC_ARGS];    /* its arguments, as the frame carried them */
} fsw_acc_t;

#endif /* FSW_APP_MISSION_H */
