/*
 * obs_mission.h — the observer as the DETUMBLE mission: its table on the wire and its adapter to
 * the executive (contract: fsw/app/fsw_mission.h; names: obs_ids.h, from obs_iface.py).
 *
 * Channel map (OBS_MIS_DESC): sensor counts[0] = gyro y, counts[1] = gyro z (2^-20 rad/s LSB per
 * the table's gyro_cnt_shift), valid in (-gyro_max_cnt, gyro_max_cnt); actuator counts[0] =
 * gimbal rate y, counts[1] = gimbal rate z (the table's act_cnt_shift), safe value 0. A channel
 * invalid, or at full scale (plant SAT), for stale_max steps is a SAFE trigger.
 */
#ifndef FSW_OBS_MISSION_H
#define FSW_OBS_MISSION_H

#include "obs.h"
#include "fsw_mission.h"

#define OBS_TBL_PAYLOAD 652u   /* bytes; obs_table.c documents the layout */

/* The mission's block inside fsw_t. */
typedef struct {
    obs_params_t p;            /* active table, decoded */
    obs_params_t cand;         /* scratch: a candidate decoded for its module check */
    bool         have_p;
    obs_state_t  s;
    obs_out_t    o;
} obs_mis_t;

/* Table image (obs_table.c). Encode returns the image bytes (header + OBS_TBL_PAYLOAD), 0 if cap
   is too small or a pointer is NULL. Decode takes the payload only and sets p->revision; in
   place, so on failure *p is partly written and must not be used. */
extern const fsw_table_desc_t OBS_TBL_DESC;
uint32_t obs_table_encode(const obs_params_t *p, uint32_t revision, uint8_t *img, uint32_t cap);
fsw_rc_t obs_table_decode(const uint8_t *payload, uint32_t len, uint32_t revision, obs_params_t *p);

/* Adapter (fsw/app/fsw_mission.h). */
extern const fsw_mis_desc_t OBS_MIS_DESC;
void     obs_mis_reset(obs_mis_t *b);
uint32_t obs_mis_check(obs_mis_t *b, const uint8_t *pl, uint32_t len, uint32_t period_us);
bool     obs_mis_load(obs_mis_t *b, const uint8_t *pl, uint32_t len, uint32_t rev, bool in_mode);
bool     obs_mis_commit_ok(const obs_mis_t *b, bool in_mode);
void     obs_mis_ranges(const obs_mis_t *b, fsw_range_t *r);
void     obs_mis_enter(obs_mis_t *b);
uint32_t obs_mis_step(obs_mis_t *b, const fsw_acc_t *acc, int32_t *act);
const obs_tlm_t *obs_mis_tlm(const obs_mis_t *b);
void     obs_tlm_wr(fsw_wr_t *w, const obs_tlm_t *t);   /* generated: obs_tlm.c */

#endif /* FSW_OBS_MISSION_H */
