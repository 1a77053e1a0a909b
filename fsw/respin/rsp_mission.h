/*
 * rsp_mission.h — respin as the RESPIN mission: its table on the wire and its adapter
 * to the executive (contract: fsw/app/fsw_mission.h; names: rsp_ids.h, from rsp_iface.py).
 *
 * Channel map (RSP_MIS_DESC): sensor counts[0] = omega_BN_B_x (2^-20 rad/s), valid in
 * (-rate_max_cnt, rate_max_cnt); actuator counts[0] = tau_cmd_B_x (2^-16 N m), safe value 0.
 * The channel invalid, or at full scale (plant SAT), for stale_max steps is a SAFE trigger.
 */
#ifndef FSW_RSP_MISSION_H
#define FSW_RSP_MISSION_H

#include "rsp.h"
#include "fsw_mission.h"

#define RSP_TBL_PAYLOAD 156u  /* bytes; rsp_table.c documents the layout */

/* The mission's block inside fsw_t. */
typedef struct {
    rsp_params_t p;       /* active table, decoded */
    rsp_params_t cand;    /* scratch: a candidate decoded for its module check */
    bool              have_p;
    rsp_state_t  s;
    rsp_out_t    o;
} rsp_mis_t;

/* Table image (rsp_table.c). Encode returns the image bytes (header + payload), 0 if cap is
   too small or a pointer is NULL. Decode takes the payload only and sets p->revision; in place,
   so on failure *p is partly written and must not be used. */
extern const fsw_table_desc_t RSP_TBL_DESC;
uint32_t rsp_table_encode(const rsp_params_t *p, uint32_t revision, uint8_t *img, uint32_t cap);
fsw_rc_t rsp_table_decode(const uint8_t *payload, uint32_t len, uint32_t revision, rsp_params_t *p);

/* Adapter (fsw/app/fsw_mission.h). */
extern const fsw_mis_desc_t RSP_MIS_DESC;
void     rsp_mis_reset(rsp_mis_t *b);
uint32_t rsp_mis_check(rsp_mis_t *b, const uint8_t *pl, uint32_t len, uint32_t period_us);
bool     rsp_mis_load(rsp_mis_t *b, const uint8_t *pl, uint32_t len, uint32_t rev, bool in_mode);
bool     rsp_mis_commit_ok(const rsp_mis_t *b, bool in_mode);
void     rsp_mis_ranges(const rsp_mis_t *b, fsw_range_t *r);
void     rsp_mis_enter(rsp_mis_t *b);
uint32_t rsp_mis_step(rsp_mis_t *b, const fsw_acc_t *acc, int32_t *act);
const rsp_tlm_t *rsp_mis_tlm(const rsp_mis_t *b);
void     rsp_tlm_wr(fsw_wr_t *w, const rsp_tlm_t *t);   /* generated: rsp_tlm.c */

#endif /* FSW_RSP_MISSION_H */
