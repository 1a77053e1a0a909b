"""Run report of one SIL log: settling metrics, faults seen, plots (10-observer §6, §7).

    python -m tools.sil report LOG --out DIR [--lcm-py DIR] [--json FILE]

Writes DIR/summary.txt, DIR/summary.json and DIR/{rates,mu,khat,gimbal,innov}.png.
Truth (GNC_TRUTH) gives the metrics, exactly as tests/observer/test_obs_closed_loop_host.c:
t = utime of the truth sample, t_s = last t with |w| >= 0.01 deg/s plus h, t_s+ = last t with
|w| >= 0.01 deg/s or max(|mu_y|, |mu_z|) >= 0.01 deg, plus h (0 if never above).
"""
import json
import math
import os
import re

import numpy as np

from tools.sil import lcmio
from tools.sil import tlm as tlmmod
from tools.sil.tlm import ROOT

DEG = math.pi / 180.0
LSB = 2.0 ** -20          # rad/s per gyro / gimbal-rate count
W_THR = 0.01              # deg/s
MU_THR = 0.01             # deg
LS6 = -1                  # table ls[6] of the shipped tables: var(kappa) = pkk * 4^ls6
PLANT_DIVERGED = 1
PLANT_RETX = 2
STATUS_STALE = 1
STATUS_SAT = 2
BRIDGE_COUNTERS = ("dups", "stale", "gaps", "rejected", "nonfinite_rej", "range_rej", "missed", "table_rej")
MODES = {0: "BOOT", 1: "STANDBY", 2: "DETUMBLE", 3: "SAFE"}
CTL_CMDS = {1: "START", 2: "STOP", 3: "READY", 4: "HEARTBEAT", 5: "SUMMARY"}
CTL_NODES = {0: "runner", 1: "plant", 2: "bridge", 3: "logger"}
ACK_RESULTS = {0: "ACCEPTED", 1: "PARTIAL", 2: "REJECTED"}
# Telemetry x_hat of step k is published after the time update (obs.c: predict, then publish), so
# it is the prediction x_hat(k+1|k): it is compared with, and plotted at, truth sample k + EST_LAG.
EST_LAG = 1


def _bit_names(header, prefix):
    """{bit value: NAME} from '#define PREFIXNAME (0x...u)' lines of a C header."""
    out = {}
    try:
        text = open(os.path.join(ROOT, header)).read()
    except OSError:
        return out
    for m in re.finditer(r"#define\s+%s(\w+)\s+\(?\s*(0x[0-9A-Fa-f]+)u?\s*\)?" % prefix, text):
        out[int(m.group(2), 16)] = m.group(1)
    return out


def bits_str(word, names):
    word = int(word) & 0xFFFFFFFF
    parts = []
    for b in range(32):
        v = 1 << b
        if word & v:
            parts.append(names.get(v, "fx%d" % b if b < 8 else "bit%d" % b))
    return "0x%08X%s" % (word, (" (" + " ".join(parts) + ")") if parts else "")


# ----------------------------------------------------------------------------------------------
# Reading

def read(path, lcm_py=None):
    """Decode a log into per-channel numpy columns. Repeated seqs (retransmissions, cached
    commands) are kept in the raw counts but the series keep the last message of each seq."""
    gnc = lcmio.load_types(lcm_py)
    dec = {
        "GNC_SENSOR": gnc.sensor_frame_t.decode, "GNC_CMD": gnc.actuator_cmd_t.decode,
        "GNC_TLM": gnc.fsw_tlm_frame_t.decode, "GNC_TRUTH": gnc.sim_truth_t.decode,
        "GNC_CTL": gnc.sil_ctl_t.decode, "GNC_TBL_UP": gnc.table_upload_t.decode,
        "GNC_TBL_ACK": gnc.table_ack_t.decode, "GNC_FSW_CMD": gnc.fsw_cmd_t.decode,
    }
    sen, cmd, tlm, tru = [], [], [], []
    ctl, ack, up = [], [], []
    other = {}
    bad = {}
    lay = tlmmod.layout()
    for ts, ch, data in lcmio.events(path):
        f = dec.get(ch)
        if f is None:
            other[ch] = other.get(ch, 0) + 1
            continue
        try:
            m = f(data)
        except ValueError:
            bad[ch] = bad.get(ch, 0) + 1
            continue
        if ch == "GNC_SENSOR":
            sen.append((m.utime, m.seq, m.period_us, m.counts[0], m.counts[1], m.status[0], m.status[1],
                        m.scenario_flags, m.plant_flags))
        elif ch == "GNC_CMD":
            cmd.append((m.utime, m.seq, m.counts[0], m.counts[1], m.fsw_mode, m.fsw_health))
        elif ch == "GNC_TLM":
            tlm.append((m.utime, m.seq, m.tlm_layout_version, m.tlm_len) +
                       tuple(getattr(m, c) for c in BRIDGE_COUNTERS) + (bytes(m.tlm[:m.tlm_len]),))
        elif ch == "GNC_TRUTH":
            tru.append((m.utime, m.seq) + tuple(m.state[:8]) + tuple(m.extra[:5]) + (m.events,))
        elif ch == "GNC_CTL":
            ctl.append(dict(utime=m.utime, command=CTL_CMDS.get(m.command, m.command),
                            node=CTL_NODES.get(m.node_id, m.node_id), status=m.status, seed=m.seed,
                            scenario=bytes(m.scenario).split(b"\0")[0].decode("ascii", "replace")))
        elif ch == "GNC_TBL_ACK":
            ack.append(dict(utime=m.utime, table_id="0x%04X" % (m.table_id & 0xFFFF), revision=m.revision,
                            result=ACK_RESULTS.get(m.result, m.result), reason="0x%08X" % (m.reason & 0xFFFFFFFF),
                            bytes_received=m.bytes_received))
        elif ch == "GNC_FSW_CMD":
            other[ch] = other.get(ch, 0) + 1
        else:
            up.append((m.utime, m.table_id, m.revision, m.total_len, m.offset, m.n))

    def cols(rows, names):
        if not rows:
            return {n: np.zeros(0) for n in names}
        a = list(zip(*rows))
        return {n: np.array(v) for n, v in zip(names, a)}

    def last_per_seq(d):
        """Keep the last message of each seq, sorted by seq; 'n_msgs' counts all."""
        n = len(d["seq"])
        if n == 0:
            return d, 0
        seq = d["seq"]
        rev = seq[::-1]
        _, idx = np.unique(rev, return_index=True)
        keep = np.sort(n - 1 - idx)
        keep = keep[np.argsort(seq[keep], kind="stable")]
        return {k: v[keep] for k, v in d.items()}, n

    S, n_sen = last_per_seq(cols(sen, ["utime", "seq", "period_us", "gy", "gz", "st_y", "st_z",
                                       "scenario_flags", "plant_flags"]))
    S_all = cols(sen, ["utime", "seq", "period_us", "gy", "gz", "st_y", "st_z", "scenario_flags", "plant_flags"])
    C, n_cmd = last_per_seq(cols(cmd, ["utime", "seq", "cy", "cz", "mode", "health"]))
    T, n_tru = last_per_seq(cols(tru, ["utime", "seq", "wy", "wz", "muy", "mudy", "muz", "mudz", "by", "bz",
                                       "k2", "bdot_y", "bdot_z", "sigma", "jf", "events"]))
    tnames = ["utime", "seq", "layout", "tlm_len"] + list(BRIDGE_COUNTERS) + ["buf"]
    if tlm:
        # keep the last message of each seq, then decode all fsw_tlm_t in one numpy pass
        by_seq = {}
        for r in tlm:
            by_seq[r[1]] = r
        rows = [by_seq[s] for s in sorted(by_seq)]
        L = cols(rows, tnames[:-1] + ["_buf"])
        bufs = [r[-1] for r in rows]
        bad_len = [i for i, b in enumerate(bufs) if len(b) != lay.nbytes]
        if bad_len:
            raise tlmmod.TlmError("GNC_TLM seq %d: tlm_len %d, %s says %d bytes" % (
                rows[bad_len[0]][1], len(bufs[bad_len[0]]), os.path.basename(lay.path), lay.nbytes))
        del L["_buf"]
        raw = lay.decode_many(bufs)
        L["raw"] = raw
        L["real"] = lay.scaled_many(raw)
    else:
        L = None
    return dict(path=path, sensor=S, sensor_all=S_all, n_sensor_msgs=n_sen, cmd=C, n_cmd_msgs=n_cmd,
                truth=T, n_truth_msgs=n_tru, tlm=L, n_tlm_msgs=len(tlm), ctl=ctl, ack=ack, uploads=len(up),
                other=other, undecodable=bad)


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

def _f(x):
    return None if x is None else float(x)


def metrics(R):
    T, S, C, L = R["truth"], R["sensor"], R["cmd"], R["tlm"]
    out = {"log": os.path.abspath(R["path"])}
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
        raise SystemExit("sil: log has neither GNC_SENSOR nor GNC_TRUTH frames")
    out["h_s"] = h
    out["messages"] = {"GNC_SENSOR": R["n_sensor_msgs"], "GNC_CMD": R["n_cmd_msgs"], "GNC_TLM": R["n_tlm_msgs"],
                       "GNC_TRUTH": R["n_truth_msgs"], "GNC_CTL": len(R["ctl"]), "GNC_TBL_UP": R["uploads"],
                       "GNC_TBL_ACK": len(R["ack"])}
    if R["other"]:
        out["messages_other_channels"] = R["other"]
    if R["undecodable"]:
        out["undecodable"] = R["undecodable"]
    out["steps"] = {"sensor_seqs": int(len(S["seq"])), "cmd_seqs": int(len(C["seq"])),
                    "tlm_seqs": int(len(L["seq"])) if L else 0, "truth_seqs": int(len(T["seq"]))}
    if len(S["seq"]):
        seq = S["seq"]
        out["steps"]["sensor_seq_range"] = [int(seq[0]), int(seq[-1])]
        out["steps"]["sensor_seq_missing"] = int(seq[-1] - seq[0] + 1 - len(seq))
    if len(T["seq"]):
        t = T["utime"] * 1e-6
        sig = T["sigma"][-1]
        out["model"] = "M-phys" if sig > 0 else ("M-paper" if sig < 0 else "unknown (sigma 0)")
        out["sigma"] = float(sig)
        out["j_factor"] = float(T["jf"][-1])
        out["t0_s"] = float(t[0])
        out["t_end_s"] = float(t[-1])
        out["duration_s"] = float(t[-1] - t[0] + h)
        w = np.hypot(T["wy"], T["wz"]) / DEG
        mu = np.maximum(np.abs(T["muy"]), np.abs(T["muz"])) / DEG
        above = np.nonzero(w >= W_THR)[0]
        above_p = np.nonzero((w >= W_THR) | (mu >= MU_THR))[0]
        out["t_s"] = float(t[above[-1]] + h) if len(above) else 0.0
        out["t_s_plus"] = float(t[above_p[-1]] + h) if len(above_p) else 0.0
        out["settled"] = bool(len(above) == 0 or above[-1] < len(t) - 1)
        out["settled_plus"] = bool(len(above_p) == 0 or above_p[-1] < len(t) - 1)
        out["k2_true"] = float(T["k2"][-1])
        out["peak_abs_mu_deg"] = {"y": float(np.max(np.abs(T["muy"])) / DEG), "z": float(np.max(np.abs(T["muz"])) / DEG),
                                  "max": float(np.max(mu))}
        out["peak_abs_w_degs"] = {"y": float(np.max(np.abs(T["wy"])) / DEG), "z": float(np.max(np.abs(T["wz"])) / DEG),
                                  "norm": float(np.max(w))}
        out["w_end_degs"] = float(w[-1])
        last20 = t >= t[-1] - 20.0
        out["last_20s"] = {"max_abs_w_degs": float(np.max(w[last20])), "max_abs_mu_deg": float(np.max(mu[last20]))}
        out["peak_abs_beta_deg"] = {"y": float(np.max(np.abs(T["by"])) / DEG), "z": float(np.max(np.abs(T["bz"])) / DEG)}
        out["beta_end_deg"] = {"y": float(T["by"][-1] / DEG), "z": float(T["bz"][-1] / DEG)}
        ev = int(np.bitwise_or.reduce(T["events"].astype(np.int64))) if len(T["events"]) else 0
        out["truth_events_or"] = "0x%08X" % (ev & 0xFFFFFFFF)
        out["truth_steps_with_events"] = int(np.count_nonzero(T["events"]))
    if len(C["seq"]):
        out["peak_abs_bdot_cmd_degs"] = {"y": float(np.max(np.abs(C["cy"])) * LSB / DEG),
                                         "z": float(np.max(np.abs(C["cz"])) * LSB / DEG)}
        out["final_mode_cmd"] = MODES.get(int(C["mode"][-1]), int(C["mode"][-1]))
        out["final_fsw_health_cmd"] = "0x%08X" % (int(C["health"][-1]) & 0xFFFFFFFF)
    if L:
        raw, real = L["raw"], L["real"]
        lay = tlmmod.layout()
        out["tlm_layout_version"] = sorted(set(int(v) for v in L["layout"]))
        out["tlm_layout_version_json"] = lay.layout_version
        out["K_hat_final"] = float(0.01 * real["obs_kappa"][-1])
        out["K_hat_initial"] = float(0.01 * real["obs_kappa"][0])
        if "k2_true" in out and out["k2_true"] != 0:
            out["K_hat_rel_err"] = out["K_hat_final"] / out["k2_true"] - 1.0
        pkk = real["obs_pkk"][-1]
        out["sigma_K_final"] = float(0.01 * math.sqrt(max(pkk, 0.0)) * 2.0 ** LS6)
        out["obs_revision"] = int(raw["obs_revision"][-1])
        out["tbl_revision"] = int(raw["tbl_revision"][-1])
        fb = _bit_names("fsw/app/fsw_exec.h", "FSW_H_")
        ob = _bit_names("fsw/observer/obs.h", "OBS_H_")
        mode = int(raw["mode"][-1])
        out["final_mode"] = MODES.get(mode, mode)
        out["modes_seen"] = [MODES.get(int(m), int(m)) for m in np.unique(raw["mode"])]
        out["health_final"] = bits_str(raw["health"][-1], fb)
        out["health_sticky"] = bits_str(raw["health_sticky"][-1], fb)
        out["obs_health_final"] = bits_str(raw["obs_health"][-1], ob)
        out["obs_health_sticky"] = bits_str(raw["obs_health_sticky"][-1], ob)
        out["bridge_counters"] = {c: int(L[c][-1]) for c in BRIDGE_COUNTERS}
        cnt = [f["name"] for f in lay.fields if f.get("unit") == "count" or f["name"].startswith("n_")
               or f["name"].startswith("obs_n_")]
        out["fsw_counters"] = {c: int(raw[c][-1]) for c in cnt}
        out["tbl_reason_last"] = "0x%08X" % int(raw["tbl_reason"][-1])
        out["deterministic"] = out["bridge_counters"]["missed"] == 0
        if len(T["seq"]):
            A = aligned(R)
            t = A["t"]
            last20 = t >= t[-1] - 20.0
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
    Sa = R["sensor_all"]
    if len(Sa["seq"]):
        pf = Sa["plant_flags"].astype(np.int64)
        out["sensor_frames_retx"] = int(np.count_nonzero(pf & PLANT_RETX))
        out["sensor_frames_diverged"] = int(np.count_nonzero(pf & PLANT_DIVERGED))
        out["sensor_status_sat"] = int(np.count_nonzero((Sa["st_y"] | Sa["st_z"]) & STATUS_SAT))
        out["sensor_status_stale"] = int(np.count_nonzero((Sa["st_y"] | Sa["st_z"]) & STATUS_STALE))
        sf = int(np.bitwise_or.reduce(Sa["scenario_flags"].astype(np.int64)))
        out["scenario_flags_or"] = "0x%08X" % (sf & 0xFFFFFFFF)
    if R["ctl"]:
        out["ctl"] = [c for c in R["ctl"] if c["command"] != "HEARTBEAT"]
        scen = [c["scenario"] for c in R["ctl"] if c["command"] == "START"]
        if scen:
            out["scenario"] = scen[0]
            out["seed"] = [c["seed"] for c in R["ctl"] if c["command"] == "START"][0]
    if R["ack"]:
        out["table_acks"] = [a for a in R["ack"] if a["result"] != "PARTIAL"]
    return out


def format_summary(m):
    g = m.get
    lines = ["SIL run report: %s" % g("log")]
    if "scenario" in m:
        lines.append("  scenario          %s (seed %s)" % (m["scenario"], g("seed")))
    lines.append("  model             %s (sigma %+g, J factor %s)" % (g("model", "?"), g("sigma", 0), g("j_factor")))
    lines.append("  period h          %d us" % g("period_us"))
    if "duration_s" in m:
        lines.append("  duration          %.3f s (t %.3f .. %.3f s)" % (m["duration_s"], m["t0_s"], m["t_end_s"]))
    st = m["steps"]
    lines.append("  steps             sensor %d, cmd %d, tlm %d, truth %d (unique seqs)"
                 % (st["sensor_seqs"], st["cmd_seqs"], st["tlm_seqs"], st["truth_seqs"]))
    lines.append("  messages          " + ", ".join("%s %d" % kv for kv in m["messages"].items()))
    if "t_s" in m:
        lines.append("  t_s               %.3f s%s" % (m["t_s"], "" if m["settled"] else "  (NOT SETTLED at end)"))
        lines.append("  t_s+              %.3f s%s" % (m["t_s_plus"], "" if m["settled_plus"] else "  (NOT SETTLED at end)"))
    if "K_hat_final" in m:
        lines.append("  K_hat final       %.6g s^-2 (+-3 sigma %.3g; initial %.6g)   true k^2 %.6g   rel err %+.3f %%"
                     % (m["K_hat_final"], 3 * m["sigma_K_final"], m["K_hat_initial"], g("k2_true", float("nan")),
                        100 * g("K_hat_rel_err", float("nan"))))
    if "peak_abs_bdot_cmd_degs" in m:
        p = m["peak_abs_bdot_cmd_degs"]
        lines.append("  peak |bdot| cmd   y %.4f  z %.4f deg/s" % (p["y"], p["z"]))
    if "peak_abs_mu_deg" in m:
        p = m["peak_abs_mu_deg"]
        lines.append("  peak |mu|         y %.4f  z %.4f  max %.4f deg" % (p["y"], p["z"], p["max"]))
        p = m["peak_abs_w_degs"]
        lines.append("  peak |w|          y %.4f  z %.4f  |w| %.4f deg/s" % (p["y"], p["z"], p["norm"]))
        lines.append("  |w| at end        %.3g deg/s" % m["w_end_degs"])
        p = m["last_20s"]
        lines.append("  last 20 s         max |w| %.3g deg/s, max |mu| %.3g deg" % (p["max_abs_w_degs"], p["max_abs_mu_deg"]))
        p = m["peak_abs_beta_deg"]
        q = m["beta_end_deg"]
        lines.append("  beta              peak y %.4f z %.4f deg; end y %+.4f z %+.4f deg" % (p["y"], p["z"], q["y"], q["z"]))
        lines.append("  truth events      OR %s in %d steps" % (m["truth_events_or"], m["truth_steps_with_events"]))
        ee = m.get("estimate_error")
        if ee:
            g2 = lambda v: "n/a" if v is None else "%.3g" % v
            lines.append("  estimate error    |w| %s deg/s after t_s, %s last 20 s; |mu| %s deg max, %s last 20 s (%s)"
                         % (g2(ee["max_w_err_degs_after_t_s"]), g2(ee["max_w_err_degs_last_20s"]),
                            g2(ee["max_mu_err_deg"]), g2(ee["max_mu_err_deg_last_20s"]), ee["alignment"]))
    lines.append("Faults seen")
    if "bridge_counters" in m:
        lines.append("  bridge            " + ", ".join("%s %d" % kv for kv in m["bridge_counters"].items()))
        c = m["fsw_counters"]
        names = list(c)
        for i in range(0, len(names), 6):
            lines.append(("  fsw counters      " if i == 0 else "                    ") +
                         ", ".join("%s %d" % (k, c[k]) for k in names[i:i + 6]))
        lines.append("  final mode        %s (modes seen: %s)" % (m["final_mode"], " ".join(str(x) for x in m["modes_seen"])))
        lines.append("  health final      %s" % m["health_final"])
        lines.append("  health sticky     %s" % m["health_sticky"])
        lines.append("  obs health final  %s" % m["obs_health_final"])
        lines.append("  obs health sticky %s" % m["obs_health_sticky"])
        lines.append("  table revision    fsw %d, obs %d; last refusal reason %s"
                     % (m["tbl_revision"], m["obs_revision"], m["tbl_reason_last"]))
        lines.append("  deterministic     %s (bridge missed = %d)" % ("yes" if m["deterministic"] else "NO",
                                                                      m["bridge_counters"]["missed"]))
    else:
        lines.append("  no GNC_TLM telemetry in the log")
    if "sensor_frames_retx" in m:
        lines.append("  sensor frames     PLANT_RETX %d, PLANT_DIVERGED %d, status SAT %d, STALE %d; scenario flags OR %s"
                     % (m["sensor_frames_retx"], m["sensor_frames_diverged"], m["sensor_status_sat"],
                        m["sensor_status_stale"], m["scenario_flags_or"]))
        lines.append("  missing seqs      %d" % m["steps"].get("sensor_seq_missing", 0))
    if "final_mode_cmd" in m:
        lines.append("  GNC_CMD final     mode %s, health %s" % (m["final_mode_cmd"], m["final_fsw_health_cmd"]))
    for a in m.get("table_acks", []):
        lines.append("  table ack         t %.3f s id %s rev %d %s reason %s (%d bytes)"
                     % (a["utime"] * 1e-6, a["table_id"], a["revision"], a["result"], a["reason"], a["bytes_received"]))
    for c in m.get("ctl", []):
        if c["command"] in ("SUMMARY", "STOP"):
            lines.append("  ctl               %s from %s, status %d" % (c["command"], c["node"], c["status"]))
    if "undecodable" in m:
        lines.append("  UNDECODABLE       %s" % m["undecodable"])
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


def _jsonable(o):
    if isinstance(o, dict):
        return {str(k): _jsonable(v) for k, v in o.items()}
    if isinstance(o, (list, tuple)):
        return [_jsonable(v) for v in o]
    if isinstance(o, (np.integer,)):
        return int(o)
    if isinstance(o, (np.floating, float)):
        v = float(o)
        return v if math.isfinite(v) else None
    return o


def main(args):
    try:
        R = read(args.log, args.lcm_py)
    except tlmmod.TlmError as e:
        raise SystemExit("sil report: %s" % e)
    m = metrics(R)
    os.makedirs(args.out, exist_ok=True)
    text = format_summary(m)
    print(text, end="")
    with open(os.path.join(args.out, "summary.txt"), "w") as fh:
        fh.write(text)
    js = json.dumps(_jsonable(m), indent=1, sort_keys=False) + "\n"
    paths = [os.path.join(args.out, "summary.json")] + ([args.json] if args.json else [])
    for p in paths:
        with open(p, "w") as fh:
            fh.write(js)
    if not args.no_plots:
        for p in plots(R, m, args.out):
            print("wrote %s" % p)
    return 0
