/*
 * rly.c — the relay law, the envelope copy and the windows (rly.h; spec 20 §3, §4, §8).
 *
 * Every quantity is an integer with its range argued where it is formed: the angle in q24 counts,
 * the envelope in q40 (anchors held to +-2^30 LSB so that u cos + v sin < 2^61 and q^2 + p^2 < 2^63),
 * the window sum in uint64 (N_w <= 2^21 ticks of a < 2^33 stays below 2^54).
 */
#include "rly_int.h"

static void rly_check_adapt(const rly_params_t *p, uint32_t *w);

uint32_t rly_tau2(uint16_t kt_q16, uint32_t tau1)
{
    uint64_t t = (((uint64_t)kt_q16 * (uint64_t)tau1) + 32768u) >> 16;   /* < 2^48: no overflow */
    uint32_t r;
    if (t < 1u) {
        r = 1u;
    } else if (t > (uint64_t)tau1) {
        r = tau1;
    } else {
        r = (uint32_t)t;
    }
    return (r < 1u) ? 1u : r;
}

uint64_t rly_dphi_of(uint64_t f_q64, uint32_t period_us)
{
    /* f period / 10^6 with f < 2^64 and period < 2^20: the high half's quotient and remainder,
       then (remainder 2^32 + low half product) < 2^53, so every piece fits uint64. */
    const uint64_t den = 1000000u;
    uint64_t hi = (f_q64 >> 32) * (uint64_t)period_us;
    uint64_t lo = (f_q64 & 0xFFFFFFFFu) * (uint64_t)period_us;
    uint64_t q_hi = hi / den;
    uint64_t mid = ((hi % den) << 32) + lo;
    uint64_t q_lo = (mid + (den / 2u)) / den;   /* unsigned: half up = half away from zero */
    uint64_t r = UINT64_MAX;
    if (q_hi < 1073741824u) {   /* 2^30: the high part of the result stays below 2^62 */
        uint64_t d = (q_hi << 32) + q_lo;       /* q_lo < 2^33: the sum stays below 2^63 */
        if (d < ((uint64_t)1u << 62)) {
            r = d;
        }
    }
    return r;
}

static uint32_t absdiff64(uint64_t a, uint64_t b)
{
    uint64_t d = (a > b) ? (a - b) : (b - a);
    return (d > 0xFFFFFFFFu) ? 0xFFFFFFFFu : (uint32_t)d;
}

static bool ratio_ok(uint8_t num, uint8_t den)
{
    return (num >= 1u) && (den >= 1u);
}

static void rly_check_adapt(const rly_params_t *p, uint32_t *w)
{
    uint32_t span = (p->kt_max_q16 >= p->kt_min_q16) ? ((uint32_t)p->kt_max_q16 - p->kt_min_q16) : 0u;
    if ((p->kt_min_q16 < 1u) || (p->kt_min_q16 > p->kt0_q16) || (p->kt0_q16 > p->kt_max_q16) ||
        (p->dk_q16 < 1u) || ((uint32_t)p->dk_q16 > (span / 4u))) {
        *w |= RLY_WHY_KT;
    }
    if (p->seed == 0u) {
        *w |= RLY_WHY_SEED;
    }
    if ((p->adapt_mode > RLY_ADAPT_IMPROVED_UP) ||
        (!ratio_ok(p->delta0_num, p->delta0_den)) || (p->delta0_num >= p->delta0_den) ||
        (!ratio_ok(p->cliff_num, p->cliff_den)) || (p->cliff_num <= p->cliff_den) ||
        (!ratio_ok(p->unfreeze_num, p->unfreeze_den)) || (p->unfreeze_num <= p->unfreeze_den) ||
        (p->n_small < 1u) || (p->unfreeze_windows < 1u) || (p->gate_dk < 1u) ||
        (p->count_before_tmin > 1u) || (p->learn_after_tmin > 1u) || (p->probe_settle > 15u)) {
        *w |= RLY_WHY_ADAPT;
    }
}

static void rly_check_modes(const rly_params_t *p, uint32_t *w)
{
    if (p->n_modes > RLY_MAX_MODES) {
        *w |= RLY_WHY_MODES;
    } else {
        uint32_t i;
        for (i = 0u; i < (uint32_t)p->n_modes; i++) {
            if ((fx_uabs(p->cu_q40[i]) > (uint32_t)RLY_C_MAX) || (fx_uabs(p->ce_q40[i]) > (uint32_t)RLY_C_MAX) ||
                (fx_uabs(p->q0_q40[i]) > (uint32_t)RLY_ANCHOR_MAX) ||
                (fx_uabs(p->p0_q40[i]) > (uint32_t)RLY_ANCHOR_MAX)) {
                *w |= RLY_WHY_MODES;
            }
            if ((p->dphi_bam64[i] >= ((uint64_t)1u << 62)) ||
                (absdiff64(p->dphi_bam64[i], rly_dphi_of(p->f_q64[i], p->period_us)) > 1u)) {
                *w |= RLY_WHY_PHASE;
            }
        }
    }
}

static void rly_check_law(const rly_params_t *p, uint32_t *w)
{
    if (p->period_us == 0u) {
        *w |= RLY_WHY_PERIOD;
    }
    if ((p->gamma_q24 < 2) || (p->gamma_q24 >= p->eps_q24) || (p->eps_q24 > p->x_max_q24) ||
        (p->x_max_q24 > RLY_X_FULL_Q24)) {
        *w |= RLY_WHY_GEOM;
    }
    if ((p->win_ticks < 1u) || (p->win_ticks > RLY_WIN_MAX) || (p->tmin_windows < 1u) || (p->tau_max_ticks < 1u)) {
        *w |= RLY_WHY_WIN;
    }
    if (p->lost_ticks < 1u) {
        *w |= RLY_WHY_LOST;
    }
}

fsw_rc_t rly_params_check(const rly_params_t *p, uint32_t *why)
{
    uint32_t w = 0u;
    fsw_rc_t rc = FSW_ERR_ARG;
    if (p != NULL) {
        rly_check_law(p, &w);
        rly_check_adapt(p, &w);
        rly_check_modes(p, &w);
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

/* c_i(level): the static deflection of mode i under the level's moment. */
static int32_t level_c(const rly_params_t *p, uint32_t i, uint8_t lvl)
{
    int32_t c = 0;
    if (lvl == RLY_LVL_FULL_POS) {
        c = p->cu_q40[i];
    } else if (lvl == RLY_LVL_FULL_NEG) {
        c = -p->cu_q40[i];   /* |cu| <= 2^29 (checked): no overflow */
    } else if (lvl == RLY_LVL_WEAK_POS) {
        c = p->ce_q40[i];
    } else if (lvl == RLY_LVL_WEAK_NEG) {
        c = -p->ce_q40[i];
    } else {
        c = 0;
    }
    return c;
}

/* Anchor value held to +-2^30 LSB (ENV_SAT when it had to be). */
static int32_t anchor_sat(int64_t v, uint32_t *h)
{
    int32_t r;
    if (v > (int64_t)RLY_ANCHOR_MAX) {
        r = RLY_ANCHOR_MAX;
        *h |= RLY_H_ENV_SAT;
    } else if (v < -(int64_t)RLY_ANCHOR_MAX) {
        r = -RLY_ANCHOR_MAX;
        *h |= RLY_H_ENV_SAT;
    } else {
        r = (int32_t)v;
    }
    return r;
}

/* The copy's (q_i, p_i) now: the anchor rotated by phi_i, plus c_i of the anchor's level. */
static void mode_now(const rly_state_t *s, const rly_params_t *p, uint32_t i, int32_t *q, int32_t *pp,
                     fx_status_t *st)
{
    int32_t sn;
    int32_t cs;
    int64_t u = (int64_t)s->u_q40[i];
    int64_t v = (int64_t)s->v_q40[i];
    fx_sincos((uint32_t)(s->phi[i] >> 32), &sn, &cs);
    /* |u|, |v| <= 2^30 and |sin|, |cos| <= 2^30: each sum < 2^61 */
    *q = fx_sat32((int64_t)level_c(p, i, s->lvl) + fx_shr_rnd64((u * cs) + (v * sn), 30u, st), st);
    *pp = fx_sat32(fx_shr_rnd64((v * cs) - (u * sn), 30u, st), st);
}

static void anchor_all(rly_state_t *s, const rly_params_t *p, const int32_t *q, const int32_t *pp, uint8_t lvl,
                       uint32_t *h)
{
    uint32_t i;
    for (i = 0u; i < RLY_MAX_MODES; i++) {
        if (i < (uint32_t)p->n_modes) {
            s->u_q40[i] = anchor_sat((int64_t)q[i] - (int64_t)level_c(p, i, lvl), h);
            s->v_q40[i] = anchor_sat((int64_t)pp[i], h);
        } else {
            s->u_q40[i] = 0;
            s->v_q40[i] = 0;
        }
        s->phi[i] = 0u;
    }
    s->lvl = lvl;
}

static const uint8_t RLY_ST_CMD[7] = {
    RLY_LVL_WEAK_POS, RLY_LVL_FULL_NEG, RLY_LVL_FULL_POS, RLY_LVL_WEAK_NEG, RLY_LVL_FULL_POS,
    RLY_LVL_FULL_NEG, RLY_LVL_OFF,
};

void rly_init(rly_state_t *s, const rly_params_t *p)
{
    static const rly_state_t zero = {0};   /* rodata: a struct copy without a stack temporary */
    uint32_t h = 0u;
    *s = zero;
    s->st = RLY_ST_W_POS;
    s->kt_q16 = p->kt0_q16;
    anchor_all(s, p, p->q0_q40, p->p0_q40, RLY_LVL_WEAK_POS, &h);
    rly_adapt_init(&s->ad, p);
    s->tlm.health_sticky = h;
    s->tlm.seed = p->seed;
    s->tlm.revision = p->revision;
    s->tlm.kt_q16 = s->kt_q16;
    s->tlm.st = s->st;
    s->tlm.cmd = RLY_ST_CMD[s->st];
}

void rly_retable(rly_state_t *s, const rly_params_t *p_old, const rly_params_t *p_new)
{
    int32_t q[RLY_MAX_MODES] = {0};
    int32_t pp[RLY_MAX_MODES] = {0};
    fx_status_t st = 0u;
    uint32_t h = 0u;
    uint32_t i;
    for (i = 0u; i < RLY_MAX_MODES; i++) {
        if (i < (uint32_t)p_old->n_modes) {
            mode_now(s, p_old, i, &q[i], &pp[i], &st);
        } else {
            q[i] = p_new->q0_q40[i];   /* a mode the old table did not model starts from the new table */
            pp[i] = p_new->p0_q40[i];
        }
    }
    anchor_all(s, p_new, q, pp, s->lvl, &h);
    s->kt_q16 = rly_kt_clamp((int32_t)s->kt_q16, p_new, &h);
    s->tlm.health_sticky |= h | (st & FX_ST_MASK);
    s->tlm.revision = p_new->revision;
    s->tlm.seed = p_new->seed;
}

static void enter_main(rly_state_t *s, uint8_t st)
{
    s->st = st;
    s->n = 0u;
    if (st == RLY_ST_R_MAIN) {
        fx_cnt_inc(&s->tlm.n_r_main);
    } else {
        fx_cnt_inc(&s->tlm.n_l_main);
    }
}

static void weak_tests(rly_state_t *s, const rly_params_t *p, int32_t x)
{
    if (x >= p->eps_q24) {
        enter_main(s, RLY_ST_R_MAIN);
    } else if (x <= -p->eps_q24) {
        enter_main(s, RLY_ST_L_MAIN);
    } else {
        /* inside the deadband: the weak level holds */
    }
}

/* R_MAIN / L_MAIN: the timer (saturating at tau_max) and the exit test at eps - gamma. */
static void main_tick(rly_state_t *s, const rly_params_t *p, int32_t x, bool valid, uint32_t *h)
{
    int32_t edge = p->eps_q24 - p->gamma_q24;   /* 2 <= gamma < eps <= 2^23: exact in int32 */
    bool right = s->st == RLY_ST_R_MAIN;
    if (s->n < p->tau_max_ticks) {
        s->n++;
    } else {
        *h |= RLY_H_TAU_SAT;
        fx_cnt_inc(&s->tlm.n_tau_sat);
    }
    if (valid && ((right && (x <= edge)) || ((!right) && (x >= -edge)))) {
        s->tlm.tau1 = s->n;
        s->nb = rly_tau2(s->kt_q16, s->n);   /* k_t is read when the brake starts */
        s->tlm.tau2 = s->nb;
        s->st = right ? RLY_ST_R_BRAKE : RLY_ST_L_BRAKE;
    }
}

/* R_BRAKE / L_BRAKE: strictly timed; its end runs the W tests in the same tick. */
static void brake_tick(rly_state_t *s, const rly_params_t *p, int32_t x, bool valid)
{
    if (s->nb > 0u) {
        s->nb--;
    }
    if (s->nb == 0u) {
        s->st = (s->st == RLY_ST_R_BRAKE) ? RLY_ST_W_POS : RLY_ST_W_NEG;
        if (valid) {
            weak_tests(s, p, x);   /* the one chained transition (§3.2) */
        }
    }
}

/* The §3.2 transition table for one tick; valid false skips the level tests only. */
static void law_tick(rly_state_t *s, const rly_params_t *p, int32_t x, bool valid, uint32_t *h)
{
    switch (s->st) {
    case RLY_ST_W_POS:
    case RLY_ST_W_NEG:
        if (valid) {
            weak_tests(s, p, x);
        }
        break;
    case RLY_ST_R_MAIN:
    case RLY_ST_L_MAIN:
        main_tick(s, p, x, valid, h);
        break;
    case RLY_ST_R_BRAKE:
    case RLY_ST_L_BRAKE:
        brake_tick(s, p, x, valid);
        break;
    default:   /* COAST: the first valid sample restarts the cycle from W_POS */
        if (valid) {
            s->st = RLY_ST_W_POS;
            s->n = 0u;
            s->nb = 0u;
        }
        break;
    }
}

/* Sample intake: F1 (skip the tests), F2 (COAST after lost_ticks in a row). */
static bool intake(rly_state_t *s, const rly_params_t *p, const rly_in_t *in, int32_t *x, uint32_t *h)
{
    bool ok = in->valid;
    if (ok && (fx_uabs(in->x_q24) > (uint32_t)p->x_max_q24)) {
        ok = false;
        *h |= RLY_H_X_RANGE;
        fx_cnt_inc(&s->tlm.n_x_range);
    }
    if (ok) {
        *x = in->x_q24;
        s->lost_run = 0u;
    } else {
        *x = 0;
        *h |= RLY_H_X_INVALID;
        fx_cnt_inc(&s->tlm.n_x_invalid);
        fx_cnt_inc(&s->w_invalid);
        if (s->lost_run < UINT32_MAX) {
            s->lost_run++;
        }
        if ((s->lost_run >= (uint32_t)p->lost_ticks) && (s->st != RLY_ST_COAST)) {
            s->st = RLY_ST_COAST;   /* pulse timing aborted: the actuator goes OFF */
            s->n = 0u;
            s->nb = 0u;
            fx_cnt_inc(&s->tlm.n_lost);
        }
        if (s->st == RLY_ST_COAST) {
            *h |= RLY_H_SENSOR_LOST;
            s->w_lost = true;
        }
    }
    return ok;
}

static void window_close(rly_state_t *s, const rly_params_t *p, uint32_t *h)
{
    rly_win_t w = s->tlm.win;
    uint64_t abar = fx_udiv_rnd64(s->s_win, (uint64_t)p->win_ticks);   /* win_ticks >= 1 (checked) */
    w.j = s->w_j;
    w.s = s->s_win;
    w.n_invalid = s->w_invalid;
    w.kt_in_q16 = s->kt_q16;
    w.abar_q40 = (abar > 0xFFFFFFFFu) ? 0xFFFFFFFFu : (uint32_t)abar;
    s->kt_q16 = rly_adapt_window(&s->ad, p, !s->w_lost, &w, h);
    if ((!s->w_lost) && (w.abar_q40 > p->env_alarm_q40)) {
        *h |= RLY_H_ENV_HIGH;
        fx_cnt_inc(&s->tlm.n_env_high);
    }
    *h |= RLY_H_WIN_DONE;
    s->tlm.win = w;
    s->tlm.win_s = (int64_t)w.s;            /* S < 2^54 (rly.h): the conversion is exact */
    s->tlm.win_s_ref = (int64_t)w.s_ref;
    fx_cnt_inc(&s->tlm.n_windows);
    s->w_j = (s->w_j < UINT32_MAX) ? (s->w_j + 1u) : s->w_j;
    s->s_win = 0u;
    s->w_n = 0u;
    s->w_invalid = 0u;
    s->w_lost = false;
}

void rly_step(rly_state_t *s, const rly_params_t *p, const rly_in_t *in, rly_out_t *out)
{
    int32_t q[RLY_MAX_MODES] = {0};
    int32_t pp[RLY_MAX_MODES] = {0};
    fx_status_t st = 0u;
    uint32_t h = 0u;
    uint64_t a = 0u;
    int32_t x = 0;
    uint32_t i;
    uint8_t cmd;
    bool ok = intake(s, p, in, &x, &h);

    /* 1. the envelope copy now */
    for (i = 0u; i < RLY_MAX_MODES; i++) {
        uint32_t ai = 0u;
        if (i < (uint32_t)p->n_modes) {
            mode_now(s, p, i, &q[i], &pp[i], &st);
            /* |q| < 2^31, |p| <= 2^30 after rotation of anchors <= 2^30: q^2 + p^2 < 2^63 */
            int64_t q2 = (int64_t)q[i] * (int64_t)q[i];
            int64_t p2 = (int64_t)pp[i] * (int64_t)pp[i];
            ai = fx_isqrt64((uint64_t)q2 + (uint64_t)p2);
        }
        s->tlm.ai_q40[i] = ai;
        a += ai;
    }
    s->tlm.a_q40 = (a > 0xFFFFFFFFu) ? 0xFFFFFFFFu : (uint32_t)a;

    /* 2. the window */
    s->s_win += a;   /* < 2^54 for any legal table */
    s->w_n++;
    if (s->w_n >= p->win_ticks) {
        window_close(s, p, &h);
    }

    /* 3. the law */
    law_tick(s, p, x, ok, &h);
    cmd = RLY_ST_CMD[(s->st < 7u) ? s->st : RLY_ST_COAST];

    /* 4. re-anchor on a level change or a re-initialisation */
    if (in->reinit) {
        anchor_all(s, p, in->q_q40, in->p_q40, cmd, &h);
        h |= RLY_H_REINIT;
        fx_cnt_inc(&s->tlm.n_reinit);
    } else if (cmd != s->lvl) {
        anchor_all(s, p, q, pp, cmd, &h);
    } else {
        /* same level: the rotation continues */
    }
    if ((h & RLY_H_ENV_SAT) != 0u) {
        fx_cnt_inc(&s->tlm.n_env_sat);
    }
    if ((h & RLY_H_KT_CLAMPED) != 0u) {
        fx_cnt_inc(&s->tlm.n_kt_clamped);
    }

    /* 5. the phases */
    for (i = 0u; i < RLY_MAX_MODES; i++) {
        s->phi[i] += p->dphi_bam64[i];   /* unsigned: modulo 2^64 by definition */
    }

    h |= (st & FX_ST_MASK);
    s->tlm.st = s->st;
    s->tlm.cmd = cmd;
    s->tlm.x_q24 = x;
    s->tlm.kt_q16 = s->kt_q16;
    s->tlm.n = s->n;
    s->tlm.nb = s->nb;
    s->tlm.health_sticky |= h;
    s->tlm.revision = p->revision;
    out->cmd = cmd;
    out->health = h;
}
