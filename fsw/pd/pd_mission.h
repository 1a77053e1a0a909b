/*
 * pd_mission.h — pd as the HOLD mission: its table on the wire and its adapter
 * to the executive (contract: fsw/app/fsw_mission.h; names: pd_ids.h, from pd_iface.py).
 *
 * Channel map (PD_MIS_DESC): sensor counts[0] = omega_BN_B_x (2^-20 rad/s), valid in
 * (-rate_max_cnt, rate_max_cnt); actuator counts[0] = tau_cmd_B_x (2^-16 N m), safe value 0.
 * The channel invalid, or at full scale (plant SAT), for stale_max steps is a SAFE trigger.
 */
#ifndef FSW_PD_MISSION_H
#define FSW_PD_MISSION_H

#include "pd.h"
#include "fsw_mission.h"

#define PD_TBL_PAYLOAD 20u   /* bytes; pd_table.c documents the layout */

/* The mission's block inside fsw_t. */
typedef struct {
    pd_params_t p;       /* active table, decoded */
    pd_params_t cand;    /* scratch: a candidate decoded for its module check */
    bool              have_p;
    pd_state_t  s;
    pd_out_t    o;
} pd_mis_t;

/* Table image (pd_table.c). Encode returns the image bytes (header + payload), 0 if cap is
   too small or a pointer is NULL. Decode takes the payload only and sets p->revision; in place,
   so on failure *p is partly written and must not be used. */
extern const fsw_table_desc_t PD_TBL_DESC;
uint32_t pd_table_encode(const pd_params_t *p, uint32_t revision, uint8_t *img, uint32_t cap);
fsw_rc_t pd_table_decode(const uint8_t *payload, uint32_t len, uint32_t revision, pd_params_t *p);

/* Adapter (fsw/app/fsw_mission.h). */
extern const fsw_mis_desc_t PD_MIS_DESC;
void     pd_mis_reset(pd_mis_t *b);
uint32_t pd_mis_check(pd_mis_t *b, const uint8_t *pl, uint32_t len, uint32_t period_us);
bool     pd_mis_load(pd_mis_t *b, const uint8_t *pl, uint32_t len, uint32_t rev, bool in_mode);
bool     pd_mis_commit_ok(const pd_mis_t *b, bool in_mode);
void     pd_mis_ranges(const pd_mis_t *b, fsw_range_t *r);
void     pd_mis_enter(pd_mis_t *b);
uint32_t pd_mis_step(pd_mis_t *b, const fsw_acc_t *acc, int32_t *act);
const pd_tlm_t *pd_mis_tlm(const pd_mis_t *b);
void     pd_tlm_wr(fsw_wr_t *w, const pd_tlm_t *t);   /* generated: pd_tlm.c */

#endif /* FSW_PD_MISSION_H */
