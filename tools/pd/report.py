"""Report of one HOLD SIL log: summary and plots. Called by
`python -m tools.sil report LOG --out DIR [--summary S.json]` (tools/sil/report.py finds this
module from the log's telemetry layout and writes the files).

Figures, computed as the live metrics compute them (hil_host/missions/pd/pd_metrics.cpp), so with
--summary they are the run summary's and the report's own derivation is checked against them (CTest
sil_pd_report_agrees), per channel (yaw, roll, pitch): the settling time t* on the truth attitude at the
sample instants (spec 40 §2.6: the first sample after the last one with |x| >= 5e-5 rad, -1 if the last
violates the band), the peak commanded torque, the peak |dy|/Ty from the telemetry, the peak |beta|
(truth), the peak |x| after 600 s, the final k2 and its number of changes, the OR of the channel's health.
Plots: DIR/attitude.png (|x| per channel on a log scale with the band), DIR/torque.png (M commands),
DIR/gimbal.png (beta truth), DIR/k2.png (k2 in use, telemetry); for a channel flying ADAPTIVE (its
estimator's published f_hat is non-zero) also f_hat at 300 s and 1 200 s with the estimator state there
and its FAULT count (log-derived only: the live summary has no estimator figures), and DIR/fest.png
(f_hat(t), the confident periods marked, the true f_min of the scenario when the log has it).
"""
import os

import numpy as np

from tools.sil.report import Key, read_log, save_fig

CH = ("yaw", "roll", "pitch")
TORQUE_LSB_NM = 2.0 ** -20     # actuator channels 0..2 (fsw/pd/pd_iface.py)
BAND_RAD = 5e-5                # PdMetrics::kBandRad
LATE_S = 600.0                 # PdMetrics::kLateS
FEST_STATES = ("ACQUIRE", "TRACK", "HOLD", "FAULT")
# PdPlant truth layout (sim/pd/pd_plant.hpp): state[0..2] x, state[3..5] beta, state[13] linear_validity
TX, TB, TLIN = 0, 3, 13

SUMMARY_KEYS = []
for _c in CH:
    SUMMARY_KEYS += [Key("t_settle_%s_s" % _c, "t_settle_%s_s" % _c),
                     Key("peak_m_%s_nm" % _c, "peak_m_%s_nm" % _c),
                     Key("peak_rate_%s_radps" % _c, "peak_rate_%s_radps" % _c),
                     Key("peak_beta_%s_rad" % _c, "peak_beta_%s_rad" % _c),
                     Key("peak_x_late_%s_rad" % _c, "peak_x_late_%s_rad" % _c),
                     Key("k2_final_%s_s" % _c, "k2_final_%s_s" % _c),
                     Key("k2_changes_%s" % _c, "k2_changes_%s" % _c),
                     Key("pd_%s_health_or" % _c, "pd_%s_health_or" % _c),
                     # the log's figures exist only for a channel whose estimator published (ADAPTIVE)
                     Key("fest_f300_%s_hz" % _c, "fest_f300_%s_hz" % _c, optional=True),
                     Key("fest_f1200_%s_hz" % _c, "fest_f1200_%s_hz" % _c, optional=True),
                     Key("fest_resets_%s" % _c, "fest_resets_%s" % _c, optional=True)]
SUMMARY_KEYS.append(Key("linear_invalid", "linear_invalid"))


def read(path, lcm_py, mission):
    tru, cmd = [], []
    C = read_log(path, lcm_py, mission, {
        "GNC_TRUTH": lambda m: tru.append((m.utime * 1e-6,) + tuple(m.state[:16])),
        "GNC_CMD": lambda m: cmd.append((m.utime * 1e-6,) + tuple(m.counts[i] if i < m.n_counts else 0
                                                                  for i in range(3))),
    })
    return dict(common=C, truth=tru, cmd=cmd, tlm=C["tlm"])


def settle(t, x):
    """t* of spec 40 §2.6 on samples (t_k, x_k)."""
    bad = np.nonzero(~(np.abs(x) < BAND_RAD))[0]
    if len(x) == 0 or not abs(x[-1]) < BAND_RAD:
        return -1.0
    return 0.0 if len(bad) == 0 else float(t[bad[-1] + 1])


def metrics(R, mission, m):
    """Adds the module's figures, all derived from the log, to m (tools.sil's common ones)."""
    T = np.array(R["truth"]) if R["truth"] else np.zeros((0, 17))
    C = np.array(R["cmd"], dtype=float) if R["cmd"] else np.zeros((0, 4))
    L = R["tlm"]
    ty = float(np.diff(T[:2, 0])[0]) if len(T) > 1 else 0.25
    for k, c in enumerate(CH):
        t, x = T[:, 0], T[:, 1 + TX + k]
        m["t_settle_%s_s" % c] = settle(t, x)
        m["peak_m_%s_nm" % c] = float(np.max(np.abs(C[:, 1 + k]) * TORQUE_LSB_NM)) if len(C) else 0.0
        m["peak_beta_%s_rad" % c] = float(np.max(np.abs(T[:, 1 + TB + k]))) if len(T) else 0.0
        late = np.abs(x[t >= LATE_S])
        m["peak_x_late_%s_rad" % c] = float(late.max()) if len(late) else 0.0
        if L is not None:
            raw = L["raw"]
            k2 = raw["pd_%s_k2" % c].astype(np.int64)
            m["k2_final_%s_s" % c] = float(k2[-1]) * 2.0 ** -22
            m["k2_changes_%s" % c] = int(np.count_nonzero(np.diff(k2)))
            m["peak_rate_%s_radps" % c] = float(np.max(np.abs(raw["pd_%s_dy" % c].astype(float)))) * 2.0 ** -30 / ty
            h = int(np.bitwise_or.reduce(raw["pd_%s_health" % c].astype(np.int64)))
            m["pd_%s_health_or" % c] = h
            m["pd_%s_flags_seen" % c] = [b.name for b in mission.iface.health if b.single and h & b.mask]
            for n in ("miss", "stale", "range_rej", "rate_rej", "period_rej", "trq_sat", "beta_lim"):
                m["fsw"]["pd_%s_%s" % (c, n)] = int(raw["pd_%s_%s" % (c, n)][-1])
            ff = raw["pd_%s_fest_f" % c].astype(np.int64)
            if np.any(ff != 0):
                tt = L["utime"] * 1e-6
                word = raw["pd_%s_fest" % c].astype(np.int64)
                for at in (300.0, 1200.0):
                    i = int(np.searchsorted(tt, at + 1e-6)) - 1
                    if i >= 0:
                        m["fest_f%d_%s_hz" % (int(at), c)] = float(ff[i]) * 2.0 ** -32
                        m["fest_state%d_%s" % (int(at), c)] = FEST_STATES[int(word[i]) & 3] + (
                            " confident" if word[i] & 4 else "")
                m["fest_resets_%s" % c] = int(raw["pd_%s_fest_resets" % c][-1])
    m["linear_invalid"] = int(bool(len(T)) and bool(np.any(T[:, 1 + TLIN] < 0.5)))
    return m


def format_summary(m, src):
    """The module's lines; src.tag(...) marks the log-derived ones when a run summary is in use."""
    o = []
    for c in CH:
        o.append("  %-5s  t* %8.2f s  peak |M| %.4f N m  peak |dy|/Ty %.3g rad/s  peak |beta| %.4f rad  "
                 "k2 %.2f s (%d changes)%s" % (c, m["t_settle_%s_s" % c], m["peak_m_%s_nm" % c],
                                                m.get("peak_rate_%s_radps" % c, 0.0), m["peak_beta_%s_rad" % c],
                                                m.get("k2_final_%s_s" % c, 0.0), m.get("k2_changes_%s" % c, 0),
                                                src.tag("t_settle_%s_s" % c)))
        if "pd_%s_health_or" % c in m:
            f = m["fsw"]
            o.append("         health OR 0x%08X %s; miss %d stale %d range %d rate %d period %d trq_sat %d "
                     "beta_lim %d" % (m["pd_%s_health_or" % c], " ".join(m["pd_%s_flags_seen" % c]) or "(no flag)",
                                      *[f["pd_%s_%s" % (c, n)] for n in ("miss", "stale", "range_rej", "rate_rej",
                                                                          "period_rej", "trq_sat", "beta_lim")]))
        # the estimator line only for a channel whose estimator published (the summary carries f^ = 0
        # for the others)
        if "fest_resets_%s" % c in m and (m.get("fest_f300_%s_hz" % c, 0.0) or m.get("fest_f1200_%s_hz" % c, 0.0)):
            o.append("         estimator: f^(300 s) %.5f Hz %s, f^(1200 s) %.5f Hz %s, FAULTs %d" % (
                m.get("fest_f300_%s_hz" % c, 0.0), m.get("fest_state300_%s" % c, "-"),
                m.get("fest_f1200_%s_hz" % c, 0.0), m.get("fest_state1200_%s" % c, "-"), m["fest_resets_%s" % c]))
    o.append("  linear model      %s" % ("strained (|beta| > 0.5 rad seen)" if m["linear_invalid"] else "valid"))
    return "\n".join(o) + "\n"


def plots(R, m, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    paths = []
    T = np.array(R["truth"]) if R["truth"] else None
    if T is not None:
        fig, ax = plt.subplots(figsize=(10, 4))
        for k, c in enumerate(CH):
            ax.semilogy(T[:, 0], np.abs(T[:, 1 + TX + k]) + 1e-12, lw=0.8, label="|x| %s (t* %.1f s)"
                        % (c, m["t_settle_%s_s" % c]))
        ax.axhline(BAND_RAD, color="k", ls="--", lw=0.8, label="band 5e-5 rad")
        ax.set_ylim(1e-8, 0.1)
        ax.set_xlabel("time [s]")
        ax.set_ylabel("|x| [rad]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
        ax.set_title("HOLD: attitude (truth)")
        save_fig(fig, out, "attitude.png", paths)
        fig, ax = plt.subplots(figsize=(10, 3.5))
        for k, c in enumerate(CH):
            ax.plot(T[:, 0], T[:, 1 + TB + k], lw=0.8, label="beta %s" % c)
        ax.set_xlabel("time [s]")
        ax.set_ylabel("gimbal angle [rad]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
        save_fig(fig, out, "gimbal.png", paths)
    if R["cmd"]:
        C = np.array(R["cmd"], dtype=float)
        fig, ax = plt.subplots(figsize=(10, 3.5))
        for k, c in enumerate(CH):
            ax.plot(C[:, 0], C[:, 1 + k] * TORQUE_LSB_NM, lw=0.8, label="M %s" % c)
        ax.set_xlabel("time [s]")
        ax.set_ylabel("gimbal torque [N m]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
        save_fig(fig, out, "torque.png", paths)
    L = R["tlm"]
    if L is not None:
        fig, ax = plt.subplots(figsize=(10, 3))
        for c in CH:
            ax.plot(L["utime"] * 1e-6, L["raw"]["pd_%s_k2" % c] * 2.0 ** -22, label="k2 %s" % c)
        ax.set_xlabel("time [s]")
        ax.set_ylabel("k2 [s]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
        save_fig(fig, out, "k2.png", paths)
        adaptive = [c for c in CH if np.any(L["raw"]["pd_%s_fest_f" % c] != 0)]
        if adaptive:
            tt = L["utime"] * 1e-6
            fig, ax = plt.subplots(figsize=(10, 3.5))
            for c in adaptive:
                f = L["raw"]["pd_%s_fest_f" % c] * 2.0 ** -32
                conf = (L["raw"]["pd_%s_fest" % c].astype(np.int64) & 4) != 0
                ax.plot(tt, f, lw=0.9, label="f^ %s" % c)
                ax.plot(tt[conf], f[conf], ".", ms=2, label="f^ %s confident" % c)
            f_true = m.get("f_hz")
            if f_true:
                ax.axhline(f_true, color="k", ls="--", lw=0.8, label="f_min (scenario)")
            ax.set_xlabel("time [s]")
            ax.set_ylabel("estimated f_min [Hz]")
            ax.grid(alpha=0.3)
            ax.legend(fontsize=8)
            ax.set_title("HOLD: on-board frequency estimate (ADAPTIVE channels)")
            save_fig(fig, out, "fest.png", paths)
    return paths
