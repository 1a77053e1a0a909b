/*
 * imp_tl.c — timeline of the impulse scheduler (spec 50-impulse §5.2, §5.4-5.6): from a rounded
 * solution to per-axis burns on the valve grid, the FINAL condition, the per-step on-windows with
 * the interlock and availability gates, the commanded response of a timeline (for the nav
 * propagation to t_a), and the expected-miss prediction.
 *
 * Grid positions are absolute uint64 counts of grid units (step * G + sub-tick), so no
 * arithmetic on them can overflow over any mission; differences fed to the trig kernels are
 * bounded by the horizon (<= 2 rad).
 */
#include "imp_int.h"

/* Bit j when b holds. */
static uint32_t flagbit(bool b, uint32_t j)
{
    return b ? (1u << j) : 0u;
}

void imp_tl_make(imp_state_t *s, const imp_params_t *p, uint32_t ta, imp_timeline_t *tl, fx_status_t *st)
{
    uint32_t r;
    uint32_t ntot = (s->tf_step - ta) * imp_grid(p);
    imp_round_best(&s->ws, p, &s->prob, &s->sol, ntot, &s->rd, st);
    tl->ta_step = ta;
    tl->ntot_g = ntot;
    tl->pattern = s->sol.pattern;
    for (r = 0u; r < IMP_NAX; r++) {
        uint32_t b1 = 2u * r;
        uint32_t b2 = b1 + 1u;
        tl->thr1[r] = (uint8_t)(b1 + (((uint32_t)s->sol.pattern >> b1) & 1u));
        tl->thr2[r] = (uint8_t)(b1 + (((uint32_t)s->sol.pattern >> b2) & 1u));
        tl->n1_g[r] = s->rd.n1[r];
        tl->n2_g[r] = s->rd.n2[r];
        tl->t1_q29[r] = s->sol.t1_q29[r];
        tl->t2_q29[r] = s->sol.t2_q29[r];
    }
    tl->valid = 1u;
}

bool imp_tl_final(const imp_state_t *s, const imp_params_t *p, uint32_t ta)
{
    uint64_t g = (uint64_t)imp_grid(p);
    uint64_t e2 = (uint64_t)s->tf_step * g;
    uint32_t r;
    for (r = 0u; r < IMP_NAX; r++) {
        uint64_t b = ((uint64_t)s->act.ta_step * g) + (uint64_t)s->act.n2_g[r];
        e2 = (b < e2) ? b : e2;
    }
    return (((uint64_t)ta * g) >= e2) || (((uint64_t)ta + (uint64_t)p->t_stop) > (uint64_t)s->tf_step);
}

/* Window of one burn [bs, be) inside the step [k0, k0 + g): into lo/hi of thruster j. Two
   windows of one thruster that do not touch are a violation (returns INTERLOCK). */
static uint32_t clip_burn(uint64_t bs, uint64_t be, uint64_t k0, uint32_t g, uint32_t j, uint32_t *lo, uint32_t *hi)
{
    uint64_t k1 = k0 + (uint64_t)g;
    uint64_t a = (bs > k0) ? bs : k0;
    uint64_t b = (be < k1) ? be : k1;
    uint32_t h = 0u;
    if (a < b) {
        uint32_t la = (uint32_t)(a - k0);
        uint32_t lb = (uint32_t)(b - k0);
        if (hi[j] == lo[j]) {
            lo[j] = la;
            hi[j] = lb;
        } else if (la == hi[j]) {
            hi[j] = lb;
        } else if (lb == lo[j]) {
            lo[j] = la;
        } else {
            h = IMP_H_INTERLOCK;
        }
    }
    return h;
}

uint32_t imp_tl_fire(imp_state_t *s, const imp_params_t *p, uint32_t k, uint32_t avail, imp_out_t *out)
{
    uint32_t g = imp_grid(p);
    uint32_t us = imp_grid_us(p);
    uint64_t k0 = (uint64_t)k * (uint64_t)g;
    uint64_t a0 = (uint64_t)s->act.ta_step * (uint64_t)g;
    uint32_t lo[IMP_NTHR] = {0u, 0u, 0u, 0u, 0u, 0u};
    uint32_t hi[IMP_NTHR] = {0u, 0u, 0u, 0u, 0u, 0u};
    uint32_t h = 0u;
    uint32_t mask = 0u;
    uint32_t r;
    uint32_t j;
    for (r = 0u; (r < IMP_NAX) && (s->act.valid != 0u); r++) {
        h |= clip_burn(a0, a0 + (uint64_t)s->act.n1_g[r], k0, g, s->act.thr1[r], lo, hi);
        h |= clip_burn(a0 + (uint64_t)s->act.n2_g[r], a0 + (uint64_t)s->act.ntot_g, k0, g, s->act.thr2[r], lo, hi);
    }
    for (j = 0u; j < IMP_NTHR; j++) {
        mask |= flagbit(hi[j] > lo[j], j);
    }
    for (r = 0u; r < IMP_NAX; r++) {
        if (((mask >> (2u * r)) & 3u) == 3u) {
            mask &= ~(3u << (2u * r));
            h |= IMP_H_INTERLOCK;
        }
    }
    mask &= avail;
    for (j = 0u; j < IMP_NTHR; j++) {
        if (((mask >> j) & 1u) != 0u) {
            out->on_start_cnt[j] = lo[j] * us;
            out->on_len_cnt[j] = (hi[j] - lo[j]) * us;
            s->on_tot_g[j] += (uint64_t)(hi[j] - lo[j]);
            imp_log_add(s, j, k0 + (uint64_t)lo[j], k0 + (uint64_t)hi[j], k0);
        }
    }
    out->on_mask = (uint8_t)mask;
    return h;
}


void imp_tl_response(imp_state_t *s, const imp_params_t *p, const imp_timeline_t *tl, uint64_t k1g, uint64_t k2g,
                     uint64_t teg, fx_status_t *st)
{
    uint64_t a0 = (uint64_t)tl->ta_step * (uint64_t)imp_grid(p);
    uint32_t r;
    for (r = 0u; (r < IMP_NAX) && (tl->valid != 0u); r++) {
        imp_burn_response(s, p, tl->thr1[r], a0, a0 + (uint64_t)tl->n1_g[r], k1g, k2g, teg, st);
        imp_burn_response(s, p, tl->thr2[r], a0 + (uint64_t)tl->n2_g[r], a0 + (uint64_t)tl->ntot_g, k1g, k2g, teg, st);
    }
}

/* The miss predicted from u_uncal is an alarm only when nothing can reduce it any more: while a
   calibration epoch is still due before the first second burn (the last point a re-plan can
   move the timeline), the level will be estimated there and the prediction uses u_cal. The
   rule raised EXPECTED_MISS at 0.1 s of every nominal calibrated run (predicting 27.9 m where
   calibration then delivers < 1 m), an alarm no operator should chase. If the epochs pass
   without a usable window (nav stale, burns below dv_cal_min) the prediction falls back to
   u_uncal before the first second burn starts, so the warning still comes in time. With
   calibration off it is final from the first plan (A4-5's "raised before the first second burn"). */
static bool cal_epoch_ahead(const imp_state_t *s, const imp_params_t *p)
{
    return (p->cal_enable != 0u) && (p->replan_period != 0u) && (s->mode != IMP_MODE_FINAL) &&
           (!imp_tl_final(s, p, s->next_tp + p->plan_lead));
}

uint32_t imp_tl_expected_miss(imp_state_t *s, const imp_params_t *p, fx_status_t *st)
{
    uint32_t h = 0u;
    uint32_t r;
    bool ahead = cal_epoch_ahead(s, p);
    for (r = 0u; r < IMP_NAX; r++) {
        s->tlm.exp_dr_q28[r] = 0;
        s->tlm.exp_dv_q28[r] = 0;
        if ((s->act.valid != 0u) && (s->act.n2_g[r] < s->act.ntot_g)) {
            uint32_t j = s->act.thr2[r];
            int32_t d = imp_g2tau(p, (uint64_t)(s->act.ntot_g - s->act.n2_g[r]), st);
            int32_t u = (ahead || imp_cal_done(s, p, j)) ? p->u_cal_q30 : p->u_uncal_q30;
            int32_t ua = fx_mul(u, IMP_ALPHA_Q, s->cal.alpha_q30[j], IMP_ALPHA_Q, IMP_ALPHA_Q, st);
            /* dV = u alpha d (q28), dR = dV d / 2 (q28: the product in q27 read as q28 halves it) */
            int32_t dv = fx_mul(ua, IMP_ALPHA_Q, d, IMP_T_Q, IMP_X_Q, st);
            int32_t dr = fx_mul(dv, IMP_X_Q, d, IMP_T_Q, IMP_X_Q - 1u, st);
            s->tlm.exp_dv_q28[r] = dv;
            s->tlm.exp_dr_q28[r] = dr;
            if (dr > p->miss_flag_q28) {
                h = IMP_H_EXPECTED_MISS;
            }
        }
    }
    return h;
}
