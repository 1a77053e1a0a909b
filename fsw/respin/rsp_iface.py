"""Interface of the respin module (mission RESPIN, spec 30-respin): the single source of its names,
enums, health bits and telemetry block. Not flight code: `python -m tools.iface c` turns it into
rsp_ids.h and rsp_tlm.c (committed; CTest golden_iface_regen checks them); Python tools read it
through tools.iface.
"""
from tools.iface.schema import Bit, Chan, Field, Module, enum, tc

AX = "xyz"


def _tlm():
    f = [Field("phase", "u8", "t->phase", note="RSP_PH_*"),
         Field("region", "u8", "t->region", note="RSP_RG_*"),
         Field("latched", "u8", "t->latched", note="1 while a_f is latched"),
         Field("mode", "u8", "t->mode", note="RSP_MODE_* in force"),
         Field("a_f", "i32", "t->a_f", note="f = a_f e_y, +1 or -1"),
         Field("flags", "u32", "t->flags", note="RSP_H_* of the last step"),
         Field("xi_abs", "i32", "t->xi_abs_q30", q=30, note="|xi| = |g x f|"),
         Field("cphi", "i32", "t->cphi_q30", q=30, note="C_phi = a_f g_y")]
    f += [Field("g_" + a, "i32", "t->g_q30[%du]" % i, q=30, note="g = G / g0") for i, a in enumerate(AX)]
    f += [Field("g0", "i32", "t->g0_q20", q=20, unit="N m s", note="frozen |G| (0 until frozen)"),
          Field("rho", "i32", "t->rho_q30", q=30, note="|G| / g0 - 1"),
          Field("rho_lp", "i32", "t->rho_lp_q30", q=30, note="rho_G low-passed (G_DRIFT)")]
    f += [Field("mcmd_" + a, "i32", "t->mcmd_q24[%du]" % i, q=24, unit="N m", note="law moment on the body")
          for i, a in enumerate(AX)]
    f += [Field("mdel_" + a, "i32", "t->mdel_q24[%du]" % i, q=24, unit="N m", note="moment after distribution")
          for i, a in enumerate(AX)]
    f += [Field("h_" + a, "i32", "t->h_q20[%du]" % i, q=20, unit="N m s", note="wheel momentum used")
          for i, a in enumerate(AX)]
    f += [Field("t", "i64", "t->t_q32", q=32, unit="J", note="kinetic energy of the body"),
          Field("w", "i64", "t->w_q32", q=32, unit="J", note="work of the internal moment since t0"),
          Field("r_e", "i64", "t->re_q32", q=32, unit="J", note="energy residual T - T0 - W"),
          Field("done_run", "u32", "t->done_run", unit="tick", note="ticks in the done tolerance in a row")]
    for n, note in (("switch", "region changes"), ("lin", "ticks in LIN"), ("mid", "ticks in MID"),
                    ("far", "ticks in FAR"), ("gyro_bad", "invalid ticks: gyro full scale or missing"),
                    ("gyro_stale", "invalid ticks: gyro words frozen"),
                    ("whl_bad", "invalid ticks: wheel speed missing too long or frozen"),
                    ("whl_est", "ticks with a propagated wheel momentum"),
                    ("outlier", "invalid ticks: |G| outlier"), ("overflow", "ticks with an fx status"),
                    ("clip", "ticks with an axis clipped to M_max"),
                    ("hbound", "ticks with an axis at the momentum bound")):
        f.append(Field("n_" + n, "u32", "t->n_" + n, unit="count", note=note))
    f += [Field("t_far_d100", "i64", "t->t_far_d100_q32", q=32, unit="J",
                note="T change over the last complete 100 s in FAR (< 0: the far relay dissipates)")]
    f += [Field("cmg_rate_%d" % (k + 1), "i32", "t->cmg_rate_cnt[%du]" % k, unit="2^-16 rad/s",
                note="gimbal rate command of gyrodine %d" % (k + 1)) for k in range(4)]
    f += [Field("cmg_ms", "i32", "t->cmg_ms_q28", q=28, note="singularity measure m_s = sqrt det(A A^T)"),
          Field("cmg_s", "i32", "t->cmg_s_q16", q=16, note="gimbal-rate scale s = max|beta_dot| / u_max"),
          Field("n_singular", "u32", "t->n_singular", unit="count", note="ticks with m_s < ms_sing"),
          Field("n_rate_limited", "u32", "t->n_rate_limited", unit="count", note="ticks with s > 1")]
    f += [Field("health_sticky", "u32", "t->health_sticky"),
          Field("revision", "u32", "t->revision", note="table revision in use")]
    return f


MODULE = Module(
    module="respin",
    prefix="rsp",
    doc="RESPIN: respin switching law with thresholds and wheel or gyrodine distribution (spec 30)",
    tlm_type="rsp_tlm_t",
    tlm_layout=2,
    tlm=_tlm(),
    sensors=([Chan("omega_BN_B_" + a, "2^-22 rad/s", "rate gyro %s: body rate wrt inertial, body axes" % a)
              for a in AX] +
             [Chan("whl_speed_" + a, "2^-10 rad/s", "wheel %s speed relative to the body" % a) for a in AX] +
             [Chan("gimbal_angle_%d" % k, "2pi/2^20 rad", "gyrodine %d gimbal angle encoder (wraps at 2^20)" % k)
              for k in range(1, 5)] +
             [Chan("rotor_speed_%d" % k, "2^-8 rad/s", "gyrodine %d rotor speed (health)" % k) for k in range(1, 5)]),
    actuators=([Chan("whl_torque_cmd_" + a, "2^-17 N m", "wheel %s motor torque command (= -M_%s)" % (a, a))
                for a in AX] +
               [Chan("gimbal_rate_cmd_%d" % k, "2^-16 rad/s", "gyrodine %d gimbal rate command" % k)
                for k in range(1, 5)]),
    health=[
        Bit("GYRO_BAD", 0x00000100, "a gyro channel missing or at full scale: tick invalid, zero command"),
        Bit("GYRO_STALE", 0x00000200, "gyro words unchanged for n_stale ticks: tick invalid"),
        Bit("WHL_BAD", 0x00000400, "a wheel speed missing beyond n_whl_est or frozen, or a gimbal angle missing: tick invalid"),
        Bit("WHL_EST", 0x00000800, "a wheel momentum propagated from the last command (ESTIMATED)"),
        Bit("OUTLIER", 0x00001000, "||G| - g0| beyond the gate: tick invalid"),
        Bit("INPUT_FAULT", 0x00002000, "n_fault invalid ticks in a row (latched until re-entry)"),
        Bit("LOW_MOMENTUM", 0x00004000, "g0 < g_min: zero command"),
        Bit("GUARD", 0x00008000, "g0 < g_guard: far law disabled"),
        Bit("CLIP", 0x00010000, "an axis clipped to M_max"),
        Bit("HBOUND", 0x00020000, "an axis at the momentum-bound clamp"),
        Bit("G_DRIFT", 0x00040000, "rho_G low-passed beyond drift"),
        Bit("ENERGY_ALARM", 0x00080000, "r_E > e_alarm: energy from nowhere"),
        Bit("OVERFLOW", 0x00100000, "an fx status this tick: zero command"),
        Bit("DONE", 0x00200000, "|xi|, C_phi > 0 and |H - H_f| in tolerance for done_ticks"),
        Bit("G0_WAIT", 0x00400000, "g0 being averaged: zero command"),
        Bit("WHEEL_FAULT", 0x00800000, "a wheel off its command by > 0.03 N m for 10 s (latched): zero command"),
        Bit("SINGULAR", 0x01000000, "gyrodines: m_s < ms_sing (telemetry only: the damped inverse passes through)"),
        Bit("RATE_LIMITED", 0x02000000, "gyrodines: the gimbal rates scaled by 1/s (direction kept)"),
        Bit("ROTOR_FAULT", 0x04000000, "gyrodines: a rotor speed off nominal by > rotor_tol for n_fault ticks (latched): zero command"),
        Bit("HBOUND_STUCK", 0x08000000, "HBOUND on every LIN tick for 600 s: H cannot return to H_f (fault, law continues)"),
        Bit("ENERGY_LOW", 0x10000000, "T below (g0 - |H|)^2 / (2 J_y) - e_alarm: wrong J, gyro scale or momentum (alarm)"),
        Bit("FAR_T_RISE", 0x20000000, "T rose over the last 100 s in FAR (the far relay must dissipate; report)"),
    ],
    why=[
        Bit("PERIOD", 0x001, "period (zero, or not the executive's)"),
        Bit("MODE", 0x002, "mode or actuator kind unknown"),
        Bit("INERTIA", 0x004, "J not positive, or J_y not the largest (principal axes, gamma_p = 0)"),
        Bit("THRESH", 0x008, "0 < h_eps, eps1 > 2 h_eps, eps2 - eps1 > 2 h_eps, eps2 + h_eps < 1"),
        Bit("GAIN", 0x010, "m, k, M*, M_max positive and m = M_max / eps1 within 1 %"),
        Bit("WHEEL", 0x020, "I_w, h_lim, 1/Ts (= 10^6 / period) out of range"),
        Bit("GUARDS", 0x040, "0 < g_min <= g_guard, n_g0 in 1..1024"),
        Bit("SENSOR", 0x080, "gyro / wheel full scale, n_fault, n_stale, n_whl_est"),
        Bit("HEALTH", 0x100, "outlier, drift, energy alarm or done limits"),
        Bit("FILTER", 0x200, "G filter alpha outside [0, 0.5]"),
        Bit("CMG", 0x400, "gyrodine h_g, lambda0, u_max, m_s threshold or rotor speed out of range"),
    ],
    enums=[
        enum("ph", "RSP_PH_", [("G0", 0), ("LOW", 1), ("RUN", 2)], "module phases: g0 averaging, low momentum, law"),
        enum("rg", "RSP_RG_", [("LIN", 0), ("MID", 1), ("FAR", 2)], "regions of the law (spec 30 §3.2)"),
        enum("mode", "RSP_MODE_", [("NEAREST", 0), ("PRINTED", 1)], "law variants (spec 30 §3.5)"),
        enum("act", "RSP_ACT_", [("WHEELS", 0), ("GYRODINES", 1)], "momentum actuator kinds"),
    ],
    commands=[tc("RESET_COUNTERS", 1, "clear the module's counters and sticky health")],
    table_id=0x0B06,
    table_layout=2,
    table_fields=["period_us", "mode", "act_kind", "j_x_q19", "j_y_q19", "j_z_q19", "iw_q30", "eps1_q30",
                  "eps2_q30", "heps_q30", "m_q24", "k_q30", "mstar_q24", "mmax_q24", "hlim_q20", "inv_ts_q16",
                  "gguard_q20", "gmin_q20", "n_g0", "gyro_max_cnt", "whl_max_cnt", "n_fault", "n_stale",
                  "n_whl_est", "outlier_q20", "outlier_rel_q16", "drift_q30", "drift_sh", "ealarm_q32",
                  "done_xi_q30", "done_h_q20", "done_ticks", "gfilt_alpha_q30", "hg_q20", "lambda_q28", "umax_cnt",
                  "ms_sing_q28", "rotor_nom_cnt", "rotor_tol_q16"],
)
