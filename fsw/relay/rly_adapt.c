/*
 * rly_adapt.c — k_t adaptation at the end of each window (spec 20 §5): random search with learning
 * in PAPER mode (faithful to the source, freeze on a run of small changes) and IMPROVED mode
 * (SEARCH / PROBE / FROZEN with the cliff retreat and the un-freeze safety net).
 *
 * Integer rules: ratios of window sums are tested as den S_a vs num S_b with num, den <= 255 and
 * S < 2^54, so every product stays below 2^62. Choices the spec leaves open, taken here and in the
 * reference alike (README "Adaptation"):
 *  - a freeze is a decision without a draw (the generator is not advanced);
 *  - the k_t history for the stationarity gate holds the k_t in force over the last windows, skipped
 *    ones included (k_t,j-6 is six windows of time back); it starts filled with kt0;
 *  - S_ref restarts at zero with every freeze.
 */
#include "rly_int.h"

uint32_t rly_xorshift32(uint32_t *x)
{
    uint32_t v = *x;
    v ^= v << 13;
    v ^= v >> 17;
    v ^= v << 5;
    *x = v;
    return v;
}

void rly_adapt_init(rly_adapt_t *a, const rly_params_t *p)
{
    static const rly_adapt_t zero = {0};
    uint32_t i;
    *a = zero;
    a->rng = p->seed;
    for (i = 0u; i < 16u; i++) {   /* spec §5.3: the first 16 outputs are discarded */
        (void)rly_xorshift32(&a->rng);
    }
    for (i = 0u; i < RLY_KT_HIST; i++) {
        a->kt_hist[i] = p->kt0_q16;
    }
    a->phase = RLY_PH_SEARCH;
    a->sign = 1;
    a->d_last = 1;
}

uint16_t rly_kt_clamp(int32_t kt, const rly_params_t *p, uint32_t *h)
{
    int32_t r = kt;
    if (r < (int32_t)p->kt_min_q16) {
        r = (int32_t)p->kt_min_q16;
    } else if (r > (int32_t)p->kt_max_q16) {
        r = (int32_t)p->kt_max_q16;
    } else {
        /* inside the limits */
    }
    if (r != kt) {
        *h |= RLY_H_KT_CLAMPED;
    }
    return (uint16_t)r;   /* within [kt_min, kt_max] <= 65535 */
}

/* One draw: sign from the top bit, magnitude in [1, 65536] standing for (0, 1]. */
static uint32_t draw(rly_adapt_t *a, int8_t *sign)
{
    uint32_t u = rly_xorshift32(&a->rng);
    *sign = ((u >> 31) != 0u) ? (int8_t)-1 : (int8_t)1;
    return ((u >> 15) & 0xFFFFu) + 1u;
}

/* k_t + sign round(mag dk), clamped; the packet records the step. */
static uint16_t apply_step(rly_adapt_t *a, const rly_params_t *p, uint16_t kt, uint32_t mag, rly_win_t *w,
                           uint32_t *h)
{
    /* mag <= 2^16, dk < 2^16: the product and its rounding fit uint32 plus one bit, use uint64 */
    int32_t step = (int32_t)((((uint64_t)mag * (uint64_t)p->dk_q16) + 32768u) >> 16);
    a->d_last = a->sign;
    w->sign = (int32_t)a->sign;
    w->mag_q16 = mag;
    w->event = RLY_EV_STEP;
    return rly_kt_clamp((int32_t)kt + ((int32_t)a->sign * step), p, h);
}

/* The sign rule of §5.1 step 6 and a fresh magnitude, then the step; `up` (IMPROVED_UP's escape)
   overrides the sign. */
static uint16_t learn_step(rly_adapt_t *a, const rly_params_t *p, uint16_t kt, uint64_t s, bool late, bool up,
                           rly_win_t *w, uint32_t *h)
{
    int8_t rs = 1;
    uint32_t mag = draw(a, &rs);   /* drawn whatever the branch: the stream never depends on it */
    if (up) {
        a->sign = 1;
        a->n_dec = 0u;
    } else if ((!late) || (p->learn_after_tmin != 0u)) {
        if (s < a->s_prev) {
            a->n_dec = (a->n_dec < UINT32_MAX) ? (a->n_dec + 1u) : a->n_dec;
        } else if (a->n_dec >= (uint32_t)p->n_ignore) {
            a->n_dec = 0u;   /* a lone increase after a run of decreases is ignored once */
        } else {
            a->sign = (int8_t)(-a->sign);
            a->n_dec = 0u;
        }
    } else {
        a->sign = rs;   /* the literal reading: pure random signs after T_min */
    }
    return apply_step(a, p, kt, mag, w, h);
}

/* A fresh random step, as at j = 0 and after an un-freeze. */
static uint16_t random_step(rly_adapt_t *a, const rly_params_t *p, uint16_t kt, rly_win_t *w, uint32_t *h)
{
    int8_t rs = 1;
    uint32_t mag = draw(a, &rs);
    a->sign = rs;
    return apply_step(a, p, kt, mag, w, h);
}

static void freeze(rly_adapt_t *a, rly_win_t *w, uint8_t ev)
{
    a->phase = RLY_PH_FROZEN;
    a->frozen_age = 0u;
    a->unf_run = 0u;
    a->s_ref = 0u;   /* set again by the 2nd window of this freeze */
    w->event = ev;
}

static uint16_t search(rly_adapt_t *a, const rly_params_t *p, uint16_t kt, uint64_t s, bool late, rly_win_t *w,
                       uint32_t *h)
{
    uint16_t next = kt;
    uint64_t diff = (s > a->s_prev) ? (s - a->s_prev) : (a->s_prev - s);
    bool small = ((uint64_t)p->delta0_den * diff) < ((uint64_t)p->delta0_num * s);
    int32_t gate = (int32_t)p->gate_dk * (int32_t)p->dk_q16;
    int32_t moved = (int32_t)kt - (int32_t)a->kt_hist[RLY_KT_HIST - 1u];
    /* IMPROVED_UP's escape: a window mean above env_alarm (the sum test is exact: alarm < 2^32 and
       win_ticks <= 2^21, so the product < 2^53) is worse than not adapting at all; on this plant that
       happens only in the erratic zone at and below k_t0, under the valley, so the search steps up
       and no settled trigger may freeze there (README "k_t adaptation"). */
    bool up = (p->adapt_mode == RLY_ADAPT_IMPROVED_UP) &&
              (s > ((uint64_t)p->env_alarm_q40 * (uint64_t)p->win_ticks));
    if ((p->count_before_tmin != 0u) || late) {
        a->n_small = small ? (a->n_small + 1u) : 0u;   /* bounded by the window count */
    }
    if (p->adapt_mode == RLY_ADAPT_PAPER) {
        if (late && (a->n_small >= (uint32_t)p->n_small)) {
            freeze(a, w, RLY_EV_FREEZE_SETTLED);   /* for good: no step */
        } else {
            next = learn_step(a, p, kt, s, late, false, w, h);
        }
    } else if (late && (((uint64_t)p->cliff_den * s) > ((uint64_t)p->cliff_num * a->s_prev)) &&
               ((p->adapt_mode != RLY_ADAPT_IMPROVED_UP) || (a->d_last > 0))) {
        /* IMPROVED_UP arms the cliff only after an upward step: a rise after a downward step is a
           regime flip of the two-regime zone, not a cliff crossing (README "k_t adaptation"). */
        /* retreat behind the k_t of the previous window, against the last step's direction */
        int32_t back = (int32_t)p->retreat_dk * (int32_t)p->dk_q16;
        next = rly_kt_clamp((int32_t)a->kt_hist[1] - ((int32_t)a->d_last * back), p, h);
        freeze(a, w, RLY_EV_FREEZE_CLIFF);
    } else if (late && (!up) && (a->n_small >= (uint32_t)p->n_small) && (moved < gate) && (moved > -gate)) {
        a->kt_probe[0] = kt;
        a->kt_probe[1] = rly_kt_clamp((int32_t)kt + (int32_t)p->dk_q16, p, h);
        a->kt_probe[2] = rly_kt_clamp((int32_t)kt - (int32_t)p->dk_q16, p, h);
        a->probe_i = 0u;
        a->probe_w = 0u;
        a->phase = RLY_PH_PROBE;
        w->event = RLY_EV_PROBE_START;
        next = a->kt_probe[0];
    } else {
        next = learn_step(a, p, kt, s, late, up, w, h);
    }
    return next;
}

static uint16_t probe(rly_adapt_t *a, const rly_params_t *p, uint16_t kt, uint64_t s, rly_win_t *w)
{
    uint16_t next = kt;
    a->probe_w++;   /* event NONE: the packet's phase says PROBE */
    if (a->probe_w > p->probe_settle) {   /* this window was the measured one */
        a->s_probe[a->probe_i] = s;
        a->probe_i++;
        a->probe_w = 0u;
        if (a->probe_i >= RLY_N_PROBE) {
            uint32_t best = 0u;
            uint32_t i;
            for (i = 1u; i < RLY_N_PROBE; i++) {
                if (a->s_probe[i] < a->s_probe[best]) {   /* ties: the earlier point */
                    best = i;
                }
            }
            next = a->kt_probe[best];
            freeze(a, w, RLY_EV_FREEZE_SETTLED);
        } else {
            next = a->kt_probe[a->probe_i];
        }
    }
    return next;
}

static uint16_t frozen(rly_adapt_t *a, const rly_params_t *p, uint16_t kt, uint64_t s, rly_win_t *w, uint32_t *h)
{
    uint16_t next = kt;
    a->frozen_age = (a->frozen_age < UINT32_MAX) ? (a->frozen_age + 1u) : a->frozen_age;
    if (a->frozen_age == 2u) {
        a->s_ref = s;   /* the 2nd window after freezing: the first ran while k_t settled */
    } else if ((a->frozen_age > 2u) && (p->adapt_mode >= RLY_ADAPT_IMPROVED)) {
        if (((uint64_t)p->unfreeze_den * s) > ((uint64_t)p->unfreeze_num * a->s_ref)) {
            a->unf_run++;
        } else {
            a->unf_run = 0u;
        }
        if (a->unf_run >= (uint32_t)p->unfreeze_windows) {
            a->phase = RLY_PH_SEARCH;
            a->n_small = 0u;
            a->n_dec = 0u;
            next = random_step(a, p, kt, w, h);
            w->event = RLY_EV_UNFREEZE;
        }
    } else {
        /* PAPER: frozen for good */
    }
    return next;
}

uint16_t rly_adapt_window(rly_adapt_t *a, const rly_params_t *p, bool valid, rly_win_t *w, uint32_t *h)
{
    uint16_t kt = w->kt_in_q16;
    uint16_t next = kt;
    uint32_t i;
    w->event = RLY_EV_NONE;
    w->sign = 0;
    w->mag_q16 = 0u;
    for (i = RLY_KT_HIST - 1u; i > 0u; i--) {
        a->kt_hist[i] = a->kt_hist[i - 1u];
    }
    a->kt_hist[0] = kt;
    if (!valid) {
        w->event = RLY_EV_SKIPPED;   /* no state change at all (spec §5.2) */
    } else if (p->adapt_mode == RLY_ADAPT_OFF) {
        next = kt;   /* OFF holds k_t and still reports the windows */
    } else {
        bool late = ((uint64_t)w->j + 1u) >= (uint64_t)p->tmin_windows;   /* (j+1) T >= T_min */
        if (a->n_valid == 0u) {
            next = random_step(a, p, kt, w, h);   /* j = 0: a random sign and magnitude */
        } else if (a->phase == RLY_PH_SEARCH) {
            next = search(a, p, kt, w->s, late, w, h);
        } else if (a->phase == RLY_PH_PROBE) {
            next = probe(a, p, kt, w->s, w);
        } else {
            next = frozen(a, p, kt, w->s, w, h);
        }
        a->s_prev = w->s;
        a->n_valid = (a->n_valid < UINT32_MAX) ? (a->n_valid + 1u) : a->n_valid;
    }
    w->kt_next_q16 = next;
    w->phase = a->phase;
    w->n_small = (a->n_small > 255u) ? 255u : (uint8_t)a->n_small;
    w->n_dec = a->n_dec;
    w->s_ref = a->s_ref;
    w->rng = a->rng;
    return next;
}
