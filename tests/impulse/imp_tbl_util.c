/* Impulse-table test helpers (see imp_tbl_util.h). */
#include "imp_tbl_util.h"
#include "ut.h"

#define CMP(f) do { if (a->f != b->f) { n++; if (report != 0) { \
    ut_record_fail(__FILE__, __LINE__, "imp_params_t field differs: " #f, (int64_t)a->f, (int64_t)b->f); } } } while (0)

uint32_t imp_params_diff(const imp_params_t *a, const imp_params_t *b, int report)
{
    uint32_t n = 0u;
    uint32_t i;
    CMP(period_us); CMP(subtick_us); CMP(t_min_us); CMP(plan_lead); CMP(replan_period);
    CMP(t_stop); CMP(nav_timeout); CMP(max_iter); CMP(plan_iter_per_step); CMP(pivot_ratio_sh);
    CMP(k_tau_sh); CMP(r_tol_lsb); CMP(pivot_min_q26); CMP(rho_warn_q28); CMP(rho_reject_q28);
    CMP(dv_tie_q28); CMP(tauf_min_q29); CMP(tauf_max_q29); CMP(w_v_q28);
    for (i = 0u; i < IMP_NTHR; i++) {
        CMP(alpha_q30[i]);
    }
    CMP(k_pos_m); CMP(k_pos_sh); CMP(k_vel_sh); CMP(k_tick_sh); CMP(spare); CMP(k_vel_m);
    CMP(k_tau_m); CMP(k_tick_m); CMP(omega_nradps); CMP(a_nom_umps2); CMP(k_gtau_m);
    CMP(k_gtick_m); CMP(k_gtau_sh); CMP(k_gtick_sh); CMP(cal_enable); CMP(cal_pool);
    CMP(dv_cal_min_q28); CMP(cal_gate_q30); CMP(u_uncal_q30); CMP(u_cal_q30); CMP(miss_flag_q28);
    CMP(fd_window); CMP(fd_frac_q30); CMP(fd_persist);
    for (i = 0u; i < 3u; i++) {
        CMP(spare2[i]);
    }
    CMP(nav_gate_pos_q28); CMP(nav_gate_vel_q28); CMP(nav_gate_acc_q28); CMP(replan_gain_q30);
    CMP(revision);
    return n;
}

/* Wire type of field idx: 1 u8, 3 u32, 4 i32 (FSW_FT_*), 0 unknown. */
static int field_type(uint32_t idx)
{
    static const uint8_t t[IMP_TBL_N_FIELDS] = {
        3, 3, 3, 3, 3, 3, 3, 1, 1, 1, 1, 4, 4, 4, 4, 4, 4, 4, 4,   /* 0..18 */
        4, 4, 4, 4, 4, 4,                                          /* 19..24 alpha */
        4, 1, 1, 1, 1, 4, 4, 4, 3, 3, 4, 4, 1, 1, 1, 1,            /* 25..40 */
        4, 4, 4, 4, 4, 3, 4, 1, 1, 1, 1, 4, 4, 4, 4,               /* 41..55 */
    };
    return (idx < IMP_TBL_N_FIELDS) ? (int)t[idx] : 0;
}

int imp_field_fits(uint32_t idx, int64_t v)
{
    int t = field_type(idx);
    return ((t == 1) && (v >= 0) && (v <= 255)) || ((t == 3) && (v >= 0) && (v <= (int64_t)UINT32_MAX)) ||
           ((t == 4) && (v >= (int64_t)INT32_MIN) && (v <= (int64_t)INT32_MAX));
}

#define U8(f)  p->f = (uint8_t)v
#define U32(f) p->f = (uint32_t)v
#define I32(f) p->f = (int32_t)v

int imp_field_set(imp_params_t *p, uint32_t idx, int64_t v)
{
    int ok = 1;
    if ((idx >= 19u) && (idx <= 24u)) {
        I32(alpha_q30[idx - 19u]);
        return ok;
    }
    if ((idx >= 49u) && (idx <= 51u)) {
        U8(spare2[idx - 49u]);
        return ok;
    }
    switch (idx) {
    case 0: U32(period_us); break;
    case 1: U32(subtick_us); break;
    case 2: U32(t_min_us); break;
    case 3: U32(plan_lead); break;
    case 4: U32(replan_period); break;
    case 5: U32(t_stop); break;
    case 6: U32(nav_timeout); break;
    case 7: U8(max_iter); break;
    case 8: U8(plan_iter_per_step); break;
    case 9: U8(pivot_ratio_sh); break;
    case 10: U8(k_tau_sh); break;
    case 11: I32(r_tol_lsb); break;
    case 12: I32(pivot_min_q26); break;
    case 13: I32(rho_warn_q28); break;
    case 14: I32(rho_reject_q28); break;
    case 15: I32(dv_tie_q28); break;
    case 16: I32(tauf_min_q29); break;
    case 17: I32(tauf_max_q29); break;
    case 18: I32(w_v_q28); break;
    case 25: I32(k_pos_m); break;
    case 26: U8(k_pos_sh); break;
    case 27: U8(k_vel_sh); break;
    case 28: U8(k_tick_sh); break;
    case 29: U8(spare); break;
    case 30: I32(k_vel_m); break;
    case 31: I32(k_tau_m); break;
    case 32: I32(k_tick_m); break;
    case 33: U32(omega_nradps); break;
    case 34: U32(a_nom_umps2); break;
    case 35: I32(k_gtau_m); break;
    case 36: I32(k_gtick_m); break;
    case 37: U8(k_gtau_sh); break;
    case 38: U8(k_gtick_sh); break;
    case 39: U8(cal_enable); break;
    case 40: U8(cal_pool); break;
    case 41: I32(dv_cal_min_q28); break;
    case 42: I32(cal_gate_q30); break;
    case 43: I32(u_uncal_q30); break;
    case 44: I32(u_cal_q30); break;
    case 45: I32(miss_flag_q28); break;
    case 46: U32(fd_window); break;
    case 47: I32(fd_frac_q30); break;
    case 48: U8(fd_persist); break;
    case 52: I32(nav_gate_pos_q28); break;
    case 53: I32(nav_gate_vel_q28); break;
    case 54: I32(nav_gate_acc_q28); break;
    case 55: I32(replan_gain_q30); break;
    default: ok = 0; break;
    }
    return ok;
}
