// obs_ref — the observer step of fsw/observer in double precision with Eigen (spec 10-observer §5).
//
// Same algorithm, same order, same decisions (validity, vector limit, quantised command, kappa
// clamp, covariance clip), on the dequantised table values, so the fixed-point step and this one
// differ by arithmetic rounding only. Covers the EKF path of a nominal step (both axes valid,
// sequence advancing by one); the fault paths are exercised by the fixed-point unit tests.
#pragma once

#include <Eigen/Dense>
#include <array>
#include <cstdint>

extern "C" {
#include "obs.h"
}

namespace ref {

struct ObsTable {
    Eigen::Matrix<double, 6, 6> phi0, phik;
    Eigen::Matrix<double, 6, 2> gam0, gamk;
    Eigen::Matrix<double, 2, 6> d;
    Eigen::Matrix<double, 7, 1> s;          // scales 2^ls
    Eigen::Matrix<double, 7, 7> q;          // scaled process noise (diagonal)
    double r, p_floor, p_ceil;              // scaled
    double kappa0, kappa_lo, kappa_hi;
    double bdot_max;                        // rad/s
    double gyro_lsb, act_lsb;               // rad/s per count
    int32_t act_max_cnt;
    // Innovation gate and rejection bookkeeping (obs.c update_channel, track_rejections).
    double d2_max = 0.0;                    // gamma^2
    bool d2_reject = false;
    uint32_t n_rej_safe = 1u, rej_leak_inc = 1u, rej_freeze_on = 1u;
};

// Dequantise a C table (integer / 2^q), the values the fixed-point code effectively uses.
ObsTable dequantise(const obs_params_t &p);

struct ObsState {
    Eigen::Matrix<double, 6, 1> x;          // rad/s, rad
    double kappa;                           // K / 0.01 s^-2
    Eigen::Matrix<double, 7, 7> p;          // scaled covariance
    Eigen::Vector2d qres = Eigen::Vector2d::Zero();   // command quantisation residual, rad/s
    std::array<uint32_t, 2> rej_run{{0u, 0u}};        // consecutive gate rejections per channel
    uint32_t rej_level = 0u;                          // leaky rejection level
    bool kappa_frozen = false;
    bool rej_safe = false;                            // latched zero command
};

// The fixed-point state read as real values (for per-step golden comparisons).
ObsState from_fixed(const obs_state_t &s);

struct ObsStepOut {
    std::array<int32_t, 2> cmd_cnt;
    bool limited;
    uint32_t rejected = 0u;                 // bit c: channel c failed the gate this step
    std::array<double, 2> d2{{0.0, 0.0}};   // normalised innovation squared per channel
    // Intermediates of the step, for golden tests that derive their error bounds per step.
    Eigen::Matrix<double, 7, 2> gain;       // scaled Kalman gains L_s, one column per channel
    Eigen::Matrix<double, 7, 7> fs;         // scaled transition matrix of the time update
    Eigen::Matrix<double, 6, 2> gam;        // Gamma(kappa) of the time update
    Eigen::Matrix<double, 7, 7> t;          // F_s P_s of the time update (range analysis)
};

// One nominal EKF step from state st with gyro counts y_cnt: update, command, predict.
// per_axis_clip (analysis only, never flight): clip each command axis to bdot_max instead of
// scaling the vector, to show why the flight code limits the vector (spec 10 S0-9).
ObsStepOut obs_step_ref(const ObsTable &t, ObsState &st, const std::array<int32_t, 2> &y_cnt,
                        bool per_axis_clip = false);

// The state the flight code starts from on its first complete sample (obs.c start_estimate):
// x = (y, 0, 0, 0, 0), kappa = kappa_init, P = P0 (scaled), no quantisation residual.
ObsState initial_state(const obs_params_t &p, const std::array<int32_t, 2> &y_cnt);

}  // namespace ref
