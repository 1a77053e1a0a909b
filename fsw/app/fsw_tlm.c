/*
 * fsw_tlm.c — fsw_tlm_t on the wire: little-endian, field by field, in the order of
 * fsw_tlm_formats.json (the tools' scaling file). tests/app checks the two agree.
 */
#include "fsw_exec.h"
#include "fsw_codec.h"

uint32_t fsw_tlm_layout(const fsw_tlm_t *t)
{
    return ((t != NULL) && (t->mission == FSW_MISSION_RENDEZVOUS)) ? FSW_TLM_RDV_LAYOUT_VERSION
                                                                     : FSW_TLM_LAYOUT_VERSION;
}

uint32_t fsw_tlm_encode(const fsw_tlm_t *t, uint8_t *buf, uint32_t cap)
{
    uint32_t n = 0u;
    if ((t != NULL) && (t->mission == FSW_MISSION_RENDEZVOUS)) {
        n = fsw_tlm_rdv_encode(t, buf, cap);
    } else if ((t != NULL) && (buf != NULL) && (cap >= FSW_TLM_BYTES)) {
        fsw_wr_t w;
        uint32_t i;
        const uint32_t head[16] = {
            t->step, t->mode, t->health, t->health_sticky, t->n_chan_rej, t->n_stale_steps,
            t->n_in_bad, t->n_tbl_acc, t->n_tbl_rej, t->tbl_reason, t->tbl_revision,
            t->n_scrub_err, t->n_safe, t->n_mode_rej, t->host_missed, t->host_rejected};
        const obs_tlm_t *o = &t->obs;
        const uint32_t cnt[11] = {
            o->health_sticky, o->n_skip, o->n_gap, o->n_lost, o->n_reinit, o->n_clamp_lo,
            o->n_clamp_hi, o->n_limited, o->n_innov, o->n_cov_clip, o->revision};
        fsw_wr_init(&w, buf, cap);
        fsw_wr_i64(&w, t->utime_us);
        fsw_wr_i64(&w, t->seq);
        for (i = 0u; i < 16u; i++) {
            fsw_wr_u32(&w, head[i]);
        }
        for (i = 0u; i < FSW_N_ACT; i++) {
            fsw_wr_i32(&w, t->act_cnt[i]);
        }
        fsw_wr_u32(&w, t->obs_health);
        for (i = 0u; i < OBS_NX; i++) {
            fsw_wr_i32(&w, o->x_q29[i]);
        }
        fsw_wr_i32(&w, o->kappa_q28);
        for (i = 0u; i < OBS_NU; i++) {
            fsw_wr_i32(&w, o->u_q29[i]);
        }
        for (i = 0u; i < OBS_NY; i++) {
            fsw_wr_i32(&w, o->e_q29[i]);
        }
        for (i = 0u; i < OBS_NY; i++) {
            fsw_wr_i32(&w, o->d2_q16[i]);
        }
        fsw_wr_i32(&w, o->pkk_q30);
        for (i = 0u; i < 11u; i++) {
            fsw_wr_u32(&w, cnt[i]);
        }
        if ((!w.err) && (w.pos == FSW_TLM_BYTES)) {
            n = w.pos;
        }
    } else {
        /* null arguments or too small a buffer: 0 */
    }
    return n;
}
