/*
 * pd.c — the HOLD law (pd.h). The product gain * rate is formed in int64
 * (|gain| <= 2^24, |rate| <= 2^31: |product| <= 2^55), brought back with the project's one
 * rounding shift (fx_shr_rnd64) and clamped in int64, so no step can overflow, shift a negative
 * value, or raise an fx status for the designed limit.
 */
#include "pd.h"

fsw_rc_t pd_params_check(const pd_params_t *p, uint32_t *why)
{
    uint32_t w = 0u;
    fsw_rc_t rc = FSW_ERR_ARG;
    if (p != NULL) {
        if (p->period_us == 0u) {
            w |= PD_WHY_PERIOD;
        }
        if ((p->gain_q16 <= 0) || (p->gain_q16 > PD_GAIN_MAX_Q16)) {
            w |= PD_WHY_GAIN;
        }
        if ((p->u_max_cnt <= 0) || (p->u_max_cnt > PD_U_MAX_CNT)) {
            w |= PD_WHY_LIMIT;
        }
        if (p->rate_max_cnt <= 0) {
            w |= PD_WHY_SENSOR;
        }
        if (p->n_sat == 0u) {
            w |= PD_WHY_FAULT;
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

void pd_init(pd_state_t *s, const pd_params_t *p)
{
    static const pd_tlm_t tlm_zero = {0};   /* rodata: a struct copy without a stack temporary */
    s->sat_run = 0u;
    s->tlm = tlm_zero;
    s->tlm.revision = p->revision;
}

void pd_step(pd_state_t *s, const pd_params_t *p, const pd_in_t *in,
                   pd_out_t *out)
{
    fx_status_t st = 0u;
    uint32_t h = 0u;
    int32_t u = 0;
    int32_t rate = 0;
    if (in->valid) {
        int64_t prod = (int64_t)p->gain_q16 * (int64_t)in->rate_cnt;
        int64_t v = fx_shr_rnd64(-prod, 16u, &st);   /* |v| < 2^39: clamped below in int64 */
        int64_t lim = (int64_t)p->u_max_cnt;
        rate = in->rate_cnt;
        if ((v > lim) || (v < -lim)) {
            /* the limit is a designed saturation point: a health bit, not an fx status */
            u = (v > 0) ? p->u_max_cnt : -p->u_max_cnt;
            h |= PD_H_CMD_LIMITED;
            fx_cnt_inc(&s->tlm.n_limited);
            s->sat_run = (s->sat_run < UINT32_MAX) ? (s->sat_run + 1u) : s->sat_run;
        } else {
            u = (int32_t)v;
            s->sat_run = 0u;
        }
    } else {
        h |= PD_H_MEAS_SKIP;
        fx_cnt_inc(&s->tlm.n_skip);
        s->sat_run = 0u;
    }
    if (s->sat_run >= (uint32_t)p->n_sat) {
        h |= PD_H_CMD_LIMIT_PERSIST;
    }
    h |= (st & FX_ST_MASK);
    s->tlm.rate_cnt = rate;
    s->tlm.u_cnt = u;
    s->tlm.health_sticky |= h;
    s->tlm.revision = p->revision;
    out->u_cnt = u;
    out->health = h;
}
