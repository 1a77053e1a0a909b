"""The campaign report: success rate with its 95 % Wilson interval, the quantiles of every metric,
the failures with their inputs and the command that replays each one in the LCM SIL with logs and
plots, and the plots (histograms; success rate against each dispersed parameter; each metric
against each parameter). Writes OUT/report.txt (printed), OUT/report.json, OUT/plots/*.png."""
import json
import math
import os

import numpy as np

from .store import Store

Q = (0.0, 0.05, 0.5, 0.95, 1.0)


def wilson(k, n, z=1.959963984540054):
    """95 % Wilson score interval of k successes in n."""
    if n == 0:
        return (0.0, 1.0)
    p = k / n
    d = 1 + z * z / n
    c = (p + z * z / (2 * n)) / d
    h = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / d
    return (max(0.0, c - h), min(1.0, c + h))


def build(c, out, plots=True):
    df = Store(out).load()
    n = len(df)
    rep = {"campaign": c.name, "mission": c.mission, "definition": os.path.relpath(c.path), "runs": c.runs,
           "recorded": n, "missing": c.runs - n}
    if n == 0:
        return rep, df
    k = int(df["passed"].sum())
    lo, hi = wilson(k, n)
    rep["passed"] = k
    rep["success_rate"] = k / n
    rep["success_ci95"] = [lo, hi]
    rep["status"] = {s: int(v) for s, v in df["status"].value_counts().sort_index().items()}
    flown = df[df["status"].isin(["ok", "fail"])]
    rep["metrics"] = {}
    for col in [x for x in df.columns if x.startswith("m.")]:
        v = flown[col].astype(float).dropna().to_numpy()
        if len(v):
            rep["metrics"][col[2:]] = {"n": int(len(v)), "mean": float(v.mean()),
                                       **{"q%g" % (100 * q): float(np.quantile(v, q)) for q in Q}}
    cols = c.columns()
    rep["failures"] = []
    for _, r in df[~df["passed"]].iterrows():
        rep["failures"].append({"run": int(r["run"]), "status": r["status"], "reason": r["reason"],
                                "inputs": {p: _plain(r.get(col)) for p, col in cols.items()},
                                "replay": "python -m tools.campaign replay %s %d --out /tmp/replay-%s-%d"
                                          % (os.path.relpath(c.path), int(r["run"]), c.name, int(r["run"]))})
    rep["wall_s_per_run"] = {"median": float(df["wall_s"].median()), "max": float(df["wall_s"].max())}
    if plots:
        rep["plots"] = _plots(c, df, os.path.join(out, "plots"))
    return rep, df


def _plain(v):
    if isinstance(v, (np.integer,)):
        return int(v)
    if isinstance(v, (np.floating,)):
        return float(v)
    return v


def text(rep):
    o = ["campaign %s (%s, %s): %d of %d runs recorded" % (rep["campaign"], rep["mission"], rep["definition"],
                                                          rep["recorded"], rep["runs"])]
    if "passed" not in rep:
        return "\n".join(o) + "\n"
    lo, hi = rep["success_ci95"]
    o.append("  passed            %d / %d = %.2f %%  (95 %% Wilson interval %.2f .. %.2f %%)"
             % (rep["passed"], rep["recorded"], 100 * rep["success_rate"], 100 * lo, 100 * hi))
    o.append("  status            " + ", ".join("%s %d" % kv for kv in rep["status"].items()))
    o.append("  wall per run      median %.3f s, max %.3f s" % (rep["wall_s_per_run"]["median"],
                                                              rep["wall_s_per_run"]["max"]))
    o.append("  metric                         n        min         p5        p50        p95        max")
    for name, m in rep["metrics"].items():
        o.append("  %-24s %7d %10.4g %10.4g %10.4g %10.4g %10.4g" % (name, m["n"], m["q0"], m["q5"], m["q50"],
                                                                   m["q95"], m["q100"]))
    if rep["failures"]:
        o.append("  failures (%d):" % len(rep["failures"]))
        for f in rep["failures"][:50]:
            ins = ", ".join("%s=%s" % (p, ("%.6g" % v) if isinstance(v, float) else v) for p, v in f["inputs"].items())
            o.append("    run %-6d %-7s %s" % (f["run"], f["status"], f["reason"]))
            o.append("               inputs: %s" % ins)
            o.append("               replay: %s" % f["replay"])
        if len(rep["failures"]) > 50:
            o.append("    ... %d more in report.json" % (len(rep["failures"]) - 50))
    for p in rep.get("plots", []):
        o.append("  plot              %s" % p)
    return "\n".join(o) + "\n"


def _plots(c, df, where):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    os.makedirs(where, exist_ok=True)
    paths = []
    flown = df[df["status"].isin(["ok", "fail"])]
    mets = [x for x in df.columns if x.startswith("m.")][:6]
    ok = flown["passed"].to_numpy(bool)
    if mets:
        fig, axs = plt.subplots(1, len(mets), figsize=(4 * len(mets), 3.4), squeeze=False)
        for ax, col in zip(axs[0], mets):
            v = flown[col].astype(float).to_numpy()
            bins = np.histogram_bin_edges(v[np.isfinite(v)], bins=30) if np.isfinite(v).any() else 10
            ax.hist([v[ok & np.isfinite(v)], v[~ok & np.isfinite(v)]], bins=bins, stacked=True,
                    color=["C0", "C3"], label=["passed", "not passed"])
            ax.set_title(col[2:], fontsize=9)
            ax.grid(alpha=0.3)
        axs[0][0].legend(fontsize=7)
        fig.suptitle("%s: metric distributions (%d runs flown)" % (c.name, len(flown)), fontsize=10)
        fig.tight_layout()
        p = os.path.join(where, "histograms.png")
        fig.savefig(p, dpi=100)
        plt.close(fig)
        paths.append(p)
    params = [(p, col) for p, col in c.columns().items() if col in df.columns and
              np.issubdtype(df[col].dtype, np.number) and [x for x in c.dispersions if x.path == p][0].kind != "seed"][:8]
    if params:
        fig, axs = plt.subplots(1, len(params), figsize=(3.6 * len(params), 3.2), squeeze=False)
        for ax, (p, col) in zip(axs[0], params):
            x = df[col].astype(float).to_numpy()
            edges = np.unique(np.quantile(x, np.linspace(0, 1, 11)))
            idx = np.clip(np.searchsorted(edges, x, side="right") - 1, 0, max(len(edges) - 2, 0))
            rate = [df["passed"].to_numpy(bool)[idx == b].mean() if (idx == b).any() else np.nan
                    for b in range(max(len(edges) - 1, 1))]
            mid = 0.5 * (edges[:-1] + edges[1:]) if len(edges) > 1 else edges
            ax.plot(mid, 100 * np.array(rate), "o-")
            ax.set_ylim(-5, 105)
            ax.set_xlabel(p, fontsize=8)
            ax.grid(alpha=0.3)
        axs[0][0].set_ylabel("passed [%]")
        fig.suptitle("%s: success rate against each dispersed parameter (deciles)" % c.name, fontsize=10)
        fig.tight_layout()
        p = os.path.join(where, "success_vs_parameter.png")
        fig.savefig(p, dpi=100)
        plt.close(fig)
        paths.append(p)
        for col in mets[:4]:
            fig, axs = plt.subplots(1, len(params), figsize=(3.6 * len(params), 3.2), squeeze=False)
            y = flown[col].astype(float).to_numpy()
            for ax, (p, pc) in zip(axs[0], params):
                x = flown[pc].astype(float).to_numpy()
                ax.scatter(x[ok], y[ok], s=4, c="C0")
                ax.scatter(x[~ok], y[~ok], s=8, c="C3")
                ax.set_xlabel(p, fontsize=8)
                ax.grid(alpha=0.3)
            axs[0][0].set_ylabel(col[2:])
            fig.suptitle("%s: %s against each parameter (red: not passed)" % (c.name, col[2:]), fontsize=10)
            fig.tight_layout()
            pth = os.path.join(where, "scatter_%s.png" % col[2:])
            fig.savefig(pth, dpi=100)
            plt.close(fig)
            paths.append(pth)
    return paths


def main(c, out, plots=True):
    rep, _ = build(c, out, plots)
    t = text(rep)
    with open(os.path.join(out, "report.txt"), "w", encoding="utf-8") as fh:
        fh.write(t)
    with open(os.path.join(out, "report.json"), "w", encoding="utf-8") as fh:
        json.dump(rep, fh, indent=1)
    print(t, end="")
    return 0
