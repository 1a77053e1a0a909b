"""Report of one DETUMBLE (observer) SIL log: settling metrics, estimate errors, faults, plots
(10-observer §6, §7). Called by `python -m tools.sil report LOG --out DIR [--summary S.json]`
(tools/sil/report.py finds this module from the log's telemetry layout and writes the files).

Plots: DIR/{rates,mu,khat,gimbal,innov}.png, always from the log.

Figures. The truth (GNC_TRUTH) gives the settling metrics, computed as the live metrics do
(hil_host/missions/observer/obs_metrics.cpp) so that both agree to the bit: t = utime of the
truth sample, h = the truth sample spacing, |w| = hypot(w_y / deg, w_z / deg); t_s = last t with
|w| >= 0.01 deg/s plus h, t_s+ = last t with |w| >= 0.01 deg/s or max(|mu_y|, |mu_z|) >= 0.01 deg,
plus h (0 if never above); the tail is t >= T_end - 20 s, T_end = end of the last step. With
--summary those (SUMMARY_KEYS) are the run summary's; the estimate errors, gimbal angles, K-hat
band, innovations and sensor flags are the log's alone.
"""
import math
import os

import numpy as np

from tools.sil.report import Key, bits_str, columns, last_per_seq, mode_name, read_log
from tools.sil import lcmio

DEG = math.pi / 180.0
LSB = 2.0 ** -20          # rad/s per gyro / gimbal-rate count (the observer tables' count scale)
W_THR = 0.01              # deg/s
MU_THR = 0.01             # deg
TAIL_S = 20.0             # the "last 20 s" of spec 10 §6
LS6 = -1                  # table ls[6] of the shipped tables: var(kappa) = pkk * 4^ls6
# Telemetry x_hat of step k is published after the time update (obs.c: predict, then publish), so
# it is the prediction x_hat(k+1|k): it is compared with, and plotted at, truth sample k + EST_LAG.
EST_LAG = 1

# The run summary's figures of this mission (obs_metrics.cpp) <-> this report's; the module
# counters (fsw_obs_n_*, fsw_obs_revision) come with tools.sil.report.CORE_KEYS' "fsw.*".
# All are the same definitions on the same doubles, so all are exact.
SUMMARY_KEYS = [
    Key("t_s", "t_s_s"),
    Key("t_s_plus", "t_s_plus_s"),
    Key("K_hat_final", "k_hat_final_per_s2"),        # 0.01 * kappa_q28 / 2^28 of the last telemetry
    Key("k2_true", "k_true_per_s2"),                 # truth extra[0] of the last sample
    Key("peak_abs_bdot_cmd_degs.max", "peak_bdot_degps"),
    Key("peak_abs_mu_deg.max", "peak_mu_deg"),
    Key("peak_abs_w_degs.axis_max", "peak_w_degps"),  # max over samples and axes of |w_y|, |w_z|
    Key("w_end_degs", "w_final_degps"),
    Key("last_20s.max_abs_w_degs", "max_w_tail_degps"),
    Key("last_20s.max_abs_mu_deg", "max_mu_tail_deg"),
    Key("t_cmd_limit_persist_s", "t_cmd_limit_persist_s"),   # first CMD_LIMIT_PERSIST, -1 never
    Key("obs_health_or", "obs_health_sticky"),       # OR of obs_health over the run
]
_SENSOR = ["utime", "seq", "period_us", "gy", "gz", "st_y", "st_z", "scenario_flags", "plant_flags"]
_CMD = ["utime", "seq", "cy", "cz", "mode", "health"]
_TRUTH = ["utime", "seq", "wy", "wz", "muy", "mudy", "muz", "mudz", "by", "bz",
          "k2", "bdot_y", "bdot_z", "sigma", "jf", "events"]


# ----------------------------------------------------------------------------------------------
# Reading

def read(path, lcm_py, mission):
    """Decode a log into per-channel numpy columns. Repeated seqs (retransmissions, cached
    commands) are kept in the raw counts but the series keep the last message of each seq.
    Truth of the sail plant (sim/observer/sail_plant.hpp): state[0..7] w_y, w_z, mu_y, mudot_y,
    mu_z, mudot_z, beta_y, beta_z; extra[0..4] k^2, bdot_y, bdot_z applied, sigma, J factor."""
    gnc = lcmio.load_types(lcm_py)
    sen, cmd, tru = [], [], []
    C = read_log(path, lcm_py, mission, {
        "GNC_SENSOR": lambda m: sen.append((m.utime, m.seq, m.period_us, m.counts[0], m.counts[1], m.status[0],
                                            m.status[1], m.scenario_flags, m.plant_flags)),
        "GNC_CMD": lambda m: cmd.append((m.utime, m.seq, m.counts[0], m.counts[1], m.fsw_mode, m.fsw_health)),
        "GNC_TRUTH": lambda m: tru.append((m.utime, m.seq) + tuple(m.state[:8]) + tuple(m.extra[:5]) + (m.events,)),
    })
    S, n_sen = last_per_seq(sen, _SENSOR)
    S_all = columns(sen, _SENSOR)
    Cm, n_cmd = last_per_seq(cmd, _CMD)
    T, n_tru = last_per_seq(tru, _TRUTH)
    sf = gnc.sensor_frame_v2_t
    return dict(common=C, sensor=S, sensor_all=S_all, n_sensor_msgs=n_sen, cmd=Cm, n_cmd_msgs=n_cmd,
                truth=T, n_truth_msgs=n_tru, tlm=C["tlm"],
                flags=dict(stale=sf.STATUS_STALE, sat=sf.STATUS_SAT, diverged=sf.PLANT_DIVERGED, retx=sf.PLANT_RETX))


def aligned(R, lag=EST_LAG):
    """Truth-seq-aligned series: for each truth sample j, the telemetry of seq j - lag and the
    command of seq j (NaN where that message is missing). Returns dict of float arrays."""
    T, L, C = R["truth"], R["tlm"], R["cmd"]
    seq = T["seq"]
    out = {"seq": seq, "t": T["utime"] * 1e-6}

    def pick(src_seq, want, col):
        v = np.full(len(want), np.nan)
        if len(src_seq) == 0:
            return v
        i = np.clip(np.searchsorted(src_seq, want), 0, len(src_seq) - 1)
        ok = src_seq[i] == want
        v[ok] = col[i[ok]]
        return v

    if L:
        for k in ("obs_x_wy", "obs_x_wz", "obs_x_muy", "obs_x_mudoty", "obs_x_muz", "obs_x_mudotz", "obs_kappa"):
            out[k] = pick(L["seq"], seq - lag, L["real"][k])
    if len(C["seq"]):
        out["cy"] = pick(C["seq"], seq, C["cy"].astype(np.float64))
        out["cz"] = pick(C["seq"], seq, C["cz"].astype(np.float64))
    return out


# ----------------------------------------------------------------------------------------------
# Metrics

def _health_bit(mission, name):
    for b in mission.iface.health:
        if b.name == name:
            return b.mask
    raise KeyError("%s health has no bit %s (fsw/%s/%s_iface.py)" % (mission.module, name, mission.module,
                                                                     mission.prefix))


def metrics(R, mission, out):
    """Adds the observer's figures, all derived from the log, to out (tools.sil's common ones)."""
    T, S, C, L = R["truth"], R["sensor"], R["cmd"], R["tlm"]
    if len(S["seq"]):
        periods = np.unique(S["period_us"])
        h = float(periods[0]) * 1e-6
        out["period_us"] = int(periods[0])
        if len(periods) > 1:
            out["period_us_all"] = [int(p) for p in periods]
    elif len(T["seq"]) > 1:
        h = float(np.median(np.diff(T["utime"]))) * 1e-6
        out["period_us"] = int(round(h * 1e6))
        out["period_note"] = "no GNC_SENSOR: period from truth utime spacing"
    else:
        raise SystemExit("sil report: log has neither GNC_SENSOR nor GNC_TRUTH frames")
    out["h_s"] = h
    out["steps"] = {"sensor_seqs": int(len(S["seq"])), "cmd_seqs": int(len(C["seq"])),
                    "tlm_seqs": int(len(L["seq"])) if L else 0, "truth_seqs": int(len(T["seq"]))}
    if len(S["seq"]):
        seq = S["seq"]
        out["steps"]["sensor_seq_range"] = [int(seq[0]), int(seq[-1])]
        out["steps"]["sensor_seq_missing"] = int(seq[-1] - seq[0] + 1 - len(seq))
    if len(T["seq"]):
        t = T["utime"] * 1e-6
        ht = float(t[1] - t[0]) if len(t) > 1 else h    # the live metrics' h: truth spacing
        sig = T["sigma"][-1]
        out["model"] = "M-phys" if sig > 0 else ("M-paper" if sig < 0 else "unknown (sigma 0)")
        out["sigma"] = float(sig)
        out["j_factor"] = float(T["jf"][-1])
        out["t0_s"] = float(t[0])
        out["t_end_s"] = float(t[-1])
        out["duration_s"] = float(t[-1] - t[0] + h)
        wy, wz = T["wy"] / DEG, T["wz"] / DEG
        w = np.hypot(wy, wz)
        mu = np.maximum(np.abs(T["muy"]), np.abs(T["muz"])) / DEG
        above = np.nonzero(w >= W_THR)[0]
        above_p = np.nonzero((w >= W_THR) | (mu >= MU_THR))[0]
        out["t_s"] = float(t[above[-1]] + ht) if len(above) else 0.0
        out["t_s_plus"] = float(t[above_p[-1]] + ht) if len(above_p) else 0.0
        out["settled"] = bool(len(above) == 0 or above[-1] < len(t) - 1)
        out["settled_plus"] = bool(len(above_p) == 0 or above_p[-1] < len(t) - 1)
        out["k2_true"] = float(T["k2"][-1])
        out["peak_abs_mu_deg"] = {"y": float(np.max(np.abs(T["muy"])) / DEG), "z": float(np.max(np.abs(T["muz"])) / DEG),
                                  "max": float(np.max(mu))}
        py, pz = float(np.max(np.abs(wy))), float(np.max(np.abs(wz)))
        out["peak_abs_w_degs"] = {"y": py, "z": pz, "axis_max": max(py, pz), "norm": float(np.max(w))}
        out["w_end_degs"] = float(w[-1])
        # T_end = (last utime + period) / 1e6 is the scenario's duration_s to the bit for a
        # completed run (both correctly rounded from the same decimal), the live metrics' T_end
        tail = t >= (int(T["utime"][-1]) + out["period_us"]) / 1e6 - TAIL_S
        out["last_20s"] = {"max_abs_w_degs": float(np.max(w[tail])), "max_abs_mu_deg": float(np.max(mu[tail]))}
        out["peak_abs_beta_deg"] = {"y": float(np.max(np.abs(T["by"])) / DEG), "z": float(np.max(np.abs(T["bz"])) / DEG)}
        out["beta_end_deg"] = {"y": float(T["by"][-1] / DEG), "z": float(T["bz"][-1] / DEG)}
        ev = int(np.bitwise_or.reduce(T["events"].astype(np.int64))) if len(T["events"]) else 0
        out["truth_events_or"] = "0x%08X" % (ev & 0xFFFFFFFF)
        out["truth_steps_with_events"] = int(np.count_nonzero(T["events"]))
    if len(C["seq"]):
        py, pz = float(np.max(np.abs(C["cy"])) * LSB / DEG), float(np.max(np.abs(C["cz"])) * LSB / DEG)
        out["peak_abs_bdot_cmd_degs"] = {"y": py, "z": pz, "max": max(py, pz)}
        out["final_mode_cmd"] = mode_name(mission, C["mode"][-1])
        out["final_fsw_health_cmd"] = "0x%08X" % (int(C["health"][-1]) & 0xFFFFFFFF)
    if L:
        raw, real = L["raw"], L["real"]
        hb = mission.iface.health
        out["K_hat_final"] = float(0.01 * real["obs_kappa"][-1])
        out["K_hat_initial"] = float(0.01 * real["obs_kappa"][0])
        if out.get("k2_true"):
            out["K_hat_rel_err"] = out["K_hat_final"] / out["k2_true"] - 1.0
        pkk = real["obs_pkk"][-1]
        out["sigma_K_final"] = float(0.01 * math.sqrt(max(pkk, 0.0)) * 2.0 ** LS6)
        # the observer's counters and table revision: last telemetry (raw), beside the executive's
        out["fsw"].update({k: int(raw[k][-1]) for k in mission.layout.names
                           if k.startswith("obs_n_") or k == "obs_revision"})
        out["obs_health_final"] = bits_str(raw["obs_health"][-1], hb)
        out["obs_health_sticky"] = bits_str(raw["obs_health_sticky"][-1], hb)
        out["obs_health_or"] = int(np.bitwise_or.reduce(raw["obs_health"].astype(np.int64)))
        hit = np.nonzero(raw["obs_health"].astype(np.int64) & _health_bit(mission, "CMD_LIMIT_PERSIST"))[0]
        out["t_cmd_limit_persist_s"] = float(L["utime"][hit[0]] * 1e-6) if len(hit) else -1.0
        if len(T["seq"]):
            A = aligned(R)
            t = A["t"]
            last20 = t >= t[-1] - TAIL_S
            ew = np.hypot(A["obs_x_wy"] - T["wy"], A["obs_x_wz"] - T["wz"]) / DEG
            em = np.maximum(np.abs(A["obs_x_muy"] - T["muy"]), np.abs(A["obs_x_muz"] - T["muz"])) / DEG
            ok = np.isfinite(ew)

            def nmax(x, sel):
                x = x[sel & ok]
                return float(np.max(x)) if len(x) else None
            out["estimate_error"] = {
                "alignment": "tlm seq k (x_hat(k+1|k)) vs truth seq k+%d" % EST_LAG,
                "samples": int(np.count_nonzero(ok)),
                "max_w_err_degs_after_t_s": nmax(ew, t >= out.get("t_s", 0.0)),
                "max_w_err_degs_last_20s": nmax(ew, last20),
                "max_mu_err_deg": nmax(em, np.ones_like(ok)),
                "max_mu_err_deg_last_20s": nmax(em, last20)}
        out["peak_abs_obs_u_degs"] = {"y": float(np.max(np.abs(real["obs_u_y"])) / DEG),
                                      "z": float(np.max(np.abs(real["obs_u_z"])) / DEG)}
    Sa, fl = R["sensor_all"], R["flags"]
    if len(Sa["seq"]):
        pf = Sa["plant_flags"].astype(np.int64)
        st = (Sa["st_y"] | Sa["st_z"]).astype(np.int64)
        out["sensor_frames_retx"] = int(np.count_nonzero(pf & fl["retx"]))
        out["sensor_frames_diverged"] = int(np.count_nonzero(pf & fl["diverged"]))
        out["sensor_status_sat"] = int(np.count_nonzero(st & fl["sat"]))
        out["sensor_status_stale"] = int(np.count_nonzero(st & fl["stale"]))
        sf = int(np.bitwise_or.reduce(Sa["scenario_flags"].astype(np.int64)))
        out["scenario_flags_or"] = "0x%08X" % (sf & 0xFFFFFFFF)
    return out


def format_summary(m, src):
    """The observer's lines; src.tag(...) marks the log-derived ones when a run summary is in use."""
    g = m.get
    lines = ["  model             %s (sigma %+g, J factor %s)" % (g("model", "?"), g("sigma", 0), g("j_factor"))]
    lines.append("  period h          %d us" % g("period_us"))
    if "duration_s" in m:
        lines.append("  duration          %.3f s (t %.3f .. %.3f s)" % (m["duration_s"], m["t0_s"], m["t_end_s"]))
    st = m["steps"]
    lines.append("  steps             sensor %d, cmd %d, tlm %d, truth %d (unique seqs)"
                 % (st["sensor_seqs"], st["cmd_seqs"], st["tlm_seqs"], st["truth_seqs"]))
    if "t_s" in m:
        lines.append("  t_s               %.3f s%s%s" % (m["t_s"], "" if m["settled"] else "  (NOT SETTLED at end)",
                                                      src.tag("t_s")))
        lines.append("  t_s+              %.3f s%s%s" % (m["t_s_plus"], "" if m["settled_plus"] else "  (NOT SETTLED at end)",
                                                      src.tag("t_s_plus")))
    if "K_hat_final" in m:
        lines.append("  K_hat final       %.6g s^-2   true k^2 %.6g%s" % (m["K_hat_final"], g("k2_true", float("nan")),
                                                                        src.tag("K_hat_final", "k2_true")))
        rel = m["K_hat_final"] / m["k2_true"] - 1.0 if m.get("k2_true") else float("nan")
        lines.append("                    rel err %+.3f %%; +-3 sigma %.3g; initial %.6g%s"
                     % (100 * rel, 3 * m["sigma_K_final"], m["K_hat_initial"], src.tag("sigma_K_final")))
    if "peak_abs_bdot_cmd_degs" in m:
        p = m["peak_abs_bdot_cmd_degs"]
        lines.append("  peak |bdot| cmd   %.4f deg/s%s" % (p["max"], src.tag("peak_abs_bdot_cmd_degs.max")))
        lines.append("                    y %.4f  z %.4f deg/s%s" % (p["y"], p["z"], src.tag("peak_abs_bdot_cmd_degs.y")))
    if "peak_abs_mu_deg" in m:
        p, q = m["peak_abs_mu_deg"], m["peak_abs_w_degs"]
        lines.append("  peak |mu|         %.4f deg; peak |w_y|, |w_z| %.4f deg/s%s"
                     % (p["max"], q["axis_max"], src.tag("peak_abs_mu_deg.max", "peak_abs_w_degs.axis_max")))
        lines.append("                    |mu| y %.4f z %.4f deg; |w| y %.4f z %.4f, norm %.4f deg/s%s"
                     % (p["y"], p["z"], q["y"], q["z"], q["norm"], src.tag("peak_abs_mu_deg.y")))
        p = m["last_20s"]
        lines.append("  |w| at end        %.3g deg/s; last 20 s max |w| %.3g deg/s, max |mu| %.3g deg%s"
                     % (m["w_end_degs"], p["max_abs_w_degs"], p["max_abs_mu_deg"],
                        src.tag("w_end_degs", "last_20s.max_abs_w_degs", "last_20s.max_abs_mu_deg")))
        p, q = m["peak_abs_beta_deg"], m["beta_end_deg"]
        lines.append("  beta              peak y %.4f z %.4f deg; end y %+.4f z %+.4f deg%s"
                     % (p["y"], p["z"], q["y"], q["z"], src.tag("beta")))
        lines.append("  truth events      OR %s in %d steps%s" % (m["truth_events_or"], m["truth_steps_with_events"],
                                                                 src.tag("truth_events_or")))
        ee = m.get("estimate_error")
        if ee:
            g2 = lambda v: "n/a" if v is None else "%.3g" % v
            lines.append("  estimate error    |w| %s deg/s after t_s, %s last 20 s; |mu| %s deg max, %s last 20 s%s"
                         % (g2(ee["max_w_err_degs_after_t_s"]), g2(ee["max_w_err_degs_last_20s"]),
                            g2(ee["max_mu_err_deg"]), g2(ee["max_mu_err_deg_last_20s"]), src.tag("estimate_error")))
            lines.append("                    (%s)" % ee["alignment"])
    lines.append("Observer faults")
    if "obs_health_or" in m:
        f = m["fsw"]
        names = [k for k in f if k.startswith("obs_n_")]
        for i in range(0, len(names), 6):
            lines.append(("  obs counters      " if i == 0 else "                    ") +
                         ", ".join("%s %s" % (k[4:], f[k]) for k in names[i:i + 6]) +
                         src.tag(*("fsw." + k for k in names[i:i + 6])))
        lines.append("  obs table rev     %s%s" % (f["obs_revision"], src.tag("fsw.obs_revision")))
        lines.append("  obs health OR     %s%s" % (bits_str(m["obs_health_or"], src.mission.iface.health), src.tag("obs_health_or")))
        lines.append("  obs health final  %s%s" % (m["obs_health_final"], src.tag("obs_health_final")))
        lines.append("  obs health sticky %s (the module's own sticky word)%s" % (m["obs_health_sticky"],
                                                                                src.tag("obs_health_sticky")))
        t = m["t_cmd_limit_persist_s"]
        lines.append("  CMD_LIMIT_PERSIST %s%s" % ("never" if t < 0 else "first at t %.2f s" % t,
                                                 src.tag("t_cmd_limit_persist_s")))
    else:
        lines.append("  no observer telemetry in the log")
    if "sensor_frames_retx" in m:
        lines.append("  sensor frames     PLANT_RETX %d, PLANT_DIVERGED %d, status SAT %d, STALE %d; scenario flags OR %s%s"
                     % (m["sensor_frames_retx"], m["sensor_frames_diverged"], m["sensor_status_sat"],
                        m["sensor_status_stale"], m["scenario_flags_or"], src.tag("sensor_frames_retx")))
        lines.append("  missing seqs      %d%s" % (m["steps"].get("sensor_seq_missing", 0), src.tag("steps")))
    if "final_mode_cmd" in m:
        lines.append("  GNC_CMD final     mode %s, health %s%s" % (m["final_mode_cmd"], m["final_fsw_health_cmd"],
                                                                 src.tag("final_mode_cmd")))
    return "\n".join(lines) + "\n"


# ----------------------------------------------------------------------------------------------
# Plots

def _env(t, y, nb=1500):
    """Min/max envelope for drawing: at most 2*nb points, every extreme of each bucket kept, so
    peaks and limit cycles look the same as the full series at the plot resolution."""
    t = np.asarray(t)
    y = np.asarray(y, dtype=np.float64)
    n = len(y)
    if n <= 4 * nb:
        return t, y
    b = int(math.ceil(n / float(nb)))
    m = (n // b) * b
    yy = y[:m].reshape(-1, b)
    base = np.arange(0, m, b)
    idx = np.concatenate([base + np.argmin(yy, axis=1), base + np.argmax(yy, axis=1), np.arange(m, n), [0, n - 1]])
    idx = np.unique(idx)
    return t[idx], y[idx]


def plots(R, m, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    T, C, L = R["truth"], R["cmd"], R["tlm"]
    files = []
    tt = T["utime"] * 1e-6
    tl = L["utime"] * 1e-6 + EST_LAG * m["h_s"] if L else None   # x_hat(k+1|k) belongs to t_k+1
    real = L["real"] if L else None
    title = "%s, h = %g s" % (m.get("model", "?"), m["h_s"])
    if "scenario" in m:
        title = "%s: %s" % (m["scenario"], title)

    def save(fig, name):
        p = os.path.join(out, name)
        # fixed margins: tight_layout costs about as much as drawing on long logs
        hin = fig.get_size_inches()[1]
        fig.subplots_adjust(left=0.1, right=0.98, bottom=0.55 / hin, top=1.0 - 0.35 / hin, hspace=0.3)
        fig.savefig(p, dpi=110)
        plt.close(fig)
        files.append(p)

    def vline(ax):
        if m.get("t_s"):
            ax.axvline(m["t_s"], color="0.4", ls=":", lw=1, label="t_s = %.2f s" % m["t_s"])

    # rates
    fig, ax = plt.subplots(2, 1, figsize=(10, 7), sharex=True)
    if len(tt):
        ax[0].plot(*_env(tt, T["wy"] / DEG), "C0", lw=1.2, label="omega_y truth")
        ax[0].plot(*_env(tt, T["wz"] / DEG), "C1", lw=1.2, label="omega_z truth")
    if L:
        ax[0].plot(*_env(tl, real["obs_x_wy"] / DEG), "C0--", lw=1, label="omega_y estimate x(k+1|k)")
        ax[0].plot(*_env(tl, real["obs_x_wz"] / DEG), "C1--", lw=1, label="omega_z estimate")
    ax[0].set_ylabel("rate [deg/s]")
    ax[0].set_title("Platform rates, truth vs estimate (%s)" % title)
    if len(tt):
        wn = np.hypot(T["wy"], T["wz"]) / DEG
        ax[1].semilogy(*_env(tt, np.maximum(wn, 1e-9)), "k", lw=1, label="|omega| truth")
    if L:
        ax[1].semilogy(*_env(tl, np.maximum(np.hypot(real["obs_x_wy"], real["obs_x_wz"]) / DEG, 1e-9)), "C2--", lw=0.8,
                       label="|omega| estimate")
    ax[1].axhline(W_THR, color="r", ls="--", lw=1, label="0.01 deg/s threshold")
    vline(ax[1])
    ax[1].set_ylabel("|omega| [deg/s]")
    ax[1].set_xlabel("time [s]")
    ax[1].set_title("Rate magnitude (log scale)")
    for a in ax:
        a.grid(True, which="both", alpha=0.3)
        a.legend(loc="upper right", fontsize=8)
    save(fig, "rates.png")

    # mu
    fig, ax = plt.subplots(1, 1, figsize=(10, 5))
    if len(tt):
        ax.plot(*_env(tt, T["muy"] / DEG), "C0", lw=1.2, label="mu_y truth")
        ax.plot(*_env(tt, T["muz"] / DEG), "C1", lw=1.2, label="mu_z truth")
    if L:
        ax.plot(*_env(tl, real["obs_x_muy"] / DEG), "C0--", lw=1, label="mu_y estimate x(k+1|k)")
        ax.plot(*_env(tl, real["obs_x_muz"] / DEG), "C1--", lw=1, label="mu_z estimate")
    if m.get("t_s_plus"):
        ax.axvline(m["t_s_plus"], color="0.4", ls=":", lw=1, label="t_s+ = %.2f s" % m["t_s_plus"])
    ax.set_xlabel("time [s]")
    ax.set_ylabel("sail tilt mu [deg]")
    ax.set_title("Sail tilt, truth vs estimate (%s)" % title)
    ax.grid(True, alpha=0.3)
    ax.legend(loc="upper right", fontsize=8)
    save(fig, "mu.png")

    # khat
    fig, ax = plt.subplots(1, 1, figsize=(10, 5))
    if L:
        kh = 0.01 * real["obs_kappa"]
        sk = 0.01 * np.sqrt(np.maximum(real["obs_pkk"], 0.0)) * 2.0 ** LS6
        ax.fill_between(tl, kh - 3 * sk, kh + 3 * sk, color="C0", alpha=0.2, lw=0, label="K_hat +- 3 sigma")
        ax.plot(*_env(tl, kh), "C0", lw=1.2, label="K_hat (final %.5g)" % kh[-1])
        lo, hi = np.min(kh), np.max(kh)
        span = max(hi - lo, 1e-4)
        ax.set_ylim(lo - 0.3 * span, hi + 0.3 * span)
    if len(tt):
        ax.plot(*_env(tt, T["k2"]), "k--", lw=1, label="true k^2 = %.5g" % T["k2"][-1])
    ax.set_xlabel("time [s]")
    ax.set_ylabel("stiffness [s^-2]")
    ax.set_title("Stiffness estimate K_hat = 0.01 kappa (%s)" % title)
    ax.grid(True, alpha=0.3)
    ax.legend(loc="upper right", fontsize=8)
    save(fig, "khat.png")

    # gimbal
    fig, ax = plt.subplots(2, 1, figsize=(10, 7), sharex=True)
    if len(C["seq"]):
        tc = C["utime"] * 1e-6
        ax[0].step(*_env(tc, C["cy"] * LSB / DEG), "C0", where="post", lw=1, label="bdot_y command")
        ax[0].step(*_env(tc, C["cz"] * LSB / DEG), "C1", where="post", lw=1, label="bdot_z command")
    if len(tt):
        ax[0].step(*_env(tt, T["bdot_y"] / DEG), "C0:", where="pre", lw=1, label="bdot_y applied over [t_k-1, t_k) (truth)")
        ax[0].step(*_env(tt, T["bdot_z"] / DEG), "C1:", where="pre", lw=1, label="bdot_z applied over [t_k-1, t_k) (truth)")
        ax[1].plot(*_env(tt, T["by"] / DEG), "C0", lw=1.2, label="beta_y")
        ax[1].plot(*_env(tt, T["bz"] / DEG), "C1", lw=1.2, label="beta_z")
    ax[0].set_ylabel("gimbal rate [deg/s]")
    ax[0].set_title("Gimbal-rate commands (%s)" % title)
    ax[1].set_ylabel("gimbal angle [deg]")
    ax[1].set_xlabel("time [s]")
    ax[1].set_title("Gimbal angles (truth)")
    for a in ax:
        a.grid(True, alpha=0.3)
        a.legend(loc="upper right", fontsize=8)
    save(fig, "gimbal.png")

    # innovations
    if L:
        tk = L["utime"] * 1e-6
        fig, ax = plt.subplots(2, 1, figsize=(10, 7), sharex=True)
        ax[0].plot(*_env(tk, real["obs_e_y"] / DEG), "C0", lw=0.8, label="e_y")
        ax[0].plot(*_env(tk, real["obs_e_z"] / DEG), "C1", lw=0.8, label="e_z")
        ax[0].set_ylabel("innovation [deg/s]")
        ax[0].set_title("Innovations (%s)" % title)
        ax[1].semilogy(*_env(tk, np.maximum(real["obs_d2_y"], 2.0 ** -16)), "C0", lw=0.8, label="d^2 y")
        ax[1].semilogy(*_env(tk, np.maximum(real["obs_d2_z"], 2.0 ** -16)), "C1", lw=0.8, label="d^2 z")
        ax[1].set_ylabel("normalised innovation squared [-]")
        ax[1].set_xlabel("time [s]")
        for a in ax:
            a.grid(True, which="both", alpha=0.3)
            a.legend(loc="upper right", fontsize=8)
        save(fig, "innov.png")
    return files
