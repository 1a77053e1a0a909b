#include "impulse/cw_sil_plant.hpp"

#include "impulse/impulse_section.hpp"

#include <cmath>

namespace sim {

CwConfig cw_config(const Scenario &scn)
{
    const CwSetup &c = scn.mission_part<CwScenario>().cw;
    CwConfig k;
    k.w = c.omega_radps;
    k.a_nom = c.a_nom_mps2;
    k.eps_c = c.eps_c;
    k.eps = c.eps;
    k.period_us = scn.period_us;
    k.t_min_us = c.t_min_us;
    k.stretch = c.stretch;
    k.stuck_off_j = c.stuck_off_j;
    k.stuck_off_t = c.stuck_off_t_s;
    k.stuck_on_j = c.stuck_on_j;
    k.stuck_on_t = c.stuck_on_t_s;
    const NavSetup &n = c.nav;
    k.nav.profile = (n.profile == "nominal") ? NavProfile::Nominal
                  : (n.profile == "degraded") ? NavProfile::Degraded
                  : (n.profile == "custom") ? NavProfile::Custom : NavProfile::Ideal;
    k.nav.f_nav = n.f_hz;
    k.nav.sigma_p = n.sigma_p_m;
    k.nav.sigma_v = n.sigma_v_mps;
    k.nav.bias_p = n.bias_p_m;
    k.nav.bias_v = n.bias_v_mps;
    k.nav.range_max = n.range_m;
    for (const auto &w : n.dropouts_s) {
        k.nav.dropouts.emplace_back(w[0], w[1]);
    }
    k.nav.p_drop = static_cast<double>(n.dropout_ppm) * 1e-6;
    k.nav.seed = n.seed;
    return k;
}

CwSilPlant::CwSilPlant(const Scenario &scn) { reset(scn); }

const CwSetup &CwSilPlant::setup() const { return scn_.mission_part<CwScenario>().cw; }

void CwSilPlant::reset(const Scenario &scn)
{
    scn_ = scn;
    CwPlant::Vec6 x0;
    for (int i = 0; i < 6; ++i) {
        x0(i) = setup().x0[static_cast<std::size_t>(i)];
    }
    // x0 is given at x0_epoch_s (e.g. the plan epoch t0 of the paper's example); the plant starts
    // at time 0 from the free-drift state that reaches it (no thrust is commanded before t0).
    x0 = CwPlant::phi(-setup().x0_epoch_s, setup().omega_radps) * x0;
    cw_.reset(new CwPlant(cw_config(scn), x0));
    mask_ = 0u;
    start_.fill(0u);
    len_.fill(0u);
    events_.clear();
    reason_.clear();
}

std::int64_t CwSilPlant::utime_us() const
{
    return static_cast<std::int64_t>(cw_->steps()) * static_cast<std::int64_t>(scn_.period_us);
}

SensorFrame CwSilPlant::sense()
{
    SensorFrame f;
    f.utime_us = utime_us();
    f.seq = seq();
    f.period_us = scn_.period_us;
    f.n_ch = kCwSensorChannels;
    const NavSample &s = cw_->nav();
    for (std::size_t i = 0; i < 3u; ++i) {
        f.cnt[i] = s.pos_mm[i];
        f.cnt[3u + i] = s.vel_cnt[i];
    }
    f.cnt[6] = static_cast<std::int32_t>(s.step & 0x7FFFFFFFu);
    for (std::size_t i = 0; i < kCwSensorChannels; ++i) {
        f.status[i] = s.valid ? std::uint8_t{0u} : kStatusStale;
    }
    return f;
}

void CwSilPlant::apply(const ActuatorCmd &cmd)
{
    // A command with too few channels or out-of-range windows is applied as "all off": the plant
    // never interprets a malformed command as a burn.
    bool ok = cmd.n_ch >= kCwActChannels && cmd.cnt[12] >= 0 && cmd.cnt[12] <= 0x3F;
    for (std::size_t j = 0; ok && j < 6u; ++j) {
        ok = cmd.cnt[j] >= 0 && cmd.cnt[6u + j] >= 0 &&
             static_cast<std::uint64_t>(cmd.cnt[j]) + static_cast<std::uint64_t>(cmd.cnt[6u + j]) <= scn_.period_us;
    }
    mask_ = ok ? static_cast<std::uint8_t>(cmd.cnt[12]) : std::uint8_t{0u};
    for (std::size_t j = 0; j < 6u; ++j) {
        start_[j] = ok ? static_cast<std::uint32_t>(cmd.cnt[j]) : 0u;
        len_[j] = ok ? static_cast<std::uint32_t>(cmd.cnt[6u + j]) : 0u;
    }
    if (!ok) {
        TruthEvent e;
        e.utime_us = utime_us();
        e.seq = cmd.seq;
        e.kind = "BAD_THRUSTER_CMD";
        events_.push_back(e);
    }
}

RunState CwSilPlant::propagate()
{
    if (!reason_.empty()) {
        return RunState::Diverged;
    }
    cw_->step(mask_, start_, len_);
    return check();
}

RunState CwSilPlant::check() const
{
    for (int i = 0; i < 6; ++i) {
        if (!std::isfinite(cw_->x()(i))) {
            reason_ = "DIVERGED: non-finite CW state";
            return RunState::Diverged;
        }
    }
    return RunState::Running;
}

std::vector<double> CwSilPlant::truth() const
{
    std::vector<double> t(cw_->x().data(), cw_->x().data() + 6);
    for (double d : cw_->dv_used()) {
        t.push_back(d);
    }
    t.push_back(static_cast<double>(cw_->violations()));
    t.push_back(static_cast<double>(cw_->short_burns()));
    return t;
}

std::vector<std::string> CwSilPlant::truth_names() const
{
    return {"x_m", "xdot_mps", "y_m", "ydot_mps", "z_m", "zdot_mps", "dv_px_mps", "dv_mx_mps", "dv_py_mps",
            "dv_my_mps", "dv_pz_mps", "dv_mz_mps", "interlock_violations", "short_burns"};
}

void CwSilPlant::truth_message(std::array<double, 16> &state, std::array<double, 8> &extra) const
{
    state.fill(0.0);
    extra.fill(0.0);
    const std::vector<double> t = truth();
    for (std::size_t i = 0; i < t.size() && i < 16u; ++i) {
        state[i] = t[i];
    }
    extra[0] = setup().omega_radps;
    extra[1] = setup().a_nom_mps2;
    extra[2] = setup().eps_c;
}

}  // namespace sim
