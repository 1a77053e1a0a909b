"""Report of one RESPIN SIL log: summary and plots. Called by
`python -m tools.sil report LOG --out DIR [--summary S.json]` (tools/sil/report.py finds this
module from the log's telemetry layout and writes the files).

Figures, computed as the live metrics compute them (hil_host/missions/respin/rsp_metrics.cpp), so
with --summary they are the run summary's and the report's own derivation is checked against them
(CTest sil_rsp_report_agrees): convergence (plant-truth |xi| < 0.01 with C_phi > 0 for the flight's
a_f, spec 30 §7) with its first time and the start of the final converged stretch, final |xi|,
C_phi, |omega - omega_f f| and |H|, peak |H| and per-axis |H_i|, T at the end, the plant's energy
check, the |G| invariant, the flight's r_E, the first DONE, region switches and counters.
Plots: DIR/xi.png (|xi| and C_phi, truth, with the flight's region), DIR/wheels.png (H_i truth and
the torque commands), DIR/energy.png (T truth, the flight's T and r_E), DIR/sphere.png (g on the
unit sphere, the momentum direction seen from the body), and with gyrodines DIR/gyrodines.png
(the gimbal rate commands against u_max, the flight's m_s).
"""
import os

import numpy as np

from tools.sil.report import Key, read_log, save_fig

TORQUE_LSB_NM = 2.0 ** -17      # actuator channels 0..2 (fsw/respin/rsp_iface.py)
GIMBAL_RATE_LSB_RADPS = 2.0 ** -16   # actuator channels 3..6
UMAX_RADPS = 0.1745              # gimbal-rate limit (spec 30 §2)
XI_DONE = 0.01                  # RespinMetrics::kXiDone
J_Y_KGM2 = 3600.0               # spec 30 §2 (the scenario's J_y: RespinSetup)
# RespinPlant truth layout (sim/respin/respin_plant.hpp): state[W..W+2] omega_BN_B [rad/s],
# state[H..H+2] h_whl_B [N m s], state[G..G+2] G_B [N m s], state[T] T [J], state[E] T0 + int w.M dt [J]
TW, TH, TG, TT, TE = 0, 3, 6, 13, 14

SUMMARY_KEYS = [
    Key("converged", "converged"),
    Key("low_momentum", "low_momentum"),
    Key("converged_or_low", "converged_or_low"),
    Key("g0_true_nms", "g0_true_nms"),
    Key("t_first_xi_s", "t_first_xi_s"),
    Key("t_settle_s", "t_settle_s"),
    Key("xi_final", "xi_final"),
    Key("cphi_final", "cphi_final"),
    Key("a_f_final", "a_f_final"),
    Key("w_err_final_radps", "w_err_final_radps"),
    Key("h_final_nms", "h_final_nms"),
    Key("h_axis_peak_nms", "h_axis_peak_nms"),
    Key("h_peak_nms", "h_peak_nms"),
    Key("t_end_j", "t_end_j"),
    Key("e_check_max_j", "e_check_max_j"),
    Key("g_rel_err_max", "g_rel_err_max"),
    Key("re_abs_max_j", "re_abs_max_j"),
    Key("t_done_s", "t_done_s"),
    Key("cmd_peak_nm", "cmd_peak_nm"),
    Key("gimbal_rate_peak_radps", "gimbal_rate_peak_radps"),
    Key("rsp_health_or", "rsp_health_sticky"),
]


def read(path, lcm_py, mission):
    tru, cmd = [], []
    C = read_log(path, lcm_py, mission, {
        "GNC_TRUTH": lambda m: tru.append((m.utime * 1e-6,) + tuple(m.state[:16])),
        "GNC_CMD": lambda m: cmd.append((m.utime * 1e-6,) + tuple(m.counts[i] if i < m.n_counts else 0
                                                                  for i in range(7))),
    })
    return dict(common=C, truth=tru, cmd=cmd, tlm=C["tlm"])


def _af_at(L, t):
    """The flight's a_f in force at truth time t (last telemetry at or before t; 0 before any)."""
    if L is None or len(L["utime"]) == 0:
        return np.zeros_like(t)
    tt = L["utime"] * 1e-6
    af = L["raw"]["rsp_a_f"].astype(float)
    # the live metrics keep the last non-zero a_f they received
    nz = np.where(af != 0)[0]
    if len(nz) == 0:
        return np.zeros_like(t)
    i = np.searchsorted(tt[nz], t, side="right") - 1
    return np.where(i >= 0, af[nz][np.clip(i, 0, None)], 0.0)


def truth_series(R):
    T = np.array(R["truth"], dtype=float)
    t = T[:, 0]
    st = T[:, 1:]
    g = st[:, TG:TG + 3]
    # the live metrics' operations in their order (sqrt of the sum of squares), so the figures agree bit for bit
    gn = np.sqrt(g[:, 0] * g[:, 0] + g[:, 1] * g[:, 1] + g[:, 2] * g[:, 2])
    af = _af_at(R["tlm"], t)
    af = np.where(af != 0, af, np.where(g[:, 1] >= 0, 1.0, -1.0))
    with np.errstate(invalid="ignore", divide="ignore"):
        xi = np.where(gn > 0, np.sqrt(g[:, 0] * g[:, 0] + g[:, 2] * g[:, 2]) / gn, 1.0)
        cphi = np.where(gn > 0, af * g[:, 1] / gn, 0.0)
    return dict(t=t, st=st, g=g, gn=gn, af=af, xi=xi, cphi=cphi)


def metrics(R, mission, m):
    """Adds the module's figures, all derived from the log, to m (tools.sil's common ones)."""
    L = R["tlm"]
    if R["truth"]:
        S = truth_series(R)
        t, st, gn = S["t"], S["st"], S["gn"]
        conv = (S["xi"] < XI_DONE) & (S["cphi"] > 0)
        first = np.nonzero(conv)[0]
        m["t_first_xi_s"] = float(t[first[0]]) if len(first) else -1.0
        if conv[-1]:
            bad = np.nonzero(~conv)[0]
            m["t_settle_s"] = float(t[bad[-1] + 1]) if len(bad) else float(t[0])
        else:
            m["t_settle_s"] = -1.0
        m["converged"] = 1 if conv[-1] else 0
        m["g0_true_nms"] = float(gn[0])
        m["xi_final"] = float(S["xi"][-1])
        m["cphi_final"] = float(S["cphi"][-1])
        w, h = st[-1, TW:TW + 3], st[-1, TH:TH + 3]
        wf = gn[-1] / J_Y_KGM2
        m["w_err_final_radps"] = float(np.sqrt(w[0] ** 2 + (w[1] - S["af"][-1] * wf) ** 2 + w[2] ** 2))
        H = st[:, TH:TH + 3]
        hn = np.sqrt(H[:, 0] * H[:, 0] + H[:, 1] * H[:, 1] + H[:, 2] * H[:, 2])
        m["h_final_nms"] = float(hn[-1])
        m["h_peak_nms"] = float(np.max(hn))
        m["h_axis_peak_nms"] = float(np.max(np.abs(H)))
        m["t_end_j"] = float(st[-1, TT])
        m["e_check_max_j"] = float(np.max(np.abs(st[:, TE] - st[:, TT])))
        m["g_rel_err_max"] = float(np.max(np.abs(gn - gn[0]) / gn[0])) if gn[0] > 0 else 0.0
    C = np.array(R["cmd"], dtype=float) if R["cmd"] else np.zeros((0, 4))
    m["cmd_peak_nm"] = float(np.max(np.abs(C[:, 1:4]))) * TORQUE_LSB_NM if len(C) else 0.0
    m["gimbal_rate_peak_radps"] = float(np.max(np.abs(C[:, 4:8]))) * GIMBAL_RATE_LSB_RADPS if len(C) else 0.0
    m["t_done_s"] = -1.0
    m["a_f_final"] = 0
    m["re_abs_max_j"] = 0.0
    if L is not None:
        raw = L["raw"]
        hw = raw["rsp_health"].astype(np.int64)
        m["rsp_health_or"] = int(np.bitwise_or.reduce(hw))
        done = [b.mask for b in mission.iface.health if b.name == "DONE"][0]
        hit = np.nonzero(hw & done)[0]
        if len(hit):
            m["t_done_s"] = float(L["utime"][hit[0]] * 1e-6)
        af = raw["rsp_a_f"]
        nz = np.nonzero(af)[0]
        m["a_f_final"] = int(af[nz[-1]]) if len(nz) else 0
        m["re_abs_max_j"] = float(np.max(np.abs(raw["rsp_r_e"].astype(float)))) * 2.0 ** -32
        for k in ("region", "mode", "n_switch", "n_lin", "n_mid", "n_far", "n_gyro_bad", "n_gyro_stale",
                  "n_whl_bad", "n_whl_est", "n_outlier", "n_overflow", "n_clip", "n_hbound", "revision"):
            m["fsw"]["rsp_" + k] = int(raw["rsp_" + k][-1])
        low = [b.mask for b in mission.iface.health if b.name == "LOW_MOMENTUM"][0]
        m["low_momentum"] = 1 if m["rsp_health_or"] & low else 0
        if "converged" in m:
            m["converged_or_low"] = 1 if (m["converged"] or m["low_momentum"]) else 0
        m["rsp_flags_seen"] = [b.name for b in mission.iface.health if m["rsp_health_or"] & b.mask]
    return m


def format_summary(m, src):
    """The module's lines; src.tag(...) marks the log-derived ones when a run summary is in use."""
    o = []
    if "xi_final" in m:
        o += ["  convergence       %s: first |xi| < %g at %.1f s, settled from %.1f s%s" % (
                  "converged" if m["converged"] else "NOT converged", XI_DONE, m["t_first_xi_s"], m["t_settle_s"],
                  src.tag("converged", "t_first_xi_s", "t_settle_s")),
              "  final state       |xi| %.3e, C_phi %.6f, a_f %+d, |omega - omega_f f| %.3e rad/s, |H| %.3e N m s%s" % (
                  m["xi_final"], m["cphi_final"], m["a_f_final"], m["w_err_final_radps"], m["h_final_nms"],
                  src.tag("xi_final", "cphi_final", "w_err_final_radps", "h_final_nms")),
              "  wheels            peak |H| %.4f N m s, peak |H_i| %.6f N m s (limit 5), peak command %.6f N m%s" % (
                  m["h_peak_nms"], m["h_axis_peak_nms"], m["cmd_peak_nm"],
                  src.tag("h_peak_nms", "h_axis_peak_nms", "cmd_peak_nm")),
              "  energy            T_end %.5f J, plant check max %.3e J, flight |r_E| max %.4f J%s" % (
                  m["t_end_j"], m["e_check_max_j"], m["re_abs_max_j"],
                  src.tag("t_end_j", "e_check_max_j", "re_abs_max_j")),
              "  invariant         max ||G| - g0| / g0 %.3e%s" % (m["g_rel_err_max"], src.tag("g_rel_err_max")),
              "  done              %s%s" % ("never" if m["t_done_s"] < 0 else "first at %.1f s" % m["t_done_s"],
                                            src.tag("t_done_s"))]
    if "rsp_health_or" in m:
        f = m["fsw"]
        o.append("  module health OR  0x%08X %s%s" % (m["rsp_health_or"], " ".join(m["rsp_flags_seen"]) or
                                                       "(no flag)", src.tag("rsp_health_or")))
        o.append("  regions           switches %d; ticks LIN %d, MID %d, FAR %d; final %d, mode %d%s" % (
            f["rsp_n_switch"], f["rsp_n_lin"], f["rsp_n_mid"], f["rsp_n_far"], f["rsp_region"], f["rsp_mode"],
            src.tag("fsw.rsp_n_switch")))
        o.append("  invalid ticks     gyro %d, gyro stale %d, wheel %d, wheel estimated %d, outlier %d, "
                 "overflow %d; clip %d, hbound %d%s" % (
                     f["rsp_n_gyro_bad"], f["rsp_n_gyro_stale"], f["rsp_n_whl_bad"], f["rsp_n_whl_est"],
                     f["rsp_n_outlier"], f["rsp_n_overflow"], f["rsp_n_clip"], f["rsp_n_hbound"],
                     src.tag("fsw.rsp_n_gyro_bad")))
    return "\n".join(o) + "\n"


def plots(R, m, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    paths = []
    L = R["tlm"]
    if not R["truth"]:
        return paths
    S = truth_series(R)
    t, st = S["t"], S["st"]
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(10, 6), sharex=True)
    a1.semilogy(t, np.maximum(S["xi"], 1e-6), label="|xi| (truth)")
    a1.axhline(XI_DONE, color="k", lw=0.7, ls=":")
    a1.set_ylabel("|xi| = sin(phi)")
    a1.grid(alpha=0.3)
    a1.legend(fontsize=8)
    a2.plot(t, S["cphi"], label="C_phi (truth, flight a_f)")
    if L is not None:
        a2.plot(L["utime"] * 1e-6, L["raw"]["rsp_region"] * 0.5 - 1.0, lw=0.6, label="region (LIN -1, MID -0.5, FAR 0)")
    a2.set_xlabel("time [s]")
    a2.grid(alpha=0.3)
    a2.legend(fontsize=8)
    a1.set_title("RESPIN: spin axis error")
    save_fig(fig, out, "xi.png", paths)
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(10, 6), sharex=True)
    for i, ax in enumerate("xyz"):
        a1.plot(t, st[:, TH + i], label="H_%s" % ax)
    a1.axhline(5.0, color="k", lw=0.7, ls=":")
    a1.axhline(-5.0, color="k", lw=0.7, ls=":")
    a1.set_ylabel("wheel momentum [N m s]")
    a1.grid(alpha=0.3)
    a1.legend(fontsize=8)
    if R["cmd"]:
        C = np.array(R["cmd"], dtype=float)
        for i, ax in enumerate("xyz"):
            a2.plot(C[:, 0], C[:, 1 + i] * TORQUE_LSB_NM, lw=0.6, label="torque cmd %s" % ax)
    a2.set_ylabel("wheel torque [N m]")
    a2.set_xlabel("time [s]")
    a2.grid(alpha=0.3)
    a2.legend(fontsize=8)
    save_fig(fig, out, "wheels.png", paths)
    fig, ax = plt.subplots(figsize=(10, 4))
    ax.plot(t, st[:, TT], label="T (truth)")
    if L is not None:
        ax.plot(L["utime"] * 1e-6, L["raw"]["rsp_t"] * 2.0 ** -32, "--", label="T (flight)")
        ax.plot(L["utime"] * 1e-6, L["raw"]["rsp_r_e"] * 2.0 ** -32, label="r_E (flight)")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("energy [J]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    save_fig(fig, out, "energy.png", paths)
    fig = plt.figure(figsize=(6, 6))
    ax = fig.add_subplot(projection="3d")
    gu = S["g"] / np.maximum(S["gn"], 1e-12)[:, None]
    ax.plot(gu[:, 0], gu[:, 1], gu[:, 2], lw=0.5)
    ax.scatter([0, 0], [1, -1], [0, 0], color="r", s=20)
    ax.set_xlabel("g_x")
    ax.set_ylabel("g_y")
    ax.set_zlabel("g_z")
    ax.set_title("G / |G| in body axes (targets +-e_y)")
    save_fig(fig, out, "sphere.png", paths)
    C = np.array(R["cmd"], dtype=float) if R["cmd"] else np.zeros((0, 8))
    if len(C) and np.any(C[:, 4:8] != 0):
        # gyrodines: the gimbal rate commands against u_max and the singularity measure m_s
        fig, (a1, a2) = plt.subplots(2, 1, figsize=(10, 6), sharex=True)
        for k in range(4):
            a1.plot(C[:, 0], C[:, 4 + k] * GIMBAL_RATE_LSB_RADPS, lw=0.6, label="beta_dot %d" % (k + 1))
        a1.axhline(UMAX_RADPS, color="k", lw=0.7, ls=":")
        a1.axhline(-UMAX_RADPS, color="k", lw=0.7, ls=":")
        a1.set_ylabel("gimbal rate cmd [rad/s]")
        a1.grid(alpha=0.3)
        a1.legend(fontsize=8)
        if L is not None:
            a2.plot(L["utime"] * 1e-6, L["raw"]["rsp_cmg_ms"] * 2.0 ** -28, lw=0.8, label="m_s (flight)")
        a2.axhline(0.05, color="r", lw=0.7, ls=":", label="SINGULAR below")
        a2.set_ylabel("m_s = sqrt det(A A^T)")
        a2.set_xlabel("time [s]")
        a2.grid(alpha=0.3)
        a2.legend(fontsize=8)
        save_fig(fig, out, "gyrodines.png", paths)
    return paths
