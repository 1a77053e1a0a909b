// rsp_ref.hpp — the RESPIN law of spec 30 in double precision: the reference the fixed-point flight
// code (fsw/respin) is proven against, and the rigid-gyrostat wheel plant both the SIL plant
// (respin_plant) and the reference closed loop integrate.
//
// It reads the flight table rsp_params_t, dequantised to SI (dequantise), and the same integer
// counts the flight code sees (RespinRefIn: gyro 2^-22 rad/s, wheel speed 2^-10 rad/s), and runs the
// same state machine (spec 30 §3.5-§3.7): g0 averaged over n_g0 valid ticks with zero command,
// low-momentum rule, small-|G| guard, regions LIN / MID / FAR with hysteresis, NEAREST re-selection
// and latch of a_f or the PRINTED fixed a_f, the law of §3.2, the wheel distribution of §4 (per-axis
// clip, momentum-bound clamp, final clip), the energy bookkeeping T, W, r_E of §8 and the done flag.
// Simplified input handling (the golden vectors judge the law, not the validation): an invalid or
// saturated gyro word commands zero and keeps the state; a missing wheel speed is propagated for
// n_wheel_est ticks from the last command as in §8, beyond that the tick is invalid; the |G| outlier
// gate of §8 applies; staleness (frozen words) and G_DRIFT are not modelled.
//
// Sign chain (spec 30 §9): M is the internal moment on the body, M = -dH/dt; the wheel motor torque
// command is -M. Units are SI with the unit in the name; "Sgn 0 = +1" everywhere.
#ifndef SIM_RSP_REF_HPP
#define SIM_RSP_REF_HPP

#include <array>
#include <cstdint>
#include <string>
#include <vector>

extern "C" {
#include "rsp.h"
}

namespace ref {

using V3 = std::array<double, 3>;

// Channel LSBs (fsw/respin/rsp_iface.py) and the command's code range.
constexpr double kRspGyroLsbRadps = 1.0 / 4194304.0;     // sensors 0..2: 2^-22 rad/s
constexpr double kRspWhlLsbRadps = 1.0 / 1024.0;         // sensors 3..5: 2^-10 rad/s
constexpr double kRspTorqueLsbNm = 1.0 / 131072.0;       // actuators 0..2: 2^-17 N m
constexpr std::int32_t kRspGyroMaxCnt = 4194304;         // +-2^22 counts = +-1 rad/s, full scale = SAT
constexpr std::int32_t kRspWhlMaxCnt = 614400;           // +-600 rad/s
constexpr std::int32_t kRspTorqueMaxCnt = 32767;         // int16 code range (+-0.25 N m)

// The flight table in SI (exact dequantisation: every field is an integer times a power of two).
struct RespinTable {
    std::uint32_t period_us = 100000u;
    double ts_s = 0.1;
    std::uint32_t mode = RSP_MODE_NEAREST;
    std::uint32_t act_kind = RSP_ACT_WHEELS;
    V3 j_kgm2{{0.0, 0.0, 0.0}};
    double iw_kgm2 = 0.0;
    double eps1 = 0.0, eps2 = 0.0, heps = 0.0;
    double m_nm = 0.0;            // law gain m
    double k_pnms = 0.0;          // k, 1/(N m s)
    double mstar_nm = 0.0;        // far-law moment M*
    double mmax_nm = 0.0;         // per-axis motor limit M_max
    double hlim_nms = 0.0;        // momentum-bound clamp h_lim
    double inv_ts_hz = 0.0;       // 1/Ts as the table states it (the clamp multiplies by it)
    double gguard_nms = 0.0, gmin_nms = 0.0;
    std::uint32_t n_g0 = 0u;
    std::int32_t gyro_max_cnt = 0, whl_max_cnt = 0;
    std::uint32_t n_fault = 0u, n_stale = 0u, n_whl_est = 0u;
    double outlier_nms = 0.0, outlier_rel = 0.0;
    double drift = 0.0;
    std::uint32_t drift_sh = 0u;
    double ealarm_j = 0.0;
    double done_xi = 0.0, done_h_nms = 0.0;
    std::uint32_t done_ticks = 0u;
    double gfilt_alpha = 0.0;     // G filter blend per tick (0: off)
    double hg_nms = 0.0;          // gyrodine rotor momentum
    double sr_lambda = 0.0;       // singularity-robust damping lambda0
    std::int32_t umax_cnt = 0;    // gimbal-rate limit, counts of 2^-16 rad/s
    double ms_sing = 0.0;         // SINGULAR threshold on m_s
    std::int32_t rotor_nom_cnt = 0;   // nominal rotor speed, counts of 2^-8 rad/s
    double rotor_tol = 0.0;       // ROTOR_FAULT tolerance (relative)
};

RespinTable dequantise(const rsp_params_t &p);

// ------------------------------------------------------------------------------------------------
// The law, one tick (spec 30 §3.1-§3.5, §4), pure: state in, state out. Usable for single-tick
// golden cases: g = G r0 (not renormalised), h_nms the wheel momentum used.

struct RespinLawState {
    bool started = false;          // false: the next tick is the first law tick (plain thresholds, a_f = Sgn g_y)
    std::uint32_t region = RSP_RG_FAR;
    std::int32_t a_f = 1;
    bool latched = false;
    bool guard = false;            // g0 < g_guard: FAR not allowed (set when g0 freezes)
};

struct RespinLawOut {
    RespinLawState next;           // the state after the tick
    bool switched = false;         // region changed this tick (not counted on the first tick)
    V3 g{{0.0, 0.0, 0.0}};
    V3 xi{{0.0, 0.0, 0.0}};        // g x f, f = a_f e_y (a_f after the tick's re-selection)
    double xi_abs = 0.0;           // |xi| = sqrt(g_x^2 + g_z^2)
    double cphi = 0.0;             // C_phi = a_f g_y
    V3 e_xi{{0.0, 0.0, 0.0}};      // xi / |xi| where region != LIN, else 0
    V3 mcmd_nm{{0.0, 0.0, 0.0}};   // law moment on the body (before distribution)
    V3 mdel_nm{{0.0, 0.0, 0.0}};   // after per-axis clip, momentum-bound clamp and final clip
    V3 whl_torque_nm{{0.0, 0.0, 0.0}};  // wheel motor torque command = -mdel
    std::array<bool, 3> clip{{false, false, false}};    // |mcmd_i| > M_max
    std::array<bool, 3> hbound{{false, false, false}};  // the momentum-bound clamp changed axis i
};

RespinLawOut rsp_law_tick(const RespinTable &t, const RespinLawState &s, const V3 &g, const V3 &h_nms);

// The wheel distribution of §4 alone (per-axis clip to M_max, clamp to [(H - h_lim)/Ts,
// (H + h_lim)/Ts], final clip); flags per axis.
V3 rsp_distribute(const RespinTable &t, const V3 &mcmd_nm, const V3 &h_nms, std::array<bool, 3> *clip,
                  std::array<bool, 3> *hbound);

// ------------------------------------------------------------------------------------------------
// The module: RespinRef, the double twin of rsp_init / rsp_step.

struct RespinRefIn {
    std::array<std::int32_t, 3> gyro_cnt{{0, 0, 0}};   // 2^-22 rad/s
    std::array<std::int32_t, 3> whl_cnt{{0, 0, 0}};    // 2^-10 rad/s
    std::array<std::int32_t, 4> gimbal_cnt{{0, 0, 0, 0}};   // 2 pi / 2^20 rad (gyrodines)
    std::array<std::int32_t, 4> rotor_cnt{{0, 0, 0, 0}};    // 2^-8 rad/s (gyrodines, health)
    std::uint32_t valid = 0x3FFFu;                     // bits 0..2 gyro, 3..5 wheel, 6..9 gimbal, 10..13 rotor
    std::uint32_t sat = 0u;                            // same bits: at full scale
};

struct RespinRefOut {
    std::uint32_t phase = RSP_PH_G0;       // RSP_PH_G0, RSP_PH_LOW, RSP_PH_RUN
    std::uint32_t region = RSP_RG_FAR;
    std::int32_t a_f = 1;
    bool latched = false;
    bool guard = false;
    bool valid = false;                    // this tick's inputs were accepted
    bool done = false;                     // RESPIN_DONE (§3.7)
    std::uint32_t health = 0u;             // RSP_H_* bits this tick (the reference's subset)
    V3 g{{0.0, 0.0, 0.0}};
    double xi_abs = 0.0, cphi = 0.0;
    V3 e_xi{{0.0, 0.0, 0.0}};
    V3 mcmd_nm{{0.0, 0.0, 0.0}};
    V3 mdel_nm{{0.0, 0.0, 0.0}};
    V3 whl_torque_nm{{0.0, 0.0, 0.0}};     // = -mdel (zero on G0 / LOW / invalid ticks; zero with gyrodines)
    std::array<std::int32_t, 4> gimbal_rate_cnt{{0, 0, 0, 0}};   // gyrodines: rate command counts (2^-16 rad/s)
    double ms = 0.0, s_rate = 0.0;         // gyrodines: m_s and the rate scale s of the tick
    V3 h_nms{{0.0, 0.0, 0.0}};             // wheel momentum used
    double g0_nms = 0.0;                   // 0 until frozen
    double rho = 0.0;                      // |G| r0 - 1
    double t_j = 0.0, w_j = 0.0, re_j = 0.0;
    std::uint32_t done_run = 0u;
    std::uint32_t n_switch = 0u;
};

class RespinRef {
public:
    RespinRef() = default;
    explicit RespinRef(const RespinTable &t) { reset(t); }
    void reset(const RespinTable &t);
    RespinRefOut step(const RespinRefIn &in);

    const RespinTable &table() const { return t_; }
    const RespinLawState &law_state() const { return law_; }
    double g0_nms() const { return g0_nms_; }
    std::uint32_t n_switch() const { return n_switch_; }
    std::uint64_t n_invalid() const { return n_invalid_; }

private:
    RespinTable t_;
    std::uint32_t phase_ = RSP_PH_G0;
    RespinLawState law_;
    std::uint32_t n_acc_ = 0u;
    double g0_sum_nms_ = 0.0, g0_nms_ = 0.0, r0_pnms_ = 0.0;
    bool have_prev_ = false, have_t0_ = false;
    V3 omega_prev_radps_{{0.0, 0.0, 0.0}}, h_prev_nms_{{0.0, 0.0, 0.0}};
    V3 h_last_nms_{{0.0, 0.0, 0.0}}, mdel_last_nm_{{0.0, 0.0, 0.0}};
    std::array<std::uint32_t, 3> whl_miss_{{0u, 0u, 0u}};
    double t0_j_ = 0.0, w_j_ = 0.0;
    bool have_ghat_ = false;
    V3 ghat_nms_{{0.0, 0.0, 0.0}};     // G filter estimate (spec 30 §3.6)
    std::uint32_t done_run_ = 0u, n_switch_ = 0u;
    std::uint64_t n_invalid_ = 0u;
    std::uint32_t rotor_run_ = 0u;
    bool rotor_fault_ = false;
};

// Wheel torque N m -> command counts as the flight rounds it (half away from zero, int16 range).
std::int32_t torque_counts(double torque_nm);

// ------------------------------------------------------------------------------------------------
// Rigid gyrostat with three wheels (spec 30 §2): dG/dt = -omega x G, omega = J^-1 (G - H),
// dH_i/dt = applied wheel torque (motor command saturated at M_max, cut at the momentum limit
// where it would increase |H_i|, plus bearing friction). Integrated by RK4 with n_sub steps per
// tick; q_BI (Hamilton, scalar first, v_I = q v_B q*) follows dq/dt = 1/2 q (0, omega).
//
// Gyrodine cluster instead of the wheels (GyrostatModel::cmg, spec 30 §2 "2-SPE"): four
// single-gimbal units of constant rotor momentum k_p h_g (k_p = rotor_scale[p], 1 nominal), ideal
// gimbal rate loop: the commanded rate is clipped to +-u_max and held over the tick, the gimbal
// angles beta are integrated inside the RK4 step (4 more slots), no gimbal stops. H is not an
// integrated state: every derivative evaluation takes H = sum_p k_p h_g u_p(beta_p) and
// dH/dt = h_g sum_p k_p a_p(beta_p) beta_dot_p from the one geometry source cmg_geom
// (rsp_cmg_ref: H = h_g (c3 - c4, c1 - c2, s1 + s2 + s3 + s4), Ahat = dH/dbeta / h_g); the moment
// on the body is M = -dH/dt, the work integral books omega^T M as for the wheels. The state's
// h_nms is H(beta) after every step, so gyrostat_omega, the energies and every consumer of h_nms
// work unchanged. The wheel motor / momentum limits and the bearing friction do not apply.

//
// Elastic variant (spec 30 §2): up to three cantilevered array modes, unit modal mass, each coupled
// with one body axis (coupling column d_i e_axis(i), distinct axes, as in the documented sets E1 and
// E2): G = J omega + H + D qdot, D^T omega_dot + q_ddot = -(delta/pi) Omega qdot - Omega^2 q.
// Integrated in the conjugate modal momenta p = D^T omega + qdot, so that dG/dt = -omega x G keeps
// its rigid form and omega = (J - D D^T)^-1 (G - H - D p) (diagonal: one mode per axis);
// dp/dt = -(delta/pi) Omega qdot - Omega^2 q. With no modes every expression reduces to the rigid
// one bit for bit (x - 0 and J - 0 are exact), so the rigid figures do not move.
// Energy: E = 1/2 omega^T J omega + omega^T D qdot + 1/2 |qdot|^2 + 1/2 q^T Omega^2 q; dE/dt =
// omega^T M - sum (delta/pi) Omega_i qdot_i^2 (the modal dissipation, booked in diss_j).

constexpr std::size_t kRspMaxModes = 3u;
// The gyrodines' null configuration beta = (gamma, gamma, -gamma, -gamma), gamma = pi/4: H = 0.
constexpr double kRspCmgNullRad = 0.78539816339744830962;

struct ElasticMode {
    std::size_t axis = 0u;           // body axis it couples with (0 x, 1 y, 2 z)
    double omega_radps = 0.0;        // constrained (clamped-root) frequency Omega_i
    double d_sqrtkgm = 0.0;          // coupling d_i, kg^1/2 m
    double delta = 0.0;              // logarithmic decrement
};

struct GyrostatModel {
    V3 j_kgm2{{2900.0, 3600.0, 670.0}};
    double iw_kgm2 = 0.01;
    double torque_max_nm = 0.15;     // motor limit
    double h_max_nms = 5.0;          // hard momentum limit (500 rad/s)
    double coulomb_nm = 0.0;         // bearing friction: -coulomb sgn(Omega) - viscous Omega on the wheel
    double viscous_nmps = 0.0;       // N m per rad/s of wheel speed
    std::size_t n_modes = 0u;        // 0: rigid
    std::array<ElasticMode, kRspMaxModes> modes{};
    // Gyrodine cluster instead of the wheels (the wheel fields above are then unused).
    bool cmg = false;
    double hg_nms = 7.5;             // nominal rotor momentum h_g
    double umax_radps = 0.1745;      // gimbal rate limit u_max (the plant clips the command to it)
    std::array<double, 4> beta0_rad{{kRspCmgNullRad, kRspCmgNullRad, -kRspCmgNullRad, -kRspCmgNullRad}};
    std::array<double, 4> rotor_scale{{1.0, 1.0, 1.0, 1.0}};   // rotor p momentum = rotor_scale[p] h_g
};

// The documented modal sets of spec 30 §2: "E1" (nominal) and "E2" (stress); "" or "none": rigid.
// Throws std::invalid_argument for another name.
void gyrostat_set_modes(GyrostatModel &m, const std::string &set);
// The fastest free-free modal frequency Omega_i / sqrt(1 - d_i^2 / J_axis) (0 when rigid).
double gyrostat_fastest_mode_radps(const GyrostatModel &m);

struct GyrostatState {
    V3 g_nms{{0.0, 0.0, 300.0}};     // total momentum, body frame
    V3 h_nms{{0.0, 0.0, 0.0}};       // wheel momenta (about the wheel axes = body axes); cmg: H(beta)
    std::array<double, 4> q_bi{{1.0, 0.0, 0.0, 0.0}};
    V3 q_m{{0.0, 0.0, 0.0}};         // modal coordinates q_i, kg^1/2 m (elastic variant)
    V3 p_m{{0.0, 0.0, 0.0}};         // conjugate modal momenta p_i = d_i omega_axis + qdot_i
    // Gimbal angles (gyrodines; not wrapped: the encoder takes them modulo 2 pi). A wheel model
    // keeps the null configuration (what a locked cluster's encoders would read).
    std::array<double, 4> beta_rad{{kRspCmgNullRad, kRspCmgNullRad, -kRspCmgNullRad, -kRspCmgNullRad}};
    double g0_nms = 300.0;           // |G| the integrator re-projects onto
    double t0_j = 0.0;               // E at t = 0 (T for a rigid body)
    double work_j = 0.0;             // integral of omega^T M dt (M = -dH/dt, the moment on the body)
    double diss_j = 0.0;             // energy dissipated in the modes (0 for a rigid body)
};

// G(0) = g0 g_dir / |g_dir|, modes at rest; a cmg model starts at beta = m.beta0_rad with
// H(0) = H(beta0) (0 at the null configuration), omega(0) = J^-1 (G - H(0)).
GyrostatState gyrostat_initial(const GyrostatModel &m, const V3 &g_dir, double g0_nms);
V3 gyrostat_omega(const GyrostatModel &m, const GyrostatState &s);
double gyrostat_energy_j(const GyrostatModel &m, const GyrostatState &s);   // T = 1/2 omega^T J omega
V3 gyrostat_qdot(const GyrostatModel &m, const GyrostatState &s);            // modal rates qdot_i
// The energy check (equals T in the exact solution): E0 + int omega^T M dt - dissipated - (E - T).
double gyrostat_energy_check_j(const GyrostatModel &m, const GyrostatState &s);
V3 gyrostat_g_inertial(const GyrostatState &s);                               // R_IB G

struct GyrostatTick {
    V3 torque_nm{{0.0, 0.0, 0.0}};          // motor torque after the motor limit
    std::array<bool, 3> motor_clip{{false, false, false}};
    std::array<bool, 3> hlim_cut{{false, false, false}};   // the momentum limit cut torque this tick
    // Gyrodines (gyrostat_tick_cmg):
    std::array<double, 4> rate_radps{{0.0, 0.0, 0.0, 0.0}};    // applied gimbal rate (after the clip)
    std::array<bool, 4> rate_clip{{false, false, false, false}};   // |command| > u_max
    V3 moment_nm{{0.0, 0.0, 0.0}};          // M on the body averaged over the tick: -(H_end - H_start) / dt
};

// One tick with the motor torque command held (ZOH) over dt_s, n_sub RK4 steps. A cmg model
// holds its gimbals (zero rates; the torque is ignored).
GyrostatTick gyrostat_tick(const GyrostatModel &m, GyrostatState &s, const V3 &torque_cmd_nm, double dt_s, int n_sub);
// One tick of a cmg model: gimbal rate commands clipped to +-u_max and held over dt_s, n_sub RK4
// steps. Throws std::invalid_argument for a wheel model.
GyrostatTick gyrostat_tick_cmg(const GyrostatModel &m, GyrostatState &s, const std::array<double, 4> &rate_cmd_radps,
                               double dt_s, int n_sub);
// The cluster momentum H(beta) of a cmg model (rotor scales included); zero for a wheel model.
V3 gyrostat_cluster_h(const GyrostatModel &m, const std::array<double, 4> &beta_rad);
// Rotor p's momentum becomes scale h_g (a rotor fault): an instantaneous internal exchange, G kept,
// H and omega jump; its work -1/2 (omega_before + omega_after)^T dH (exact for the rigid and the
// elastic body: the energy is quadratic in omega at fixed G, p, q) is booked into work_j.
void gyrostat_set_rotor_scale(GyrostatModel &m, GyrostatState &s, std::size_t p, double scale);

// ------------------------------------------------------------------------------------------------
// Linearisation of the LIN law (spec 30 §3.3 item 2, §6): the 6x6 Jacobian in x = (G, H) at
// g = e_y, H = 0 with D = I, H_f = 0. Row and column G_y (the |G| direction: its row and column
// are zero, eigenvalue 0) are removed; the eigenvalues of the remaining 5x5 matrix.

struct LinResult {
    std::array<double, 36> a{};                 // the 6x6 Jacobian, row-major
    std::vector<double> eig_re, eig_im;         // eigenvalues of the 5x5 reduction
    double slowest_re = 0.0;                    // largest real part among the non-zero eigenvalues
};

// xi_sign = +1: the law M = -m [xi - k (H - H_f)]; -1: the xi term's sign flipped.
LinResult linearise_lin(const V3 &j_kgm2, double g0_nms, double m_nm, double k_pnms, double xi_sign);

}  // namespace ref

#endif
