/*
 * fsw_tlm.c — fsw_tlm_t on the wire, one rule for every mission: the header of fsw_iface.py
 * (fsw_tlm_head.c), the mission's actuator counts, the module's health word, then the module's
 * block (<p>_tlm.c, from its <p>_iface.py). Little-endian, field by field; the layout version
 * and total size come from the mission's descriptor. tools/iface decodes the same layouts.
 */
#include "fsw_exec.h"

uint32_t fsw_tlm_layout(const fsw_tlm_t *t)
{
    const fsw_mis_desc_t *d = (t != NULL) ? fsw_mis_desc(t->mission) : NULL;
    return (d != NULL) ? d->tlm_layout : 0u;
}

uint32_t fsw_tlm_encode(const fsw_tlm_t *t, uint8_t *buf, uint32_t cap)
{
    uint32_t n = 0u;
    const fsw_mis_desc_t *d = (t != NULL) ? fsw_mis_desc(t->mission) : NULL;
    if ((d != NULL) && (buf != NULL) && (cap >= d->tlm_bytes)) {
        fsw_wr_t w;
        uint32_t i;
        fsw_wr_init(&w, buf, cap);
        fsw_tlm_wr_head(&w, t);
        for (i = 0u; (i < d->n_act) && (i < FSW_ACT_MAX); i++) {
            fsw_wr_i32(&w, t->act_cnt[i]);
        }
        fsw_wr_u32(&w, t->mod_health);
        fsw_mis_tlm_wr(t->mission, &w, &t->m);
        if ((!w.err) && (w.pos == d->tlm_bytes)) {
            n = w.pos;
        }
    }
    return n;
}
