"""Run report of one SIL log, for whichever registered mission flew it (spec 00 §5).

    python -m tools.sil report LOG --out DIR [--summary SUMMARY.json] [--json FILE] [--no-plots]
                                             [--lcm-py DIR]

Writes DIR/report.txt (also printed), DIR/report.json (and FILE with --json) and the mission's
plots. The run's own summary.txt / summary.json (written by `sil run|plant --summary[-json]`)
are never overwritten: they may live in DIR.

Which mission: the tlm_layout_version of the log's GNC_TLM frames is one registered mission's
(tools.iface.mission(layout_version)). Its report module is found by convention,
tools.<module>.report, and provides

    read(log, lcm_py, mission) -> R        its channels; R["common"] = read_log(...) below
    metrics(R, mission, m)                 adds every figure it derives from the log to m
    SUMMARY_KEYS                           its figures that the run summary also holds (Key list)
    format_summary(m, src) -> str          its part of the text; src.tag(path, ...) marks a line
                                           whose figures are log-derived while a summary is in use
    plots(R, m, out) -> [paths]

This file names no mission. It does what every mission shares: the executive header of the
telemetry (mode, health, table and input counters; names from tools.iface), the bridge counters,
run control and table acks, and the run summary.

Figures. Without --summary every figure is derived from the log (the report says so). With
--summary SUMMARY.json (the C++ live metrics of the same run: hil_host/sil/metrics.cpp and
hil_host/missions/<module>/*_metrics.cpp) each figure of the key map (CORE_KEYS here, the
mission's SUMMARY_KEYS) is the summary's value; the figures only the log gives (whatever the
mission's report derives beyond them) stay log-derived and are marked "(log)"; the summary's
other keys are listed as they are; and the report's own re-derivation is compared with the
summary (the check of `python -m tools.sil agree`).
"""
import collections
import copy
import importlib
import json
import math
import os

import numpy as np

from tools import iface

from . import lcmio

# One entry of a key map: report figure (dotted path into the report's dict) <-> run-summary key.
# tol None: equal (same definition, same doubles); otherwise |report - summary| <= tol, and why
# says why the definitions differ. "a.*" <-> "p_*" maps every key k of report dict a to p_k.
# optional: the figure exists only in some runs (e.g. no truth sample at t_f).
Key = collections.namedtuple("Key", "report summary tol why optional", defaults=(None, "", False))

# The figures every mission's summary has (hil_host/sil/metrics.cpp) and every report derives.
CORE_KEYS = [
    Key("mission", "mission"),
    # The tap counts the truth messages it decoded, the report those the log holds: the same
    # messages in a memq run (a udpm logger may drop some; then they differ, rightly).
    Key("messages.GNC_TRUTH", "steps_truth"),
    Key("tlm_frames", "steps_tlm"),
    Key("tlm_undecodable", "tlm_undecodable"),
    Key("messages.GNC_TBL_ACK", "table_acks"),
    # Last telemetry of the run: executive header and the mission's counters (raw integers).
    Key("fsw.*", "fsw_*"),
    Key("bridge.*", "bridge_*"),
    # First telemetry with an fx status bit (health bits 0..7) and its bits; -1 / 0 when none.
    Key("fx.t_first_s", "t_first_fx_status_s"),
    Key("fx.first_bits", "first_fx_status_bits"),
]

# Summary keys that describe the run rather than measure it, left out of the "other keys" list.
_SUMMARY_SKIP = ("scenario", "scenario_file", "mission", "wall_s", "steps_per_s")


# ---------------------------------------------------------------------------------- names

def bits_str(word, bits):
    """"0x00001104 (fx2 STALE SAFE)": fx status bits 0..7 as fx<b>, named bits (tools.iface
    Bit list) by name, a multi-bit field as NAME=value, anything else as bit<b>."""
    word = int(word) & 0xFFFFFFFF
    parts = []
    covered = 0
    for b in bits:
        v = word & b.mask
        covered |= b.mask
        if v and b.single:
            parts.append((b.shift, b.name))
        elif v:
            parts.append((b.shift, "%s=%d" % (b.name, v >> b.shift)))
    for k in range(32):
        if word & (1 << k) and not covered & (1 << k):
            parts.append((k, "fx%d" % k if k < 8 else "bit%d" % k))
    parts.sort()
    return "0x%08X%s" % (word, (" (" + " ".join(p for _, p in parts) + ")") if parts else "")


def exec_health_str(word):
    return bits_str(word, iface.exec_iface().HEALTH)


def mode_name(mission, mode):
    return mission.modes().get(int(mode), "mode %d" % int(mode))


def reason_str(mission, word):
    """A table reason word in words: code name, and the field / relation / check its detail names."""
    word = int(word) & 0xFFFFFFFF
    if word == 0:
        return "0x00000000 (none)"
    code, detail = word & 0xFF, (word >> 8) & 0xFF
    name = iface.exec_iface().TBL_REASONS.by_value().get(code, "reason %d" % code)
    fields = mission.iface.table_fields
    if name in ("RANGE_LO", "RANGE_HI"):
        name += ": field %d (%s)" % (detail, fields[detail] if detail < len(fields) else "?")
    elif name == "INVARIANT":
        name += ": relation %d" % detail
    elif name == "MODULE":
        why = mission.iface.why
        name += ": %s check %s" % (mission.module, "could not decode the table" if detail == 0xFF else
                                   "refused it (%s)" % (why[detail - 1].name if 1 <= detail <= len(why) else detail))
    return "0x%08X (%s)" % (word, name)


# -------------------------------------------------------------------------------- reading

def save_fig(fig, out, name, paths):
    """A mission report's figure: laid out, written as OUT/NAME at 110 dpi, closed, its path appended."""
    import matplotlib.pyplot as plt
    fig.tight_layout()
    p = os.path.join(out, name)
    fig.savefig(p, dpi=110)
    plt.close(fig)
    paths.append(p)


def read_log(path, lcm_py, mission, handlers=None):
    """One pass over the log. handlers: {channel: f(msg)} for the mission's channels (msg decoded
    with the channel's type). GNC_TLM frames in the mission's layout become the telemetry series
    (the last message of each seq, sorted by seq, decoded in one numpy pass with
    mission.layout); GNC_CTL and GNC_TBL_ACK are decoded here."""
    gnc = lcmio.load_types(lcm_py)
    handlers = handlers or {}
    tlm_cls = gnc.fsw_tlm_frame_t
    bridge = [s for s in tlm_cls.__slots__ if s not in ("utime", "seq", "tlm_layout_version", "tlm_len", "tlm")]
    cmds = lcmio.consts(gnc.sil_ctl_t, "CMD_")
    nodes = lcmio.consts(gnc.sil_ctl_t, "NODE_")
    results = lcmio.consts(gnc.table_ack_t, "RESULT_")
    messages, undecodable = collections.Counter(), collections.Counter()
    by_seq = {}
    n_frames = n_other_layout = 0
    ctl, ack = [], []
    for _, ch, data in lcmio.events(path):
        messages[ch] += 1
        cls = lcmio.msg_type(gnc, ch)
        if cls is None or (ch not in handlers and ch not in ("GNC_TLM", "GNC_CTL", "GNC_TBL_ACK")):
            continue
        try:
            m = cls.decode(data)
        except ValueError:
            undecodable[ch] += 1
            continue
        if ch == "GNC_TLM":
            if (m.tlm_layout_version & 0xFFFFFFFF) != mission.layout_version or m.tlm_len != mission.layout.nbytes:
                n_other_layout += 1
                continue
            n_frames += 1
            by_seq[m.seq] = (m.utime, m.seq) + tuple(getattr(m, c) for c in bridge) + (bytes(m.tlm[:m.tlm_len]),)
        elif ch == "GNC_CTL":
            ctl.append(dict(utime=m.utime, command=cmds.get(m.command, m.command),
                            node=nodes.get(m.node_id, m.node_id), status=m.status, seed=m.seed,
                            scenario=bytes(m.scenario).split(b"\0")[0].decode("ascii", "replace")))
        elif ch == "GNC_TBL_ACK":
            ack.append(dict(utime=m.utime, table_id="0x%04X" % (m.table_id & 0xFFFF), revision=m.revision,
                            result=results.get(m.result, m.result), reason=m.reason & 0xFFFFFFFF,
                            bytes_received=m.bytes_received))
        if ch in handlers:
            handlers[ch](m)
    L = None
    if by_seq:
        rows = [by_seq[s] for s in sorted(by_seq)]
        cols = list(zip(*rows))
        L = {n: np.array(v) for n, v in zip(["utime", "seq"] + bridge, cols[:-1])}
        raw = mission.layout.decode_many(cols[-1])
        L["raw"] = raw
        L["real"] = mission.layout.scaled_many(raw)
    return dict(path=path, tlm=L, tlm_frames=n_frames, tlm_undecodable=n_other_layout + undecodable["GNC_TLM"],
                bridge_counters=bridge, messages=dict(messages), undecodable=dict(undecodable), ctl=ctl, ack=ack)


def columns(rows, names):
    """Rows of tuples -> {name: numpy column}, every message kept."""
    if not rows:
        return {n: np.zeros(0) for n in names}
    return {n: np.array(v) for n, v in zip(names, zip(*rows))}


def last_per_seq(rows, names):
    """Rows of tuples -> numpy columns keeping the last message of each seq (column "seq"),
    sorted by seq; and the number of messages."""
    if not rows:
        return columns(rows, names), 0
    d = columns(rows, names)
    seq = d["seq"]
    n = len(seq)
    _, idx = np.unique(seq[::-1], return_index=True)
    keep = np.sort(n - 1 - idx)
    keep = keep[np.argsort(seq[keep], kind="stable")]
    return {k: v[keep] for k, v in d.items()}, n


# -------------------------------------------------------------------------------- figures

def common_metrics(C, mission):
    """The figures every mission's log gives: messages, run control, table acks, the executive's
    telemetry header (last values in out["fsw"]; the mission adds its counters there), the
    bridge counters, the first fx status bit."""
    out = {"log": os.path.abspath(C["path"]), "mission": mission.name, "module": mission.module,
           "layout_version": "0x%08X" % mission.layout_version, "messages": C["messages"],
           "tlm_frames": C["tlm_frames"], "tlm_undecodable": C["tlm_undecodable"]}
    if C["undecodable"]:
        out["undecodable"] = C["undecodable"]
    out["messages"].setdefault("GNC_TBL_ACK", 0)
    out["messages"].setdefault("GNC_TRUTH", 0)
    start = [c for c in C["ctl"] if c["command"] == "START"]
    if start:
        out["scenario"], out["seed"] = start[0]["scenario"], start[0]["seed"]
    if C["ctl"]:
        out["ctl"] = [c for c in C["ctl"] if c["command"] != "HEARTBEAT"]
    if C["ack"]:
        out["table_acks"] = [a for a in C["ack"] if a["result"] != "PARTIAL"]
    L = C["tlm"]
    if L is None:
        return out
    raw = L["raw"]
    head = iface.exec_iface().HEAD
    names = ["mode", "health", "health_sticky", "tbl_reason", "tbl_revision"] + [f.name for f in head if f.unit == "count"]
    out["fsw"] = {k: int(raw[k][-1]) for k in names}
    out["final_mode"] = mode_name(mission, raw["mode"][-1])
    out["modes_seen"] = [mode_name(mission, v) for v in np.unique(raw["mode"])]
    out["health_final"] = exec_health_str(raw["health"][-1])
    out["health_sticky"] = exec_health_str(raw["health_sticky"][-1])
    out["tbl_reason_last"] = reason_str(mission, raw["tbl_reason"][-1])
    out["bridge"] = {c: int(L[c][-1]) for c in C["bridge_counters"]}
    fx = np.nonzero(raw["health"].astype(np.int64) & 0xFF)[0]
    out["fx"] = {"t_first_s": float(L["utime"][fx[0]] * 1e-6) if len(fx) else -1.0,
                 "first_bits": int(raw["health"][fx[0]] & 0xFF) if len(fx) else 0}
    out["deterministic"] = out["bridge"].get("missed", 0) == 0
    return out


def format_common(m, src):
    """The executive and bridge part of the text (every mission)."""
    o = ["Executive and bridge (telemetry header, names from tools.iface)"]
    if "fsw" not in m:
        o.append("  no GNC_TLM telemetry in the log's mission layout")
    else:
        f = m["fsw"]
        o.append("  final mode        %s (modes seen: %s)%s" % (m["final_mode"], " ".join(m["modes_seen"]), src.tag("fsw.mode")))
        o.append("  health final      %s%s" % (m["health_final"], src.tag("fsw.health")))
        o.append("  health sticky     %s%s" % (exec_health_str(f["health_sticky"]), src.tag("fsw.health_sticky")))
        cnt = [k for k in f if k.startswith("n_") or k.startswith("host_")]
        for i in range(0, len(cnt), 6):
            o.append(("  fsw counters      " if i == 0 else "                    ") +
                     ", ".join("%s %s" % (k, f[k]) for k in cnt[i:i + 6]) + src.tag(*("fsw." + k for k in cnt[i:i + 6])))
        o.append("  table             revision %s; last refusal %s%s" % (f["tbl_revision"], m["tbl_reason_last"],
                                                                       src.tag("fsw.tbl_revision", "fsw.tbl_reason")))
        o.append("  bridge            " + ", ".join("%s %s" % kv for kv in m["bridge"].items()) +
                 src.tag(*("bridge." + k for k in m["bridge"])))
        fx = m["fx"]
        o.append("  first fx status   %s%s" % ("none" if fx["t_first_s"] < 0 else "t %.3f s, bits 0x%02X" % (
            fx["t_first_s"], fx["first_bits"]), src.tag("fx.t_first_s", "fx.first_bits")))
        o.append("  deterministic     %s (bridge missed = %d)%s" % ("yes" if m["deterministic"] else "NO",
                                                                   m["bridge"].get("missed", 0), src.tag("bridge.missed")))
    for a in m.get("table_acks", []):
        o.append("  table ack         t %.3f s id %s rev %d %s%s (%d bytes)"
                 % (a["utime"] * 1e-6, a["table_id"], a["revision"], a["result"],
                    ", reason " + reason_str(src.mission, a["reason"]) if a["reason"] else "", a["bytes_received"]))
    for c in m.get("ctl", []):
        if c["command"] in ("SUMMARY", "STOP"):
            o.append("  ctl               %s from %s, status %d" % (c["command"], c["node"], c["status"]))
    o.append("  messages          " + ", ".join("%s %d" % kv for kv in sorted(m["messages"].items())) +
             "; telemetry frames %d, undecodable %d" % (m["tlm_frames"], m["tlm_undecodable"]))
    if "undecodable" in m:
        o.append("  UNDECODABLE       %s" % m["undecodable"])
    return o


# ---------------------------------------------------------------------- key maps, summary

def get_path(d, path):
    for p in path.split("."):
        if not isinstance(d, dict) or p not in d:
            raise KeyError(path)
        d = d[p]
    return d


def set_path(d, path, v):
    ps = path.split(".")
    for p in ps[:-1]:
        d = d.setdefault(p, {})
    d[ps[-1]] = v


def expand(keys, report, summary):
    """Concrete (Key, report path, summary key) of a key map: a wildcard entry becomes one row per
    key of the report's dict that the summary also has (compare) or per summary key (apply,
    report None)."""
    out = []
    explicit = {k.summary for k in keys if not k.report.endswith(".*")}
    for k in keys:
        if not k.report.endswith(".*"):
            out.append((k, k.report, k.summary))
            continue
        base, pre = k.report[:-2], k.summary[:-1]
        if report is None:   # numbers only: a summary's text keys (..._names) stay its own
            subs = [s[len(pre):] for s in summary if s.startswith(pre) and s not in explicit
                    and isinstance(summary[s], (int, float))]
        else:
            try:
                d = get_path(report, base)
            except KeyError:
                d = {}
            subs = [s for s in d if pre + s in summary and pre + s not in explicit]
        out += [(k, base + "." + s, pre + s) for s in subs]
    return out


def compare(report, summary, keys):
    """Every figure of the key map present in both: [(report path, summary key, report value,
    summary value, tol, ok, why)], and the entries missing on a side (not optional)."""
    rows, missing = [], []
    for k in keys:
        if k.report.endswith(".*"):
            got = expand([k], report, summary)
            if not got and not k.optional:
                missing.append("%s <-> %s: no common key" % (k.report, k.summary))
            continue
        have_r, have_s = True, k.summary in summary
        try:
            get_path(report, k.report)
        except KeyError:
            have_r = False
        if not (have_r and have_s):
            if not k.optional:
                missing.append("%s <-> %s: %s" % (k.report, k.summary, "missing in the report" if not have_r
                                                                         else "missing in the summary"))
    for k, rp, sk in expand(keys, report, summary):
        try:
            rv = get_path(report, rp)
        except KeyError:
            continue
        if sk not in summary:
            continue
        sv = summary[sk]
        if isinstance(rv, bool) or isinstance(sv, bool) or isinstance(rv, str) or isinstance(sv, str):
            ok = rv == sv
        elif rv is None or sv is None:
            ok = rv is None and sv is None
        elif k.tol is None:
            ok = rv == sv
        else:
            ok = abs(float(rv) - float(sv)) <= k.tol
        rows.append((rp, sk, rv, sv, k.tol, ok, k.why))
    return rows, missing


class Sources(object):
    """Where the figures come from: the summary's path and the report paths it supplied; and the
    mission, for its names."""

    def __init__(self, mission, path=None, from_summary=()):
        self.mission = mission
        self.path = path
        self.from_summary = set(from_summary)

    def tag(self, *paths):
        """"  (log)" for a line whose figures are (partly) log-derived while a summary is in use."""
        if self.path is None or all(p in self.from_summary for p in paths):
            return ""
        return "  (log)"


def load_summary(path, mission):
    try:
        with open(path) as fh:
            s = json.load(fh)
    except (OSError, ValueError) as e:
        raise SystemExit("sil report: --summary %s: %s" % (path, e))
    if not isinstance(s, dict):
        raise SystemExit("sil report: --summary %s is not a JSON object" % path)
    if s.get("mission", mission.name) != mission.name:
        raise SystemExit("sil report: --summary %s is a %s run, the log a %s run" % (path, s.get("mission"), mission.name))
    return s


def apply_summary(m, summary, keys):
    """The key map's figures take the summary's values; returns the report paths they set."""
    done = []
    for _, rp, sk in expand(keys, None, summary):
        if sk in summary:
            set_path(m, rp, summary[sk])
            done.append(rp)
    return done


def format_run_summary(summary, used):
    """The summary's keys that no figure above shows, as they are."""
    rest = [k for k in summary if k not in used and k not in _SUMMARY_SKIP]
    o = ["Run summary, other keys (C++ live metrics, not re-derived)"]
    line = "  "
    for k in rest:
        v = summary[k]
        item = "%s = %s" % (k, ("%.6g" % v) if isinstance(v, float) else v)
        if len(line) + len(item) > 100 and line.strip():
            o.append(line.rstrip(", "))
            line = "  "
        line += item + ", "
    if line.strip():
        o.append(line.rstrip(", "))
    return o


# ---------------------------------------------------------------------------------- output

def jsonable(o):
    if isinstance(o, dict):
        return {str(k): jsonable(v) for k, v in o.items()}
    if isinstance(o, (list, tuple)):
        return [jsonable(v) for v in o]
    if isinstance(o, (bool, np.bool_)):
        return bool(o)
    if isinstance(o, np.integer):
        return int(o)
    if isinstance(o, (np.floating, float)):
        v = float(o)
        return v if math.isfinite(v) else None
    return o


def mission_of_log(path, lcm_py=None):
    """The registered mission whose telemetry layout the log's first GNC_TLM frame carries."""
    gnc = lcmio.load_types(lcm_py)
    for _, ch, data in lcmio.events(path):
        if ch == "GNC_TLM":
            v = gnc.fsw_tlm_frame_t.decode(data).tlm_layout_version & 0xFFFFFFFF
            try:
                return iface.mission(v)
            except iface.IfaceError:
                raise SystemExit("sil report: %s: telemetry layout 0x%08X is no registered mission's" % (path, v))
    raise SystemExit("sil report: %s has no GNC_TLM frame, so no mission" % path)


def report_module(mission):
    """tools.<module>.report: the mission's report, by convention."""
    return importlib.import_module("tools.%s.report" % mission.module)


def key_map(mod):
    return CORE_KEYS + list(getattr(mod, "SUMMARY_KEYS", []))


def main(args):
    mission = mission_of_log(args.log, args.lcm_py)
    mod = report_module(mission)
    summary = load_summary(args.summary, mission) if args.summary else None
    try:
        R = mod.read(args.log, args.lcm_py, mission)
    except iface.IfaceError as e:
        raise SystemExit("sil report: %s" % e)
    m = common_metrics(R["common"], mission)
    mod.metrics(R, mission, m)
    keys = key_map(mod)
    head = ["SIL run report: %s" % m["log"],
            "  mission           %s (module %s, report tools/%s/report.py, telemetry layout %s)"
            % (mission.name, mission.module, mission.module, m["layout_version"])]
    if "scenario" in m:
        head.append("  scenario          %s (seed %s)" % (m["scenario"], m.get("seed")))
    tail = []
    if summary is None:
        src = Sources(mission)
        m["figures_from"] = {"summary": None, "note": "every figure derived from the log (no --summary given)"}
        head.append("  figures           every figure derived from the log (no --summary given)")
    else:
        derived = copy.deepcopy(jsonable(m))
        rows, missing = compare(derived, summary, keys)
        used = apply_summary(m, summary, keys)
        src = Sources(mission, os.path.abspath(args.summary), used)
        bad = [r for r in rows if not r[5]]
        m["figures_from"] = {"summary": src.path, "from_summary": used,
                             "note": "the figures listed come from the run summary (C++ live metrics); "
                                     "every other figure is derived from the log",
                             "log_rederivation": {"compared": len(rows), "disagree": [
                                 dict(report=r[0], summary=r[1], log=r[2], run=r[3]) for r in bad],
                                 "missing": missing}}
        m["run_summary"] = summary
        head.append("  figures           run summary %s (C++ live metrics); lines marked (log) are"
                    % args.summary)
        head.append("                    derived from the log; the log's own derivation %s on %d shared figures%s"
                    % ("agrees" if not bad else "DISAGREES (%d)" % len(bad), len(rows),
                       "" if not missing else "; %d key-map entries missing" % len(missing)))
        for r in bad:
            head.append("                    DISAGREE %s: log %r, run summary %s = %r" % (r[0], r[2], r[1], r[3]))
        tail = format_run_summary(summary, {sk for _, _, sk in expand(keys, None, summary)})
    text = "\n".join(head + [mod.format_summary(m, src).rstrip("\n")] + format_common(m, src) + tail) + "\n"
    os.makedirs(args.out, exist_ok=True)
    print(text, end="")
    with open(os.path.join(args.out, "report.txt"), "w") as fh:
        fh.write(text)
    js = json.dumps(jsonable(m), indent=1) + "\n"
    for p in [os.path.join(args.out, "report.json")] + ([args.json] if args.json else []):
        with open(p, "w") as fh:
            fh.write(js)
    if not args.no_plots:
        for p in mod.plots(R, m, args.out):
            print("wrote %s" % p)
    return 0
