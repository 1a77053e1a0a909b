#include "obs_backend.hpp"

extern "C" {
#include "fsw_codec.h"
#include "obs_tables.h"
}

namespace bridge {

InProcessObsBackend::InProcessObsBackend(const obs_params_t *params)
    : p_((params != nullptr) ? params : &OBS_TBL_50HZ_PHYS)
{
    ok_ = reset();
}

bool InProcessObsBackend::reset()
{
    s_ = obs_state_t{};
    out_ = obs_out_t{};
    steps_ = 0;
    ok_ = (obs_init(&s_, p_, &out_) == FSW_OK);
    return ok_;
}

SensorLimits InProcessObsBackend::sensor_limits(const obs_params_t *params)
{
    const obs_params_t *p = (params != nullptr) ? params : &OBS_TBL_50HZ_PHYS;
    SensorLimits l{};
    l.n_channels = static_cast<std::int16_t>(OBS_NY);
    l.period_us = static_cast<std::int32_t>(p->period_us);
    const std::int32_t m = (p->gyro_max_cnt > 0) ? (p->gyro_max_cnt - 1) : 0;
    for (std::size_t i = 0; i < OBS_NY; ++i) {
        l.ch[i].min = -m;
        l.ch[i].max = m;
    }
    return l;
}

namespace {

// Telemetry layout kObsTlmLayoutVersion (little-endian, fsw codec): health u32,
// bdot_cmd_cnt[2] i32, x_q29[6], kappa_q28, u_q29[2], e_q29[2], d2_q16[2], pkk_q30 (i32),
// health_sticky, n_skip, n_gap, n_lost, n_reinit, n_clamp_lo, n_clamp_hi, n_limited, n_innov,
// n_cov_clip, revision (u32). 128 bytes.
std::int16_t encode_obs_tlm(const obs_out_t &o, std::uint8_t *buf, std::uint32_t len)
{
    fsw_wr_t w;
    fsw_wr_init(&w, buf, len);
    fsw_wr_u32(&w, o.health);
    for (std::size_t i = 0; i < OBS_NU; ++i) { fsw_wr_i32(&w, o.bdot_cmd_cnt[i]); }
    const obs_tlm_t &t = o.tlm;
    for (std::size_t i = 0; i < OBS_NX; ++i) { fsw_wr_i32(&w, t.x_q29[i]); }
    fsw_wr_i32(&w, t.kappa_q28);
    for (std::size_t i = 0; i < OBS_NU; ++i) { fsw_wr_i32(&w, t.u_q29[i]); }
    for (std::size_t i = 0; i < OBS_NY; ++i) { fsw_wr_i32(&w, t.e_q29[i]); }
    for (std::size_t i = 0; i < OBS_NY; ++i) { fsw_wr_i32(&w, t.d2_q16[i]); }
    fsw_wr_i32(&w, t.pkk_q30);
    const std::uint32_t u[] = {t.health_sticky, t.n_skip,     t.n_gap,     t.n_lost,
                               t.n_reinit,      t.n_clamp_lo, t.n_clamp_hi, t.n_limited,
                               t.n_innov,       t.n_cov_clip, t.revision};
    for (std::uint32_t v : u) { fsw_wr_u32(&w, v); }
    return w.err ? static_cast<std::int16_t>(0) : static_cast<std::int16_t>(w.pos);
}

}  // namespace

bool InProcessObsBackend::step(const Frame &f, StepOutput &out)
{
    if (!ok_ || (f.n_counts < static_cast<std::int16_t>(OBS_NY))) {
        return false;
    }
    obs_in_t in{};
    in.seq = static_cast<std::uint32_t>(static_cast<std::uint64_t>(f.seq) & 0xFFFFFFFFu);
    std::uint8_t stale = 0;
    std::uint8_t sat = 0;
    for (std::size_t i = 0; i < OBS_NY; ++i) {
        in.gyro_cnt[i] = f.counts[i];
        const auto bit = static_cast<std::uint8_t>(1u << i);
        if ((f.status[i] & kStatusStale) != 0) { stale = static_cast<std::uint8_t>(stale | bit); }
        if ((f.status[i] & kStatusSat) != 0) { sat = static_cast<std::uint8_t>(sat | bit); }
    }
    in.stale = stale;
    in.sat = sat;
    obs_step(&s_, p_, &in, &out_);
    ++steps_;

    out = StepOutput{};
    out.n_counts = static_cast<std::int16_t>(OBS_NU);
    for (std::size_t i = 0; i < OBS_NU; ++i) { out.counts[i] = out_.bdot_cmd_cnt[i]; }
    out.fsw_mode = 0;
    out.fsw_health = out_.health;
    out.tlm_layout_version = kObsTlmLayoutVersion;
    out.tlm_len = encode_obs_tlm(out_, out.tlm, static_cast<std::uint32_t>(kMaxTlm));
    return true;
}

}  // namespace bridge
