"""Monte Carlo campaign of the switching-time solver (spec 50 §3.5-3.7, §4.6, §7 A4-3).

    python -m tools.impulse mc --n 500 --box nominal --seed 1 --out DIR [--jobs N] [--resume] [--check]
    python -m tools.impulse mc --box nominal,wide --n 1000,400 --seed 1 --out DIR --check

The work is done by the host executable `imp_mc` (tools/impulse/imp_mc.cpp: reference ref::solve
and fixed-point imp_solve per sample, one CSV row each). This driver splits each box's index
range into fixed chunks of --chunk samples (aligned to multiples of --chunk, so a longer
campaign with the same seed reuses the chunks of a shorter one), runs them as parallel
subprocesses (--jobs, default os.cpu_count()), shows progress (tqdm, on stderr), and writes

    DIR/chunks/<box>_<i0>_<i1>.csv   one per chunk (written to .tmp, renamed when complete)
    DIR/campaign.json                seed, w, tau_f, chunk size, executable digest
    DIR/samples.csv                  every sample, boxes in the order given, indices ascending
    DIR/summary.json                 per box figures, the A4-3 checks, timing
    DIR/*.png                        outcome vs rho_max, iterations, |dT|, true miss

--resume skips chunks already complete (header and row count checked) and refuses if the seed,
w, tau_f, chunk size or executable differ from DIR/campaign.json. Without --resume the chunks
are recomputed. --check asserts A4-3 per box and exits 1 on a failure. --bench R reruns the
campaign R times from scratch and records runs/s (a benchmark, never a pass/fail figure).

The executable: --exe, else $IMP_MC_EXE, else build/host/tools/impulse/imp_mc.
"""
import concurrent.futures as cf
import csv
import datetime
import hashlib
import io
import json
import math
import os
import re
import shutil
import subprocess
import sys
import time

import numpy as np
from tqdm import tqdm

from tools.bench import provenance

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
DEFAULT_EXE = os.path.join(ROOT, "build", "host", "tools", "impulse", "imp_mc")
BOXES = ("nominal", "wide")
MIN_N = {"nominal": 500, "wide": 200}   # spec 50 §7 A4-3
OUTCOMES = ("VALID", "NO_SOLUTION", "INFEASIBLE")
CAUSES = ("NONE", "ITER", "DIVERGE", "SINGULAR", "COND", "FX", "ORDER")
# Flight-table values the checks refer to (spec 50 §5.7); the executable uses the table itself.
RHO_WARN, RHO_REJECT = 0.38, 0.55
DT_G4_MS = 0.25          # G4: times within 0.25 ms of the reference
MISS_MAX_M = 0.01        # A4-3: true miss <= 1 cm
ITER_MAX_NOM = 6         # A4-3: no accepted attempt needs more than 6 iterations
RULE_BAND = (78.0, 85.0)  # A4-3: rule alone valid in 78-85 %
WIDE_BAND = (5.0, 15.0)   # A4-3: wide box solved fraction 5-15 %
NPAT = {"xy": 16, "z": 4}


# ------------------------------------------------------------------ campaign plumbing

def sha256(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for b in iter(lambda: f.read(1 << 20), b""):
            h.update(b)
    return h.hexdigest()


def exe_header(exe):
    """The executable's CSV header (list of column names): its output for an empty index range."""
    r = subprocess.run([exe, "--box", "nominal", "--seed", "0", "--i0", "0", "--i1", "0"],
                       stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, check=False)
    if r.returncode != 0:
        sys.exit(f"mc: {exe} failed: {r.stderr.strip()}")
    return next(csv.reader([r.stdout.strip()]))


def chunk_ranges(n, chunk):
    return [(i, min(i + chunk, n)) for i in range(0, n, chunk)]


def chunk_path(d, box, i0, i1):
    return os.path.join(d, "chunks", f"{box}_{i0:07d}_{i1:07d}.csv")


def read_table(path):
    """The records of a CSV file (header first) as lists of strings, or None when the file cannot
    be read or is truncated (imp_mc ends every record, the header's too, with a newline)."""
    try:
        with open(path, encoding="utf-8", newline="") as f:
            text = f.read()
    except OSError:
        return None
    if not text.endswith("\n"):
        return None
    return list(csv.reader(io.StringIO(text)))


def chunk_complete(path, header, rows):
    t = read_table(path)
    return t is not None and len(t) == rows + 1 and t[0] == header


def build_type_of(exe):
    d = os.path.dirname(os.path.abspath(exe))
    for _ in range(4):
        cache = os.path.join(d, "CMakeCache.txt")
        if os.path.isfile(cache):
            with open(cache, encoding="utf-8") as f:
                for line in f:
                    if line.startswith("CMAKE_BUILD_TYPE:"):
                        return line.split("=", 1)[1].strip() or "(none)"
            return "(none)"
        d = os.path.dirname(d)
    return "unknown"


def run_chunks(a, exe, header, plan):
    """Run the pending chunks in parallel; returns (wall seconds, process seconds, samples run)."""
    pending = [c for c in plan if not c["done"]]
    total = sum(c["i1"] - c["i0"] for c in plan)
    done_n = total - sum(c["i1"] - c["i0"] for c in pending)
    if done_n:
        print(f"mc: resume: {len(plan) - len(pending)} of {len(plan)} chunks already complete "
              f"({done_n} samples)", flush=True)
    if not pending:
        return 0.0, 0.0, 0
    t0 = time.monotonic()
    proc_s = 0.0
    ran = 0

    def one(c):
        tmp = c["path"] + f".tmp{os.getpid()}"
        cmd = [exe, "--box", c["box"], "--seed", str(a.seed), "--i0", str(c["i0"]), "--i1", str(c["i1"]),
               "--out", tmp]
        if a.omega:
            cmd += ["--omega", repr(a.omega)]
        if a.tauf:
            cmd += ["--tauf", repr(a.tauf)]
        r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, check=False)
        if r.returncode != 0:
            raise RuntimeError(f"{' '.join(cmd)} exited {r.returncode}: {r.stderr.strip()}")
        if not chunk_complete(tmp, header, c["i1"] - c["i0"]):
            raise RuntimeError(f"{tmp}: incomplete output")
        os.replace(tmp, c["path"])
        m = re.search(r"samples in ([0-9.]+) s", r.stderr)
        if not m:
            raise RuntimeError(f"{' '.join(cmd)}: no timing line on stderr")
        return c, float(m.group(1))

    # Progress: samples done of the campaign (resumed chunks count from the start), rate, ETA and
    # the last chunk completed.
    with tqdm(total=total, initial=done_n, unit="sample", desc="mc", file=sys.stderr, dynamic_ncols=True) as bar, \
            cf.ThreadPoolExecutor(max_workers=a.jobs) as ex:
        futs = [ex.submit(one, c) for c in pending]
        try:
            for f in cf.as_completed(futs):
                c, s = f.result()
                proc_s += s
                ran += c["i1"] - c["i0"]
                bar.set_postfix_str(f"{c['box']} [{c['i0']}, {c['i1']})", refresh=False)
                bar.update(c["i1"] - c["i0"])
        except BaseException:
            for f in futs:
                f.cancel()
            raise
    return time.monotonic() - t0, proc_s, ran


def merge(a, header, plan):
    """DIR/samples.csv: the header, then the records of every chunk in plan order (chunks are
    complete here). Returns the records as dicts, column name -> text."""
    rows = []
    for c in plan:
        rows.extend(read_table(c["path"])[1:])
    with open(os.path.join(a.out, "samples.csv"), "w", encoding="utf-8", newline="") as fo:
        w = csv.writer(fo, lineterminator="\n")
        w.writerow(header)
        w.writerows(rows)
    return [dict(zip(header, x)) for x in rows]


# ------------------------------------------------------------------ figures and checks

def fnum(s):
    return float(s) if s not in ("", "nan", "-nan") else math.nan


def pct(k, n):
    return 100.0 * k / n if n else math.nan


def finite(v):
    return [x for x in v if not math.isnan(x)]


def quantiles(v):
    """n, min, median, p95 and max of the non-NaN values. p95 is a sample value, the one at rank
    round((n - 1) 0.95) ascending, ties to even (numpy's "nearest" method); the median of an even
    count is the mean of the middle two. (The figures equal the former sorted-list code's, except
    that with both -0.0 and 0.0 in the middle the median's sign of zero may differ; no column
    summarised here holds a negative zero.)"""
    v = np.asarray(finite(v), dtype=float)
    if not v.size:
        return {"n": 0}
    return {"n": int(v.size), "min": float(v.min()), "median": float(np.median(v)),
            "p95": float(np.quantile(v, 0.95, method="nearest")), "max": float(v.max())}


def median_count(v):
    """Median of a list of integers: an int for an odd count, else the mean of the middle two."""
    m = np.median(v)
    return int(m) if len(v) % 2 else float(m)


def histogram(v):
    h = {}
    for x in v:
        h[str(x)] = h.get(str(x), 0) + 1
    return dict(sorted(h.items(), key=lambda kv: int(kv[0])))


def summarise(box, r):
    """Figures of one box (r: list of CSV dicts)."""
    n = len(r)
    s = {"n": n}
    if n == 0:
        return s
    for side in ("fx", "ref"):
        oc = {o: sum(x[f"outcome_{side}"] == o for x in r) for o in OUTCOMES}
        s[f"outcome_{side}"] = oc
        s[f"valid_pct_{side}"] = pct(oc["VALID"], n)
        s[f"rule_alone_pct_{side}"] = pct(sum(x[f"rule_ok_{side}"] == "1" for x in r), n)
        val = [x for x in r if x[f"outcome_{side}"] == "VALID"]
        s[f"how_{side}"] = {f"{h1}/{h2}": sum((x[f"how_xy_{side}"], x[f"how_z_{side}"]) == (h1, h2) for x in val)
                            for h1 in ("rule", "search") for h2 in ("rule", "search")}
        its = [max(int(x[f"it_xy_{side}"]), int(x[f"it_z_{side}"])) for x in val]
        s[f"iters_{side}"] = {"max": max(its) if its else None,
                              "median": median_count(its) if its else None,
                              "hist_max_of_subsystems": histogram(its)}
        s[f"rule_cause_{side}"] = {
            sub: {c: sum(x[f"rule_cause_{sub}_{side}"] == c for x in r) for c in CAUSES
                  if any(x[f"rule_cause_{sub}_{side}"] == c for x in r)} for sub in ("xy", "z")}
        rho = [fnum(x[f"rho_max_{side}"]) for x in r]
        sol = [fnum(x[f"rho_max_{side}"]) for x in r if x[f"outcome_{side}"] == "VALID"]
        uns = [fnum(x[f"rho_max_{side}"]) for x in r if x[f"outcome_{side}"] != "VALID"]
        s[f"rho_max_{side}"] = {"all": quantiles(rho), "solved_max": max(sol) if sol else None,
                                "unsolved_min": min(uns) if uns else None,
                                "marginal": sum(x[f"marginal_{side}"] == "1" for x in r)}
    # The rule's failures (reference, ungated), by axis: spec §3.5 reports T1 < 0 / T2 > T.
    order = [int(x["rule_order_ref"]) for x in r]
    s["rule_order_ref_pct"] = {"T1<0": pct(sum(o & 1 != 0 for o in order), n),
                               "T2>T": pct(sum(o & 2 != 0 for o in order), n),
                               "both": pct(sum(o & 3 == 3 for o in order), n),
                               "T2<T1": pct(sum(o & 4 != 0 for o in order), n)}
    s["reason_fx"] = {}
    for x in r:
        s["reason_fx"][x["reason_fx"]] = s["reason_fx"].get(x["reason_fx"], 0) + 1
    s["fail_cnt_fx"] = {c: sum(int(x[f"fail_{c.lower()}_fx"]) for x in r) for c in CAUSES[1:]}
    s["dt_max_ms"] = quantiles(fnum(x["dt_max_ms"]) for x in r)
    dtb = [(fnum(x["dt_max_ms"]), fnum(x["dt_bound_ms"])) for x in r if not math.isnan(fnum(x["dt_max_ms"]))]
    s["dt_within_first_order_bound"] = f"{sum(d <= b for d, b in dtb)}/{len(dtb)}"
    s["dt_over_g4"] = [{"index": int(x["index"]), "dt_ms": fnum(x["dt_max_ms"]), "bound_ms": fnum(x["dt_bound_ms"]),
                        "fres_lsb": [int(x["fres_xy_lsb"]), int(x["fres_z_lsb"])]}
                       for x in r if fnum(x["dt_max_ms"]) > DT_G4_MS]
    low = [x for x in r if x["rho_band_ref"] == "0"]
    s["rho_below_warn_unsolved_ref"] = [int(x["index"]) for x in low if x["outcome_ref"] != "VALID"]
    s["miss_r_m"] = quantiles(fnum(x["miss_r_m"]) for x in r)
    s["miss_v_mps"] = quantiles(fnum(x["miss_v_mps"]) for x in r)
    s["miss_r_ref_m"] = quantiles(fnum(x["miss_r_ref_m"]) for x in r)
    s["fres_lsb"] = quantiles([float(x["fres_xy_lsb"]) for x in r if x["outcome_fx"] == "VALID"] +
                              [float(x["fres_z_lsb"]) for x in r if x["outcome_fx"] == "VALID"])
    s["iters_total_fx"] = quantiles(float(x["iters_total_fx"]) for x in r)
    worst = max(r, key=lambda x: int(x["iters_total_fx"]))
    s["iters_total_fx_worst"] = {"index": int(worst["index"]), "iters_total": int(worst["iters_total_fx"]),
                                 "outcome": worst["outcome_fx"], "x0": [float(worst[k]) for k in
                                 ("x0_m", "xd0_mps", "y0_m", "yd0_mps", "z0_m", "zd0_mps")]}
    dv = [fnum(x["dv_fx_mps"]) - fnum(x["dv_imp_mps"]) for x in r if x["outcome_fx"] == "VALID"]
    s["dv_over_impulsive_mps"] = quantiles(dv)
    s["ties"] = sum(x["tie"] == "1" for x in r)
    s["st_ok_nonzero"] = sum(x["st_ok"] != "0" for x in r)
    s["st_fail_nonzero"] = sum(x["st_fail"] != "0" for x in r)
    return s


def reason_ok(x):
    """The flight code's outcome carries a reason consistent with its own figures."""
    o, why = x["outcome_fx"], x["reason_fx"]
    if o == "VALID":
        return why == "ok"
    if o == "INFEASIBLE":
        return ((why == "rho>reject" and x["rho_band_fx"] == "2") or (why == "impulsive" and x["rho_band_fx"] != "2"))
    if o == "NO_SOLUTION":
        parts = why.split(";")
        if not parts or any(":" not in p for p in parts):
            return False
        for p in parts:
            sub, cause = p.split(":", 1)
            # every pattern of a failed subsystem was tried (rule + search), each with a cause
            if sub not in NPAT or cause not in CAUSES[1:] or int(x[f"attempts_{sub}_fx"]) != NPAT[sub]:
                return False
        return True
    return False


def checks(box, r):
    """A4-3 (and the G4 comparison it refers to) for one box: list of (name, ok, measured)."""
    n = len(r)
    out = []

    def add(name, bad, measured):
        out.append((name, bad == 0, measured))

    add(f"samples >= {MIN_N[box]}", 0 if n >= MIN_N[box] else 1, f"{n}")
    val_fx = [x for x in r if x["outcome_fx"] == "VALID"]
    val_ref = [x for x in r if x["outcome_ref"] == "VALID"]
    both = [x for x in r if x["outcome_fx"] == "VALID" and x["outcome_ref"] == "VALID"]
    # G4: fixed point vs reference on every sample
    add("same outcome fx / ref (G4)", sum(x["outcome_fx"] != x["outcome_ref"] for x in r),
        f"{sum(x['outcome_fx'] == x['outcome_ref'] for x in r)}/{n}")
    add("same polarities fx / ref, ties as §3.5 (G4)", sum(x["tie"] == "-1" for x in both),
        f"{sum(x['pattern_fx'] == x['pattern_ref'] for x in both)}/{len(both)} equal, "
        f"{sum(x['tie'] == '1' for x in both)} ties")
    dts = finite(fnum(x["dt_max_ms"]) for x in both)
    add(f"|dT| fx - ref <= {DT_G4_MS} ms (G4)", sum(d > DT_G4_MS for d in dts),
        f"max {max(dts):.4f} ms" if dts else "none")
    idiff = [max(abs(int(x["it_xy_fx"]) - int(x["it_xy_ref"])), abs(int(x["it_z_fx"]) - int(x["it_z_ref"])))
             for x in both if x["tie"] == "0"]
    add("iterations fx = ref +-1 (G4)", sum(d > 1 for d in idiff), f"max |diff| {max(idiff) if idiff else 0}")
    add("0 <= T1 <= T2 <= T on every accepted schedule (fx, ref)",
        sum(x["order_ok_fx"] != "1" for x in val_fx) + sum(x["order_ok_ref"] != "1" for x in val_ref),
        f"{len(val_fx)} fx, {len(val_ref)} ref schedules")
    add("no fx status bit outside failed attempts", sum(x["st_ok"] != "0" for x in r),
        f"{sum(x['st_ok'] != '0' for x in r)} samples with st_ok != 0")
    miss = finite(fnum(x["miss_r_m"]) for x in val_fx)
    add(f"true miss of the fx schedule <= {MISS_MAX_M * 100:.0f} cm", sum(m > MISS_MAX_M for m in miss),
        f"max {max(miss) * 1e3:.2f} mm" if miss else "none")
    if box == "nominal":
        for side in ("ref", "fx"):
            p = pct(sum(x[f"rule_ok_{side}"] == "1" for x in r), n)
            add(f"rule alone valid in {RULE_BAND[0]:.0f}-{RULE_BAND[1]:.0f} % ({side})",
                0 if RULE_BAND[0] <= p <= RULE_BAND[1] else 1, f"{p:.2f} %")
            v = pct(sum(x[f"outcome_{side}"] == "VALID" for x in r), n)
            add(f"rule + search valid in 100 % ({side})", 0 if v == 100.0 else 1, f"{v:.2f} %")
            its = [max(int(x[f"it_xy_{side}"]), int(x[f"it_z_{side}"])) for x in r if x[f"outcome_{side}"] == "VALID"]
            add(f"accepted attempts <= {ITER_MAX_NOM} iterations ({side})", sum(i > ITER_MAX_NOM for i in its),
                f"max {max(its) if its else 0}")
    else:
        add("every case VALID / NO_SOLUTION / INFEASIBLE with a reason (fx)", sum(not reason_ok(x) for x in r),
            ", ".join(f"{o} {sum(x['outcome_fx'] == o for x in r)}" for o in OUTCOMES))
        for side in ("ref", "fx"):
            v = pct(sum(x[f"outcome_{side}"] == "VALID" for x in r), n)
            add(f"solved fraction in {WIDE_BAND[0]:.0f}-{WIDE_BAND[1]:.0f} % ({side})",
                0 if WIDE_BAND[0] <= v <= WIDE_BAND[1] else 1, f"{v:.2f} %")
            low = [x for x in r if x[f"rho_band_{side}"] == "0"]   # rho_max < rho_warn, exact
            add(f"every case with rho_max < {RHO_WARN} solved ({side})",
                sum(x[f"outcome_{side}"] != "VALID" for x in low),
                f"{sum(x[f'outcome_{side}'] == 'VALID' for x in low)}/{len(low)}")
    return out


def plots(a, by_box, summ):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    boxes = [b for b in by_box if by_box[b]]
    figs = []
    ncol = len(boxes)
    # 1. outcome vs rho_max (flight code)
    fig, axs = plt.subplots(1, ncol, figsize=(6.5 * ncol, 4.2), squeeze=False)
    cats = (("VALID, rule", "tab:green", lambda x: x["outcome_fx"] == "VALID" and x["rule_ok_fx"] == "1"),
            ("VALID, search", "tab:olive", lambda x: x["outcome_fx"] == "VALID" and x["rule_ok_fx"] != "1"),
            ("NO_SOLUTION", "tab:orange", lambda x: x["outcome_fx"] == "NO_SOLUTION"),
            ("INFEASIBLE", "tab:red", lambda x: x["outcome_fx"] == "INFEASIBLE"))
    for ax, b in zip(axs[0], boxes):
        r = by_box[b]
        rho = [fnum(x["rho_max_fx"]) for x in r]
        hi = max(1.0, min(max(rho), 3.0))
        bins = [hi * i / 60 for i in range(61)]
        data = [[min(fnum(x["rho_max_fx"]), hi) for x in r if f(x)] for _, _, f in cats]
        ax.hist(data, bins=bins, stacked=True, color=[c for _, c, _ in cats],
                label=[f"{l} ({len(d)})" for (l, _, _), d in zip(cats, data)])
        for v, ls in ((RHO_WARN, "--"), (RHO_REJECT, ":")):
            ax.axvline(v, color="k", ls=ls, lw=1)
        ax.set_xlabel("rho_max = max_r (|dv1| + |dv2|) / (a_nom T)  (clipped at %.1f)" % hi)
        ax.set_ylabel("samples")
        ax.set_title(f"{b}: outcome vs rho_max (n = {len(r)}; rho_warn --, rho_reject :)")
        ax.legend(fontsize=8)
    figs.append(("outcome_vs_rho.png", fig))
    # 2. iterations of the accepted attempt, fixed point vs reference, per subsystem
    fig, axs = plt.subplots(1, ncol, figsize=(6.5 * ncol, 4.2), squeeze=False)
    for ax, b in zip(axs[0], boxes):
        r = [x for x in by_box[b] if x["outcome_fx"] == "VALID"]
        series = [[int(x[k]) for x in r] for k in ("it_xy_fx", "it_xy_ref", "it_z_fx", "it_z_ref")]
        top = max([max(s) for s in series if s] + [1])
        ax.hist(series, bins=[i - 0.5 for i in range(0, top + 2)],
                label=["x-y fixed", "x-y reference", "z fixed", "z reference"])
        ax.axvline(ITER_MAX_NOM + 0.5, color="k", ls="--", lw=1)
        ax.set_xlabel("Newton iterations of the accepted attempt")
        ax.set_ylabel("samples")
        ax.set_title(f"{b}: iterations ({len(r)} solved; A4-3 nominal limit {ITER_MAX_NOM} --)")
        ax.legend(fontsize=8)
    figs.append(("iterations.png", fig))
    # 3. |dT| and 4. true miss, log bins
    for name, key, scale, unit, lim, title in (
            ("dt_hist.png", "dt_max_ms", 1.0, "ms", DT_G4_MS, "max |T_fx - T_ref| over the 6 times"),
            ("miss_hist.png", "miss_r_m", 1e3, "mm", MISS_MAX_M * 1e3, "true miss of the fixed-point schedule")):
        fig, ax = plt.subplots(figsize=(7, 4.2))
        for b in boxes:
            v = [fnum(x[key]) * scale for x in by_box[b]]
            v = [max(x, 1e-6) for x in finite(v)]
            if v:
                lo = math.floor(math.log10(min(v)))
                hi = math.ceil(math.log10(max(max(v), lim)))
                bins = [10 ** (lo + (hi - lo) * i / 50) for i in range(51)]
                ax.hist(v, bins=bins, histtype="step", lw=1.5, label=f"{b} (n = {len(v)}, max {max(v):.3g} {unit})")
        ax.axvline(lim, color="k", ls="--", lw=1)
        ax.set_xscale("log")
        ax.set_xlabel(f"{title} [{unit}] (limit --)")
        ax.set_ylabel("samples")
        ax.legend(fontsize=8)
        figs.append((name, fig))
    for name, fig in figs:
        fig.tight_layout()
        fig.savefig(os.path.join(a.out, name), dpi=110)
        plt.close(fig)
    return [n for n, _ in figs]


# ------------------------------------------------------------------ entry

def main(a):
    boxes = [b.strip() for b in a.box.split(",") if b.strip()]
    ns = [int(v) for v in str(a.n).split(",")]
    if any(b not in BOXES for b in boxes) or len(set(boxes)) != len(boxes):
        sys.exit(f"mc: --box must list distinct boxes of {BOXES}")
    if len(ns) == 1:
        ns = ns * len(boxes)
    if len(ns) != len(boxes) or any(v < 0 for v in ns):
        sys.exit("mc: --n takes one count, or one per box")
    a.jobs = max(1, a.jobs or os.cpu_count() or 1)
    exe = os.path.abspath(a.exe or os.environ.get("IMP_MC_EXE") or DEFAULT_EXE)
    if not os.access(exe, os.X_OK):
        sys.exit(f"mc: executable {exe} not found: build the imp_mc target, pass --exe or set IMP_MC_EXE")
    header = exe_header(exe)
    camp = {"seed": a.seed, "omega": a.omega, "tauf": a.tauf, "chunk": a.chunk, "exe_sha256": sha256(exe)}
    os.makedirs(os.path.join(a.out, "chunks"), exist_ok=True)
    cpath = os.path.join(a.out, "campaign.json")
    if a.resume and os.path.isfile(cpath):
        with open(cpath, encoding="utf-8") as f:
            old = json.load(f)
        diff = [k for k in camp if old.get(k) != camp[k]]
        if diff:
            sys.exit(f"mc: --resume: {', '.join(diff)} differ from {cpath}; use another --out or drop --resume")
    if not a.resume:
        shutil.rmtree(os.path.join(a.out, "chunks"))
        os.makedirs(os.path.join(a.out, "chunks"))
    for fn in os.listdir(os.path.join(a.out, "chunks")):
        if ".tmp" in fn:   # left by an interrupted run
            os.remove(os.path.join(a.out, "chunks", fn))
    with open(cpath, "w", encoding="utf-8") as f:
        json.dump(camp, f, indent=1)
        f.write("\n")

    plan = []
    for b, n in zip(boxes, ns):
        for i0, i1 in chunk_ranges(n, a.chunk):
            p = chunk_path(a.out, b, i0, i1)
            plan.append({"box": b, "i0": i0, "i1": i1, "path": p,
                         "done": a.resume and chunk_complete(p, header, i1 - i0)})
    total = sum(ns)
    print(f"mc: {', '.join(f'{b} {n}' for b, n in zip(boxes, ns))} samples, seed {a.seed}, {len(plan)} chunks "
          f"of <= {a.chunk}, {a.jobs} jobs, {exe}", flush=True)
    bench = []
    reps = max(1, a.bench or 1)
    for rep in range(reps):
        if rep > 0:
            for c in plan:
                c["done"] = False
        wall, proc_s, ran = run_chunks(a, exe, header, plan)
        if ran:
            bench.append({"samples": ran, "wall_s": wall, "runs_per_s": ran / wall,
                          "process_s": proc_s, "runs_per_core_s": ran / proc_s if proc_s > 0 else None})
            if a.bench:
                print(f"mc: bench rep {rep + 1}/{reps}: {ran} samples in {wall:.2f} s = {ran / wall:.1f} runs/s "
                      f"({a.jobs} jobs); {ran / proc_s:.1f} runs/s per process", flush=True)
    rows = merge(a, header, plan)
    by_box = {b: [x for x in rows if x["box"] == b] for b in boxes}

    summ = {"generated": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
            "commit": provenance.commit(), "machine": provenance.machine_description(), "exe": exe, "exe_build_type": build_type_of(exe),
            "campaign": dict(camp, boxes=dict(zip(boxes, ns)), jobs=a.jobs),
            "sampling": "sim::Rng(seed, (box_id << 32) | index), 6 uniform draws, X0 = (2u - 1) half-width; "
                        "nominal +-5 km / +-1 m/s (box_id 1), wide +-20 km / +-5 m/s (box_id 2)",
            "boxes": {b: summarise(b, by_box[b]) for b in boxes}, "checks": {}}
    if bench:
        rates = [x["runs_per_s"] for x in bench]
        summ["timing"] = {"reps": bench, "runs_per_s_median": float(np.median(rates)), "runs_per_s_min": min(rates),
                          "note": "benchmark only (spec 00 §9), wall time of the whole parallel campaign"}
    failed = []
    for b in boxes:
        res = checks(b, by_box[b])
        summ["checks"][b] = [{"check": nm, "ok": ok, "measured": m} for nm, ok, m in res]
        if a.check:
            for nm, ok, m in res:
                print(f"  {'PASS' if ok else 'FAIL'} {b}: {nm}: {m}")
                if not ok:
                    failed.append(f"{b}: {nm}: {m}")
    if not a.no_plots and rows:
        summ["plots"] = plots(a, by_box, summ)
    with open(os.path.join(a.out, "summary.json"), "w", encoding="utf-8") as f:
        json.dump(summ, f, indent=1, allow_nan=False, default=str)
        f.write("\n")
    for b in boxes:
        s = summ["boxes"][b]
        if not s["n"]:
            continue
        print(f"mc {b}: n {s['n']}; VALID {s['valid_pct_fx']:.2f} % (ref {s['valid_pct_ref']:.2f} %), rule alone "
              f"{s['rule_alone_pct_fx']:.2f} % (ref {s['rule_alone_pct_ref']:.2f} %); iterations max fx "
              f"{s['iters_fx']['max']} ref {s['iters_ref']['max']}; max |dT| "
              f"{s['dt_max_ms'].get('max', math.nan):.4f} ms; max true miss "
              f"{s['miss_r_m'].get('max', math.nan) * 1e3:.3f} mm, {s['miss_v_mps'].get('max', math.nan):.3g} m/s; "
              f"rho_max solved <= {s['rho_max_ref']['solved_max']}, unsolved >= {s['rho_max_ref']['unsolved_min']}")
    if bench:
        t = summ["timing"]
        print(f"mc: {t['runs_per_s_median']:.1f} runs/s median, {t['runs_per_s_min']:.1f} min over {len(bench)} "
              f"run(s), {a.jobs} jobs ({summ['exe_build_type']} build)")
    print(f"mc: wrote {os.path.join(a.out, 'samples.csv')}, summary.json"
          + (", " + ", ".join(summ.get("plots", [])) if summ.get("plots") else ""))
    if failed:
        print("mc: A4-3 check FAILED:\n  " + "\n  ".join(failed), file=sys.stderr)
        return 1
    if a.check:
        print("mc: A4-3 check passed")
    return 0


def add_parser(sub):
    p = sub.add_parser("mc", help="Monte Carlo campaign over initial conditions (spec 50 §7 A4-3)")
    p.add_argument("--n", default="500", help="samples, one count or one per box (e.g. 1000,400)")
    p.add_argument("--box", default="nominal", help="nominal (+-5 km, +-1 m/s), wide (+-20 km, +-5 m/s), "
                                                    "or both as nominal,wide")
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--omega", type=float, default=0.0, help="orbit rate [rad/s] (default: the table's)")
    p.add_argument("--tauf", type=float, default=0.0, help="tau_f = w T [rad] (default: w * 1055 s)")
    p.add_argument("--out", required=True, help="output directory")
    p.add_argument("--jobs", type=int, default=0, help="parallel processes (default: os.cpu_count())")
    p.add_argument("--chunk", type=int, default=100, help="samples per chunk (default 100)")
    p.add_argument("--resume", action="store_true", help="skip chunks already complete in --out")
    p.add_argument("--check", action="store_true", help="assert A4-3, exit 1 on failure")
    p.add_argument("--exe", help="imp_mc executable (default $IMP_MC_EXE, else build/host/...)")
    p.add_argument("--no-plots", action="store_true")
    p.add_argument("--bench", type=int, default=0, metavar="R",
                   help="rerun the whole campaign R times from scratch and record runs/s")
    return p
