"""Spec 30 §7 figures of a RESPIN campaign store (A4, A6, A7): the success rate among runs with
g0 >= g_min (below it the module commands zero by design: LOW_MOMENTUM), settle-time median and
p90 among the converged, the most region switches of a run with g0 >= g_guard, and every failure
with its g0, final C_phi, |xi| and switch count.

    python -m tools.respin stats build/campaigns/respin_a4 [--compare build/campaigns/respin_a6]

The campaign runner's own report (python -m tools.campaign report) gives the generic tables and
plots; this adds the spec's conditional figures (pandas over the runner's Parquet store).
"""
import glob
import os

import pandas as pd

from . import design

G_MIN = design.WHEELS["gmin_nms"]
G_GUARD = design.WHEELS["guard_hcap"] * 3 ** 0.5 * design.WHEELS["hmax_nms"]


def load(store):
    fs = sorted(glob.glob(os.path.join(store, "results", "*.parquet")))
    if not fs:
        raise SystemExit("stats: no results under %s/results" % store)
    df = pd.concat([pd.read_parquet(f) for f in fs], ignore_index=True)
    df.columns = [c[2:] if c.startswith("m.") else c for c in df.columns]
    return df.sort_values("run").reset_index(drop=True)


def figures(df):
    hi = df[df["g0_true_nms"] >= G_MIN]
    conv = hi[hi["converged"] == 1]
    f = dict(runs=len(df), runs_g0_ge_gmin=len(hi), converged=len(conv),
             rate_pct=100.0 * len(conv) / max(len(hi), 1),
             settle_median_s=float(conv["t_settle_s"].median()) if len(conv) else float("nan"),
             settle_p90_s=float(conv["t_settle_s"].quantile(0.9)) if len(conv) else float("nan"),
             settle_max_s=float(conv["t_settle_s"].max()) if len(conv) else float("nan"),
             switches_max_g0_ge_gguard=int(df[df["g0_true_nms"] >= G_GUARD]["fsw_rsp_n_switch"].max())
             if (df["g0_true_nms"] >= G_GUARD).any() else 0)
    f["failures"] = [dict(run=int(r["run"]), g0_nms=float(r["g0_true_nms"]), cphi=float(r["cphi_final"]),
                          xi=float(r["xi_final"]), switches=int(r["fsw_rsp_n_switch"]))
                     for _, r in hi[hi["converged"] != 1].iterrows()]
    return f


def show(name, f):
    print("%s: %d runs, %d with g0 >= g_min, converged %d = %.2f %%; settle median %.1f s, p90 %.1f s, max %.1f s; "
          "max region switches (g0 >= g_guard) %d" % (name, f["runs"], f["runs_g0_ge_gmin"], f["converged"],
                                                       f["rate_pct"], f["settle_median_s"], f["settle_p90_s"],
                                                       f["settle_max_s"], f["switches_max_g0_ge_gguard"]))
    for x in f["failures"]:
        print("  failure: run %d, g0 %.3f N m s, C_phi %.4f, |xi| %.4f, %d switches" % (
            x["run"], x["g0_nms"], x["cphi"], x["xi"], x["switches"]))


def main(args):
    a = load(args.store)
    show(args.store, figures(a))
    if args.compare:
        b = load(args.compare)
        runs = sorted(set(b["run"]))
        show("%s (its %d runs)" % (args.store, len(runs)), figures(a[a["run"].isin(runs)]))
        show(args.compare, figures(b))
    return 0
