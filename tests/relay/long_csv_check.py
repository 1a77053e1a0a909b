"""CTest rly_long_csv: `rly_long stats --csv` of the flight module and of the double reference over the
same seeds and length, then tools/relay/long_plots.py on them. Asserts that every file is there with
one row per seed and one per 500-s window, and that the flight's k_t decisions (k_t in force and next,
phase, event per window) equal the reference's window for window — the same check as golden G5, now
through the tool that writes the long-run statistics (a broken CSV writer or a drifted tool fails).

    python tests/relay/long_csv_check.py RLY_LONG OUT_DIR
"""
import os
import subprocess
import sys

import pandas as pd

SEEDS, T_END_S, WIN_S = (1, 3), 3000.0, 500.0


def main():
    rly_long, out = sys.argv[1], sys.argv[2]
    os.makedirs(out, exist_ok=True)
    for code in ("flight", "ref"):
        subprocess.run([rly_long, "stats", "--mode", "improved-up", "--seeds", "%d-%d" % SEEDS, "--t", str(T_END_S),
                        "--code", code, "--jobs", "1", "--csv", out], check=True)
    subprocess.run([sys.executable, "-B", "-m", "tools.relay.long_plots", out], check=True)
    n_seeds = SEEDS[1] - SEEDS[0] + 1
    n_win = int(T_END_S / WIN_S)
    w = {}
    for code in ("flight", "ref"):
        runs = pd.read_csv(os.path.join(out, "improved-up_%s_runs.csv" % code))
        assert len(runs) == n_seeds, (code, len(runs))
        w[code] = pd.read_csv(os.path.join(out, "improved-up_%s_windows.csv" % code))
        assert len(w[code]) == n_seeds * n_win, (code, len(w[code]))
        assert (w[code].abar_rad > 1e-6).all() and (w[code].abar_rad < 1e-4).all(), code
        assert w[code].kt_in.between(0.28, 0.40).all(), code
    cols = ["seed", "j", "t_end_s", "kt_in", "kt_next", "phase", "event"]
    f, r = w["flight"][cols].reset_index(drop=True), w["ref"][cols].reset_index(drop=True)
    diff = (f != r).any(axis=1)
    assert not diff.any(), "flight and reference windows differ:\n%s\n%s" % (f[diff].head(), r[diff].head())
    # the search moved k_t (a constant column would pass the comparison trivially)
    assert f.kt_in.nunique() > n_seeds, f.kt_in.unique()
    for png in ("abar_late.png", "runs_improved-up_flight.png", "runs_improved-up_ref.png"):
        assert os.path.getsize(os.path.join(out, png)) > 10000, png
    print("rly_long_csv: %d seeds x %d windows, flight == reference decisions; plots written" % (n_seeds, n_win))
    return 0


if __name__ == "__main__":
    sys.exit(main())
