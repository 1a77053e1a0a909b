"""Report of one RELAY SIL log: summary and plots. Called by
`python -m tools.sil report LOG --out DIR [--summary S.json]` (tools/sil/report.py finds this
module from the log's telemetry layout and writes the files).

Figures, computed as the live metrics compute them (hil_host/missions/relay/rly_metrics.cpp), in
the same order of operations, so with --summary they are the run summary's and the report's own
derivation is checked against them (CTest sil_rly_report_agrees): peak |x|, applied level
changes, the true and the flight envelope means over [2000 s, end], the largest envelope error
of the flight copy against the plant truth (LSB of 2^-40 rad), main and brake pulse ranges, the
first freeze, the final k_t, the envelope period and the OR of the module's health. Plots: DIR/angle.png (x with the
deadband), DIR/envelope.png (true and flight a), DIR/kt.png (k_t and the window means).
"""
import math
import os

import numpy as np

from tools.sil.report import Key, read_log

Q40 = 2.0 ** 40
LATE_FROM_S = 2000.0           # RelayMetrics::kLateFromS
EPS_RAD = 5e-4                 # the default table's deadband (plot only)

SUMMARY_KEYS = [
    Key("x_peak_rad", "x_peak_rad"),
    Key("level_changes", "level_changes"),
    Key("abar_true_late_rad", "abar_true_late_rad"),
    Key("abar_fsw_late_rad", "abar_fsw_late_rad"),
    Key("env_err_max_lsb", "env_err_max_lsb"),
    Key("env_pairs", "env_pairs"),
    Key("main_pulses", "main_pulses"),
    Key("tau_main_min_s", "tau_main_min_s"),
    Key("tau_main_max_s", "tau_main_max_s"),
    Key("tau_brake_min_s", "tau_brake_min_s"),
    Key("tau_brake_max_s", "tau_brake_max_s"),
    Key("t_first_freeze_s", "t_first_freeze_s"),
    Key("kt_final", "kt_final"),
    Key("env_period_s", "env_period_s", 0.01, "autocorrelation sums in numpy's order, not the C++ loop's; "
        "the peak's lag is an integer count of 0.05-s samples and the parabola moves it by < 1e-6 s"),
    Key("rly_health_or", "rly_health_sticky"),
]
COUNTERS = ["n_r_main", "n_l_main", "n_x_invalid", "n_x_range", "n_lost", "n_tau_sat", "n_kt_clamped", "n_env_sat",
            "n_reinit", "n_env_high", "n_windows", "revision", "seed"]


def read(path, lcm_py, mission):
    tru = []
    C = read_log(path, lcm_py, mission, {
        "GNC_TRUTH": lambda m: tru.append((m.utime, tuple(m.state[:12]))),
    })
    return dict(common=C, truth=tru, tlm=C["tlm"])


def metrics(R, mission, m):
    """Adds the module's figures, all derived from the log, to m (tools.sil's common ones)."""
    ev = {n: v for n, v, _ in [e for e in mission.iface.enums if e.name == "ev"][0].values}
    st = {n: v for n, v, _ in [e for e in mission.iface.enums if e.name == "st"][0].values}
    x_peak, changes, last_level = 0.0, 0, 0
    sum_true, n_true = 0.0, 0
    a_true_at = {}
    for i, (us, s) in enumerate(R["truth"]):   # arrival order, as the live metrics see them
        x_peak = max(x_peak, abs(s[0]))
        a = []
        tot = 0.0
        for k in range(4):
            q, p = s[3 + k], s[7 + k]
            a.append(math.sqrt(q * q + p * p))
            tot += a[-1]
        lv = int(round(s[11]))
        if i > 0 and lv != last_level:
            changes += 1
        last_level = lv
        if us * 1e-6 >= LATE_FROM_S:
            sum_true += tot
            n_true += 1
        a_true_at[us] = a
    m.update(x_peak_rad=x_peak, level_changes=changes,
             abar_true_late_rad=sum_true / n_true if n_true else 0.0)
    L = R["tlm"]
    if L is None:
        return m
    raw = L["raw"]
    err, pairs, sum_fsw, n_fsw = 0.0, 0, 0.0, 0
    pulses, t1r, t2r = 0, [], []
    t20, a20 = [], []
    last_st, last_win = -1, 0
    t_freeze = -1.0
    ut = L["utime"]
    h_s = float(ut[1] - ut[0]) * 1e-6 if len(ut) > 1 else 0.0
    for j in range(len(ut)):
        us = int(ut[j])
        ts = us * 1e-6
        if us in a_true_at:
            at = a_true_at[us]
            for k in range(4):   # unmodelled modes: 0 in both
                err = max(err, abs(float(raw["rly_a_%d" % k][j]) - at[k] * Q40))
            pairs += 1
        if us % ENV_SAMPLE_US == 0:
            t20.append(ts)
            a20.append(float(raw["rly_a"][j]) / Q40)
        if ts >= LATE_FROM_S:
            sum_fsw += float(raw["rly_a"][j]) / Q40
            n_fsw += 1
        s_ = int(raw["rly_st"][j])
        if s_ in (st["R_BRAKE"], st["L_BRAKE"]) and last_st in (st["R_MAIN"], st["L_MAIN"]):
            t1r.append(float(raw["rly_tau1"][j]) * h_s)
            t2r.append(float(raw["rly_tau2"][j]) * h_s)
            pulses += 1
        last_st = s_
        if int(raw["rly_n_windows"][j]) != last_win:
            e = int(raw["rly_win_event"][j])
            if t_freeze < 0 and e in (ev["FREEZE_SETTLED"], ev["FREEZE_CLIFF"]):
                t_freeze = ts
            last_win = int(raw["rly_n_windows"][j])
    m.update(env_err_max_lsb=err, env_pairs=pairs, abar_fsw_late_rad=sum_fsw / n_fsw if n_fsw else 0.0,
             main_pulses=pulses, tau_main_min_s=min(t1r, default=0.0), tau_main_max_s=max(t1r, default=0.0),
             tau_brake_min_s=min(t2r, default=0.0), tau_brake_max_s=max(t2r, default=0.0),
             t_first_freeze_s=t_freeze, kt_final=float(raw["rly_kt"][-1]) / 65536.0,
             env_period_s=env_period_s(t20, a20))
    hw = raw["rly_health"].astype(np.int64)
    m["rly_health_or"] = int(np.bitwise_or.reduce(hw))
    for k in COUNTERS:
        m["fsw"]["rly_" + k] = int(raw["rly_" + k][-1])
    m["rly_flags_seen"] = [b.name for b in mission.iface.health if m["rly_health_or"] & b.mask]
    m["rly_windows"] = [(int(raw["rly_win_j"][j]), float(raw["rly_win_abar"][j]) / Q40,
                         float(raw["rly_win_kt_in"][j]) / 65536.0, int(raw["rly_win_event"][j]))
                        for j in range(len(ut)) if (raw["rly_health"][j] & 0x10000)]
    return m


ENV_SAMPLE_US = 50000         # RelayMetrics::kEnvSampleUs (20 Hz)
ENV_MAX_LAG = 2400            # RelayMetrics::kEnvMaxLag (120 s)


def env_period_s(t_s, a_rad):
    """RelayMetrics::env_period_s: first autocorrelation peak of a (20 Hz) past its first dip."""
    if len(t_s) == 0:
        return -1.0
    t0 = min(LATE_FROM_S, 0.5 * t_s[-1])
    x = np.asarray([a for t, a in zip(t_s, a_rad) if t >= t0], dtype=float)
    x = x - x.mean()
    n = len(x)
    lmax = min(ENV_MAX_LAG, n // 2)
    r = np.zeros(lmax + 1)
    for lag in range(1, lmax + 1):
        r[lag] = float(np.dot(x[:n - lag], x[lag:])) / (n - lag)
    lag = 2
    while lag < lmax and not (r[lag] <= r[lag - 1] and r[lag] < r[lag + 1]):
        lag += 1
    while lag < lmax and not (r[lag] >= r[lag - 1] and r[lag] > r[lag + 1]):
        lag += 1
    if lag >= lmax:
        return -1.0
    den = r[lag - 1] - 2.0 * r[lag] + r[lag + 1]
    d = 0.5 * (r[lag - 1] - r[lag + 1]) / den if den < 0.0 else 0.0
    return (lag + d) * ENV_SAMPLE_US * 1e-6


def format_summary(m, src):
    """The module's lines; src.tag(...) marks the log-derived ones when a run summary is in use."""
    o = ["  angle             peak |x| %.4g rad; %d level changes%s" % (
             m["x_peak_rad"], m["level_changes"], src.tag("x_peak_rad")),
         "  envelope          mean over [%g s, end]: true %.4g rad, flight %.4g rad; max error %.2f LSB (2^-40 rad)"
         " over %d ticks%s" % (LATE_FROM_S, m["abar_true_late_rad"], m.get("abar_fsw_late_rad", 0.0),
                               m.get("env_err_max_lsb", 0.0), m.get("env_pairs", 0), src.tag("env_err_max_lsb"))]
    if "main_pulses" in m:
        f = m["fsw"]
        o += ["  pulses            %d main (R %d, L %d): main %.3f-%.3f s, brake %.3f-%.3f s%s" % (
                  m["main_pulses"], f["rly_n_r_main"], f["rly_n_l_main"], m["tau_main_min_s"], m["tau_main_max_s"],
                  m["tau_brake_min_s"], m["tau_brake_max_s"], src.tag("main_pulses")),
              "  envelope period   %.2f s (autocorrelation of the flight a at 20 Hz; spec S2 44 +- 2 s)%s" % (
                  m["env_period_s"], src.tag("env_period_s")),
              "  adaptation        k_t final %.5f; first freeze %s; %d windows%s" % (
                  m["kt_final"], "never" if m["t_first_freeze_s"] < 0 else "%.0f s" % m["t_first_freeze_s"],
                  f["rly_n_windows"], src.tag("kt_final"))]
        for j, abar, kt, e in m.get("rly_windows", [])[:60]:
            o.append("    window %3d  abar %.4g rad  k_t %.5f  event %d" % (j, abar, kt, e))
        o.append("  module health OR  0x%08X %s%s" % (m["rly_health_or"], " ".join(m["rly_flags_seen"]) or
                                                       "(no flag)", src.tag("rly_health_or")))
        o.append("  module counters   " + ", ".join("%s %d" % (k, f["rly_" + k]) for k in COUNTERS))
    return "\n".join(o) + "\n"


def plots(R, m, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    paths = []

    def save(fig, name):
        fig.tight_layout()
        p = os.path.join(out, name)
        fig.savefig(p, dpi=110)
        plt.close(fig)
        paths.append(p)

    if R["truth"]:
        us = np.array([u for u, _ in R["truth"]], dtype=float) * 1e-6
        S = np.array([s for _, s in R["truth"]])
        step = max(1, len(us) // 200000)   # plots keep at most ~2e5 points
        fig, ax = plt.subplots(figsize=(10, 4))
        ax.plot(us[::step], S[::step, 0], lw=0.6, label="x (truth)")
        for y in (EPS_RAD, -EPS_RAD):
            ax.axhline(y, color="k", lw=0.5, ls="--")
        ax.set_xlabel("time [s]")
        ax.set_ylabel("x [rad]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
        ax.set_title("RELAY: angle and deadband")
        save(fig, "angle.png")
        L = R["tlm"]
        fig, ax = plt.subplots(figsize=(10, 4))
        at = np.sqrt(S[:, 3:7] ** 2 + S[:, 7:11] ** 2).sum(axis=1)
        ax.plot(us[::step], at[::step], lw=0.6, label="true envelope sum sqrt(x~^2 + p~^2)")
        if L is not None:
            tl = L["utime"] * 1e-6
            sl = max(1, len(tl) // 200000)
            ax.plot(tl[::sl], L["raw"]["rly_a"][::sl] / Q40, "--", lw=0.6, label="flight a (tlm)")
        ax.set_xlabel("time [s]")
        ax.set_ylabel("a [rad]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
        save(fig, "envelope.png")
    W = m.get("rly_windows", [])
    if W:
        fig, ax = plt.subplots(2, 1, figsize=(10, 5), sharex=True)
        j = np.array([w[0] for w in W])
        ax[0].step(j, [w[1] for w in W], where="post")
        ax[0].set_ylabel("window mean a [rad]")
        ax[1].step(j, [w[2] for w in W], where="post")
        ax[1].set_ylabel("k_t in force")
        ax[1].set_xlabel("window j (500 s)")
        for a_ in ax:
            a_.grid(alpha=0.3)
        save(fig, "kt.png")
    return paths
