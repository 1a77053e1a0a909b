/*
 * pd_mission.h — pd as the HOLD mission: its table on the wire and its adapter to the executive
 * (contract: fsw/app/fsw_mission.h; names: pd_ids.h, from pd_iface.py).
 *
 * Channel map (PD_MIS_DESC): sensors counts[0..2] attitude yaw / roll / pitch (2^-26 rad),
 * counts[3..5] gimbal encoders (2^-24 rad); actuators counts[0..2] gimbal torque (2^-20 N m), safe
 * value 0 (coasting is passive-safe, spec 40 §8). The executive's range accepts every count; the law
 * itself refuses out-of-range samples, so they are counted as range_rej, not as missing.
 * Step divider: the law runs on every n_div-th frame by seq from the mode entry (Ty = n_div period);
 * in between the actuators hold the sample's torque (the zero-order hold of spec 40 §3.2). A seq jump is
 * a gap of lost samples (pd_note_gap).
 */
#ifndef FSW_PD_MISSION_H
#define FSW_PD_MISSION_H

#include "pd.h"
#include "fsw_mission.h"

#define PD_TBL_PAYLOAD 3068u  /* bytes: 56 common + 3 x (100 gains and nodes + 904 estimator block); pd_table.c */

/* The mission's block inside fsw_t. */
typedef struct {
    pd_table_t  t;                 /* active table, decoded */
    pd_table_t  cand;              /* scratch: a candidate decoded for its module check */
    pd_params_t chk;               /* scratch: one channel of the candidate for pd_params_check (a
                                      pd_params_t, estimator block included, is ~1 kB: never on the stack) */
    pd_params_t p[PD_N_CH];        /* each channel's parameters, from t */
    pd_state_t  s[PD_N_CH];
    pd_out_t    o[PD_N_CH];
    pd_tlm_t    tlm;
    int64_t     seq0;              /* seq of the first step after the mode entry: sample phase origin */
    int64_t     last_seq;          /* seq of the previous step (stale: not advanced) */
    int64_t     last_idx;          /* sample index of the last law sample (-1: none yet) */
    bool        have_seq;
    bool        have_p;
    uint32_t    n_loads;           /* tables made active since boot (1: the boot table) */
    uint32_t    health;            /* OR of the channels' words at the last sample */
} pd_mis_t;

/* Table image (pd_table.c). Encode returns the image bytes (header + payload), 0 if cap is too small
   or a pointer is NULL. Decode takes the payload only and sets revision; in place, so on failure *t
   is partly written and must not be used. */
extern const fsw_table_desc_t PD_TBL_DESC;
uint32_t pd_table_encode(const pd_table_t *t, uint32_t revision, uint8_t *img, uint32_t cap);
fsw_rc_t pd_table_decode(const uint8_t *payload, uint32_t len, uint32_t revision, pd_table_t *t);
/* One channel's parameters from a decoded table (k < PD_N_CH). */
void     pd_params_of(const pd_table_t *t, uint32_t k, pd_params_t *p);
/* The module check of a whole table: pd_params_check of every channel, plus the roll cap. p is the
   caller's scratch for one channel's parameters (overwritten). */
uint32_t pd_table_check(const pd_table_t *t, pd_params_t *p, uint32_t *why);

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
