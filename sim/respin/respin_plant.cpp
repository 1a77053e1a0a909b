#include "respin/respin_plant.hpp"

#include <algorithm>
#include <cmath>

#include "sensors/counts.hpp"

namespace sim {

RespinPlant::RespinPlant(const Scenario &scn) { reset(scn); }

void RespinPlant::reset(const Scenario &scn)
{
    b_ = scn.mission_part<RespinScenario>().body;
    model_ = respin_model(b_);
    period_us_ = scn.period_us;
    k_ = 0u;
    s_ = ref::gyrostat_initial(model_, respin_initial_direction(b_), b_.g0_nms);
    cmd_nm_ = {{0.0, 0.0, 0.0}};
    applied_nm_ = {{0.0, 0.0, 0.0}};
    clip_on_ = {{false, false, false}};
    cut_on_ = {{false, false, false}};
    rate_cmd_ = {{0.0, 0.0, 0.0, 0.0}};
    rate_applied_ = {{0.0, 0.0, 0.0, 0.0}};
    rate_clip_on_ = {{false, false, false, false}};
    max_rate_radps_ = 0.0;
    moment_nm_ = {{0.0, 0.0, 0.0}};
    rotor_fault_us_ = (model_.cmg && b_.rotor_fault) ? static_cast<std::int64_t>(std::llround(b_.rotor_fault_t_s * 1e6)) : -1;
    rotor_fault_done_ = false;
    noise_ = Rng(b_.gyro_seed, 0u);
    events_.clear();
    reason_.clear();
    rotor_fault_due();   // a fault at t_s = 0 is there from the start
}

void RespinPlant::rotor_fault_due()
{
    if (rotor_fault_us_ < 0 || rotor_fault_done_ || utime_us() < rotor_fault_us_) {
        return;
    }
    const std::size_t p = b_.rotor_fault_index;
    ref::gyrostat_set_rotor_scale(model_, s_, p, b_.rotor_fault_scale);
    rotor_fault_done_ = true;
    TruthEvent e;
    e.utime_us = utime_us();
    e.seq = k_;
    e.kind = "ROTOR_FAULT";
    e.channel = static_cast<int>(kRespinChRotor + p);
    e.requested = model_.hg_nms;                              // nominal rotor momentum
    e.applied = b_.rotor_fault_scale * model_.hg_nms;         // from now on
    events_.push_back(e);
}

std::int32_t gimbal_encoder_counts(double beta_rad)
{
    constexpr double kTwoPi = 6.283185307179586476925286766559;
    if (!std::isfinite(beta_rad)) {
        return 0;
    }
    double b = std::fmod(beta_rad, kTwoPi);   // exact; (-2 pi, 2 pi)
    if (b < 0.0) {
        b += kTwoPi;
    }
    std::int64_t c = std::llround(b / kRespinGimbalLsbRad);   // [0, 2^20]
    if (c >= static_cast<std::int64_t>(kRespinGimbalCounts)) {
        c -= static_cast<std::int64_t>(kRespinGimbalCounts);
    }
    return static_cast<std::int32_t>(c);
}

std::int64_t RespinPlant::utime_us() const
{
    return static_cast<std::int64_t>(k_) * static_cast<std::int64_t>(period_us_);
}

SensorFrame RespinPlant::sense()
{
    SensorFrame f;
    f.utime_us = utime_us();
    f.seq = k_;
    f.period_us = period_us_;
    f.n_ch = kRespinSensorChannels;
    const ref::V3 w = omega_radps();
    for (std::size_t i = 0; i < 3u; ++i) {
        // Three draws per period whether or not the noise is on, so the stream never shifts.
        const double n = noise_.gaussian();
        const double meas = (1.0 + b_.gyro_scale_ppm[i] * 1e-6) * w[i] + b_.gyro_bias_radps[i] + b_.gyro_noise_radps * n;
        f.cnt[i] = counts_from_si(meas, kRespinRateLsbRadps, kRespinGyroMaxCnt, &f.status[i]);
    }
    for (std::size_t i = 0; i < 3u; ++i) {
        // No wheels with gyrodines fitted: speed 0, status OK (the channel is always published).
        const double om = model_.cmg ? 0.0 : s_.h_nms[i] / model_.iw_kgm2;
        f.cnt[3u + i] = counts_from_si(om, kRespinWhlSpeedLsbRadps, kRespinWhlSpeedMaxCnt, &f.status[3u + i]);
    }
    for (std::size_t p = 0; p < 4u; ++p) {
        // With wheels s_.beta_rad stays at the null configuration (a locked cluster's encoders).
        f.cnt[kRespinChGimbal + p] = gimbal_encoder_counts(s_.beta_rad[p]);
        f.status[kRespinChGimbal + p] = 0u;
        const double om = model_.cmg ? model_.rotor_scale[p] * b_.cmg_rotor_speed_radps : 0.0;
        f.cnt[kRespinChRotor + p] = counts_from_si(om, kRespinRotorLsbRadps, kRespinRotorMaxCnt, &f.status[kRespinChRotor + p]);
    }
    return f;
}

void RespinPlant::apply(const ActuatorCmd &cmd)
{
    if (model_.cmg) {
        apply_cmg(cmd);
        return;
    }
    for (std::size_t i = 0; i < 3u; ++i) {
        // A command without its channel is applied as zero torque: the plant never guesses.
        const double req = (cmd.n_ch > i) ? static_cast<double>(cmd.cnt[i]) * kRespinTorqueLsbNm : 0.0;
        cmd_nm_[i] = req;
        // The flight's M_max (a Q24 value) rounds to a count up to 1/2 LSB above the motor limit:
        // that is quantisation, not a clip worth an event. Beyond one count it is, logged on entry.
        const bool clip = std::fabs(req) > model_.torque_max_nm + kRespinTorqueLsbNm;
        if (clip && !clip_on_[i]) {
            TruthEvent e;
            e.utime_us = utime_us();
            e.seq = cmd.seq;
            e.kind = "ACT_CLIP";
            e.channel = static_cast<int>(i);
            e.requested = req;
            e.applied = std::copysign(model_.torque_max_nm, req);
            events_.push_back(e);
        }
        clip_on_[i] = clip;
    }
}

void RespinPlant::apply_cmg(const ActuatorCmd &cmd)
{
    for (std::size_t p = 0; p < 4u; ++p) {
        const std::size_t ch = kRespinActGimbalRate + p;
        // A command without its channel holds the gimbal (rate 0).
        const double req = (cmd.n_ch > ch) ? static_cast<double>(cmd.cnt[ch]) * kRespinGimbalRateLsbRadps : 0.0;
        rate_cmd_[p] = req;   // ref::gyrostat_tick_cmg clips to +-u_max
        // The flight's limit 11 437 counts is 0.174515 rad/s, within one count above u_max = 0.1745:
        // quantisation, clipped without an event. Beyond one count it is a clip, logged on entry.
        const bool clip = std::fabs(req) > model_.umax_radps + kRespinGimbalRateLsbRadps;
        if (clip && !rate_clip_on_[p]) {
            TruthEvent e;
            e.utime_us = utime_us();
            e.seq = cmd.seq;
            e.kind = "GIMBAL_RATE_CLIP";
            e.channel = static_cast<int>(ch);
            e.requested = req;
            e.applied = std::copysign(model_.umax_radps, req);
            events_.push_back(e);
        }
        rate_clip_on_[p] = clip;
    }
}

RunState RespinPlant::propagate()
{
    if (!reason_.empty()) {
        return RunState::Diverged;
    }
    if (model_.cmg) {
        const ref::GyrostatTick t =
            ref::gyrostat_tick_cmg(model_, s_, rate_cmd_, static_cast<double>(period_us_) * 1e-6, b_.n_sub);
        rate_applied_ = t.rate_radps;
        moment_nm_ = t.moment_nm;
        for (std::size_t p = 0; p < 4u; ++p) {
            max_rate_radps_ = std::max(max_rate_radps_, std::fabs(t.rate_radps[p]));
        }
        ++k_;
        rotor_fault_due();
        return check();
    }
    const ref::GyrostatTick t =
        ref::gyrostat_tick(model_, s_, cmd_nm_, static_cast<double>(period_us_) * 1e-6, b_.n_sub);
    for (std::size_t i = 0; i < 3u; ++i) {
        applied_nm_[i] = t.hlim_cut[i] ? 0.0 : t.torque_nm[i];
        if (t.hlim_cut[i] && !cut_on_[i]) {   // the wheel at its hard limit: visible in truth only
            TruthEvent e;
            e.utime_us = utime_us();
            e.seq = k_;
            e.kind = "WHL_HLIM";
            e.channel = static_cast<int>(i);
            e.requested = t.torque_nm[i];
            e.applied = 0.0;
            events_.push_back(e);
        }
        cut_on_[i] = t.hlim_cut[i];
    }
    ++k_;
    return check();
}

RunState RespinPlant::check() const
{
    const ref::V3 w = omega_radps();
    const double wn = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    if (!std::isfinite(wn) || wn > b_.omega_max_radps) {
        reason_ = "DIVERGED: |omega| above omega_max_radps or not finite";
        return RunState::Diverged;
    }
    return RunState::Running;
}

std::vector<std::string> RespinPlant::truth_names() const
{
    if (model_.cmg) {
        return {"omega_BN_B_x_radps", "omega_BN_B_y_radps", "omega_BN_B_z_radps", "h_cmg_x_nms", "h_cmg_y_nms",
                "h_cmg_z_nms", "g_B_x_nms", "g_B_y_nms", "g_B_z_nms", "q_BI_w", "q_BI_x", "q_BI_y", "q_BI_z", "t_body_j",
                "e_check_j", "xi_abs", "m_cmg_x_nm", "m_cmg_y_nm", "m_cmg_z_nm", "g0_nms", "q_mode1_sqrtkgm",
                "q_mode2_sqrtkgm", "q_mode3_sqrtkgm", "g_y_rel"};
    }
    return {"omega_BN_B_x_radps", "omega_BN_B_y_radps", "omega_BN_B_z_radps", "h_whl_x_nms", "h_whl_y_nms",
            "h_whl_z_nms", "g_B_x_nms", "g_B_y_nms", "g_B_z_nms", "q_BI_w", "q_BI_x", "q_BI_y", "q_BI_z", "t_body_j",
            "e_check_j", "xi_abs", "tau_whl_x_nm", "tau_whl_y_nm", "tau_whl_z_nm", "g0_nms", "q_mode1_sqrtkgm",
            "q_mode2_sqrtkgm", "q_mode3_sqrtkgm", "g_y_rel"};
}

std::vector<double> RespinPlant::truth() const
{
    std::array<double, 16> st{};
    std::array<double, 8> ex{};
    truth_message(st, ex);
    std::vector<double> t(st.begin(), st.end());
    t.insert(t.end(), ex.begin(), ex.end());
    return t;
}

void RespinPlant::truth_message(std::array<double, 16> &state, std::array<double, 8> &extra) const
{
    state.fill(0.0);
    extra.fill(0.0);
    const ref::V3 w = omega_radps();
    const double gn = std::sqrt(s_.g_nms[0] * s_.g_nms[0] + s_.g_nms[1] * s_.g_nms[1] + s_.g_nms[2] * s_.g_nms[2]);
    for (std::size_t i = 0; i < 3u; ++i) {
        state[i] = w[i];
        state[3u + i] = s_.h_nms[i];
        state[6u + i] = s_.g_nms[i];
        extra[i] = model_.cmg ? moment_nm_[i] : applied_nm_[i];
    }
    for (std::size_t i = 0; i < 4u; ++i) {
        state[9u + i] = s_.q_bi[i];
    }
    state[13] = energy_j();
    state[14] = energy_check_j();
    state[15] = gn > 0.0 ? std::sqrt(s_.g_nms[0] * s_.g_nms[0] + s_.g_nms[2] * s_.g_nms[2]) / gn : 0.0;
    extra[3] = s_.g0_nms;
    for (std::size_t k = 0; k < 3u; ++k) {
        extra[kExtraQm + k] = s_.q_m[k];   // zero for a rigid body
    }
    extra[7] = gn > 0.0 ? s_.g_nms[1] / gn : 0.0;
}

// ------------------------------------------------------------------------------------------------
// Reference closed loop

ref::RespinRefIn respin_ref_input(const SensorFrame &f)
{
    ref::RespinRefIn in;
    in.valid = 0u;
    in.sat = 0u;
    for (std::size_t i = 0; i < kRespinSensorChannels; ++i) {
        const std::uint32_t bit = 1u << i;
        const std::int32_t c = i < f.n_ch ? f.cnt[i] : 0;
        if (i < kRespinChWhlSpeed) {
            in.gyro_cnt[i] = c;
        } else if (i < kRespinChGimbal) {
            in.whl_cnt[i - kRespinChWhlSpeed] = c;
        } else if (i < kRespinChRotor) {
            in.gimbal_cnt[i - kRespinChGimbal] = c;
        } else {
            in.rotor_cnt[i - kRespinChRotor] = c;
        }
        const std::uint8_t st = i < f.n_ch ? f.status[i] : kStatusStale;
        if ((st & (kStatusStale | kStatusNonFinite)) == 0u) {
            in.valid |= bit;
        }
        if ((st & kStatusSat) != 0u) {
            in.sat |= bit;
        }
    }
    return in;
}

RespinLoopRun run_respin_reference(const Scenario &scn, const rsp_params_t &p, const RespinLoopOptions &opt)
{
    RespinLoopRun run;
    RespinPlant plant(scn);
    ref::RespinRef law(ref::dequantise(p));
    const double h_s = scn.h_s();
    const std::uint64_t n = scn.n_steps();
    const std::uint64_t log_every =
        opt.sample_dt_s > 0.0 ? std::max<std::uint64_t>(1u, static_cast<std::uint64_t>(std::llround(opt.sample_dt_s / h_s))) : 0u;
    const ref::V3 gi0 = ref::gyrostat_g_inertial(plant.state());
    const double g0 = plant.state().g0_nms;
    const double t_tail0_s = static_cast<double>(n) * h_s - opt.tail_s;
    bool in_conv = false;
    double conv_since_s = -1.0;
    ref::RespinRefOut out;
    for (std::uint64_t k = 0; k < n; ++k) {
        const SensorFrame f = plant.sense();
        out = law.step(respin_ref_input(f));
        ActuatorCmd cmd;
        cmd.seq = f.seq;
        cmd.n_ch = kRespinActuatorChannels;
        for (std::size_t i = 0; i < 3u; ++i) {
            cmd.cnt[i] = ref::torque_counts(out.whl_torque_nm[i]);
            run.max_torque_cmd_nm = std::max(run.max_torque_cmd_nm, std::fabs(static_cast<double>(cmd.cnt[i]) * kRespinTorqueLsbNm));
        }
        for (std::size_t j = 0; j < 4u; ++j) {
            cmd.cnt[kRespinActGimbalRate + j] = out.gimbal_rate_cnt[j];
        }
        plant.apply(cmd);
        const RunState rs = plant.propagate();
        run.ticks = k + 1u;
        const double t_s = static_cast<double>(k + 1u) * h_s;
        if (out.n_switch != run.n_switch && static_cast<double>(k) * h_s >= t_tail0_s) {
            run.n_switch_tail += out.n_switch - run.n_switch;
        }
        run.n_switch = out.n_switch;
        if (out.done && run.t_done_s < 0.0) {
            run.t_done_s = static_cast<double>(k) * h_s;
        }
        if (rs == RunState::Diverged) {
            run.diverged = true;
            run.reason = plant.diverged_reason();
            break;
        }
        // Truth at t_{k+1}, judged against the f the reference holds after tick k.
        const ref::GyrostatState &s = plant.state();
        const double gn = std::sqrt(s.g_nms[0] * s.g_nms[0] + s.g_nms[1] * s.g_nms[1] + s.g_nms[2] * s.g_nms[2]);
        const double xi = std::sqrt(s.g_nms[0] * s.g_nms[0] + s.g_nms[2] * s.g_nms[2]) / gn;
        const double cphi = static_cast<double>(out.a_f) * s.g_nms[1] / gn;
        const bool conv = xi < opt.conv_xi && cphi > 0.0;
        if (conv && run.t_first_conv_s < 0.0) {
            run.t_first_conv_s = t_s;
        }
        if (conv && !in_conv) {
            conv_since_s = t_s;
        }
        in_conv = conv;
        run.max_g_rel_err = std::max(run.max_g_rel_err, std::fabs(gn - g0) / g0);
        for (std::size_t i = 0; i < 3u; ++i) {
            run.max_h_abs_nms = std::max(run.max_h_abs_nms, std::fabs(s.h_nms[i]));
        }
        const double tj = plant.energy_j();
        run.max_energy_err_j = std::max(run.max_energy_err_j, std::fabs(plant.energy_check_j() - tj));
        run.max_abs_re_j = std::max(run.max_abs_re_j, std::fabs(out.re_j));
        const ref::V3 gi = ref::gyrostat_g_inertial(s);
        const double dgi = std::sqrt((gi[0] - gi0[0]) * (gi[0] - gi0[0]) + (gi[1] - gi0[1]) * (gi[1] - gi0[1]) +
                                     (gi[2] - gi0[2]) * (gi[2] - gi0[2]));
        run.max_gi_dev_rel = std::max(run.max_gi_dev_rel, dgi / g0);
        if (log_every != 0u && (k + 1u) % log_every == 0u) {
            RespinLoopSample smp;
            smp.t_s = t_s;
            smp.xi_abs = xi;
            smp.cphi = cphi;
            smp.t_j = tj;
            smp.h_abs_nms = std::sqrt(s.h_nms[0] * s.h_nms[0] + s.h_nms[1] * s.h_nms[1] + s.h_nms[2] * s.h_nms[2]);
            smp.region = out.region;
            smp.a_f = out.a_f;
            run.log.push_back(smp);
        }
        run.xi_end = xi;
        run.cphi_end = cphi;
        run.t_end_j = tj;
        run.h_end_nms = std::sqrt(s.h_nms[0] * s.h_nms[0] + s.h_nms[1] * s.h_nms[1] + s.h_nms[2] * s.h_nms[2]);
        const ref::V3 w = plant.omega_radps();
        const double wf = static_cast<double>(out.a_f) * g0 / plant.model().j_kgm2[1];
        run.omega_err_end_radps = std::sqrt(w[0] * w[0] + (w[1] - wf) * (w[1] - wf) + w[2] * w[2]);
    }
    run.t_settle_s = in_conv ? conv_since_s : -1.0;
    run.max_gimbal_rate_radps = plant.max_gimbal_rate_radps();
    run.a_f_end = out.a_f;
    run.region_end = out.region;
    run.g0_ref_nms = law.g0_nms();
    return run;
}

}  // namespace sim
