"""A3-5 (spec 40 §7) over the SIL campaign stores: the adaptive pitch channel's t* from a cold start
and a warm start against the best constant, min(t*(k2 = 0), t*(k2 = 150 s)), on the same plant and
seed, with R3 / R5 of the estimator per run and the t* spread across seeds per f.

    .venv/bin/python -m tools.pd.a3_5 --out build/campaigns [--check cold,warm]

reads OUT/pd_a3_5_cold, OUT/pd_a3_5_warm and OUT/pd_a3_5_constant (the stores of
tools/pd/campaigns/pd_a3_5_{cold,warm,constant}.yaml; any subset of the runs, joined on (f, seed)),
prints the table, writes OUT/a3_5.csv and OUT/a3_5.png, and with --check STARTS exits 1 when a run
of those starts misses a criterion:

    f <= 0.03 Hz: t* <= 0.55 x best    f < 0.05 Hz: t* < best    f >= 0.05 Hz: t* <= 1.3 x best + 10 s

A t* of -1 (not settled within the horizon) is infinite; a node where neither constant settles has
no bound and is reported, not judged.
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

from tools.campaign.store import Store  # noqa: E402

EPS_HZ = 1e-9   # the grid's f are decimal: 0.03 must count as "<= 0.03"
K2_150_Q22 = 150 << 22


def settle(v):
    """t* with 'not settled' (-1) as infinity."""
    return np.where(v < 0, np.inf, v)


def bound(f, best):
    """The A3-5 limit on t* (and whether it is strict) for a node and its best constant."""
    if f <= 0.03 + EPS_HZ:
        return 0.55 * best, False
    if f < 0.05 - EPS_HZ:
        return best, True
    return 1.3 * best + 10.0, False


def load(out, name):
    path = os.path.join(out, name)
    if not os.path.isdir(os.path.join(path, "results")):
        return None
    d = Store(path).load()
    d = d.rename(columns={"in.pd.f_hz": "f_hz", "in.pd.sensor.seed": "seed"})
    d["f_hz"] = d["f_hz"].round(6)
    return d


def judge(out):
    cold, warm, const = load(out, "pd_a3_5_cold"), load(out, "pd_a3_5_warm"), load(out, "pd_a3_5_constant")
    if cold is None or const is None:
        raise SystemExit("a3_5: %s needs pd_a3_5_cold and pd_a3_5_constant stores (tools/pd/campaigns)" % out)
    const["k2"] = np.where(const["in.table.pitch_k2_nom_q22"] == K2_150_Q22, 150, 0)
    c = const.pivot_table(index=["f_hz", "seed"], columns="k2", values="m.t_settle_pitch_s", aggfunc="first")
    c = c.reindex(columns=[0, 150]).rename(columns={0: "t_k2_0", 150: "t_k2_150"}).reset_index()
    # a constant not flown at a node is NaN and left out; neither flown: no bound
    c["best"] = np.fmin(settle(c["t_k2_0"].to_numpy()), settle(c["t_k2_150"].to_numpy()))
    rows = []
    for start, d in (("cold", cold), ("warm", warm)):
        if d is None:
            continue
        j = d.merge(c, on=["f_hz", "seed"], how="inner")
        for _, r in j.iterrows():
            t = settle(np.array([r["m.t_settle_pitch_s"]]))[0]
            lim, strict = bound(r.f_hz, r.best)
            judged = np.isfinite(r.best)
            ok = (t < lim if strict else t <= lim) if judged else True
            row = {"start": start, "f_hz": r.f_hz, "seed": int(r.seed), "t_star_s": r["m.t_settle_pitch_s"],
                   "best_s": r.best, "t_k2_0_s": r.t_k2_0, "t_k2_150_s": r.t_k2_150, "bound_s": lim,
                   "judged": judged, "t_ok": bool(ok), "run_passed": bool(r.passed), "reason": r.reason,
                   "k2_final_s": r["m.k2_final_pitch_s"]}
            if start == "cold":
                row.update({"err300": r["m.fest_err300_pitch"], "err1200": r["m.fest_err1200_pitch"],
                            "conf_ratio_max": r["m.fest_conf_ratio_max_pitch"],
                            "resets": r["m.fest_resets_pitch"]})
            rows.append(row)
    return pd.DataFrame(rows)


def plot(t, path):
    fig, ax = plt.subplots(figsize=(8, 4.5))
    for start, mk in (("cold", "o"), ("warm", "s")):
        d = t[t.start == start]
        if len(d):
            ax.plot(d.f_hz, d.t_star_s, mk, ms=4, alpha=0.7, label="%s start t*" % start)
    b = t[t.start == "cold"].groupby("f_hz").agg(best=("best_s", "median"), lim=("bound_s", "median")).reset_index()
    ax.plot(b.f_hz, b.best, "k-", lw=1, label="best constant (median over seeds)")
    ax.plot(b.f_hz, b.lim, "r--", lw=1, label="A3-5 bound")
    ax.set_yscale("log")
    ax.set_xlabel("f_min [Hz]")
    ax.set_ylabel("t* [s]")
    ax.set_title("A3-5 in SIL: adaptive pitch against the best constant (spec 40 §7)")
    ax.grid(True, which="both", lw=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m tools.pd.a3_5", description=__doc__.split("\n")[0])
    ap.add_argument("--out", required=True, help="folder holding the three campaign stores")
    ap.add_argument("--check", default="", metavar="STARTS",
                    help="cold, warm or cold,warm: exit 1 when a run of these starts misses a criterion")
    a = ap.parse_args(argv)
    t = judge(a.out)
    pd.set_option("display.width", 200)
    pd.set_option("display.max_rows", 500)
    cols = ["start", "f_hz", "seed", "t_star_s", "best_s", "bound_s", "t_ok", "run_passed", "k2_final_s"]
    print(t[cols + [c for c in ("err300", "err1200") if c in t]].to_string(index=False, float_format="%.4g"))
    checked = [s for s in a.check.split(",") if s]
    if any(s not in ("cold", "warm") for s in checked):
        ap.error("--check takes cold, warm or cold,warm")
    bad = 0
    for start in ("cold", "warm"):
        d = t[t.start == start]
        if not len(d):
            continue
        ok = d.t_ok & d.run_passed
        bad += int((~ok).sum()) if start in checked else 0
        spread = d[np.isfinite(settle(d.t_star_s.to_numpy()))].groupby("f_hz").t_star_s.agg(["min", "max", "median"])
        rel = ((spread["max"] - spread["min"]) / 2 / spread["median"]).max() if len(spread) else float("nan")
        print("%s start: %d runs, t* criterion %d/%d, run criteria %d/%d, both %d/%d (nodes with no settling "
              "constant: %d); t* spread across seeds at most +-%.1f %% of the node's median"
              % (start, len(d), int(d.t_ok.sum()), len(d), int(d.run_passed.sum()), len(d), int(ok.sum()), len(d),
                 int((~d.judged).sum()), 100 * rel))
        if start == "cold":
            w3, w12 = d.loc[d.err300.idxmax()], d.loc[d.err1200.idxmax()]
            print("  R3 worst |f^/f - 1|: %.2f %% at 300 s (%.3f Hz seed %d), %.2f %% at 1 200 s (%.3f Hz seed %d); "
                  "R5 max confident f^/f %.4f; FAULTs %d"
                  % (100 * w3.err300, w3.f_hz, w3.seed, 100 * w12.err1200, w12.f_hz, w12.seed,
                     d.conf_ratio_max.max(), int(d.resets.sum())))
        for _, r in d[~ok].iterrows():
            print("  FAIL %s %.3f Hz seed %d: t* %.2f s, bound %.2f s (best %.2f s)%s"
                  % (start, r.f_hz, r.seed, r.t_star_s, r.bound_s, r.best_s,
                     "" if r.run_passed else "; run: " + str(r.reason)))
    t.to_csv(os.path.join(a.out, "a3_5.csv"), index=False)
    plot(t, os.path.join(a.out, "a3_5.png"))
    print("wrote %s, %s" % (os.path.join(a.out, "a3_5.csv"), os.path.join(a.out, "a3_5.png")))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
