"""Report of one HOLD SIL log: summary and plots. Called by
`python -m tools.sil report LOG --out DIR [--summary S.json]` (tools/sil/report.py finds this
module from the log's telemetry layout and writes the files).

Figures, computed as the live metrics compute them (hil_host/missions/pd/pd_metrics.cpp),
so with --summary they are the run summary's and the report's own derivation is checked against
them (CTest sil_pd_report_agrees): settling time (last truth time with |omega| >= 1e-3 rad/s,
plus one period), final |omega|, peak commanded torque, first CMD_LIMIT_PERSIST, the OR of the
module's health. Plots: DIR/rate.png (truth omega and the flight's rate), DIR/torque.png.
"""
import os

import numpy as np

from tools.sil.report import Key, read_log

TORQUE_LSB_NM = 2.0 ** -16     # actuator channel 0 (fsw/pd/pd_iface.py)
RATE_LSB_RADPS = 2.0 ** -20    # sensor channel 0
SETTLE_RADPS = 1e-3            # PdMetrics::kSettleRadps

SUMMARY_KEYS = [
    Key("t_settle_s", "t_settle_s"),
    Key("rate_final_radps", "rate_final_radps"),
    Key("peak_torque_nm", "peak_torque_nm"),
    Key("t_cmd_limit_persist_s", "t_cmd_limit_persist_s"),
    Key("pd_health_or", "pd_health_sticky"),
]


def read(path, lcm_py, mission):
    tru, cmd = [], []
    C = read_log(path, lcm_py, mission, {
        "GNC_TRUTH": lambda m: tru.append((m.utime * 1e-6, m.state[0], m.state[1])),
        "GNC_CMD": lambda m: cmd.append((m.utime * 1e-6, m.counts[0] if m.n_counts >= 1 else 0, m.n_counts)),
    })
    return dict(common=C, truth=tru, cmd=cmd, tlm=C["tlm"])


def metrics(R, mission, m):
    """Adds the module's figures, all derived from the log, to m (tools.sil's common ones)."""
    h = 0.0
    t_settle = 0.0
    t_last = 0.0
    w = 0.0
    for i, (ts, om, _) in enumerate(R["truth"]):   # arrival order, as the live metrics see them
        if i == 1:
            h = ts - t_last
        w = abs(om)
        if w >= SETTLE_RADPS:
            t_settle = ts + (h if i >= 1 else 0.0)
        t_last = ts
    m["t_settle_s"] = t_settle
    m["rate_final_radps"] = w
    m["peak_torque_nm"] = max([abs(c * TORQUE_LSB_NM) for _, c, n in R["cmd"] if n >= 1], default=0.0)
    L = R["tlm"]
    m["t_cmd_limit_persist_s"] = -1.0
    if L is not None:
        raw = L["raw"]
        hw = raw["pd_health"].astype(np.int64)
        m["pd_health_or"] = int(np.bitwise_or.reduce(hw))
        bit = [b.mask for b in mission.iface.health if b.name == "CMD_LIMIT_PERSIST"][0]
        hit = np.nonzero(hw & bit)[0]
        if len(hit):
            m["t_cmd_limit_persist_s"] = float(L["utime"][hit[0]] * 1e-6)
        for k in ("n_skip", "n_limited", "revision"):
            m["fsw"]["pd_" + k] = int(raw["pd_" + k][-1])
        m["pd_flags_seen"] = [b.name for b in mission.iface.health if m["pd_health_or"] & b.mask]
    return m


def format_summary(m, src):
    """The module's lines; src.tag(...) marks the log-derived ones when a run summary is in use."""
    o = ["  settling          t_settle %.2f s (|omega| < %g rad/s after it)%s" % (
             m["t_settle_s"], SETTLE_RADPS, src.tag("t_settle_s")),
         "  final rate        |omega| %.3g rad/s%s" % (m["rate_final_radps"], src.tag("rate_final_radps")),
         "  peak torque       %.6f N m%s" % (m["peak_torque_nm"], src.tag("peak_torque_nm"))]
    if "pd_health_or" in m:
        f = m["fsw"]
        o.append("  module health OR  0x%08X %s%s" % (m["pd_health_or"], " ".join(m["pd_flags_seen"]) or
                                                       "(no flag)", src.tag("pd_health_or")))
        o.append("  module counters   n_skip %d, n_limited %d, revision %d%s" % (
            f["pd_n_skip"], f["pd_n_limited"], f["pd_revision"], src.tag("fsw.pd_n_skip")))
        o.append("  limit persist     %s%s" % ("never" if m["t_cmd_limit_persist_s"] < 0 else
                                               "first at %.2f s" % m["t_cmd_limit_persist_s"],
                                               src.tag("t_cmd_limit_persist_s")))
    return "\n".join(o) + "\n"


def plots(R, m, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    paths = []
    if R["truth"]:
        T = np.array(R["truth"])
        fig, ax = plt.subplots(figsize=(10, 4))
        ax.plot(T[:, 0], T[:, 1], label="truth omega")
        L = R["tlm"]
        if L is not None:
            ax.plot(L["utime"] * 1e-6, L["raw"]["pd_rate"] * RATE_LSB_RADPS, "--", label="flight rate (tlm)")
        ax.set_xlabel("time [s]")
        ax.set_ylabel("omega [rad/s]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
        ax.set_title("HOLD: body rate")
        fig.tight_layout()
        p = os.path.join(out, "rate.png")
        fig.savefig(p, dpi=110)
        plt.close(fig)
        paths.append(p)
    if R["cmd"]:
        C = np.array(R["cmd"], dtype=float)
        fig, ax = plt.subplots(figsize=(10, 3.5))
        ax.plot(C[:, 0], C[:, 1] * TORQUE_LSB_NM, label="torque command (GNC_CMD)")
        ax.set_xlabel("time [s]")
        ax.set_ylabel("torque [N m]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
        fig.tight_layout()
        p = os.path.join(out, "torque.png")
        fig.savefig(p, dpi=110)
        plt.close(fig)
        paths.append(p)
    return paths
