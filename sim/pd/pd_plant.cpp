#include "pd/pd_plant.hpp"

#include <cmath>
#include <cstdint>

#include "sensors/counts.hpp"

namespace sim {

namespace {

constexpr double kPi = 3.141592653589793238462643383279;

std::int64_t us_of(double t_s) { return static_cast<std::int64_t>(std::llround(t_s * 1e6)); }

// Sample time t_us inside the window [t0_s, t1_s) on channel c.
bool in_window(const PdWindow &w, std::uint32_t c, std::int64_t t_us)
{
    return w.channel == c && t_us >= us_of(w.t0_s) && t_us < us_of(w.t1_s);
}

}  // namespace

std::array<ref::pd::Channel, 3> pd_channels(const PdSetup &b, double Ty)
{
    ref::pd::Scales sc;
    sc.coupling = b.scale_coupling;
    sc.ix = b.scale_ix;
    sc.h = b.scale_h;
    return ref::pd::three_channels(sc, Ty);
}

PdPlant::PdPlant(const Scenario &scn) { reset(scn); }

void PdPlant::reset(const Scenario &scn)
{
    b_ = scn.mission_part<PdScenario>().body;
    period_us_ = scn.period_us;
    k_ = 0u;
    ch_ = pd_channels(b_, scn.h_s());
    L_ = ref::pd::layout(ch_);
    f_hz_ = b_.f_hz;
    recompute();
    s_ = Eigen::VectorXd::Zero(2 * L_.n_dof);
    u_ = Eigen::VectorXd::Zero(3);
    for (int c = 0; c < 3; ++c) {
        s_(ref::pd::Layout::x(c)) = b_.x0_rad[static_cast<std::size_t>(c)];
    }
    cmd_nm_ = {{0.0, 0.0, 0.0}};
    delayed_nm_ = {{0.0, 0.0, 0.0}};
    applied_nm_ = {{0.0, 0.0, 0.0}};
    clip_on_ = {{false, false, false}};
    next_step_ = 0u;
    next_kick_ = 0u;
    // One independent stream per attitude channel (stream id = channel): changing one channel's
    // sigma, or adding a channel, never shifts another channel's noise.
    for (std::size_t c = 0; c < 3u; ++c) {
        noise_[c] = Rng(b_.sensor_seed, c);
    }
    last_cnt_ = {{0, 0, 0}};
    last_status_ = {{0u, 0u, 0u}};
    have_last_ = {{false, false, false}};
    events_.clear();
    reason_.clear();
    boundary_events();   // a step or kick at t_s = 0 is there from the start
}

void PdPlant::recompute()
{
    d_ = (b_.kind == PdPlantKind::Coupled) ? ref::pd::discretise_coupled(ch_, f_hz_, b_.coupling_sign, 1e-6 * period_us_)
                                           : ref::pd::discretise_single(ch_, f_hz_, 1e-6 * period_us_);
}

void PdPlant::boundary_events()
{
    const std::int64_t t = utime_us();
    const double f_old = f_hz_;
    while (next_step_ < b_.f_steps.size() && t >= us_of(b_.f_steps[next_step_].t_s)) {
        f_hz_ = b_.f_steps[next_step_].f_hz;
        ++next_step_;
    }
    if (std::fabs(f_hz_ - f_old) > 0.0) {
        recompute();   // only the model changes: the state carries over (continuous)
        TruthEvent e;
        e.utime_us = t;
        e.seq = k_;
        e.kind = "F_STEP";
        e.channel = -1;
        e.requested = f_old;
        e.applied = f_hz_;
        events_.push_back(e);
    }
    while (next_kick_ < b_.kicks.size() && t >= us_of(b_.kicks[next_kick_].t_s)) {
        for (int c = 0; c < 3; ++c) {
            const double dx = b_.kicks[next_kick_].dx_rad[static_cast<std::size_t>(c)];
            if (!(std::fabs(dx) > 0.0)) {
                continue;
            }
            s_(ref::pd::Layout::x(c)) += dx;
            TruthEvent e;
            e.utime_us = t;
            e.seq = k_;
            e.kind = "KICK";
            e.channel = c;
            e.requested = dx;
            e.applied = dx;
            events_.push_back(e);
        }
        ++next_kick_;
    }
}

std::int64_t PdPlant::utime_us() const
{
    return static_cast<std::int64_t>(k_) * static_cast<std::int64_t>(period_us_);
}

SensorFrame PdPlant::sense()
{
    SensorFrame f;
    f.utime_us = utime_us();
    f.seq = k_;
    f.period_us = period_us_;
    f.n_ch = kPdSensorChannels;
    for (std::uint32_t c = 0u; c < 3u; ++c) {
        const std::size_t i = c;
        // The draw comes first and always, so the stream never depends on sigma or on a window.
        const double n = noise_[i].gaussian();
        double meas = s_(ref::pd::Layout::x(static_cast<int>(c))) + b_.bias_rad[i] + b_.noise_rad[i] * n;
        for (const PdWindow &w : b_.offset) {
            if (in_window(w, c, f.utime_us)) {
                meas += w.rad;
            }
        }
        std::uint8_t st = 0u;
        std::int32_t cnt = counts_from_si(meas, kPdAttLsbRad, kPdAttMaxCnt, &st);
        bool frozen = false;
        for (const PdWindow &w : b_.frozen) {
            frozen = frozen || in_window(w, c, f.utime_us);
        }
        if (frozen && have_last_[i]) {   // a stuck sensor: the last output, bit for bit
            cnt = last_cnt_[i];
            st = last_status_[i];
        }
        last_cnt_[i] = cnt;
        last_status_[i] = st;
        have_last_[i] = true;
        f.cnt[kPdChAtt + c] = cnt;
        f.status[kPdChAtt + c] = st;
    }
    for (std::uint32_t c = 0u; c < 3u; ++c) {
        const double beta = s_(ref::pd::Layout::beta(static_cast<int>(c)));
        f.cnt[kPdChEnc + c] = counts_from_si(beta, kPdEncLsbRad, kPdEncMaxCnt, &f.status[kPdChEnc + c]);
    }
    return f;
}

void PdPlant::apply(const ActuatorCmd &cmd)
{
    for (std::size_t c = 0; c < 3u; ++c) {
        // A command without its channel is applied as zero torque: the plant never guesses.
        const double req = (cmd.n_ch > c) ? static_cast<double>(cmd.cnt[c]) * kPdTorqueLsbNm : 0.0;
        const bool clip = std::fabs(req) > b_.act_max_nm;
        cmd_nm_[c] = clip ? std::copysign(b_.act_max_nm, req) : req;
        if (clip && !clip_on_[c]) {   // clipped by the hardware: visible in truth only
            TruthEvent e;
            e.utime_us = utime_us();
            e.seq = cmd.seq;
            e.kind = "ACT_CLIP";
            e.channel = static_cast<int>(c);
            e.requested = req;
            e.applied = cmd_nm_[c];
            events_.push_back(e);
        }
        clip_on_[c] = clip;
    }
}

RunState PdPlant::propagate()
{
    if (!reason_.empty()) {
        return RunState::Diverged;
    }
    // With one sample of latency the command received at t_k acts over [t_k+1, t_k+2).
    applied_nm_ = (b_.latency_samples != 0u) ? delayed_nm_ : cmd_nm_;
    delayed_nm_ = cmd_nm_;
    for (std::size_t c = 0; c < 3u; ++c) {
        u_(static_cast<Eigen::Index>(c)) = applied_nm_[c];
    }
    s_ = d_.Ad * s_ + d_.Bd * u_;   // exact ZOH over [t_k, t_k+1)
    ++k_;
    boundary_events();
    return check();
}

RunState PdPlant::check() const
{
    if (!s_.allFinite()) {
        reason_ = "DIVERGED: state not finite";
        return RunState::Diverged;
    }
    static const char *const kName[3] = {"yaw", "roll", "pitch"};
    for (int c = 0; c < 3; ++c) {
        if (std::fabs(s_(ref::pd::Layout::x(c))) > 1.0) {
            reason_ = std::string("DIVERGED: |x| above 1 rad (") + kName[c] + ")";
            return RunState::Diverged;
        }
        if (std::fabs(s_(ref::pd::Layout::beta(c))) > kPi) {
            reason_ = std::string("DIVERGED: |beta| above pi rad (") + kName[c] + ")";
            return RunState::Diverged;
        }
    }
    return RunState::Running;
}

std::vector<std::string> PdPlant::truth_names() const
{
    return {"x_yaw_rad",          "x_roll_rad",          "x_pitch_rad",        "beta_yaw_rad",       "beta_roll_rad",
            "beta_pitch_rad",     "q_yaw1_rad",          "q_yaw2_rad",         "q_roll_rad",         "q_pitch_rad",
            "xdot_yaw_radps",     "xdot_roll_radps",     "xdot_pitch_radps",   "linear_validity",    "f_min_hz",
            "plant_coupling",     "m_yaw_nm",            "m_roll_nm",          "m_pitch_nm",         "betadot_yaw_radps",
            "betadot_roll_radps", "betadot_pitch_radps", "latency_samples",    "spare"};
}

std::vector<double> PdPlant::truth() const
{
    std::array<double, 16> st{};
    std::array<double, 8> ex{};
    truth_message(st, ex);
    std::vector<double> t(st.begin(), st.end());
    t.insert(t.end(), ex.begin(), ex.end());
    return t;
}

void PdPlant::truth_message(std::array<double, 16> &state, std::array<double, 8> &extra) const
{
    state.fill(0.0);
    extra.fill(0.0);
    const Eigen::Index nd = L_.n_dof;
    bool valid = true;
    for (int c = 0; c < 3; ++c) {
        const std::size_t i = static_cast<std::size_t>(c);
        const double beta = s_(ref::pd::Layout::beta(c));
        state[kTruthX + i] = s_(ref::pd::Layout::x(c));
        state[kTruthBeta + i] = beta;
        state[kTruthXdot + i] = s_(nd + ref::pd::Layout::x(c));
        extra[kExtraTorque + i] = applied_nm_[i];
        extra[kExtraBetadot + i] = s_(nd + ref::pd::Layout::beta(c));
        valid = valid && std::fabs(beta) <= 0.5;   // the linear model is strained beyond (§2.6)
    }
    for (int m = 0; m < L_.n_modes() && m < 4; ++m) {
        state[kTruthQ + static_cast<std::size_t>(m)] = s_(2 * ref::pd::kChannels + m);
    }
    state[kTruthLinValid] = valid ? 1.0 : 0.0;
    state[kTruthFHz] = f_hz_;
    state[kTruthPlant] = (b_.kind == PdPlantKind::Coupled) ? static_cast<double>(b_.coupling_sign) : 0.0;
    extra[kExtraLatency] = static_cast<double>(b_.latency_samples);
}

}  // namespace sim
