"""CTest campaign_rly_s7_matches_rly_long: the S5/S7 statistics are measured two ways — the campaign
runner flying `sil run --batch` (plant, sealed packets, bridge, executive, fsw_step; the memq streams)
and rly_long (the flight
module alone against the same exact plant, 3e7 ticks in seconds). This checks that they are the same
experiment: over tests/relay/campaign_s7_short.yaml (seeds 1-2, 2000 s, the default table: IMPROVED_UP) every run passes,
and per seed the final k_t is equal (both print it to 1e-6 of the Q0.16 value: the same k_t decisions),
the freeze time agrees, and the true mean envelope of the SIL run is within the estimator's budget of
rly_long's mean of the flight window means.

    python tests/relay/campaign_vs_long.py SIL RLY_LONG OUT_DIR
"""
import os
import shutil
import subprocess
import sys

import pandas as pd

from tools.campaign.store import Store

CAMPAIGN = os.path.join(os.path.dirname(os.path.abspath(__file__)), "campaign_s7_short.yaml")
SEEDS, T_END_S = (1, 2), 2000
# rly_long's abar_late is the mean of the flight's window means (the copy a_fx), the campaign's
# abar_true_from_rad the mean of the plant's true a over the same ticks. Per tick and mode
# |a_fx - a_true| <= (4 + N_changes) 2^-40 rad (spec 20 S3); four modes; N_changes < 300 in 2000 s
# (274 measured): |difference of the means| <= 4 (4 + 300) 2^-40 = 1.1e-9 rad (0.006 % of 2e-5).
ABAR_TOL_RAD = 4 * (4 + 300) * 2.0 ** -40


def main():
    sil, rly_long, out = sys.argv[1:4]
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    subprocess.run([sys.executable, "-m", "tools.campaign", "run", CAMPAIGN, "--out", os.path.join(out, "campaign"),
                    "--workers", "2", "--sil", sil, "--no-progress"], check=True)
    subprocess.run([rly_long, "stats", "--mode", "improved-up", "--seeds", "%d-%d" % SEEDS, "--t", str(T_END_S),
                    "--code", "flight", "--jobs", "1", "--csv", out], check=True)
    c = Store(os.path.join(out, "campaign")).load().set_index("in.table.seed")
    r = pd.read_csv(os.path.join(out, "improved-up_flight_runs.csv")).set_index("seed")
    assert sorted(c.index) == sorted(r.index) == list(range(SEEDS[0], SEEDS[1] + 1)), (c.index, r.index)
    assert (c.status == "ok").all() and c.passed.all(), c[["status", "passed", "reason"]]
    for seed in r.index:
        kc, kr = c.loc[seed, "m.kt_final"], r.loc[seed, "kt_final"]
        fc, fr = c.loc[seed, "m.t_first_freeze_s"], r.loc[seed, "t_first_freeze_s"]
        ac, ar = c.loc[seed, "m.abar_true_from_rad"], r.loc[seed, "abar_late_rad"]
        print("seed %d: k_t final %.6f / %.6f, first freeze %.1f / %.1f s, abar %.6e / %.6e rad (campaign / rly_long)"
              % (seed, kc, kr, fc, fr, ac, ar))
        assert abs(kc - kr) < 0.5e-6, "k_t decisions differ"
        assert (fc < 0) == (not r.loc[seed, "frozen"]) and (fc < 0 or abs(fc - fr) < 1.0), "freeze differs"
        assert abs(ac - ar) <= ABAR_TOL_RAD, "abar differs by %.3g rad > %.3g" % (ac - ar, ABAR_TOL_RAD)
    # the seeds steered k_t apart (equal values would make the comparison weak)
    assert r.kt_final.nunique() == len(r), r.kt_final
    print("campaign and rly_long: the same k_t decisions and envelope for seeds %d-%d" % SEEDS)


if __name__ == "__main__":
    main()
