/*
 * rly_int.h — internal interface between the parts of the relay module (not its API). Calls go
 * downward only: rly.c (contract, law, envelope copy, windows) -> rly_adapt.c (k_t adaptation).
 */
#ifndef FSW_RLY_INT_H
#define FSW_RLY_INT_H

#include "rly.h"

/* The adaptation state for a new run (generator seeded and warmed up, k_t = kt0). */
void     rly_adapt_init(rly_adapt_t *a, const rly_params_t *p);
/* The decision at the end of a window: w->s, w->j, w->n_invalid and w->kt_in_q16 set by the
   caller; valid false skips the window with no state change. Fills the rest of *w, returns the
   k_t for the next window and RLY_H_* bits (KT_CLAMPED). */
uint16_t rly_adapt_window(rly_adapt_t *a, const rly_params_t *p, bool valid, rly_win_t *w, uint32_t *h);
/* k_t held inside [kt_min, kt_max]; *h |= KT_CLAMPED when it moved. */
uint16_t rly_kt_clamp(int32_t kt, const rly_params_t *p, uint32_t *h);

#endif /* FSW_RLY_INT_H */
