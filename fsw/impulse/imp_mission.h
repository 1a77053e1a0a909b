/*
 * imp_mission.h — the impulse scheduler as the RENDEZVOUS mission: its table on the wire and its
 * adapter to the executive (contract: fsw/app/fsw_mission.h; names: imp_ids.h, from imp_iface.py).
 *
 * Channel map (IMP_MIS_DESC): sensor counts[0..2] = nav position x, y, z [1 mm], counts[3..5] =
 * nav velocity [10 um/s], counts[6] = the sample's step index (the plant's k); one sample, valid
 * only when all 7 channels are (FSW_MIS_SAMPLE). Actuator counts[0..5] = on_start, [6..11] =
 * on_len [1 us within the step], [12] = on_mask (bit j: thruster +x, -x, +y, -y, +z, -z); safe
 * values 0 (every valve closed). A stale nav sample is never a SAFE trigger: the scheduler flies a
 * dropout open loop by design (spec 50 §8 "nav dropout in FIRING"); its own faults (STUCK_*,
 * INTERLOCK) raise FSW_H_MODULE. Telecommands START, ABORT, CLEAR_FAULTS (imp_ids.h IMP_CMD_*).
 * The scheduler's time base is the frame's seq (the plant's step index k, as in its commands and
 * nav tags), not the executive's step counter, so lost frames do not shift it.
 */
#ifndef FSW_IMP_MISSION_H
#define FSW_IMP_MISSION_H

#include "imp.h"
#include "fsw_mission.h"

#define IMP_TBL_PAYLOAD 176u   /* bytes; imp_table.c documents the layout */
#define IMP_ACT_MASK    12u    /* index of on_mask in the actuator counts */
#define IMP_CH_NAV_STEP 6u     /* index of the nav sample's step index in the sensor counts */

/* Nav counts accepted: +-200 km (1 mm) and +-250 m/s (10 um/s), inside the scheduler's q28 state
   range (+-8 length units = +-250 km, +-283 m/s at 400 km). */
#define IMP_NAV_POS_MAX_MM   INT32_C(200000000)
#define IMP_NAV_VEL_MAX_CNT  INT32_C(25000000)

/* The mission's block inside fsw_t. */
typedef struct {
    imp_params_t p;            /* active table, decoded */
    imp_params_t cand;         /* scratch: a candidate decoded for its module check */
    imp_state_t  s;
    imp_out_t    o;
    imp_in_t     in;
} imp_mis_t;

/* Table image (imp_table.c): every imp_params_t field but `revision`, which the header carries.
   Encode returns the image bytes (header + IMP_TBL_PAYLOAD), 0 if cap is too small or a pointer
   is NULL. Decode takes the payload only (FSW_ERR_ARG for a wrong length or NULL) and sets
   p->revision; in place, so on failure *p is partly written and must not be used. */
extern const fsw_table_desc_t IMP_TBL_DESC;
uint32_t imp_table_encode(const imp_params_t *p, uint32_t revision, uint8_t *img, uint32_t cap);
fsw_rc_t imp_table_decode(const uint8_t *payload, uint32_t len, uint32_t revision, imp_params_t *p);

/* Adapter (fsw/app/fsw_mission.h). */
extern const fsw_mis_desc_t IMP_MIS_DESC;
void     imp_mis_reset(imp_mis_t *b);
uint32_t imp_mis_check(imp_mis_t *b, const uint8_t *pl, uint32_t len, uint32_t period_us);
bool     imp_mis_load(imp_mis_t *b, const uint8_t *pl, uint32_t len, uint32_t rev, bool in_mode);
bool     imp_mis_commit_ok(const imp_mis_t *b, bool in_mode);
void     imp_mis_ranges(const imp_mis_t *b, fsw_range_t *r);
void     imp_mis_enter(imp_mis_t *b);
uint32_t imp_mis_step(imp_mis_t *b, const fsw_acc_t *acc, int32_t *act);
const imp_tlm_t *imp_mis_tlm(const imp_mis_t *b);
void     imp_tlm_wr(fsw_wr_t *w, const imp_tlm_t *t);   /* generated: imp_tlm.c */

#endif /* FSW_IMP_MISSION_H */
