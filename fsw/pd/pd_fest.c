/*
 * pd_fest.c — the on-board frequency estimator in fixed point (see pd_fest.h). Step for step the
 * double design sim/pd/pd_fest_ref.cpp (FestRef::step, step_td, step_period) with one notch
 * section; the comments there give the reasons for each step, the ones here only what the port adds.
 */
#include "pd_fest.h"

/* ---- tuning constants: the reference's FestParams defaults, in the formats of pd_fest.h ---------- */
#define FE_ONE_Q30              1073741824   /* 1.0 */
#define FE_ONE_M_LAMBDA_NOISE   1073742      /* 1 - 0.999 (per sample) */
#define FE_NOISE_CLIP           9            /* each D^3 term <= 9 x the running estimate */
#define FE_ONE_M_LAMBDA_RMS     53687091     /* 1 - 0.95 (per Td) */
#define FE_LAMBDA_NORM          1068373115   /* 0.995 */
#define FE_LAMBDA_NORM_LO       1020054733   /* 0.95 */
#define FE_K_NORM               483183821u   /* 0.45 */
#define FE_LAMBDA_NORM_ATT      858993459    /* 0.8 */
#define FE_GATE_ON              8u
#define FE_GATE_OFF             4u
#define FE_U_MAX_Q24            268435456    /* 16 */
#define FE_LAMBDA_Q30           1041529569u  /* RLS forgetting 0.97 */
#define FE_KAPPA0               644245094u   /* 0.6 */
#define FE_KAPPA_MAX            998579896    /* 0.93 */
#define FE_RHO_KAPPA            1041529569   /* 0.97 */
#define FE_P0                   1073741824u  /* 1 */
#define FE_P_MIN                107374u      /* 1e-4 */
#define FE_P_MAX                1073741824u  /* 1 */
#define FE_ONE_M_LAMBDA_S       32212255     /* 1 - 0.97 */
#define FE_RMS_S_MIN_Q16        66u          /* 1e-3 (65.5, rounded up) */
#define FE_FOBS_LO              21474836u    /* 0.005 Hz */
#define FE_FOBS_HI              1288490189u  /* 0.30 Hz */
#define FE_F0                   214748365u   /* 0.05 Hz, the prior */
#define FE_PUB_HYST_PERMILLE    5u           /* 0.5 % */
#define FE_F_LO                 34359738u    /* 0.008 Hz */
#define FE_F_HI                 515396076u   /* 0.12 Hz */
#define FE_C_F0                 21474836u    /* c grid origin 0.005 Hz; steps 0.01 Hz and 100 s */
#define FE_ONE_M_LAMBDA_ATT     107374182    /* 1 - 0.9 */
#define FE_KAPPA_CONF           805306368u   /* 0.75 */
#define FE_P_CONF               107374182u   /* 0.1 */
#define FE_ATT_CONF_Q16         39322u       /* 0.6 */
#define FE_ATT_LOSE_Q16         45875u       /* 0.7 */
#define FE_RISE_HOLD            2u
#define FE_STAB_PERCENT         1u           /* |f_j / f_(j-1) - 1| < 1 % */
#define FE_N_STAB               3u
#define FE_CYC_Q32_TY           4u           /* n T0 f >= 1 cycle: n n_y f >= 1 / Ty = 4 */
#define FE_LAMBDA_TH_Q24        16693330     /* 0.995 */
#define FE_INV_LAMBDA_TH        1079137512   /* 1 / 0.995, q30 */
#define FE_P_TH0_Q27            1342177      /* 0.01 */
#define FE_P_TH_MAX_Q27         1342177280   /* 10 */
#define FE_THETA_MAX_Q30        322122547    /* 0.3 */
#define FE_CLAMP_SAMPLES        240u         /* 60 s at Ty = 0.25 s */
#define FE_JUMP_FIFTHS          5u           /* |df| > 20 % */
#define FE_N_ATTEN_FAULT        8u
#define FE_E_FAULT_Q40          1099511628   /* 1e-3 rad */
#define FE_TWO_PI_Q28           1686629713u
#define FE_SIG_FLOOR_Q16        32768u       /* sigma_floor = sigma_y / 2 (make_fest_params) */
#define FE_N_MAX                1000u        /* saturation of the period counters */
#define FE_2P26                 67108864
#define FE_2P28                 268435456
#define FE_2P30                 1073741824
#define FE_2P32                 4294967296
#define FE_2P40                 1099511627776
#define FE_ONE_Q16              65536u
#define FE_HALF_Q30             536870912u   /* the rounding half of a q30 product */
/* yaw (n_sec = 2): the line logic of the reference (FestParams, "yaw") */
#define FE_INV_MODE_RATIO_Q30   617093002u   /* 1 / 1.74, yaw's mode-1 / mode-2 ratio (Channel::yaw):
                                                section 2's start below section 1 and the high-pass
                                                line (hp_ref_scale) */
#define FE_INV_SEC2_HI_Q30      488064465u   /* section 2 searches [f1 / 2.2, ... */
#define FE_INV_SEC2_LO_Q30      825955249u   /* ... f1 / 1.3] */
#define FE_SEC2_COMOVE_DK       21474836     /* 0.02: co-motion while kappa_2 < its target - this */
#define FE_KAPPA_PASS3          1041529569   /* 0.97, the third pass's pole radius ... */
#define FE_KAPPA_PASS3_SQ       1010283682   /* ... and its square */
#define FE_TWO_ATT1_SQ          429497       /* two lines: section 1 leaves >= 0.02 (rms) ... */
#define FE_TWO_ATT2_SQ          268435456    /* ... and section 2 leaves <= 0.5 */
#define FE_PAIR_ATT_SQ          96636764     /* pair accepted while the cascade leaves <= 0.3 (rms) */
#define FE_SINGLE_ATT_SQ        96636764     /* a single line is one section 1 notches to <= 0.3 */
#define FE_SINGLE_MAX_Q32       66571993u    /* a single line below 0.0155 Hz is mode 1 */
#define FE_VER_TOL_Q30          42949673u    /* ... or within 4 % of the last verified lower line */
#define FE_ZETA_ENV_TY_Q30      188902528u   /* zeta_single 2 pi PD_FEST_ENV Ty = 0.007 2 pi 16 0.25 s */
#define FE_N_PROOF              50u          /* decay proof: gate open >= 50 periods ... */
#define FE_F_PROOF_MIN_Q32      171798692u   /* ... for lines >= 0.04 Hz */

static int64_t fe_mul(int64_t a, int32_t b, uint32_t n, fx_status_t *st)
{
    return fx_mul64_shr(a, b, n, st);
}

/* a - b, saturating (either may be a saturated extreme) */
static int64_t fe_sub(int64_t a, int64_t b, fx_status_t *st)
{
    const int64_t nb = (b == INT64_MIN) ? INT64_MAX : -b;
    return fx_add64_sat(a, nb, st);
}

static int64_t fe_clamp64(int64_t v, int64_t lo, int64_t hi)
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

/* int64 -> int32 after an explicit clamp (the clamp is the design, not an error) */
static int32_t fe_i32(int64_t v)
{
    return (int32_t)fe_clamp64(v, (int64_t)INT32_MIN, (int64_t)INT32_MAX);
}

static uint32_t fe_u32(int64_t v)
{
    return (uint32_t)fe_clamp64(v, 0, (int64_t)UINT32_MAX);
}

/* the section count, bounded by the array whatever the table says (pd_fest_check refuses others) */
static uint32_t fe_nsec(const pd_fest_params_t *p)
{
    return ((uint32_t)p->n_sec == PD_FEST_NSEC) ? PD_FEST_NSEC : 1u;
}

/* the regressor count, bounded by the arrays whatever the table says (pd_fest_check refuses others) */
static uint32_t fe_nreg(const pd_fest_params_t *p)
{
    return ((uint32_t)p->n_reg < PD_FEST_NR) ? (uint32_t)p->n_reg : PD_FEST_NR;
}

/* x m / 2^sh summed over a coefficient row (2^-40 results) */
static int64_t fe_row(const int32_t *m, uint8_t sh, const int64_t *x, fx_status_t *st)
{
    int64_t acc = 0;
    uint32_t j;
    for (j = 0u; j < PD_FEST_NX; j++) {
        acc = fx_add64_sat(acc, fe_mul(x[j], m[j], (uint32_t)sh, st), st);
    }
    return acc;
}

/* exponential average m + (1 - lambda) (v - m), (1 - lambda) in q30 */
static int64_t fe_ema(int64_t m, int64_t v, int32_t one_m_lambda_q30, fx_status_t *st)
{
    return fx_add64_sat(m, fe_mul(fe_sub(v, m, st), one_m_lambda_q30, 30u, st), st);
}

/* square of a q24 value as q32 (through q16, clamped at 2^31: 2^62 fits) */
static int64_t fe_sq24(int64_t v_q24, fx_status_t *st)
{
    const int64_t v16 = fe_clamp64(fx_shr_rnd64(v_q24, 8u, st), -(int64_t)INT32_MAX, (int64_t)INT32_MAX);
    return v16 * v16;
}

static uint32_t fe_sqrt_q32(int64_t v_q32)
{
    return (v_q32 > 0) ? fx_isqrt64((uint64_t)v_q32) : 0u;
}

/* a = -2 cos(2 pi f Td) in q29, f uq32 Hz = BAM per Td (Td = 1 s) */
static int32_t fe_a_of_f(uint32_t f_q32)
{
    int32_t s_q30;
    int32_t c_q30;
    fx_sincos(f_q32, &s_q30, &c_q30);
    return -c_q30;  /* -2c in q29 is -c in q30; |c| <= 2^30 */
}

/* f = 2 asin(sqrt(2 + a) / 2) / (2 pi Td) = 2 atan2(sqrt(2 + a), sqrt(2 - a)) in BAM (Td = 1 s) */
static uint32_t fe_f_of_a(int32_t a_q29, fx_status_t *st)
{
    const int64_t a = (int64_t)a_q29;
    const int64_t two = FE_2P30;
    const uint64_t yp = (uint64_t)fe_clamp64(two + a, 0, (int64_t)2 * two);
    const uint64_t xp = (uint64_t)fe_clamp64(two - a, 0, (int64_t)2 * two);
    const uint32_t y = fx_isqrt64(yp << 29);   /* q29 of sqrt(2 + a) <= 2: < 2^31 */
    const uint32_t x = fx_isqrt64(xp << 29);
    const uint32_t half = fx_atan2_bam((int32_t)y, (int32_t)x, st);  /* in [0, pi/2] */
    return half << 1;
}

uint32_t pd_fest_cinv(const pd_fest_params_t *p, uint32_t f_q32, uint32_t k2_q22)
{
    /* grid coordinates in q28: u = (f - 0.005) / 0.01, v = k2 / 100 (floored: <= 2^-28 of a cell) */
    const uint64_t df = (f_q32 > FE_C_F0) ? ((uint64_t)f_q32 - FE_C_F0) : 0u;
    const uint64_t u_max = ((uint64_t)PD_FEST_CF - 1u) << 28;
    const uint64_t v_max = ((uint64_t)PD_FEST_CK - 1u) << 28;
    const uint64_t u_raw = (df * 100u) >> 4;
    const uint64_t v_raw = ((uint64_t)k2_q22 * 16u) / 25u;    /* k2 2^22 / 100 x 2^6 */
    const uint64_t u = (u_raw < u_max) ? u_raw : u_max;
    const uint64_t v = (v_raw < v_max) ? v_raw : v_max;
    const uint32_t i0 = (uint32_t)(u >> 28);
    const uint32_t j0 = (uint32_t)(v >> 28);
    const uint32_t i = (i0 < (PD_FEST_CF - 2u)) ? i0 : (PD_FEST_CF - 2u);
    const uint32_t j = (j0 < (PD_FEST_CK - 2u)) ? j0 : (PD_FEST_CK - 2u);
    const int64_t fu = (int64_t)u - ((int64_t)i * FE_2P28);  /* [0, 2^28] */
    const int64_t fv = (int64_t)v - ((int64_t)j * FE_2P28);
    const int64_t c00 = (int64_t)p->cinv_q30[i][j];
    const int64_t c01 = (int64_t)p->cinv_q30[i][j + 1u];
    const int64_t c10 = (int64_t)p->cinv_q30[i + 1u][j];
    const int64_t c11 = (int64_t)p->cinv_q30[i + 1u][j + 1u];
    fx_status_t st = 0u;  /* nodes in [0.8, 1.25] (pd_fest_check): |differences| < 2^29, x 2^28 < 2^57 */
    const int64_t c0 = c00 + fx_shr_rnd64((c01 - c00) * fv, 28u, &st);
    const int64_t c1 = c10 + fx_shr_rnd64((c11 - c10) * fv, 28u, &st);
    return fe_u32(c0 + fx_shr_rnd64((c1 - c0) * fu, 28u, &st));
}

static bool fe_shifts_ok(const pd_fest_params_t *p)
{
    uint32_t bad = 0u;
    uint32_t i;
    for (i = 0u; i < PD_FEST_NX; i++) {
        uint32_t j;
        bad |= ((p->ad_sh[i] > 62u) || (p->bd_sh[i] > 62u) || (p->l_sh[i] > 62u)) ? 1u : 0u;
        for (j = 0u; j < PD_FEST_NR; j++) {
            bad |= ((p->dad_sh[j][i] > 62u) || (p->dbd_sh[j][i] > 62u)) ? 1u : 0u;
        }
    }
    return bad == 0u;
}

static bool fe_cinv_ok(const pd_fest_params_t *p)
{
    uint32_t bad = 0u;
    uint32_t i;
    for (i = 0u; i < PD_FEST_CF; i++) {
        uint32_t j;
        for (j = 0u; j < PD_FEST_CK; j++) {
            /* c in [0.8, 1.25] (make_fest_params clamps it) */
            bad |= ((p->cinv_q30[i][j] < 858993459u) || (p->cinv_q30[i][j] > 1342177280u)) ? 1u : 0u;
        }
    }
    return bad == 0u;
}

uint32_t pd_fest_check(const pd_fest_params_t *p)
{
    uint32_t why;
    if ((p->n_sec != 1u) && (p->n_sec != PD_FEST_NSEC)) {
        why = 1u;
    } else if ((p->n_reg != 0u) && (p->n_reg != PD_FEST_NR)) {
        why = 2u;
    } else if ((p->inv_m_q30 < 536870912u) || (p->inv_m_q30 > 1073741824u)) {
        why = 3u;                               /* m_ch in [1, 2] */
    } else if ((p->alpha_hp_q30 == 0u) || (p->alpha_hp_q30 > 536870912u)) {
        why = 4u;                               /* (0, 0.5] */
    } else if ((p->f_hp_min_q32 < FE_FOBS_LO) || (p->f_hp_min_q32 > FE_F_HI)) {
        why = 5u;
    } else if ((p->kappa_hi_q30 < (uint32_t)FE_KAPPA_MAX) || (p->kappa_hi_q30 > 1068373115u) ||
               (p->beta_kappa_q30 > 536870912u)) {
        why = 6u;                               /* kappa_hi in [0.93, 0.995], beta <= 0.5 */
    } else if ((p->sigma_y_q40 < 109951u) || (p->sigma_y_q40 > 109951163u)) {
        why = 7u;                               /* sigma_y in [1e-7, 1e-4] rad */
    } else if (!fe_shifts_ok(p)) {
        why = 8u;
    } else if (!fe_cinv_ok(p)) {
        why = 9u;
    } else {
        why = 0u;
    }
    return why;
}

static void fe_reset(pd_fest_t *s, bool keep_predictor)
{
    uint32_t i;
    uint32_t r;
    if (!keep_predictor) {
        s->pred_init = false;
        for (i = 0u; i < PD_FEST_NX; i++) {
            s->xh[i] = 0;
        }
    }
    for (i = 0u; i < 3u; i++) {
        s->e_prev[i] = 0;
    }
    s->n_run = 0u;
    s->blk_sum = 0;
    s->blk_n = 0u;
    s->blk_valid = 0u;
    s->e_d = 0;
    s->ms_e_q32 = 0;
    s->ms_n_q32 = 0;
    s->gate = false;
    s->aa_x[0] = 0;
    s->aa_x[1] = 0;
    s->aa_y[0] = 0;
    s->aa_y[1] = 0;
    s->hp_x1 = 0;
    s->hp_h1 = 0;
    s->hp_h2 = 0;
    for (r = 0u; r < PD_FEST_NR; r++) {
        for (i = 0u; i < PD_FEST_NX; i++) {
            s->w[r][i] = 0;
        }
        s->phi_sum[r] = 0;
        s->phi_d[r] = 0;
        s->theta_q30[r] = 0;
        s->r1_q24[r] = 0;
        s->r2_q24[r] = 0;
        for (i = 0u; i < PD_FEST_NR; i++) {
            s->pth_q27[r][i] = (r == i) ? FE_P_TH0_Q27 : 0;
        }
    }
    for (i = 0u; i < PD_FEST_NSEC; i++) {
        pd_fest_sec_t *c = &s->sec[i];
        c->p_q30 = FE_P0;
        c->kap_q30 = FE_KAPPA0;
        c->s1_q24 = 0;
        c->s2_q24 = 0;
        c->ms_s_q32 = 0;
        c->ms_in_q32 = 0;
        c->ms_out_q32 = 0;
        c->f_obs_q32 = 0u;
        c->a_q29 = 0;  /* set by pd_fest_step on the first sample after a reset (it needs the table's m_ch) */
    }
    s->d1_q24 = 0;
    s->d2_q24 = 0;
    s->q1_q24 = 0;
    s->q2_q24 = 0;
    s->two = false;
    s->slow_ok = false;
    s->n_single = 0u;
    s->n_excite = 0u;
    s->f_lo_ver_q32 = 0u;
    s->env_i = 0u;
    for (i = 0u; i < PD_FEST_ENV; i++) {
        s->env_q16[i] = 0u;
    }
    s->f_raw_q32 = FE_F0;
    s->f_prev_q32 = FE_F0;
    s->f_hat_q32 = FE_F0;
    s->n_stable = 0u;
    s->n_clamp = 0u;
    s->n_att_bad = 0u;
    s->e_fault = false;
    s->held_conf = false;
    s->state = (uint8_t)PD_FEST_ACQUIRE;
    s->confident = false;
    s->hold_valid = false;
    s->p_a_q30 = 0u;
    s->att_q16 = FE_ONE_Q16;
    s->r_e_q16 = 0u;
    s->kappa_q30 = 0u;
    s->a_set = false;
}

void pd_fest_init(pd_fest_t *s)
{
    s->resets = 0u;
    s->fault = 0u;
    s->st_sticky = 0u;
    s->st_period = 0u;
    s->k_in_period = 0u;
    s->ms_d3_q32 = FE_2P32;   /* sigma_hat starts at the table's sigma_y */
    s->f_rep_q32 = FE_F0;
    s->sig_ref_q16 = FE_ONE_Q16;
    s->sig_hat_q16 = FE_ONE_Q16;
    s->gate_rose = false;
    s->f_moved = false;
    s->r_hold_q16 = 0u;
    s->resid_run = 0u;
    s->period_end = false;
    fe_reset(s, false);
}

/* the notches' starting points: the prior f0 seen through the channel's m_ch; yaw's section 2 starts
   below section 1, where mode 1 sits when section 1 holds mode 2 */
static void fe_start_notch(pd_fest_t *s, const pd_fest_params_t *p, fx_status_t *st)
{
    const uint32_t f_obs0 = fe_u32(fx_div64_shl((int64_t)FE_F0, 30u, (uint64_t)p->inv_m_q30, st));
    s->sec[0].a_q29 = fe_a_of_f(f_obs0);
    s->sec[1].a_q29 = fe_a_of_f((uint32_t)((((uint64_t)f_obs0 * FE_INV_MODE_RATIO_Q30) + FE_HALF_Q30) >> 30));
}

/* ---- per sample: predictor, regressors, noise reference, anti-alias and block sums ------------- */
/* w <- (Ad - L C) w + dA xh + dB M (the sensitivities use xh before its update) */
static void fe_regressors(pd_fest_t *s, const pd_fest_params_t *p, bool y_valid, int64_t m, fx_status_t *st)
{
    uint32_t r;
    for (r = 0u; r < fe_nreg(p); r++) {
        int64_t wn[PD_FEST_NX];
        const int64_t w0 = s->w[r][0];
        uint32_t i;
        for (i = 0u; i < PD_FEST_NX; i++) {
            int64_t acc = fe_mul(m, p->dbd_m[r][i], (uint32_t)p->dbd_sh[r][i], st);
            if (y_valid) {
                acc = fe_sub(acc, fe_mul(w0, p->l_m[i], (uint32_t)p->l_sh[i], st), st);
            }
            acc = fx_add64_sat(acc, fe_row(p->ad_m[i], p->ad_sh[i], s->w[r], st), st);
            wn[i] = fx_add64_sat(acc, fe_row(p->dad_m[r][i], p->dad_sh[r][i], s->xh, st), st);
        }
        for (i = 0u; i < PD_FEST_NX; i++) {
            s->w[r][i] = wn[i];
        }
    }
}

/* the rigid predictor with output injection; returns this sample's residual (0 when invalid) */
static int64_t fe_predict(pd_fest_t *s, const pd_fest_params_t *p, bool y_valid, int64_t y, int64_t m,
                          fx_status_t *st)
{
    int64_t e = 0;
    int64_t xn[PD_FEST_NX];
    uint32_t i;
    if (y_valid) {
        e = fe_sub(y, s->xh[0], st);
        if ((e > (int64_t)FE_E_FAULT_Q40) || (e < -(int64_t)FE_E_FAULT_Q40)) {
            s->e_fault = true;   /* §8 divergence; re-anchor the attitude, nothing enters the filters */
            s->xh[0] = y;
            e = 0;
        }
    }
    fe_regressors(s, p, y_valid, m, st);
    for (i = 0u; i < PD_FEST_NX; i++) {
        int64_t acc = fe_mul(m, p->bd_m[i], (uint32_t)p->bd_sh[i], st);
        acc = fx_add64_sat(acc, fe_mul(e, p->l_m[i], (uint32_t)p->l_sh[i], st), st);
        xn[i] = fx_add64_sat(acc, fe_row(p->ad_m[i], p->ad_sh[i], s->xh, st), st);
    }
    for (i = 0u; i < PD_FEST_NX; i++) {
        s->xh[i] = xn[i];
    }
    return e;
}

/* a valid sample: noise reference from the third difference, anti-alias low-pass, block sums */
static void fe_accumulate(pd_fest_t *s, const pd_fest_params_t *p, int64_t e, const int64_t *phi_k, fx_status_t *st)
{
    int64_t lp;
    uint32_t r;
    if (s->n_run >= 3u) {
        /* D^3 e / sigma_y in q16, clamped at 1024 (its square / 20 then exceeds any clip) */
        const int64_t d3 = e - (3 * s->e_prev[0]) + (3 * s->e_prev[1]) - s->e_prev[2];
        const int64_t rq = fe_clamp64(fx_div64_shl(d3, 16u, (uint64_t)p->sigma_y_q40, st), -FE_2P26, FE_2P26);
        const int64_t rq2 = rq * rq;
        const int64_t v = (int64_t)fx_udiv_rnd64((uint64_t)rq2, 20u);
        const int64_t clip = FE_NOISE_CLIP * s->ms_d3_q32;
        s->ms_d3_q32 = fe_ema(s->ms_d3_q32, (v < clip) ? v : clip, FE_ONE_M_LAMBDA_NOISE, st);
    }
    s->e_prev[2] = s->e_prev[1];
    s->e_prev[1] = s->e_prev[0];
    s->e_prev[0] = e;
    s->n_run = (s->n_run < 3u) ? (s->n_run + 1u) : 3u;
    lp = fe_mul(e, p->aa_b_q29[0], 29u, st);
    lp = fx_add64_sat(lp, fe_mul(s->aa_x[0], p->aa_b_q29[1], 29u, st), st);
    lp = fx_add64_sat(lp, fe_mul(s->aa_x[1], p->aa_b_q29[2], 29u, st), st);
    lp = fe_sub(lp, fe_mul(s->aa_y[0], p->aa_a_q29[0], 29u, st), st);
    lp = fe_sub(lp, fe_mul(s->aa_y[1], p->aa_a_q29[1], 29u, st), st);
    s->aa_x[1] = s->aa_x[0];
    s->aa_x[0] = e;
    s->aa_y[1] = s->aa_y[0];
    s->aa_y[0] = lp;
    s->blk_sum = fx_add64_sat(s->blk_sum, lp, st);
    for (r = 0u; r < fe_nreg(p); r++) {
        s->phi_sum[r] = fx_add64_sat(s->phi_sum[r], phi_k[r], st);
    }
    s->blk_valid++;
}

static void fe_sample(pd_fest_t *s, const pd_fest_params_t *p, bool y_valid, int32_t y_q30, int32_t m_q28,
                      fx_status_t *st)
{
    const int64_t y = (int64_t)y_q30 * 1024;   /* 2^-40 */
    int64_t e = 0;
    int64_t phi_k[PD_FEST_NR];
    phi_k[0] = s->w[0][0];   /* C w_k, aligned with e_k (zero while n_reg = 0) */
    phi_k[1] = s->w[1][0];
    if (!s->pred_init && y_valid) {
        s->xh[0] = y;
        s->xh[1] = 0;
        s->xh[2] = 0;
        s->xh[3] = 0;
        s->pred_init = true;
    }
    if (s->pred_init) {
        e = fe_predict(s, p, y_valid, y, (int64_t)m_q28, st);
    }
    if (y_valid && s->pred_init) {
        fe_accumulate(s, p, e, phi_k, st);
    } else {
        s->n_run = 0u;   /* never difference across a gap */
    }
}

/* theta: RLS of the rigid-model errors on the notch output (reference step_td, "1b") */
static void fe_theta(pd_fest_t *s, const int64_t *psi, uint32_t rms_s_q16, int64_t et, fx_status_t *st)
{
    int64_t ps[PD_FEST_NR];
    int64_t pps[PD_FEST_NR];
    int32_t k[PD_FEST_NR];
    int64_t pn[PD_FEST_NR][PD_FEST_NR];
    int64_t den = FE_LAMBDA_TH_Q24;
    int64_t tr;
    uint32_t r;
    uint32_t c;
    for (r = 0u; r < PD_FEST_NR; r++) {
        ps[r] = (int64_t)fe_i32(fx_div64_shl(psi[r], 16u, (uint64_t)rms_s_q16, st));  /* q24, |.| <= 128 */
    }
    for (r = 0u; r < PD_FEST_NR; r++) {
        pps[r] = 0;
        for (c = 0u; c < PD_FEST_NR; c++) {
            pps[r] = fx_add64_sat(pps[r], fe_mul(ps[c], s->pth_q27[r][c], 27u, st), st);
        }
        den = fx_add64_sat(den, fe_mul(pps[r], (int32_t)ps[r], 24u, st), st);
    }
    den = (den > 1) ? den : 1;  /* >= lambda_th for a positive semi-definite P_th */
    for (r = 0u; r < PD_FEST_NR; r++) {
        k[r] = fe_i32(fx_div64_shl(pps[r], 24u, (uint64_t)den, st));   /* q24 */
        s->theta_q30[r] = (int32_t)fe_clamp64(fx_add64_sat((int64_t)s->theta_q30[r], fe_mul(et, k[r], 18u, st), st),
                                              -(int64_t)FE_THETA_MAX_Q30, (int64_t)FE_THETA_MAX_Q30);
    }
    /* P_th - K Pps', formed on the upper triangle and mirrored (symmetric by construction) */
    for (r = 0u; r < PD_FEST_NR; r++) {
        for (c = r; c < PD_FEST_NR; c++) {
            const int64_t d = fe_sub((int64_t)s->pth_q27[r][c], fe_mul(pps[c], k[r], 21u, st), st);
            pn[r][c] = fe_mul(d, FE_INV_LAMBDA_TH, 30u, st);
            pn[c][r] = pn[r][c];
        }
    }
    tr = fx_add64_sat(pn[0][0], pn[1][1], st);
    if (tr > (int64_t)FE_P_TH_MAX_Q27) {
        const int32_t sc = fe_i32(fx_div64_shl((int64_t)FE_P_TH_MAX_Q27, 30u, (uint64_t)tr, st));
        for (r = 0u; r < PD_FEST_NR; r++) {
            for (c = 0u; c < PD_FEST_NR; c++) {
                pn[r][c] = fe_mul(pn[r][c], sc, 30u, st);
            }
        }
    }
    for (r = 0u; r < PD_FEST_NR; r++) {
        for (c = 0u; c < PD_FEST_NR; c++) {
            s->pth_q27[r][c] = fx_sat32(pn[r][c], st);
        }
    }
}

/* kappa target 1 - beta w Td within [kappa_max, kappa_hi], w Td in q30 from a section's last f_obs */
static int64_t fe_kappa_target(const pd_fest_params_t *p, uint32_t f_obs_q32, fx_status_t *st)
{
    const int64_t w_td = (int64_t)(((uint64_t)f_obs_q32 * FE_TWO_PI_Q28) >> 30);
    return fe_clamp64(fe_sub((int64_t)FE_ONE_Q30, fe_mul(w_td, (int32_t)p->beta_kappa_q30, 30u, st), st),
                      (int64_t)FE_KAPPA_MAX, (int64_t)p->kappa_hi_q30);
}

/* f_obs x scale (q30), rounded */
static uint32_t fe_fscale(uint32_t f_q32, uint32_t scale_q30)
{
    return (uint32_t)((((uint64_t)f_q32 * scale_q30) + FE_HALF_Q30) >> 30);
}

/* yaw's section 2 while its notch anneals: keep its ratio to section 1 (whose a has adapted this Td) */
static void fe_comove(pd_fest_t *s, const pd_fest_params_t *p, fx_status_t *st)
{
    const uint32_t f1_old = s->sec[0].f_obs_q32;
    if ((f1_old > 0u) && ((int64_t)s->sec[1].kap_q30 < (fe_kappa_target(p, s->sec[1].f_obs_q32, st) - FE_SEC2_COMOVE_DK))) {
        const uint64_t f1_new = (uint64_t)fe_f_of_a(s->sec[0].a_q29, st);
        const uint64_t f2 = fx_udiv_rnd64((uint64_t)s->sec[1].f_obs_q32 * f1_new, (uint64_t)f1_old);
        s->sec[1].a_q29 = fe_a_of_f((f2 < (uint64_t)UINT32_MAX) ? (uint32_t)f2 : UINT32_MAX);
    }
}

/* a section's RLS on a and its kappa schedule (reference step_td, "6") */
static void fe_adapt_notch(pd_fest_t *s, const pd_fest_params_t *p, uint32_t i, int64_t phi, int64_t et,
                           fx_status_t *st)
{
    pd_fest_sec_t *c = &s->sec[i];
    const int64_t phi2_q30 = fe_mul(phi * phi, (int32_t)c->p_q30, 48u, st);  /* phi^2 P: q48 x q30 */
    const uint64_t den = (uint64_t)FE_LAMBDA_Q30 + (uint64_t)phi2_q30;
    const int64_t pn = (int64_t)fx_udiv_rnd64((uint64_t)c->p_q30 << 30, den);
    int64_t a_lo;
    int64_t a_hi;
    int64_t t;
    int64_t k_tgt;
    c->p_q30 = (uint32_t)fe_clamp64(pn, (int64_t)FE_P_MIN, (int64_t)FE_P_MAX);
    if (i == 0u) {
        a_lo = (int64_t)fe_a_of_f(FE_FOBS_LO);
        a_hi = (int64_t)fe_a_of_f(FE_FOBS_HI);
    } else {
        /* section 2 searches [f1 / 2.2, f1 / 1.3] below section 1's line of the last Td */
        fe_comove(s, p, st);
        a_lo = (int64_t)fe_a_of_f(fe_fscale(s->sec[0].f_obs_q32, FE_INV_SEC2_HI_Q30));
        a_hi = (int64_t)fe_a_of_f(fe_fscale(s->sec[0].f_obs_q32, FE_INV_SEC2_LO_Q30));
    }
    t = fe_mul(et, (int32_t)c->p_q30, 30u, st);                      /* P et, q24 */
    c->a_q29 = (int32_t)fe_clamp64(fe_sub((int64_t)c->a_q29, fe_mul(t, (int32_t)phi, 19u, st), st), a_lo, a_hi);
    k_tgt = fe_kappa_target(p, c->f_obs_q32, st);
    c->kap_q30 = fe_u32(fe_sub(k_tgt, fe_mul(k_tgt - (int64_t)c->kap_q30, FE_RHO_KAPPA, 30u, st), st));
}

/* f_hat = f_obs / (m_ch c(f, k2)), c evaluated at the once-corrected estimate */
static void fe_f_update(pd_fest_t *s, const pd_fest_params_t *p, uint32_t k2_q22)
{
    const uint64_t half = FE_HALF_Q30;
    const uint64_t fr = (((uint64_t)s->f_rep_q32 * p->inv_m_q30) + half) >> 30;     /* < 2^32 */
    const uint64_t f1 = ((fr * pd_fest_cinv(p, (uint32_t)fr, k2_q22)) + half) >> 30;  /* x <= 1.25 */
    const uint64_t fh = ((fr * pd_fest_cinv(p, (uint32_t)f1, k2_q22)) + half) >> 30;
    s->f_raw_q32 = (uint32_t)((fh < FE_F_LO) ? FE_F_LO : ((fh > FE_F_HI) ? FE_F_HI : fh));
}

/* yaw: a pair's ratio hi / lo in [1.5, 2.0], without a division */
static bool fe_ratio_ok(uint32_t lo, uint32_t hi)
{
    return (((uint64_t)hi * 2u) >= ((uint64_t)lo * 3u)) && ((uint64_t)hi <= ((uint64_t)lo * 2u));
}

/* ms_out <= att^2 ms_in (att^2 in q30) */
static bool fe_att_le(int64_t ms_out, int64_t ms_in, int32_t att_sq_q30, fx_status_t *st)
{
    return ms_out <= fe_mul(ms_in, att_sq_q30, 30u, st);
}

/* yaw: a single line is mode 1 if it is a real line (section 1 notches it) and (a) too low to be
   mode 2, (b) continues the lower line of a verified pair, or (c) passed the decay proof */
static bool fe_single_proof(const pd_fest_t *s, uint32_t f_q32, fx_status_t *st)
{
    const bool line = fe_att_le(s->sec[0].ms_out_q32, s->sec[0].ms_in_q32, FE_SINGLE_ATT_SQ, st);
    const uint32_t v = s->f_lo_ver_q32;
    const uint32_t d = (f_q32 > v) ? (f_q32 - v) : (v - f_q32);
    const bool low = f_q32 <= FE_SINGLE_MAX_Q32;
    const bool cont = (v > 0u) && ((uint64_t)d <= (((uint64_t)v * FE_VER_TOL_Q30) >> 30));
    return line && (low || cont || s->slow_ok);
}

/* a second pass of section 1's notch (a, kappa a and kappa^2 in q29 / q29 / q30) over in, states x1, x2 */
static int64_t fe_pass(int64_t in, int32_t a_q29, int64_t ka, int64_t kk, int64_t *x1, int64_t *x2, fx_status_t *st)
{
    const int64_t t0 = fe_sub(fe_sub(in, fe_mul(*x1, (int32_t)ka, 29u, st), st), fe_mul(*x2, (int32_t)kk, 30u, st), st);
    const int64_t out = fx_add64_sat(fx_add64_sat(t0, fe_mul(*x1, a_q29, 29u, st), st), *x2, st);
    *x2 = *x1;
    *x1 = t0;
    return out;
}

/* one notch section over in (q24) at this Td; returns what the next section sees */
static int64_t fe_section(pd_fest_t *s, const pd_fest_params_t *p, uint32_t i, int64_t in, const int64_t *psi,
                          bool adapt, fx_status_t *st)
{
    pd_fest_sec_t *c = &s->sec[i];
    const int32_t a = c->a_q29;
    const int64_t ka = fe_mul((int64_t)c->kap_q30, a, 30u, st);                   /* kappa a, q29 */
    const int64_t kk = fe_mul((int64_t)c->kap_q30, (int32_t)c->kap_q30, 30u, st);  /* kappa^2, q30 */
    const int64_t s0 = fe_sub(fe_sub(in, fe_mul(c->s1_q24, (int32_t)ka, 29u, st), st),
                              fe_mul(c->s2_q24, (int32_t)kk, 30u, st), st);
    const int64_t eps = fx_add64_sat(fx_add64_sat(s0, fe_mul(c->s1_q24, a, 29u, st), st), c->s2_q24, st);
    int64_t out = eps;
    uint32_t rms_s;
    int64_t phi;
    int64_t et;
    c->ms_s_q32 = fe_ema(c->ms_s_q32, fe_sq24(s0, st), FE_ONE_M_LAMBDA_S, st);
    rms_s = fe_sqrt_q32(c->ms_s_q32);
    rms_s = (rms_s > FE_RMS_S_MIN_Q16) ? rms_s : FE_RMS_S_MIN_Q16;
    phi = (int64_t)fe_i32(fx_div64_shl(c->s1_q24, 16u, (uint64_t)rms_s, st));   /* q24, |.| <= 128 */
    et = (int64_t)fe_i32(fx_div64_shl(eps, 16u, (uint64_t)rms_s, st));
    if (adapt && (i == 0u) && (fe_nreg(p) > 0u)) {
        fe_theta(s, psi, rms_s, et, st);
    }
    if (adapt) {
        fe_adapt_notch(s, p, i, phi, et, st);
    }
    c->ms_in_q32 = fe_ema(c->ms_in_q32, fe_sq24(in, st), FE_ONE_M_LAMBDA_ATT, st);
    c->ms_out_q32 = fe_ema(c->ms_out_q32, fe_sq24(eps, st), FE_ONE_M_LAMBDA_ATT, st);
    c->s2_q24 = c->s1_q24;
    c->s1_q24 = s0;
    if ((i == 0u) && (fe_nsec(p) == PD_FEST_NSEC)) {
        /* yaw: section 2 sees section 1's line notched twice more, the third pass wider (kappa 0.97),
           both with section 1's coefficients of this Td before its update */
        const int64_t ka3 = fe_mul((int64_t)FE_KAPPA_PASS3, a, 30u, st);
        out = fe_pass(eps, a, ka, kk, &s->d1_q24, &s->d2_q24, st);
        out = fe_pass(out, a, ka3, FE_KAPPA_PASS3_SQ, &s->q1_q24, &s->q2_q24, st);
    }
    return out;
}

/* step 7: the sections' lines, the reported line and (yaw) whether it is mode 1; f_hat from it */
static void fe_lines(pd_fest_t *s, const pd_fest_params_t *p, uint32_t k2_q22, bool adapt, fx_status_t *st)
{
    uint32_t f_rep;
    bool line_ok = true;
    uint32_t i;
    for (i = 0u; i < fe_nsec(p); i++) {
        s->sec[i].f_obs_q32 = fe_f_of_a(s->sec[i].a_q29, st);
    }
    f_rep = s->sec[0].f_obs_q32;
    if (fe_nsec(p) == PD_FEST_NSEC) {
        const pd_fest_sec_t *c1 = &s->sec[0];
        const pd_fest_sec_t *c2 = &s->sec[1];
        const uint32_t lo = (c1->f_obs_q32 < c2->f_obs_q32) ? c1->f_obs_q32 : c2->f_obs_q32;
        const uint32_t hi = (c1->f_obs_q32 < c2->f_obs_q32) ? c2->f_obs_q32 : c1->f_obs_q32;
        /* two lines: section 1 leaves a real line for section 2, which notches most of it */
        s->two = (c1->ms_out_q32 >= fe_mul(c1->ms_in_q32, FE_TWO_ATT1_SQ, 30u, st)) &&
                 fe_att_le(c2->ms_out_q32, c2->ms_in_q32, FE_TWO_ATT2_SQ, st);
        if (s->two) {
            /* the pair, judged once section 2 has narrowed and while the cascade removes most of
               the residual */
            f_rep = lo;
            line_ok = fe_ratio_ok(lo, hi) && (c2->kap_q30 >= FE_KAPPA_CONF) &&
                      fe_att_le(c2->ms_out_q32, c1->ms_in_q32, FE_PAIR_ATT_SQ, st);
        } else {
            line_ok = fe_single_proof(s, f_rep, st);
        }
    }
    s->f_rep_q32 = f_rep;
    s->f_moved = s->f_moved || (adapt && line_ok);
    if (adapt && line_ok) {
        fe_f_update(s, p, k2_q22);
    }
}

/* ---- per Td: residual, high-pass, gate, normalisation, notch, frequency ------------------------- */
/* the high-pass line: the reported line (pitch, roll), section 1's / 1.74 (yaw), floored */
static uint32_t fe_hp_line(const pd_fest_t *s, const pd_fest_params_t *p, fx_status_t *st)
{
    const uint32_t f = (fe_nsec(p) == PD_FEST_NSEC)
                           ? fe_fscale(fe_f_of_a(s->sec[0].a_q29, st), FE_INV_MODE_RATIO_Q30) : s->f_rep_q32;
    return (f > p->f_hp_min_q32) ? f : p->f_hp_min_q32;
}

static void fe_td(pd_fest_t *s, const pd_fest_params_t *p, uint32_t k2_q22, fx_status_t *st)
{
    const bool have = s->blk_valid > 0u;
    const uint32_t n_reg = fe_nreg(p);
    const int64_t sy = (int64_t)p->sigma_y_q40;
    int64_t v_d;
    int64_t en;
    int64_t en2;
    int64_t den_n;
    int64_t in;
    int64_t psi[PD_FEST_NR] = {0, 0};
    uint32_t r_n;
    uint32_t f_hp;
    int32_t lam_n;
    int64_t lam_rel;
    uint32_t r;
    bool adapt;
    if (have) {
        s->e_d = fx_div64_shl(s->blk_sum, 0u, (uint64_t)s->blk_valid, st);
        for (r = 0u; r < n_reg; r++) {
            s->phi_d[r] = fx_div64_shl(s->phi_sum[r], 0u, (uint64_t)s->blk_valid, st);
        }
    }
    v_d = s->e_d;
    for (r = 0u; r < n_reg; r++) {
        v_d = fe_sub(v_d, fe_mul(s->phi_d[r], s->theta_q30[r], 30u, st), st);
    }
    /* high-pass: rho = 1 - alpha 2 pi f_hp Td */
    f_hp = fe_hp_line(s, p, st);
    {
        /* alpha f_hp <= 0.5 x 0.3 Hz: w = 2 pi alpha f_hp Td < 1 in q30, rho in (0, 1] */
        const uint64_t af_q30 = ((uint64_t)p->alpha_hp_q30 * f_hp) >> 32;
        const uint32_t w_q30 = (uint32_t)((af_q30 * FE_TWO_PI_Q28) >> 28);
        const int32_t rho = FE_ONE_Q30 - (int32_t)w_q30;
        const int64_t h1 = fx_add64_sat(fe_sub(v_d, s->hp_x1, st), fe_mul(s->hp_h1, rho, 30u, st), st);
        const int64_t h2 = fx_add64_sat(fe_sub(h1, s->hp_h1, st), fe_mul(s->hp_h2, rho, 30u, st), st);
        s->hp_x1 = v_d;
        s->hp_h1 = h1;
        s->hp_h2 = h2;
        v_d = h2;
    }
    /* noise reference and the gate, as ratios to sigma_y */
    s->sig_hat_q16 = fe_sqrt_q32(s->ms_d3_q32);
    s->sig_ref_q16 = (s->sig_hat_q16 > FE_SIG_FLOOR_Q16) ? s->sig_hat_q16 : FE_SIG_FLOOR_Q16;
    en = fe_clamp64(fx_div64_shl(v_d, 16u, (uint64_t)sy, st), -FE_2P30, FE_2P30);
    en2 = en * en;                                                     /* q32 */
    s->ms_e_q32 = fe_ema(s->ms_e_q32, en2, FE_ONE_M_LAMBDA_RMS, st);
    s->r_e_q16 = fe_sqrt_q32(s->ms_e_q32);
    if (!s->gate && ((uint64_t)s->r_e_q16 >= ((uint64_t)FE_GATE_ON * s->sig_ref_q16))) {
        s->gate = true;
        s->gate_rose = true;
    } else if (s->gate && ((uint64_t)s->r_e_q16 < ((uint64_t)FE_GATE_OFF * s->sig_ref_q16))) {
        s->gate = false;
    } else {
        /* the gate holds */
    }
    /* normaliser: fast attack, release 1 - k_norm f_obs Td */
    lam_rel = fe_clamp64((int64_t)FE_ONE_Q30 - (int64_t)(((uint64_t)FE_K_NORM * s->f_rep_q32) >> 32),
                         FE_LAMBDA_NORM_LO, FE_LAMBDA_NORM);
    lam_n = (en2 > s->ms_n_q32) ? FE_LAMBDA_NORM_ATT : (int32_t)lam_rel;
    s->ms_n_q32 = fe_ema(s->ms_n_q32, en2, FE_ONE_Q30 - lam_n, st);
    r_n = fe_sqrt_q32(s->ms_n_q32);
    den_n = (int64_t)((r_n > s->sig_ref_q16) ? r_n : s->sig_ref_q16);   /* >= 2^15 */
    in = fe_clamp64(fx_div64_shl(en, 24u, (uint64_t)den_n, st), -FE_U_MAX_Q24, FE_U_MAX_Q24);
    adapt = have && s->gate && ((s->state == (uint8_t)PD_FEST_ACQUIRE) || (s->state == (uint8_t)PD_FEST_TRACK));
    /* the regressors through section 1's notch (its a, kappa before this update) */
    {
        const pd_fest_sec_t *c = &s->sec[0];
        const int64_t ka = fe_mul((int64_t)c->kap_q30, c->a_q29, 30u, st);
        const int64_t kk = fe_mul((int64_t)c->kap_q30, (int32_t)c->kap_q30, 30u, st);
        for (r = 0u; r < n_reg; r++) {
            const int64_t pn16 = fx_div64_shl(s->phi_d[r], 16u, (uint64_t)sy, st);
            const int64_t phin = fx_div64_shl(pn16, 24u, (uint64_t)den_n, st);
            const int64_t r0 = fe_sub(fe_sub(phin, fe_mul(s->r1_q24[r], (int32_t)ka, 29u, st), st),
                                      fe_mul(s->r2_q24[r], (int32_t)kk, 30u, st), st);
            psi[r] = fx_add64_sat(fx_add64_sat(r0, fe_mul(s->r1_q24[r], c->a_q29, 29u, st), st), s->r2_q24[r], st);
            s->r2_q24[r] = s->r1_q24[r];
            s->r1_q24[r] = r0;
        }
    }
    /* the notch sections, cascaded (two call sites, not a loop: -Os then keeps fe_section out of line,
       and pd_fest_step's frame under the 256-byte per-function budget of the M3 build) */
    in = fe_section(s, p, 0u, in, psi, adapt, st);
    if (fe_nsec(p) == PD_FEST_NSEC) {
        (void)fe_section(s, p, 1u, in, psi, adapt, st);
    }
    /* frequency (frozen outside ACQUIRE / TRACK) */
    fe_lines(s, p, k2_q22, adapt, st);
}

static void fe_enter_hold(pd_fest_t *s, bool held_conf)
{
    s->state = (uint8_t)PD_FEST_HOLD;
    s->held_conf = held_conf;
    s->gate_rose = false;
    s->r_hold_q16 = (s->r_e_q16 > FE_SIG_FLOOR_Q16) ? s->r_e_q16 : FE_SIG_FLOOR_Q16;
}

static uint32_t fe_inc(uint32_t n)
{
    return (n < FE_N_MAX) ? (n + 1u) : FE_N_MAX;
}

/* the state machine of a period end that raised no fault; other_line (yaw): the residual is still
   strong while the reported line fades, so another line has taken over: re-acquire, do not hold */
static void fe_transition(pd_fest_t *s, bool conf_ok, bool fading, bool keep, bool other_line)
{
    if (s->state == (uint8_t)PD_FEST_ACQUIRE) {
        if (!s->gate) {
            fe_enter_hold(s, false);
        } else if (conf_ok) {
            s->state = (uint8_t)PD_FEST_TRACK;
            s->resid_run = 0u;
        } else {
            /* still acquiring */
        }
    } else if (s->state == (uint8_t)PD_FEST_TRACK) {
        if (!s->gate || (fading && !other_line)) {
            fe_enter_hold(s, true);
        } else if (fading || !keep) {
            s->state = (uint8_t)PD_FEST_ACQUIRE;
            s->n_stable = 0u;
        } else {
            /* tracking */
        }
    } else if (s->state == (uint8_t)PD_FEST_HOLD) {
        if (s->gate_rose || ((uint64_t)s->r_e_q16 >= ((uint64_t)FE_RISE_HOLD * s->r_hold_q16))) {
            s->state = (uint8_t)PD_FEST_ACQUIRE;
            s->held_conf = false;
            s->n_stable = 0u;
        }
    } else {
        /* FAULT is handled by the caller */
    }
}

/* the §8 divergence reasons of this period end */
static uint32_t fe_faults(const pd_fest_t *s, uint32_t n_y, bool jump, bool numeric)
{
    uint32_t fault = 0u;
    if (((uint64_t)s->n_clamp * n_y) > FE_CLAMP_SAMPLES) {
        fault |= PD_FEST_F_CLAMP;
    }
    if ((s->state == (uint8_t)PD_FEST_TRACK) && jump) {
        fault |= PD_FEST_F_JUMP;
    }
    if (s->n_att_bad >= FE_N_ATTEN_FAULT) {
        fault |= PD_FEST_F_ATTEN;
    }
    if (s->e_fault) {
        fault |= PD_FEST_F_RESID;
    }
    if (numeric) {
        fault |= PD_FEST_F_NUMERIC;
    }
    return fault;
}

/* yaw, per period: the residual envelope ring, the single-line decay proof; returns tone_ok */
static bool fe_yaw_period(pd_fest_t *s, uint32_t n_y, fx_status_t *st)
{
    uint32_t r_old = 0u;  /* the envelope's peak over the window (a growing start-up envelope must not pass) */
    uint32_t i;
    bool tone_ok;
    s->env_q16[s->env_i] = s->r_e_q16;
    s->env_i = ((s->env_i + 1u) < PD_FEST_ENV) ? (s->env_i + 1u) : 0u;
    for (i = 0u; i < PD_FEST_ENV; i++) {
        r_old = (s->env_q16[i] > r_old) ? s->env_q16[i] : r_old;
    }
    if (s->two) {
        const uint32_t f1 = s->sec[0].f_obs_q32;
        const uint32_t f2 = s->sec[1].f_obs_q32;
        tone_ok = (f1 < f2) ? fe_ratio_ok(f1, f2) : fe_ratio_ok(f2, f1);
        s->n_single = 0u;
        s->slow_ok = false;
    } else {
        /* decay proof: r_old <= r_e (1 + x + x^2 / 2), x = zeta 2 pi f PD_FEST_ENV n_y Ty, i.e. the
           envelope decays no faster than a mode of damping zeta_single; x clamped at 1 (n_y 16 and
           f <= 0.3 Hz: x <= 0.85) so that r_e (1 + x + x^2 / 2) < 2^32 x 2^32 */
        const uint64_t x0 = (((uint64_t)s->f_rep_q32 * FE_ZETA_ENV_TY_Q30) >> 32) * n_y;
        const uint64_t x = (x0 < (uint64_t)FE_ONE_Q30) ? x0 : (uint64_t)FE_ONE_Q30;
        const uint64_t poly = (uint64_t)FE_ONE_Q30 + x + ((x * x) >> 31);
        s->n_single = fe_inc(s->n_single);
        s->slow_ok = (s->n_single >= PD_FEST_ENV) && (s->n_excite >= FE_N_PROOF) &&
                     (s->f_rep_q32 >= FE_F_PROOF_MIN_Q32) && (r_old > 0u) &&
                     (((uint64_t)r_old << 30) <= ((uint64_t)s->r_e_q16 * poly));
        tone_ok = fe_single_proof(s, s->f_rep_q32, st);
    }
    return tone_ok;
}

/* the period end's state decision: FAULT handling, or the transitions of a fault-free period */
static void fe_decide(pd_fest_t *s, uint32_t fault, bool numeric, bool conf_ok, bool keep, bool yaw)
{
    if (s->state == (uint8_t)PD_FEST_FAULT) {
        /* one period in FAULT (k2_cold applied by the law), then ACQUIRE at f0; the predictor is kept
           unless a numeric fault, or a second RESID FAULT since the last TRACK, says its rates are wrong
           (RESID zeroes the residual, so the injection could never correct them) */
        const bool keep_pred = (!numeric) && (s->resid_run < 2u);
        s->resid_run = keep_pred ? s->resid_run : 0u;
        fe_reset(s, keep_pred);
    } else if (fault != 0u) {
        s->state = (uint8_t)PD_FEST_FAULT;
        s->fault = fault;
        fx_cnt_inc(&s->resets);
        s->resid_run = ((fault & PD_FEST_F_RESID) != 0u) ? fe_inc(s->resid_run) : 0u;
    } else {
        const bool other_line = yaw && ((uint64_t)s->r_e_q16 >= ((uint64_t)FE_GATE_ON * s->sig_ref_q16));
        fe_transition(s, conf_ok, s->att_q16 > FE_ATT_LOSE_Q16, keep, other_line);
    }
    if (yaw && s->two && (s->state == (uint8_t)PD_FEST_TRACK)) {
        s->f_lo_ver_q32 = s->f_rep_q32;   /* the lower line of a verified pair */
    }
}

/* outputs of the period end; the published f_hat moves in TRACK only by >= 0.5 % */
static void fe_publish(pd_fest_t *s)
{
    const uint64_t fr = (uint64_t)s->f_raw_q32;
    const uint64_t fpub = (uint64_t)s->f_hat_q32;
    const uint64_t d = (fr > fpub) ? (fr - fpub) : (fpub - fr);
    s->f_prev_q32 = s->f_raw_q32;
    s->confident = s->state == (uint8_t)PD_FEST_TRACK;
    s->hold_valid = (s->state == (uint8_t)PD_FEST_HOLD) && s->held_conf;
    if (((d * 1000u) >= (fpub * FE_PUB_HYST_PERMILLE)) || !s->confident) {
        s->f_hat_q32 = s->f_raw_q32;
    }
    s->p_a_q30 = s->sec[0].p_q30;
    s->kappa_q30 = s->sec[0].kap_q30;
}

static void fe_period(pd_fest_t *s, const pd_fest_params_t *p, uint32_t n_y)
{
    const uint32_t f = s->f_raw_q32;
    const uint64_t fp = (uint64_t)s->f_prev_q32;              /* >= f_lo > 0 */
    const uint64_t dfa = (f > s->f_prev_q32) ? ((uint64_t)f - fp) : (fp - (uint64_t)f);
    const bool moved = s->f_moved;
    const bool on_clamp = (f <= FE_F_LO) || (f >= FE_F_HI);
    const bool active = (s->state == (uint8_t)PD_FEST_ACQUIRE) || (s->state == (uint8_t)PD_FEST_TRACK);
    const bool yaw = fe_nsec(p) == PD_FEST_NSEC;
    const pd_fest_sec_t *c1 = &s->sec[0];
    const int64_t ms_in = (c1->ms_in_q32 > 1) ? c1->ms_in_q32 : 1;
    uint64_t att2;
    fx_status_t st_att = 0u;  /* a ratio beyond 2^24 is clamped below, not an error */
    uint32_t fault;
    bool numeric;
    bool conf_ok;
    bool tone_ok = true;
    s->f_moved = false;
    s->n_stable = (((dfa * 100u) < (fp * FE_STAB_PERCENT)) && moved) ? fe_inc(s->n_stable) : 0u;
    s->n_clamp = (active && s->gate && on_clamp && moved) ? fe_inc(s->n_clamp) : 0u;
    s->n_excite = s->gate ? fe_inc(s->n_excite) : 0u;   /* compared with 50 only: saturates at FE_N_MAX */
    /* att = sqrt(ms_out / ms_in) in q16 (the cascade's output over section 1's input), capped at 2^24 */
    att2 = (uint64_t)fe_clamp64(fx_div64_shl(s->sec[fe_nsec(p) - 1u].ms_out_q32, 16u, (uint64_t)ms_in, &st_att),
                                0, FE_2P40);
    s->att_q16 = fx_isqrt64(att2 << 16);
    s->n_att_bad = (active && s->gate && (c1->kap_q30 >= FE_KAPPA_CONF) && (s->att_q16 >= FE_ONE_Q16))
                       ? fe_inc(s->n_att_bad) : 0u;
    if (yaw) {
        tone_ok = fe_yaw_period(s, n_y, &s->st_period);
    }
    numeric = s->st_period != 0u;
    conf_ok = s->gate && (c1->kap_q30 >= FE_KAPPA_CONF) && (c1->p_q30 <= FE_P_CONF) &&
              (s->att_q16 <= FE_ATT_CONF_Q16) && (s->n_stable >= FE_N_STAB) &&
              (((uint64_t)s->n_stable * n_y * s->f_rep_q32) >= ((uint64_t)FE_CYC_Q32_TY << 32)) && !on_clamp &&
              tone_ok;
    fault = fe_faults(s, n_y, (dfa * FE_JUMP_FIFTHS) > fp, numeric);
    s->st_sticky |= s->st_period;
    s->st_period = 0u;
    fe_decide(s, fault, numeric, conf_ok, (!on_clamp) && tone_ok, yaw);
    fe_publish(s);
}

void pd_fest_step(pd_fest_t *s, const pd_fest_params_t *p, uint32_t n_y, bool y_valid, int32_t y_q30,
                  int32_t m_q28, uint32_t k2_q22)
{
    fx_status_t st = 0u;
    s->period_end = false;
    if (!s->a_set) {
        fe_start_notch(s, p, &st);   /* after init or a reset */
        s->a_set = true;
    }
    fe_sample(s, p, y_valid, y_q30, m_q28, &st);
    s->blk_n++;
    if (s->blk_n == PD_FEST_DECIM) {
        fe_td(s, p, k2_q22, &st);
        s->blk_n = 0u;
        s->blk_valid = 0u;
        s->blk_sum = 0;
        s->phi_sum[0] = 0;
        s->phi_sum[1] = 0;
    }
    s->st_period |= st;
    s->k_in_period++;
    if (s->k_in_period >= n_y) {
        s->k_in_period = 0u;
        fe_period(s, p, n_y);
        s->period_end = true;
    }
}
