/*
 * rsp.c — the respin law (rsp.h; spec 30 §3 law, §4 wheel distribution, §5 formats, §8 health).
 *
 * Ranges, argued where a value is formed (the table is checked by rsp_params_check first):
 *   omega_q28 = cnt 2^6 with |cnt| < gyro_max_cnt <= 2^22, so |omega| < 2^28;
 *   J omega: j_q19 < 2^31 times |omega| < 2^28 < 2^59; H: |cnt| iw_q30 < 2^62;
 *   |G|^2 sums three squares of int32 (<= 3 2^62 < 2^64 in uint64); |xi|^2 two of them (<= 2^63);
 *   g = round(G 2^30 / g0) through the reciprocal of g0 made once (fx_recip: the correctly
 *   rounded quotient, so g carries no error of its own beyond 1/2 LSB; a Q1.30 r0 = 1/g0 as in
 *   spec 30 §5 has only 22 significant bits at g0 = 300 N m s and puts up to 2^7 LSB into g);
 *   k H < 2^62 and xi 2^20 < 2^51 (inner term); m inner < 2^62; the momentum bound
 *   (H +- h_lim) inv_ts < 2^32 2^31; T and dW: three products < 2^59 resp. 2^61 each.
 * Every narrowing goes through fx (sticky status). A status in the step zeroes its command
 * (spec 30 §5). The designed clips (M_max, momentum bound) are done in int64 and report CLIP /
 * HBOUND, never an fx status.
 */
#include "rsp.h"

#define RSP_Q30_ONE      ((int64_t)1073741824)        /* 1.0 in Q1.30 */
#define RSP_Q20_TO_Q50   ((int64_t)1048576)           /* 2^20: a Q1.30 direction in the q50 sum */
#define RSP_GYRO_CNT_MAX ((int32_t)4194304)           /* 2^22: omega = cnt 2^6 stays below 2^28 */
#define RSP_GMIN_FLOOR   ((int32_t)524288)            /* 2^19 (0.5 N m s): below it the momentum LSB
                                                          over g0 exceeds 2^-19 of g (README) */
#define RSP_MMAX_CODE    ((int32_t)4194176)           /* 32767 * 2^7: M_max in int16 counts of 2^-17 N m */
#define RSP_INV_TS_NUM   ((uint64_t)65536000000u)     /* 2^16 * 10^6: inv_ts_q16 = this / period_us */
#define RSP_WHL_M_STALE  ((int32_t)167772)            /* 0.01 N m in 2^-24 N m (spec 30 §8) */
#define RSP_Q24US_PER_Q20S ((uint64_t)16000000u)      /* 2^24 N m us -> 2^20 N m s: 2^4 * 10^6 */
#define RSP_FOLLOW_Q24   ((int64_t)503316)            /* 0.03 N m in 2^-24 N m (spec 30 §8) */
#define RSP_FOLLOW_S     ((int64_t)10)                /* ... for 10 s */
#define RSP_ALPHA_MAX    ((int32_t)536870912)         /* 0.5 in Q30: the G filter's largest blend */
#define RSP_US_PER_S     ((uint64_t)1000000u)         /* Ts in Q0.31 = period_us 2^31 / 10^6 */

/* Per-step scratch of the samples' derived values. g, |xi|, C_phi, M_cmd and M_del are formed
   straight in the telemetry block (the stack of rsp_step stays well under its 256 B budget). */
typedef struct {
    int32_t omega_q28[RSP_N_AX];   /* body rate, Q3.28 rad/s */
    int32_t h_q20[RSP_N_AX];       /* wheel momentum used (measured or propagated) */
    int32_t jw_q20[RSP_N_AX];      /* J omega */
    int32_t gm_q20[RSP_N_AX];      /* G = J omega + H */
    int32_t gabs_q20;              /* |G| */
    fx_status_t st;
    uint32_t h;                    /* RSP_H_* of the step */
    bool steered;                  /* the gyrodine steering ran this tick (s->cmg_out holds it) */
} rsp_work_t;

/* ------------------------------------------------------------------ table check */

static void check_law(const rsp_params_t *p, uint32_t *w)
{
    int64_t heps = (int64_t)p->heps_q30;
    int64_t eps1 = (int64_t)p->eps1_q30;
    int64_t eps2 = (int64_t)p->eps2_q30;
    if (p->period_us == 0u) {
        *w |= RSP_WHY_PERIOD;
    }
    if (((p->mode != RSP_MODE_NEAREST) && (p->mode != RSP_MODE_PRINTED)) ||
        ((p->act_kind != RSP_ACT_WHEELS) && (p->act_kind != RSP_ACT_GYRODINES))) {
        *w |= RSP_WHY_MODE;
    }
    if ((p->j_q19[0] <= 0) || (p->j_q19[1] <= 0) || (p->j_q19[2] <= 0) ||
        (p->j_q19[1] <= p->j_q19[0]) || (p->j_q19[1] <= p->j_q19[2])) {
        *w |= RSP_WHY_INERTIA;
    }
    if ((heps <= 0) || (eps1 <= (2 * heps)) || ((eps2 - eps1) <= (2 * heps)) || ((eps2 + heps) >= RSP_Q30_ONE)) {
        *w |= RSP_WHY_THRESH;
    }
}

/* m eps1 = M_max within 1 %: m eps1 taken to q24 once, then compared exactly in int64. */
static bool gain_consistent(const rsp_params_t *p)
{
    fx_status_t st = 0u;
    int64_t m_eps1_q24 = fx_shr_rnd64((int64_t)p->m_q24 * (int64_t)p->eps1_q30, 30u, &st);
    int64_t d = m_eps1_q24 - (int64_t)p->mmax_q24;
    int64_t d_abs = (d < 0) ? -d : d;
    return (d_abs * 100) <= (int64_t)p->mmax_q24;
}

static void check_gains(const rsp_params_t *p, uint32_t *w)
{
    if ((p->m_q24 <= 0) || (p->k_q30 <= 0) || (p->mstar_q24 <= 0) || (p->mmax_q24 <= 0) ||
        (p->mmax_q24 > RSP_MMAX_CODE) || (p->eps1_q30 <= 0) || (!gain_consistent(p))) {
        *w |= RSP_WHY_GAIN;
    }
    if ((p->iw_q30 <= 0) || (p->hlim_q20 <= 0) || (p->inv_ts_q16 <= 0)) {
        *w |= RSP_WHY_WHEEL;
    } else if (p->period_us != 0u) {
        int64_t want = (int64_t)fx_udiv_rnd64(RSP_INV_TS_NUM, (uint64_t)p->period_us);   /* <= 2^36 */
        int64_t d = (int64_t)p->inv_ts_q16 - want;
        if ((d > 1) || (d < -1)) {
            *w |= RSP_WHY_WHEEL;
        }
    } else {
        /* period 0 is RSP_WHY_PERIOD; 1/Ts has nothing to be compared with */
    }
}

static void check_limits(const rsp_params_t *p, uint32_t *w)
{
    if ((p->gmin_q20 <= RSP_GMIN_FLOOR) || (p->gmin_q20 > p->gguard_q20) || (p->n_g0 < 1u) ||
        (p->n_g0 > RSP_G0_TICKS_MAX)) {
        *w |= RSP_WHY_GUARDS;
    }
    if ((p->gyro_max_cnt < 1) || (p->gyro_max_cnt > RSP_GYRO_CNT_MAX) || (p->whl_max_cnt <= 0) || (p->n_fault < 1u) ||
        (p->n_stale < 1u) || (p->n_whl_est < 1u)) {
        *w |= RSP_WHY_SENSOR;
    }
    if ((p->gfilt_alpha_q30 < 0) || (p->gfilt_alpha_q30 > RSP_ALPHA_MAX)) {
        *w |= RSP_WHY_FILTER;
    }
    if ((p->hg_q20 <= 0) || (p->lambda_q28 <= 0) || (p->lambda_q28 > (int32_t)268435456) || (p->umax_cnt < 1) ||
        (p->umax_cnt > (int32_t)INT16_MAX) || (p->ms_sing_q28 <= 0) || (p->rotor_nom_cnt <= 0) ||
        (p->rotor_tol_q16 < 1u) || (p->rotor_tol_q16 > 65536u)) {
        *w |= RSP_WHY_CMG;
    }
    if ((p->outlier_q20 <= 0) || (p->outlier_rel_q16 < 1u) || (p->drift_q30 <= 0) || (p->drift_sh < 1u) ||
        (p->drift_sh > 20u) || (p->ealarm_q32 <= 0) || (p->done_xi_q30 <= 0) || (p->done_h_q20 <= 0) ||
        (p->done_ticks < 1u)) {
        *w |= RSP_WHY_HEALTH;
    }
}

fsw_rc_t rsp_params_check(const rsp_params_t *p, uint32_t *why)
{
    uint32_t w = 0u;
    fsw_rc_t rc = FSW_ERR_ARG;
    if (p != NULL) {
        check_law(p, &w);
        check_gains(p, &w);
        check_limits(p, &w);
        if (w == 0u) {
            rc = FSW_OK;
        } else {
            rc = FSW_ERR_RANGE;
        }
    }
    if (why != NULL) {
        *why = w;
    }
    return rc;
}

void rsp_init(rsp_state_t *s, const rsp_params_t *p)
{
    static const rsp_state_t zero = {0};   /* rodata: a struct copy without a stack temporary */
    uint32_t i;
    *s = zero;
    s->phase = RSP_PH_G0;
    s->region = RSP_RG_LIN;
    s->a_f = 1;   /* placeholder: Sgn(g_y) at the first RUN tick decides */
    for (i = 0u; i < RSP_N_AX; i++) {
        /* never a valid word (|cnt| < 2^22), so the first sample cannot count as a repeat */
        s->gyro_last_cnt[i] = INT32_MIN;
    }
    s->tlm.a_f = 1;
    s->tlm.mode = (uint8_t)p->mode;
    s->tlm.revision = p->revision;
}

/* ------------------------------------------------------------------ small helpers */

static int64_t clamp64(int64_t v, int64_t lo, int64_t hi)
{
    int64_t r = v;
    if (r < lo) {
        r = lo;
    }
    if (r > hi) {
        r = hi;
    }
    return r;
}

/* a - b with ACC_OVF instead of overflow (b = INT64_MIN cannot be negated). */
static int64_t sub64_sat(int64_t a, int64_t b, fx_status_t *st)
{
    int64_t r;
    if (b == INT64_MIN) {
        r = fx_add64_sat(fx_add64_sat(a, INT64_MAX, st), 1, st);
    } else {
        r = fx_add64_sat(a, -b, st);
    }
    return r;
}

static int32_t neg_if(int32_t v, bool neg, fx_status_t *st)
{
    return neg ? fx_neg(v, st) : v;
}

/* ------------------------------------------------------------------ input validation (§8) */

/* Gyro: all three accepted, none at full scale; then the frozen-word test. A sample that is
   not usable neither extends nor breaks the stale run (a sensor that freezes and drops out in
   turn must still be caught). */
static bool intake_gyro(rsp_state_t *s, const rsp_params_t *p, const rsp_in_t *in, rsp_work_t *w)
{
    bool ok = ((in->valid & 7u) == 7u) && ((in->sat & 7u) == 0u);
    uint32_t i;
    for (i = 0u; i < RSP_N_AX; i++) {
        if (fx_uabs(in->omega_BN_B_cnt[i]) >= (uint32_t)p->gyro_max_cnt) {
            ok = false;
        }
    }
    if (!ok) {
        w->h |= RSP_H_GYRO_BAD;
        fx_cnt_inc(&s->tlm.n_gyro_bad);
    } else {
        bool same = true;
        for (i = 0u; i < RSP_N_AX; i++) {
            if (in->omega_BN_B_cnt[i] != s->gyro_last_cnt[i]) {
                same = false;
            }
            s->gyro_last_cnt[i] = in->omega_BN_B_cnt[i];
            w->omega_q28[i] = fx_shl_sat(in->omega_BN_B_cnt[i], 6u, &w->st);
        }
        if (same) {
            fx_cnt_inc(&s->gyro_same);
        } else {
            s->gyro_same = 0u;
        }
        if (s->gyro_same >= p->n_stale) {
            ok = false;
            w->h |= RSP_H_GYRO_STALE;
            fx_cnt_inc(&s->tlm.n_gyro_stale);
        }
    }
    return ok;
}

/* H_last - M_del_last Ts, Ts = period_us / 10^6 (M in 2^-24 N m, H in 2^-20 N m s). */
static int32_t propagate_h(int32_t h_q20, int32_t m_q24, uint32_t period_us, fx_status_t *st)
{
    uint64_t mag = (uint64_t)fx_uabs(m_q24) * (uint64_t)period_us;       /* < 2^63 */
    int64_t dh = (int64_t)fx_udiv_rnd64(mag, RSP_Q24US_PER_Q20S);         /* < 2^40 */
    if (m_q24 < 0) {
        dh = -dh;
    }
    return fx_sat32((int64_t)h_q20 - dh, st);
}

/* Wheel stale run: a changed word restarts it, an unchanged word extends it only while the
   commanded moment would have moved the wheel (|M_del| > 0.01 N m), otherwise it holds. */
static bool wheel_stale(rsp_state_t *s, const rsp_params_t *p, uint32_t i, int32_t cnt)
{
    if (cnt != s->whl_last_cnt[i]) {
        s->whl_same[i] = 0u;
    } else if (fx_uabs(s->mdel_last_q24[i]) > (uint32_t)RSP_WHL_M_STALE) {
        fx_cnt_inc(&s->whl_same[i]);
    } else {
        /* no torque asked: an unchanged speed is expected */
    }
    s->whl_last_cnt[i] = cnt;
    return s->whl_same[i] >= p->n_stale;
}

/* One wheel: measured, or propagated for up to n_whl_est missing samples. Returns false when
   the wheel makes the tick invalid; *est tells a propagated momentum. */
static bool intake_wheel(rsp_state_t *s, const rsp_params_t *p, const rsp_in_t *in, uint32_t i, rsp_work_t *w,
                         bool *est)
{
    uint32_t bit = 1u << (3u + i);
    int32_t cnt = in->whl_speed_cnt[i];
    bool ok = true;
    bool present = ((in->valid & bit) != 0u) && ((in->sat & bit) == 0u) &&
                   (fx_uabs(cnt) <= (uint32_t)p->whl_max_cnt);
    if (present) {
        s->whl_miss[i] = 0u;
        ok = !wheel_stale(s, p, i, cnt);
        s->h_last_q20[i] = fx_rshift_sat((int64_t)cnt * (int64_t)p->iw_q30, 20u, &w->st);
    } else {
        fx_cnt_inc(&s->whl_miss[i]);
        if (s->whl_miss[i] <= p->n_whl_est) {
            s->h_last_q20[i] = propagate_h(s->h_last_q20[i], s->mdel_last_q24[i], p->period_us, &w->st);
            *est = true;
        } else {
            ok = false;
        }
    }
    w->h_q20[i] = s->h_last_q20[i];
    return ok;
}

/* Gyrodines: all four gimbal angles present (no propagation: a missing angle leaves H unknown), H and
   the Jacobian from them (rsp_cmg_geom, into the state: kept off rsp_step's frame). The rotor speeds
   are health only (spec 30 §8): a present rotor more than rotor_tol off nominal for n_fault ticks in a
   row latches ROTOR_FAULT (a momentum the steering does not know: command zero); a missing rotor
   sample neither extends nor breaks the run. Encoder counts beyond one turn are refused by the
   adapter's range check; here they wrap as binary angles. */
static bool intake_gimbals(rsp_state_t *s, const rsp_params_t *p, const rsp_in_t *in, rsp_work_t *w)
{
    bool ok = (in->valid & 0x3C0u) == 0x3C0u;
    bool off = false;
    uint32_t bam[RSP_CMG_N];
    static const uint32_t rotor_bit[RSP_CMG_N] = {0x400u, 0x800u, 0x1000u, 0x2000u};   /* valid bits 10..13 */
    uint32_t k;
    for (k = 0u; k < RSP_CMG_N; k++) {
        uint32_t rbit = rotor_bit[k];
        /* |cnt - nom| 2^16 > tol nom, in int64: both terms < 2^31 2^16 */
        int64_t d = (int64_t)in->rotor_cnt[k] - (int64_t)p->rotor_nom_cnt;
        int64_t d_abs = (d < 0) ? -d : d;
        if (((in->valid & rbit) != 0u) &&
            ((d_abs * 65536) > ((int64_t)p->rotor_tol_q16 * (int64_t)p->rotor_nom_cnt))) {
            off = true;
        }
        bam[k] = (uint32_t)in->gimbal_enc_cnt[k] << 12;   /* wraps: 2^20 counts are one turn */
    }
    if (off) {
        fx_cnt_inc(&s->rotor_run);
        if (s->rotor_run >= p->n_fault) {
            s->rotor_fault = true;
        }
    } else {
        s->rotor_run = 0u;
    }
    if (ok) {
        rsp_cmg_geom(bam, p->hg_q20, &s->cmg_geom, &w->st);
        for (k = 0u; k < RSP_N_AX; k++) {
            w->h_q20[k] = s->cmg_geom.h_q20[k];
        }
    } else {
        w->h |= RSP_H_WHL_BAD;
        fx_cnt_inc(&s->tlm.n_whl_bad);
    }
    return ok;
}

static bool intake_wheels(rsp_state_t *s, const rsp_params_t *p, const rsp_in_t *in, rsp_work_t *w)
{
    bool ok = true;
    bool est = false;
    uint32_t i;
    for (i = 0u; i < RSP_N_AX; i++) {
        if (!intake_wheel(s, p, in, i, w, &est)) {
            ok = false;
        }
    }
    if (!ok) {
        w->h |= RSP_H_WHL_BAD;
        fx_cnt_inc(&s->tlm.n_whl_bad);
    }
    if (est) {
        w->h |= RSP_H_WHL_EST;
        fx_cnt_inc(&s->tlm.n_whl_est);
    }
    return ok;
}

/* ------------------------------------------------------------------ G, g0 (§3.1, §3.6) */

static void momentum(const rsp_params_t *p, rsp_work_t *w)
{
    uint64_t sq = 0u;
    uint32_t i;
    for (i = 0u; i < RSP_N_AX; i++) {
        int64_t gi;
        int64_t gi_sq;
        w->jw_q20[i] = fx_rshift_sat((int64_t)p->j_q19[i] * (int64_t)w->omega_q28[i], 27u, &w->st);
        w->gm_q20[i] = fx_add_sat(w->jw_q20[i], w->h_q20[i], &w->st);
        gi = (int64_t)w->gm_q20[i];
        gi_sq = gi * gi;
        sq += (uint64_t)gi_sq;   /* each <= 2^62: the sum of three stays below 2^64 */
    }
    w->gabs_q20 = fx_sat32((int64_t)fx_isqrt64(sq), &w->st);
}

static void g0_tick(rsp_state_t *s, const rsp_params_t *p, rsp_work_t *w)
{
    w->h |= RSP_H_G0_WAIT;
    s->g0_sum_q20 = fx_add64_sat(s->g0_sum_q20, (int64_t)w->gabs_q20, &w->st);
    fx_cnt_inc(&s->n_g0_acc);
    /* >= : a table committed during the average may have lowered n_g0 */
    if (s->n_g0_acc >= p->n_g0) {
        /* the sum of non-negative |G| is non-negative; the mean of int32 values fits int32 */
        uint64_t g0 = fx_udiv_rnd64((uint64_t)s->g0_sum_q20, (uint64_t)s->n_g0_acc);
        s->tlm.g0_q20 = fx_sat32((int64_t)g0, &w->st);
        if (s->tlm.g0_q20 < p->gmin_q20) {
            s->phase = RSP_PH_LOW;
        } else {
            fx_recip_init(&s->r0, s->tlm.g0_q20, &w->st);
            s->phase = RSP_PH_RUN;
        }
    }
}

/* ||G| - g0| beyond max(rel g0, floor): |G| is conserved whatever the motion. */
static bool outlier(rsp_state_t *s, const rsp_params_t *p, rsp_work_t *w)
{
    int64_t g0 = (int64_t)s->tlm.g0_q20;
    int64_t gate = fx_shr_rnd64(g0 * (int64_t)p->outlier_rel_q16, 16u, &w->st);
    int64_t d = (int64_t)w->gabs_q20 - g0;
    bool bad;
    if (gate < (int64_t)p->outlier_q20) {
        gate = (int64_t)p->outlier_q20;
    }
    bad = (d > gate) || (d < -gate);
    if (bad) {
        w->h |= RSP_H_OUTLIER;
        fx_cnt_inc(&s->tlm.n_outlier);
    }
    return bad;
}

/* a x b of two int32 vectors in Q(qa) and Q(qb), result in Q(qb) (one rounding per component):
   each product < 2^(31+31), the difference of two < 2^63 for the ranges argued at the call. */
static void cross_q(const int32_t a[3], const int32_t b[3], uint32_t qa, int32_t r[3], fx_status_t *st)
{
    r[0] = fx_rshift_sat(((int64_t)a[1] * (int64_t)b[2]) - ((int64_t)a[2] * (int64_t)b[1]), qa, st);
    r[1] = fx_rshift_sat(((int64_t)a[2] * (int64_t)b[0]) - ((int64_t)a[0] * (int64_t)b[2]), qa, st);
    r[2] = fx_rshift_sat(((int64_t)a[0] * (int64_t)b[1]) - ((int64_t)a[1] * (int64_t)b[0]), qa, st);
}

/* The kinematic G filter of spec 30 §3.6: G_hat^- = G_hat - theta x G_hat + 1/2 theta x (theta x
   G_hat), theta = omega Ts (the body turns by theta over a tick, so a body-fixed view of the
   inertially fixed G turns by -theta); G_hat = G_hat^- + alpha (G_k - G_hat^-); then |G_hat| back to
   g0 by one Newton step c = 2 - |G_hat| / g0 (second order in the step's few-1e-5 error). Rigid
   motion passes without lag; modal ringing in G_k = J omega + H (which misses D qdot) is attenuated
   by about alpha / (Omega Ts). Seeded from G_k on the first valid tick and after every invalid
   tick: propagating through a gap with no rate would leave G_hat rotated by the gap's |omega| t.
   Ranges: |omega| < 1 rad/s, Ts <= 1 s, so |theta| < 2^30 (Q1.30); |G_hat| <= 2 g0 < 2^31 (q20);
   products < 2^61, cross differences < 2^62. */
static void gfilter(rsp_state_t *s, const rsp_params_t *p, rsp_work_t *w)
{
    if (!s->have_ghat) {
        uint32_t i;
        for (i = 0u; i < RSP_N_AX; i++) {
            s->ghat_q20[i] = w->gm_q20[i];
        }
        s->have_ghat = true;
    } else {
        int32_t th_q30[3];
        int32_t c1[3];
        int32_t c2[3];
        uint64_t sq = 0u;
        int64_t ratio_q30;
        int64_t c_q30;
        uint32_t i;
        /* period_us <= 10^6 (table limit): Ts <= 1 s, ts_q31 <= 2^31 */
        int64_t ts_q31 = (int64_t)fx_udiv_rnd64((uint64_t)p->period_us << 31, RSP_US_PER_S);
        for (i = 0u; i < RSP_N_AX; i++) {
            th_q30[i] = fx_rshift_sat((int64_t)w->omega_q28[i] * ts_q31, 29u, &w->st);
        }
        cross_q(th_q30, s->ghat_q20, 30u, c1, &w->st);
        cross_q(th_q30, c1, 30u, c2, &w->st);
        for (i = 0u; i < RSP_N_AX; i++) {
            int64_t gm = ((int64_t)s->ghat_q20[i] - (int64_t)c1[i]) + fx_shr_rnd64((int64_t)c2[i], 1u, &w->st);
            int64_t gb = gm + fx_shr_rnd64(((int64_t)w->gm_q20[i] - gm) * (int64_t)p->gfilt_alpha_q30, 30u, &w->st);
            s->ghat_q20[i] = fx_sat32(gb, &w->st);
            int64_t g_sq = (int64_t)s->ghat_q20[i] * (int64_t)s->ghat_q20[i];
            sq += (uint64_t)g_sq;   /* each <= 2^62: three stay below 2^64 */
        }
        ratio_q30 = (int64_t)fx_recip_div((int64_t)fx_isqrt64(sq), &s->r0, 30u, &w->st);
        c_q30 = (2 * RSP_Q30_ONE) - ratio_q30;
        for (i = 0u; i < RSP_N_AX; i++) {
            s->ghat_q20[i] = fx_rshift_sat((int64_t)s->ghat_q20[i] * c_q30, 30u, &w->st);
        }
    }
}

static void direction(rsp_state_t *s, const rsp_params_t *p, rsp_work_t *w)
{
    uint32_t i;
    int64_t gx_sq;
    int64_t gz_sq;
    const int32_t *gsrc = w->gm_q20;
    if (p->gfilt_alpha_q30 > 0) {
        gfilter(s, p, w);
        gsrc = s->ghat_q20;
    }
    for (i = 0u; i < RSP_N_AX; i++) {
        s->tlm.g_q30[i] = fx_recip_div((int64_t)gsrc[i], &s->r0, 30u, &w->st);
    }
    gx_sq = (int64_t)s->tlm.g_q30[0] * (int64_t)s->tlm.g_q30[0];
    gz_sq = (int64_t)s->tlm.g_q30[2] * (int64_t)s->tlm.g_q30[2];
    /* Q2.60 sum of two squares <= 2^63: exact floor root in Q1.30 */
    s->tlm.xi_abs_q30 = fx_sat32((int64_t)fx_isqrt64((uint64_t)gx_sq + (uint64_t)gz_sq), &w->st);
    s->tlm.cphi_q30 = neg_if(s->tlm.g_q30[1], s->a_f < 0, &w->st);
}

/* ------------------------------------------------------------------ regions, target (§3.2, §3.5) */

static uint32_t region_plain(int32_t xi_q30, const rsp_params_t *p, bool guard)
{
    uint32_t rg = RSP_RG_FAR;
    if (xi_q30 < p->eps1_q30) {
        rg = RSP_RG_LIN;
    } else if ((xi_q30 <= p->eps2_q30) || guard) {
        rg = RSP_RG_MID;
    } else {
        /* beyond eps2 without guard */
    }
    return rg;
}

static uint32_t region_hyst(uint32_t rg, int32_t xi_q30, const rsp_params_t *p, bool guard)
{
    int64_t xi = (int64_t)xi_q30;
    int64_t up1 = (int64_t)p->eps1_q30 + (int64_t)p->heps_q30;
    int64_t dn1 = (int64_t)p->eps1_q30 - (int64_t)p->heps_q30;
    int64_t up2 = (int64_t)p->eps2_q30 + (int64_t)p->heps_q30;
    int64_t dn2 = (int64_t)p->eps2_q30 - (int64_t)p->heps_q30;
    uint32_t nx = rg;
    if (rg == RSP_RG_FAR) {
        if (xi < dn1) {
            nx = RSP_RG_LIN;
        } else if (xi < dn2) {
            nx = RSP_RG_MID;
        } else {
            /* stays FAR */
        }
    } else if (xi > up2) {
        nx = RSP_RG_FAR;                         /* LIN -> FAR and MID -> FAR */
    } else if ((rg == RSP_RG_MID) && (xi < dn1)) {
        nx = RSP_RG_LIN;
    } else if ((rg == RSP_RG_LIN) && (xi > up1)) {
        nx = RSP_RG_MID;
    } else {
        /* inside the band: no change */
    }
    if (guard && (nx == RSP_RG_FAR)) {
        nx = RSP_RG_MID;                         /* guard: MID covers every |xi| >= eps1 */
    }
    return nx;
}

static void region_tick(rsp_state_t *s, const rsp_params_t *p, bool first, bool guard)
{
    if (first) {
        s->a_f = 1;   /* Sgn 0 = +1 */
        if (s->tlm.g_q30[1] < 0) {
            s->a_f = -1;
        }
        s->region = region_plain(s->tlm.xi_abs_q30, p, guard);
    } else {
        uint32_t nx = region_hyst(s->region, s->tlm.xi_abs_q30, p, guard);
        if (nx != s->region) {
            fx_cnt_inc(&s->tlm.n_switch);
            s->region = nx;
        }
    }
    if (s->region == RSP_RG_LIN) {
        fx_cnt_inc(&s->tlm.n_lin);
    } else if (s->region == RSP_RG_MID) {
        fx_cnt_inc(&s->tlm.n_mid);
    } else {
        fx_cnt_inc(&s->tlm.n_far);
    }
}

/* NEAREST re-selects f as the nearer of +-e_y while the far law runs (or, under the guard,
   while |xi| > eps2) and holds it otherwise; PRINTED keeps the first tick's a_f for good. The latch
   reports where the law is (outside that band) in both modes, as the reference twin does. */
static void target_tick(rsp_state_t *s, const rsp_params_t *p, rsp_work_t *w, bool guard)
{
    bool reselect = (s->region == RSP_RG_FAR) || (guard && (s->tlm.xi_abs_q30 > p->eps2_q30));
    if ((p->mode == RSP_MODE_NEAREST) && reselect && (s->tlm.cphi_q30 < 0)) {
        s->a_f = -s->a_f;
        s->tlm.cphi_q30 = neg_if(s->tlm.g_q30[1], s->a_f < 0, &w->st);
    }
    s->latched = !reselect;
}

/* ------------------------------------------------------------------ law (§3.2) and distribution (§4) */

/* M = -m [dir - k H] with dir in Q1.30: dir 2^20 and k H are both q50, rounded once to the
   Q5.26 inner term, then m inner (q50) rounded once to 2^-24 N m. */
static int32_t law_axis(const rsp_params_t *p, int32_t dir_q30, int32_t h_q20, fx_status_t *st)
{
    int64_t kh_q50 = (int64_t)p->k_q30 * (int64_t)h_q20;
    int64_t sum_q50 = fx_add64_sat((int64_t)dir_q30 * RSP_Q20_TO_Q50, -kh_q50, st);
    int32_t inner_q26 = fx_rshift_sat(sum_q50, 24u, st);
    return fx_rshift_sat((int64_t)p->m_q24 * -(int64_t)inner_q26, 26u, st);
}

static void law(rsp_state_t *s, const rsp_params_t *p, rsp_work_t *w)
{
    uint32_t i;
    if (s->region == RSP_RG_FAR) {
        for (i = 0u; i < RSP_N_AX; i++) {
            s->tlm.mcmd_q24[i] = (s->tlm.g_q30[i] >= 0) ? -p->mstar_q24 : p->mstar_q24;
        }
    } else {
        int32_t dir_q30[RSP_N_AX];
        bool neg = s->a_f < 0;
        dir_q30[0] = neg_if(s->tlm.g_q30[2], !neg, &w->st);   /* xi = a_f (-g_z, 0, g_x) */
        dir_q30[1] = 0;
        dir_q30[2] = neg_if(s->tlm.g_q30[0], neg, &w->st);
        /* e_xi only where |xi| >= eps1 - h_eps (> h_eps > 0): MID never holds a smaller |xi| */
        if ((s->region == RSP_RG_MID) &&
            ((int64_t)s->tlm.xi_abs_q30 >= ((int64_t)p->eps1_q30 - (int64_t)p->heps_q30))) {
            fx_recip_t r;
            fx_recip_init(&r, s->tlm.xi_abs_q30, &w->st);
            for (i = 0u; i < RSP_N_AX; i++) {
                int32_t e_q30 = fx_recip_div((int64_t)dir_q30[i], &r, 30u, &w->st);
                dir_q30[i] = neg_if(e_q30, s->tlm.cphi_q30 < 0, &w->st);   /* e_xi Sgn C_phi */
            }
        }
        for (i = 0u; i < RSP_N_AX; i++) {
            s->tlm.mcmd_q24[i] = law_axis(p, dir_q30[i], w->h_q20[i], &w->st);
        }
    }
}

/* Gyrodines (spec 30 §4): the whole M_cmd to the singularity-robust steering (no per-axis clip;
   the rate limit scales the four rates together). M_del is what the commanded counts deliver. */
static void steer(rsp_state_t *s, const rsp_params_t *p, rsp_work_t *w)
{
    rsp_cmg_params_t cp;
    uint32_t i;
    cp.hg_q20 = p->hg_q20;
    cp.lambda_q28 = p->lambda_q28;
    cp.umax_cnt = p->umax_cnt;
    cp.ms_sing_q28 = p->ms_sing_q28;
    rsp_cmg_steer(&cp, &s->cmg_geom, s->tlm.mcmd_q24, &s->cmg_out, &w->st);
    w->steered = true;
    for (i = 0u; i < RSP_N_AX; i++) {
        s->tlm.mdel_q24[i] = s->cmg_out.mdel_q24[i];
    }
    s->tlm.cmg_ms_q28 = s->cmg_out.ms_q28;
    s->tlm.cmg_s_q16 = s->cmg_out.s_q16;
    if ((s->cmg_out.flags & RSP_CMG_F_SINGULAR) != 0u) {
        w->h |= RSP_H_SINGULAR;
        fx_cnt_inc(&s->tlm.n_singular);
    }
    if ((s->cmg_out.flags & RSP_CMG_F_RATE_LIMITED) != 0u) {
        w->h |= RSP_H_RATE_LIMITED;
        fx_cnt_inc(&s->tlm.n_rate_limited);
    }
}

/* Per axis: clip to M_max, clamp to the momentum bound [(H - h_lim)/Ts, (H + h_lim)/Ts] (it may
   point back once |H| > h_lim), clip to M_max again. All in int64: designed limits, no status.
   CLIP reports the first clip only; a bound beyond M_max is reported by HBOUND. */
static void distribute(rsp_state_t *s, const rsp_params_t *p, rsp_work_t *w)
{
    int64_t mmax = (int64_t)p->mmax_q24;
    int64_t hlim = (int64_t)p->hlim_q20;
    int64_t inv_ts = (int64_t)p->inv_ts_q16;
    bool clip = false;
    bool hbound = false;
    uint32_t i;
    for (i = 0u; i < RSP_N_AX; i++) {
        int64_t h = (int64_t)w->h_q20[i];
        int64_t m0 = (int64_t)s->tlm.mcmd_q24[i];
        int64_t m1 = clamp64(m0, -mmax, mmax);
        /* (H +- h_lim) < 2^32 times 1/Ts < 2^31: q36, one rounding to 2^-24 N m */
        int64_t lo = fx_shr_rnd64((h - hlim) * inv_ts, 12u, &w->st);
        int64_t hi = fx_shr_rnd64((h + hlim) * inv_ts, 12u, &w->st);
        int64_t m2 = clamp64(m1, lo, hi);
        int64_t m3 = clamp64(m2, -mmax, mmax);
        clip = clip || (m1 != m0);   /* the law asked for more than M_max */
        hbound = hbound || (m2 != m1);
        s->tlm.mdel_q24[i] = (int32_t)m3;   /* |m3| <= M_max < 2^31 */
    }
    if (clip) {
        w->h |= RSP_H_CLIP;
        fx_cnt_inc(&s->tlm.n_clip);
    }
    if (hbound) {
        w->h |= RSP_H_HBOUND;
        fx_cnt_inc(&s->tlm.n_hbound);
    }
}

/* ------------------------------------------------------------------ health (§8) */

/* T = 1/2 sum (J omega)_i omega_i; W -= 1/2 (omega_k + omega_k-1) . (H_k - H_k-1); r_E = T - T0 - W.
   A gap (invalid ticks) is not integrated across: its first valid tick re-bases W so that r_E
   carries on from its last value, because the work done over the unseen interval is unknown. */
/* Wheel not following its command (spec 30 §8): the moment a wheel delivered over the last hold,
   -dH/Ts from two consecutive measured momenta, against the moment commanded then. Off by more than
   0.03 N m for 10 s latches WHEEL_FAULT (respin on two wheels is not validated: zero command from
   then on). Only across consecutive valid ticks (have_prev): a propagated momentum (WHL_EST) equals
   the command by construction and an invalid tick commanded zero. */
static void wheel_follow(rsp_state_t *s, const rsp_params_t *p, rsp_work_t *w)
{
    /* 10 s in ticks: 10 inv_ts_q16 / 2^16, rounded (100 at Ts = 0.1 s) */
    uint32_t n = (uint32_t)fx_shr_rnd64(RSP_FOLLOW_S * (int64_t)p->inv_ts_q16, 16u, &w->st);
    uint32_t i;
    for (i = 0u; i < RSP_N_AX; i++) {
        /* |dH| < 2^32 times 1/Ts < 2^31: q36, one rounding to 2^-24 N m */
        int64_t dh = (int64_t)w->h_q20[i] - (int64_t)s->h_prev_q20[i];
        int64_t m_meas = fx_shr_rnd64(-dh * (int64_t)p->inv_ts_q16, 12u, &w->st);
        int64_t d = m_meas - (int64_t)s->mdel_last_q24[i];
        if ((d > RSP_FOLLOW_Q24) || (d < -RSP_FOLLOW_Q24)) {
            fx_cnt_inc(&s->follow_run[i]);
        } else {
            s->follow_run[i] = 0u;
        }
        if (s->follow_run[i] >= n) {
            s->wheel_fault = true;
        }
    }
}

static void energy(rsp_state_t *s, const rsp_params_t *p, rsp_work_t *w)
{
    int64_t acc = 0;
    int64_t t_q32;
    uint32_t i;
    for (i = 0u; i < RSP_N_AX; i++) {
        acc = fx_add64_sat(acc, (int64_t)w->jw_q20[i] * (int64_t)w->omega_q28[i], &w->st);
    }
    t_q32 = fx_shr_rnd64(acc, 17u, &w->st);   /* q48 with the 1/2: 2^-32 J */
    if (!s->have_t0) {
        s->t0_q32 = t_q32;
        s->tlm.w_q32 = 0;
        s->have_t0 = true;
    } else if (s->have_prev) {
        int64_t dw = 0;
        for (i = 0u; i < RSP_N_AX; i++) {
            int64_t om = (int64_t)w->omega_q28[i] + (int64_t)s->omega_prev_q28[i];
            int64_t dh = (int64_t)w->h_q20[i] - (int64_t)s->h_prev_q20[i];
            dw = fx_add64_sat(dw, om * dh, &w->st);
        }
        s->tlm.w_q32 = sub64_sat(s->tlm.w_q32, fx_shr_rnd64(dw, 17u, &w->st), &w->st);
    } else {
        s->tlm.w_q32 = sub64_sat(sub64_sat(t_q32, s->t0_q32, &w->st), s->tlm.re_q32, &w->st);
    }
    s->tlm.t_q32 = t_q32;
    s->tlm.re_q32 = sub64_sat(sub64_sat(t_q32, s->t0_q32, &w->st), s->tlm.w_q32, &w->st);
    for (i = 0u; i < RSP_N_AX; i++) {
        s->omega_prev_q28[i] = w->omega_q28[i];
        s->h_prev_q20[i] = w->h_q20[i];
    }
    s->have_prev = true;
    if (s->tlm.re_q32 > p->ealarm_q32) {
        w->h |= RSP_H_ENERGY_ALARM;
    }
}

/* The reporting checks of spec 30 §8 (none changes the command):
   - HBOUND on every LIN tick for 600 s: near f the clamp should never bind, so H cannot return to H_f
     (a wheel at its bound with friction, a wrong h_lim): HBOUND_STUCK, a module fault;
   - the energy floor: |J omega| = |G - H| >= g0 - |H| and T >= |J omega|^2 / (2 J_max) with J_max = J_y,
     so T < (g0 - |H|)^2 / (2 J_y) - e_alarm means a wrong J, gyro scale or momentum: ENERGY_LOW;
   - in FAR the relay dissipates (T falls while |H_i| < |G_i|): the T change over each complete 100 s
     window in FAR is reported, FAR_T_RISE when it is positive. Windows restart on leaving FAR.
   Durations from 1/Ts (inv_ts_q16, checked against the period): 600 s and 100 s in ticks. */
static void energy_floor(const rsp_state_t *s, const rsp_params_t *p, rsp_work_t *w)
{
    uint64_t hsq = 0u;
    uint32_t i;
    int64_t d;
    for (i = 0u; i < RSP_N_AX; i++) {
        int64_t hi = (int64_t)w->h_q20[i];
        int64_t hi_sq = hi * hi;
        hsq += (uint64_t)hi_sq;   /* three squares of int32 < 3 2^62 */
    }
    d = (int64_t)s->tlm.g0_q20 - (int64_t)fx_isqrt64(hsq);
    if (d > 0) {
        /* d^2 < 2^62 (q40) over J_y (q19): q21 < 2^53 (J_y >= 2^19 kg m^2 LSBs), then 2^-32 J with the 1/2 */
        int64_t d_sq = d * d;
        uint32_t jy = (uint32_t)p->j_q19[1];   /* > 0: rsp_params_check */
        uint64_t q21 = fx_udiv_rnd64((uint64_t)d_sq, (uint64_t)jy);
        int64_t tmin_q32 = fx_shl64_chk((int64_t)q21, 10u, &w->st);
        if ((s->tlm.t_q32 + p->ealarm_q32) < tmin_q32) {
            w->h |= RSP_H_ENERGY_LOW;
        }
    }
}

static void report_checks(rsp_state_t *s, const rsp_params_t *p, rsp_work_t *w)
{
    uint32_t n100 = (uint32_t)(((uint64_t)(uint32_t)p->inv_ts_q16 * 100u) >> 16);   /* inv_ts < 2^31 */
    uint32_t n600 = 6u * n100;
    if ((s->region == RSP_RG_LIN) && ((w->h & RSP_H_HBOUND) != 0u)) {
        fx_cnt_inc(&s->hbound_lin_run);
    } else {
        s->hbound_lin_run = 0u;
    }
    if ((n600 > 0u) && (s->hbound_lin_run >= n600)) {
        w->h |= RSP_H_HBOUND_STUCK;
    }
    energy_floor(s, p, w);
    if (s->region != RSP_RG_FAR) {
        s->far_win = 0u;
    } else {
        if (s->far_win == 0u) {
            s->far_t0_q32 = s->tlm.t_q32;
        }
        fx_cnt_inc(&s->far_win);
        if (s->far_win > n100) {
            s->tlm.t_far_d100_q32 = sub64_sat(s->tlm.t_q32, s->far_t0_q32, &w->st);
            s->far_t0_q32 = s->tlm.t_q32;
            s->far_win = 1u;
        }
    }
    if ((s->region == RSP_RG_FAR) && (s->tlm.t_far_d100_q32 > 0)) {
        w->h |= RSP_H_FAR_T_RISE;
    }
}

/* rho_G = |G| / g0 - 1 and its first-order low pass (alpha = 2^-drift_sh). */
static void drift(rsp_state_t *s, const rsp_params_t *p, rsp_work_t *w)
{
    int64_t rho = (int64_t)fx_recip_div((int64_t)w->gabs_q20, &s->r0, 30u, &w->st) - RSP_Q30_ONE;
    int64_t lp = (int64_t)s->tlm.rho_lp_q30;
    s->tlm.rho_q30 = fx_sat32(rho, &w->st);
    lp += fx_shr_rnd64((int64_t)s->tlm.rho_q30 - lp, p->drift_sh, &w->st);
    s->tlm.rho_lp_q30 = fx_sat32(lp, &w->st);
    if ((s->tlm.rho_lp_q30 > p->drift_q30) || (s->tlm.rho_lp_q30 < -p->drift_q30)) {
        w->h |= RSP_H_G_DRIFT;
    }
}

static void done_tick(rsp_state_t *s, const rsp_params_t *p, const rsp_work_t *w)
{
    bool in_tol = (s->tlm.xi_abs_q30 < p->done_xi_q30) && (s->tlm.cphi_q30 > 0);
    uint32_t i;
    for (i = 0u; i < RSP_N_AX; i++) {
        if (fx_uabs(w->h_q20[i]) >= (uint32_t)p->done_h_q20) {
            in_tol = false;
        }
    }
    if (in_tol) {
        fx_cnt_inc(&s->tlm.done_run);
    } else {
        s->tlm.done_run = 0u;
    }
}

/* ------------------------------------------------------------------ the step (§3.7) */

/* A valid RUN tick from |G| on; false when the outlier gate refuses the sample. */
static bool run_tick(rsp_state_t *s, const rsp_params_t *p, rsp_work_t *w)
{
    bool ok = !outlier(s, p, w);
    if (ok) {
        bool first = !s->have_t0;
        bool guard = s->tlm.g0_q20 < p->gguard_q20;
        direction(s, p, w);
        region_tick(s, p, first, guard);
        if (first) {
            s->tlm.cphi_q30 = neg_if(s->tlm.g_q30[1], s->a_f < 0, &w->st);
        }
        target_tick(s, p, w, guard);
        law(s, p, w);
        if (p->act_kind == RSP_ACT_GYRODINES) {
            steer(s, p, w);
        } else {
            distribute(s, p, w);
            if (s->have_prev) {
                wheel_follow(s, p, w);
            }
        }
        energy(s, p, w);
        report_checks(s, p, w);
        drift(s, p, w);
        done_tick(s, p, w);
    }
    return ok;
}

/* Bookkeeping of an invalid tick: the command is zero (the scratch M never left zero), region,
   a_f and latch stay, and the energy pair is dropped so that nothing is integrated across it. */
static void invalid_tick(rsp_state_t *s, const rsp_params_t *p)
{
    fx_cnt_inc(&s->bad_run);
    if (s->bad_run >= p->n_fault) {
        s->input_fault = true;
    }
    s->have_prev = false;
    s->have_ghat = false;
}

static void phase_flags(const rsp_state_t *s, const rsp_params_t *p, rsp_work_t *w)
{
    if (s->phase == RSP_PH_G0) {
        w->h |= RSP_H_G0_WAIT;
    } else if (s->phase == RSP_PH_LOW) {
        w->h |= RSP_H_LOW_MOMENTUM;
    } else {
        if (s->tlm.g0_q20 < p->gguard_q20) {
            w->h |= RSP_H_GUARD;
        }
        if (s->tlm.done_run >= p->done_ticks) {
            w->h |= RSP_H_DONE;
        }
    }
    if (s->input_fault) {
        w->h |= RSP_H_INPUT_FAULT;
    }
}

/* Commands (wheels: -M_del in 2^-17 N m; gyrodines: the steering's rate counts), the fx-status
   and fault rules, telemetry. A gimbal rate of zero holds the cluster: no moment. */
static void finish(rsp_state_t *s, const rsp_params_t *p, rsp_work_t *w, rsp_out_t *out)
{
    int16_t cmd[RSP_N_AX] = {0, 0, 0};
    int16_t rate[RSP_CMG_N] = {0, 0, 0, 0};
    bool gyrodines = p->act_kind == RSP_ACT_GYRODINES;
    uint32_t i;
    for (i = 0u; i < RSP_N_AX; i++) {
        if (!gyrodines) {
            cmd[i] = fx_sat16(fx_rshift_sat(-(int64_t)s->tlm.mdel_q24[i], 7u, &w->st), &w->st);
        }
    }
    for (i = 0u; i < RSP_CMG_N; i++) {
        if (w->steered) {
            rate[i] = s->cmg_out.rate_cnt[i];
        }
    }
    if ((w->st != 0u) || s->wheel_fault || s->rotor_fault) {
        for (i = 0u; i < RSP_N_AX; i++) {
            cmd[i] = 0;
            s->tlm.mdel_q24[i] = 0;
        }
        for (i = 0u; i < RSP_CMG_N; i++) {
            rate[i] = 0;
        }
    }
    if (s->wheel_fault) {
        w->h |= RSP_H_WHEEL_FAULT;
    }
    if (s->rotor_fault) {
        w->h |= RSP_H_ROTOR_FAULT;
    }
    for (i = 0u; i < RSP_CMG_N; i++) {
        out->gimbal_rate_cnt[i] = rate[i];
        s->tlm.cmg_rate_cnt[i] = (int32_t)rate[i];
    }
    if (w->st != 0u) {
        w->h |= RSP_H_OVERFLOW;
        fx_cnt_inc(&s->tlm.n_overflow);
    }
    w->h |= (w->st & FX_ST_MASK);
    for (i = 0u; i < RSP_N_AX; i++) {
        out->whl_torque_cnt[i] = cmd[i];
        s->mdel_last_q24[i] = s->tlm.mdel_q24[i];
        s->tlm.h_q20[i] = w->h_q20[i];
    }
    s->tlm.phase = (uint8_t)s->phase;
    s->tlm.region = (uint8_t)s->region;
    s->tlm.latched = s->latched ? 1u : 0u;
    s->tlm.mode = (uint8_t)p->mode;
    s->tlm.a_f = s->a_f;
    s->tlm.flags = w->h;
    s->tlm.health_sticky |= w->h;
    s->tlm.revision = p->revision;
    out->health = w->h;
}

void rsp_step(rsp_state_t *s, const rsp_params_t *p, const rsp_in_t *in, rsp_out_t *out)
{
    static const rsp_work_t work_zero = {0};   /* rodata: a struct copy without a stack temporary */
    rsp_work_t w = work_zero;
    bool gyro_ok;
    bool whl_ok;
    bool ok;
    uint32_t i;
    for (i = 0u; i < RSP_N_AX; i++) {
        s->tlm.mcmd_q24[i] = 0;   /* stays zero unless the law runs this tick */
        s->tlm.mdel_q24[i] = 0;
    }
    gyro_ok = intake_gyro(s, p, in, &w);
    if (p->act_kind == RSP_ACT_GYRODINES) {
        whl_ok = intake_gimbals(s, p, in, &w);
    } else {
        whl_ok = intake_wheels(s, p, in, &w);   /* every tick: a missing wheel is propagated */
    }
    ok = gyro_ok && whl_ok;
    if (ok) {
        momentum(p, &w);
        if (s->phase == RSP_PH_G0) {
            g0_tick(s, p, &w);
        } else if (s->phase == RSP_PH_RUN) {
            ok = run_tick(s, p, &w);
        } else {
            /* LOW: zero command for good */
        }
    }
    if (ok) {
        s->bad_run = 0u;
    } else {
        invalid_tick(s, p);
    }
    phase_flags(s, p, &w);
    finish(s, p, &w, out);
}
