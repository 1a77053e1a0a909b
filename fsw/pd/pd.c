/*
 * pd.c — one gyrodine PD channel (pd.h; spec 40 §3, §4.2, §5, §8).
 *
 * Every product is formed in int64 from operands whose bounds pd_params_check guarantees (the bounds
 * are noted where the product is formed), brought back with the project's one rounding shift
 * (fx_shr_rnd64, half away from zero), so no step can overflow or shift a negative value. The only
 * designated saturation is the torque clamp (TRQ_SAT); any fx status bit is a defect signal.
 */
#include "pd.h"

#define Q22_HALF_OF_Q28 ((uint64_t)1u << 27)

/* uq22 * uq22 -> uq16 with one rounding: a, b < 2^32 so a b < 2^64 - 2^28 (k < 1024). */
static uint64_t mul_q22_q16(uint32_t a, uint32_t b)
{
    const uint64_t pr = (uint64_t)a * (uint64_t)b;
    return (pr + Q22_HALF_OF_Q28) >> 28;
}

/* G_D = k0 k2 / Ty in uq16 with one rounding: rnd(k0k2_q44 10^6 / (Ty_us 2^28)). With 10^6 = 2^6 15625
   the divisor is D = Ty_us 2^22 (< 2^44 for Ty <= 4 s): q = k0k2 / D exactly, and the remainder r < D
   gives rnd(r 15625 / D) with r 15625 < 2^58, so nothing overflows and the result is correctly rounded.
   (At Ty = 0.25 s this is the exact x4 of spec 40 §5 item 4; the table's 1/Ty is only checked.) */
static uint64_t gain_d(const pd_params_t *p, uint32_t k2_q22)
{
    const uint64_t pr = (uint64_t)p->g.k0_q22 * (uint64_t)k2_q22;   /* uq44, k < 1024: < 2^64 */
    const uint64_t ty_us = (uint64_t)p->c.period_us * (uint64_t)p->c.n_div;
    uint64_t gd;
    if (ty_us == (uint64_t)PD_TY_EXACT_US) {
        gd = (pr + ((uint64_t)1u << 25)) >> 26;   /* the same rounding without two 64-bit divisions */
    } else {
        const uint64_t d = ty_us << 22;
        const uint64_t q = pr / d;
        const uint64_t r = pr - (q * d);
        gd = (q * 15625u) + fx_udiv_rnd64(r * 15625u, d);
    }
    return gd;
}

/* rnd(a b / 2^n), half away from zero, for |a| < 2^40, b < 2^32, 16 <= n <= 62: the exact product
   (up to 2^72) is split at bit 16 of b so no intermediate exceeds 2^63; one rounding. */
static int64_t pd_mul_shr(int64_t a, uint32_t b, uint32_t n)
{
    const int64_t na = -a;                               /* |a| < 2^40: no overflow */
    const uint64_t mag = (a < 0) ? (uint64_t)na : (uint64_t)a;
    const uint32_t bh = b >> 16;
    const uint32_t bl = b & 0xFFFFu;
    const uint64_t t = mag * (uint64_t)bh;               /* < 2^56 */
    const uint64_t l = mag * (uint64_t)bl;               /* < 2^56 */
    const uint32_t m = n - 16u;
    const uint64_t q1 = t >> m;
    const uint64_t r1 = t & (((uint64_t)1u << m) - 1u);
    const uint64_t frac = (r1 << 16) + l;                /* < 2^n + 2^56 <= 2^63 */
    uint64_t q2 = frac >> n;
    const uint64_t rem = frac & (((uint64_t)1u << n) - 1u);
    uint64_t q;
    int64_t r;
    if (rem >= ((uint64_t)1u << (n - 1u))) {
        q2++;
    }
    q = q1 + q2;                                         /* < 2^63: |a b| / 2^16 */
    r = (int64_t)q;
    return (a < 0) ? -r : r;
}

static uint32_t clamp_k2(const pd_params_t *p, uint32_t k2)
{
    uint32_t k = k2;
    if (k < p->g.k2_min_q22) {
        k = p->g.k2_min_q22;
    }
    if (k > p->g.k2_max_q22) {
        k = p->g.k2_max_q22;
    }
    return k;
}

static uint32_t log2_ny(uint8_t n_y)
{
    uint32_t l = 0u;
    uint32_t i;
    for (i = 1u; i <= 6u; i++) {
        if (((uint32_t)n_y >> i) != 0u) {
            l = i;
        }
    }
    return l;
}

/* The common part's reasons (period, modes, n_y, limits, fault thresholds, schedule grid). */
static uint32_t pd_check_common(const pd_common_t *c)
{
    uint32_t w = 0u;
    const uint64_t ty_us = (uint64_t)c->period_us * (uint64_t)c->n_div;
    if ((c->period_us == 0u) || (c->n_div == 0u) || (ty_us > 4000000u)) {
        w |= PD_WHY_PERIOD;
    } else {
        /* 1/Ty in uq22 within 1 LSB of 2^22 * 10^6 / Ty_us */
        const uint64_t want = fx_udiv_rnd64((uint64_t)1000000u << 22, ty_us);
        const uint64_t have = (uint64_t)c->inv_ty_q22;
        const uint64_t d = (have > want) ? (have - want) : (want - have);
        w |= (d > 1u) ? PD_WHY_PERIOD : 0u;
    }
    if ((c->law > (uint8_t)PD_LAW_LITERAL) || (c->src > (uint8_t)PD_SRC_ADAPTIVE) ||
        (c->sched_law > (uint8_t)PD_LAW_LITERAL) ||
        ((c->src != (uint8_t)PD_SRC_FIXED) && (c->sched_law != c->law)) ||
        ((c->src == (uint8_t)PD_SRC_ADAPTIVE) && (ty_us != (uint64_t)PD_TY_EXACT_US))) {
        w |= PD_WHY_MODE;   /* the estimator is tuned for Ty = 0.25 s only (pd_fest.h) */
    }
    if ((c->n_y < 2u) || (c->n_y > 64u) || ((c->n_y & (uint8_t)(c->n_y - 1u)) != 0u) ||
        (c->n_bad_max >= c->n_y)) {
        w |= PD_WHY_NY;
    }
    if ((c->y_lim_q30 <= 0) || (c->y_lim_q30 > PD_Y_MAX_Q30) || (c->dy_max_q30 <= 0) ||
        (c->dy_max_q30 > PD_DY_MAX_Q30) || (c->m_max_q28 <= 0) || (c->m_max_q28 > PD_M_MAX_Q28) ||
        (c->m_frozen_q28 < 0) || (c->ch_mask > 7u)) {
        w |= PD_WHY_LIMIT;
    }
    if ((c->n_frozen < 2u) || (c->beta_warn_q24 <= 0) || (c->beta_lim_q24 < c->beta_warn_q24)) {
        w |= PD_WHY_FAULT;
    }
    if ((c->df_inv_q16 == 0u) || (c->df_inv_q16 > 0x7FFFFFFFu) || (c->f0_q32 > 0x7FFFFFFFu)) {
        w |= PD_WHY_SCHED;
    }
    return w;
}

/* The channel's reasons: gain order, the accumulator bounds (needs a valid period), the schedule. */
static uint32_t pd_check_gains(const pd_params_t *p, bool period_ok)
{
    const pd_gains_t *g = &p->g;
    uint32_t w = 0u;
    uint32_t i;
    const bool order_ok = (g->k0_q22 <= PD_K_MAX_Q22) && (g->k1_q22 <= PD_K_MAX_Q22) &&
                          (g->k2_max_q22 <= PD_K_MAX_Q22) && (g->k2_min_q22 <= g->k2_nom_q22) &&
                          (g->k2_nom_q22 <= g->k2_max_q22) && (g->k2_cold_q22 >= g->k2_min_q22) &&
                          (g->k2_cold_q22 <= g->k2_max_q22);
    /* the products are formed only for gains within range (k < 1024: no uint64 overflow) */
    const bool gp_ok = order_ok && (mul_q22_q16(g->k0_q22, g->k1_q22) < (uint64_t)PD_GP_MAX_Q16);
    const bool gd_ok = gp_ok && ((!period_ok) || (gain_d(p, g->k2_max_q22) < PD_GD_MAX_Q16));
    if (!gd_ok) {
        w |= PD_WHY_GAIN;
    }
    for (i = 0u; i < PD_N_NODES; i++) {
        const bool up = (i > 0u) && (g->k2_node_q22[i] > g->k2_node_q22[i - 1u]);
        if ((g->k2_node_q22[i] > g->k2_max_q22) || up) {
            w |= PD_WHY_SCHED;
        }
    }
    return w;
}

fsw_rc_t pd_params_check(const pd_params_t *p, uint32_t *why)
{
    uint32_t w = 0u;
    fsw_rc_t rc = FSW_ERR_ARG;
    if (p != NULL) {
        w = pd_check_common(&p->c);
        w |= pd_check_gains(p, (w & PD_WHY_PERIOD) == 0u);
        if ((p->c.src == (uint8_t)PD_SRC_ADAPTIVE) && (pd_fest_check(&p->g.fest) != 0u)) {
            w |= PD_WHY_MODE;   /* no usable estimator block on this channel */
        }
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

uint32_t pd_sched_k2(const pd_params_t *p, uint32_t f_q32)
{
    uint32_t k2;
    if (f_q32 <= p->c.f0_q32) {
        k2 = p->g.k2_node_q22[0];
    } else {
        /* u = (f - f0) / df: uq32 * uq16 -> uq48, < 2^31 * 2^31 (both checked); rounded to uq16 (index and
           a 16-bit fraction phi), the carry moving into the index: f on a node (rounded to uq32 from below
           or above) gives that node exactly */
        const uint32_t df_q32 = f_q32 - p->c.f0_q32;
        const uint64_t u48 = (uint64_t)df_q32 * (uint64_t)p->c.df_inv_q16;
        const uint64_t u = ((u48 + ((uint64_t)1u << 31)) >> 32) << 32;
        const uint64_t idx = u >> 48;
        const uint64_t last = PD_N_NODES - 1u;
        if (idx >= last) {
            k2 = p->g.k2_node_q22[PD_N_NODES - 1u];
        } else {
            fx_status_t st = 0u;   /* the shift below cannot raise one (n = 16) */
            const uint32_t i = (uint32_t)idx;
            const uint64_t phi_u = (u >> 32) & 0xFFFFu;
            const int64_t phi = (int64_t)phi_u;
            const int64_t d = (int64_t)p->g.k2_node_q22[i + 1u] - (int64_t)p->g.k2_node_q22[i];
            const int64_t step = fx_shr_rnd64(d * phi, 16u, &st);   /* |d phi| < 2^48 */
            const int64_t k = (int64_t)p->g.k2_node_q22[i] + step;  /* between the two nodes */
            k2 = (uint32_t)k;
        }
    }
    return clamp_k2(p, k2);
}

static void set_gains(pd_state_t *s, const pd_params_t *p, uint32_t k2_q22)
{
    s->k2_q22 = k2_q22;
    s->g_p_q16 = (int64_t)mul_q22_q16(p->g.k0_q22, p->g.k1_q22);   /* < 2^26 */
    s->g_d_q16 = (int64_t)gain_d(p, k2_q22);                        /* < 2^32 (k2 <= k2_max) */
}

static uint32_t k2_wanted(const pd_state_t *s, const pd_params_t *p)
{
    uint32_t k2 = s->k2_fixed_q22;
    if (s->src == (uint8_t)PD_SRC_GROUND) {
        k2 = pd_sched_k2(p, s->f_ground_q32);
    } else if (s->src == (uint8_t)PD_SRC_ADAPTIVE) {
        k2 = s->k2_adapt_q22;
    } else {
        /* FIXED */
    }
    return k2;
}

/* ADAPTIVE from a cold start: the estimator at its prior, k2_cold, its period aligned with the law's */
static void adaptive_start(pd_state_t *s, const pd_params_t *p)
{
    pd_fest_init(&s->fest);
    s->fest.k_in_period = s->nu;
    s->k2_adapt_q22 = clamp_k2(p, p->g.k2_cold_q22);
    s->f_pub_prev_q32 = s->fest.f_hat_q32;
    s->n_inv_fest = 0u;
}

/* One estimator sample with the torque that acts over the coming sample, and at its period end the
   re-tune rule of spec 40 §4.2: FAULT -> k2_cold; a confident estimate that moved < 2 % since the last
   period end, over a period with at most n_bad_max invalid samples -> the schedule at it; else k2 stays. */
static void adaptive_sample(pd_state_t *s, const pd_params_t *p, bool ok, int32_t y, int32_t m)
{
    pd_fest_step(&s->fest, &p->g.fest, (uint32_t)p->c.n_y, ok, y, m, s->k2_q22);
    s->n_inv_fest += ok ? 0u : 1u;
    if (s->fest.period_end) {
        const uint64_t f = (uint64_t)s->fest.f_hat_q32;
        const uint64_t fp = (uint64_t)s->f_pub_prev_q32;
        const uint64_t d = (f > fp) ? (f - fp) : (fp - f);
        if (s->fest.state == (uint8_t)PD_FEST_FAULT) {
            s->k2_adapt_q22 = clamp_k2(p, p->g.k2_cold_q22);
        } else if (s->fest.confident && ((d * 50u) < fp) && (s->n_inv_fest <= (uint32_t)p->c.n_bad_max)) {
            s->k2_adapt_q22 = pd_sched_k2(p, s->fest.f_hat_q32);
        } else {
            /* k2 stays */
        }
        s->f_pub_prev_q32 = s->fest.f_hat_q32;
        s->n_inv_fest = 0u;
    }
    s->tlm.fest_f_q32 = s->fest.f_hat_q32;
    s->tlm.fest_word = (uint32_t)s->fest.state | (s->fest.confident ? 4u : 0u) | (s->fest.gate ? 8u : 0u) |
                       ((s->fest.fault & 0xFFu) << 8);
    s->tlm.fest_p_a_q30 = s->fest.p_a_q30;
    s->tlm.fest_att_q16 = s->fest.att_q16;
    s->tlm.fest_resets = s->fest.resets;
}

void pd_reset_counters(pd_state_t *s)
{
    s->tlm.miss_cnt = 0u;
    s->tlm.stale_cnt = 0u;
    s->tlm.range_rej = 0u;
    s->tlm.rate_rej = 0u;
    s->tlm.period_rej = 0u;
    s->tlm.trq_sat_cnt = 0u;
    s->tlm.beta_lim_cnt = 0u;
    s->tlm.health_sticky = 0u;
}

void pd_init(pd_state_t *s, const pd_params_t *p)
{
    static const pd_state_t zero = {0};   /* rodata: a struct copy without a stack temporary */
    *s = zero;
    s->src = p->c.src;
    s->f_ground_q32 = p->c.f_ground_q32;
    s->k2_fixed_q22 = clamp_k2(p, p->g.k2_nom_q22);
    if (s->src == (uint8_t)PD_SRC_ADAPTIVE) {
        adaptive_start(s, p);
    }
    set_gains(s, p, k2_wanted(s, p));
    s->tlm.k2_q22 = s->k2_q22;
}

bool pd_set_source(pd_state_t *s, const pd_params_t *p, uint8_t src)
{
    /* GROUND and ADAPTIVE need a schedule synthesised for the law in use, ADAPTIVE an estimator for the
       channel at Ty = 0.25 s (pd_params_check's rules for the boot source) */
    const uint64_t ty_us = (uint64_t)p->c.period_us * (uint64_t)p->c.n_div;
    const bool sched_ok = p->c.sched_law == p->c.law;
    const bool fest_ok = sched_ok && (ty_us == (uint64_t)PD_TY_EXACT_US) && (pd_fest_check(&p->g.fest) == 0u);
    const bool ok = (src == (uint8_t)PD_SRC_FIXED) || ((src == (uint8_t)PD_SRC_GROUND) && sched_ok) ||
                    ((src == (uint8_t)PD_SRC_ADAPTIVE) && fest_ok);
    if (ok) {
        if ((src == (uint8_t)PD_SRC_ADAPTIVE) && (s->src != src)) {
            adaptive_start(s, p);
        }
        s->src = src;
    }
    return ok;
}

void pd_set_f_ground(pd_state_t *s, uint32_t f_q32)
{
    s->f_ground_q32 = f_q32;
}

void pd_set_k2_fixed(pd_state_t *s, const pd_params_t *p, uint32_t k2_q22)
{
    s->k2_fixed_q22 = clamp_k2(p, k2_q22);
}

/* The sample's y in q30 if it is usable; counts and flags the reason otherwise. */
static bool accept_sample(pd_state_t *s, const pd_params_t *p, const pd_in_t *in, int32_t *y, uint32_t *h)
{
    bool ok = in->y_valid;
    /* |count| <= 2^31 - 1, so count * 16 is formed in int64 and range-checked before narrowing */
    const int64_t y64 = (int64_t)in->y_cnt * 16;
    if (!ok) {
        fx_cnt_inc(&s->tlm.miss_cnt);
    } else if (in->y_sat || (y64 > (int64_t)p->c.y_lim_q30) || (y64 < -(int64_t)p->c.y_lim_q30)) {
        ok = false;
        *h |= PD_H_REJECT;
        fx_cnt_inc(&s->tlm.range_rej);
    } else {
        const int32_t yv = (int32_t)y64;
        const int32_t am = (s->m_last_q28 < 0) ? -s->m_last_q28 : s->m_last_q28;   /* |M| <= 2^30 */
        /* the run grows only under torque (a resting body may repeat a count), but once latched
           FROZEN it lasts until the count changes: the coasting torque must not un-freeze it */
        const bool latched = s->same_run >= (uint32_t)p->c.n_frozen;
        if ((s->same_run > 0u) && (yv == s->y_same_q30) && (latched || (am >= p->c.m_frozen_q28))) {
            s->same_run = (s->same_run < UINT32_MAX) ? (s->same_run + 1u) : s->same_run;
        } else {
            s->same_run = 1u;
            s->y_same_q30 = yv;
        }
        if (s->same_run >= (uint32_t)p->c.n_frozen) {
            ok = false;
            *h |= PD_H_FROZEN;
            fx_cnt_inc(&s->tlm.stale_cnt);
        } else if (s->have_prev) {
            const int64_t dy = (int64_t)yv - (int64_t)s->y_prev_q30;
            if ((dy > (int64_t)p->c.dy_max_q30) || (dy < -(int64_t)p->c.dy_max_q30)) {
                ok = false;   /* never clamped: refused, and the next valid sample restarts dy */
                *h |= PD_H_REJECT;
                fx_cnt_inc(&s->tlm.rate_rej);
            }
        } else {
            /* first sample after a restart: no difference to test */
        }
        *y = yv;
    }
    return ok;
}

/* An already-rounded q28 torque (|m| < 2^45), clamped to +-M_max. */
static int32_t torque_q28(pd_state_t *s, const pd_params_t *p, int64_t m, uint32_t *h)
{
    const int64_t lim = (int64_t)p->c.m_max_q28;
    int32_t r;
    bool sat = true;
    if (m > lim) {
        r = p->c.m_max_q28;
    } else if (m < -lim) {
        r = -p->c.m_max_q28;
    } else {
        r = (int32_t)m;
        sat = false;
    }
    if (sat) {
        *h |= PD_H_TRQ_SAT;
        fx_cnt_inc(&s->tlm.trq_sat_cnt);
    }
    return r;
}

/* -rnd(acc / 2^18) in q28, clamped to +-M_max (the designated saturation point). */
static int32_t torque(pd_state_t *s, const pd_params_t *p, int64_t acc, uint32_t *h, fx_status_t *st)
{
    return torque_q28(s, p, -fx_shr_rnd64(acc, 18u, st), h);   /* |acc| < 2^57: |m| < 2^39 */
}

/* Control-period bookkeeping; returns true at the period's last sample with a good mean. */
static bool period_step(pd_state_t *s, const pd_params_t *p, bool ok, int32_t y, uint32_t *h)
{
    bool done = false;
    if (ok) {
        s->y_fill_q30 = y;
        s->have_fill = true;
    } else {
        s->n_bad++;
    }
    /* an invalid sample is filled with the last good y (0 before any): the mean needs n_y terms */
    s->sum_q30 += s->have_fill ? (int64_t)s->y_fill_q30 : 0;   /* |sum| <= 64 * 2^29 */
    s->nu++;
    if (s->nu >= (uint32_t)p->c.n_y) {
        if (s->n_bad > (uint32_t)p->c.n_bad_max) {
            fx_cnt_inc(&s->tlm.period_rej);
            *h |= PD_H_PERIOD_BAD;
            s->have_xbar = false;   /* the averaged modes restart their difference */
            s->zero_run = (uint32_t)p->c.n_y;
            s->m_held_q28 = 0;
        } else {
            s->xsum_prev_q30 = s->have_xbar ? s->xsum_q30 : s->sum_q30;   /* no kick on the first mean */
            s->xsum_q30 = s->sum_q30;
            s->have_xbar = true;
            done = true;
        }
        s->nu = 0u;
        s->sum_q30 = 0;
        s->n_bad = 0u;
    }
    return done;
}

/* The gain source's k2 and, on a change, the gains (no state depends on k2: no bumpless transfer, §3.2). */
static void retune(pd_state_t *s, const pd_params_t *p, uint32_t *h)
{
    const uint32_t k2 = k2_wanted(s, p);
    if (k2 != s->k2_q22) {
        set_gains(s, p, k2);
        *h |= PD_H_RETUNE;
    }
    if (s->k2_q22 == p->g.k2_cold_q22) {
        *h |= PD_H_FALLBACK_GAIN;
    }
}

/* LITERAL at a completed period: P = G_P xsum / n_y, D = G_D (xsum - xsum_prev) / n_y^2, each at q28
   with one rounding (|xsum| <= 64 2^29 = 2^35, |dsum| <= 2^36: pd_mul_shr's |a| < 2^40), held. */
static void literal_update(pd_state_t *s, const pd_params_t *p, uint32_t *h)
{
    const uint32_t l = log2_ny(p->c.n_y);
    const int64_t pt = pd_mul_shr(s->xsum_q30, (uint32_t)s->g_p_q16, 18u + l);
    const int64_t dt = pd_mul_shr(s->xsum_q30 - s->xsum_prev_q30, (uint32_t)s->g_d_q16, 18u + (2u * l));
    s->m_held_q28 = torque_q28(s, p, -(pt + dt), h);
}

void pd_note_gap(pd_state_t *s, const pd_params_t *p, uint32_t n)
{
    /* the samples that never reached the module: each one missing (counted, and invalid in its
       control period); the derivative restarts on the next sample, never differenced across the gap */
    uint32_t h = 0u;
    uint32_t i;
    /* a gap longer than 64 samples (n_y <= 64) ends with whole invalid periods: n_y + n mod n_y passes
       leave the period phase where n would, at bounded cost */
    const uint32_t ny = (uint32_t)p->c.n_y;
    const uint32_t k = ((n <= 64u) || (ny == 0u)) ? ((n < 64u) ? n : 64u) : (ny + (n % ny));
    for (i = 0u; i < k; i++) {
        /* a LITERAL period that completes inside the gap still forms its torque (held from the gap) */
        if (period_step(s, p, false, 0, &h) && (p->c.law == (uint8_t)PD_LAW_LITERAL)) {
            literal_update(s, p, &h);
        }
        if (s->src == (uint8_t)PD_SRC_ADAPTIVE) {
            adaptive_sample(s, p, false, 0, s->m_last_q28);   /* the plant held the last torque */
        }
        fx_cnt_inc(&s->tlm.miss_cnt);
    }
    if (n > k) {
        const uint32_t rest = n - k;
        s->tlm.miss_cnt = ((UINT32_MAX - s->tlm.miss_cnt) > rest) ? (s->tlm.miss_cnt + rest) : UINT32_MAX;
    }
    /* the plant held the last torque over the whole gap (platform §5.2): a short gap is differenced
       across like one missing sample (pd_step); beyond PD_GAP_DIFF_MAX the span makes the D term a kick
       (G_D x 4 samples of motion at most), so it restarts */
    if ((n > PD_GAP_DIFF_MAX) || (s->miss_run > 0u)) {
        s->have_prev = false;
    }
    s->miss_run = ((UINT32_MAX - s->miss_run) > n) ? (s->miss_run + n) : UINT32_MAX;
    s->tlm.health_sticky |= h | PD_H_STALE;
}

/* The law's torque for this sample (before the beta rule). */
static int32_t law_torque(pd_state_t *s, const pd_params_t *p, bool ok, bool mean_done, int32_t y, int32_t dy,
                          uint32_t *h, fx_status_t *st)
{
    int32_t m = 0;
    if (p->c.law == (uint8_t)PD_LAW_LITERAL) {
        /* the new torque acts from the period's last sample and is held for n_y samples */
        if (mean_done) {
            literal_update(s, p, h);
        }
        m = s->m_held_q28;
    } else if ((p->c.law == (uint8_t)PD_LAW_FAST_AVGP) && (s->zero_run > 0u)) {
        s->zero_run--;   /* averaged P after a bad period: coast for one period (FAST has no mean) */
    } else if (!ok) {
        if (s->miss_run <= (uint32_t)p->c.n_hold) {
            m = s->m_last_q28;   /* hold for n_hold samples */
        } else {
            *h |= PD_H_COAST;    /* then coast: passive-safe (spec 40 §8) */
        }
    } else if ((p->c.law == (uint8_t)PD_LAW_FAST_AVGP) && s->have_xbar) {
        /* P on the held mean, D as FAST: one rounding each (G_D < 2^32, |dy| <= 2^24: < 2^56) */
        const int64_t pt = pd_mul_shr(s->xsum_q30, (uint32_t)s->g_p_q16, 18u + log2_ny(p->c.n_y));
        const int64_t dt = fx_shr_rnd64(s->g_d_q16 * (int64_t)dy, 18u, st);
        m = torque_q28(s, p, -(pt + dt), h);
    } else {
        /* FAST (§5 items 2, 3): one rounding of acc = G_P y + G_D dy, |acc| < 2^55 + 2^56 */
        const int64_t acc = (s->g_p_q16 * (int64_t)y) + (s->g_d_q16 * (int64_t)dy);
        m = torque(s, p, acc, h, st);
    }
    return m;
}

/* §8 gimbal rows: flag a high angle; at the limit zero a torque that drives |beta| further out. */
static int32_t beta_rule(pd_state_t *s, const pd_params_t *p, const pd_in_t *in, int32_t m, uint32_t *h)
{
    int32_t r = m;
    if (in->beta_valid) {
        const int32_t b = in->beta_cnt;
        const int32_t ab = (b < 0) ? ((b == INT32_MIN) ? INT32_MAX : -b) : b;
        if (ab > p->c.beta_warn_q24) {
            *h |= PD_H_BETA_WARN;
        }
        if (ab >= p->c.beta_lim_q24) {
            *h |= PD_H_BETA_LIM;
            fx_cnt_inc(&s->tlm.beta_lim_cnt);
            if (((m > 0) && (b > 0)) || ((m < 0) && (b < 0))) {
                r = 0;
            }
        }
    }
    return r;
}

void pd_step(pd_state_t *s, const pd_params_t *p, const pd_in_t *in, pd_out_t *out)
{
    fx_status_t st = 0u;
    uint32_t h = ((uint32_t)p->c.law << 8) | ((uint32_t)s->src << 10);
    int32_t y = 0;
    int32_t dy = 0;
    int32_t m;
    bool ok;
    bool mean_done;

    retune(s, p, &h);
    ok = accept_sample(s, p, in, &y, &h);
    if (ok) {
        if (!s->have_prev) {
            s->y_prev_q30 = y;   /* the first sample after a gap: no derivative kick */
        }
        dy = (int32_t)((int64_t)y - (int64_t)s->y_prev_q30);   /* |dy| <= dy_max (tested) */
        s->y_prev_q30 = y;
        s->have_prev = true;
        s->miss_run = 0u;
    } else {
        /* One missing sample (the torque was held over it, n_hold = 1) is differenced across: the next
           valid sample's dy spans two samples. Measured (fsw/pd/README.md, decision 9): restarting after a
           single loss costs t* 219 -> 350..1012 s at 0.01 Hz under 5 % frame loss, differencing across it
           223..227 s. A second missing sample in a row, or any refused sample (a spike, an out-of-range or
           frozen value), restarts the derivative: never a difference across a longer gap or a bad value. */
        const bool plain_miss = (!in->y_valid) && (s->miss_run == 0u);
        if (!plain_miss) {
            s->have_prev = false;
        }
        s->miss_run = (s->miss_run < UINT32_MAX) ? (s->miss_run + 1u) : s->miss_run;
        h |= PD_H_STALE;
    }
    mean_done = period_step(s, p, ok, y, &h);
    m = law_torque(s, p, ok, mean_done, y, dy, &h, &st);
    m = beta_rule(s, p, in, m, &h);
    if (s->src == (uint8_t)PD_SRC_ADAPTIVE) {
        adaptive_sample(s, p, ok, y, m);
        h |= ((uint32_t)s->fest.state << 12) & PD_H_FEST;
        h |= (s->fest.state == (uint8_t)PD_FEST_FAULT) ? PD_H_FEST_FAULT : 0u;
    }

    s->m_last_q28 = m;
    out->m_cnt = (int32_t)fx_shr_rnd64((int64_t)m, 8u, &st);   /* |m| <= 2^30: < 2^22 counts */
    h |= (st & FX_ST_MASK);
    out->m_q28 = m;
    out->health = h;
    s->tlm.y_q30 = ok ? y : s->tlm.y_q30;
    s->tlm.dy_q30 = dy;
    s->tlm.m_q28 = m;
    s->tlm.k2_q22 = s->k2_q22;
    s->tlm.health = h;
    s->tlm.health_sticky |= h;
}
