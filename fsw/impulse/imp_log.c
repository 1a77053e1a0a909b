/*
 * imp_log.c — bookkeeping of the impulse scheduler (spec 50-impulse §5.4, §5.5): the log of the
 * commanded burns (appended by the valve windows of imp_tl.c, pruned by the nav side) with its
 * commanded response, and the thrust-level calibration's reset and "calibrated" test (the
 * estimate itself runs at a re-plan epoch in imp_nav.c).
 */
#include "imp_int.h"

/* ------------------------------------------------------------------ log of commanded burns */

void imp_log_add(imp_state_t *s, uint32_t j, uint64_t a_g, uint64_t b_g, uint64_t step_g)
{
    uint32_t i;
    uint32_t last = IMP_LOG_CAP;
    for (i = 0u; (i < (uint32_t)s->log.n) && (i < IMP_LOG_CAP); i++) {
        if ((uint32_t)s->log.thr[i] == j) {
            last = i;
        }
    }
    if ((last < IMP_LOG_CAP) && (s->log.e_g[last] == a_g)) {
        s->log.e_g[last] = b_g;
    } else {
        if ((uint32_t)s->log.n >= IMP_LOG_CAP) {
            s->log.n = 0u;            /* overflow: the history before this step is lost */
            s->log.lost_g = step_g;
        }
        s->log.s_g[s->log.n] = a_g;
        s->log.e_g[s->log.n] = b_g;
        s->log.thr[s->log.n] = (uint8_t)j;
        s->log.n++;
    }
}

void imp_log_response(imp_state_t *s, const imp_params_t *p, uint64_t k1g, uint64_t k2g, uint64_t teg,
                      fx_status_t *st)
{
    uint32_t i;
    for (i = 0u; (i < (uint32_t)s->log.n) && (i < IMP_LOG_CAP); i++) {
        imp_burn_response(s, p, s->log.thr[i], s->log.s_g[i], s->log.e_g[i], k1g, k2g, teg, st);
    }
}

/* ------------------------------------------------------------------ calibration */

void imp_cal_reset(imp_state_t *s, const imp_params_t *p)
{
    uint32_t j;
    for (j = 0u; j < IMP_NTHR; j++) {
        s->cal.sum_w_q24[j] = 0;
        s->cal.sum_wa_q54[j] = 0u;
        s->cal.n_acc[j] = 0u;
        s->cal.alpha_q30[j] = p->alpha_q30[j];
    }
    s->cal.ref.valid = 0u;
}

static bool any_window(const imp_state_t *s)
{
    bool any = false;
    uint32_t j;
    for (j = 0u; j < IMP_NTHR; j++) {
        any = any || (s->cal.n_acc[j] != 0u);
    }
    return any;
}

bool imp_cal_done(const imp_state_t *s, const imp_params_t *p, uint32_t j)
{
    return (p->cal_enable != 0u) && ((s->cal.n_acc[j] != 0u) || ((p->cal_pool != 0u) && any_window(s)));
}
