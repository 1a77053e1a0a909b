/*
 * imp_solve.c — switching-time solver of the impulse scheduler (spec 50-impulse §3, §4).
 *
 * Nondimensional CW model (w = a_nom = 1), Newton's method with the analytic Jacobian
 * J = [s1 a1 Phi(tau_f - T1) e_r, -s2 a2 Phi(tau_f - T2) e_r] per axis, solved per subsystem
 * (x-y: n = 4, z: n = 2) with fx_solve, on the exact kernels of imp_cw.c. The residual is
 * accumulated exactly in int64 (q58) and rounded once to q28; single terms may exceed the q28
 * range while the sum does not.
 *
 * The solver has no designated saturating points (spec 50 §3.6): any fx status bit inside an
 * attempt ends that attempt as failed (IMP_FAIL_FX), and the next pattern is tried.
 */
#include "imp.h"
#include "imp_int.h"
#include "fx_inline.h"

#define U16_MAX      0xFFFFu
/* Shifts between formats (spec 00 §1.2: named, checked). */
#define SH_ACC_TO_X    30u  /* q58 -> q28 */
#define SH_ACC_TO_J    32u  /* q58 -> q26 */
#define SH_XX_TO_ACC   2u   /* q56 -> q58 */
#define SH_DV_TO_X     31u  /* q59 (alpha q30 x tau q29) -> q28 */
FX_STATIC_ASSERT(imp_sa_acc, (IMP_ALPHA_Q + IMP_M_Q) == (IMP_X_Q + SH_ACC_TO_X));
FX_STATIC_ASSERT(imp_sa_accj, (IMP_ALPHA_Q + IMP_M_Q) == (IMP_J_Q + SH_ACC_TO_J));
FX_STATIC_ASSERT(imp_sa_xx, (IMP_M_Q + IMP_X_Q + SH_XX_TO_ACC) == (IMP_ALPHA_Q + IMP_M_Q));
FX_STATIC_ASSERT(imp_sa_dv, (IMP_ALPHA_Q + IMP_T_Q) == (IMP_X_Q + SH_DV_TO_X));

#define ATT_RUNNING  0xFFu

/* ------------------------------------------------------------------ subsystem helpers */

/* Number of polarity patterns, bit offset in the 6-bit pattern, local pattern mask. */
static uint32_t sub_npat(uint32_t sub)
{
    return (sub == IMP_SUB_XY) ? 16u : 4u;
}

static uint32_t sub_pshift(uint32_t sub)
{
    return (sub == IMP_SUB_XY) ? 0u : 4u;
}

static uint32_t sub_pmask(uint32_t sub)
{
    return (sub == IMP_SUB_XY) ? 0x0Fu : 0x03u;
}

/* sigma = tau_f - T as q29; an out-of-range difference is a CONV status (attempt fails). */
static int32_t sigma_of(int32_t tauf_q29, int32_t t_q29, fx_status_t *st)
{
    int64_t d = (int64_t)tauf_q29 - (int64_t)t_q29;
    int32_t r = 0;
    if ((d > (int64_t)INT32_MAX) || (d < -(int64_t)INT32_MAX)) {
        *st |= FX_ST_CONV;
    } else {
        r = (int32_t)d;
    }
    return r;
}

/* Per plan: px = Phi(tau_f) X0 - X_t (q58) and Psi_r(tau_f) for every axis. */
static void plan_setup(imp_ws_t *ws, const imp_problem_t *pr, fx_status_t *st)
{
    imp_trig_t t;
    int64_t y_q56[IMP_NX];
    uint32_t i;
    imp_trig(pr->tauf_q29, &t, st);
    imp_phi_apply(pr->tauf_q29, &t, pr->x0_q28, y_q56, st);
    for (i = 0u; i < IMP_NX; i++) {
        int64_t a = fx_shl64_chk(y_q56[i], SH_XX_TO_ACC, st);
        ws->px_q58[i] = fx_add64_sat_i(a, -fx_shl64_chk((int64_t)pr->xt_q28[i], SH_ACC_TO_X, st), st);
    }
    for (i = 0u; i < IMP_NAX; i++) {
        imp_psi(i, pr->tauf_q29, &t, ws->psif_q28[i], st);
    }
}

/* Per attempt: signed thrust factors of pattern pat (subsystem-local bits) and the constant
   part of the residual c = px + sum_k s1 a1 Psi_r(tau_f). */
static void attempt_setup(imp_ws_t *ws, const imp_problem_t *pr, uint32_t sub, uint32_t pat, fx_status_t *st)
{
    uint32_t nax = imp_sub_nax(sub);
    uint32_t n = 2u * nax;
    uint32_t r0 = imp_sub_row0(sub);
    uint32_t k;
    uint32_t i;
    for (i = 0u; i < n; i++) {
        ws->c_q58[i] = ws->px_q58[r0 + i];
    }
    for (k = 0u; k < nax; k++) {
        uint32_t r = imp_sub_ax0(sub) + k;
        uint32_t neg1 = (pat >> (2u * k)) & 1u;
        uint32_t neg2 = (pat >> ((2u * k) + 1u)) & 1u;
        int32_t a1 = pr->alpha_q30[(2u * r) + neg1];
        int32_t a2 = pr->alpha_q30[(2u * r) + neg2];
        ws->sa1_q30[k] = (neg1 != 0u) ? fx_neg(a1, st) : a1;
        ws->sa2_q30[k] = (neg2 != 0u) ? fx_neg(a2, st) : a2;
        for (i = 0u; i < n; i++) {
            ws->c_q58[i] = fx_add64_sat_i(ws->c_q58[i], (int64_t)ws->sa1_q30[k] * (int64_t)ws->psif_q28[r][i], st);
        }
    }
}

/* Contribution of one switching time: F += sgn_psi * sa * Psi(sigma), J column = sgn_j * sa *
   Phi(sigma) e_r. sgn is -1 for T1 (Psi enters negated, column positive), +1 for T2. */
static void add_switch(imp_ws_t *ws, uint32_t r, uint32_t n, int32_t sig_q29, int32_t sa_q30, bool first,
                       uint32_t col, int64_t *facc, fx_status_t *st)
{
    imp_trig_t t;
    int32_t v[4] = {0, 0, 0, 0};
    uint32_t i;
    int32_t sa_f = first ? fx_neg(sa_q30, st) : sa_q30;     /* multiplies Psi */
    int32_t sa_j = first ? sa_q30 : fx_neg(sa_q30, st);     /* multiplies Phi e_r */
    imp_trig(sig_q29, &t, st);
    imp_psi(r, sig_q29, &t, v, st);
    for (i = 0u; i < n; i++) {
        facc[i] = fx_add64_sat_i(facc[i], (int64_t)sa_f * (int64_t)v[i], st);
    }
    imp_phie(r, sig_q29, &t, v, st);
    for (i = 0u; i < n; i++) {
        ws->j_q26[(i * n) + col] = fx_rshift_sat_i((int64_t)sa_j * (int64_t)v[i], SH_ACC_TO_J, st);
    }
}

/* Residual F (q28) and Jacobian (q26) at the current iterate; returns max |F_i| in LSB. */
static uint32_t eval(imp_ws_t *ws, const imp_problem_t *pr, uint32_t sub, fx_status_t *st)
{
    uint32_t nax = imp_sub_nax(sub);
    uint32_t n = 2u * nax;
    int64_t facc[4];
    uint32_t k;
    uint32_t i;
    uint32_t fmax = 0u;
    for (i = 0u; i < n; i++) {
        facc[i] = ws->c_q58[i];
    }
    for (k = 0u; k < nax; k++) {
        uint32_t r = imp_sub_ax0(sub) + k;
        int32_t s1 = sigma_of(pr->tauf_q29, ws->t1_q29[k], st);
        int32_t s2 = sigma_of(pr->tauf_q29, ws->t2_q29[k], st);
        add_switch(ws, r, n, s1, ws->sa1_q30[k], true, 2u * k, facc, st);
        add_switch(ws, r, n, s2, ws->sa2_q30[k], false, (2u * k) + 1u, facc, st);
    }
    for (i = 0u; i < n; i++) {
        uint32_t a;
        ws->f_q28[i] = fx_rshift_sat_i(facc[i], SH_ACC_TO_X, st);
        a = fx_uabs(ws->f_q28[i]);
        fmax = (a > fmax) ? a : fmax;
    }
    return fmax;
}

/* Solve J d = F and check the pivots; returns an IMP_FAIL_* code (NONE on success). */
static uint32_t newton_solve(imp_ws_t *ws, const imp_params_t *p, uint32_t n, fx_status_t *st)
{
    fx_status_t sst = 0u;
    uint32_t res = IMP_FAIL_NONE;
    fx_solve_fast(&ws->sws, ws->j_q26, IMP_J_Q, ws->f_q28, IMP_X_Q, n, ws->d_q29, IMP_T_Q, p->pivot_min_q26, &sst);
    if ((sst & FX_ST_SINGULAR) != 0u) {
        res = IMP_FAIL_SINGULAR;
    } else if (sst != 0u) {
        res = IMP_FAIL_FX;
    } else {
        uint32_t pmin = UINT32_MAX;
        uint32_t pmax = 0u;
        uint32_t k;
        for (k = 0u; k < n; k++) {
            uint32_t a = fx_uabs(ws->sws.rec[k].d);
            pmin = (a < pmin) ? a : pmin;
            pmax = (a > pmax) ? a : pmax;
        }
        if (((uint64_t)pmin << p->pivot_ratio_sh) < (uint64_t)pmax) {
            res = IMP_FAIL_COND;
        }
    }
    *st |= sst;
    return res;
}

/* Newton update T <- T - d and the divergence guard: every T inside (-tau_f, 2 tau_f). */
static uint32_t newton_update(imp_ws_t *ws, int32_t tauf_q29, uint32_t nax, fx_status_t *st)
{
    uint32_t res = IMP_FAIL_NONE;
    uint32_t k;
    int64_t lo = -(int64_t)tauf_q29;
    int64_t hi = 2 * (int64_t)tauf_q29;
    for (k = 0u; k < nax; k++) {
        uint32_t c1 = 2u * k;
        uint32_t c2 = c1 + 1u;
        ws->t1_q29[k] = fx_sub_sat(ws->t1_q29[k], ws->d_q29[c1], st);
        ws->t2_q29[k] = fx_sub_sat(ws->t2_q29[k], ws->d_q29[c2], st);
        if (((int64_t)ws->t1_q29[k] <= lo) || ((int64_t)ws->t1_q29[k] >= hi) ||
            ((int64_t)ws->t2_q29[k] <= lo) || ((int64_t)ws->t2_q29[k] >= hi)) {
            res = IMP_FAIL_DIVERGE;
        }
    }
    return res;
}

/* Validity of a converged schedule, +-1 LSB of tau (spec 50 §3.6); clamps that LSB. */
static uint32_t check_order(imp_ws_t *ws, int32_t tauf_q29, uint32_t nax)
{
    uint32_t res = IMP_FAIL_NONE;
    uint32_t k;
    for (k = 0u; k < nax; k++) {
        int64_t t1 = (int64_t)ws->t1_q29[k];
        int64_t t2 = (int64_t)ws->t2_q29[k];
        if ((t1 < -1) || ((t2 - t1) < -1) || (t2 > ((int64_t)tauf_q29 + 1))) {
            res = IMP_FAIL_ORDER;
        } else {
            t1 = (t1 < 0) ? 0 : t1;
            t2 = (t2 > (int64_t)tauf_q29) ? (int64_t)tauf_q29 : t2;
            t2 = (t2 < t1) ? t1 : t2;
            ws->t1_q29[k] = (int32_t)t1;
            ws->t2_q29[k] = (int32_t)t2;
        }
    }
    return res;
}

/*
 * One iteration of an attempt (one work unit): evaluate F and J at the iterate in ws->t1/t2;
 * converged -> validity; else, below max_iter, one guarded Newton step. Returns ATT_RUNNING
 * while the attempt goes on (*it then advanced), else IMP_FAIL_NONE or the cause. *it is the
 * iteration index of the last evaluation, *fres its max |F|, *ast the attempt's fx status.
 */
static uint32_t attempt_iter(imp_ws_t *ws, const imp_params_t *p, const imp_problem_t *pr, uint32_t sub,
                             uint32_t *it, uint32_t *fres, fx_status_t *ast)
{
    uint32_t nax = imp_sub_nax(sub);
    uint32_t res = IMP_FAIL_ITER;
    if (*it > IMP_ITER_CAP) {
        *it = IMP_ITER_CAP;                 /* only with max_iter > IMP_ITER_CAP (refused table) */
    } else {
        uint32_t fmax = eval(ws, pr, sub, ast);
        *fres = fmax;
        if (*ast != 0u) {
            res = IMP_FAIL_FX;
        } else if (fmax <= (uint32_t)p->r_tol_lsb) {
            res = check_order(ws, pr->tauf_q29, nax);
        } else if (*it >= (uint32_t)p->max_iter) {
            res = IMP_FAIL_ITER;
        } else {
            res = newton_solve(ws, p, 2u * nax, ast);
            if (res == IMP_FAIL_NONE) {
                res = newton_update(ws, pr->tauf_q29, nax, ast);
            }
            if ((res == IMP_FAIL_NONE) && (*ast != 0u)) {
                res = IMP_FAIL_FX;
            }
            if (res == IMP_FAIL_NONE) {
                res = ATT_RUNNING;
                (*it)++;
            }
        }
    }
    return res;
}

/* A whole attempt from the times already in ws->t1/t2 (imp_attempt). */
static uint32_t attempt(imp_ws_t *ws, const imp_params_t *p, const imp_problem_t *pr, uint32_t sub, uint32_t pat,
                        fx_status_t *ast, uint32_t *iters, uint32_t *fres)
{
    uint32_t res = ATT_RUNNING;
    uint32_t n;
    *iters = 0u;
    attempt_setup(ws, pr, sub, pat, ast);
    for (n = 0u; (n <= (IMP_ITER_CAP + 1u)) && (res == ATT_RUNNING); n++) {
        res = attempt_iter(ws, p, pr, sub, iters, fres, ast);
    }
    if (res == ATT_RUNNING) {
        res = IMP_FAIL_ITER;
    }
    return res;
}
/* Plan delta-v of the schedule in ws->t1/t2: sum |s a| (T1 + tau_f - T2), q28. */
static int32_t attempt_dv(const imp_ws_t *ws, int32_t tauf_q29, uint32_t nax, fx_status_t *st)
{
    int64_t acc = 0;
    uint32_t k;
    for (k = 0u; k < nax; k++) {
        int64_t a1 = (int64_t)fx_uabs(ws->sa1_q30[k]);
        int64_t a2 = (int64_t)fx_uabs(ws->sa2_q30[k]);
        acc = fx_add64_sat_i(acc, a1 * (int64_t)ws->t1_q29[k], st);
        acc = fx_add64_sat_i(acc, a2 * ((int64_t)tauf_q29 - (int64_t)ws->t2_q29[k]), st);
    }
    return fx_rshift_sat_i(acc, SH_DV_TO_X, st);
}

static void start_times(imp_ws_t *ws, int32_t tauf_q29)
{
    uint32_t k;
    for (k = 0u; k < 2u; k++) {
        ws->t1_q29[k] = 0;
        ws->t2_q29[k] = tauf_q29;
    }
}

static void count_fail(imp_solution_t *sol, uint32_t sub, uint32_t cause)
{
    sol->last_fail[sub] = (uint8_t)cause;
    if ((cause < IMP_FAIL_N) && ((uint32_t)sol->n_fail[cause] < U16_MAX)) {
        sol->n_fail[cause]++;
    }
}

static void count_iters(imp_solution_t *sol, uint32_t sub, uint32_t iters)
{
    uint32_t t = (uint32_t)sol->iters_total + iters;
    sol->iters_total = (uint16_t)((t > U16_MAX) ? U16_MAX : t);
    if ((uint32_t)sol->attempts[sub] < U16_MAX) {
        sol->attempts[sub]++;
    }
}


static void accept(imp_ws_t *ws, imp_solution_t *sol, uint32_t sub, uint32_t pat, uint32_t how, uint32_t iters,
                   uint32_t fres, int32_t tauf_q29)
{
    uint32_t nax = imp_sub_nax(sub);
    uint32_t k;
    fx_status_t st = 0u;
    for (k = 0u; k < nax; k++) {
        sol->t1_q29[imp_sub_ax0(sub) + k] = ws->t1_q29[k];
        sol->t2_q29[imp_sub_ax0(sub) + k] = ws->t2_q29[k];
    }
    sol->sub_outcome[sub] = IMP_SOL_VALID;
    sol->how[sub] = (uint8_t)how;
    sol->iters[sub] = (uint8_t)iters;
    sol->fres_lsb[sub] = (int32_t)fres;
    sol->dv_q28[sub] = attempt_dv(ws, tauf_q29, nax, &st);
    sol->st_ok |= st;
    sol->pattern |= (uint8_t)(pat << sub_pshift(sub));
}

/* Rule pattern of a subsystem from the signs of the impulsive delta-v. */
static uint32_t rule_pattern(const imp_solution_t *sol, uint32_t sub)
{
    uint32_t pat = 0u;
    uint32_t k;
    for (k = 0u; k < imp_sub_nax(sub); k++) {
        uint32_t r = imp_sub_ax0(sub) + k;
        pat |= ((sol->dv1_q28[r] < 0) ? 1u : 0u) << (2u * k);
        pat |= ((sol->dv2_q28[r] < 0) ? 1u : 0u) << ((2u * k) + 1u);
    }
    return pat;
}

/* The impulsive solution of one subsystem (one work unit): one Newton step from (0, tau_f) with
   every polarity positive (spec 50 §3.2). Fills dv1, dv2 (alpha of the + thrusters) and rho;
   returns false when the step itself cannot be formed (singular J: treated as infeasible). */
static bool impulsive_sub(imp_ws_t *ws, const imp_params_t *p, const imp_problem_t *pr, uint32_t sub,
                          imp_solution_t *sol, fx_status_t *st)
{
    uint32_t nax = imp_sub_nax(sub);
    uint32_t k;
    bool ok = true;
    start_times(ws, pr->tauf_q29);
    attempt_setup(ws, pr, sub, 0u, st);
    (void)eval(ws, pr, sub, st);
    if (newton_solve(ws, p, 2u * nax, st) != IMP_FAIL_NONE) {
        ok = false;
    }
    for (k = 0u; k < nax; k++) {
        uint32_t r = imp_sub_ax0(sub) + k;
        uint32_t jp = 2u * r;                               /* the + thruster of axis r */
        uint32_t c1 = 2u * k;
        uint32_t c2 = c1 + 1u;
        int32_t a = pr->alpha_q30[jp];
        int32_t l1 = fx_neg(ws->d_q29[c1], st);             /* T1 after the step */
        int32_t l2 = ws->d_q29[c2];                         /* tau_f - T2 after the step */
        int32_t sum;
        sol->dv1_q28[r] = fx_rshift_sat_i((int64_t)a * (int64_t)l1, SH_DV_TO_X, st);
        sol->dv2_q28[r] = fx_rshift_sat_i((int64_t)a * (int64_t)l2, SH_DV_TO_X, st);
        sum = fx_add_sat(fx_abs(sol->dv1_q28[r], st), fx_abs(sol->dv2_q28[r], st), st);
        sol->rho_q28[r] = fx_div(sum, IMP_X_Q, pr->tauf_q29, IMP_T_Q, IMP_X_Q, st);
    }
    return ok;
}

static void clear_solution(imp_solution_t *sol)
{
    uint32_t i;
    sol->outcome = (uint8_t)IMP_SOL_NO_SOLUTION;
    sol->pattern = 0u;
    sol->marginal = 0u;
    sol->iters_total = 0u;
    sol->st_ok = 0u;
    sol->st_fail = 0u;
    for (i = 0u; i < IMP_NSUB; i++) {
        sol->how[i] = IMP_HOW_NONE;
        sol->iters[i] = 0u;
        sol->sub_outcome[i] = IMP_SOL_NO_SOLUTION;
        sol->last_fail[i] = IMP_FAIL_NONE;
        sol->attempts[i] = 0u;
        sol->fres_lsb[i] = 0;
        sol->dv_q28[i] = 0;
    }
    for (i = 0u; i < IMP_FAIL_N; i++) {
        sol->n_fail[i] = 0u;
    }
    for (i = 0u; i < IMP_NAX; i++) {
        sol->t1_q29[i] = 0;
        sol->t2_q29[i] = 0;
        sol->dv1_q28[i] = 0;
        sol->dv2_q28[i] = 0;
        sol->rho_q28[i] = 0;
    }
}

/* Feasibility gate (spec 50 §3.7): returns true when the plan may be attempted. */
static bool gate(const imp_params_t *p, imp_solution_t *sol)
{
    int32_t rmax = 0;
    uint32_t r;
    bool go = true;
    for (r = 0u; r < IMP_NAX; r++) {
        rmax = (sol->rho_q28[r] > rmax) ? sol->rho_q28[r] : rmax;
    }
    if (rmax > p->rho_reject_q28) {
        sol->outcome = IMP_SOL_INFEASIBLE;
        go = false;
    } else if (rmax > p->rho_warn_q28) {
        sol->marginal = 1u;
    } else {
        /* nominal */
    }
    return go;
}


/* ------------------------------------------------------------------ resumable plan job */

#define JOB_SETUP    0u   /* plan set-up (one unit) */
#define JOB_IMPULSE  1u   /* impulsive step of subsystem job.sub (one unit each) */
#define JOB_GATE     2u   /* feasibility gate (free) */
#define JOB_SOLVE    3u   /* warm -> rule -> search of subsystem job.sub */
#define JOB_DONE     4u

#define STG_WARM     0u
#define STG_RULE     1u
#define STG_SEARCH   2u
#define STG_END      3u

/* Free (unit-less) ticks of a whole plan: per subsystem warm, rule, search cursor (16), end and
   an attempt start per pattern, plus the gate and the final outcome; generously rounded up. */
#define JOB_FREE_MAX 96u
#define JOB_UNITS_CAP IMP_JOB_UNITS(IMP_ITER_CAP)

/* Thruster used by burn b of local axis k under the subsystem-local pattern pat. */
static uint32_t pat_thruster(uint32_t sub, uint32_t pat, uint32_t k, uint32_t b)
{
    uint32_t r = imp_sub_ax0(sub) + k;
    return (2u * r) + ((pat >> ((2u * k) + b)) & 1u);
}

/* A pattern is allowed when none of its thrusters is in pr->thr_off. */
static bool pat_allowed(const imp_problem_t *pr, uint32_t sub, uint32_t pat)
{
    uint32_t k;
    uint32_t b;
    uint32_t used = 0u;
    for (k = 0u; k < imp_sub_nax(sub); k++) {
        for (b = 0u; b < 2u; b++) {
            used |= 1u << pat_thruster(sub, pat, k, b);
        }
    }
    return (used & (uint32_t)pr->thr_off) == 0u;
}

static void attempt_begin(imp_ws_t *ws, const imp_problem_t *pr, uint32_t pat, uint32_t how)
{
    imp_job_t *j = &ws->job;
    j->cur = (uint8_t)pat;
    j->how = (uint8_t)how;
    j->it = 0u;
    j->fres = 0u;
    j->ast = 0u;
    j->running = 1u;
    attempt_setup(ws, pr, j->sub, pat, &j->ast);
}

/* Search bookkeeping of a valid attempt: keep the least delta-v (ties within dv_tie to the lower
   index, which came first). */
static void search_keep(imp_ws_t *ws, const imp_params_t *p, const imp_problem_t *pr, uint32_t nax,
                        imp_solution_t *sol)
{
    fx_status_t st = 0u;
    int32_t dv = attempt_dv(ws, pr->tauf_q29, nax, &st);
    sol->st_ok |= st;
    if ((ws->have_best == 0u) || ((int64_t)dv < ((int64_t)ws->best_dv_q28 - (int64_t)p->dv_tie_q28))) {
        uint32_t k;
        ws->have_best = 1u;
        ws->best_dv_q28 = dv;
        ws->best_pat = ws->job.cur;
        ws->best_iters = ws->job.it;
        ws->best_fres = (int32_t)ws->job.fres;
        for (k = 0u; k < nax; k++) {
            ws->best_t1_q29[k] = ws->t1_q29[k];
            ws->best_t2_q29[k] = ws->t2_q29[k];
        }
    }
}

/* The running attempt ended with res: book-keeping, accept (warm, rule) or keep (search). */
static void attempt_end(imp_ws_t *ws, const imp_params_t *p, const imp_problem_t *pr, uint32_t res,
                        imp_solution_t *sol)
{
    imp_job_t *j = &ws->job;
    uint32_t sub = j->sub;
    j->running = 0u;
    count_iters(sol, sub, j->it);
    if (res == IMP_FAIL_NONE) {
        sol->st_ok |= j->ast;
        if (j->how == IMP_HOW_SEARCH) {
            search_keep(ws, p, pr, imp_sub_nax(sub), sol);
        } else {
            accept(ws, sol, sub, j->cur, j->how, j->it, j->fres, pr->tauf_q29);
            j->stage = STG_END;
        }
    } else {
        sol->st_fail |= j->ast;
        count_fail(sol, sub, res);
    }
}

/* Warm stage: the previous polarities with the shifted times (re-plans only). */
static void stage_warm(imp_ws_t *ws, const imp_problem_t *pr)
{
    imp_job_t *j = &ws->job;
    uint32_t sub = j->sub;
    j->stage = STG_RULE;
    if (((uint32_t)pr->warm_mask & (1u << sub)) != 0u) {
        uint32_t wp = ((uint32_t)pr->warm_pattern >> sub_pshift(sub)) & sub_pmask(sub);
        j->tried = (uint16_t)((uint32_t)j->tried | (1u << wp));
        if (pat_allowed(pr, sub, wp)) {
            uint32_t k;
            for (k = 0u; k < imp_sub_nax(sub); k++) {
                ws->t1_q29[k] = pr->warm_t1_q29[imp_sub_ax0(sub) + k];
                ws->t2_q29[k] = pr->warm_t2_q29[imp_sub_ax0(sub) + k];
            }
            attempt_begin(ws, pr, wp, IMP_HOW_WARM);
        }
    }
}

/* Rule stage: the signs of the impulsive delta-v, from (0, tau_f). */
static void stage_rule(imp_ws_t *ws, const imp_problem_t *pr, const imp_solution_t *sol)
{
    imp_job_t *j = &ws->job;
    uint32_t rp = rule_pattern(sol, j->sub) & sub_pmask(j->sub);
    j->stage = STG_SEARCH;
    j->pat = 0u;
    ws->have_best = 0u;
    if ((((uint32_t)j->tried >> rp) & 1u) == 0u) {
        j->tried = (uint16_t)((uint32_t)j->tried | (1u << rp));
        if (pat_allowed(pr, j->sub, rp)) {
            start_times(ws, pr->tauf_q29);
            attempt_begin(ws, pr, rp, IMP_HOW_RULE);
        }
    }
}

/* Search stage, one pattern per tick in ascending index; at the end accept the best. */
static void stage_search(imp_ws_t *ws, const imp_problem_t *pr, imp_solution_t *sol)
{
    imp_job_t *j = &ws->job;
    uint32_t sub = j->sub;
    if ((uint32_t)j->pat >= sub_npat(sub)) {
        j->stage = STG_END;
        if (ws->have_best != 0u) {
            uint32_t k;
            for (k = 0u; k < imp_sub_nax(sub); k++) {
                ws->t1_q29[k] = ws->best_t1_q29[k];
                ws->t2_q29[k] = ws->best_t2_q29[k];
            }
            accept(ws, sol, sub, ws->best_pat, IMP_HOW_SEARCH, ws->best_iters, (uint32_t)ws->best_fres,
                   pr->tauf_q29);
        }
    } else {
        uint32_t cp = j->pat;
        j->pat++;
        if (((((uint32_t)j->tried >> cp) & 1u) == 0u) && pat_allowed(pr, sub, cp)) {
            start_times(ws, pr->tauf_q29);
            attempt_begin(ws, pr, cp, IMP_HOW_SEARCH);
        }
    }
}

/* Next subsystem, or the plan's outcome once both are done. */
static void stage_end(imp_ws_t *ws, imp_solution_t *sol)
{
    imp_job_t *j = &ws->job;
    if (j->sub == 0u) {
        j->sub = 1u;
        j->stage = STG_WARM;
        j->tried = 0u;
    } else {
        bool both = (sol->sub_outcome[IMP_SUB_XY] == IMP_SOL_VALID) && (sol->sub_outcome[IMP_SUB_Z] == IMP_SOL_VALID);
        sol->outcome = both ? (uint8_t)IMP_SOL_VALID : (uint8_t)IMP_SOL_NO_SOLUTION;
        j->phase = JOB_DONE;
    }
}

/* One tick of the SOLVE phase; returns the work units used (0 or 1). */
static uint32_t solve_tick(imp_ws_t *ws, const imp_params_t *p, const imp_problem_t *pr, imp_solution_t *sol)
{
    imp_job_t *j = &ws->job;
    uint32_t used = 0u;
    if (j->running != 0u) {
        uint32_t it = j->it;
        uint32_t fres = j->fres;
        uint32_t res = attempt_iter(ws, p, pr, j->sub, &it, &fres, &j->ast);
        j->it = (uint8_t)it;
        j->fres = fres;
        used = 1u;
        if (res != ATT_RUNNING) {
            attempt_end(ws, p, pr, res, sol);
        }
    } else if (j->stage == STG_WARM) {
        stage_warm(ws, pr);
    } else if (j->stage == STG_RULE) {
        stage_rule(ws, pr, sol);
    } else if (j->stage == STG_SEARCH) {
        stage_search(ws, pr, sol);
    } else {
        stage_end(ws, sol);
    }
    return used;
}

/* Gate phase (free): an impulsive step that could not be formed, or any fx status in the
   set-up, is INFEASIBLE; then rho (START plans only). */
static void gate_tick(imp_ws_t *ws, const imp_params_t *p, const imp_problem_t *pr, imp_solution_t *sol)
{
    imp_job_t *j = &ws->job;
    if ((j->bad != 0u) || (j->pst != 0u)) {
        sol->outcome = IMP_SOL_INFEASIBLE;
        sol->st_fail |= j->pst;
        j->phase = JOB_DONE;
    } else if (gate(p, sol) || (pr->replan != 0u)) {
        if (pr->replan != 0u) {
            sol->outcome = (uint8_t)IMP_SOL_NO_SOLUTION;
            sol->marginal = 0u;
        }
        j->phase = JOB_SOLVE;
        j->sub = 0u;
        j->stage = STG_WARM;
        j->tried = 0u;
        j->running = 0u;
    } else {
        j->phase = JOB_DONE;   /* infeasible: nothing attempted */
    }
}

/* One tick of the job; returns the work units used (0 or 1). */
static uint32_t job_tick(imp_ws_t *ws, const imp_params_t *p, const imp_problem_t *pr, imp_solution_t *sol)
{
    imp_job_t *j = &ws->job;
    uint32_t used = 1u;
    if (j->phase == JOB_SETUP) {
        plan_setup(ws, pr, &j->pst);
        j->phase = JOB_IMPULSE;
        j->sub = 0u;
    } else if (j->phase == JOB_IMPULSE) {
        if (!impulsive_sub(ws, p, pr, j->sub, sol, &j->pst)) {
            j->bad = 1u;
        }
        if (j->sub == 0u) {
            j->sub = 1u;
        } else {
            j->phase = JOB_GATE;
        }
    } else if (j->phase == JOB_GATE) {
        gate_tick(ws, p, pr, sol);
        used = 0u;
    } else if (j->phase == JOB_SOLVE) {
        used = solve_tick(ws, p, pr, sol);
    } else {
        used = 0u;
    }
    return used;
}

void imp_solve_begin(imp_ws_t *ws, imp_solution_t *sol)
{
    imp_job_t *j = &ws->job;
    clear_solution(sol);
    j->phase = JOB_SETUP;
    j->sub = 0u;
    j->stage = STG_WARM;
    j->pat = 0u;
    j->cur = 0u;
    j->it = 0u;
    j->running = 0u;
    j->how = IMP_HOW_NONE;
    j->bad = 0u;
    j->tried = 0u;
    j->units = 0u;
    j->ast = 0u;
    j->pst = 0u;
    j->fres = 0u;
    ws->have_best = 0u;
}

/* The job may take another tick: budget left and not done. */
static bool job_more(const imp_ws_t *ws, uint32_t used, uint32_t budget)
{
    return (used < budget) && (ws->job.phase != JOB_DONE);
}

uint32_t imp_solve_run(imp_ws_t *ws, const imp_params_t *p, const imp_problem_t *pr, imp_solution_t *sol,
                       uint32_t budget)
{
    uint32_t b = (budget > JOB_UNITS_CAP) ? JOB_UNITS_CAP : budget;
    uint32_t used = 0u;
    uint32_t n;
    /* at most b unit ticks plus the plan's free ticks; idle passes once the budget is used */
    for (n = 0u; n < (b + JOB_FREE_MAX); n++) {
        if (job_more(ws, used, b)) {
            used += job_tick(ws, p, pr, sol);
        }
    }
    {
        uint32_t u = (uint32_t)ws->job.units + used;
        ws->job.units = (uint16_t)((u > U16_MAX) ? U16_MAX : u);
    }
    return used;
}

bool imp_solve_done(const imp_ws_t *ws)
{
    return ws->job.phase == JOB_DONE;
}

uint32_t imp_attempt(imp_ws_t *ws, const imp_params_t *p, const imp_problem_t *pr, uint32_t sub, uint32_t pat,
                     const int32_t *t1_q29, const int32_t *t2_q29, uint32_t *iters, uint32_t *fres_lsb,
                     fx_status_t *ast)
{
    uint32_t res = IMP_FAIL_FX;
    fx_status_t pst = 0u;
    *iters = 0u;
    *fres_lsb = 0u;
    if (sub < IMP_NSUB) {
        uint32_t k;
        plan_setup(ws, pr, &pst);
        *ast |= pst;
        for (k = 0u; k < imp_sub_nax(sub); k++) {
            ws->t1_q29[k] = t1_q29[k];
            ws->t2_q29[k] = t2_q29[k];
        }
        res = attempt(ws, p, pr, sub, pat & sub_pmask(sub), ast, iters, fres_lsb);
    }
    return res;
}

void imp_solve(imp_ws_t *ws, const imp_params_t *p, const imp_problem_t *pr, imp_solution_t *sol)
{
    imp_solve_begin(ws, sol);
    (void)imp_solve_run(ws, p, pr, sol, JOB_UNITS_CAP);
}
