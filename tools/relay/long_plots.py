"""Plots of the relay's long runs (spec 20 §5, §7 S5-S7), from the CSV files `rly_long` writes:

    build/host-release/tools/relay/rly_long stats --mode paper --csv DIR
    build/host-release/tools/relay/rly_long stats --mode improved --csv DIR       (spec 20 §5.6 as printed)
    build/host-release/tools/relay/rly_long stats --mode improved-up --csv DIR    (the flight default)
    build/host-release/tools/relay/rly_long sweep --csv DIR            (continuous law, reference)
    .venv/bin/python -m tools.relay.long_plots DIR [--out DIR]

Writes, for whatever inputs are present:
  abar_vs_kt.png            ā over [2000, 20000] s against fixed k_t (sweep_ref.csv, sweep_flight.csv):
                            the cliff above 0.3389, the valley at 0.361, the erratic zone below 0.306
  runs_<mode>_<code>.png    per seed: the window means ā_j (log scale) and k_t in force against time,
                            with the freeze (or probe start) marked — what the search did in each run
  abar_late.png             ā_late per seed as an empirical CDF, one curve per mode: the S5/S7 comparison
                            (medians and p90 in the legend)
A report, never a test.
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

from tools.iface import mission  # noqa: E402

# The window-packet event codes, from the module's interface (fsw/relay/rly_iface.py).
_EV = {n: v for n, v, _ in [e for e in mission("RELAY").iface.enums if e.name == "ev"][0].values}
EV_PROBE_START, EV_FREEZE_SETTLED, EV_FREEZE_CLIFF, EV_UNFREEZE = (
    _EV["PROBE_START"], _EV["FREEZE_SETTLED"], _EV["FREEZE_CLIFF"], _EV["UNFREEZE"])


def plot_sweep(d, out):
    fig, ax = plt.subplots(figsize=(8, 4.2))
    found = False
    for code, style in (("ref", "-"), ("flight", "o")):
        p = os.path.join(d, "sweep_%s.csv" % code)
        if os.path.exists(p):
            s = pd.read_csv(p)
            ax.semilogy(s.kt, s.abar_rad, style, ms=4, label="continuous law (reference)" if code == "ref"
                        else "flight module at 1 ms")
            found = True
    if not found:
        plt.close(fig)
        return None
    ax.axvline(0.3389, color="0.6", lw=0.8, ls="--", label="k_t = 0.3389 (the source's end state)")
    ax.set_xlabel("k_t")
    ax.set_ylabel("ā over [2000, 20000] s [rad]")
    ax.set_title("Mean envelope against a fixed brake ratio (spec 20 §5.5, S6)")
    ax.grid(True, which="both", lw=0.3)
    ax.legend(fontsize=8)
    path = os.path.join(out, "abar_vs_kt.png")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def plot_runs(d, out, tag):
    p = os.path.join(d, "%s_windows.csv" % tag)
    if not os.path.exists(p):
        return None
    w = pd.read_csv(p)
    seeds = sorted(w.seed.unique())
    ncol = 5
    nrow = int(np.ceil(len(seeds) / ncol))
    fig, axes = plt.subplots(nrow, ncol, figsize=(3.2 * ncol, 2.2 * nrow), sharex=True, squeeze=False)
    for ax in axes.flat[len(seeds):]:
        ax.set_visible(False)
    for ax, seed in zip(axes.flat, seeds):
        r = w[w.seed == seed]
        t_ks = r.t_end_s / 1000.0
        ax.semilogy(t_ks, r.abar_rad, color="C0", lw=0.8)
        ax.set_ylim(3e-6, 6e-5)
        ax2 = ax.twinx()
        ax2.step(t_ks, r.kt_in, where="post", color="C1", lw=0.8)
        ax2.set_ylim(0.28, 0.40)
        for ev, c in ((EV_PROBE_START, "C2"), (EV_FREEZE_SETTLED, "C3"), (EV_FREEZE_CLIFF, "C4"), (EV_UNFREEZE, "k")):
            for t in r.t_end_s[r.event == ev] / 1000.0:
                ax.axvline(t, color=c, lw=0.8, ls="--")
        ax.set_title("seed %d" % seed, fontsize=8)
        ax.tick_params(which="both", labelsize=6)
        ax2.tick_params(which="both", labelsize=6)
    fig.suptitle("%s: window mean ā_j (blue, log) and k_t (orange) against time [ks]; dashed: probe start (green),"
                 " settled freeze (red), cliff freeze (purple), un-freeze (black)" % tag, fontsize=9)
    path = os.path.join(out, "runs_%s.png" % tag)
    fig.tight_layout(rect=(0, 0, 1, 0.97))
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path


def plot_late(d, out):
    fig, ax = plt.subplots(figsize=(7, 4))
    found = False
    for tag in ("paper_flight", "improved_flight", "improved-up_flight", "paper_ref", "improved_ref", "improved-up_ref"):
        p = os.path.join(d, "%s_runs.csv" % tag)
        if not os.path.exists(p):
            continue
        r = pd.read_csv(p)
        v = np.sort(r.abar_late_rad.to_numpy())
        ax.step(v, np.arange(1, len(v) + 1) / len(v), where="post",
                label="%s: median %.3g, p90 %.3g, frozen %d/%d" % (
                    tag, np.median(v), np.quantile(v, 0.9), int(r.frozen.sum()), len(r)))
        found = True
    if not found:
        plt.close(fig)
        return None
    ax.set_xscale("log")
    ax.set_xlabel("ā_late, mean over [20000, 30000] s [rad]")
    ax.set_ylabel("fraction of seeds")
    ax.set_title("PAPER against IMPROVED and IMPROVED_UP over seeds (spec 20 §7 S5, S7)")
    ax.grid(True, which="both", lw=0.3)
    ax.legend(fontsize=7)
    path = os.path.join(out, "abar_late.png")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("dir", help="directory with rly_long's CSV files")
    ap.add_argument("--out", help="where the PNGs go (default: the same directory)")
    a = ap.parse_args(argv)
    out = a.out or a.dir
    os.makedirs(out, exist_ok=True)
    made = [plot_sweep(a.dir, out), plot_late(a.dir, out)]
    for f in sorted(os.listdir(a.dir)):
        if f.endswith("_windows.csv"):
            made.append(plot_runs(a.dir, out, f[:-len("_windows.csv")]))
    made = [m for m in made if m]
    if not made:
        print("long_plots: no rly_long CSV in %s" % a.dir, file=sys.stderr)
        return 2
    for m in made:
        print("wrote", m)
    return 0


if __name__ == "__main__":
    sys.exit(main())
