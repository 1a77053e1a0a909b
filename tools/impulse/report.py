"""Report of one RENDEZVOUS (impulse scheduler) SIL log (spec 50 §7): summary and plots. Called
by `python -m tools.sil report LOG --out DIR [--summary S.json]` (tools/sil/report.py finds this
module from the log's telemetry layout and writes the files).

Plots: DIR/{trajectory,cyclogram,miss}.png, always from the log.

Figures. Truth (GNC_TRUTH of the CW plant, sim/impulse/cw_sil_plant.hpp) gives the terminal miss
and the delta-v; the flight telemetry (the mission's layout, tools.iface) the plans, iterations,
flags and the predicted miss; GNC_CMD the thruster windows; GNC_FSW_CMD the START command (t0,
t_f). Computed as the live metrics do (hil_host/missions/impulse/imp_metrics.cpp): with
--summary those (SUMMARY_KEYS) are the run summary's; thrust factors, residuals, the
per-thruster delta-v and the predicted miss are the log's alone.
"""
import math
import os

import numpy as np

from tools.sil.report import Key, read_log

THR = ["+x", "-x", "+y", "-y", "+z", "-z"]   # thruster j (fsw/impulse/imp_iface.py THR: px mx py my pz mz)
AXES = "xyz"                                  # axis r of the STUCK_OFF / STUCK_ON health fields
ACT_MASK = 12                                 # actuator channel of the on-mask (imp_iface actuators)

# The run summary's figures of this mission (imp_metrics.cpp) <-> this report's; the scheduler's
# last telemetry (fsw_imp_*) comes with tools.sil.report.CORE_KEYS' "fsw.*". All are the same
# definitions on the same doubles, so all are exact.
SUMMARY_KEYS = [
    Key("miss_r_m", "miss_r_m", optional=True),        # |R| at t_f (truth seq == t_f step)
    Key("miss_v_mps", "miss_v_mps", optional=True),
    Key("dv_used_mps", "dv_used_mps"),                 # sum over the thrusters, in thruster order
    Key("iterations_max.xy", "max_iters_xy"),
    Key("iterations_max.z", "max_iters_z"),
    Key("interlock_violations", "interlock_violations"),
    Key("tf_step", "t_f_step"),
    Key("thruster_on_steps", "thruster_on_steps"),      # GNC_CMD messages with any thruster on
    Key("imp_health_or", "imp_health_sticky"),          # OR of imp_health over the run
    Key("t_first_s.*", "t_first_*"),                   # first telemetry time of each flag / mode
]


def _modes(mission):
    for e in mission.iface.enums:
        if e.name == "mode":
            return e.by_value()
    return {}


def flag_names(mission, word):
    """The scheduler's health flags set in word: single bits by name, the per-axis fields as
    NAME_<axis>; the MODE field (the scheduler mode, not a flag) left out."""
    out = []
    for b in mission.iface.health:
        if b.name == "MODE":
            continue
        v = (int(word) & b.mask) >> b.shift
        if b.single:
            out += [b.name] if v else []
        else:
            out += ["%s_%s" % (b.name, AXES[r] if r < len(AXES) else r) for r in range(32) if v >> r & 1]
    return out


def first_keys(mission):
    """The live metrics' t_first names: each health flag but MODE (mask), then each scheduler
    mode (value; a mode named like a flag gets _MODE), as imp_metrics.cpp builds them."""
    flags = [(b.name, b.mask) for b in mission.iface.health if b.name != "MODE"]
    names = {f for f, _ in flags}
    modes = {v: (n + "_MODE" if n in names else n) for v, n in _modes(mission).items()}
    return flags, modes


def read(path, lcm_py, mission):
    start_id = mission.tc_id("START")
    tru, cmd, fcmd = {}, {}, []
    on = [0]

    def on_cmd(m):
        cmd[m.seq] = (m.utime * 1e-6, m.counts[ACT_MASK], m.fsw_mode, m.fsw_health) + tuple(m.counts[0:12])
        if m.n_counts > ACT_MASK and m.counts[ACT_MASK] != 0:
            on[0] += 1

    C = read_log(path, lcm_py, mission, {
        "GNC_TRUTH": lambda m: tru.__setitem__(m.seq, (m.utime * 1e-6,) + tuple(m.state[:14]) + tuple(m.extra[:3])),
        "GNC_CMD": on_cmd,
        "GNC_FSW_CMD": lambda m: fcmd.append(dict(utime=m.utime, apply_seq=m.apply_seq, cmd=m.cmd, args=list(m.args))),
    })
    seqs = sorted(tru)
    T = np.array([tru[s] for s in seqs]) if seqs else np.zeros((0, 18))
    cs = sorted(cmd)
    Cm = np.array([cmd[s] for s in cs]) if cs else np.zeros((0, 16))
    L = C["tlm"]
    return dict(common=C, seq=np.array(seqs), T=T, cseq=np.array(cs), C=Cm, thruster_on_msgs=on[0],
                tseq=L["seq"] if L else np.zeros(0), tutime=L["utime"] if L else np.zeros(0),
                raw=L["raw"] if L else None, real=L["real"] if L else None,
                start=[c for c in fcmd if c["cmd"] == start_id])


def metrics(R, mission, m):
    """Adds the scheduler's figures, all derived from the log, to m (tools.sil's common ones)."""
    T, raw = R["T"], R["raw"]
    omega = float(T[0, 15]) if len(T) else 1.131367e-3
    a_nom = float(T[0, 16]) if len(T) else 0.04
    L, V = a_nom / omega ** 2, a_nom / omega
    start = R["start"]
    tf = start[0]["args"][1] if start else None
    t0 = start[0]["args"][0] if start else None
    m.update(omega_radps=omega, a_nom_mps2=a_nom, length_unit_m=L, velocity_unit_mps=V, t0_step=t0, tf_step=tf)
    if tf is not None and tf in set(R["seq"].tolist()):
        x = T[int(np.where(R["seq"] == tf)[0][0]), 1:7]
        m["miss_r_m"] = math.sqrt(x[0] * x[0] + x[2] * x[2] + x[4] * x[4])
        m["miss_v_mps"] = math.sqrt(x[1] * x[1] + x[3] * x[3] + x[5] * x[5])
        m["miss_m"] = [float(x[0]), float(x[2]), float(x[4])]
        m["miss_mps"] = [float(x[1]), float(x[3]), float(x[5])]
    if len(T):
        dv = [float(v) for v in T[-1, 7:13]]
        s = 0.0
        for v in dv:            # in thruster order, as the live metrics add them
            s += v
        m["dv_used_mps"] = s
        m["dv_per_thruster_mps"] = {THR[j]: dv[j] for j in range(6)}
        m["interlock_violations"] = int(T[-1, 13])
        m["short_burns"] = int(T[-1, 14])
    m["thruster_on_steps"] = R["thruster_on_msgs"]
    if raw is not None:
        last = {k: int(v[-1]) for k, v in raw.items()}
        names = _modes(mission)
        for k in ("plans", "plans_failed", "plans_late", "plans_skipped", "plans_kept", "cmd_rej", "nav_rej",
                  "cal_rej", "mode", "rej_reason", "iters_xy", "iters_z", "how_xy", "how_z", "pattern", "fres_xy",
                  "fres_z", "stuck_j"):
            m["fsw"]["imp_" + k] = last["imp_" + k]
        m["iterations_max"] = {"xy": int(raw["imp_iters_xy"].max()), "z": int(raw["imp_iters_z"].max())}
        m["imp_mode_final"] = names.get(last["imp_mode"], last["imp_mode"])
        m["imp_modes_seen"] = [names.get(int(v), int(v)) for v in np.unique(raw["imp_mode"])]
        h = raw["imp_health"].astype(np.int64)
        m["imp_health_or"] = int(np.bitwise_or.reduce(h))
        m["imp_flags_seen"] = flag_names(mission, m["imp_health_or"])
        # first telemetry time (its utime, s) of each flag and each scheduler mode
        flags, modes = first_keys(mission)
        ts = R["tutime"] * 1e-6
        first = {}
        for nm, mask in flags:
            hit = np.nonzero(h & mask)[0]
            if len(hit):
                first[nm] = float(ts[hit[0]])
        mode = raw["imp_mode"].astype(np.int64)
        for v, nm in modes.items():
            hit = np.nonzero(mode == v)[0]
            if len(hit):
                first[nm] = float(ts[hit[0]])
        m["t_first_s"] = dict(sorted(first.items(), key=lambda kv: (kv[1], kv[0])))
        m["fx_status_sticky"] = "0x%02X" % (last["imp_st_sticky"] & 0xFF)
        m["alpha_final"] = {THR[j]: float(R["real"]["imp_alpha_" + t][-1])
                            for j, t in enumerate(["px", "mx", "py", "my", "pz", "mz"])}
    return m


def format_summary(m, src):
    """The scheduler's lines; src.tag(...) marks the log-derived ones when a run summary is in use."""
    o = ["  CW                omega %.6e rad/s, a_nom %.3f m/s^2 (length unit %.1f m, velocity unit %.4f m/s)%s" % (
             m["omega_radps"], m["a_nom_mps2"], m["length_unit_m"], m["velocity_unit_mps"], src.tag("omega_radps")),
         "  START             t0 step %s, t_f step %s%s" % (m.get("t0_step"), m.get("tf_step"), src.tag("t0_step", "tf_step"))]
    if "miss_r_m" in m and m["miss_r_m"] >= 0:
        o.append("  terminal miss     |dR| %.4f m, |dV| %.6f m/s%s" % (m["miss_r_m"], m["miss_v_mps"],
                                                                     src.tag("miss_r_m", "miss_v_mps")))
        if "miss_m" in m:
            o.append("                    x, y, z: %s m%s" % (", ".join("%.3f" % v for v in m["miss_m"]), src.tag("miss_m")))
    else:
        o.append("  terminal miss     (no truth sample at t_f)")
    if "dv_used_mps" in m:
        o.append("  delta-v used      %.4f m/s%s" % (m["dv_used_mps"], src.tag("dv_used_mps")))
        if "dv_per_thruster_mps" in m:
            o.append("                    %s%s" % (", ".join("%s %.3f" % kv for kv in m["dv_per_thruster_mps"].items()),
                                                  src.tag("dv_per_thruster_mps")))
        o.append("  interlock viol.   %d; thruster-on steps %d%s" % (m["interlock_violations"], m["thruster_on_steps"],
                                                                     src.tag("interlock_violations", "thruster_on_steps")))
        if "short_burns" in m:
            o.append("  short burns       %d%s" % (m["short_burns"], src.tag("short_burns")))
    if "imp_health_or" in m:
        f = m["fsw"]
        o.append("  plans             %d (failed %d, late %d, skipped %d, kept %d); cmd_rej %d, nav_rej %d, cal_rej %d%s" % (
            f["imp_plans"], f["imp_plans_failed"], f["imp_plans_late"], f["imp_plans_skipped"], f["imp_plans_kept"],
            f["imp_cmd_rej"], f["imp_nav_rej"], f["imp_cal_rej"], src.tag("fsw.imp_plans", "fsw.imp_cal_rej")))
        o.append("  iterations        last x-y %d, z %d; max x-y %d, z %d%s" % (
            f["imp_iters_xy"], f["imp_iters_z"], m["iterations_max"]["xy"], m["iterations_max"]["z"],
            src.tag("fsw.imp_iters_xy", "iterations_max.xy", "iterations_max.z")))
        o.append("  final |F|         %d / %d LSB%s" % (f["imp_fres_xy"], f["imp_fres_z"], src.tag("fsw.imp_fres_xy")))
        modes = _modes(src.mission)
        o.append("  scheduler modes   %s; final %s%s" % (" ".join(str(x) for x in m["imp_modes_seen"]),
                                                         modes.get(f["imp_mode"], f["imp_mode"]), src.tag("imp_modes_seen")))
        hs = m["imp_health_or"]
        o.append("  health OR         0x%08X %s%s" % (hs, " ".join(flag_names(src.mission, hs)) or "(no flag)",
                                                      src.tag("imp_health_or")))
        tf = m.get("t_first_s", {})
        o.append("  first seen [s]    %s%s" % (", ".join("%s %.1f" % kv for kv in sorted(tf.items(), key=lambda kv: (kv[1], kv[0])))
                                               or "none", src.tag(*("t_first_s." + k for k in tf))))
        o.append("  thrust factors    %s%s" % (", ".join("%s %.4f" % kv for kv in m["alpha_final"].items()),
                                               src.tag("alpha_final")))
        o.append("  fx status sticky  %s%s" % (m["fx_status_sticky"], src.tag("fx_status_sticky")))
    return "\n".join(o) + "\n"


def plots(R, m, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    T, C = R["T"], R["C"]
    paths = []
    if len(T):
        t = T[:, 0]
        fig, ax = plt.subplots(1, 2, figsize=(12, 5))
        ax[0].plot(T[:, 1] / 1000.0, T[:, 3] / 1000.0, label="chaser (x, y)")
        ax[0].plot([0], [0], "k*", ms=12, label="target")
        ax[0].plot([T[0, 1] / 1000.0], [T[0, 3] / 1000.0], "go", label="start")
        ax[0].set_xlabel("x along-track [km]")
        ax[0].set_ylabel("y radial, towards the Earth [km]")
        ax[0].invert_yaxis()
        ax[0].grid(alpha=0.3)
        ax[0].legend(fontsize=8)
        ax[0].set_title("Relative trajectory in the orbit plane")
        for k, nm in ((1, "x"), (3, "y"), (5, "z")):
            ax[1].plot(t, T[:, k] / 1000.0, label=nm)
        ax[1].set_xlabel("time [s]")
        ax[1].set_ylabel("position [km]")
        ax[1].grid(alpha=0.3)
        ax[1].legend(fontsize=8)
        ax[1].set_title("Position components (CW truth)")
        fig.tight_layout()
        p = os.path.join(out, "trajectory.png")
        fig.savefig(p, dpi=110)
        plt.close(fig)
        paths.append(p)
    if len(C):
        t = C[:, 0]
        mask = C[:, 1].astype(int)
        fig, ax = plt.subplots(figsize=(12, 4))
        h = (t[1] - t[0]) if len(t) > 1 else 0.1
        for j in range(6):
            on = (mask >> j) & 1
            # contiguous on-runs as bars
            d = np.diff(np.concatenate([[0], on, [0]]))
            s, e = np.nonzero(d == 1)[0], np.nonzero(d == -1)[0]
            ax.broken_barh([(t[a], (e[i] - a) * h) for i, a in enumerate(s)], (5 - j - 0.4, 0.8),
                           color="C%d" % (j // 2))
        ax.set_yticks(range(6))
        ax.set_yticklabels(THR[::-1])
        ax.set_xlabel("time [s]")
        ax.set_title("Thruster cyclogram (commanded on-windows, GNC_CMD)")
        ax.grid(axis="x", alpha=0.3)
        fig.tight_layout()
        p = os.path.join(out, "cyclogram.png")
        fig.savefig(p, dpi=110)
        plt.close(fig)
        paths.append(p)
    if R["raw"] is not None and len(T):
        real = R["real"]
        h = (T[1, 0] - T[0, 0]) if len(T) > 1 else 0.1
        t = R["tseq"] * h
        L, V = m["length_unit_m"], m["velocity_unit_mps"]
        dr = np.sqrt(sum(real["imp_miss_" + s] ** 2 for s in ("x", "y", "z"))) * L
        dvv = np.sqrt(sum(real["imp_miss_" + s] ** 2 for s in ("xd", "yd", "zd"))) * V
        fig, ax = plt.subplots(figsize=(12, 4.5))
        ax.semilogy(t, np.maximum(dr, 1e-4), label="predicted terminal |dR| after rounding (flight telemetry)")
        ax.semilogy(t, np.maximum(dvv * 100.0, 1e-4), label="predicted |dV| x 100 s")
        if "miss_r_m" in m:
            tf = m["tf_step"] * h
            ax.semilogy([tf], [max(m["miss_r_m"], 1e-4)], "r*", ms=14, label="true |dR| at t_f = %.3f m" % m["miss_r_m"])
        ax.set_xlabel("time [s]")
        ax.set_ylabel("[m]")
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=8)
        ax.set_title("Terminal miss: predicted by each plan, and the true one")
        fig.tight_layout()
        p = os.path.join(out, "miss.png")
        fig.savefig(p, dpi=110)
        plt.close(fig)
        paths.append(p)
    return paths
