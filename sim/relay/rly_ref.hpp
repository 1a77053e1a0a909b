// rly_ref — double-precision reference of the relay-logic attitude law (spec 20-relay §2–§6).
//
// Self-contained (no fsw header): the plant in modal form with its exact closed-form propagator, the
// law in tick form with the flight's integer semantics (TickLaw, the golden G1 oracle) and in
// continuous form, the three drivers of §2.2 plus the RK4 comparator of §2.3, the envelope (closed form
// and the double model copy of §4), the k_t adaptation on integer window sums (§5, PAPER and
// IMPROVED), and the tick-form closed loop with adaptation used for the S5/S7 campaigns.
//
// Units: SI with the unit in the name; integers carry their format (_q24 = 2^-24 rad, _q16 = Q0.16,
// S_j in 2^-40 rad·tick, _ticks). Levels: -2 FULL_NEG, -1 WEAK_NEG, 0 OFF, +1 WEAK_POS, +2 FULL_POS.
#ifndef SIM_RLY_REF_HPP
#define SIM_RLY_REF_HPP

#include <array>
#include <cstdint>
#include <limits>
#include <vector>

namespace ref {

constexpr int kRelayMaxModes = 4;

// ----------------------------------------------------------------------------------------------
// Plant (§2.1, §2.2)

struct RelayModel {
    double m_u_radps2 = 4e-5, m_eps_radps2 = 1e-6;
    int n_modes = 2;
    std::array<double, kRelayMaxModes> omega_radps{{0.44, 0.755, 0.0, 0.0}};
    std::array<double, kRelayMaxModes> k{{0.0213, 0.0216, 0.0, 0.0}};
};

// Truth: rigid part and modes. Mode entries at index >= n_modes must be zero (x() sums all four).
struct RelayState {
    double xbar_rad = 4.5e-4, xbardot_radps = 2.2e-5;
    std::array<double, kRelayMaxModes> q_rad{{2.75e-6, 0.0, 0.0, 0.0}};      // x~_i
    std::array<double, kRelayMaxModes> qdot_radps{{0.0, 0.0, 0.0, 0.0}};     // x~_i'
    double x() const;                   // measured angle xbar + sum q_i
};

double level_moment(const RelayModel &model, int level);
// Exact closed form of §2.2 over dt_s at a constant level (no integrator).
RelayState propagate(const RelayModel &model, const RelayState &anchor, int level, double dt_s);
// Osculating amplitude of mode i about zero, sqrt(q^2 + (qdot/omega)^2) (§4.1).
double mode_amplitude(const RelayModel &model, const RelayState &s, int i);

// One constant-level stretch of the plant from its anchor: x(dt) and the full state without
// re-deriving c_i, plus the bound on |x''| that makes the crossing scans rigorous.
class Segment {
public:
    Segment(const RelayModel &model, const RelayState &anchor, int level);
    double x_rad(double dt_s) const;
    double xdot_radps(double dt_s) const;
    RelayState state(double dt_s) const;
    // max |x''| over the whole segment: |m| + sum omega_i^2 r_i, r_i the radius about c_i.
    double xddot_max_radps2() const { return xddot_max_; }
    int level() const { return level_; }
    int n_modes() const { return n_; }
    double omega_radps(int i) const { return omega_[idx(i)]; }
    double c_rad(int i) const { return c_[idx(i)]; }
    double y_rad(int i) const { return y_[idx(i)]; }       // q_i - c_i at the anchor
    double p_rad(int i) const { return p_[idx(i)]; }       // qdot_i / omega_i at the anchor

private:
    static std::size_t idx(int i) { return static_cast<std::size_t>(i); }
    RelayState a_;
    int level_;
    int n_;
    double m_;
    std::array<double, kRelayMaxModes> omega_{}, c_{}, y_{}, p_{};
    double xddot_max_;
};

// ----------------------------------------------------------------------------------------------
// Law parameters and integer helpers (§3.5)

struct RelayLaw {
    double eps_rad = 5e-4, gamma_rad = 1e-4;
    double h_s = 1e-3;                       // tick of the tick-form law
    std::uint32_t kt_q16 = 20316;            // k_t in Q0.16 (0.31)
    std::uint32_t tau_max_ticks = 60000;
};

// tau2 = clamp((kt_q16 * tau1 + 2^15) >> 16, 1, tau1) in uint64. tau1 >= 1 whenever the law calls
// it (n is incremented before the exit test); tau1 = 0 would give 1, never 0, so a brake always ends.
std::uint32_t tau2_ticks(std::uint32_t kt_q16, std::uint32_t tau1);
// Round half away from zero to 2^-24 rad counts, saturated at the sensor range +-2^23 (§2.4).
std::int32_t quantise_q24(double x_rad);
std::int32_t q24_from_rad(double v_rad);     // table value, round half away from zero

enum class RlyRefState : std::uint8_t { W_POS, R_MAIN, R_BRAKE, W_NEG, L_MAIN, L_BRAKE };
int state_command(RlyRefState s);            // level commanded while in s (§3.2)
bool is_main(RlyRefState s);
bool is_brake(RlyRefState s);

// ----------------------------------------------------------------------------------------------
// Tick law (§3.2), generic in the sample type: std::int32_t q24 counts is the flight law (G1);
// double is the same machine on the unquantised angle (driver 2 unquantised, RK4 comparator).

struct TickTransition {
    std::uint64_t tick;
    RlyRefState from, to;
};

template <class X>
class TickLawT {
public:
    // eps and gamma in the sample's unit; eps - gamma is formed here, in that arithmetic (integers for
    // q24, so the three thresholds keep their order, §9).
    TickLawT(X eps, X gamma, std::uint32_t kt_q16, std::uint32_t tau_max_ticks, bool log_transitions);

    // One tick with sample x_k: the tests of the state the tick starts in, the chained brake-end ->
    // W tests, then the command of the state after the tick.
    int step(X x);
    // n_ticks ticks on which the current state's test does not fire, in one call (drivers' jump-ahead).
    // Equivalent to n_ticks calls of step() with non-firing samples; in a brake, n_ticks < nb().
    void skip(std::uint64_t n_ticks);
    // Whether step(x) would leave the current state on its level test (W and MAIN states only).
    bool fires(X x) const;

    int command() const { return state_command(s_); }
    RlyRefState state() const { return s_; }
    std::uint32_t n() const { return n_; }
    std::uint32_t nb() const { return nb_; }
    std::uint32_t tau1() const { return tau1_; }     // last main pulse, ticks (tau1 or tau3)
    std::uint32_t tau2() const { return tau2_; }     // last brake, ticks
    std::uint32_t kt_q16() const { return kt_q16_; }
    void set_kt_q16(std::uint32_t kt) { kt_q16_ = kt; }  // read at the next brake start
    std::uint64_t tick() const { return k_; }        // ticks run so far
    std::uint64_t tau_sat_count() const { return tau_sat_; }  // increments of n suppressed at tau_max
    X eps() const { return eps_; }
    X eps_minus_gamma() const { return epg_; }
    const std::vector<TickTransition> &transitions() const { return log_; }

private:
    void enter(RlyRefState to);
    void w_tests(X x);
    void count_main_tick();

    X eps_, epg_;
    std::uint32_t kt_q16_, tau_max_;
    bool log_on_;
    RlyRefState s_ = RlyRefState::W_POS;
    std::uint32_t n_ = 0u, nb_ = 0u, tau1_ = 0u, tau2_ = 0u;
    std::uint64_t k_ = 0u, tau_sat_ = 0u;
    std::vector<TickTransition> log_;
};

using TickLaw = TickLawT<std::int32_t>;     // flight semantics, q24 sample (golden G1)
using TickLawD = TickLawT<double>;          // same machine, double sample in rad

TickLaw make_tick_law(const RelayLaw &law, bool log_transitions = true);
TickLawD make_tick_law_double(const RelayLaw &law, bool log_transitions = false);

// ----------------------------------------------------------------------------------------------
// Drivers (§2.2, §2.3)

struct SwitchEvent {
    double t_s;
    int level;          // level applied from t_s on
};

struct MainPulse {
    int side;                   // +1 right (R_MAIN, x >= eps), -1 left
    double t_entry_s;           // main-pulse start
    double xdot_entry_radps;    // rate at the start
    double tau_main_s;          // tau1 / tau3
    double tau_brake_s;         // tau2 / tau4
};

struct RunOptions {
    double abar_t0_s = 2000.0, abar_t1_s = 20000.0;  // window of the mean envelope
    double env_dt_s = 0.05;            // a(t) samples (20 Hz) for the envelope period
    double scan_h_s = 0.05;            // crossing-scan grid (driver 1; driver 2 in whole ticks)
    double mean_dt_s = 1e-3;           // driver 1 only: grid on which a(t) is averaged
    bool quantise = false;             // driver 2 / adaptive: sample = q24 counts instead of x
    bool jump_ahead = true;            // driver 2 / adaptive: false = every tick evaluated (check)
    int resync = 1024;                 // envelope sweeps: exact re-rotation every this many points
};

// abar: the time-average of a(t) = sum_i a_i over [abar_t0_s, abar_t1_s), taken as the arithmetic
// mean of a on a uniform grid t_k = k*g with k in [round(t0/g), round(t1/g)): g = h for the tick
// drivers (what the flight's window sums compute), g = mean_dt_s for driver 1 (a(t) is continuous
// with bounded slope, so a 1-ms rectangle rule is far below the 4-digit figures compared).
struct RelayRun {
    std::vector<SwitchEvent> switches;
    std::vector<MainPulse> pulses;
    double env_dt_s = 0.05;
    std::vector<double> env_rad;       // a(i * env_dt_s), i = 0, 1, ...
    double abar_rad = 0.0;
    std::uint64_t abar_points = 0u;
    RelayState final_state;
    std::uint64_t grazes = 0u;         // driver 1: crossings the plain grid scan would have missed
    std::uint64_t tau_sat = 0u;        // tick drivers: TickLaw::tau_sat_count()
    std::uint64_t x_evaluations = 0u;  // closed-form x evaluations (cost of the scans)
};

// Driver 1: event-driven, continuous law, k_t = kt_q16 / 2^16 (or kt_override if >= 0).
RelayRun run_continuous(const RelayModel &model, const RelayLaw &law, const RelayState &state0,
                        double t_end_s, const RunOptions &opt = {}, double kt_override = -1.0);
// Driver 2: tick-sampled law (TickLaw semantics at law.h_s), exact plant, jump-ahead to the ticks
// where a test can fire; runs floor(t_end_s / h + 0.5) ticks.
RelayRun run_tick_sampled(const RelayModel &model, const RelayLaw &law, const RelayState &state0,
                          double t_end_s, const RunOptions &opt = {});
// Fixed-step RK4 at h_s on the 2 + 2n state, TickLawD evaluated once per step on the RK4 x.
RelayRun run_rk4(const RelayModel &model, const RelayLaw &law, const RelayState &state0, double t_end_s,
                 double h_s = 1e-4, const RunOptions &opt = {});

// Envelope period: the first local maximum, within 10 % of the largest, of the autocorrelation of
// a - mean(a) over lags [lag_min_s, lag_max_s], from the 20-Hz samples at t >= t_from_s.
double envelope_period_s(const RelayRun &run, double t_from_s, double lag_min_s = 5.0,
                         double lag_max_s = 100.0);

// ----------------------------------------------------------------------------------------------
// Envelope model copy (§4) in double

// The copy of the modes driven by the level applied over each tick: anchored exact rotation (§4.2),
// (q_i - c_i(l), p_i) rotated by omega_i * n * h from the last level change. Between exact
// re-rotations every resync_ticks ticks it advances by the one-tick rotation; the relative error this
// adds is <= resync_ticks * 1e-16, invisible next to the 2^-40-rad LSB (a ~ 2^-15.6 rad).
class EnvelopeCopy {
public:
    EnvelopeCopy(const RelayModel &model, double h_s, const RelayState &initial, int level0,
                 int resync_ticks = 1024);
    double a_rad() const;                        // at the current tick
    double a_i_rad(int i) const;
    double q_rad(int i) const { return c_[idx(i)] + y_[idx(i)]; }
    double p_rad(int i) const { return p_[idx(i)]; }
    // The level applied over the current tick: re-anchor if it changed, then move to the next tick.
    void advance(int level);

private:
    static std::size_t idx(int i) { return static_cast<std::size_t>(i); }
    void set_c(int level);
    RelayModel model_;
    double h_;
    int resync_;
    int level_;
    std::uint64_t n_ = 0u;                       // ticks since the anchor
    std::array<double, kRelayMaxModes> c_{}, u_{}, v_{}, y_{}, p_{}, cs_{}, sn_{};
};

// ----------------------------------------------------------------------------------------------
// Adaptation (§5) on integer window sums

// IMPROVED_UP: IMPROVED with the cliff trigger armed only after an upward step, and the escape: a
// window sum above escape_s steps up and blocks the settled trigger (fsw/relay README).
enum class AdaptMode : std::uint8_t { OFF, PAPER, IMPROVED, IMPROVED_UP };
enum class AdaptPhase : std::uint8_t { SEARCH, PROBE, FROZEN };
enum class AdaptEvent : std::uint8_t { NONE, STEP, PROBE_START, FREEZE_SETTLED, FREEZE_CLIFF, UNFREEZE,
                                       SKIPPED };

struct AdaptParams {
    AdaptMode mode = AdaptMode::IMPROVED;
    std::uint32_t tmin_windows = 20;
    std::uint32_t dk_q16 = 131;
    std::uint32_t kt0_q16 = 20316, kt_min_q16 = 18350, kt_max_q16 = 26214;
    std::uint32_t delta0_num = 1, delta0_den = 20;
    std::uint32_t n_small = 6, n_ignore = 4;
    bool count_before_tmin = true, learn_after_tmin = true;
    std::uint32_t seed = 1;
    // IMPROVED only
    std::uint32_t gate_dk = 2, probe_settle = 1;
    std::uint32_t cliff_num = 3, cliff_den = 2;
    std::uint32_t retreat_dk = 2;
    std::uint32_t unfreeze_num = 3, unfreeze_den = 2, unfreeze_windows = 3;
    // IMPROVED_UP only: env_alarm · win_ticks in S's units (the flight table's ENV_HIGH level)
    std::uint64_t escape_s = std::numeric_limits<std::uint64_t>::max();
};

class Xorshift32 {
public:
    explicit Xorshift32(std::uint32_t seed);     // nonzero; discards the first 16 outputs
    std::uint32_t next();
    std::uint32_t state() const { return s_; }

private:
    std::uint32_t s_;
};
std::vector<std::uint32_t> xorshift32_stream(std::uint32_t seed, int n);   // after the warm-up (G6)

struct WindowResult {
    std::uint32_t j = 0;                 // window index (skipped windows included)
    std::uint64_t s = 0;                 // S_j as given
    std::uint32_t kt_in_force_q16 = 0;   // k_t,j
    std::uint32_t kt_next_q16 = 0;       // k_t,j+1
    AdaptPhase phase = AdaptPhase::SEARCH;   // after this window's decision
    AdaptEvent event = AdaptEvent::NONE;
    int sign = 0;                        // sign applied to the step (0: no draw this window)
    std::uint32_t mag_q16 = 0;           // magnitude drawn, [1, 65536] (0: no draw)
    std::uint32_t step_q16 = 0;          // (mag * dk + 2^15) >> 16
    bool kt_clamped = false;
    std::uint32_t n_small = 0, n_dec = 0;
    std::uint64_t s_ref = 0;
    std::uint32_t rng_state = 0;         // after this window's draw
};

class Adapt {
public:
    explicit Adapt(const AdaptParams &p);
    WindowResult window_end(std::uint64_t s_j, bool valid);
    std::uint32_t kt_q16() const { return kt_; }
    AdaptPhase phase() const { return phase_; }
    std::uint32_t rng_state() const { return rng_.state(); }
    std::uint32_t windows() const { return j_; }
    std::uint64_t kt_clamped_count() const { return clamped_; }

private:
    std::uint32_t clamp_kt(std::int64_t kt, bool *clamped);
    void draw_step(WindowResult &r, bool random_sign);
    void freeze(std::uint32_t kt_f);

    AdaptParams p_;
    Xorshift32 rng_;
    std::uint32_t kt_;
    AdaptPhase phase_ = AdaptPhase::SEARCH;
    std::uint32_t j_ = 0;                // index of the next window
    bool have_prev_ = false;             // S_{j-1} exists (first valid window draws as at j = 0)
    std::uint64_t s_prev_ = 0;
    std::uint32_t n_small_ = 0, n_dec_ = 0;
    int sign_ = 1;                       // sign of the last r
    std::array<std::uint32_t, 64> kt_hist_{};   // k_t in force per window, ring by j
    // PROBE
    std::array<std::uint32_t, 3> probe_kt_{};
    std::array<std::uint64_t, 3> probe_s_{};
    std::uint32_t probe_idx_ = 0, probe_win_ = 0;
    // FROZEN
    std::uint32_t frozen_age_ = 0, above_ref_ = 0;
    std::uint64_t s_ref_ = 0;
    std::uint64_t clamped_ = 0;
};

// ----------------------------------------------------------------------------------------------
// Tick-form closed loop with adaptation (campaigns S5/S7 in double)

struct WindowRecord {
    std::uint64_t s;             // S_j, 2^-40 rad·tick
    double abar_rad;             // S_j * 2^-40 / win_ticks
    WindowResult adapt;
};

struct AdaptiveRun {
    RelayRun run;                // switches, pulses, 20-Hz envelope; abar over opt's window
    std::vector<WindowRecord> windows;
};

// The tick law at law.h_s (k_t from the adaptation, starting at p.kt0_q16; law.kt_q16 is unused), the
// exact plant, the double model copy of the modes summed per window: per tick and mode
// a_i is rounded to the nearest 2^-40 rad (half away from zero) and S_j is the uint64 sum over the
// win_ticks ticks of window j. Order of work per tick as §4.2: a_k into S, window end -> adaptation
// (new k_t read at the next brake start), then the law. In double the copy driven by the applied level
// equals the plant's own modes, so the plant's segments serve as the copy.
AdaptiveRun run_adaptive(const RelayModel &model, const RelayLaw &law, const AdaptParams &p,
                         const RelayState &state0, double t_end_s, std::uint32_t win_ticks,
                         const RunOptions &opt = {});

// ----------------------------------------------------------------------------------------------
// TickLawT implementation

template <class X>
TickLawT<X>::TickLawT(X eps, X gamma, std::uint32_t kt_q16, std::uint32_t tau_max_ticks,
                      bool log_transitions)
    : eps_(eps), epg_(eps - gamma), kt_q16_(kt_q16), tau_max_(tau_max_ticks), log_on_(log_transitions)
{
}

template <class X>
void TickLawT<X>::enter(RlyRefState to)
{
    if (log_on_) {
        log_.push_back(TickTransition{k_, s_, to});
    }
    s_ = to;
}

template <class X>
void TickLawT<X>::w_tests(X x)
{
    if (x >= eps_) {
        enter(RlyRefState::R_MAIN);
        n_ = 0u;
    } else if (x <= -eps_) {
        enter(RlyRefState::L_MAIN);
        n_ = 0u;
    }
}

template <class X>
void TickLawT<X>::count_main_tick()
{
    if (n_ < tau_max_) {
        ++n_;
    } else {
        ++tau_sat_;
    }
}

template <class X>
bool TickLawT<X>::fires(X x) const
{
    switch (s_) {
    case RlyRefState::W_POS:
    case RlyRefState::W_NEG: return x >= eps_ || x <= -eps_;
    case RlyRefState::R_MAIN: return x <= epg_;
    case RlyRefState::L_MAIN: return x >= -epg_;
    case RlyRefState::R_BRAKE:
    case RlyRefState::L_BRAKE: break;
    }
    return false;
}

template <class X>
int TickLawT<X>::step(X x)
{
    switch (s_) {
    case RlyRefState::W_POS:
    case RlyRefState::W_NEG: w_tests(x); break;
    case RlyRefState::R_MAIN:
    case RlyRefState::L_MAIN: {
        count_main_tick();
        const bool right = s_ == RlyRefState::R_MAIN;
        if (right ? x <= epg_ : x >= -epg_) {
            tau1_ = n_;
            tau2_ = tau2_ticks(kt_q16_, tau1_);
            nb_ = tau2_;
            enter(right ? RlyRefState::R_BRAKE : RlyRefState::L_BRAKE);
        }
        break;
    }
    case RlyRefState::R_BRAKE:
    case RlyRefState::L_BRAKE:
        --nb_;
        if (nb_ == 0u) {
            enter(s_ == RlyRefState::R_BRAKE ? RlyRefState::W_POS : RlyRefState::W_NEG);
            w_tests(x);
        }
        break;
    }
    ++k_;
    return command();
}

template <class X>
void TickLawT<X>::skip(std::uint64_t n_ticks)
{
    if (is_main(s_)) {
        const std::uint64_t room = tau_max_ - n_;
        if (n_ticks > room) {
            tau_sat_ += n_ticks - room;
            n_ = tau_max_;
        } else {
            n_ += static_cast<std::uint32_t>(n_ticks);
        }
    } else if (is_brake(s_)) {
        nb_ -= static_cast<std::uint32_t>(n_ticks);   // caller keeps n_ticks < nb
    }
    k_ += n_ticks;
}

}  // namespace ref

#endif
