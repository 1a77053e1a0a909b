/*
 * @prefix@_mission.h — @module@ as the @MISSION@ mission: its table on the wire and its adapter
 * to the executive (contract: fsw/app/fsw_mission.h; names: @prefix@_ids.h, from @prefix@_iface.py).
 *
 * Channel map (@PREFIX@_MIS_DESC): sensor counts[0] = omega_BN_B_x (2^-20 rad/s), valid in
 * (-rate_max_cnt, rate_max_cnt); actuator counts[0] = tau_cmd_B_x (2^-16 N m), safe value 0.
 * The channel invalid, or at full scale (plant SAT), for stale_max steps is a SAFE trigger.
 */
#ifndef FSW_@PREFIX@_MISSION_H
#define FSW_@PREFIX@_MISSION_H

#include "@prefix@.h"
#include "fsw_mission.h"

#define @PREFIX@_TBL_PAYLOAD 20u   /* bytes; @prefix@_table.c documents the layout */

/* The mission's block inside fsw_t. */
typedef struct {
    @prefix@_params_t p;       /* active table, decoded */
    @prefix@_params_t cand;    /* scratch: a candidate decoded for its module check */
    bool              have_p;
    @prefix@_state_t  s;
    @prefix@_out_t    o;
} @prefix@_mis_t;

/* Table image (@prefix@_table.c). Encode returns the image bytes (header + payload), 0 if cap is
   too small or a pointer is NULL. Decode takes the payload only and sets p->revision; in place,
   so on failure *p is partly written and must not be used. */
extern const fsw_table_desc_t @PREFIX@_TBL_DESC;
uint32_t @prefix@_table_encode(const @prefix@_params_t *p, uint32_t revision, uint8_t *img, uint32_t cap);
fsw_rc_t @prefix@_table_decode(const uint8_t *payload, uint32_t len, uint32_t revision, @prefix@_params_t *p);

/* Adapter (fsw/app/fsw_mission.h). */
extern const fsw_mis_desc_t @PREFIX@_MIS_DESC;
void     @prefix@_mis_reset(@prefix@_mis_t *b);
uint32_t @prefix@_mis_check(@prefix@_mis_t *b, const uint8_t *pl, uint32_t len, uint32_t period_us);
bool     @prefix@_mis_load(@prefix@_mis_t *b, const uint8_t *pl, uint32_t len, uint32_t rev, bool in_mode);
bool     @prefix@_mis_commit_ok(const @prefix@_mis_t *b, bool in_mode);
void     @prefix@_mis_ranges(const @prefix@_mis_t *b, fsw_range_t *r);
void     @prefix@_mis_enter(@prefix@_mis_t *b);
uint32_t @prefix@_mis_step(@prefix@_mis_t *b, const fsw_acc_t *acc, int32_t *act);
const @prefix@_tlm_t *@prefix@_mis_tlm(const @prefix@_mis_t *b);
void     @prefix@_tlm_wr(fsw_wr_t *w, const @prefix@_tlm_t *t);   /* generated: @prefix@_tlm.c */

#endif /* FSW_@PREFIX@_MISSION_H */
