/*
 * imp_nav.c — navigation side of the impulse scheduler (spec 50-impulse §5.4, §5.5, §8):
 * nav counts to the module's state, the pruning of the log of commanded burns (imp_log.c), the
 * prediction of a sample through the commanded burns (exact Phi / Psi in q28, alpha in force),
 * the nav outlier gate, the stuck-valve monitor and the thrust-level calibration.
 *
 * Prediction. For a window [k1, k2] (sample steps) and thruster j, R_j is the response at k2 of
 * j's commanded on-intervals inside the window per unit alpha (signed, full state):
 * R_j = sum_seg s_j (Psi_r(k2 - a) - Psi_r(k2 - b)); the prediction is
 * X(k2) = Phi(k2 - k1) X(k1) + sum_j alpha_j R_j, and m = X_nav(k2) - X(k2).
 *
 * Monitor (spec 50 §8), per window of fd_window steps between accepted samples, with
 * g_j the velocity rows of R_j and m the velocity innovation:
 *  - stuck-off evidence for j commanded on >= W/2: the measured response along g_j,
 *    g_j . (m + alpha_j g_j), is below fd_frac of the expected alpha_j |g_j|^2;
 *  - stuck-on evidence for j commanded off over the whole window: the innovation projected on
 *    j's full-window response gf_j exceeds fd_frac |gf_j|^2 (acceleration > fd_frac a_nom) when
 *    the axis twin was off too; with the twin on for a fraction f_t, "twin stuck off" would give
 *    f_t, so the threshold moves to f_t + fd_frac (1 - f_t); above f_t = 3/4 the two cannot be
 *    told apart and only the twin's stuck-off test runs;
 *  fd_persist windows in a row raise the fault; STUCK_ON has priority over STUCK_OFF.
 *
 * Calibration (spec 50 §5.5): between epoch samples, at most one unknown per axis (the thruster
 * with the larger commanded on-time, if its commanded delta-v reaches dv_cal_min); normal
 * equations G^T G da = G^T nu, block-scaled to q28 and solved by fx_solve (n <= 3); the window is
 * discarded (THRUST_LEVEL) if any |alpha_hat - 1| > cal_gate; else alpha_j = sum w alpha_hat /
 * sum w with w = |g_j|^2; thrusters without an accepted window take the pooled mean (cal_pool).
 */
#include "imp_int.h"

#define SH_Q56_Q36    20u                   /* dot products q56 -> q36 (monitor) */
#define SH_Q56_Q24    32u                   /* |g|^2 q56 -> q24 (calibration weight) */
#define SH_ACC_TO_X   30u                   /* q58 -> q28 */
#define SH_XX_TO_ACC  2u                    /* q56 -> q58 */
#define CAL_NORM      INT64_C(268435456)    /* block scale: largest diagonal below 2^28 */
#define CAL_PIVOT_MIN INT32_C(65536)        /* 2^16: 2^-12 of the largest diagonal */
#define CAL_SH_MAX    48u                   /* bound of the block-scale search */
#define CAL_Q         28u                   /* nominal format handed to fx_solve (relative) */
FX_STATIC_ASSERT(imp_nav_sa_one30, FX_Q_RAT_FITS(1, 1, 30));

/* Position and velocity rows of axis i in the full state. */
static uint32_t prow(uint32_t i)
{
    return 2u * i;
}

static uint32_t vrow(uint32_t i)
{
    return (2u * i) + 1u;
}

bool imp_nav_convert(const imp_params_t *p, const int32_t *pos_mm, const int32_t *vel_cnt, imp_nav_t *nv)
{
    fx_status_t st = 0u;
    uint32_t r;
    for (r = 0u; r < IMP_NAX; r++) {
        nv->x_q28[prow(r)] = fx_from_count(pos_mm[r], p->k_pos_m, p->k_pos_sh, 0, &st);
        nv->x_q28[vrow(r)] = fx_from_count(vel_cnt[r], p->k_vel_m, p->k_vel_sh, 0, &st);
    }
    return st == 0u;
}

static bool log_covers(const imp_state_t *s, const imp_params_t *p, uint32_t k)
{
    return ((uint64_t)k * (uint64_t)imp_grid(p)) >= s->log.lost_g;
}

bool imp_nav_fresh(const imp_state_t *s, const imp_params_t *p, uint32_t k)
{
    return (s->nav.valid != 0u) && (s->nav.step <= k) && ((k - s->nav.step) <= p->nav_timeout) &&
           log_covers(s, p, s->nav.step);
}

void imp_win_clear(imp_win_t *w)
{
    uint32_t j;
    uint32_t i;
    for (j = 0u; j < IMP_NTHR; j++) {
        for (i = 0u; i < IMP_NX; i++) {
            w->r_q28[j][i] = 0;
        }
        w->on_g[j] = 0u;
    }
    for (i = 0u; i < IMP_NX; i++) {
        w->xp_q28[i] = 0;
        w->m_q28[i] = 0;
    }
}

/* Drop the segments that no window can reach any more (before every reference sample). */
static void log_prune(imp_state_t *s, const imp_params_t *p)
{
    uint64_t g = (uint64_t)imp_grid(p);
    uint64_t ref = (uint64_t)s->nav.step * g;
    uint32_t i;
    uint32_t n = 0u;
    if ((s->fd.x0.valid != 0u) && (((uint64_t)s->fd.x0.step * g) < ref)) {
        ref = (uint64_t)s->fd.x0.step * g;
    }
    if ((s->cal.ref.valid != 0u) && (((uint64_t)s->cal.ref.step * g) < ref)) {
        ref = (uint64_t)s->cal.ref.step * g;
    }
    for (i = 0u; (i < (uint32_t)s->log.n) && (i < IMP_LOG_CAP); i++) {
        if (s->log.e_g[i] > ref) {
            s->log.s_g[n] = s->log.s_g[i];
            s->log.e_g[n] = s->log.e_g[i];
            s->log.thr[n] = s->log.thr[i];
            n++;
        }
    }
    s->log.n = (uint8_t)n;
}

/* xp = Phi(tau(dg)) x1 + sum_j alpha_j R_j (q28), R_j from s->win. */
static void nav_predict(imp_state_t *s, const imp_params_t *p, const int32_t *x1_q28, uint64_t dg, int32_t *xp_q28,
                    fx_status_t *st)
{
    imp_trig_t t;
    int64_t acc[IMP_NX];
    uint32_t i;
    uint32_t j;
    int32_t sig = imp_g2tau(p, dg, st);
    imp_trig(sig, &t, st);
    imp_phi_apply(sig, &t, x1_q28, acc, st);
    for (i = 0u; i < IMP_NX; i++) {
        acc[i] = fx_shl64_chk(acc[i], SH_XX_TO_ACC, st);
        for (j = 0u; j < IMP_NTHR; j++) {
            int32_t r = fx_sat32(s->win.r_q28[j][i], st);
            acc[i] = fx_add64_sat(acc[i], (int64_t)s->cal.alpha_q30[j] * (int64_t)r, st);
        }
        xp_q28[i] = fx_rshift_sat(acc[i], SH_ACC_TO_X, st);
    }
}

void imp_propagate(imp_state_t *s, const imp_params_t *p, const imp_nav_t *nv, uint32_t now, uint32_t ta,
                   bool use_tl, int32_t *x_q28, fx_status_t *st)
{
    uint64_t g = (uint64_t)imp_grid(p);
    uint64_t k1g = (uint64_t)nv->step * g;
    uint64_t nowg = (uint64_t)now * g;
    uint64_t teg = (uint64_t)ta * g;
    imp_win_clear(&s->win);
    imp_log_response(s, p, k1g, nowg, teg, st);
    if (use_tl) {
        imp_tl_response(s, p, &s->act, nowg, teg, teg, st);
    }
    nav_predict(s, p, nv->x_q28, teg - k1g, x_q28, st);
}

uint64_t imp_keep_cost(imp_state_t *s, const imp_params_t *p, uint32_t ta, fx_status_t *st)
{
    uint64_t g = (uint64_t)imp_grid(p);
    uint64_t tag = (uint64_t)ta * g;
    uint64_t teg = (uint64_t)s->tf_step * g;
    int32_t xe[IMP_NX];
    uint64_t cost = 0u;
    uint32_t i;
    imp_win_clear(&s->win);
    imp_tl_response(s, p, &s->act, tag, teg, teg, st);
    nav_predict(s, p, s->prob.x0_q28, teg - tag, xe, st);
    for (i = 0u; i < IMP_NX; i++) {
        int32_t e = fx_sub_sat(xe[i], s->prob.xt_q28[i], st);
        int64_t e2;
        if ((i & 1u) != 0u) {
            e = fx_mul(e, IMP_X_Q, p->w_v_q28, IMP_X_Q, IMP_X_Q, st);
        }
        e2 = (int64_t)e * (int64_t)e;
        cost = (cost > (UINT64_MAX - (uint64_t)e2)) ? UINT64_MAX : (cost + (uint64_t)e2);
    }
    return cost;
}

/* Window [a, b] between two samples: responses, prediction and innovation into s->win. */
static void window(imp_state_t *s, const imp_params_t *p, const imp_nav_t *a, const imp_nav_t *b, fx_status_t *st)
{
    uint64_t g = (uint64_t)imp_grid(p);
    uint64_t k1g = (uint64_t)a->step * g;
    uint64_t k2g = (uint64_t)b->step * g;
    uint32_t i;
    imp_win_clear(&s->win);
    imp_log_response(s, p, k1g, k2g, k2g, st);
    nav_predict(s, p, a->x_q28, k2g - k1g, s->win.xp_q28, st);
    for (i = 0u; i < IMP_NX; i++) {
        s->win.m_q28[i] = fx_sub_sat(b->x_q28[i], s->win.xp_q28[i], st);
    }
}

/* Outlier gate (spec 50 §8): per axis, |m| <= gate + allowance, the allowance being what one
   thruster fully on or off (nav_gate_acc) adds over the span: dv = a dtau, dr = a dtau^2 / 2.
   Any fx status in the test (a wildly wrong sample) rejects it. */
static bool gate_ok(imp_state_t *s, const imp_params_t *p, const imp_nav_t *c)
{
    fx_status_t st = 0u;
    fx_status_t lst = 0u;         /* a limit that saturates is simply no limit */
    bool ok = true;
    if ((s->nav.valid != 0u) && log_covers(s, p, s->nav.step)) {
        uint32_t r;
        uint64_t span = (uint64_t)(c->step - s->nav.step) * (uint64_t)imp_grid(p);
        int32_t dtau = imp_g2tau(p, span, &lst);
        int32_t dv = fx_mul(p->nav_gate_acc_q28, IMP_X_Q, dtau, IMP_T_Q, IMP_X_Q, &lst);
        int32_t dr = fx_mul(dv, IMP_X_Q, dtau, IMP_T_Q, IMP_X_Q - 1u, &lst);
        int32_t lim_p = fx_add_sat(p->nav_gate_pos_q28, dr, &lst);
        int32_t lim_v = fx_add_sat(p->nav_gate_vel_q28, dv, &lst);
        window(s, p, &s->nav, c, &st);
        for (r = 0u; r < IMP_NAX; r++) {
            if ((fx_uabs(s->win.m_q28[prow(r)]) > (uint32_t)lim_p) || (fx_uabs(s->win.m_q28[vrow(r)]) > (uint32_t)lim_v)) {
                ok = false;
            }
        }
        ok = ok && (st == 0u);
    }
    return ok;
}

/* 3-vector dot product of velocity rows (q28 x q28 = q56), as q(56 - sh). */
static int64_t vdot(const int32_t *a, const int32_t *b, uint32_t sh, fx_status_t *st)
{
    int64_t acc = 0;
    uint32_t i;
    for (i = 0u; i < IMP_NAX; i++) {
        acc = fx_add64_sat(acc, (int64_t)a[i] * (int64_t)b[i], st);
    }
    return fx_shr_rnd64(acc, sh, st);
}

/* Velocity rows of thruster j's window response (q28). */
static void resp_vel(const imp_state_t *s, uint32_t j, int32_t *g, fx_status_t *st)
{
    uint32_t i;
    for (i = 0u; i < IMP_NAX; i++) {
        g[i] = fx_sat32(s->win.r_q28[j][vrow(i)], st);
    }
}

static void innov_vel(const imp_state_t *s, int32_t *m)
{
    uint32_t i;
    for (i = 0u; i < IMP_NAX; i++) {
        m[i] = s->win.m_q28[vrow(i)];
    }
}

/* v * f (f q30, v >= 0 small enough: q36 products of the monitor). */
static int64_t frac_of(int64_t v, int32_t f_q30, fx_status_t *st)
{
    return fx_shr_rnd64(v * (int64_t)f_q30, IMP_ALPHA_Q, st);
}

/* Stuck-off evidence of j (commanded on >= W/2). */
static bool evid_off(const imp_state_t *s, const imp_params_t *p, uint32_t j, fx_status_t *st)
{
    int32_t g[IMP_NAX];
    int32_t m[IMP_NAX];
    int64_t gg;
    bool e = false;
    resp_vel(s, j, g, st);
    innov_vel(s, m);
    gg = vdot(g, g, SH_Q56_Q36, st);
    if (gg > 0) {
        int64_t expd = frac_of(gg, s->cal.alpha_q30[j], st);
        int64_t meas = fx_add64_sat(vdot(g, m, SH_Q56_Q36, st), expd, st);
        e = meas < frac_of(expd, p->fd_frac_q30, st);
    }
    return e;
}

/* Stuck-on evidence of j (commanded off over the whole window of sig_q29). The innovation
   projected on j's full-window response gf (per |gf|^2) is 1 if j is stuck on; if instead the
   twin (commanded on for part of the window) is stuck off, it is f_t, the twin's expected
   response projected likewise. Evidence when the projection exceeds f_t + fd_frac (1 - f_t)
   (fd_frac itself with a quiet twin); with f_t above 3/4 the two cannot be told apart, and the
   twin's stuck-off test decides. */
static bool evid_on(const imp_state_t *s, const imp_params_t *p, uint32_t j, int32_t sig_q29, fx_status_t *st)
{
    imp_trig_t t;
    int32_t v[4] = {0, 0, 0, 0};
    int32_t gf[IMP_NAX] = {0, 0, 0};
    int32_t gt[IMP_NAX];
    int32_t m[IMP_NAX];
    uint32_t r = j / 2u;
    int64_t ff;
    bool e = false;
    imp_trig(sig_q29, &t, st);
    imp_psi(r, sig_q29, &t, v, st);
    if (r == 2u) {
        gf[2] = v[1];
    } else {
        gf[0] = v[1];
        gf[1] = v[3];
    }
    if ((j & 1u) != 0u) {
        uint32_t i;
        for (i = 0u; i < IMP_NAX; i++) {
            gf[i] = fx_neg(gf[i], st);
        }
    }
    innov_vel(s, m);
    resp_vel(s, j ^ 1u, gt, st);
    ff = vdot(gf, gf, SH_Q56_Q36, st);
    if (ff > 0) {
        int64_t ft = -frac_of(vdot(gt, gf, SH_Q56_Q36, st), s->cal.alpha_q30[j ^ 1u], st);
        ft = (ft < 0) ? 0 : ft;
        if (ft <= (ff - (ff / 4))) {
            int64_t thr = ft + frac_of(ff - ft, p->fd_frac_q30, st);
            e = vdot(gf, m, SH_Q56_Q36, st) > thr;
        }
    }
    return e;
}

static uint8_t cnt_step(uint8_t c, bool e)
{
    uint8_t r = 0u;
    if (e) {
        r = (c < 0xFFu) ? (uint8_t)(c + 1u) : c;
    }
    return r;
}

/* Evidence of every thruster over the window in s->win, counters, event. */
static uint32_t fd_evaluate(imp_state_t *s, const imp_params_t *p, uint32_t span, fx_status_t *st)
{
    uint64_t half = ((uint64_t)p->fd_window * (uint64_t)imp_grid(p)) / 2u;
    int32_t sig = imp_g2tau(p, (uint64_t)span * (uint64_t)imp_grid(p), st);
    uint32_t ev = IMP_EV_NONE;
    uint32_t j;
    for (j = 0u; j < IMP_NTHR; j++) {
        bool eo = false;
        bool en = false;
        if (s->win.on_g[j] >= half) {
            eo = evid_off(s, p, j, st);
        } else if (s->win.on_g[j] == 0u) {
            en = evid_on(s, p, j, sig, st);
        } else {
            /* partly commanded: no test */
        }
        s->fd.cnt_off[j] = cnt_step(s->fd.cnt_off[j], eo);
        s->fd.cnt_on[j] = cnt_step(s->fd.cnt_on[j], en);
    }
    for (j = IMP_NTHR; j > 0u; j--) {
        uint32_t k = j - 1u;
        if ((s->fd.cnt_off[k] >= p->fd_persist) && ((((uint32_t)s->fd.stuck_off >> k) & 1u) == 0u)) {
            ev = IMP_EV_STUCK_OFF | k;
        }
    }
    for (j = IMP_NTHR; j > 0u; j--) {
        uint32_t k = j - 1u;
        if (s->fd.cnt_on[k] >= p->fd_persist) {
            ev = IMP_EV_STUCK_ON | k;
        }
    }
    return ev;
}

/* Monitor window ending at the newly accepted sample. */
static uint32_t fd_step(imp_state_t *s, const imp_params_t *p)
{
    uint32_t ev = IMP_EV_NONE;
    uint32_t span = s->nav.step - s->fd.x0.step;
    if ((s->fd.x0.valid == 0u) || (!log_covers(s, p, s->fd.x0.step)) || (s->nav.step < s->fd.x0.step) ||
        (span > (2u * p->fd_window))) {
        s->fd.x0 = s->nav;                       /* (re)start, or paused by a nav gap */
    } else if (span >= p->fd_window) {
        fx_status_t st = 0u;
        window(s, p, &s->fd.x0, &s->nav, &st);
        if (st == 0u) {
            ev = fd_evaluate(s, p, span, &st);
        }
        if (st != 0u) {
            ev = IMP_EV_NONE;                    /* not evaluable: no evidence either way */
        }
        s->fd.x0 = s->nav;
    } else {
        /* window still open */
    }
    return ev;
}

bool imp_active(uint32_t mode)
{
    return (mode == IMP_MODE_PLANNING) || (mode == IMP_MODE_ARMED) || (mode == IMP_MODE_FIRING) ||
           (mode == IMP_MODE_FINAL);
}

uint32_t imp_nav_intake(imp_state_t *s, const imp_params_t *p, const imp_in_t *in)
{
    uint32_t ev = IMP_EV_NONE;
    bool fresh = (s->nav_seen == 0u) || (in->nav_step > s->nav_seen_step);
    if ((in->nav_valid != 0u) && (in->nav_step <= in->step) && fresh &&
        ((s->nav.valid == 0u) || (in->nav_step > s->nav.step))) {
        imp_nav_t c;
        bool act = imp_active(s->mode);
        bool ok;
        c.step = in->nav_step;
        c.valid = 1u;
        c.spare[0] = 0u;
        c.spare[1] = 0u;
        c.spare[2] = 0u;
        s->nav_seen = 1u;             /* each sample is examined once */
        s->nav_seen_step = in->nav_step;
        ok = imp_nav_convert(p, in->nav_pos_mm, in->nav_vel_cnt, &c);
        if (ok && act) {
            ok = gate_ok(s, p, &c);
        }
        if (!ok) {
            fx_cnt_inc(&s->tlm.nav_rej);
        } else {
            s->nav = c;
            if (act) {
                ev = fd_step(s, p);
            }
            log_prune(s, p);
        }
    }
    return ev;
}

/* ------------------------------------------------------------------ calibration */

/* alpha_j = sum w alpha_hat / sum w; without a window: the pooled mean (cal_pool) or the table. */
static void cal_update(imp_state_t *s, const imp_params_t *p)
{
    uint64_t sw = 0u;
    uint64_t swa = 0u;
    uint32_t j;
    for (j = 0u; j < IMP_NTHR; j++) {
        sw += (uint64_t)s->cal.sum_w_q24[j];
        swa += s->cal.sum_wa_q54[j];
    }
    for (j = 0u; j < IMP_NTHR; j++) {
        uint64_t a = (uint64_t)(uint32_t)p->alpha_q30[j];
        if ((s->cal.n_acc[j] != 0u) && (s->cal.sum_w_q24[j] > 0)) {
            a = fx_udiv_rnd64(s->cal.sum_wa_q54[j], (uint64_t)s->cal.sum_w_q24[j]);
        } else if ((p->cal_pool != 0u) && (sw > 0u)) {
            a = fx_udiv_rnd64(swa, sw);
        } else {
            /* table value */
        }
        s->cal.alpha_q30[j] = (a > (uint64_t)INT32_MAX) ? INT32_MAX : (int32_t)a;
    }
}

/* Unknowns of the window: per axis the thruster with the larger commanded on-time, if its
   commanded delta-v reaches dv_cal_min. Returns their number, thrusters in unk[]. */
static uint32_t cal_unknowns(const imp_state_t *s, const imp_params_t *p, uint32_t *unk, fx_status_t *st)
{
    uint32_t n = 0u;
    uint32_t r;
    for (r = 0u; r < IMP_NAX; r++) {
        uint32_t j = 2u * r;
        int32_t dv;
        j = (s->win.on_g[j + 1u] > s->win.on_g[j]) ? (j + 1u) : j;
        dv = fx_shr_rnd(imp_g2tau(p, s->win.on_g[j], st), IMP_T_Q - IMP_X_Q, st);   /* q29 -> q28 */
        if ((s->win.on_g[j] > 0u) && (dv >= p->dv_cal_min_q28)) {
            unk[n] = j;
            n++;
        }
    }
    return n;
}

/* Normal equations of the unknowns, block-scaled so that the largest diagonal is below 2^28. */
static void cal_normal(imp_state_t *s, const uint32_t *unk, uint32_t n, fx_status_t *st)
{
    int64_t *a = s->cal.a_q56;
    int64_t *b = s->cal.b_q56;
    int64_t dmax = 0;
    int32_t m[IMP_NAX];
    uint32_t u;
    uint32_t v;
    uint32_t sh = 0u;
    innov_vel(s, m);
    for (u = 0u; u < n; u++) {
        resp_vel(s, unk[u], s->cal.g_q28[u], st);
    }
    for (u = 0u; u < n; u++) {
        for (v = 0u; v < n; v++) {
            a[(u * n) + v] = vdot(s->cal.g_q28[u], s->cal.g_q28[v], 0u, st);
        }
        b[u] = vdot(s->cal.g_q28[u], m, 0u, st);
        dmax = (a[(u * n) + u] > dmax) ? a[(u * n) + u] : dmax;
    }
    while ((sh < CAL_SH_MAX) && (((uint64_t)dmax >> sh) >= (uint64_t)CAL_NORM)) {
        sh++;
    }
    for (u = 0u; u < n; u++) {
        for (v = 0u; v < n; v++) {
            s->cal.a_q[(u * n) + v] = fx_rshift_sat(a[(u * n) + v], sh, st);
        }
        s->cal.b_q[u] = fx_rshift_sat(b[u], sh, st);
    }
}

/* Accept the window's estimates alpha_j + da_j with weights |g_j|^2. */
static void cal_accept(imp_state_t *s, const uint32_t *unk, uint32_t n, const int32_t *ah_q30, fx_status_t *st)
{
    uint32_t u;
    for (u = 0u; u < n; u++) {
        uint32_t j = unk[u];
        int32_t g[IMP_NAX];
        int64_t w;
        resp_vel(s, j, g, st);
        w = vdot(g, g, SH_Q56_Q24, st);
        if ((w > 0) && (ah_q30[u] > 0)) {
            s->cal.sum_w_q24[j] = fx_add64_sat(s->cal.sum_w_q24[j], w, st);
            s->cal.sum_wa_q54[j] += (uint64_t)w * (uint64_t)(uint32_t)ah_q30[u];
            if (s->cal.n_acc[j] < 0xFFFFu) {
                s->cal.n_acc[j]++;
            }
        }
    }
}

uint32_t imp_cal_epoch(imp_state_t *s, const imp_params_t *p)
{
    uint32_t h = 0u;
    fx_status_t st = 0u;
    uint32_t unk[IMP_NAX] = {0u, 0u, 0u};
    uint32_t n = 0u;
    uint32_t u;
    if ((s->cal.ref.valid != 0u) && log_covers(s, p, s->cal.ref.step) && (s->nav.step > s->cal.ref.step)) {
        window(s, p, &s->cal.ref, &s->nav, &st);
        for (u = 0u; u < IMP_NAX; u++) {
            s->tlm.nu_q28[u] = s->win.m_q28[vrow(u)];
        }
        n = cal_unknowns(s, p, unk, &st);
    }
    if ((n > 0u) && (st == 0u)) {
        int32_t ah[IMP_NAX] = {0, 0, 0};
        bool out = false;
        cal_normal(s, unk, n, &st);
        fx_solve(&s->cal.sws, s->cal.a_q, CAL_Q, s->cal.b_q, CAL_Q, n, s->cal.x_q30, IMP_ALPHA_Q, CAL_PIVOT_MIN, &st);
        for (u = 0u; u < n; u++) {
            ah[u] = fx_add_sat(s->cal.alpha_q30[unk[u]], s->cal.x_q30[u], &st);
            out = out || (fx_uabs(fx_sub_sat(ah[u], FX_Q_INT(1, 30), &st)) > (uint32_t)p->cal_gate_q30);
        }
        if (st != 0u) {
            /* singular or out of range: the window is not evaluable */
        } else if (out) {
            h = IMP_H_THRUST_LEVEL;
            fx_cnt_inc(&s->tlm.cal_rej);
        } else {
            cal_accept(s, unk, n, ah, &st);
            cal_update(s, p);
        }
    }
    return h;
}
