/*
 * imp.h — impulse scheduler: terminal rendezvous with six on/off thrusters (spec 50-impulse).
 *
 * The solver (imp_solve.c) finds, per axis, the two interior switching times T1 <= T2 of a
 * burn / coast / burn profile over [t0, t_f) so that the Clohessy-Wiltshire prediction of the
 * state at t_f equals the target. It works in the nondimensional system of spec 50 §4.1
 * (time 1/w, length a_nom/w^2, velocity a_nom/w), so w and a_nom never appear at run time:
 *     x'' = 2y' + u_x,   y'' = -2x' + 3y + u_y,   z'' = -z + u_z,   u in {0, +-alpha_j}.
 * Newton's method with the analytic Jacobian, taken separately for the coupled x-y subsystem
 * (4 unknowns) and for z (2 unknowns); polarities from the impulsive two-impulse solution, then
 * a search over all patterns (spec 50 §3.5). The planner is a resumable job (spec 50 §4.7):
 * imp_solve_begin / imp_solve_run advance it by at most `budget` work units per call.
 *
 * The module (imp.c, imp_nav.c, imp_tl.c) turns a plan into a per-thruster timeline on the valve
 * grid (whole steps, or sub-ticks of subtick_us), re-plans every replan_period steps, calibrates
 * the thrust levels (§5.5), watches for stuck valves (§8) and gates navigation outliers.
 *
 * Formats (spec 50 §4.2): tau (T1, T2, tau_f, sigma) q29; state, target, residual F q28;
 * Phi, Psi, Phi e_r entries q28; derived trig q30; thrust factors alpha q30; the Jacobian handed
 * to fx_solve q26 (three spare bits for the 2^(n-1) element growth of an n = 4 elimination).
 *
 * State order everywhere: (x, x', y, y', z, z'); x along-track, y radial (towards the Earth),
 * z cross-track. Thruster j = 0..5 is +x, -x, +y, -y, +z, -z (bit j of every mask).
 * Polarity pattern (6 bits, bit = 1 means the negative thruster): bit 0 s1x, 1 s2x, 2 s1y,
 * 3 s2y, 4 s1z, 5 s2z. The x-y search index is bits 0..3, the z index bits 4..5 shifted down.
 */
#ifndef FSW_IMP_H
#define FSW_IMP_H

#include <stdint.h>
#include <stdbool.h>
#include "fx.h"
#include "imp_ids.h"

#define IMP_NX      6u     /* state dimension */
#define IMP_NAX     3u     /* axes */
#define IMP_NTHR    6u     /* thrusters */
#define IMP_NSUB    2u     /* subsystems: x-y, z */
#define IMP_SUB_XY  0u
#define IMP_SUB_Z   1u
#define IMP_THR_ALL 0x3Fu  /* every thruster */

#define IMP_T_Q      29u   /* tau, T1, T2, sigma: rad (nondimensional time) */
#define IMP_X_Q      28u   /* nondimensional state, target, residual, impulsive dv, rho */
#define IMP_M_Q      28u   /* Phi, Psi, Phi e_r entries */
#define IMP_TRIG_Q   30u   /* sin, cos, 1 - cos, tau - sin tau */
#define IMP_ALPHA_Q  30u   /* thrust factor alpha_j = a_j / a_nom; also fractions (gates, u_alpha) */
#define IMP_J_Q      26u   /* Jacobian given to fx_solve (3 headroom bits for n = 4) */

#define IMP_ITER_CAP 16u   /* compile-time bound of max_iter */
#define IMP_G_MAX    1000u /* largest number of sub-ticks per step */
#define IMP_LOG_CAP  16u   /* commanded-burn segments kept for prediction, calibration, monitor */
/* Work units of the resumable plan (spec 50 §4.7): one unit is one residual + Jacobian
   evaluation (with its 4x4 or 2x2 solve), the plan set-up counts one, and the rounding counts
   IMP_ROUND_UNITS. Worst case: set-up + 2 impulsive steps + (16 + 4) attempts of max_iter + 1
   evaluations each (warm and rule are patterns of the search, never tried twice). */
#define IMP_ROUND_UNITS  4u
#define IMP_JOB_UNITS(mi) (3u + (20u * ((uint32_t)(mi) + 1u)))
#define IMP_PLAN_WORST_ITER 240u   /* spec 50 §4.7: plan_lead >= ceil(240 / plan_iter_per_step) */

/* Plan / subsystem outcome. */
#define IMP_SOL_VALID        0u
#define IMP_SOL_NO_SOLUTION  1u
#define IMP_SOL_INFEASIBLE   2u

/* Scheduler modes (IMP_MODE_*, spec 50 §5.1), health bits (IMP_H_*, §8), attempt failure causes
   (IMP_FAIL_*), polarity sources (IMP_HOW_*), command refusal reasons (IMP_REJ_*), params_check
   reasons (IMP_WHY_*) and telecommand ids (IMP_CMD_*): imp_ids.h, generated from imp_iface.py.
   The cross-field invariants alone (LEAD, SCALE, GRID) give FSW_ERR_INVARIANT, range bits
   FSW_ERR_RANGE. */
#define IMP_WHY_INVARIANTS (IMP_WHY_LEAD | IMP_WHY_SCALE | IMP_WHY_GRID)

typedef struct {
    uint32_t period_us;            /* fsw period (valve tick) */
    uint32_t subtick_us;           /* 0: whole steps; else the valve grid (divides period_us) */
    uint32_t t_min_us;             /* minimum on-time (<= period_us) */
    uint32_t plan_lead;            /* steps between START and the earliest t0; re-plan t_p -> t_a */
    uint32_t replan_period;        /* steps between re-plan epochs t_p = t0 + i N (0: never) */
    uint32_t t_stop;               /* no re-plan with t_a > t_f - t_stop (steps) */
    uint32_t nav_timeout;          /* a nav sample older than this (steps) is stale */
    uint8_t  max_iter;             /* Newton iterations per attempt, <= IMP_ITER_CAP */
    uint8_t  plan_iter_per_step;   /* work units (Newton iterations) of the plan job per step */
    uint8_t  pivot_ratio_sh;       /* smallest/largest pivot must be >= 2^-sh (12) */
    uint8_t  k_tau_sh;             /* k_tau shift */
    int32_t  r_tol_lsb;            /* convergence: max |F_i| <= r_tol (q28 LSB), 32 */
    int32_t  pivot_min_q26;        /* 2^-10 in the Jacobian format */
    int32_t  rho_warn_q28;         /* 0.38 */
    int32_t  rho_reject_q28;       /* 0.55 */
    int32_t  dv_tie_q28;           /* 1 mm/s, nondimensional: search ties */
    int32_t  tauf_min_q29;         /* 0.2 */
    int32_t  tauf_max_q29;         /* 2.0 */
    int32_t  w_v_q28;              /* rounding cost weight w t_w (t_w = 100 s): 0.1131 */
    int32_t  alpha_q30[IMP_NTHR];  /* thrust factors (initial calibration), [0.8, 1.2] */
    /* counts -> q28: v = count * m / 2^sh (fx_from_count), from w, a_nom and the nav LSBs */
    int32_t  k_pos_m;              /* position count (1 mm) */
    uint8_t  k_pos_sh;
    uint8_t  k_vel_sh;
    uint8_t  k_tick_sh;
    uint8_t  spare;
    int32_t  k_vel_m;              /* velocity count (10 um/s) */
    int32_t  k_tau_m;              /* steps -> tau q29: tau = n * m / 2^k_tau_sh (w h) */
    int32_t  k_tick_m;             /* tau q29 -> steps: n = tau * m / 2^k_tick_sh (1/(w h)) */
    uint32_t omega_nradps;         /* informative: 1 131 367 */
    uint32_t a_nom_umps2;          /* informative: 40 000 */
    /* valve grid (sub-ticks; equal to the step constants when subtick_us = 0) */
    int32_t  k_gtau_m;             /* grid units -> tau q29: tau = n * m / 2^k_gtau_sh (w delta) */
    int32_t  k_gtick_m;            /* tau q29 -> grid units: n = tau * m / 2^k_gtick_sh */
    uint8_t  k_gtau_sh;
    uint8_t  k_gtick_sh;
    /* thrust-level calibration (spec 50 §5.5) */
    uint8_t  cal_enable;           /* 1: calibrate at every re-plan epoch after the first */
    uint8_t  cal_pool;             /* 1: thrusters without an accepted window take the pooled mean */
    int32_t  dv_cal_min_q28;       /* 0.5 m/s: a window counts for j only above this commanded dv */
    int32_t  cal_gate_q30;         /* 0.2: |alpha_hat - 1| above it discards the window */
    int32_t  u_uncal_q30;          /* 0.03: level uncertainty before calibration */
    int32_t  u_cal_q30;            /* 0.005: after */
    int32_t  miss_flag_q28;        /* 10 m: EXPECTED_MISS when a predicted |dR| exceeds it */
    /* stuck-valve monitor (spec 50 §8) */
    uint32_t fd_window;            /* window W (steps), 10 s */
    int32_t  fd_frac_q30;          /* 0.5 */
    uint8_t  fd_persist;           /* windows in a row, 2 */
    uint8_t  spare2[3];
    /* nav outlier gate (spec 50 §8): |nu| > gate + model allowance discards the sample */
    int32_t  nav_gate_pos_q28;     /* 2.5 m (5 sigma of the degraded profile) */
    int32_t  nav_gate_vel_q28;     /* 25 mm/s */
    int32_t  nav_gate_acc_q28;     /* 1.5 a_nom: one thruster fully off or on, plus level error */
    /* a re-plan replaces the timeline in force only if its predicted post-rounding cost is at most
       (1 - replan_gain) times the cost of keeping it (same state, same metric): 0.5 */
    int32_t  replan_gain_q30;
    uint32_t revision;
} imp_params_t;

/* ------------------------------------------------------------------ solver interface */

/* One terminal problem in nondimensional units. */
typedef struct {
    int32_t tauf_q29;              /* horizon w (t_f - t_a) */
    int32_t x0_q28[IMP_NX];        /* state at the plan epoch */
    int32_t xt_q28[IMP_NX];        /* target state at t_f */
    int32_t alpha_q30[IMP_NTHR];   /* thrust factors in use */
    uint8_t warm_mask;             /* bit s: warm start for subsystem s (re-plans) */
    uint8_t replan;                /* 1: re-plan: rho is reported but not gated (late re-plans of a
                                      feasible plan naturally have rho near 1) */
    uint8_t warm_pattern;          /* 6-bit polarity pattern of the warm start */
    uint8_t thr_off;               /* thrusters to avoid (bit j): patterns using one are never
                                      tried (0: all available) */
    int32_t warm_t1_q29[IMP_NAX];
    int32_t warm_t2_q29[IMP_NAX];
} imp_problem_t;

typedef struct {
    uint8_t  outcome;              /* IMP_SOL_* of the whole plan */
    uint8_t  pattern;              /* 6-bit polarity pattern */
    uint8_t  marginal;             /* rho_warn < rho_max <= rho_reject */
    uint8_t  how[IMP_NSUB];        /* IMP_HOW_* per subsystem */
    uint8_t  iters[IMP_NSUB];      /* iterations of the accepted attempt */
    uint8_t  sub_outcome[IMP_NSUB];
    uint8_t  last_fail[IMP_NSUB];  /* cause of the last failed attempt */
    uint16_t attempts[IMP_NSUB];
    uint16_t n_fail[IMP_FAIL_N]; /* per-cause counters over the plan */
    uint16_t iters_total;
    int32_t  t1_q29[IMP_NAX];
    int32_t  t2_q29[IMP_NAX];
    int32_t  fres_lsb[IMP_NSUB];   /* final max |F_i| of the accepted attempt, q28 LSB */
    int32_t  dv_q28[IMP_NSUB];     /* sum of alpha (T1 + tau_f - T2) per subsystem */
    int32_t  dv1_q28[IMP_NAX];     /* impulsive signed dv at t0, per axis */
    int32_t  dv2_q28[IMP_NAX];     /* impulsive signed dv at t_f, per axis */
    int32_t  rho_q28[IMP_NAX];
    fx_status_t st_ok;             /* fx status outside failed attempts (expected 0) */
    fx_status_t st_fail;           /* fx status seen inside failed attempts */
} imp_solution_t;

/* Derived trig of one angle sigma (spec 50 §4.3), all q30. */
typedef struct {
    int32_t s_q30;      /* sin sigma */
    int32_t c_q30;      /* cos sigma */
    int32_t omc_q30;    /* 1 - cos sigma (= 2 sin^2(sigma/2), cancellation-free) */
    int32_t tms_q30;    /* sigma - sin sigma (series below 0.5) */
} imp_trig_t;

/* Resumable plan job (spec 50 §4.7): where imp_solve_run resumes. */
typedef struct {
    uint8_t  phase;                /* internal phase of the plan */
    uint8_t  sub;                  /* subsystem being solved */
    uint8_t  stage;                /* warm, rule, search, end */
    uint8_t  pat;                  /* search cursor */
    uint8_t  cur;                  /* pattern of the running attempt */
    uint8_t  it;                   /* iteration of the running attempt */
    uint8_t  running;              /* an attempt is in progress */
    uint8_t  how;                  /* how the running attempt's pattern was chosen */
    uint8_t  bad;                  /* the impulsive step could not be formed */
    uint8_t  spare[3];
    uint16_t tried;                /* patterns already tried in this subsystem */
    uint16_t units;                /* work units used by this plan so far */
    fx_status_t ast;               /* fx status of the running attempt */
    fx_status_t pst;               /* fx status of the plan set-up and impulsive solution */
    uint32_t fres;                 /* max |F| of the running attempt's last evaluation */
} imp_job_t;

/* Caller-owned solver workspace (no function needs a large stack frame). */
typedef struct {
    fx_solve_fast_ws_t sws;        /* Newton's solve: the int32 fast path (relative error suffices) */
    int32_t j_q26[16];             /* Jacobian, row-major n x n */
    int32_t f_q28[4];              /* residual */
    int32_t d_q29[4];              /* Newton step */
    int64_t px_q58[IMP_NX];        /* per plan: Phi(tau_f) X0 - X_t */
    int64_t c_q58[4];              /* per attempt: px + sum s1 a1 Psi_r(tau_f) on the subsystem rows */
    int32_t psif_q28[IMP_NAX][4];  /* Psi_r(tau_f) */
    int32_t t1_q29[2];             /* current attempt */
    int32_t t2_q29[2];
    int32_t sa1_q30[2];            /* signed thrust factor per burn */
    int32_t sa2_q30[2];
    int32_t best_t1_q29[2];
    int32_t best_t2_q29[2];
    int32_t best_dv_q28;
    int32_t best_fres;
    uint8_t best_pat;
    uint8_t best_iters;
    uint8_t have_best;
    uint8_t spare;
    int64_t rc_q58[IMP_NAX * 4u][4];  /* rounding: terminal contribution per switch x candidate */
    int64_t rx_q58[2][4];          /* rounding: second-burn contribution of a widened coast, per axis */
    uint32_t rn[IMP_NAX * 4u];     /* rounding: grid position per switch x candidate */
    imp_job_t job;
} imp_ws_t;

/* Result of the best rounding of a schedule onto the valve grid (spec 50 §5.3). Grid units are
   steps when subtick_us = 0, sub-ticks otherwise. */
typedef struct {
    uint32_t n1[IMP_NAX];          /* first burn: grid units [0, n1) from the plan epoch */
    uint32_t n2[IMP_NAX];          /* second burn: [n2, n_total) */
    uint8_t  choice[IMP_NSUB];     /* bit b = 1: ceil for switch b (T1x T2x T1y T2y / T1z T2z) */
    uint8_t  nearest[IMP_NSUB];    /* the nearest-rounding choice, for comparison */
    uint8_t  fixed[IMP_NSUB];      /* bit k: axis k's coast was merged or widened (§5.3) */
    int32_t  miss_q28[IMP_NX];     /* predicted terminal error of the chosen rounding */
    uint64_t cost_q56;             /* |dR|^2 + w_v^2 |dV|^2 of the choice (both subsystems) */
    uint64_t cost_nearest_q56;     /* the same for nearest rounding */
} imp_round_t;

/* Derived trig of sigma (q29, |sigma| < 4). One fx_sincos at sigma/2. */
void imp_trig(int32_t sig_q29, imp_trig_t *t, fx_status_t *st);
/* Psi_r(sigma) on the axis's subsystem rows (4 for x, y; 2 for z), q28. */
void imp_psi(uint32_t axis, int32_t sig_q29, const imp_trig_t *t, int32_t *psi_q28, fx_status_t *st);
/* Phi(sigma) e_r on the axis's subsystem rows, q28. */
void imp_phie(uint32_t axis, int32_t sig_q29, const imp_trig_t *t, int32_t *col_q28, fx_status_t *st);
/* y = Phi(sigma) x for the full 6-state: x q28, y q56 = exact int64 sums of q28 entries (each
   rounded once from q30) times x. The entries are held in int64 because 6 (1 - cos sigma) leaves
   the q28 range above sigma = 1.9106 (8.5 at 2.0); nothing saturates for |sigma| <= 2. */
void imp_phi_apply(int32_t sig_q29, const imp_trig_t *t, const int32_t *x_q28, int64_t *y_q56, fx_status_t *st);

/*
 * Full plan (spec 50 §3.5-3.7): impulsive solution and feasibility gate, then per subsystem
 * warm -> rule -> search. Never fails; the outcome and the reasons go to *sol. All loops are
 * bounded: at most IMP_JOB_UNITS(max_iter) work units. Equal, bit for bit, to imp_solve_begin
 * followed by imp_solve_run calls with any budgets until imp_solve_done.
 */
void imp_solve(imp_ws_t *ws, const imp_params_t *p, const imp_problem_t *pr, imp_solution_t *sol);
/* Resumable form (spec 50 §4.7): begin clears *sol and arms the job; each run performs at most
   `budget` work units (one unit = one residual + Jacobian evaluation and its solve) and returns
   the units used; *pr and *sol must stay untouched between calls. */
void     imp_solve_begin(imp_ws_t *ws, imp_solution_t *sol);
uint32_t imp_solve_run(imp_ws_t *ws, const imp_params_t *p, const imp_problem_t *pr, imp_solution_t *sol,
                       uint32_t budget);
bool     imp_solve_done(const imp_ws_t *ws);

/*
 * One Newton attempt on subsystem sub with the subsystem-local polarity pattern pat, from the
 * times t1, t2 (nax entries), with the guards of spec 50 §3.6. Returns IMP_FAIL_NONE for a valid
 * converged schedule, else the cause. The final (or last) iterate is left in ws->t1_q29 and
 * ws->t2_q29, its residual in ws->f_q28. For tests and diagnostics: imp_solve uses the same path.
 */
uint32_t imp_attempt(imp_ws_t *ws, const imp_params_t *p, const imp_problem_t *pr, uint32_t sub, uint32_t pat,
                     const int32_t *t1_q29, const int32_t *t2_q29, uint32_t *iters, uint32_t *fres_lsb,
                     fx_status_t *ast);

/*
 * Best rounding (spec 50 §5.3) of a VALID solution onto the valve grid (whole steps, or sub-ticks
 * of subtick_us), for a plan epoch t_a and n_total grid units to t_f (pr->tauf_q29 must be
 * n_total grid units). Each interior switching time has a floor and a ceil candidate; a candidate
 * that makes a burn shorter than t_min is replaced by its executable neighbour in the same
 * direction (length 0 or t_min rounded up to the grid). A coast that would put two windows of
 * one thruster into one step, or is shorter than t_min, is merged (same thruster); one that would
 * put both thrusters of an axis into one step is widened to the next step boundary (opposite
 * thrusters). The terminal error of a choice is the solver's residual plus one exactly
 * precomputed vector per switch and candidate, so all 16 (x-y) and 4 (z) choices are scored with
 * the same exact kernels; the lowest cost |dR|^2 + w_v^2 |dV|^2 wins, ties to the lower index.
 * Needs ws as left by imp_solve for that problem.
 */
void imp_round_best(imp_ws_t *ws, const imp_params_t *p, const imp_problem_t *pr, const imp_solution_t *sol,
                    uint32_t n_total, imp_round_t *rd, fx_status_t *st);

/* ------------------------------------------------------------------ module interface */

typedef struct {
    uint32_t step;                 /* step index k */
    /* relative-navigation sample (spec 50 §2.5) */
    int32_t  nav_pos_mm[IMP_NAX];  /* (x, y, z), 1 mm */
    int32_t  nav_vel_cnt[IMP_NAX]; /* (x', y', z'), 10 um/s */
    uint32_t nav_step;             /* step index of the sample */
    uint8_t  nav_valid;
    uint8_t  cmd;                  /* IMP_CMD_* */
    uint8_t  avail_mask;           /* thrusters available (bit j) */
    uint8_t  spare;
    uint32_t cmd_t0_step;
    uint32_t cmd_tf_step;
    int32_t  cmd_tgt_pos_mm[IMP_NAX];
    int32_t  cmd_tgt_vel_cnt[IMP_NAX];
} imp_in_t;

/* Telemetry (spec 50 §8). Delta-v and times are nondimensional (q28 velocity a_nom/w, q29 rad). */
typedef struct {
    uint32_t plans;                /* plan jobs started (START and re-plans) */
    uint32_t plans_failed;         /* plans that found no valid schedule (or infeasible) */
    uint32_t plans_late;           /* plans unfinished at their application epoch */
    uint32_t plans_skipped;        /* re-plan epochs without a usable nav sample (or busy) */
    uint32_t cmd_rej;
    uint32_t nav_rej;              /* samples discarded by the outlier gate */
    uint32_t cal_rej;              /* calibration windows discarded by cal_gate (THRUST_LEVEL) */
    uint32_t plans_kept;           /* valid re-plans not applied: no gain over the timeline in force */
    uint32_t n_fail[IMP_FAIL_N]; /* attempt failures per cause, over all plans */
    uint8_t  mode;
    uint8_t  rej_reason;           /* IMP_REJ_* of the last refused command */
    uint8_t  how_xy;
    uint8_t  how_z;
    uint8_t  pattern;
    uint8_t  iters_xy;
    uint8_t  iters_z;
    uint8_t  last_fail_xy;
    uint8_t  last_fail_z;
    uint8_t  stuck_j;              /* thruster of the latest STUCK_* (0xFF: none) */
    uint8_t  stuck_off_mask;       /* thrusters marked unavailable by the monitor */
    uint8_t  job_active;           /* a plan job is running */
    uint16_t plan_units;           /* work units of the last finished plan */
    uint16_t plan_steps;           /* steps it took */
    int32_t  fres_lsb[IMP_NSUB];   /* final max |F| of the accepted attempts, q28 LSB */
    int32_t  t1_q29[IMP_NAX];
    int32_t  t2_q29[IMP_NAX];
    uint32_t on1_step[IMP_NAX];    /* rounded switching steps (absolute): the step holding the end of
                                      the first burn ... */
    uint32_t on2_step[IMP_NAX];    /* ... and the start of the second burn */
    uint32_t on1_us[IMP_NAX];      /* offsets of those switches within their steps */
    uint32_t on2_us[IMP_NAX];
    int32_t  miss_q28[IMP_NX];     /* predicted terminal error after rounding */
    uint8_t  round_choice[IMP_NSUB];
    uint8_t  spare2[2];
    int32_t  rho_q28[IMP_NAX];
    int32_t  dv1_q28[IMP_NAX];     /* impulsive dv per axis (at t_a and at t_f) */
    int32_t  dv2_q28[IMP_NAX];
    int32_t  dv_cmd_q28[IMP_NTHR]; /* commanded so far: on-time at the nominal level */
    int32_t  dv_used_q28[IMP_NTHR];/* used so far: on-time x alpha_j (the calibrated estimate) */
    int32_t  alpha_q30[IMP_NTHR];  /* thrust factors in force */
    uint16_t cal_windows[IMP_NTHR];/* accepted calibration windows per thruster */
    int32_t  nu_q28[IMP_NAX];      /* last calibration innovation (x', y', z') */
    int32_t  exp_dr_q28[IMP_NAX];  /* predicted uncorrectable miss per axis (spec 50 §5.5) */
    int32_t  exp_dv_q28[IMP_NAX];
    uint32_t nav_age;              /* steps since the latest accepted nav sample */
    fx_status_t st_step;           /* fx status of this step */
    fx_status_t st_sticky;         /* OR of st_step since init / CLEAR_FAULTS */
    uint32_t health_sticky;
    uint32_t revision;
} imp_tlm_t;

typedef struct {
    uint8_t   on_mask;                     /* bit j: thruster j on in this step */
    uint8_t   spare[3];
    uint32_t  on_start_cnt[IMP_NTHR];      /* valve-timer counts (1 us) within the step */
    uint32_t  on_len_cnt[IMP_NTHR];
    uint32_t  health;                      /* bits 0-7 fx status of this step; 8-31 IMP_H_* */
    imp_tlm_t tlm;
} imp_out_t;

/* A committed timeline: plan epoch t_a, thrusters and grid switching positions per axis
   (relative to t_a), and the continuous solution it came from (warm start of the next plan). */
typedef struct {
    uint32_t ta_step;
    uint32_t ntot_g;                       /* grid units from t_a to t_f */
    uint32_t n1_g[IMP_NAX];                /* first burn: [0, n1) grid units from t_a */
    uint32_t n2_g[IMP_NAX];                /* second burn: [n2, ntot) */
    int32_t  t1_q29[IMP_NAX];              /* solution times relative to t_a */
    int32_t  t2_q29[IMP_NAX];
    uint8_t  thr1[IMP_NAX];
    uint8_t  thr2[IMP_NAX];
    uint8_t  pattern;
    uint8_t  valid;
} imp_timeline_t;

/* A navigation sample in the module's units. */
typedef struct {
    uint32_t step;                         /* step index of the sample */
    int32_t  x_q28[IMP_NX];                /* nondimensional state */
    uint8_t  valid;
    uint8_t  spare[3];
} imp_nav_t;

/* Commanded burns (after the interlock and availability gates), absolute grid positions. */
typedef struct {
    uint64_t s_g[IMP_LOG_CAP];             /* segment start */
    uint64_t e_g[IMP_LOG_CAP];             /* segment end (exclusive) */
    uint64_t lost_g;                       /* history before this position is incomplete */
    uint8_t  thr[IMP_LOG_CAP];
    uint8_t  n;
    uint8_t  spare[7];
} imp_log_t;

/* Response of the commanded burns over a window [k1, k2] (evaluated at k2). */
typedef struct {
    int64_t  r_q28[IMP_NTHR][IMP_NX];      /* per thruster, per unit alpha, signed: full state */
    uint64_t on_g[IMP_NTHR];               /* commanded on-time in the window, grid units */
    int32_t  xp_q28[IMP_NX];               /* predicted state at the window end */
    int32_t  m_q28[IMP_NX];                /* measured - predicted (innovation) at the window end */
} imp_win_t;

/* Thrust-level calibration (spec 50 §5.5). */
typedef struct {
    imp_nav_t ref;                         /* previous epoch's sample (valid = 0: paused) */
    int64_t  sum_w_q24[IMP_NTHR];          /* sum of |g_j|^2 over accepted windows */
    uint64_t sum_wa_q54[IMP_NTHR];         /* sum of |g_j|^2 alpha_hat_j */
    uint16_t n_acc[IMP_NTHR];              /* accepted windows */
    int32_t  alpha_q30[IMP_NTHR];          /* thrust factors in force */
    fx_solve_ws_t sws;
    int32_t  a_q[9];                       /* normal equations (block-scaled) */
    int32_t  b_q[3];
    int32_t  x_q30[3];
    int64_t  a_q56[9];                     /* scratch: the exact normal equations */
    int64_t  b_q56[3];
    int32_t  g_q28[3][IMP_NAX];            /* scratch: velocity responses of the unknowns */
} imp_cal_t;

/* Stuck-valve monitor (spec 50 §8). */
typedef struct {
    imp_nav_t x0;                          /* window start sample */
    uint8_t  cnt_off[IMP_NTHR];            /* windows in a row with stuck-off evidence */
    uint8_t  cnt_on[IMP_NTHR];             /* windows in a row with stuck-on evidence */
    uint8_t  stuck_off;                    /* thrusters marked unavailable */
    uint8_t  spare[3];
} imp_fd_t;

typedef struct {
    uint8_t  mode;
    uint8_t  job_kind;                     /* none, START plan, re-plan, stuck-off re-plan */
    uint8_t  job_solved;                   /* the running job's solve has finished */
    uint8_t  retry;                        /* a skipped epoch waits for the next fresh sample */
    uint8_t  marginal;                     /* the START plan was MARGINAL */
    uint8_t  nav_seen;                     /* a sample has been examined ... */
    uint8_t  spare[2];
    uint32_t nav_seen_step;                /* ... with this step tag */
    uint32_t latched;                      /* THRUST_LEVEL, STUCK_* until CLEAR_FAULTS */
    uint32_t t0_step;
    uint32_t tf_step;
    uint32_t next_tp;                      /* next re-plan epoch */
    uint32_t job_ta;                       /* application epoch of the running job */
    uint32_t job_t_start;                  /* step the running job started */
    uint64_t on_tot_g[IMP_NTHR];           /* commanded on-time since START, grid units */
    uint64_t keep_cost_q56;                /* predicted cost of keeping the timeline (running re-plan) */
    /* The inputs of the per-thruster telemetry (dv_cmd, dv_used) when it was last computed, and the
       fx status of that computation: it is recomputed only when one of them changed (imp.c). */
    uint64_t tlm_on_g[IMP_NTHR];
    int32_t  tlm_alpha_q30[IMP_NTHR];
    int32_t  tlm_k_gtau_m;
    uint8_t  tlm_k_gtau_sh;
    uint8_t  tlm_thr_valid;                /* bit j: thruster j's cached inputs are meaningful */
    uint8_t  tlm_thr_st[IMP_NTHR];
    imp_timeline_t act;                    /* timeline in force */
    imp_timeline_t pend;                   /* re-plan waiting for its t_a */
    imp_nav_t nav;                         /* latest accepted nav sample */
    imp_log_t log;
    imp_win_t win;
    imp_cal_t cal;
    imp_fd_t fd;
    imp_problem_t prob;
    imp_solution_t sol;
    imp_round_t rd;
    imp_ws_t ws;
    imp_tlm_t tlm;                         /* counters and sticky health live here */
} imp_state_t;

fsw_rc_t imp_params_check(const imp_params_t *p, uint32_t *why);
fsw_rc_t imp_init(imp_state_t *s, const imp_params_t *p, imp_out_t *out);
void     imp_step(imp_state_t *s, const imp_params_t *p, const imp_in_t *in, imp_out_t *out);

#endif /* FSW_IMP_H */
