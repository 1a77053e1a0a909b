/*
 * obs.c — adaptive observer step (spec 10-observer §4.4), fixed point.
 *
 * Why the EKF works in scaled coordinates: in SI the covariance spans eight decades
 * (1e-13 .. 1e-5), far beyond one int32 format. With power-of-two scales S the scaled
 * covariance P_s = S^-1 P S^-1 lies in [7e-6, 1.44] and fits q30. Because the scales are powers
 * of two, every change of coordinates is a change of Q format, never a multiply: an SI value
 * v in qN is the scaled value v / 2^ls in q(N + ls).
 *
 * Designated saturating points (spec 10-observer §4.4): the command vector limit, the conversion
 * to actuator counts, the kappa clamp and the covariance floor/ceiling. They report through
 * their own health bits and never set fx SAT bits, so any SAT bit in the health word marks an
 * unexpected saturation.
 */
#include "obs.h"

#define MIN_MATRIX_Q 16u                /* spec 10-observer §4.5: never fewer fraction bits */
#define Q_LSB4   4                      /* smallest scaled process noise, LSB of q30 */
FX_STATIC_ASSERT(obs_sa_one28, FX_Q_RAT_FITS(1, 1, 28));

/* ------------------------------------------------------------------ small helpers */

/* Q of EKF state j: x in q29, kappa in q28. */
static uint32_t state_q(uint32_t j)
{
    uint32_t q = OBS_KAPPA_Q;
    if (j < OBS_NX) {
        q = OBS_X_Q;
    }
    return q;
}

/* A derived format as uint32 (the checks in obs_params_check keep it in [0, 62]). */
static uint32_t qfmt(int32_t q)
{
    return (q < 0) ? 0u : (uint32_t)q;
}

static uint32_t valid_q(uint32_t q)
{
    return ((q >= MIN_MATRIX_Q) && (q <= FX_Q_MAX)) ? 1u : 0u;
}

/* Exact sum_j a_j x_j [qa + qx] + sum_k b_k v_k [qb + qx], in q(*qs) = q(max(qa, qb) + qx). */
static int64_t affine_sum(const int32_t *a, uint32_t qa, const int32_t *x, uint32_t nx,
                          const int32_t *b, uint32_t qb, const int32_t *v, uint32_t nv,
                          uint32_t qx, uint32_t *qs, fx_status_t *st)
{
    uint32_t qm = (qa > qb) ? qa : qb;
    int64_t s1 = fx_shl64_chk(fx_dot_acc(a, x, nx, st), qm - qa, st);
    int64_t s2 = fx_shl64_chk(fx_dot_acc(b, v, nv, st), qm - qb, st);
    fx_status_t acc = 0u;
    int64_t s = fx_add64_sat(s1, s2, &acc);
    *st |= acc;
    *qs = qm + qx;
    return s;
}

/* y = round(sum_j a_j x_j [qa + qx] + sum_k b_k v_k [qb + qx]) in qy, one rounding. */
static int32_t affine_row(const int32_t *a, uint32_t qa, const int32_t *x, uint32_t nx,
                          const int32_t *b, uint32_t qb, const int32_t *v, uint32_t nv,
                          uint32_t qx, uint32_t qy, fx_status_t *st)
{
    uint32_t qs;
    int64_t s = affine_sum(a, qa, x, nx, b, qb, v, nv, qx, &qs, st);
    int32_t y = 0;
    if (qs >= qy) {
        y = fx_rshift_sat(s, qs - qy, st);
    } else {
        *st |= FX_ST_ARG;
    }
    return y;
}

/* Phi(kappa) = Phi0 + (kappa - kappa0) Phi_k in q_phi0; Gamma(kappa) likewise in q_gam0. */
static void build_model(obs_state_t *s, const obs_params_t *p, fx_status_t *st)
{
    uint32_t i;
    int32_t dk_q28 = fx_sub_sat(s->kappa_q28, p->kappa0_q28, st);
    for (i = 0u; i < (OBS_NX * OBS_NX); i++) {
        int32_t t = fx_mul(dk_q28, OBS_KAPPA_Q, p->phik[i], p->q_phik, p->q_phi0, st);
        s->phi_q[i] = fx_add_sat(p->phi0[i], t, st);
    }
    for (i = 0u; i < (OBS_NX * OBS_NU); i++) {
        int32_t t = fx_mul(dk_q28, OBS_KAPPA_Q, p->gamk[i], p->q_gamk, p->q_gam0, st);
        s->gam_q[i] = fx_add_sat(p->gam0[i], t, st);
    }
}

/* The scaled transition matrix F_s = S^-1 [[Phi, f], [0, 1]] S in q28. f = Phi_k x + Gamma_k u
   is formed directly in its scaled Q so no precision is lost to the power-of-two scaling, and is
   held in int64: the scaling multiplies the omega rows by 2^(ls_k - ls_w) = 4096, which on M-phys
   takes f_s past int32's q28 range (8) once |mu| passes 0.18 rad, while the products f_s P_s still
   fit the exact int64 sums of predict (fx_dot_wide; README "Formats and ranges"). */
static void build_f(obs_state_t *s, const obs_params_t *p, const int32_t *u_q29, fx_status_t *st)
{
    uint32_t i;
    uint32_t j;
    for (i = 0u; i < OBS_NX; i++) {
        /* f_s,i = f_i 2^(ls_k - ls_i): f_i in q(28 + ls_k - ls_i) reads as f_s,i in q28. */
        int32_t m = (int32_t)p->ls[OBS_NX] - (int32_t)p->ls[i];
        uint32_t qy = qfmt((int32_t)OBS_F_Q + m);
        uint32_t qs;
        int64_t f;
        for (j = 0u; j < OBS_NX; j++) {
            /* F_s,ij = Phi_ij 2^(ls_j - ls_i): Phi_ij in q_phi0 reads as q(q_phi0 - ls_j + ls_i). */
            int32_t qf = (int32_t)p->q_phi0 - ((int32_t)p->ls[j] - (int32_t)p->ls[i]);
            s->f_q28[(i * OBS_NX) + j] = fx_convert(s->phi_q[(i * OBS_NX) + j], qfmt(qf), OBS_F_Q, st);
        }
        f = affine_sum(&p->phik[(size_t)i * OBS_NX], p->q_phik, s->x_q29, OBS_NX,
                       &p->gamk[(size_t)i * OBS_NU], p->q_gamk, u_q29, OBS_NU, OBS_X_Q, &qs, st);
        if (qs >= qy) {
            f = fx_shr_rnd64(f, qs - qy, st);
        } else {
            *st |= FX_ST_ARG;
            f = 0;
        }
        s->fk_q28[i] = f;
    }
}

/* Clip the covariance diagonal into [floor, ceiling]; a clip is a designated point. */
static uint32_t clip_cov(obs_state_t *s, const obs_params_t *p)
{
    uint32_t h = 0u;
    uint32_t i;
    for (i = 0u; i < OBS_NZ; i++) {
        int32_t *d = &s->p_q30[(i * OBS_NZ) + i];
        if (*d < p->p_floor_q30) {
            *d = p->p_floor_q30;
            h = OBS_H_COV_CLIP;
        } else if (*d > p->p_ceil_q30) {
            *d = p->p_ceil_q30;
            h = OBS_H_COV_CLIP;
        } else {
            /* inside */
        }
    }
    if (h != 0u) {
        fx_cnt_inc(&s->tlm.n_cov_clip);
    }
    return h;
}

/* ------------------------------------------------------------------ time update */

/* x <- Phi(kappa) x + Gamma(kappa) u;  P <- F P F^T + Q (EKF only). F and f use the x before
   propagation, as the filter's linearisation point. */
static uint32_t predict(obs_state_t *s, const obs_params_t *p, const int32_t *u_q29, fx_status_t *st)
{
    int32_t xn[OBS_NX];
    uint32_t i;
    uint32_t h = 0u;
    build_model(s, p, st);
    if (p->estimator == OBS_EST_EKF) {
        build_f(s, p, u_q29, st);
    }
    for (i = 0u; i < OBS_NX; i++) {
        xn[i] = affine_row(&s->phi_q[(size_t)i * OBS_NX], p->q_phi0, s->x_q29, OBS_NX,
                           &s->gam_q[(size_t)i * OBS_NU], p->q_gam0, u_q29, OBS_NU, OBS_X_Q, OBS_X_Q, st);
    }
    for (i = 0u; i < OBS_NX; i++) {
        s->x_q29[i] = xn[i];
    }
    if (p->estimator == OBS_EST_EKF) {
        /* T = F P (q28 x q30 -> q30); P+ = T F^T on the upper triangle only, mirrored, so P
           stays exactly symmetric; then + Q on the diagonal. Each entry is one exact int64 sum
           with the kappa column's wide term, rounded once (fx_dot_wide). F's kappa row is exactly
           e_kappa^T, so T's kappa row is P's and P+'s kappa column is T's: those products by 1.0
           are exact and are copied, not computed (14 of the 77 dot products). */
        for (i = 0u; i < OBS_NX; i++) {
            uint32_t j;
            for (j = 0u; j < OBS_NZ; j++) {
                s->t_q30[(i * OBS_NZ) + j] = fx_dot_wide(&s->f_q28[(size_t)i * OBS_NX], &s->p_q30[j], OBS_NZ, OBS_NX,
                                                         s->fk_q28[i], s->p_q30[(OBS_NX * OBS_NZ) + j], OBS_F_Q, st);
            }
        }
        for (i = 0u; i < OBS_NZ; i++) {
            s->t_q30[(OBS_NX * OBS_NZ) + i] = s->p_q30[(OBS_NX * OBS_NZ) + i];
        }
        for (i = 0u; i < OBS_NZ; i++) {
            uint32_t j;
            for (j = i; j < OBS_NZ; j++) {
                int32_t v = s->t_q30[((size_t)i * OBS_NZ) + OBS_NX];
                if (j < OBS_NX) {
                    v = fx_dot_wide(&s->f_q28[(size_t)j * OBS_NX], &s->t_q30[(size_t)i * OBS_NZ], 1u, OBS_NX,
                                    s->fk_q28[j], s->t_q30[((size_t)i * OBS_NZ) + OBS_NX], OBS_F_Q, st);
                }
                if (i == j) {
                    v = fx_add_sat(v, p->qd_q30[i], st);
                }
                s->p_q30[(i * OBS_NZ) + j] = v;
                s->p_q30[(j * OBS_NZ) + i] = v;
            }
        }
        h |= clip_cov(s, p);
    }
    return h;
}

/* ------------------------------------------------------------------ measurement update */

/* The update of an accepted sample on channel c: gain L_s = P_s[:, c] / S_n, state correction,
   P_s <- P_s - L_s P_s[c, :]. */
static void apply_update(obs_state_t *s, const obs_params_t *p, uint32_t c, int32_t e, const fx_recip_t *rs,
                         fx_status_t *st)
{
    int32_t l_q28[OBS_NZ];
    int32_t row_q30[OBS_NZ];
    uint32_t j;
    uint32_t k;
    for (j = 0u; j < OBS_NZ; j++) {
        /* L_s = P_s[:, c] / S_n (q30 / q30 -> q28): one divide for the channel. */
        l_q28[j] = fx_recip_div((int64_t)s->p_q30[(j * OBS_NZ) + c], rs, OBS_F_Q, st);
        row_q30[j] = s->p_q30[(c * OBS_NZ) + j];
    }
    for (j = 0u; j < OBS_NZ; j++) {
        /* SI correction L_j e 2^(ls_j - ls_c), formed in the Q of the state it corrects:
           the product L e held with qst + ls_j - ls_c fraction bits is that value in qst. */
        uint32_t qst = state_q(j);
        int32_t qr = ((int32_t)qst + (int32_t)p->ls[j]) - (int32_t)p->ls[c];
        int32_t dx = fx_mul(l_q28[j], OBS_F_Q, e, OBS_X_Q, qfmt(qr), st);
        if (j < OBS_NX) {
            s->x_q29[j] = fx_add_sat(s->x_q29[j], dx, st);
        } else if (!s->kappa_frozen) {
            s->kappa_q28 = fx_add_sat(s->kappa_q28, dx, st);
        } else {
            /* frozen: kappa keeps its value */
        }
    }
    /* P_s <- P_s - L_s P_s[c, :] (symmetric form: upper triangle, mirrored). */
    for (j = 0u; j < OBS_NZ; j++) {
        for (k = j; k < OBS_NZ; k++) {
            /* Frozen kappa is the gain L_kappa = 0: the Joseph form of that suboptimal gain
               equals this update everywhere except P_kk, which keeps its value (the x rows
               of L are unchanged, and L_kappa P_cx = P_kc L_x^T in the cross terms). */
            if (!(s->kappa_frozen && (j == OBS_NX) && (k == OBS_NX))) {
                int32_t v = fx_sub_sat(s->p_q30[(j * OBS_NZ) + k],
                                       fx_mul(l_q28[j], OBS_F_Q, row_q30[k], OBS_P_Q, OBS_P_Q, st), st);
                s->p_q30[(j * OBS_NZ) + k] = v;
                s->p_q30[(k * OBS_NZ) + j] = v;
            }
        }
    }
}

/* One scalar update on gyro channel c (state c). Returns health bits. */
static uint32_t update_channel(obs_state_t *s, const obs_params_t *p, uint32_t c, int32_t y_q29,
                               obs_out_t *out, fx_status_t *st)
{
    /* Innovation gate (d2_reject): a sample with d^2 = e_s^2 / S above gamma^2 = d2_max is not
       used at all, so one wild sample moves neither x-hat, kappa nor P. An accepted sample has
       |e_s| <= gamma sqrt(S), hence moves state j by |L_j e_s| = |P_jc| |e_s| / S <= gamma
       sqrt(P_jj) (Cauchy-Schwarz, P_cc <= S): at most gamma standard deviations. */
    uint32_t h = 0u;
    int32_t e = fx_sub_sat(y_q29, s->x_q29[c], st);
    int32_t sn = fx_add_sat(s->p_q30[(c * OBS_NZ) + c], p->r_q30, st);
    fx_recip_t rs;
    fx_status_t mon = 0u;   /* d^2 is telemetry: its own clamp is not a flight saturation */
    int32_t d2 = INT32_MAX;
    bool weighable = (sn > 0);
    out->tlm.e_q29[c] = e;
    fx_recip_init(&rs, sn, st);
    /* S_n = P_cc + R <= 0: P_s is no longer a covariance (only after it has left its formats, with
       fx bits raised). Such a sample cannot be weighed: it is never used, reads as d^2 = INT32_MAX
       and counts as a rejection under the gate, so a stuck gyro far outside the design range still
       ends in INNOV_PERSIST (tests/app/test_fsw_exec.c). */
    if (weighable) {
        /* d^2 = e_s^2 / S_n with e_s = e 2^-ls_c: e in q29 reads as e_s in q(29 + ls_c). */
        int32_t k = ((int32_t)OBS_D2_Q + (int32_t)OBS_P_Q) - (2 * ((int32_t)OBS_X_Q + (int32_t)p->ls[c]));
        d2 = fx_recip_div((int64_t)e * (int64_t)e, &rs, qfmt(k), &mon);
    }
    out->tlm.d2_q16[c] = d2;
    if (d2 > p->d2_max_q16) {
        h |= OBS_H_INNOV_HIGH;
        fx_cnt_inc(&s->tlm.n_innov);
    }
    if ((p->d2_reject != 0u) && ((d2 > p->d2_max_q16) || !weighable)) {
        fx_cnt_inc(&s->rej_run[c]);
    } else if (weighable) {
        apply_update(s, p, c, e, &rs, st);
        s->rej_run[c] = 0u;
    } else {
        /* monitor only and not weighable: not used, not counted */
    }
    return h;
}

/* Clamp kappa into the band (an edge counts as inside). */
static uint32_t clamp_kappa(obs_state_t *s, const obs_params_t *p)
{
    uint32_t h = 0u;
    if (s->kappa_q28 < p->kappa_lo_q28) {
        s->kappa_q28 = p->kappa_lo_q28;
        h = OBS_H_K_CLAMP_LO;
        fx_cnt_inc(&s->tlm.n_clamp_lo);
    } else if (s->kappa_q28 > p->kappa_hi_q28) {
        s->kappa_q28 = p->kappa_hi_q28;
        h = OBS_H_K_CLAMP_HI;
        fx_cnt_inc(&s->tlm.n_clamp_hi);
    } else {
        /* inside the band */
    }
    return h;
}

/* The paper's constant-gain structure (predictor form): x+ = Phi x + Gamma u + W6 e,
   kappa+ = kappa + W7 e. Applied after the EKF-free time update. */
static void const_w_correct(obs_state_t *s, const obs_params_t *p, const int32_t *e_q29, fx_status_t *st)
{
    uint32_t i;
    for (i = 0u; i < OBS_NZ; i++) {
        uint32_t qst = state_q(i);
        int64_t acc = fx_dot_acc(&p->w[(size_t)i * OBS_NY], e_q29, OBS_NY, st);
        int32_t dx = fx_rshift_sat(acc, (p->q_w + OBS_X_Q) - qst, st);
        if (i < OBS_NX) {
            s->x_q29[i] = fx_add_sat(s->x_q29[i], dx, st);
        } else {
            s->kappa_q28 = fx_add_sat(s->kappa_q28, dx, st);
        }
    }
}

/* ------------------------------------------------------------------ command */

/* u = -D x, limited as a vector (never per axis: the direction is kept). */
static uint32_t command(obs_state_t *s, const obs_params_t *p, int32_t *u_q29, fx_status_t *st)
{
    uint32_t h = 0u;
    uint32_t i;
    uint32_t mag = 0u;
    fx_matvec(p->d, p->q_d, s->x_q29, OBS_X_Q, OBS_NU, OBS_NX, u_q29, OBS_U_Q, st);
    for (i = 0u; i < OBS_NU; i++) {
        u_q29[i] = fx_neg(u_q29[i], st);
        mag = (fx_uabs(u_q29[i]) > mag) ? fx_uabs(u_q29[i]) : mag;
    }
    if (mag > (uint32_t)p->bdot_max_q29) {
        fx_recip_t rm;
        fx_status_t lim = 0u;   /* designated point: reported as CMD_LIMITED */
        /* |u|inf < 2^31 here (a negated INT32_MIN saturated above), so mag fits int32. */
        fx_recip_init(&rm, (int32_t)mag, &lim);
        for (i = 0u; i < OBS_NU; i++) {
            u_q29[i] = fx_recip_div((int64_t)u_q29[i] * (int64_t)p->bdot_max_q29, &rm, 0u, &lim);
        }
        h = OBS_H_CMD_LIMITED;
        fx_cnt_inc(&s->tlm.n_limited);
        fx_cnt_inc(&s->limited_run);
        if (s->limited_run >= p->n_sat) {
            h |= OBS_H_CMD_LIMIT_PERSIST;
        }
    } else {
        s->limited_run = 0u;
    }
    return h;
}

/* Quantise the command to actuator counts and give back exactly what the actuator applies:
   the model must propagate with the quantised command, or the filter reads the quantisation
   error (up to half a count per step) as a stiffness error (measured: K_hat 7 % low).
   With shape set, the quantisation is error-feedback (first-order noise shaping): the part of
   the command a count could not carry this step is added to the next one, so the gimbal angle
   the actuator integrates stays within half a count-period of the commanded one instead of
   random-walking. Rounding each step alone leaves a limit cycle of 4e-4 deg/s on M-paper
   (fsw/observer/README.md "Command quantisation"). The residual is below half a count; a clip
   at the actuator range, an unshaped (zero or held) command and init clear it. */
static void to_counts(obs_state_t *s, const obs_params_t *p, int32_t *u_q29, bool shape, obs_out_t *out,
                      fx_status_t *st)
{
    uint32_t i;
    for (i = 0u; i < OBS_NU; i++) {
        fx_status_t clip = 0u;   /* designated point: the actuator range */
        int32_t want = shape ? fx_add_sat(u_q29[i], s->qres_q29[i], st) : u_q29[i];
        out->bdot_cmd_cnt[i] = fx_to_count(want, 1, p->act_cnt_shift, -p->act_max_cnt, p->act_max_cnt, &clip);
        u_q29[i] = fx_shl_sat(out->bdot_cmd_cnt[i], p->act_cnt_shift, st);
        s->qres_q29[i] = (shape && (clip == 0u)) ? fx_sub_sat(want, u_q29[i], st) : 0;
    }
}

/* ------------------------------------------------------------------ rejection bookkeeping */

uint32_t obs_rej_persist_mask(const obs_state_t *s, const obs_params_t *p)
{
    uint32_t m = 0u;
    uint32_t c;
    for (c = 0u; c < OBS_NY; c++) {
        if (s->rej_run[c] >= (uint32_t)p->n_rej_safe) {
            m |= (uint32_t)1 << c;
        }
    }
    return m;
}

/* Leaky rejection level: + rej_leak_inc on a step with a rejection, - 1 on a step without, capped
   at rej_freeze_on + rej_leak_inc so that it drains within that many clean steps. kappa
   adaptation freezes when the level reaches rej_freeze_on and resumes when it is back at 0: a
   single rejected sample needs no freeze (the gate removed it); a burst means the samples that
   pass the gate may be contaminated too, each able to move kappa by up to gamma sigma_kappa,
   while x-hat keeps tracking. With the shipped 50 / 51, two rejections within 49 steps (1 s)
   freeze, any sustained rate above 1 in 51 steps keeps it frozen, and it releases at most
   101 clean steps after the last rejection. */
static uint32_t track_rejections(obs_state_t *s, const obs_params_t *p, bool rejected)
{
    uint32_t h = 0u;
    uint32_t cap = (uint32_t)p->rej_freeze_on + (uint32_t)p->rej_leak_inc;
    if (rejected) {
        s->rej_level += (uint32_t)p->rej_leak_inc;
        if (s->rej_level > cap) {
            s->rej_level = cap;
        }
    } else if (s->rej_level > 0u) {
        s->rej_level--;
    } else {
        /* clean and drained */
    }
    if (s->rej_level >= (uint32_t)p->rej_freeze_on) {
        s->kappa_frozen = true;
    } else if (s->rej_level == 0u) {
        s->kappa_frozen = false;
    } else {
        /* hysteresis: keep */
    }
    if (s->kappa_frozen) {
        h |= OBS_H_ADAPT_FROZEN;
    }
    if (obs_rej_persist_mask(s, p) != 0u) {
        s->rej_safe = true;
    }
    if (s->rej_safe) {
        /* Latched until init (mode re-entry): either the sensor is bad or the estimate has lost
           lock, and neither is cured by flying on; the command is zero meanwhile. */
        h |= OBS_H_INNOV_PERSIST | OBS_H_ADAPT_FROZEN;
    }
    return h;
}

/* ------------------------------------------------------------------ sequencing and validity */

/* Steps since the last sample, from the modular u32 sequence: 1 normally, <= 0 for a stale
   (repeated or older) sample. */
static int64_t seq_delta(const obs_state_t *s, uint32_t seq)
{
    int64_t d = 1;
    if (s->have_seq) {
        d = (int64_t)seq - (int64_t)s->last_seq;
        if (d > INT64_C(2147483647)) {
            d -= INT64_C(4294967296);
        } else if (d < INT64_C(-2147483648)) {
            d += INT64_C(4294967296);
        } else {
            /* already the shortest distance */
        }
    }
    return d;
}

/* Valid channels as a bit mask, measurements converted to q29. */
static uint32_t read_gyros(const obs_params_t *p, const obs_in_t *in, int32_t *y_q29, fx_status_t *st)
{
    uint32_t mask = 0u;
    uint32_t c;
    for (c = 0u; c < OBS_NY; c++) {
        uint32_t bit = (uint32_t)1 << c;
        y_q29[c] = 0;
        if (((in->stale & bit) == 0u) && ((in->sat & bit) == 0u) &&
            (fx_uabs(in->gyro_cnt[c]) < (uint32_t)p->gyro_max_cnt)) {
            y_q29[c] = fx_from_count(in->gyro_cnt[c], 1, 0u, 0, st);
            y_q29[c] = fx_shl_sat(y_q29[c], p->gyro_cnt_shift, st);
            mask |= bit;
        }
    }
    return mask;
}

/* (Re)initialise the estimate from a full measurement; keep kappa and P_KK on a re-init. */
static void start_estimate(obs_state_t *s, const obs_params_t *p, const int32_t *y_q29, bool keep_kappa)
{
    uint32_t i;
    int32_t pkk = s->p_q30[(OBS_NZ * OBS_NZ) - 1u];
    for (i = 0u; i < OBS_NX; i++) {
        s->x_q29[i] = (i < OBS_NY) ? y_q29[i] : 0;
    }
    for (i = 0u; i < (OBS_NZ * OBS_NZ); i++) {
        s->p_q30[i] = 0;
    }
    for (i = 0u; i < OBS_NZ; i++) {
        s->p_q30[(i * OBS_NZ) + i] = p->p0_q30[i];
    }
    if (keep_kappa) {
        s->p_q30[(OBS_NZ * OBS_NZ) - 1u] = pkk;
    } else {
        s->kappa_q28 = p->kappa_init_q28;
    }
    s->initialized = true;
    s->lost = false;
    s->invalid_run = 0u;
    s->good_run = 0u;
    s->rej_run[0] = 0u;
    s->rej_run[1] = 0u;
    s->rej_level = 0u;
    s->kappa_frozen = false;
}

/* Track loss of measurements; returns health bits and whether the filter may update. */
static uint32_t track_loss(obs_state_t *s, const obs_params_t *p, uint32_t mask, bool gap_lost,
                           const int32_t *y_q29)
{
    uint32_t h = 0u;
    if ((mask == 0u) || gap_lost) {
        s->good_run = 0u;
        fx_cnt_inc(&s->invalid_run);
        if (((s->invalid_run >= p->n_lost) || gap_lost) && (!s->lost)) {
            s->lost = true;
            fx_cnt_inc(&s->tlm.n_lost);
        }
    } else {
        s->invalid_run = 0u;
        if (s->lost && (mask == ((uint32_t)1 << OBS_NY) - 1u)) {
            fx_cnt_inc(&s->good_run);
            if (s->good_run >= p->n_good) {
                start_estimate(s, p, y_q29, true);
                fx_cnt_inc(&s->tlm.n_reinit);
                h |= OBS_H_REINIT;
            }
        }
    }
    if (s->lost) {
        h |= OBS_H_MEAS_LOST | OBS_H_ADAPT_FROZEN;
    }
    return h;
}

/* ------------------------------------------------------------------ public API */

static uint32_t check_formats(const obs_params_t *p)
{
    uint32_t ok = valid_q(p->q_phi0) & valid_q(p->q_phik) & valid_q(p->q_gam0) & valid_q(p->q_gamk) &
                  valid_q(p->q_d) & valid_q(p->q_w);
    return (ok != 0u) ? 0u : OBS_WHY_FORMAT;
}

static bool q_legal(int32_t q)
{
    return (q >= 0) && (q <= (int32_t)FX_Q_MAX);
}

/* Formats of the scaled transition matrix (Phi block and f column). */
static uint32_t check_scales_model(const obs_params_t *p)
{
    uint32_t why = 0u;
    uint32_t i;
    for (i = 0u; i < OBS_NX; i++) {
        uint32_t j;
        if (!q_legal(((int32_t)OBS_F_Q + (int32_t)p->ls[OBS_NX]) - (int32_t)p->ls[i])) {
            why = OBS_WHY_SCALE;
        }
        for (j = 0u; j < OBS_NX; j++) {
            if (!q_legal((int32_t)p->q_phi0 - ((int32_t)p->ls[j] - (int32_t)p->ls[i]))) {
                why = OBS_WHY_SCALE;
            }
        }
    }
    return why;
}

/* Formats of the measurement update (d^2 and the state corrections). */
static uint32_t check_scales_update(const obs_params_t *p)
{
    uint32_t why = 0u;
    uint32_t c;
    for (c = 0u; c < OBS_NY; c++) {
        uint32_t j;
        int32_t kd2 = ((int32_t)OBS_D2_Q + (int32_t)OBS_P_Q) - (2 * ((int32_t)OBS_X_Q + (int32_t)p->ls[c]));
        if ((kd2 < 0) || (kd2 > 62)) {
            why = OBS_WHY_SCALE;
        }
        for (j = 0u; j < OBS_NZ; j++) {
            if (!q_legal(((int32_t)state_q(j) + (int32_t)p->ls[j]) - (int32_t)p->ls[c])) {
                why = OBS_WHY_SCALE;
            }
        }
    }
    return why;
}

/* Every Q the filter derives from the scales must be a legal format. */
static uint32_t check_scales(const obs_params_t *p)
{
    uint32_t why = 0u;
    uint32_t i;
    for (i = 0u; i < OBS_NZ; i++) {
        if ((p->ls[i] < -20) || (p->ls[i] > 0)) {
            why = OBS_WHY_SCALE;
        }
    }
    if (why == 0u) {
        why = check_scales_model(p) | check_scales_update(p);
    }
    return why;
}

static uint32_t check_cov(const obs_params_t *p)
{
    uint32_t why = 0u;
    uint32_t i;
    for (i = 0u; i < OBS_NZ; i++) {
        if ((p->p0_q30[i] <= 0) || (p->qd_q30[i] < Q_LSB4)) {
            why = OBS_WHY_COV;
        }
    }
    if ((p->r_q30 <= 0) || (p->p_floor_q30 <= 0) || (p->p_floor_q30 >= p->p_ceil_q30)) {
        why = OBS_WHY_COV;
    }
    return why;
}

fsw_rc_t obs_params_check(const obs_params_t *p, uint32_t *why)
{
    uint32_t w = 0u;
    if (p->period_us == 0u) {
        w |= OBS_WHY_PERIOD;
    }
    if ((p->estimator != OBS_EST_EKF) && (p->estimator != OBS_EST_CONST_W)) {
        w |= OBS_WHY_ESTIMATOR;
    }
    w |= check_formats(p);
    if ((p->kappa_lo_q28 <= 0) || (p->kappa_lo_q28 >= p->kappa_hi_q28) ||
        (p->kappa0_q28 < p->kappa_lo_q28) || (p->kappa0_q28 > p->kappa_hi_q28) ||
        (p->kappa_init_q28 < p->kappa_lo_q28) || (p->kappa_init_q28 > p->kappa_hi_q28)) {
        w |= OBS_WHY_BAND;
    }
    if ((p->bdot_max_q29 <= 0) || (p->bdot_max_q29 > p->bdot_hw_q29)) {
        w |= OBS_WHY_LIMIT;
    }
    w |= check_cov(p);
    w |= check_scales(p);
    if ((p->n_lost == 0u) || (p->n_good == 0u) || (p->n_sat == 0u) || (p->n_gap_max == 0u) || (p->d2_max_q16 <= 0) ||
        (p->n_rej_safe == 0u) || (p->rej_leak_inc == 0u) || (p->rej_freeze_on == 0u)) {
        w |= OBS_WHY_FAULT;
    }
    if ((p->gyro_cnt_shift > 31u) || (p->act_cnt_shift > 31u) || (p->gyro_max_cnt <= 0) || (p->act_max_cnt <= 0)) {
        w |= OBS_WHY_SENSOR;
    }
    *why = w;
    return (w == 0u) ? FSW_OK : FSW_ERR_INVARIANT;
}

static void publish(const obs_state_t *s, const int32_t *u_q29, uint32_t health, obs_out_t *out)
{
    uint32_t i;
    int32_t e0 = out->tlm.e_q29[0];
    int32_t e1 = out->tlm.e_q29[1];
    int32_t d0 = out->tlm.d2_q16[0];
    int32_t d1 = out->tlm.d2_q16[1];
    out->tlm = s->tlm;
    out->tlm.e_q29[0] = e0;
    out->tlm.e_q29[1] = e1;
    out->tlm.d2_q16[0] = d0;
    out->tlm.d2_q16[1] = d1;
    for (i = 0u; i < OBS_NX; i++) {
        out->tlm.x_q29[i] = s->x_q29[i];
    }
    out->tlm.kappa_q28 = s->kappa_q28;
    for (i = 0u; i < OBS_NU; i++) {
        out->tlm.u_q29[i] = u_q29[i];
    }
    out->tlm.pkk_q30 = s->p_q30[(OBS_NZ * OBS_NZ) - 1u];
    out->health = health;
}

/* Zero every word of the state and the output (no libc, and no 1 KiB zero image in rodata). */
static void zero_words(int32_t *w, uint32_t n)
{
    uint32_t i;
    for (i = 0u; i < n; i++) {
        w[i] = 0;
    }
}

static void zero_tlm(obs_tlm_t *t)
{
    zero_words(t->x_q29, OBS_NX);
    t->kappa_q28 = 0;
    zero_words(t->u_q29, OBS_NU);
    zero_words(t->e_q29, OBS_NY);
    zero_words(t->d2_q16, OBS_NY);
    t->pkk_q30 = 0;
    t->health_sticky = 0u;
    t->n_skip = 0u;
    t->n_gap = 0u;
    t->n_lost = 0u;
    t->n_reinit = 0u;
    t->n_clamp_lo = 0u;
    t->n_clamp_hi = 0u;
    t->n_limited = 0u;
    t->n_innov = 0u;
    t->n_cov_clip = 0u;
    t->revision = 0u;
}

fsw_rc_t obs_init(obs_state_t *s, const obs_params_t *p, obs_out_t *out)
{
    uint32_t why = 0u;
    fsw_rc_t rc = obs_params_check(p, &why);
    zero_words(s->x_q29, OBS_NX);
    zero_words(s->p_q30, OBS_NZ * OBS_NZ);
    zero_words(s->u_prev_q29, OBS_NU);
    zero_words(s->qres_q29, OBS_NU);
    zero_words(s->f_q28, OBS_NZ * OBS_NZ);
    zero_words(s->t_q30, OBS_NZ * OBS_NZ);
    zero_words(s->phi_q, OBS_NX * OBS_NX);
    zero_words(s->gam_q, OBS_NX * OBS_NU);
    s->kappa_q28 = p->kappa_init_q28;
    s->last_seq = 0u;
    s->have_seq = false;
    s->initialized = false;
    s->lost = false;
    s->invalid_run = 0u;
    s->good_run = 0u;
    s->limited_run = 0u;
    s->rej_run[0] = 0u;
    s->rej_run[1] = 0u;
    s->rej_level = 0u;
    s->kappa_frozen = false;
    s->rej_safe = false;
    zero_tlm(&s->tlm);
    s->tlm.revision = p->revision;
    s->tlm.health_sticky = OBS_H_NOT_INIT;
    /* Safe outputs: zero gimbal-rate command. */
    out->bdot_cmd_cnt[0] = 0;
    out->bdot_cmd_cnt[1] = 0;
    out->health = OBS_H_NOT_INIT;
    out->tlm = s->tlm;
    out->tlm.kappa_q28 = s->kappa_q28;
    return rc;
}

#define OBS_ALL_AXES (((uint32_t)1 << OBS_NY) - 1u)

/* 1. Sequence: predict across missed periods with the held command; a stale sample is not a
   measurement; a gap beyond n_gap_max is a loss of measurements. */
static uint32_t handle_seq(obs_state_t *s, const obs_params_t *p, uint32_t seq, uint32_t *mask,
                           bool *gap_lost, fx_status_t *st)
{
    uint32_t h = 0u;
    int64_t d = seq_delta(s, seq);
    if (d < 1) {
        h = OBS_H_SEQ | OBS_H_MEAS_SKIP;
        *mask = 0u;
    } else if (d > (int64_t)p->n_gap_max) {
        h = OBS_H_SEQ;
        *gap_lost = true;
        s->last_seq = seq;
    } else {
        int64_t k;
        for (k = 1; (k < d) && (k <= (int64_t)p->n_gap_max); k++) {
            if (s->initialized) {
                h |= predict(s, p, s->u_prev_q29, st);
            }
            fx_cnt_inc(&s->tlm.n_gap);
            h |= OBS_H_SEQ;
        }
        s->last_seq = seq;
    }
    s->have_seq = true;
    return h;
}

/* 4.-6. Measurement update, command, time update of an initialised filter. u_q29 returns the
   command as applied (quantised to counts); out gets the counts. */
static uint32_t run_filter(obs_state_t *s, const obs_params_t *p, uint32_t mask, const int32_t *y_q29,
                           int32_t *u_q29, obs_out_t *out, fx_status_t *st)
{
    uint32_t h = 0u;
    uint32_t c;
    bool rejected = false;
    int32_t e_q29[OBS_NY];
    for (c = 0u; c < OBS_NY; c++) {
        bool valid = (mask & ((uint32_t)1 << c)) != 0u;
        /* Innovation against the prior (CONST_W uses it in the predictor form). */
        e_q29[c] = valid ? fx_sub_sat(y_q29[c], s->x_q29[c], st) : 0;
        if (valid && (!s->lost) && (p->estimator == OBS_EST_EKF)) {
            h |= update_channel(s, p, c, y_q29[c], out, st);
            /* an accepted update zeroes the run, a rejection raises it */
            rejected = rejected || (s->rej_run[c] > 0u);
        }
    }
    h |= track_rejections(s, p, rejected);
    h |= clamp_kappa(s, p);
    if (p->estimator == OBS_EST_EKF) {
        h |= clip_cov(s, p);
    }
    /* Command from the updated estimate; zero while measurements are lost or persistently
       rejected. */
    if ((!s->lost) && (!s->rej_safe)) {
        h |= command(s, p, u_q29, st);
    }
    to_counts(s, p, u_q29, (!s->lost) && (!s->rej_safe), out, st);
    /* Time update with the command actually applied. */
    h |= predict(s, p, u_q29, st);
    if (p->estimator == OBS_EST_CONST_W) {
        const_w_correct(s, p, e_q29, st);
        h |= clamp_kappa(s, p);
    }
    return h;
}

void obs_step(obs_state_t *s, const obs_params_t *p, const obs_in_t *in, obs_out_t *out)
{
    fx_status_t st = 0u;
    int32_t y_q29[OBS_NY];
    int32_t u_q29[OBS_NU] = {0, 0};
    bool gap_lost = false;
    uint32_t mask = read_gyros(p, in, y_q29, &st);
    uint32_t h;

    out->tlm.e_q29[0] = 0;
    out->tlm.e_q29[1] = 0;
    out->tlm.d2_q16[0] = 0;
    out->tlm.d2_q16[1] = 0;
    s->tlm.revision = p->revision;   /* the table this step ran with (tables swap at run time) */
    h = handle_seq(s, p, in->seq, &mask, &gap_lost, &st);
    if ((mask != OBS_ALL_AXES) && ((h & OBS_H_MEAS_SKIP) == 0u)) {
        h |= OBS_H_MEAS_SKIP;
        fx_cnt_inc(&s->tlm.n_skip);
    }
    if (!s->initialized) {
        if (mask == OBS_ALL_AXES) {
            /* 3. Initialise on the first complete measurement, then steps 4-6 on the same
               sample (spec 10 §4.4): command from x-hat(0|0). Holding a zero command for this
               first period lets the 51 rad/s nutation kick the sail (M-paper: peak mu 0.51 deg
               instead of 0.19, and divergence at the 1.2 deg/s limit). */
            start_estimate(s, p, y_q29, false);
            h |= run_filter(s, p, mask, y_q29, u_q29, out, &st);
        } else {
            to_counts(s, p, u_q29, false, out, &st);   /* zero command */
            h |= OBS_H_NOT_INIT;
        }
    } else {
        h |= track_loss(s, p, mask, gap_lost, y_q29);
        h |= run_filter(s, p, mask, y_q29, u_q29, out, &st);
    }
    s->u_prev_q29[0] = u_q29[0];
    s->u_prev_q29[1] = u_q29[1];
    h |= (st & FX_ST_MASK);
    s->tlm.health_sticky |= h;
    publish(s, u_q29, h, out);
}
