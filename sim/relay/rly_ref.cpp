#include "relay/rly_ref.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ref {

namespace {

constexpr double kQ24Lsb_rad = 1.0 / 16777216.0;       // 2^-24
constexpr double kQ40PerRad = 1099511627776.0;          // 2^40
constexpr double kRootTol_s = 1e-12;                    // crossing refinement (§2.2)
constexpr double kGrazeMinWidth_s = 1e-9;               // below this a graze overshoots < 1e-22 rad
constexpr double kEvalSlack_rad = 1e-15;                // >> rounding of a closed-form x (~1e-19 rad)

std::size_t ix(int i) { return static_cast<std::size_t>(i); }

// Signed distance of x into the region where state s's level test fires (>= 0: fires, in the
// continuous reading). W: |x| >= eps; R_MAIN: x <= eps - gamma; L_MAIN: x >= -(eps - gamma).
double fire_margin(RlyRefState s, double x_rad, double eps_rad, double epg_rad)
{
    switch (s) {
    case RlyRefState::W_POS:
    case RlyRefState::W_NEG: return std::fabs(x_rad) - eps_rad;
    case RlyRefState::R_MAIN: return epg_rad - x_rad;
    case RlyRefState::L_MAIN: return x_rad + epg_rad;
    case RlyRefState::R_BRAKE:
    case RlyRefState::L_BRAKE: break;
    }
    return -std::numeric_limits<double>::infinity();
}

// A smooth g with |g''| <= M on [a, b] satisfies g <= max(g(a), g(b)) + M (b - a)^2 / 8 there
// (the chord bound), so an interval whose end values clear the threshold by that much holds no
// crossing. This is the miss bound of §2.2: a plain scan on grid h_s misses a crossing only if it
// overshoots by less than max|x''|·h_s^2/8 (≈ 2e-8 rad at h_s = 0.05 s in a main pulse); the scans
// below subdivide every interval that does not clear it, so they miss nothing wider than
// kGrazeMinWidth_s (driver 1) or no tick at all (driver 2).
double chord_bound(double xddot_max, double width_s) { return xddot_max * width_s * width_s / 8.0; }

// Sweep of a(t) = sum_i a_i over the points dt(k) = (k - k_off)*step + base of one segment: exact
// rotation of the anchor at the first point and every `resync` points, the one-step rotation in
// between (relative error <= resync * 1e-16; never propagates across segments).
class Sweep {
public:
    Sweep(const Segment &seg, std::uint64_t k_first, std::uint64_t k_off, double base_s, double step_s,
          int resync)
        : seg_(seg), k_(k_first), k_off_(k_off), base_(base_s), step_(step_s), resync_(std::max(resync, 1))
    {
        for (int i = 0; i < seg.n_modes(); ++i) {
            const double th = seg.omega_radps(i) * step_s;
            cs_[ix(i)] = std::cos(th);
            sn_[ix(i)] = std::sin(th);
        }
        exact();
    }
    void next()
    {
        ++k_;
        if (++since_ == resync_) {
            exact();
            return;
        }
        for (int i = 0; i < seg_.n_modes(); ++i) {
            const std::size_t j = ix(i);
            const double y = y_[j] * cs_[j] + p_[j] * sn_[j];
            p_[j] = p_[j] * cs_[j] - y_[j] * sn_[j];
            y_[j] = y;
        }
    }
    double a_i_rad(int i) const
    {
        const double q = seg_.c_rad(i) + y_[ix(i)];
        return std::sqrt(q * q + p_[ix(i)] * p_[ix(i)]);
    }
    double a_rad() const
    {
        double a = 0.0;
        for (int i = 0; i < seg_.n_modes(); ++i) {
            a += a_i_rad(i);
        }
        return a;
    }

private:
    void exact()
    {
        since_ = 0;
        const double dt = static_cast<double>(k_ - k_off_) * step_ + base_;
        for (int i = 0; i < seg_.n_modes(); ++i) {
            const double th = seg_.omega_radps(i) * dt;
            const double c = std::cos(th), s = std::sin(th);
            y_[ix(i)] = seg_.y_rad(i) * c + seg_.p_rad(i) * s;
            p_[ix(i)] = seg_.p_rad(i) * c - seg_.y_rad(i) * s;
        }
    }

    const Segment &seg_;
    std::uint64_t k_, k_off_;
    double base_, step_;
    int resync_, since_ = 0;
    std::array<double, kRelayMaxModes> y_{}, p_{}, cs_{}, sn_{};
};

// Envelope points k in [k_from, k_to) of a segment, handed to sink(k, sweep).
template <class Sink>
void sweep_points(const Segment &seg, std::uint64_t k_from, std::uint64_t k_to, std::uint64_t k_off,
                  double base_s, double step_s, int resync, Sink &sink)
{
    if (k_from >= k_to) {
        return;
    }
    Sweep sw(seg, k_from, k_off, base_s, step_s, resync);
    for (std::uint64_t k = k_from;;) {
        sink(k, sw);
        if (++k == k_to) {
            break;
        }
        sw.next();
    }
}

// abar over grid indices [k0, k1) and the 20-Hz samples (every env_every-th grid point).
class MeanSink {
public:
    MeanSink(double grid_s, const RunOptions &opt, RelayRun &run)
        : k0_(static_cast<std::uint64_t>(std::llround(opt.abar_t0_s / grid_s))),
          k1_(static_cast<std::uint64_t>(std::llround(opt.abar_t1_s / grid_s))),
          env_every_(static_cast<std::uint64_t>(std::max<long long>(1, std::llround(opt.env_dt_s / grid_s)))),
          run_(run)
    {
        run_.env_dt_s = static_cast<double>(env_every_) * grid_s;
    }
    void add(std::uint64_t k, double a_rad)
    {
        if (k >= k0_ && k < k1_) {
            part_ += a_rad;
            if (++n_ % 4096u == 0u) {   // partial sums keep the 2e8-term mean at ~1e-13 relative
                sum_ += part_;
                part_ = 0.0;
            }
        }
        if (k % env_every_ == 0u) {
            run_.env_rad.push_back(a_rad);
        }
    }
    void finish()
    {
        run_.abar_points = n_;
        run_.abar_rad = n_ > 0u ? (sum_ + part_) / static_cast<double>(n_) : 0.0;
    }

private:
    std::uint64_t k0_, k1_, env_every_;
    double sum_ = 0.0, part_ = 0.0;
    std::uint64_t n_ = 0u;
    RelayRun &run_;
};

// Pulse bookkeeping shared by the tick drivers, from the law state before and after a tick.
class PulseTracker {
public:
    void on_tick(RlyRefState before, RlyRefState after, double t_s, double xdot_radps, std::uint32_t tau1,
                 std::uint32_t tau2, double h_s, RelayRun &run)
    {
        if (after == before) {
            return;
        }
        if (is_main(after)) {
            cur_ = MainPulse{after == RlyRefState::R_MAIN ? 1 : -1, t_s, xdot_radps, 0.0, 0.0};
        } else if (is_brake(after) && is_main(before)) {
            cur_.tau_main_s = static_cast<double>(tau1) * h_s;
            cur_.tau_brake_s = static_cast<double>(tau2) * h_s;
            run.pulses.push_back(cur_);
        }
    }

private:
    MainPulse cur_{};
};

// First tick in [k, k_last] at which the law's current W/MAIN test fires on the closed-form x of
// the segment; k_last + 1 if none. Blocks of `block` ticks are cleared by the chord bound and
// halved where they are not, down to single ticks, which run the law's own (exact) test.
template <class X, class SampleFn>
class TickSearch {
public:
    TickSearch(const Segment &seg, std::uint64_t k_a, double h_s, const TickLawT<X> &law, SampleFn sample,
               double eps_rad, double epg_rad, double slack_rad, std::uint64_t &evals)
        : seg_(seg), k_a_(k_a), h_(h_s), law_(law), sample_(sample), eps_(eps_rad), epg_(epg_rad),
          slack_(slack_rad), evals_(evals)
    {
    }
    std::uint64_t first_fire(std::uint64_t k, std::uint64_t k_last, std::uint64_t block)
    {
        double xa = x(k);
        if (law_.fires(sample_(xa))) {
            return k;
        }
        std::uint64_t hit = 0u;
        for (std::uint64_t a = k; a < k_last;) {
            const std::uint64_t b = std::min(a + block, k_last);
            const double xb = x(b);
            if (find(a, xa, b, xb, hit)) {
                return hit;
            }
            a = b;
            xa = xb;
        }
        return k_last + 1u;
    }

private:
    double x(std::uint64_t k)
    {
        ++evals_;
        return seg_.x_rad(static_cast<double>(k - k_a_) * h_);
    }
    double g(double x_rad) const { return fire_margin(law_.state(), x_rad, eps_, epg_); }
    // First firing tick in (a, b].
    bool find(std::uint64_t a, double xa, std::uint64_t b, double xb, std::uint64_t &hit)
    {
        const double w = static_cast<double>(b - a) * h_;
        if (std::max(g(xa), g(xb)) + chord_bound(seg_.xddot_max_radps2(), w) < -slack_) {
            return false;
        }
        if (b - a == 1u) {
            if (law_.fires(sample_(xb))) {
                hit = b;
                return true;
            }
            return false;
        }
        const std::uint64_t mid = a + (b - a) / 2u;
        const double xm = x(mid);
        return find(a, xa, mid, xm, hit) || find(mid, xm, b, xb, hit);
    }

    const Segment &seg_;
    std::uint64_t k_a_;
    double h_;
    const TickLawT<X> &law_;
    SampleFn sample_;
    double eps_, epg_, slack_;
    std::uint64_t &evals_;
};

// Window sums for run_adaptive: per tick sum_i round(a_i * 2^40), adaptation at the window's last tick.
struct WindowAcc {
    Adapt *adapt = nullptr;
    std::uint32_t win_ticks = 0u;
    std::uint64_t s = 0u;
    std::vector<WindowRecord> *out = nullptr;
};

// Driver 2 and the adaptive loop: tick law at h over the exact plant (§2.2 driver 2 / lock-step
// semantics: command k acts over [t_k, t_k + h), x_k from the anchor of the last level change with
// elapsed (k - k_a)*h). With jump_ahead the ticks on which no test can fire are skipped in one
// TickLaw::skip; otherwise every tick is run (the check of the jump-ahead).
template <class X, class SampleFn>
void tick_core(const RelayModel &model, TickLawT<X> &law, SampleFn sample, double eps_rad, double epg_rad,
               double slack_rad, const RelayState &state0, double h_s, std::uint64_t n_ticks,
               const RunOptions &opt, RelayRun &run, WindowAcc *win)
{
    MeanSink mean(h_s, opt, run);
    PulseTracker pulses;
    int level = law.command();
    Segment seg(model, state0, level);
    std::uint64_t k_a = 0u, k_env = 0u;
    const std::uint64_t block =
        static_cast<std::uint64_t>(std::max<long long>(1, std::llround(opt.scan_h_s / h_s)));

    auto sink = [&](std::uint64_t k, const Sweep &sw) {
        mean.add(k, sw.a_rad());
        if (win == nullptr) {
            return;
        }
        for (int i = 0; i < model.n_modes; ++i) {
            win->s += static_cast<std::uint64_t>(std::llround(sw.a_i_rad(i) * kQ40PerRad));
        }
        if ((k + 1u) % win->win_ticks == 0u) {
            WindowRecord rec{};
            rec.s = win->s;
            rec.abar_rad = static_cast<double>(win->s) / kQ40PerRad / static_cast<double>(win->win_ticks);
            rec.adapt = win->adapt->window_end(win->s, true);
            win->out->push_back(rec);
            law.set_kt_q16(win->adapt->kt_q16());
            win->s = 0u;
        }
    };
    // a_k for every tick below k_to, from the segment in force (a_k does not depend on command k).
    auto flush = [&](std::uint64_t k_to) {
        sweep_points(seg, k_env, k_to, k_a, 0.0, h_s, opt.resync, sink);
        k_env = std::max(k_env, k_to);
    };

    for (std::uint64_t k = 0u; k < n_ticks;) {
        const RlyRefState before = law.state();
        std::uint64_t quiet = 0u;
        if (opt.jump_ahead) {
            if (is_brake(before)) {
                quiet = std::min<std::uint64_t>(law.nb() - 1u, n_ticks - k);
            } else {
                TickSearch<X, SampleFn> search(seg, k_a, h_s, law, sample, eps_rad, epg_rad, slack_rad,
                                               run.x_evaluations);
                quiet = search.first_fire(k, n_ticks - 1u, block) - k;
            }
        }
        if (quiet > 0u) {
            law.skip(quiet);
            k += quiet;
            continue;
        }
        flush(k + 1u);
        const double dt = static_cast<double>(k - k_a) * h_s;
        const double xk = seg.x_rad(dt);
        ++run.x_evaluations;
        const int cmd = law.step(sample(xk));
        pulses.on_tick(before, law.state(), static_cast<double>(k) * h_s, seg.xdot_radps(dt), law.tau1(),
                       law.tau2(), h_s, run);
        if (cmd != level) {
            seg = Segment(model, seg.state(dt), cmd);
            k_a = k;
            level = cmd;
            run.switches.push_back(SwitchEvent{static_cast<double>(k) * h_s, cmd});
        }
        ++k;
    }
    flush(n_ticks);
    mean.finish();
    run.final_state = seg.state(static_cast<double>(n_ticks - k_a) * h_s);
    run.tau_sat = law.tau_sat_count();
}

std::uint64_t tick_count(double t_end_s, double h_s)
{
    return static_cast<std::uint64_t>(std::llround(t_end_s / h_s));
}

void run_tick_typed(const RelayModel &model, const RelayLaw &law, const RelayState &state0, double t_end_s,
                    const RunOptions &opt, RelayRun &run, WindowAcc *win, std::uint32_t kt_q16)
{
    const std::uint64_t n = tick_count(t_end_s, law.h_s);
    if (opt.quantise) {
        TickLaw tl = make_tick_law(law, false);
        tl.set_kt_q16(kt_q16);
        const double eps = static_cast<double>(tl.eps()) * kQ24Lsb_rad;
        const double epg = static_cast<double>(tl.eps_minus_gamma()) * kQ24Lsb_rad;
        // Rounding moves a threshold by half a count: one count of slack keeps the chord test safe.
        tick_core(model, tl, [](double x) { return quantise_q24(x); }, eps, epg, kQ24Lsb_rad + kEvalSlack_rad,
                  state0, law.h_s, n, opt, run, win);
    } else {
        TickLawD tl = make_tick_law_double(law, false);
        tl.set_kt_q16(kt_q16);
        tick_core(model, tl, [](double x) { return x; }, tl.eps(), tl.eps_minus_gamma(), kEvalSlack_rad, state0,
                  law.h_s, n, opt, run, win);
    }
}

// Driver 1 crossing search: first dt in [0, dt_max] with g(dt) >= 0, refined to kRootTol_s.
class CrossingSearch {
public:
    CrossingSearch(const Segment &seg, RlyRefState s, double eps_rad, double epg_rad, std::uint64_t &evals)
        : seg_(seg), s_(s), eps_(eps_rad), epg_(epg_rad), evals_(evals)
    {
    }
    bool first(double dt_max, double h_scan, double &dt_hit, std::uint64_t &grazes)
    {
        double a = 0.0, ga = g(0.0);
        if (ga >= 0.0) {
            dt_hit = 0.0;
            return true;
        }
        while (a < dt_max) {
            const double b = std::min(a + h_scan, dt_max);
            const double gb = g(b);
            if (gb >= 0.0) {
                dt_hit = bisect(a, b);
                return true;
            }
            if (suspect(a, ga, b, gb, dt_hit)) {
                ++grazes;
                return true;
            }
            a = b;
            ga = gb;
        }
        return false;
    }

private:
    double g(double dt)
    {
        ++evals_;
        return fire_margin(s_, seg_.x_rad(dt), eps_, epg_);
    }
    // Both ends below: subdivide while the chord bound allows a crossing in between.
    bool suspect(double a, double ga, double b, double gb, double &dt_hit)
    {
        if (std::max(ga, gb) + chord_bound(seg_.xddot_max_radps2(), b - a) < -kEvalSlack_rad ||
            b - a < kGrazeMinWidth_s) {
            return false;
        }
        const double m = 0.5 * (a + b);
        const double gm = g(m);
        if (gm >= 0.0) {
            dt_hit = bisect(a, m);
            return true;
        }
        return suspect(a, ga, m, gm, dt_hit) || suspect(m, gm, b, gb, dt_hit);
    }
    // g(lo) < 0 <= g(hi): returns the hi end once the bracket is below kRootTol_s (or one ulp).
    double bisect(double lo, double hi)
    {
        while (hi - lo > kRootTol_s) {
            const double m = 0.5 * (lo + hi);
            if (m <= lo || m >= hi) {
                break;
            }
            (g(m) >= 0.0 ? hi : lo) = m;
        }
        return hi;
    }

    const Segment &seg_;
    RlyRefState s_;
    double eps_, epg_;
    std::uint64_t &evals_;
};

}  // namespace

// ------------------------------------------------------------------------------------------------
// Plant

double RelayState::x() const
{
    double x = xbar_rad;
    for (double q : q_rad) {
        x += q;
    }
    return x;
}

double level_moment(const RelayModel &model, int level)
{
    switch (level) {
    case -2: return -model.m_u_radps2;
    case -1: return -model.m_eps_radps2;
    case 1: return model.m_eps_radps2;
    case 2: return model.m_u_radps2;
    default: return 0.0;
    }
}

Segment::Segment(const RelayModel &model, const RelayState &anchor, int level)
    : a_(anchor), level_(level), n_(std::clamp(model.n_modes, 0, kRelayMaxModes)),
      m_(level_moment(model, level)), xddot_max_(std::fabs(m_))
{
    for (int i = 0; i < n_; ++i) {
        const std::size_t j = ix(i);
        const double w = model.omega_radps[j];
        omega_[j] = w;
        c_[j] = model.k[j] * m_ / (w * w);
        y_[j] = anchor.q_rad[j] - c_[j];
        p_[j] = anchor.qdot_radps[j] / w;
        xddot_max_ += w * w * std::sqrt(y_[j] * y_[j] + p_[j] * p_[j]);
    }
}

double Segment::x_rad(double dt_s) const
{
    double x = a_.xbar_rad + a_.xbardot_radps * dt_s + 0.5 * m_ * dt_s * dt_s;
    for (int i = 0; i < n_; ++i) {
        const std::size_t j = ix(i);
        const double th = omega_[j] * dt_s;
        x += c_[j] + y_[j] * std::cos(th) + p_[j] * std::sin(th);
    }
    return x;
}

double Segment::xdot_radps(double dt_s) const
{
    double v = a_.xbardot_radps + m_ * dt_s;
    for (int i = 0; i < n_; ++i) {
        const std::size_t j = ix(i);
        const double th = omega_[j] * dt_s;
        v += -omega_[j] * y_[j] * std::sin(th) + a_.qdot_radps[j] * std::cos(th);
    }
    return v;
}

RelayState Segment::state(double dt_s) const
{
    RelayState s = a_;
    s.xbar_rad = a_.xbar_rad + a_.xbardot_radps * dt_s + m_ * dt_s * dt_s / 2.0;
    s.xbardot_radps = a_.xbardot_radps + m_ * dt_s;
    for (int i = 0; i < n_; ++i) {
        const std::size_t j = ix(i);
        const double th = omega_[j] * dt_s;
        const double c = std::cos(th), sn = std::sin(th);
        s.q_rad[j] = c_[j] + y_[j] * c + (a_.qdot_radps[j] / omega_[j]) * sn;
        s.qdot_radps[j] = -omega_[j] * y_[j] * sn + a_.qdot_radps[j] * c;
    }
    return s;
}

RelayState propagate(const RelayModel &model, const RelayState &anchor, int level, double dt_s)
{
    return Segment(model, anchor, level).state(dt_s);
}

double mode_amplitude(const RelayModel &model, const RelayState &s, int i)
{
    const double p = s.qdot_radps[ix(i)] / model.omega_radps[ix(i)];
    return std::sqrt(s.q_rad[ix(i)] * s.q_rad[ix(i)] + p * p);
}

// ------------------------------------------------------------------------------------------------
// Law helpers

std::uint32_t tau2_ticks(std::uint32_t kt_q16, std::uint32_t tau1)
{
    const std::uint64_t v = (static_cast<std::uint64_t>(kt_q16) * tau1 + (1u << 15)) >> 16;
    return static_cast<std::uint32_t>(std::max<std::uint64_t>(1u, std::min<std::uint64_t>(v, tau1)));
}

std::int32_t quantise_q24(double x_rad)
{
    constexpr double kMax = 8388608.0;   // 2^23 counts
    const double c = std::clamp(std::round(x_rad / kQ24Lsb_rad), -kMax, kMax);   // round: half away
    return static_cast<std::int32_t>(c);
}

std::int32_t q24_from_rad(double v_rad) { return static_cast<std::int32_t>(std::lround(v_rad / kQ24Lsb_rad)); }

int state_command(RlyRefState s)
{
    switch (s) {
    case RlyRefState::W_POS: return 1;
    case RlyRefState::R_MAIN: return -2;
    case RlyRefState::R_BRAKE: return 2;
    case RlyRefState::W_NEG: return -1;
    case RlyRefState::L_MAIN: return 2;
    case RlyRefState::L_BRAKE: return -2;
    }
    return 0;
}

bool is_main(RlyRefState s) { return s == RlyRefState::R_MAIN || s == RlyRefState::L_MAIN; }
bool is_brake(RlyRefState s) { return s == RlyRefState::R_BRAKE || s == RlyRefState::L_BRAKE; }

TickLaw make_tick_law(const RelayLaw &law, bool log_transitions)
{
    return TickLaw(q24_from_rad(law.eps_rad), q24_from_rad(law.gamma_rad), law.kt_q16, law.tau_max_ticks,
                   log_transitions);
}

TickLawD make_tick_law_double(const RelayLaw &law, bool log_transitions)
{
    return TickLawD(law.eps_rad, law.gamma_rad, law.kt_q16, law.tau_max_ticks, log_transitions);
}

// ------------------------------------------------------------------------------------------------
// Drivers

RelayRun run_continuous(const RelayModel &model, const RelayLaw &law, const RelayState &state0, double t_end_s,
                        const RunOptions &opt, double kt_override)
{
    const double kt = kt_override >= 0.0 ? kt_override : static_cast<double>(law.kt_q16) / 65536.0;
    const double epg = law.eps_rad - law.gamma_rad;
    const double hm = opt.mean_dt_s;
    RelayRun run;
    MeanSink mean(hm, opt, run);
    auto sink = [&](std::uint64_t k, const Sweep &sw) { mean.add(k, sw.a_rad()); };
    auto grid_index = [hm](double t) { return static_cast<std::uint64_t>(std::ceil(t / hm)); };

    RlyRefState st = RlyRefState::W_POS;
    double t_a = 0.0;                       // anchor time; events are 10^3 apart, not 10^7 steps
    Segment seg(model, state0, state_command(st));
    std::uint64_t k_env = 0u;
    MainPulse pulse{};

    // Close the segment at dt after its anchor and open the next one in state `to`.
    auto switch_to = [&](double dt, RlyRefState to) {
        const double t_new = t_a + dt;
        const std::uint64_t k_to = grid_index(t_new);
        sweep_points(seg, k_env, k_to, 0u, -t_a, hm, opt.resync, sink);
        k_env = std::max(k_env, k_to);
        seg = Segment(model, seg.state(dt), state_command(to));
        t_a = t_new;
        st = to;
        run.switches.push_back(SwitchEvent{t_new, state_command(to)});
    };

    for (;;) {
        const double dt_max = t_end_s - t_a;
        if (is_brake(st)) {
            if (pulse.tau_brake_s > dt_max) {
                break;
            }
            switch_to(pulse.tau_brake_s, st == RlyRefState::R_BRAKE ? RlyRefState::W_POS : RlyRefState::W_NEG);
            continue;
        }
        double dt = 0.0;
        CrossingSearch cs(seg, st, law.eps_rad, epg, run.x_evaluations);
        if (!cs.first(dt_max, opt.scan_h_s, dt, run.grazes)) {
            break;
        }
        if (is_main(st)) {
            pulse.tau_main_s = dt;   // the main segment is anchored at the pulse start
            pulse.tau_brake_s = kt * dt;
            run.pulses.push_back(pulse);
            switch_to(dt, st == RlyRefState::R_MAIN ? RlyRefState::R_BRAKE : RlyRefState::L_BRAKE);
        } else {
            const bool right = seg.x_rad(dt) >= 0.0;
            pulse = MainPulse{right ? 1 : -1, t_a + dt, seg.xdot_radps(dt), 0.0, 0.0};
            switch_to(dt, right ? RlyRefState::R_MAIN : RlyRefState::L_MAIN);
        }
    }
    sweep_points(seg, k_env, grid_index(t_end_s), 0u, -t_a, hm, opt.resync, sink);
    mean.finish();
    run.final_state = seg.state(t_end_s - t_a);
    return run;
}

RelayRun run_tick_sampled(const RelayModel &model, const RelayLaw &law, const RelayState &state0, double t_end_s,
                          const RunOptions &opt)
{
    RelayRun run;
    run_tick_typed(model, law, state0, t_end_s, opt, run, nullptr, law.kt_q16);
    return run;
}

RelayRun run_rk4(const RelayModel &model, const RelayLaw &law, const RelayState &state0, double t_end_s,
                 double h_s, const RunOptions &opt)
{
    struct Y {
        double xb, xd;
        std::array<double, kRelayMaxModes> q, qd;
    };
    const int n = std::clamp(model.n_modes, 0, kRelayMaxModes);
    auto deriv = [&](const Y &y, double m) {
        Y d{y.xd, m, {}, {}};
        for (int i = 0; i < n; ++i) {
            const std::size_t j = ix(i);
            d.q[j] = y.qd[j];
            d.qd[j] = model.k[j] * m - model.omega_radps[j] * model.omega_radps[j] * y.q[j];
        }
        return d;
    };
    auto axpy = [&](const Y &y, const Y &d, double s) {
        Y r = y;
        r.xb += s * d.xb;
        r.xd += s * d.xd;
        for (int i = 0; i < n; ++i) {
            r.q[ix(i)] += s * d.q[ix(i)];
            r.qd[ix(i)] += s * d.qd[ix(i)];
        }
        return r;
    };

    RelayRun run;
    RelayLaw lh = law;
    lh.h_s = h_s;
    TickLawD tl = make_tick_law_double(lh, false);
    MeanSink mean(h_s, opt, run);
    PulseTracker pulses;
    Y y{state0.xbar_rad, state0.xbardot_radps, state0.q_rad, state0.qdot_radps};
    int level = tl.command();
    const std::uint64_t n_ticks = tick_count(t_end_s, h_s);
    for (std::uint64_t k = 0u; k < n_ticks; ++k) {
        double x = y.xb, xdot = y.xd, a = 0.0;
        for (int i = 0; i < n; ++i) {
            const std::size_t j = ix(i);
            x += y.q[j];
            xdot += y.qd[j];
            const double p = y.qd[j] / model.omega_radps[j];
            a += std::sqrt(y.q[j] * y.q[j] + p * p);
        }
        mean.add(k, a);
        const double t = static_cast<double>(k) * h_s;
        const RlyRefState before = tl.state();
        const int cmd = tl.step(x);
        pulses.on_tick(before, tl.state(), t, xdot, tl.tau1(), tl.tau2(), h_s, run);
        if (cmd != level) {
            level = cmd;
            run.switches.push_back(SwitchEvent{t, cmd});
        }
        const double m = level_moment(model, level);
        const Y k1 = deriv(y, m);
        const Y k2 = deriv(axpy(y, k1, h_s / 2.0), m);
        const Y k3 = deriv(axpy(y, k2, h_s / 2.0), m);
        const Y k4 = deriv(axpy(y, k3, h_s), m);
        y.xb += h_s / 6.0 * (k1.xb + 2.0 * k2.xb + 2.0 * k3.xb + k4.xb);
        y.xd += h_s / 6.0 * (k1.xd + 2.0 * k2.xd + 2.0 * k3.xd + k4.xd);
        for (int i = 0; i < n; ++i) {
            const std::size_t j = ix(i);
            y.q[j] += h_s / 6.0 * (k1.q[j] + 2.0 * k2.q[j] + 2.0 * k3.q[j] + k4.q[j]);
            y.qd[j] += h_s / 6.0 * (k1.qd[j] + 2.0 * k2.qd[j] + 2.0 * k3.qd[j] + k4.qd[j]);
        }
    }
    mean.finish();
    run.final_state.xbar_rad = y.xb;
    run.final_state.xbardot_radps = y.xd;
    run.final_state.q_rad = y.q;
    run.final_state.qdot_radps = y.qd;
    run.tau_sat = tl.tau_sat_count();
    return run;
}

double envelope_period_s(const RelayRun &run, double t_from_s, double lag_min_s, double lag_max_s)
{
    const double dt = run.env_dt_s;
    const std::size_t i0 = static_cast<std::size_t>(std::max(0.0, std::ceil(t_from_s / dt)));
    if (i0 >= run.env_rad.size()) {
        return 0.0;
    }
    std::vector<double> a(run.env_rad.begin() + static_cast<std::ptrdiff_t>(i0), run.env_rad.end());
    double mean = 0.0;
    for (double v : a) {
        mean += v;
    }
    mean /= static_cast<double>(a.size());
    for (double &v : a) {
        v -= mean;
    }
    const std::size_t l0 = static_cast<std::size_t>(std::llround(lag_min_s / dt));
    const std::size_t l1 = std::min(static_cast<std::size_t>(std::llround(lag_max_s / dt)), a.size() / 2u);
    auto corr = [&](std::size_t lag) {
        double s = 0.0;
        for (std::size_t i = 0; i + lag < a.size(); ++i) {
            s += a[i] * a[i + lag];
        }
        return s / static_cast<double>(a.size() - lag);
    };
    std::vector<double> r(l1 + 2u, 0.0);
    std::size_t best = l0;
    for (std::size_t lag = l0 > 0u ? l0 - 1u : 0u; lag <= l1 + 1u && lag < a.size(); ++lag) {
        r[lag] = corr(lag);
    }
    for (std::size_t lag = l0; lag <= l1; ++lag) {
        if (r[lag] > r[best]) {
            best = lag;
        }
    }
    // An almost periodic a(t) correlates about as well at 2, 3, ... periods: take the first local
    // maximum within 10 % of the largest.
    const double r_max = r[best];
    for (std::size_t lag = std::max<std::size_t>(l0, 1u); lag <= l1; ++lag) {
        if (r[lag] >= 0.9 * r_max && r[lag] >= r[lag - 1u] && r[lag] >= r[lag + 1u]) {
            best = lag;
            break;
        }
    }
    // Parabolic refinement of the peak between samples.
    double frac = 0.0;
    if (best > 0u && best + 1u < r.size()) {
        const double den = r[best - 1u] - 2.0 * r[best] + r[best + 1u];
        if (den < 0.0) {
            frac = 0.5 * (r[best - 1u] - r[best + 1u]) / den;
        }
    }
    return (static_cast<double>(best) + frac) * dt;
}

// ------------------------------------------------------------------------------------------------
// Envelope copy

EnvelopeCopy::EnvelopeCopy(const RelayModel &model, double h_s, const RelayState &initial, int level0,
                           int resync_ticks)
    : model_(model), h_(h_s), resync_(std::max(resync_ticks, 1)), level_(level0)
{
    model_.n_modes = std::clamp(model.n_modes, 0, kRelayMaxModes);
    set_c(level0);
    for (int i = 0; i < model_.n_modes; ++i) {
        const std::size_t j = ix(i);
        const double w = model_.omega_radps[j];
        cs_[j] = std::cos(w * h_s);
        sn_[j] = std::sin(w * h_s);
        u_[j] = initial.q_rad[j] - c_[j];
        v_[j] = initial.qdot_radps[j] / w;
        y_[j] = u_[j];
        p_[j] = v_[j];
    }
}

void EnvelopeCopy::set_c(int level)
{
    const double m = level_moment(model_, level);
    for (int i = 0; i < model_.n_modes; ++i) {
        const double w = model_.omega_radps[ix(i)];
        c_[ix(i)] = model_.k[ix(i)] * m / (w * w);
    }
}

double EnvelopeCopy::a_i_rad(int i) const
{
    const double q = q_rad(i);
    return std::sqrt(q * q + p_[ix(i)] * p_[ix(i)]);
}

double EnvelopeCopy::a_rad() const
{
    double a = 0.0;
    for (int i = 0; i < model_.n_modes; ++i) {
        a += a_i_rad(i);
    }
    return a;
}

void EnvelopeCopy::advance(int level)
{
    if (level != level_) {
        std::array<double, kRelayMaxModes> q{};
        for (int i = 0; i < model_.n_modes; ++i) {
            q[ix(i)] = q_rad(i);
        }
        set_c(level);
        for (int i = 0; i < model_.n_modes; ++i) {
            u_[ix(i)] = q[ix(i)] - c_[ix(i)];
            v_[ix(i)] = p_[ix(i)];
            y_[ix(i)] = u_[ix(i)];
        }
        level_ = level;
        n_ = 0u;
    }
    ++n_;
    const bool exact = n_ % static_cast<std::uint64_t>(resync_) == 0u;
    for (int i = 0; i < model_.n_modes; ++i) {
        const std::size_t j = ix(i);
        if (exact) {
            const double th = model_.omega_radps[j] * (static_cast<double>(n_) * h_);
            const double c = std::cos(th), s = std::sin(th);
            y_[j] = u_[j] * c + v_[j] * s;
            p_[j] = v_[j] * c - u_[j] * s;
        } else {
            const double y = y_[j] * cs_[j] + p_[j] * sn_[j];
            p_[j] = p_[j] * cs_[j] - y_[j] * sn_[j];
            y_[j] = y;
        }
    }
}

// ------------------------------------------------------------------------------------------------
// Adaptation

Xorshift32::Xorshift32(std::uint32_t seed) : s_(seed)
{
    for (int i = 0; i < 16; ++i) {
        next();
    }
}

std::uint32_t Xorshift32::next()
{
    s_ ^= s_ << 13;
    s_ ^= s_ >> 17;
    s_ ^= s_ << 5;
    return s_;
}

std::vector<std::uint32_t> xorshift32_stream(std::uint32_t seed, int n)
{
    Xorshift32 g(seed);
    std::vector<std::uint32_t> out;
    out.reserve(static_cast<std::size_t>(std::max(n, 0)));
    for (int i = 0; i < n; ++i) {
        out.push_back(g.next());
    }
    return out;
}

Adapt::Adapt(const AdaptParams &p) : p_(p), rng_(p.seed), kt_(p.kt0_q16) {}

std::uint32_t Adapt::clamp_kt(std::int64_t kt, bool *clamped)
{
    const std::int64_t lo = p_.kt_min_q16, hi = p_.kt_max_q16;
    const std::int64_t c = std::clamp(kt, lo, hi);
    if (c != kt) {
        ++clamped_;
        if (clamped != nullptr) {
            *clamped = true;
        }
    }
    return static_cast<std::uint32_t>(c);
}

// One draw per decision (§5.3); random_sign takes the sign bit, otherwise sign_ was set by learning
// and the bit is ignored, the draw still consumed.
void Adapt::draw_step(WindowResult &r, bool random_sign)
{
    const std::uint32_t u = rng_.next();
    if (random_sign) {
        sign_ = (u >> 31) != 0u ? -1 : 1;
    }
    const std::uint32_t mag = ((u >> 15) & 0xFFFFu) + 1u;
    const std::uint64_t step = (static_cast<std::uint64_t>(mag) * p_.dk_q16 + (1u << 15)) >> 16;
    kt_ = clamp_kt(static_cast<std::int64_t>(kt_) + sign_ * static_cast<std::int64_t>(step), &r.kt_clamped);
    r.event = AdaptEvent::STEP;
    r.sign = sign_;
    r.mag_q16 = mag;
    r.step_q16 = static_cast<std::uint32_t>(step);
}

void Adapt::freeze(std::uint32_t kt_f)
{
    kt_ = kt_f;
    phase_ = AdaptPhase::FROZEN;
    frozen_age_ = 0u;
    above_ref_ = 0u;
    s_ref_ = 0u;
}

// Choices where §5 leaves one open (all documented here, exercised by G5):
//  - j counts every window, skipped ones included ((j+1)·T >= T_min is elapsed time); a skipped
//    window changes no decision state, but its k_t is kept in the history the settled gate reads.
//  - The "j = 0" draw happens at the first valid window (no S_{j-1} yet).
//  - count_before_tmin = 0: n_small is held at 0 for windows with j+1 < tmin_windows.
//  - learn_after_tmin = 0: after T_min the sign is the drawn sign bit; n_dec is left as it is.
//  - Freezes and probe windows draw nothing (no step decision); UNFREEZE draws as at j = 0.
//  - The settled gate compares k_t,j with k_t,j-n_small (the run length, 6), needing j >= n_small.
//  - PAPER keeps S_ref for telemetry (2nd window after the freeze) but never un-freezes.
//  - PROBE and FROZEN windows leave n_small and n_dec as they are; S_{j-1} follows every valid window.
WindowResult Adapt::window_end(std::uint64_t s_j, bool valid)
{
    WindowResult r;
    r.j = j_;
    r.s = s_j;
    r.kt_in_force_q16 = kt_;
    kt_hist_[j_ % kt_hist_.size()] = kt_;
    const bool after_tmin = static_cast<std::uint64_t>(j_) + 1u >= p_.tmin_windows;

    if (!valid) {
        r.event = AdaptEvent::SKIPPED;
    } else if (p_.mode == AdaptMode::OFF) {
        r.event = AdaptEvent::NONE;
    } else if (phase_ == AdaptPhase::SEARCH && !have_prev_) {
        draw_step(r, true);
    } else if (phase_ == AdaptPhase::SEARCH) {
        const std::uint64_t diff = s_j > s_prev_ ? s_j - s_prev_ : s_prev_ - s_j;
        const bool small = p_.delta0_den * diff < p_.delta0_num * s_j;    // den·S < 2^62 (§4.5)
        n_small_ = (small && (p_.count_before_tmin || after_tmin)) ? n_small_ + 1u : 0u;
        bool decided = false;
        const bool escape = p_.mode == AdaptMode::IMPROVED_UP && s_j > p_.escape_s;
        if (after_tmin && p_.mode == AdaptMode::PAPER && n_small_ >= p_.n_small) {
            freeze(kt_);
            r.event = AdaptEvent::FREEZE_SETTLED;
            decided = true;
        } else if (after_tmin && (p_.mode == AdaptMode::IMPROVED || p_.mode == AdaptMode::IMPROVED_UP)) {
            const std::uint32_t kt_prev = kt_hist_[(j_ - 1u) % kt_hist_.size()];   // j >= 1 here
            const std::uint32_t lag = p_.n_small;
            const int d = kt_ > kt_prev ? 1 : (kt_ < kt_prev ? -1 : sign_);
            if (p_.cliff_den * s_j > p_.cliff_num * s_prev_ && (p_.mode != AdaptMode::IMPROVED_UP || d > 0)) {
                const std::int64_t back = static_cast<std::int64_t>(p_.retreat_dk) * p_.dk_q16;
                freeze(clamp_kt(static_cast<std::int64_t>(kt_prev) - d * back, &r.kt_clamped));
                r.event = AdaptEvent::FREEZE_CLIFF;
                decided = true;
            } else if (!escape && n_small_ >= p_.n_small && j_ >= lag && lag < kt_hist_.size()) {
                const std::uint32_t kt_lag = kt_hist_[(j_ - lag) % kt_hist_.size()];
                const std::uint32_t span = kt_ > kt_lag ? kt_ - kt_lag : kt_lag - kt_;
                if (span < p_.gate_dk * p_.dk_q16) {
                    const std::int64_t kt = kt_, dk = p_.dk_q16;
                    probe_kt_ = {kt_, clamp_kt(kt + dk, &r.kt_clamped), clamp_kt(kt - dk, &r.kt_clamped)};
                    probe_idx_ = 0u;
                    probe_win_ = 0u;
                    phase_ = AdaptPhase::PROBE;
                    kt_ = probe_kt_[0];
                    r.event = AdaptEvent::PROBE_START;
                    decided = true;
                }
            }
        }
        if (!decided) {
            const bool learn = !after_tmin || p_.learn_after_tmin;
            if (escape) {
                sign_ = 1;                   // out of the erratic zone, towards the valley
                n_dec_ = 0u;
            } else if (learn) {
                if (s_j < s_prev_) {
                    ++n_dec_;
                } else if (n_dec_ >= p_.n_ignore) {
                    n_dec_ = 0u;             // a lone increase after a run of decreases is ignored
                } else {
                    sign_ = -sign_;
                    n_dec_ = 0u;
                }
            }
            draw_step(r, !learn && !escape);
        }
    } else if (phase_ == AdaptPhase::PROBE) {
        if (++probe_win_ > p_.probe_settle) {            // settle window(s), then the measured one
            probe_s_[probe_idx_] = s_j;
            probe_win_ = 0u;
            if (++probe_idx_ == probe_kt_.size()) {
                std::size_t best = 0u;
                for (std::size_t i = 1u; i < probe_s_.size(); ++i) {
                    if (probe_s_[i] < probe_s_[best]) {   // ties: the earlier point
                        best = i;
                    }
                }
                freeze(probe_kt_[best]);
                r.event = AdaptEvent::FREEZE_SETTLED;
            } else {
                kt_ = probe_kt_[probe_idx_];
            }
        }
    } else {   // FROZEN
        if (frozen_age_ < std::numeric_limits<std::uint32_t>::max()) {
            ++frozen_age_;
        }
        if (frozen_age_ == 2u) {
            s_ref_ = s_j;
        } else if (frozen_age_ > 2u && (p_.mode == AdaptMode::IMPROVED || p_.mode == AdaptMode::IMPROVED_UP)) {
            above_ref_ = p_.unfreeze_den * s_j > p_.unfreeze_num * s_ref_ ? above_ref_ + 1u : 0u;
            if (above_ref_ >= p_.unfreeze_windows) {
                phase_ = AdaptPhase::SEARCH;
                n_small_ = 0u;
                n_dec_ = 0u;
                draw_step(r, true);
                r.event = AdaptEvent::UNFREEZE;
            }
        }
    }
    if (valid) {
        s_prev_ = s_j;
        have_prev_ = true;
    }
    r.kt_next_q16 = kt_;
    r.phase = phase_;
    r.n_small = n_small_;
    r.n_dec = n_dec_;
    r.s_ref = s_ref_;
    r.rng_state = rng_.state();
    if (j_ < std::numeric_limits<std::uint32_t>::max()) {
        ++j_;
    }
    return r;
}

// ------------------------------------------------------------------------------------------------
// Closed loop with adaptation

AdaptiveRun run_adaptive(const RelayModel &model, const RelayLaw &law, const AdaptParams &p,
                         const RelayState &state0, double t_end_s, std::uint32_t win_ticks, const RunOptions &opt)
{
    AdaptiveRun out;
    Adapt adapt(p);
    WindowAcc win;
    win.adapt = &adapt;
    win.win_ticks = std::max<std::uint32_t>(win_ticks, 1u);
    win.out = &out.windows;
    run_tick_typed(model, law, state0, t_end_s, opt, out.run, &win, adapt.kt_q16());
    return out;
}

}  // namespace ref
