/*
 * rly_mission.h — relay as the RELAY mission: its table on the wire and its adapter
 * to the executive (contract: fsw/app/fsw_mission.h; names: rly_ids.h, from rly_iface.py).
 *
 * Channel map (RLY_MIS_DESC): sensor counts[0] = x_B_rad (2^-24 rad, the sensor's +-2^23
 * counts); actuator counts[0] = m_cmd_B, a RLY_LVL_* code, safe value RLY_LVL_OFF. Loss of the
 * angle is the module's own business (F1/F2: tests skipped, then COAST, never the executive's
 * SAFE), so the mission declares no SAFE trigger; a sample with the plant's SAT bit is invalid.
 */
#ifndef FSW_RLY_MISSION_H
#define FSW_RLY_MISSION_H

#include "rly.h"
#include "fsw_mission.h"

#define RLY_TBL_PAYLOAD 188u   /* bytes; rly_table.c documents the layout */

/* The mission's block inside fsw_t. */
typedef struct {
    rly_params_t p;       /* active table, decoded */
    rly_params_t cand;    /* scratch: a candidate decoded for its module check */
    bool              have_p;
    rly_state_t  s;
    rly_out_t    o;
} rly_mis_t;

/* Table image (rly_table.c). Encode returns the image bytes (header + payload), 0 if cap is
   too small or a pointer is NULL. Decode takes the payload only and sets p->revision; in place,
   so on failure *p is partly written and must not be used. */
extern const fsw_table_desc_t RLY_TBL_DESC;
uint32_t rly_table_encode(const rly_params_t *p, uint32_t revision, uint8_t *img, uint32_t cap);
fsw_rc_t rly_table_decode(const uint8_t *payload, uint32_t len, uint32_t revision, rly_params_t *p);

/* Adapter (fsw/app/fsw_mission.h). */
extern const fsw_mis_desc_t RLY_MIS_DESC;
void     rly_mis_reset(rly_mis_t *b);
uint32_t rly_mis_check(rly_mis_t *b, const uint8_t *pl, uint32_t len, uint32_t period_us);
bool     rly_mis_load(rly_mis_t *b, const uint8_t *pl, uint32_t len, uint32_t rev, bool in_mode);
bool     rly_mis_commit_ok(const rly_mis_t *b, bool in_mode);
void     rly_mis_ranges(const rly_mis_t *b, fsw_range_t *r);
void     rly_mis_enter(rly_mis_t *b);
uint32_t rly_mis_step(rly_mis_t *b, const fsw_acc_t *acc, int32_t *act);
const rly_tlm_t *rly_mis_tlm(const rly_mis_t *b);
void     rly_tlm_wr(fsw_wr_t *w, const rly_tlm_t *t);   /* generated: rly_tlm.c */

#endif /* FSW_RLY_MISSION_H */
