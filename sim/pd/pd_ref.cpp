#include "pd/pd_ref.hpp"

#include <cmath>
#include <stdexcept>

namespace ref {

namespace {
constexpr double kY = 1.0 / 67108864.0;      // 2^-26 rad per attitude count
constexpr double kBeta = 1.0 / 16777216.0;   // 2^-24 rad per encoder count
double q(double v, int bits) { return std::ldexp(v, -bits); }
double quant16(double g) { return std::round(std::ldexp(g, 16)) * std::ldexp(1.0, -16); }
}  // namespace

PdChannelTable dequantise(const pd_params_t &p)
{
    PdChannelTable t;
    t.law = p.c.law;
    t.src = p.c.src;
    t.sched_law = p.c.sched_law;
    t.Ty = static_cast<double>(p.c.period_us) * static_cast<double>(p.c.n_div) * 1e-6;
    t.n_y = p.c.n_y;
    t.n_bad_max = p.c.n_bad_max;
    t.n_hold = p.c.n_hold;
    t.n_frozen = p.c.n_frozen;
    t.y_lim = q(p.c.y_lim_q30, 30);
    t.dy_max = q(p.c.dy_max_q30, 30);
    t.m_max = q(p.c.m_max_q28, 28);
    t.m_frozen = q(p.c.m_frozen_q28, 28);
    t.beta_warn = q(p.c.beta_warn_q24, 24);
    t.beta_lim = q(p.c.beta_lim_q24, 24);
    t.f0 = q(p.c.f0_q32, 32);
    t.df = 1.0 / q(p.c.df_inv_q16, 16);
    t.f_ground = q(p.c.f_ground_q32, 32);
    t.k0 = q(p.g.k0_q22, 22);
    t.k1 = q(p.g.k1_q22, 22);
    t.k2_nom = q(p.g.k2_nom_q22, 22);
    t.k2_cold = q(p.g.k2_cold_q22, 22);
    t.k2_min = q(p.g.k2_min_q22, 22);
    t.k2_max = q(p.g.k2_max_q22, 22);
    for (std::size_t i = 0; i < PD_N_NODES; ++i) { t.k2_node[i] = q(p.g.k2_node_q22[i], 22); }
    t.revision = p.c.revision;
    const std::uint64_t ty_us = static_cast<std::uint64_t>(p.c.period_us) * static_cast<std::uint64_t>(p.c.n_div);
    t.fest_ok = pd_fest_check(&p.g.fest) == 0u && ty_us == static_cast<std::uint64_t>(PD_TY_EXACT_US);
    return t;
}

double pd_sched_k2(const PdChannelTable &t, double f_hz)
{
    // The node index and the 16-bit fraction phi are the §5 item 6 format (f in uq32, 1/df in uq16, phi
    // truncated to 2^-16 of a node step), taken as the design, like the gains' uq16: computed here from
    // the dequantised table by the same integer rule (phi rounded, its carry moving into the index); the interpolation itself is in double.
    const double f0_q = std::round(std::ldexp(t.f0, 32));
    const double dfi_q = std::round(std::ldexp(1.0 / t.df, 16));
    const double f_q = std::round(std::ldexp(f_hz, 32));
    double k2;
    if (!(f_q > f0_q)) {
        k2 = t.k2_node[0];
    } else {
        const auto u48 = static_cast<std::uint64_t>(f_q - f0_q) * static_cast<std::uint64_t>(dfi_q);   // < 2^62
        const std::uint64_t u = ((u48 + (std::uint64_t{1} << 31)) >> 32) << 32;   // phi rounded, carry to i
        const std::uint64_t i = u >> 48;
        if (i >= PD_N_NODES - 1u) {
            k2 = t.k2_node[PD_N_NODES - 1u];
        } else {
            const double phi = static_cast<double>((u >> 32) & 0xFFFFu) / 65536.0;
            k2 = t.k2_node[i] + (t.k2_node[i + 1] - t.k2_node[i]) * phi;
        }
    }
    return std::fmin(std::fmax(k2, t.k2_min), t.k2_max);
}

double pd_sched_k2_continuous(const PdChannelTable &t, double f_hz)
{
    const double u = (f_hz - t.f0) / t.df;
    double k2;
    if (u <= 0.0) {
        k2 = t.k2_node[0];
    } else if (u >= static_cast<double>(PD_N_NODES - 1u)) {
        k2 = t.k2_node[PD_N_NODES - 1u];
    } else {
        const auto i = static_cast<std::size_t>(std::floor(u));
        k2 = t.k2_node[i] + (t.k2_node[i + 1] - t.k2_node[i]) * (u - static_cast<double>(i));
    }
    return std::fmin(std::fmax(k2, t.k2_min), t.k2_max);
}

double pd_gain_p(const PdChannelTable &t) { return quant16(t.k0 * t.k1); }
double pd_gain_d(const PdChannelTable &t, double k2) { return quant16(t.k0 * k2 / t.Ty); }

PdRefChannel::PdRefChannel(const PdChannelTable &t, std::shared_ptr<const pd::FestParams> fest) : t_(t)
{
    if (fest) {
        // the estimator's period is the law's control period of the table (pd_fest_step gets n_y)
        auto fp = std::make_shared<pd::FestParams>(*fest);
        fp->n_y = t_.n_y;
        fest_p_ = fp;
    }
    // An ADAPTIVE boot source the flight refuses (pd_params_check: PD_WHY_MODE, the table is vetoed)
    // is refused here rather than flown as something else.
    if (t_.src == PD_SRC_ADAPTIVE && !adaptive_ok()) {
        throw std::invalid_argument(fest_p_ ? "reference channel: gain source ADAPTIVE refused (no usable estimator "
                                              "block, Ty != 0.25 s or schedule law != law: PD_WHY_MODE)"
                                            : "reference channel: gain source ADAPTIVE without the estimator's design");
    }
    init();
}

bool PdRefChannel::set_source(int src)
{
    const bool sched_ok = t_.sched_law == t_.law;
    const bool ok = src == PD_SRC_FIXED || (src == PD_SRC_GROUND && sched_ok) || (src == PD_SRC_ADAPTIVE && adaptive_ok());
    if (ok) {
        if (src == PD_SRC_ADAPTIVE && src_ != src) { adaptive_start(); }
        src_ = src;
    }
    return ok;
}

// ADAPTIVE from a cold start (as adaptive_start): the estimator at its prior, its period aligned with
// the law's, k2_cold until the first confident re-tune.
void PdRefChannel::adaptive_start()
{
    fest_.emplace(*fest_p_);
    fest_->set_period_phase(nu_);
    k2_adapt_ = clamp_k2(t_.k2_cold);
    f_pub_prev_ = fest_->out().f_hat_hz;
    n_inv_fest_ = 0;
}

// One estimator sample (as adaptive_sample): the sample or invalid, the torque m that acts over the
// coming sample, the k2 in use this sample; at the period end the §4.2 re-tune rule, the new k2 acting
// from the next sample (step's re-tune at its start).
void PdRefChannel::adaptive_sample(bool ok, double y, double m)
{
    const pd::FestOut &o = fest_->step(ok, ok ? y : 0.0, m, k2_);
    n_inv_fest_ += ok ? 0 : 1;
    if (o.period_end) {
        const double d = std::fabs(o.f_hat_hz - f_pub_prev_);
        if (o.state == pd::FestState::Fault) {
            k2_adapt_ = clamp_k2(t_.k2_cold);
        } else if (o.confident && d * 50.0 < f_pub_prev_ && n_inv_fest_ <= t_.n_bad_max) {
            k2_adapt_ = pd_sched_k2(t_, o.f_hat_hz);   // (clamped to [k2_min, k2_max] there)
        }
        f_pub_prev_ = o.f_hat_hz;
        n_inv_fest_ = 0;
    }
    fest_f = o.f_hat_hz;
    fest_word = static_cast<std::uint32_t>(o.state) | (o.confident ? 4u : 0u) | (o.gate_open ? 8u : 0u) |
                ((o.fault & 0xFFu) << 8);
    fest_p_a = o.P_a;
    fest_att = o.att;
    fest_resets = static_cast<std::uint32_t>(o.resets);
}

void PdRefChannel::init()
{
    miss = stale = range_rej = rate_rej = period_rej = trq_sat = beta_lim = 0u;
    health_sticky = 0u;
    y_last = dy_last = 0.0;
    src_ = t_.src;
    f_ground_ = t_.f_ground;
    k2_fixed_ = clamp_k2(t_.k2_nom);
    y_prev_ = m_last_ = m_held_ = 0.0;
    have_prev_ = false;
    same_cnt_ = 0;
    same_run_ = miss_run_ = 0u;
    nu_ = n_bad_ = zero_run_ = 0;
    sum_ = fill_ = xbar_ = xbar_prev_ = 0.0;
    have_fill_ = have_xbar_ = false;
    fest_.reset();
    fest_f = fest_p_a = fest_att = 0.0;
    fest_word = fest_resets = 0u;
    k2_adapt_ = f_pub_prev_ = 0.0;
    n_inv_fest_ = 0;
    if (src_ == PD_SRC_ADAPTIVE) { adaptive_start(); }   // (the constructor refused it where unusable)
    k2_ = (src_ == PD_SRC_GROUND) ? pd_sched_k2(t_, f_ground_) : (src_ == PD_SRC_ADAPTIVE) ? k2_adapt_ : k2_fixed_;
    gp_ = pd_gain_p(t_);
    gd_ = pd_gain_d(t_, k2_);
}

double PdRefChannel::clamp_k2(double k2) const { return std::fmin(std::fmax(k2, t_.k2_min), t_.k2_max); }

void PdRefChannel::set_k2_fixed(double k2) { k2_fixed_ = clamp_k2(k2); }

double PdRefChannel::torque(double m, std::uint32_t &h)
{
    if (std::fabs(m) > t_.m_max) {
        h |= PD_H_TRQ_SAT;
        ++trq_sat;
        return std::copysign(t_.m_max, m);
    }
    return m;
}

bool PdRefChannel::period(bool ok, double y, std::uint32_t &h)
{
    // the control period: invalid samples filled with the last good y
    bool mean_done = false;
    if (ok) {
        fill_ = y;
        have_fill_ = true;
    } else {
        ++n_bad_;
    }
    sum_ += have_fill_ ? fill_ : 0.0;
    if (++nu_ >= t_.n_y) {
        if (n_bad_ > t_.n_bad_max) {
            ++period_rej;
            h |= PD_H_PERIOD_BAD;
            have_xbar_ = false;
            zero_run_ = t_.n_y;
            m_held_ = 0.0;
        } else {
            const double xb = sum_ / static_cast<double>(t_.n_y);
            xbar_prev_ = have_xbar_ ? xbar_ : xb;
            xbar_ = xb;
            have_xbar_ = true;
            mean_done = true;
        }
        nu_ = 0;
        sum_ = 0.0;
        n_bad_ = 0;
    }
    return mean_done;
}

void PdRefChannel::literal_update(std::uint32_t &h)
{
    m_held_ = torque(-(gp_ * xbar_ + gd_ * (xbar_ - xbar_prev_) / static_cast<double>(t_.n_y)), h);
}

void PdRefChannel::note_gap(std::uint32_t n)
{
    std::uint32_t h = 0u;
    const auto ny = static_cast<std::uint32_t>(t_.n_y);
    const std::uint32_t k = (n <= 64u) ? n : ny + n % ny;   // the period phase n leaves (as pd_note_gap)
    for (std::uint32_t i = 0; i < k; ++i) {
        if (period(false, 0.0, h) && t_.law == PD_LAW_LITERAL) { literal_update(h); }
        if (src_ == PD_SRC_ADAPTIVE) { adaptive_sample(false, 0.0, m_last_); }   // the plant held the last torque
    }
    miss += n;
    if (n > PD_GAP_DIFF_MAX || miss_run_ > 0u) { have_prev_ = false; }
    miss_run_ += n;
    health_sticky |= h | PD_H_STALE;
}

PdRefOut PdRefChannel::step(const PdRefIn &in)
{
    std::uint32_t h = (static_cast<std::uint32_t>(t_.law) << 8) | (static_cast<std::uint32_t>(src_) << 10);
    const double k2 = (src_ == PD_SRC_GROUND) ? pd_sched_k2(t_, f_ground_) : (src_ == PD_SRC_ADAPTIVE) ? k2_adapt_ : k2_fixed_;
    if (std::fabs(k2 - k2_) > 0.0) {   // an exact change, as the flight compares integers
        k2_ = k2;
        gp_ = pd_gain_p(t_);
        gd_ = pd_gain_d(t_, k2);
        h |= PD_H_RETUNE;
    }
    if (!(std::fabs(k2_ - t_.k2_cold) > 0.0)) { h |= PD_H_FALLBACK_GAIN; }

    // accept or refuse the sample (§8)
    bool ok = in.y_valid;
    const double y = static_cast<double>(in.y_cnt) * kY;
    if (!ok) {
        ++miss;
    } else if (in.y_sat || std::fabs(y) > t_.y_lim) {
        ok = false;
        h |= PD_H_REJECT;
        ++range_rej;
    } else {
        const bool latched = same_run_ >= static_cast<std::uint32_t>(t_.n_frozen);
        if (same_run_ > 0 && in.y_cnt == same_cnt_ && (latched || std::fabs(m_last_) >= t_.m_frozen)) {
            ++same_run_;
        } else {
            same_run_ = 1;
            same_cnt_ = in.y_cnt;
        }
        if (same_run_ >= static_cast<std::uint32_t>(t_.n_frozen)) {
            ok = false;
            h |= PD_H_FROZEN;
            ++stale;
        } else if (have_prev_ && std::fabs(y - y_prev_) > t_.dy_max) {
            ok = false;
            h |= PD_H_REJECT;
            ++rate_rej;
        }
    }
    double dy = 0.0;
    if (ok) {
        if (!have_prev_) { y_prev_ = y; }
        dy = y - y_prev_;
        y_prev_ = y;
        have_prev_ = true;
        miss_run_ = 0;
        y_last = y;
    } else {
        if (in.y_valid || miss_run_ > 0u) { have_prev_ = false; }   // one plain miss is differenced across
        ++miss_run_;
        h |= PD_H_STALE;
    }
    dy_last = dy;

    const bool mean_done = period(ok, y, h);

    double m = 0.0;
    if (t_.law == PD_LAW_LITERAL) {
        if (mean_done) { literal_update(h); }
        m = m_held_;
    } else if (t_.law == PD_LAW_FAST_AVGP && zero_run_ > 0) {
        --zero_run_;
    } else if (ok) {
        const double xp = (t_.law == PD_LAW_FAST_AVGP && have_xbar_) ? xbar_ : y;
        m = torque(-(gp_ * xp + gd_ * dy), h);
    } else if (miss_run_ <= static_cast<std::uint32_t>(t_.n_hold)) {
        m = m_last_;
    } else {
        h |= PD_H_COAST;
    }

    if (in.beta_valid) {
        const double b = static_cast<double>(in.beta_cnt) * kBeta;
        if (std::fabs(b) > t_.beta_warn) { h |= PD_H_BETA_WARN; }
        if (std::fabs(b) >= t_.beta_lim) {
            h |= PD_H_BETA_LIM;
            ++beta_lim;
            if ((m > 0.0 && b > 0.0) || (m < 0.0 && b < 0.0)) { m = 0.0; }
        }
    }
    if (src_ == PD_SRC_ADAPTIVE) {
        adaptive_sample(ok, y, m);
        const auto st = static_cast<std::uint32_t>(fest_->out().state);
        h |= (st << 12) & PD_H_FEST;
        h |= (fest_->out().state == pd::FestState::Fault) ? PD_H_FEST_FAULT : 0u;
    }
    m_last_ = m;
    health_sticky |= h;
    return PdRefOut{m, h};
}

}  // namespace ref
