/*
 * imp_sched.c — best rounding of the switching times onto the valve grid (spec 50-impulse §5.3).
 *
 * The terminal error of a rounded schedule is the constant part of the residual,
 * c = Phi(tau_f) X0 - X_t + sum s1 a1 Psi_r(tau_f), plus one term per interior switch:
 * -s1 a1 Psi_r(tau_f - T1) for a first-burn end, +s2 a2 Psi_r(tau_f - T2) for a second-burn
 * start. Each of these is precomputed exactly (int64, q58) for the floor and the ceil grid
 * position, so a choice of candidates is scored by additions only and rounded once: 16 choices
 * for x-y, 4 for z.
 *
 * The grid is the step (subtick_us = 0) or the sub-tick. Minimum impulse bit: a candidate that
 * leaves a burn of length in (0, t_min) is replaced by its executable neighbour in the same
 * direction (floor -> the shorter executable length, ceil -> the longer: 0 or n_min grid units,
 * n_min = ceil(t_min / grid)). Coasts: with the same thruster on both burns, a coast shorter than
 * t_min, or one whose two edges fall into one step (two windows of one thruster in a step), is
 * merged (the two switch terms then cancel exactly: both are dropped); with opposite thrusters,
 * a coast whose edges fall into one step (both thrusters of an axis in one step) is widened: the
 * second burn starts at the next step boundary (its term is then computed for that position).
 * With whole steps and t_min <= period none of these rules can trigger.
 */
#include "imp.h"
#include "imp_int.h"

#define SH_ACC_TO_X   30u   /* q58 -> q28 */
#define NCH_CAP       16u   /* compile-time bound of the choices per subsystem */
#define SRC_C0        0u    /* the precomputed floor candidate */
#define SRC_C1        1u    /* the precomputed ceil candidate */
#define SRC_ZERO      2u    /* merged coast: no term */
#define SRC_X         3u    /* widened coast: ws->rx_q58[k] */

static uint64_t u64_add_sat(uint64_t a, uint64_t b)
{
    return (a > (UINT64_MAX - b)) ? UINT64_MAX : (a + b);
}

/* Rows of an axis's Psi. */
static uint32_t rnd_nrow(uint32_t r)
{
    return (r == 2u) ? 2u : 4u;
}

static uint32_t flag(bool b)
{
    return b ? 1u : 0u;
}

/* Shortest executable burn, grid units: ceil(t_min / grid). */
static uint32_t min_units(const imp_params_t *p)
{
    uint32_t u = imp_grid_us(p);
    return (u == 0u) ? 0u : ((p->t_min_us / u) + flag((p->t_min_us % u) != 0u));
}

/* Thruster of burn b (0 first, 1 second) of axis r under the 6-bit pattern. */
static uint32_t burn_thruster(uint32_t pattern, uint32_t r, uint32_t b)
{
    return (2u * r) + ((pattern >> ((2u * r) + b)) & 1u);
}

/* Signed thrust factor of burn b of axis r under the 6-bit pattern. */
static int32_t signed_alpha(const imp_problem_t *pr, uint32_t pattern, uint32_t r, uint32_t b, fx_status_t *st)
{
    uint32_t j = burn_thruster(pattern, r, b);
    int32_t a = pr->alpha_q30[j];
    return ((j & 1u) != 0u) ? fx_neg(a, st) : a;
}

/* floor(T * k_gtick) in grid units (T >= 0, a valid schedule), and whether nearest rounding is the
   ceil. */
static uint32_t floor_grid(const imp_params_t *p, int32_t t_q29, uint32_t n_total, uint32_t *near_ceil)
{
    uint64_t v = (uint64_t)fx_uabs(t_q29) * (uint64_t)fx_uabs(p->k_gtick_m);
    uint32_t sh = ((p->k_gtick_sh >= 1u) && (p->k_gtick_sh <= 62u)) ? (uint32_t)p->k_gtick_sh : 1u;
    uint64_t n = v >> sh;
    uint64_t half = (uint64_t)1u << (sh - 1u);
    uint64_t frac = v - (n << sh);
    *near_ceil = flag(frac >= half);
    return (n > (uint64_t)n_total) ? n_total : (uint32_t)n;
}

/* Minimum impulse bit (spec 50 §5.3): candidate v of switch b (0: end of the first burn, 1: start
   of the second), rounded up (ceil != 0) or down, snapped to its executable neighbour. */
static uint32_t snap(uint32_t v, uint32_t b, uint32_t ceil, uint32_t nmin, uint32_t n_total)
{
    uint32_t r = v;
    uint32_t m = (nmin > n_total) ? n_total : nmin;
    if (b == 0u) {
        if ((v > 0u) && (v < m)) {
            r = (ceil != 0u) ? m : 0u;
        }
    } else {
        uint32_t len = n_total - v;
        if ((len > 0u) && (len < m)) {
            r = (ceil != 0u) ? n_total : (n_total - m);
        }
    }
    return r;
}

/* Terminal contribution (q58) of burn b of axis r switching at grid position n into row[]. */
static void contribution(const imp_params_t *p, const imp_problem_t *pr, uint32_t pattern, uint32_t r,
                         uint32_t b, uint32_t n, uint32_t n_total, int64_t *row, fx_status_t *st)
{
    imp_trig_t t;
    int32_t v[4] = {0, 0, 0, 0};
    uint32_t i;
    uint32_t nrow = rnd_nrow(r);
    int32_t sa = signed_alpha(pr, pattern, r, b, st);
    int32_t coef = (b == 0u) ? fx_neg(sa, st) : sa;
    uint32_t dn = (n < n_total) ? (n_total - n) : 0u;
    int32_t sig = fx_rshift_sat((int64_t)dn * (int64_t)p->k_gtau_m, p->k_gtau_sh, st);
    imp_trig(sig, &t, st);
    imp_psi(r, sig, &t, v, st);
    for (i = 0u; i < 4u; i++) {
        row[i] = (i < nrow) ? ((int64_t)coef * (int64_t)v[i]) : 0;
    }
}

/* Constant part c of the residual of subsystem sub (q58) into ws->c_q58. */
static void base_residual(imp_ws_t *ws, const imp_problem_t *pr, uint32_t pattern, uint32_t sub, fx_status_t *st)
{
    uint32_t nax = imp_sub_nax(sub);
    uint32_t n = 2u * nax;
    uint32_t r0 = imp_sub_row0(sub);
    uint32_t i;
    uint32_t k;
    for (i = 0u; i < n; i++) {
        ws->c_q58[i] = ws->px_q58[r0 + i];
    }
    for (k = 0u; k < nax; k++) {
        uint32_t r = imp_sub_ax0(sub) + k;
        int32_t sa1 = signed_alpha(pr, pattern, r, 0u, st);
        for (i = 0u; i < n; i++) {
            ws->c_q58[i] = fx_add64_sat(ws->c_q58[i], (int64_t)sa1 * (int64_t)ws->psif_q28[r][i], st);
        }
    }
}

/* Term of local switch s under source src, row i. */
static int64_t term(const imp_ws_t *ws, uint32_t sub, uint32_t s, uint32_t src, uint32_t i)
{
    int64_t v = 0;
    uint32_t sw = (2u * imp_sub_ax0(sub)) + s;          /* global switch index 2r + b */
    if ((src == SRC_C0) || (src == SRC_C1)) {
        v = ws->rc_q58[(2u * sw) + src][i];
    } else if (src == SRC_X) {
        v = ws->rx_q58[s / 2u][i];
    } else {
        /* merged: no term */
    }
    return v;
}

/* Terminal error (q28) and cost (q56) of the resolved sources src[] of subsystem sub. */
static uint64_t score(const imp_ws_t *ws, const imp_params_t *p, uint32_t sub, const uint32_t *src, int32_t *f_q28,
                      fx_status_t *st)
{
    uint32_t n = 2u * imp_sub_nax(sub);
    uint32_t i;
    uint32_t s;
    uint64_t cost = 0u;
    for (i = 0u; i < n; i++) {
        int64_t acc = ws->c_q58[i];
        for (s = 0u; s < n; s++) {
            acc = fx_add64_sat(acc, term(ws, sub, s, src[s], i), st);
        }
        f_q28[i] = fx_rshift_sat(acc, SH_ACC_TO_X, st);
    }
    for (i = 0u; i < n; i++) {
        int32_t e = ((i & 1u) == 0u) ? f_q28[i] : fx_mul(f_q28[i], IMP_X_Q, p->w_v_q28, IMP_X_Q, IMP_X_Q, st);
        int64_t e2 = (int64_t)e * (int64_t)e;
        cost = u64_add_sat(cost, (uint64_t)e2);
    }
    return cost;
}

/* Coast rules of axis k (local) with burns [0, n1) and [n2, n_total); may change nv[s2], src[].
   Returns the fixed flag (1 when merged or widened). */
static uint32_t coast_fix(imp_ws_t *ws, const imp_params_t *p, const imp_problem_t *pr, uint32_t pattern,
                          uint32_t r, uint32_t k, uint32_t n_total, uint32_t *nv, uint32_t *src, fx_status_t *st)
{
    uint32_t s1 = 2u * k;
    uint32_t s2 = s1 + 1u;
    uint32_t n1 = nv[s1];
    uint32_t n2 = nv[s2];
    uint32_t fixed = 0u;
    if ((n1 > 0u) && (n2 < n_total)) {
        uint32_t g = imp_grid(p);
        bool share = ((n1 - 1u) / g) == (n2 / g);
        bool same = burn_thruster(pattern, r, 0u) == burn_thruster(pattern, r, 1u);
        uint32_t coast = n2 - n1;
        if (same && (coast > 0u) && ((coast < min_units(p)) || share)) {
            nv[s2] = n1;                               /* merged: the two terms cancel */
            src[s1] = SRC_ZERO;
            src[s2] = SRC_ZERO;
            fixed = 1u;
        } else if ((!same) && share) {
            uint32_t w = ((n1 + g) - 1u) / g * g;      /* next step boundary */
            if ((w >= n_total) || ((n_total - w) < min_units(p))) {
                w = n_total;
            }
            nv[s2] = w;
            src[s2] = SRC_X;
            contribution(p, pr, pattern, r, 1u, w, n_total, ws->rx_q58[k], st);
            fixed = 1u;
        } else {
            /* executable as it is */
        }
    }
    return fixed;
}

/* Grid positions and term sources of choice ch; returns false when the choice is not a valid
   schedule (n1 > n2 or n2 > n_total on some axis). */
static bool resolve(imp_ws_t *ws, const imp_params_t *p, const imp_problem_t *pr, uint32_t pattern, uint32_t sub,
                    uint32_t ch, uint32_t n_total, uint32_t *nv, uint32_t *src, uint32_t *fixed, fx_status_t *st)
{
    uint32_t nax = imp_sub_nax(sub);
    uint32_t k;
    bool ok = true;
    *fixed = 0u;
    for (k = 0u; k < (2u * nax); k++) {
        uint32_t sw = (2u * imp_sub_ax0(sub)) + k;
        src[k] = (ch >> k) & 1u;
        nv[k] = ws->rn[(2u * sw) + src[k]];
    }
    for (k = 0u; k < nax; k++) {
        uint32_t s1 = 2u * k;
        uint32_t n1 = nv[s1];
        uint32_t n2 = nv[s1 + 1u];
        if ((n1 > n2) || (n2 > n_total)) {
            ok = false;
        } else {
            *fixed |= coast_fix(ws, p, pr, pattern, imp_sub_ax0(sub) + k, k, n_total, nv, src, st) << k;
        }
    }
    return ok;
}

/* Candidates of every switch of subsystem sub: floor / ceil grid positions after the
   minimum-impulse rule, their precomputed terms, and the nearest-rounding choice. */
static uint32_t candidates(imp_ws_t *ws, const imp_params_t *p, const imp_problem_t *pr, const imp_solution_t *sol,
                           uint32_t sub, uint32_t n_total, fx_status_t *st)
{
    uint32_t nsw = 2u * imp_sub_nax(sub);
    uint32_t nmin = min_units(p);
    uint32_t near = 0u;
    uint32_t s;
    for (s = 0u; s < nsw; s++) {
        uint32_t r = imp_sub_ax0(sub) + (s / 2u);
        uint32_t b = s & 1u;
        uint32_t sw = (2u * r) + b;
        int32_t t = (b == 0u) ? sol->t1_q29[r] : sol->t2_q29[r];
        uint32_t nc = 0u;
        uint32_t nf = floor_grid(p, t, n_total, &nc);
        uint32_t c;
        near |= nc << s;
        for (c = 0u; c < 2u; c++) {
            uint32_t v = (c == 0u) ? nf : ((nf < n_total) ? (nf + 1u) : n_total);
            uint32_t row = (2u * sw) + c;
            ws->rn[row] = snap(v, b, c, nmin, n_total);
            contribution(p, pr, sol->pattern, r, b, ws->rn[row], n_total, ws->rc_q58[row], st);
        }
    }
    return near;
}

static void round_sub(imp_ws_t *ws, const imp_params_t *p, const imp_problem_t *pr, const imp_solution_t *sol,
                      uint32_t sub, uint32_t n_total, imp_round_t *rd, fx_status_t *st)
{
    uint32_t nax = imp_sub_nax(sub);
    uint32_t nsw = 2u * nax;
    uint32_t nch = 1u << nsw;
    uint32_t near = candidates(ws, p, pr, sol, sub, n_total, st);
    uint32_t best = 0u;
    uint64_t best_cost = UINT64_MAX;
    int32_t f[4] = {0, 0, 0, 0};
    uint32_t nv[4] = {0u, 0u, 0u, 0u};
    uint32_t src[4] = {0u, 0u, 0u, 0u};
    uint32_t fixed = 0u;
    uint32_t s;
    uint32_t ch;
    base_residual(ws, pr, sol->pattern, sub, st);
    for (ch = 0u; (ch < nch) && (ch < NCH_CAP); ch++) {
        if (resolve(ws, p, pr, sol->pattern, sub, ch, n_total, nv, src, &fixed, st)) {
            uint64_t c = score(ws, p, sub, src, f, st);
            if (c < best_cost) {
                best_cost = c;
                best = ch;
            }
            if (ch == near) {
                rd->cost_nearest_q56 = u64_add_sat(rd->cost_nearest_q56, c);
            }
        }
    }
    (void)resolve(ws, p, pr, sol->pattern, sub, best, n_total, nv, src, &fixed, st);
    rd->cost_q56 = u64_add_sat(rd->cost_q56, score(ws, p, sub, src, f, st));
    rd->choice[sub] = (uint8_t)best;
    rd->nearest[sub] = (uint8_t)near;
    rd->fixed[sub] = (uint8_t)fixed;
    for (s = 0u; s < nsw; s++) {
        rd->miss_q28[imp_sub_row0(sub) + s] = f[s];
    }
    for (s = 0u; s < nax; s++) {
        uint32_t r = imp_sub_ax0(sub) + s;
        uint32_t i1 = 2u * s;
        uint32_t i2 = i1 + 1u;
        rd->n2[r] = (nv[i2] > n_total) ? n_total : nv[i2];
        rd->n1[r] = (nv[i1] > rd->n2[r]) ? rd->n2[r] : nv[i1];
    }
}

void imp_round_best(imp_ws_t *ws, const imp_params_t *p, const imp_problem_t *pr, const imp_solution_t *sol,
                    uint32_t n_total, imp_round_t *rd, fx_status_t *st)
{
    uint32_t sub;
    rd->cost_q56 = 0u;
    rd->cost_nearest_q56 = 0u;
    for (sub = 0u; sub < IMP_NSUB; sub++) {
        round_sub(ws, p, pr, sol, sub, n_total, rd, st);
    }
}
