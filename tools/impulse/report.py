"""Run report of one rendezvous SIL log (spec 50 §7): summary and plots.

    python -m tools.sil report LOG --out DIR       (dispatched here for a RENDEZVOUS log)

Writes DIR/summary.txt, DIR/summary.json and DIR/{trajectory,cyclogram,miss}.png.
Truth (GNC_TRUTH of the CW plant, sim/impulse/cw_sil_plant.hpp) gives the terminal miss and the
delta-v; the flight telemetry (layout fsw_tlm_formats_rdv.json) gives the plans, iterations and
the predicted miss; GNC_CMD gives the thruster windows.
"""
import json
import math
import os

import numpy as np

from tools.sil import lcmio
from tools.sil.tlm import Layout, ROOT

FORMATS_RDV = os.path.join(ROOT, "fsw", "app", "fsw_tlm_formats_rdv.json")
RDV_LAYOUT = 0x00020001
THR = ["+x", "-x", "+y", "-y", "+z", "-z"]
IMP_MODES = ["IDLE", "PLANNING", "ARMED", "FIRING", "FINAL", "DONE", "INFEASIBLE", "NO_SOLUTION", "ABORTED",
             "FAULT"]
IMP_FLAGS = [(12, "INFEASIBLE"), (13, "NO_SOLUTION"), (14, "MARGINAL"), (15, "NAV_STALE"), (16, "THRUST_LEVEL"),
             (17, "EXPECTED_MISS"), (18, "INTERLOCK"), (19, "STUCK_OFF_x"), (20, "STUCK_OFF_y"),
             (21, "STUCK_OFF_z"), (22, "STUCK_ON_x"), (23, "STUCK_ON_y"), (24, "STUCK_ON_z"), (25, "CMD_REJ")]


def is_rdv_log(path, lcm_py=None):
    """True when the log's flight telemetry is the RENDEZVOUS layout."""
    gnc = lcmio.load_types(lcm_py)
    for _, ch, data in lcmio.events(path):
        if ch == "GNC_TLM":
            return gnc.fsw_tlm_frame_t.decode(data).tlm_layout_version == RDV_LAYOUT
    return False


def read(path, lcm_py=None):
    gnc = lcmio.load_types(lcm_py)
    lay = Layout(FORMATS_RDV)
    tru, cmd, tlm, fcmd = {}, {}, {}, []
    n = {}
    for _, ch, data in lcmio.events(path):
        n[ch] = n.get(ch, 0) + 1
        if ch == "GNC_TRUTH":
            m = gnc.sim_truth_t.decode(data)
            tru[m.seq] = (m.utime * 1e-6,) + tuple(m.state[:14]) + tuple(m.extra[:3])
        elif ch == "GNC_CMD":
            m = gnc.actuator_cmd_t.decode(data)
            cmd[m.seq] = (m.utime * 1e-6, m.counts[12], m.fsw_mode, m.fsw_health) + tuple(m.counts[0:12])
        elif ch == "GNC_TLM":
            m = gnc.fsw_tlm_frame_t.decode(data)
            if m.tlm_layout_version == RDV_LAYOUT:
                tlm[m.seq] = bytes(m.tlm[:m.tlm_len])
        elif ch == "GNC_FSW_CMD":
            m = gnc.fsw_cmd_t.decode(data)
            fcmd.append(dict(utime=m.utime, apply_seq=m.apply_seq, cmd=m.cmd, args=list(m.args)))
    seqs = sorted(tru)
    T = np.array([tru[s] for s in seqs]) if seqs else np.zeros((0, 18))
    cs = sorted(cmd)
    C = np.array([cmd[s] for s in cs]) if cs else np.zeros((0, 16))
    ts = sorted(tlm)
    raw = lay.decode_many([tlm[s] for s in ts]) if ts else None
    return dict(seq=np.array(seqs), T=T, cseq=np.array(cs), C=C, tseq=np.array(ts), raw=raw,
                real=lay.scaled_many(raw) if raw is not None else None, counts=n, commands=fcmd)


def metrics(R):
    T, raw = R["T"], R["raw"]
    m = {}
    omega = float(T[0, 15]) if len(T) else 1.131367e-3
    a_nom = float(T[0, 16]) if len(T) else 0.04
    L, V = a_nom / omega ** 2, a_nom / omega
    start = [c for c in R["commands"] if c["cmd"] == 2]
    tf = start[0]["args"][1] if start else None
    t0 = start[0]["args"][0] if start else None
    m.update(omega_radps=omega, a_nom_mps2=a_nom, length_unit_m=L, velocity_unit_mps=V, t0_step=t0, tf_step=tf)
    if tf is not None and tf in set(R["seq"].tolist()):
        i = int(np.where(R["seq"] == tf)[0][0])
        x = T[i, 1:7]
        m["miss_r_m"] = float(math.sqrt(x[0] ** 2 + x[2] ** 2 + x[4] ** 2))
        m["miss_v_mps"] = float(math.sqrt(x[1] ** 2 + x[3] ** 2 + x[5] ** 2))
        m["miss_m"] = [float(x[0]), float(x[2]), float(x[4])]
        m["miss_mps"] = [float(x[1]), float(x[3]), float(x[5])]
    if len(T):
        dv = T[-1, 7:13]
        m["dv_used_mps"] = float(dv.sum())
        m["dv_per_thruster_mps"] = {THR[j]: float(dv[j]) for j in range(6)}
        m["interlock_violations"] = int(T[-1, 13])
        m["short_burns"] = int(T[-1, 14])
    if raw is not None:
        last = {k: int(v[-1]) for k, v in raw.items()}
        m["plans"] = last["imp_plans"]
        for k in ("plans_failed", "plans_late", "plans_skipped", "plans_kept", "cmd_rej", "nav_rej", "cal_rej"):
            m[k] = last["imp_" + k]
        m["iterations_last"] = {"xy": last["imp_iters_xy"], "z": last["imp_iters_z"]}
        m["iterations_max"] = {"xy": int(raw["imp_iters_xy"].max()), "z": int(raw["imp_iters_z"].max())}
        m["final_residual_lsb"] = {"xy": last["imp_fres_xy"], "z": last["imp_fres_z"]}
        m["imp_mode_final"] = IMP_MODES[last["imp_mode"]] if last["imp_mode"] < len(IMP_MODES) else last["imp_mode"]
        modes = sorted(set(int(v) for v in raw["imp_mode"]))
        m["imp_modes_seen"] = [IMP_MODES[v] if v < len(IMP_MODES) else v for v in modes]
        hs = int(np.bitwise_or.reduce(raw["imp_health"].astype(np.int64)))
        m["imp_health_sticky"] = "0x%08X" % hs
        m["imp_flags_seen"] = [nm for b, nm in IMP_FLAGS if hs & (1 << b)]
        first = {}
        tsec = R["tseq"] * 0.0 + 0.0
        if len(T):
            h = (T[1, 0] - T[0, 0]) if len(T) > 1 else 0.1
            tsec = R["tseq"] * h
        for b, nm in IMP_FLAGS:
            hit = np.nonzero(raw["imp_health"].astype(np.int64) & (1 << b))[0]
            if len(hit):
                first[nm] = float(tsec[hit[0]])
        m["t_first_flag_s"] = first
        m["fx_status_sticky"] = "0x%02X" % (last["imp_st_sticky"] & 0xFF)
        m["alpha_final"] = {THR[j]: float(R["real"]["imp_alpha_" + t][-1])
                            for j, t in enumerate(["px", "mx", "py", "my", "pz", "mz"])}
        m["fsw_mode_final"] = last["mode"]
        m["n_safe"] = last["n_safe"]
        m["n_tc"], m["n_tc_rej"] = last["n_tc"], last["n_tc_rej"]
    m["messages"] = R["counts"]
    return m


def format_summary(m):
    o = ["Rendezvous SIL report (spec 50 §7)",
         "  CW, omega %.6e rad/s, a_nom %.3f m/s^2 (length unit %.1f m, velocity unit %.4f m/s)" % (
             m["omega_radps"], m["a_nom_mps2"], m["length_unit_m"], m["velocity_unit_mps"]),
         "  t0 step %s, t_f step %s" % (m.get("t0_step"), m.get("tf_step"))]
    if "miss_r_m" in m:
        o.append("  terminal miss     |dR| %.4f m, |dV| %.6f m/s  (x, y, z: %s m)" % (
            m["miss_r_m"], m["miss_v_mps"], ", ".join("%.3f" % v for v in m["miss_m"])))
    else:
        o.append("  terminal miss     (no truth sample at t_f)")
    if "dv_used_mps" in m:
        o.append("  delta-v used      %.4f m/s  (%s)" % (m["dv_used_mps"], ", ".join(
            "%s %.3f" % (k, v) for k, v in m["dv_per_thruster_mps"].items())))
        o.append("  interlock violations %d, short burns %d" % (m["interlock_violations"], m["short_burns"]))
    if "plans" in m:
        o.append("  plans             %d (failed %d, late %d, skipped %d, kept %d); cmd_rej %d, nav_rej %d, cal_rej %d" % (
            m["plans"], m["plans_failed"], m["plans_late"], m["plans_skipped"], m["plans_kept"], m["cmd_rej"],
            m["nav_rej"], m["cal_rej"]))
        o.append("  iterations        last x-y %d, z %d; max x-y %d, z %d; final |F| %d / %d LSB" % (
            m["iterations_last"]["xy"], m["iterations_last"]["z"], m["iterations_max"]["xy"],
            m["iterations_max"]["z"], m["final_residual_lsb"]["xy"], m["final_residual_lsb"]["z"]))
        o.append("  scheduler modes   %s; final %s" % (" ".join(str(x) for x in m["imp_modes_seen"]), m["imp_mode_final"]))
        o.append("  health sticky     %s %s" % (m["imp_health_sticky"], " ".join(m["imp_flags_seen"])))
        o.append("  first flags [s]   %s" % (", ".join("%s %.1f" % kv for kv in m["t_first_flag_s"].items()) or "none"))
        o.append("  thrust factors    %s" % ", ".join("%s %.4f" % kv for kv in m["alpha_final"].items()))
        o.append("  fx status sticky  %s; SAFE entries %d; telecommands %d taken, %d refused" % (
            m["fx_status_sticky"], m["n_safe"], m["n_tc"], m["n_tc_rej"]))
    o.append("  messages          %s" % ", ".join("%s %d" % kv for kv in sorted(m["messages"].items())))
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


def main(args):
    R = read(args.log, args.lcm_py)
    m = metrics(R)
    os.makedirs(args.out, exist_ok=True)
    text = format_summary(m)
    print(text, end="")
    with open(os.path.join(args.out, "summary.txt"), "w") as fh:
        fh.write(text)
    js = json.dumps(m, indent=1) + "\n"
    for p in [os.path.join(args.out, "summary.json")] + ([args.json] if args.json else []):
        with open(p, "w") as fh:
            fh.write(js)
    if not args.no_plots:
        for p in plots(R, m, args.out):
            print("wrote %s" % p)
    return 0
