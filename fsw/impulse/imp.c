/*
 * imp.c — impulse scheduler module (spec 50-impulse §5, §8), platform contract (spec 00 §3.1):
 * parameter checks, init, and the step: navigation intake (imp_nav.c), executive commands (START
 * checks, ABORT, CLEAR_FAULTS), the resumable plan job (START plan and re-plans, at most
 * plan_iter_per_step work units per step, late / failed bookkeeping), re-plan epochs with the
 * thrust-level calibration, the stuck-valve reactions, FINAL, the timeline in force (imp_tl.c),
 * health and telemetry.
 *
 * Step order: outputs off; nav intake (gate, monitor); command; monitor reaction; plan job
 * (late check, epoch, run, commit at t_a); DONE at t_f; valve windows (FIRING, FINAL only);
 * health and telemetry. Every path ends with defined outputs.
 */
#include "imp_int.h"

#define ALPHA_MIN_Q30  INT32_C(858993459)        /* 0.8 */
#define ALPHA_MAX_Q30  INT32_C(1288490189)       /* 1.2 */
#define TAU_LO_Q29     INT32_C(107374182)        /* 0.2 rad */
#define TAU_HI_Q29     INT32_C(1073741824)       /* 2.0 rad */
#define SCALE_ONE_SH   60u                       /* k_tau * k_tick = 2^60 (= 1) */
#define SCALE_TOL_SH   32u                       /* within 2^(60 - 28): relative 2^-28 */
#define PERIOD_MAX_US  10000000u                 /* 10 s */
#define FD_SPAN_MAX_US UINT64_C(60000000)        /* fd_window <= 60 s (monitor formats) */
#define DEC7           UINT64_C(10000000)        /* 10^7 */
#define DEC8           UINT64_C(100000000)       /* 10^8 */
#define DEC15          UINT64_C(1000000000000000) /* 10^15 */
#define REL_TOL_SH     20u                       /* scale constants agree within 2^-20 */
#define GRID_TOL_SH    26u                       /* grid vs step constant within 2^-26 */
#define NORM_MAX_IT    64u
#define STUCK_NONE     0xFFu
#define U16_MAX        0xFFFFu

#define JOBK_NONE      0u
#define JOBK_START     1u
#define JOBK_REPLAN    2u
#define JOBK_STUCK     3u                        /* immediate re-plan avoiding a stuck-off thruster */

FX_STATIC_ASSERT(imp_sa_one28, FX_Q_RAT_FITS(1, 1, 28));
FX_STATIC_ASSERT(imp_sa_one30, FX_Q_RAT_FITS(1, 1, 30));
FX_STATIC_ASSERT(imp_sa_half30, FX_Q_RAT_FITS(1, 2, 30));

static bool in_range(int32_t v, int32_t lo, int32_t hi)
{
    return (v >= lo) && (v <= hi);
}

/* ------------------------------------------------------------------ parameter checks */

/* a * 2^ea for a product of two unsigned values, each first reduced below 2^32. */
static uint64_t mulx(uint64_t a, uint64_t b, int32_t *e)
{
    uint64_t x = a;
    uint64_t y = b;
    uint32_t i;
    for (i = 0u; (i < NORM_MAX_IT) && (x >= (UINT64_C(1) << 32u)); i++) {
        x >>= 1u;
        (*e)++;
    }
    for (i = 0u; (i < NORM_MAX_IT) && (y >= (UINT64_C(1) << 32u)); i++) {
        y >>= 1u;
        (*e)++;
    }
    return x * y;
}

/* Normalise m * 2^e so that m lies in [2^62, 2^63) (m > 0). */
static uint64_t norm62(uint64_t m, int32_t *e)
{
    uint64_t x = m;
    uint32_t i;
    for (i = 0u; (i < NORM_MAX_IT) && (x != 0u) && ((x >> 62u) == 0u); i++) {
        x <<= 1u;
        (*e)--;
    }
    for (i = 0u; (i < NORM_MAX_IT) && ((x >> 63u) != 0u); i++) {
        x >>= 1u;
        (*e)++;
    }
    return x;
}

/* a 2^ea == b 2^eb within a relative 2^-tol_sh (a, b > 0). */
static bool rel_close(uint64_t a, int32_t ea, uint64_t b, int32_t eb, uint32_t tol_sh)
{
    int32_t xa = ea;
    int32_t xb = eb;
    uint64_t ma = norm62(a, &xa);
    uint64_t mb = norm62(b, &xb);
    bool ok = (ma != 0u) && (mb != 0u);
    if (ok && (xa == (xb + 1))) {
        mb >>= 1u;
    } else if (ok && (xb == (xa + 1))) {
        ma >>= 1u;
    } else if (xa != xb) {
        ok = false;
    } else {
        /* same exponent */
    }
    if (ok) {
        uint64_t d = (ma > mb) ? (ma - mb) : (mb - ma);
        uint64_t mx = (ma > mb) ? ma : mb;
        ok = d <= (mx >> tol_sh);
    }
    return ok;
}

/* k_m * k2_m = 2^60 within 2^-28 (a reciprocal pair), shifts summing to 60. */
static bool recip_pair(int32_t m1, uint32_t sh1, int32_t m2, uint32_t sh2)
{
    bool ok = (m1 > 0) && (m2 > 0) && ((sh1 + sh2) == SCALE_ONE_SH);
    if (ok) {
        uint64_t prod = (uint64_t)(uint32_t)m1 * (uint64_t)(uint32_t)m2;
        uint64_t one = UINT64_C(1) << SCALE_ONE_SH;
        uint64_t diff = (prod > one) ? (prod - one) : (one - prod);
        ok = (diff >> SCALE_TOL_SH) == 0u;
    }
    return ok;
}

static uint32_t check_timing(const imp_params_t *p)
{
    uint32_t w = 0u;
    uint32_t pips = (uint32_t)p->plan_iter_per_step;
    if ((p->period_us == 0u) || (p->period_us > PERIOD_MAX_US) || (p->t_min_us > p->period_us) ||
        (p->k_tick_sh < 1u) || (p->w_v_q28 <= 0)) {
        w |= IMP_WHY_PERIOD;
    }
    if ((p->replan_period != 0u) && ((p->replan_period <= p->plan_lead) || (p->nav_timeout > p->replan_period))) {
        w |= IMP_WHY_ITER;
    }
    if (!in_range(p->replan_gain_q30, 0, FX_Q_INT(1, 30) - 1)) {
        w |= IMP_WHY_ITER;
    }
    if ((p->max_iter == 0u) || (p->max_iter > IMP_ITER_CAP) || (pips < IMP_ROUND_UNITS)) {
        w |= IMP_WHY_ITER;
    } else {
        /* the worst plan must end before its t_a: spec 50 §4.7 (240 iterations), and this
           implementation's own bound (one extra step for the rounding) */
        uint32_t units = IMP_JOB_UNITS(p->max_iter) + IMP_ROUND_UNITS;
        uint32_t need = ((units + pips) - 1u) / pips;
        uint32_t spec = ((IMP_PLAN_WORST_ITER + pips) - 1u) / pips;
        need += 1u;
        if ((p->plan_lead < need) || (p->plan_lead < spec)) {
            w |= IMP_WHY_LEAD;
        }
    }
    return w;
}

static uint32_t check_solver(const imp_params_t *p)
{
    uint32_t w = 0u;
    uint32_t i;
    if ((p->r_tol_lsb < 1) || (p->pivot_min_q26 < 1) || (p->pivot_ratio_sh > 30u) || (p->dv_tie_q28 < 0)) {
        w |= IMP_WHY_TOL;
    }
    if ((p->rho_warn_q28 <= 0) || (p->rho_warn_q28 > p->rho_reject_q28) || (p->rho_reject_q28 > FX_Q_INT(1, 28))) {
        w |= IMP_WHY_RHO;
    }
    for (i = 0u; i < IMP_NTHR; i++) {
        if (!in_range(p->alpha_q30[i], ALPHA_MIN_Q30, ALPHA_MAX_Q30)) {
            w |= IMP_WHY_ALPHA;
        }
    }
    if ((p->tauf_min_q29 < TAU_LO_Q29) || (p->tauf_max_q29 > TAU_HI_Q29) || (p->tauf_min_q29 > p->tauf_max_q29)) {
        w |= IMP_WHY_TAU;
    }
    return w;
}

/* Scale constants: reciprocal pairs, and counts / tick / informative w, a_nom consistent. */
static uint32_t check_scale_consts(const imp_params_t *p)
{
    uint32_t w = 0u;
    if ((p->k_pos_m <= 0) || (p->k_vel_m <= 0) || (p->k_pos_sh > 62u) || (p->k_vel_sh > 62u) ||
        (p->omega_nradps == 0u) || (p->a_nom_umps2 == 0u) || (p->period_us == 0u) ||
        (!recip_pair(p->k_tau_m, p->k_tau_sh, p->k_tick_m, p->k_tick_sh))) {
        w |= IMP_WHY_SCALE;
    } else {
        int32_t ea = 29 - (int32_t)p->k_pos_sh;
        int32_t eb = -(int32_t)p->k_vel_sh - (int32_t)p->k_tau_sh;
        int32_t ec = 0;
        int32_t ed = (int32_t)p->k_tau_sh + 29;
        int32_t ee = -(int32_t)p->k_vel_sh;
        int32_t ef = -(int32_t)p->k_tau_sh - 1;
        /* k_pos / k_vel = 100 w = 100 k_tau / (2^29 h) */
        uint64_t a = mulx((uint64_t)(uint32_t)p->k_pos_m, (uint64_t)p->period_us, &ea);
        uint64_t b = mulx(mulx((uint64_t)(uint32_t)p->k_vel_m, DEC8, &eb), (uint64_t)(uint32_t)p->k_tau_m, &eb);
        /* k_tau = w h (informative w) */
        uint64_t c = mulx((uint64_t)(uint32_t)p->k_tau_m, DEC15, &ec);
        uint64_t d = mulx((uint64_t)p->omega_nradps, (uint64_t)p->period_us, &ed);
        /* k_vel = 10 um/s * w / a_nom (informative a_nom) */
        uint64_t e = mulx(mulx((uint64_t)(uint32_t)p->k_vel_m, (uint64_t)p->a_nom_umps2, &ee), (uint64_t)p->period_us, &ee);
        uint64_t f = mulx((uint64_t)(uint32_t)p->k_tau_m, DEC7, &ef);
        if ((!rel_close(a, ea, b, eb, REL_TOL_SH)) || (!rel_close(c, ec, d, ed, REL_TOL_SH)) ||
            (!rel_close(e, ee, f, ef, REL_TOL_SH))) {
            w |= IMP_WHY_SCALE;
        }
    }
    return w;
}

/* Valve grid: sub-tick divides the period, at most IMP_G_MAX per step; grid constants a
   reciprocal pair and G k_gtau = k_tau. */
static uint32_t check_grid(const imp_params_t *p)
{
    uint32_t w = 0u;
    uint32_t g = 1u;
    if (p->subtick_us != 0u) {
        if ((p->subtick_us > p->period_us) || ((p->period_us % p->subtick_us) != 0u) ||
            ((p->period_us / p->subtick_us) > IMP_G_MAX)) {
            w |= IMP_WHY_GRID;
        } else {
            g = p->period_us / p->subtick_us;
        }
    }
    if ((w == 0u) && ((!recip_pair(p->k_gtau_m, p->k_gtau_sh, p->k_gtick_m, p->k_gtick_sh)) || (p->k_tau_m <= 0))) {
        w |= IMP_WHY_GRID;
    }
    if (w == 0u) {
        int32_t ea = -(int32_t)p->k_gtau_sh;
        int32_t eb = -(int32_t)p->k_tau_sh;
        uint64_t a = mulx((uint64_t)(uint32_t)p->k_gtau_m, (uint64_t)g, &ea);
        if (!rel_close(a, ea, (uint64_t)(uint32_t)p->k_tau_m, eb, GRID_TOL_SH)) {
            w |= IMP_WHY_GRID;
        }
    }
    return w;
}

static uint32_t check_cal_fd_nav(const imp_params_t *p)
{
    uint32_t w = 0u;
    if ((p->cal_enable > 1u) || (p->cal_pool > 1u) || (!in_range(p->dv_cal_min_q28, 0, FX_Q_INT(1, 28))) ||
        (!in_range(p->cal_gate_q30, 1, FX_Q_RAT(1, 2, 30))) || (!in_range(p->u_uncal_q30, 0, FX_Q_RAT(1, 2, 30))) ||
        (!in_range(p->u_cal_q30, 0, p->u_uncal_q30)) || (p->miss_flag_q28 <= 0)) {
        w |= IMP_WHY_CAL;
    }
    if ((p->fd_window == 0u) || (((uint64_t)p->fd_window * (uint64_t)p->period_us) > FD_SPAN_MAX_US) ||
        (!in_range(p->fd_frac_q30, 1, FX_Q_INT(1, 30) - 1)) || (p->fd_persist == 0u)) {
        w |= IMP_WHY_FD;
    }
    if ((p->nav_timeout == 0u) || (p->nav_gate_pos_q28 <= 0) || (p->nav_gate_vel_q28 <= 0) ||
        (p->nav_gate_acc_q28 < 0)) {
        w |= IMP_WHY_NAV;
    }
    return w;
}

fsw_rc_t imp_params_check(const imp_params_t *p, uint32_t *why)
{
    uint32_t w = check_timing(p) | check_solver(p) | check_scale_consts(p) | check_grid(p) | check_cal_fd_nav(p);
    fsw_rc_t rc = FSW_OK;
    if ((w & ~IMP_WHY_INVARIANTS) != 0u) {
        rc = FSW_ERR_RANGE;
    } else if (w != 0u) {
        rc = FSW_ERR_INVARIANT;
    } else {
        /* valid */
    }
    *why = w;
    return rc;
}

/* ------------------------------------------------------------------ init */

static void outputs_off(imp_out_t *out)
{
    uint32_t j;
    out->on_mask = 0u;
    for (j = 0u; j < IMP_NTHR; j++) {
        out->on_start_cnt[j] = 0u;
        out->on_len_cnt[j] = 0u;
    }
}

fsw_rc_t imp_init(imp_state_t *s, const imp_params_t *p, imp_out_t *out)
{
    uint32_t i;
    /* Zero the whole state: a byte loop keeps it free of memset and of struct copies. */
    uint8_t *b = (uint8_t *)s;
    for (i = 0u; i < (uint32_t)sizeof(imp_state_t); i++) {
        b[i] = 0u;
    }
    s->mode = IMP_MODE_IDLE;
    s->tlm.revision = p->revision;
    s->tlm.stuck_j = STUCK_NONE;
    s->tlm.nav_age = UINT32_MAX;
    imp_cal_reset(s, p);
    outputs_off(out);
    out->health = (uint32_t)IMP_MODE_IDLE << IMP_H_MODE_SH;
    out->tlm = s->tlm;
    return FSW_OK;
}

/* ------------------------------------------------------------------ plan job */

static void job_cancel(imp_state_t *s)
{
    s->job_kind = JOBK_NONE;
    s->job_solved = 0u;
    s->pend.valid = 0u;
}

static void job_begin(imp_state_t *s, uint32_t kind, uint32_t now, uint32_t ta)
{
    imp_solve_begin(&s->ws, &s->sol);
    s->job_kind = (uint8_t)kind;
    s->job_solved = 0u;
    s->job_ta = ta;
    s->job_t_start = now;
    fx_cnt_inc(&s->tlm.plans);
}

static uint32_t thr_off(const imp_state_t *s, const imp_in_t *in)
{
    return (~((uint32_t)in->avail_mask & ~(uint32_t)s->fd.stuck_off)) & IMP_THR_ALL;
}

/* Re-plan job at `now` for the application epoch ta (spec 50 §5.4): the latest accepted nav
   sample propagated to ta through the commanded burns and the timeline in force; warm start with
   the active polarities, T1' = max(T1 - D, 0), T2' = T2 - D. */
static void start_replan(imp_state_t *s, const imp_params_t *p, const imp_in_t *in, uint32_t kind, uint32_t ta,
                         fx_status_t *st)
{
    fx_status_t cst = 0u;
    uint32_t g = imp_grid(p);
    int32_t shift;
    uint32_t r;
    uint32_t j;
    imp_propagate(s, p, &s->nav, in->step, ta, true, s->prob.x0_q28, &cst);
    s->keep_cost_q56 = UINT64_MAX;                 /* a stuck-off re-plan always replaces */
    if (kind == JOBK_REPLAN) {
        fx_status_t kst = 0u;
        uint64_t kc = imp_keep_cost(s, p, ta, &kst);
        s->keep_cost_q56 = (kst == 0u) ? kc : UINT64_MAX;
    }
    s->prob.tauf_q29 = imp_g2tau(p, (uint64_t)(s->tf_step - ta) * (uint64_t)g, &cst);
    shift = imp_g2tau(p, (uint64_t)(ta - s->act.ta_step) * (uint64_t)g, &cst);
    s->prob.warm_mask = 3u;
    s->prob.replan = 1u;
    s->prob.warm_pattern = s->act.pattern;
    s->prob.thr_off = (uint8_t)thr_off(s, in);
    for (r = 0u; r < IMP_NAX; r++) {
        int32_t t1 = fx_sub_sat(s->act.t1_q29[r], shift, &cst);
        s->prob.warm_t1_q29[r] = (t1 < 0) ? 0 : t1;
        s->prob.warm_t2_q29[r] = fx_sub_sat(s->act.t2_q29[r], shift, &cst);
    }
    for (j = 0u; j < IMP_NTHR; j++) {
        s->prob.alpha_q30[j] = s->cal.alpha_q30[j];
    }
    job_begin(s, kind, in->step, ta);
    if (cst != 0u) {
        fx_cnt_inc(&s->tlm.plans_failed);
        *st |= cst;
        s->job_kind = JOBK_NONE;
        if (kind == JOBK_STUCK) {
            s->mode = IMP_MODE_ABORTED;
        }
    }
}

/* (1 - gain) * cost for gain in [0, 1) (q30), without overflow: cost - cost * gain. */
static uint64_t keep_threshold(uint64_t cost, int32_t gain_q30)
{
    uint64_t f = (gain_q30 > 0) ? (uint64_t)(uint32_t)gain_q30 : 0u;
    uint64_t hi = (cost >> 30u) * f;
    uint64_t lo = ((cost & ((UINT64_C(1) << 30u) - 1u)) * f) >> 30u;
    return cost - (hi + lo);
}

/* The finished job's outcome: timeline (rounded now), mode, counters. */
static void job_finish(imp_state_t *s, const imp_params_t *p, uint32_t now, fx_status_t *st)
{
    uint32_t k;
    uint32_t steps = (now - s->job_t_start) + 1u;
    *st |= s->sol.st_ok;
    for (k = 0u; k < IMP_FAIL_N; k++) {
        s->tlm.n_fail[k] += (uint32_t)s->sol.n_fail[k];
    }
    s->tlm.plan_units = s->ws.job.units;
    s->tlm.plan_steps = (uint16_t)((steps > U16_MAX) ? U16_MAX : steps);
    if (s->sol.outcome == IMP_SOL_VALID) {
        s->tlm.plan_units = (uint16_t)(s->tlm.plan_units + IMP_ROUND_UNITS);
        if (s->job_kind == JOBK_START) {
            imp_tl_make(s, p, s->job_ta, &s->act, st);
            s->pend.valid = 0u;
            s->next_tp = s->t0_step + p->replan_period;
            s->marginal = s->sol.marginal;
            s->mode = IMP_MODE_ARMED;
        } else {
            imp_tl_make(s, p, s->job_ta, &s->pend, st);
            if ((s->job_kind == JOBK_REPLAN) && (s->rd.cost_q56 > keep_threshold(s->keep_cost_q56, p->replan_gain_q30))) {
                s->pend.valid = 0u;          /* no gain over the timeline in force: keep it */
                fx_cnt_inc(&s->tlm.plans_kept);
            }
        }
    } else {
        fx_cnt_inc(&s->tlm.plans_failed);
        if (s->job_kind == JOBK_START) {
            s->mode = (s->sol.outcome == IMP_SOL_INFEASIBLE) ? IMP_MODE_INFEASIBLE : IMP_MODE_NO_SOLUTION;
        } else if (s->job_kind == JOBK_STUCK) {
            s->mode = IMP_MODE_ABORTED;     /* no pattern avoids the stuck-off thruster */
        } else {
            /* re-plan failed: the timeline in force stays */
        }
    }
    s->job_kind = JOBK_NONE;
}

/* At most plan_iter_per_step work units of the running job this step. */
static void job_run(imp_state_t *s, const imp_params_t *p, uint32_t now, fx_status_t *st)
{
    uint32_t budget = (uint32_t)p->plan_iter_per_step;
    if (s->job_solved == 0u) {
        budget -= imp_solve_run(&s->ws, p, &s->prob, &s->sol, budget);
        s->job_solved = imp_solve_done(&s->ws) ? 1u : 0u;
    }
    if ((s->job_solved != 0u) && ((budget >= IMP_ROUND_UNITS) || (s->sol.outcome != IMP_SOL_VALID))) {
        job_finish(s, p, now, st);
    }
}

/* A job still running at its application epoch is late: the old timeline stays (START: no
   timeline, NO_SOLUTION; stuck-off re-plan: ABORTED). */
static void job_late(imp_state_t *s)
{
    fx_cnt_inc(&s->tlm.plans_late);
    if (s->job_kind == JOBK_START) {
        s->mode = IMP_MODE_NO_SOLUTION;
    } else if (s->job_kind == JOBK_STUCK) {
        s->mode = IMP_MODE_ABORTED;
    } else {
        /* the timeline in force stays */
    }
    job_cancel(s);
}

/* ------------------------------------------------------------------ START */

static uint32_t start_checks(const imp_state_t *s, const imp_params_t *p, const imp_in_t *in, int32_t *tauf)
{
    uint32_t why = IMP_REJ_NONE;
    fx_status_t cst = 0u;
    if ((in->step > (UINT32_MAX - p->plan_lead)) || (in->cmd_tf_step <= in->cmd_t0_step) ||
        (in->cmd_t0_step < (in->step + p->plan_lead))) {
        why = IMP_REJ_TIME;
    } else {
        *tauf = imp_g2tau(p, (uint64_t)(in->cmd_tf_step - in->cmd_t0_step) * (uint64_t)imp_grid(p), &cst);
        if ((cst != 0u) || (!in_range(*tauf, p->tauf_min_q29, p->tauf_max_q29))) {
            why = IMP_REJ_TAU;
        } else if ((!imp_nav_fresh(s, p, in->step)) || (s->nav.step > in->cmd_t0_step)) {
            why = IMP_REJ_NO_NAV;
        } else {
            /* accepted so far */
        }
    }
    return why;
}

/* Mission state of a new START. */
static void start_reset(imp_state_t *s, const imp_params_t *p, const imp_in_t *in)
{
    uint32_t j;
    s->t0_step = in->cmd_t0_step;
    s->tf_step = in->cmd_tf_step;
    s->act.valid = 0u;
    s->pend.valid = 0u;
    s->retry = 0u;
    s->marginal = 0u;
    imp_cal_reset(s, p);
    s->cal.ref = s->nav;
    s->fd.x0 = s->nav;
    for (j = 0u; j < IMP_NTHR; j++) {
        s->fd.cnt_off[j] = 0u;
        s->fd.cnt_on[j] = 0u;
        s->on_tot_g[j] = 0u;
    }
}

/* START: checks, problem (the nav sample drifted to t0 through any commanded burns), job. */
static uint32_t start(imp_state_t *s, const imp_params_t *p, const imp_in_t *in)
{
    int32_t tauf = 0;
    uint32_t why = start_checks(s, p, in, &tauf);
    if (why == IMP_REJ_NONE) {
        fx_status_t cst = 0u;
        imp_nav_t tgt;
        bool ok = imp_nav_convert(p, in->cmd_tgt_pos_mm, in->cmd_tgt_vel_cnt, &tgt);
        imp_propagate(s, p, &s->nav, in->step, in->cmd_t0_step, false, s->prob.x0_q28, &cst);
        if ((!ok) || (cst != 0u)) {
            why = IMP_REJ_TARGET;
        } else {
            uint32_t j;
            start_reset(s, p, in);
            for (j = 0u; j < IMP_NX; j++) {
                s->prob.xt_q28[j] = tgt.x_q28[j];
            }
            s->prob.tauf_q29 = tauf;
            s->prob.warm_mask = 0u;
            s->prob.replan = 0u;
            s->prob.warm_pattern = 0u;
            s->prob.thr_off = (uint8_t)thr_off(s, in);
            for (j = 0u; j < IMP_NTHR; j++) {
                s->prob.alpha_q30[j] = s->cal.alpha_q30[j];
            }
            job_begin(s, JOBK_START, in->step, in->cmd_t0_step);
            s->mode = IMP_MODE_PLANNING;
        }
    }
    return why;
}

static bool terminal(uint32_t mode)
{
    return (mode == IMP_MODE_IDLE) || (mode == IMP_MODE_DONE) || (mode == IMP_MODE_INFEASIBLE) ||
           (mode == IMP_MODE_NO_SOLUTION) || (mode == IMP_MODE_ABORTED) || (mode == IMP_MODE_FAULT);
}

static void clear_faults(imp_state_t *s)
{
    uint32_t j;
    s->mode = IMP_MODE_IDLE;
    s->latched &= ~(IMP_H_STUCK_OFF | IMP_H_STUCK_ON | IMP_H_THRUST_LEVEL);
    s->fd.stuck_off = 0u;
    s->tlm.stuck_j = STUCK_NONE;
    s->tlm.health_sticky = 0u;
    s->tlm.st_sticky = 0u;
    for (j = 0u; j < IMP_NTHR; j++) {
        s->fd.cnt_off[j] = 0u;
        s->fd.cnt_on[j] = 0u;
    }
}

/* Executive command; returns IMP_H_CMD_REJ when refused (reason in telemetry). */
static uint32_t exec_command(imp_state_t *s, const imp_params_t *p, const imp_in_t *in)
{
    uint32_t why = IMP_REJ_NONE;
    if (in->cmd == IMP_CMD_ABORT) {
        s->mode = IMP_MODE_ABORTED;
        job_cancel(s);
    } else if (in->cmd == IMP_CMD_CLEAR_FAULTS) {
        if (terminal(s->mode)) {
            clear_faults(s);
        }
    } else if ((in->cmd == IMP_CMD_START) && terminal(s->mode)) {
        why = start(s, p, in);
    } else if (in->cmd != IMP_CMD_NONE) {
        why = IMP_REJ_MODE;
    } else {
        /* no command */
    }
    if (why != IMP_REJ_NONE) {
        fx_cnt_inc(&s->tlm.cmd_rej);
        s->tlm.rej_reason = (uint8_t)why;
    }
    return (why != IMP_REJ_NONE) ? IMP_H_CMD_REJ : 0u;
}

/* ------------------------------------------------------------------ monitor reaction */

/* STUCK_ON: all off, ABORTED. STUCK_OFF: j unavailable, immediate re-plan avoiding it (FIRING);
   in FINAL (no re-plan possible) or without a fresh sample, ABORTED. */
static void fd_react(imp_state_t *s, const imp_params_t *p, const imp_in_t *in, uint32_t ev, fx_status_t *st)
{
    uint32_t j = ev & IMP_EV_THR_MASK;
    uint32_t kind = ev & IMP_EV_KIND_MASK;
    if ((kind != IMP_EV_NONE) && (j < IMP_NTHR) && imp_active(s->mode)) {
        s->tlm.stuck_j = (uint8_t)j;
        if (kind == IMP_EV_STUCK_ON) {
            s->latched |= 1u << (IMP_H_STUCK_ON_SH + (j / 2u));
            s->mode = IMP_MODE_ABORTED;
            job_cancel(s);
        } else {
            uint32_t ta = in->step + p->plan_lead;
            s->latched |= 1u << (IMP_H_STUCK_OFF_SH + (j / 2u));
            s->fd.stuck_off = (uint8_t)((uint32_t)s->fd.stuck_off | (1u << j));
            job_cancel(s);
            if ((s->mode == IMP_MODE_FIRING) && (!imp_tl_final(s, p, ta)) && imp_nav_fresh(s, p, in->step)) {
                start_replan(s, p, in, JOBK_STUCK, ta, st);
            } else {
                s->mode = IMP_MODE_ABORTED;
            }
        }
    }
}

/* ------------------------------------------------------------------ re-plan epochs */

/* Re-plan epoch at `now` (regular, or the retry of a skipped one): FINAL when t_a reaches a
   second burn or t_f - t_stop; busy or stale navigation skips it (counted; stale: NAV_STALE via
   the nav age, retried at the next fresh sample, calibration paused); else calibrate (regular
   epochs after the first) and start the re-plan job. */
static void epoch(imp_state_t *s, const imp_params_t *p, const imp_in_t *in, bool regular, fx_status_t *st)
{
    uint32_t ta = in->step + p->plan_lead;
    if (imp_tl_final(s, p, ta)) {
        s->mode = IMP_MODE_FINAL;
        s->retry = 0u;
    } else if ((s->job_kind != JOBK_NONE) || (s->pend.valid != 0u)) {
        fx_cnt_inc(&s->tlm.plans_skipped);
    } else if (!imp_nav_fresh(s, p, in->step)) {
        if (regular) {
            fx_cnt_inc(&s->tlm.plans_skipped);
        }
        s->retry = 1u;
        s->cal.ref.valid = 0u;
    } else {
        s->retry = 0u;
        if (regular && (p->cal_enable != 0u)) {
            s->latched |= imp_cal_epoch(s, p);
        }
        s->cal.ref = s->nav;
        start_replan(s, p, in, JOBK_REPLAN, ta, st);
    }
}

static void firing_epochs(imp_state_t *s, const imp_params_t *p, const imp_in_t *in, fx_status_t *st)
{
    if ((p->replan_period != 0u) && (in->step >= s->next_tp)) {
        s->next_tp += p->replan_period;
        if (s->next_tp <= in->step) {
            s->next_tp = in->step + p->replan_period;   /* steps were skipped by the caller */
        }
        epoch(s, p, in, true, st);
    } else if ((s->retry != 0u) && imp_nav_fresh(s, p, in->step)) {
        epoch(s, p, in, false, st);
    } else {
        /* nothing due */
    }
}

/* Plan job, epochs, commit, DONE. */
static void progress(imp_state_t *s, const imp_params_t *p, const imp_in_t *in, fx_status_t *st)
{
    if ((s->job_kind != JOBK_NONE) && (in->step >= s->job_ta)) {
        job_late(s);
    }
    if ((s->mode == IMP_MODE_ARMED) && (in->step >= s->t0_step)) {
        s->mode = IMP_MODE_FIRING;
    }
    if (s->mode == IMP_MODE_FIRING) {
        firing_epochs(s, p, in, st);
    }
    if ((s->job_kind != JOBK_NONE) && imp_active(s->mode)) {
        job_run(s, p, in->step, st);
    }
    if ((s->pend.valid != 0u) && (in->step >= s->pend.ta_step)) {
        s->act = s->pend;
        s->pend.valid = 0u;
    }
    if (((s->mode == IMP_MODE_FIRING) || (s->mode == IMP_MODE_FINAL)) && (in->step >= s->tf_step)) {
        s->mode = IMP_MODE_DONE;
        job_cancel(s);
    }
}

/* ------------------------------------------------------------------ health and telemetry */

static uint32_t health(imp_state_t *s, const imp_params_t *p, const imp_in_t *in, fx_status_t *st)
{
    uint32_t mode = s->mode;
    uint32_t h = ((uint32_t)mode << IMP_H_MODE_SH) & IMP_H_MODE;
    if (mode == IMP_MODE_INFEASIBLE) {
        h |= IMP_H_INFEASIBLE;
    }
    if (mode == IMP_MODE_NO_SOLUTION) {
        h |= IMP_H_NO_SOLUTION;
    }
    if ((s->marginal != 0u) && (mode != IMP_MODE_IDLE)) {
        h |= IMP_H_MARGINAL;
    }
    if (imp_active(mode) && (!imp_nav_fresh(s, p, in->step))) {
        h |= IMP_H_NAV_STALE;
    }
    if ((mode == IMP_MODE_ARMED) || (mode == IMP_MODE_FIRING) || (mode == IMP_MODE_FINAL)) {
        h |= imp_tl_expected_miss(s, p, st);
    }
    return h | s->latched;
}

static void tlm_plan(imp_state_t *s, const imp_params_t *p)
{
    uint32_t g = imp_grid(p);
    uint32_t us = imp_grid_us(p);
    uint32_t r;
    s->tlm.how_xy = s->sol.how[IMP_SUB_XY];
    s->tlm.how_z = s->sol.how[IMP_SUB_Z];
    s->tlm.pattern = s->sol.pattern;
    s->tlm.iters_xy = s->sol.iters[IMP_SUB_XY];
    s->tlm.iters_z = s->sol.iters[IMP_SUB_Z];
    s->tlm.last_fail_xy = s->sol.last_fail[IMP_SUB_XY];
    s->tlm.last_fail_z = s->sol.last_fail[IMP_SUB_Z];
    for (r = 0u; r < IMP_NSUB; r++) {
        s->tlm.fres_lsb[r] = s->sol.fres_lsb[r];
        s->tlm.round_choice[r] = s->rd.choice[r];
    }
    for (r = 0u; r < IMP_NX; r++) {
        s->tlm.miss_q28[r] = s->rd.miss_q28[r];
    }
    for (r = 0u; r < IMP_NAX; r++) {
        s->tlm.t1_q29[r] = s->sol.t1_q29[r];
        s->tlm.t2_q29[r] = s->sol.t2_q29[r];
        s->tlm.on1_step[r] = s->act.ta_step + (s->act.n1_g[r] / g);
        s->tlm.on2_step[r] = s->act.ta_step + (s->act.n2_g[r] / g);
        s->tlm.on1_us[r] = (s->act.n1_g[r] % g) * us;
        s->tlm.on2_us[r] = (s->act.n2_g[r] % g) * us;
        s->tlm.rho_q28[r] = s->sol.rho_q28[r];
        s->tlm.dv1_q28[r] = s->sol.dv1_q28[r];
        s->tlm.dv2_q28[r] = s->sol.dv2_q28[r];
    }
}

/* dv_cmd and dv_used of thruster j are recomputed only when their inputs changed (its on-time,
   its level estimate alpha, the grid-to-time constants): a thruster that does not fire keeps its
   values, and the conversion and product cost ~220 instructions per thruster on the M3, most of a
   step with no planning work (spec 50 §4.7). The status bits of the last computation are reported
   on every step, as when each step computed them. */
static void tlm_thrusters(imp_state_t *s, const imp_params_t *p, fx_status_t *st)
{
    uint32_t j;
    if ((s->tlm_k_gtau_m != p->k_gtau_m) || (s->tlm_k_gtau_sh != p->k_gtau_sh)) {
        s->tlm_thr_valid = 0u;
        s->tlm_k_gtau_m = p->k_gtau_m;
        s->tlm_k_gtau_sh = p->k_gtau_sh;
    }
    for (j = 0u; j < IMP_NTHR; j++) {
        uint8_t bit = (uint8_t)(1u << j);
        if (((s->tlm_thr_valid & bit) == 0u) || (s->tlm_on_g[j] != s->on_tot_g[j]) ||
            (s->tlm_alpha_q30[j] != s->cal.alpha_q30[j])) {
            fx_status_t sj = 0u;
            int32_t tau = imp_g2tau(p, s->on_tot_g[j], &sj);
            int32_t dv = fx_shr_rnd(tau, IMP_T_Q - IMP_X_Q, &sj);          /* on-time at a_nom, q28 */
            s->tlm.dv_cmd_q28[j] = dv;
            s->tlm.dv_used_q28[j] = fx_mul(dv, IMP_X_Q, s->cal.alpha_q30[j], IMP_ALPHA_Q, IMP_X_Q, &sj);
            s->tlm_on_g[j] = s->on_tot_g[j];
            s->tlm_alpha_q30[j] = s->cal.alpha_q30[j];
            s->tlm_thr_st[j] = (uint8_t)(sj & FX_ST_MASK);
            s->tlm_thr_valid |= bit;
        }
        *st |= s->tlm_thr_st[j];
        s->tlm.alpha_q30[j] = s->cal.alpha_q30[j];
        s->tlm.cal_windows[j] = s->cal.n_acc[j];
    }
    s->tlm.stuck_off_mask = s->fd.stuck_off;
}

void imp_step(imp_state_t *s, const imp_params_t *p, const imp_in_t *in, imp_out_t *out)
{
    fx_status_t st = 0u;
    uint32_t h;
    uint32_t ev;
    uint32_t avail;
    outputs_off(out);
    ev = imp_nav_intake(s, p, in);
    h = exec_command(s, p, in);
    fd_react(s, p, in, ev, &st);
    progress(s, p, in, &st);
    avail = (uint32_t)in->avail_mask & ~(uint32_t)s->fd.stuck_off & IMP_THR_ALL;
    if ((s->mode == IMP_MODE_FIRING) || (s->mode == IMP_MODE_FINAL)) {
        h |= imp_tl_fire(s, p, in->step, avail, out);
    }
    h |= health(s, p, in, &st);
    tlm_plan(s, p);
    tlm_thrusters(s, p, &st);
    h |= st & FX_ST_MASK;
    s->tlm.mode = s->mode;
    s->tlm.job_active = (s->job_kind != JOBK_NONE) ? 1u : 0u;
    s->tlm.nav_age = (s->nav.valid != 0u) ? (in->step - s->nav.step) : UINT32_MAX;
    s->tlm.st_step = st;
    s->tlm.st_sticky |= st;
    s->tlm.health_sticky |= h;
    out->health = h;
    out->tlm = s->tlm;
}
