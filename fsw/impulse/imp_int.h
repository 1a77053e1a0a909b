/*
 * imp_int.h — internal interface between the parts of the impulse scheduler module. Not part of
 * the module API. The files call downward only, top to bottom:
 *   imp.c        contract, modes, plan job, re-plan epochs, health, telemetry
 *   imp_nav.c    navigation intake, prediction through the commanded burns, outlier gate,
 *                stuck-valve monitor, thrust-level calibration at an epoch
 *   imp_tl.c     timeline and valve windows, response of a timeline, expected miss
 *   imp_solve.c  switching-time solver (API in imp.h)
 *   imp_sched.c  best rounding onto the valve grid (API in imp.h)
 *   imp_log.c    log of commanded burns and its response, calibration bookkeeping
 *   imp_cw.c     CW kernels (API in imp.h), valve-grid units, response of one burn
 */
#ifndef FSW_IMP_INT_H
#define FSW_IMP_INT_H

#include "imp.h"

/* Monitor events returned by imp_nav_intake (kind in bits 8.., thruster in bits 0..7). */
#define IMP_EV_NONE       0u
#define IMP_EV_STUCK_OFF  0x100u
#define IMP_EV_STUCK_ON   0x200u
#define IMP_EV_KIND_MASK  0xF00u
#define IMP_EV_THR_MASK   0x0FFu

/* ------------------------------------------------------------------ subsystem geometry */
/* The decoupled subsystems of the solve and of the rounding (imp_solve.c, imp_sched.c): x-y
   (axes 0-1, state rows 0-3) and z (axis 2, state rows 4-5). Inline: they sit in the inner loops. */
static inline uint32_t imp_sub_nax(uint32_t sub)
{
    return (sub == IMP_SUB_XY) ? 2u : 1u;
}

static inline uint32_t imp_sub_ax0(uint32_t sub)
{
    return (sub == IMP_SUB_XY) ? 0u : 2u;
}

static inline uint32_t imp_sub_row0(uint32_t sub)
{
    return (sub == IMP_SUB_XY) ? 0u : 4u;
}

/* ------------------------------------------------------------------ imp_cw.c */
/* (and the CW kernels of imp.h: imp_trig, imp_psi, imp_phie, imp_phi_apply) */
/* Grid units per step (1 with whole steps) and the grid unit in us. */
uint32_t imp_grid(const imp_params_t *p);
uint32_t imp_grid_us(const imp_params_t *p);
/* Grid units -> tau q29 (n * k_gtau); n > INT32_MAX sets CONV. */
int32_t  imp_g2tau(const imp_params_t *p, uint64_t n, fx_status_t *st);
/* Commanded response of one burn [bs, be) of thruster j, clipped to [k1g, k2g), evaluated at teg
   (<= the window end), per unit alpha, into s->win (r_q28[j] and on_g[j]). */
void     imp_burn_response(imp_state_t *s, const imp_params_t *p, uint32_t j, uint64_t bs, uint64_t be, uint64_t k1g,
                           uint64_t k2g, uint64_t teg, fx_status_t *st);

/* ------------------------------------------------------------------ imp_log.c */
/* Append a commanded window [a_g, b_g) of thruster j (extends a contiguous segment). */
void     imp_log_add(imp_state_t *s, uint32_t j, uint64_t a_g, uint64_t b_g, uint64_t step_g);
/* Commanded response of the logged burns within [k1g, k2g), evaluated at teg, into s->win. */
void     imp_log_response(imp_state_t *s, const imp_params_t *p, uint64_t k1g, uint64_t k2g, uint64_t teg,
                          fx_status_t *st);
/* Reset the calibration to the table's thrust factors. */
void     imp_cal_reset(imp_state_t *s, const imp_params_t *p);
/* True when thruster j's level counts as calibrated (own window, or pooled). */
bool     imp_cal_done(const imp_state_t *s, const imp_params_t *p, uint32_t j);

/* ------------------------------------------------------------------ imp_tl.c */
/* Timeline of the solution in s->sol (rounded into s->rd) for the application epoch ta. */
void     imp_tl_make(imp_state_t *s, const imp_params_t *p, uint32_t ta, imp_timeline_t *tl, fx_status_t *st);
/* FINAL condition for a plan applied at ta (spec 50 §5.4). */
bool     imp_tl_final(const imp_state_t *s, const imp_params_t *p, uint32_t ta);
/* This step's valve windows from the timeline in force, interlock and availability last, into
   *out; records the commanded windows. Returns the health bits (INTERLOCK). */
uint32_t imp_tl_fire(imp_state_t *s, const imp_params_t *p, uint32_t k, uint32_t avail, imp_out_t *out);
/* Commanded response of timeline tl's burns within [k1g, k2g), evaluated at teg, into s->win. */
void     imp_tl_response(imp_state_t *s, const imp_params_t *p, const imp_timeline_t *tl, uint64_t k1g, uint64_t k2g,
                         uint64_t teg, fx_status_t *st);
/* EXPECTED_MISS (spec 50 §5.5): predicted uncorrectable miss of the timeline in force into the
   telemetry; returns IMP_H_EXPECTED_MISS when a |dR| exceeds miss_flag. */
uint32_t imp_tl_expected_miss(imp_state_t *s, const imp_params_t *p, fx_status_t *st);

/* ------------------------------------------------------------------ imp_nav.c */
/* Nav counts -> the module's sample; false when a count leaves the q28 range. */
bool     imp_nav_convert(const imp_params_t *p, const int32_t *pos_mm, const int32_t *vel_cnt, imp_nav_t *nv);
/* Modes in which the module has a mission: the nav gate and the monitor run. */
bool     imp_active(uint32_t mode);
/* A new sample: outlier gate (active modes), acceptance, monitor window. Returns IMP_EV_*. */
uint32_t imp_nav_intake(imp_state_t *s, const imp_params_t *p, const imp_in_t *in);
/* Accepted nav sample usable at step k: valid, not newer than k, at most nav_timeout old and
   inside the commanded-burn history. */
bool     imp_nav_fresh(const imp_state_t *s, const imp_params_t *p, uint32_t k);
/* Clear the window accumulators. */
void     imp_win_clear(imp_win_t *w);
/* Nav sample propagated to ta through the logged burns up to `now` and, from `now`, through
   the timeline in force when use_tl (spec 50 §5.4); result q28. */
void     imp_propagate(imp_state_t *s, const imp_params_t *p, const imp_nav_t *nv, uint32_t now, uint32_t ta,
                       bool use_tl, int32_t *x_q28, fx_status_t *st);
/* Predicted terminal cost |dR|^2 + w_v^2 |dV|^2 (q56, the rounding's metric) of keeping the
   timeline in force from the state s->prob.x0_q28 at ta. */
uint64_t imp_keep_cost(imp_state_t *s, const imp_params_t *p, uint32_t ta, fx_status_t *st);
/* Thrust-level calibration at a re-plan epoch (window from s->cal.ref to s->nav). Returns
   IMP_H_THRUST_LEVEL when the window was discarded by cal_gate. */
uint32_t imp_cal_epoch(imp_state_t *s, const imp_params_t *p);

#endif /* FSW_IMP_INT_H */
