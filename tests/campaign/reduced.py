"""A mission's campaign definition, reduced (CTests campaign_<prefix>_*): the first N runs on a
LocalCluster, then the report; fails when a run could not be flown (error, timeout) or when fewer
than --min-rate of the runs pass the campaign's own criteria.

    python tests/campaign/reduced.py CAMPAIGN.yaml --runs N --min-rate R --sil SIL --out DIR
"""
import argparse
import json
import os
import shutil
import subprocess
import sys


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("campaign")
    ap.add_argument("--runs", type=int, required=True)
    ap.add_argument("--min-rate", type=float, required=True)
    ap.add_argument("--sil", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--workers", type=int, default=2)
    a = ap.parse_args(argv)
    shutil.rmtree(a.out, ignore_errors=True)
    r = subprocess.run([sys.executable, "-m", "tools.campaign", "run", a.campaign, "--out", a.out, "--runs", str(a.runs),
                        "--workers", str(a.workers), "--sil", a.sil, "--no-progress"])
    if r.returncode != 0:
        return 1
    with open(os.path.join(a.out, "report.json"), encoding="utf-8") as fh:
        rep = json.load(fh)
    flown = rep.get("status", {})
    lost = {k: v for k, v in flown.items() if k not in ("ok", "fail")}
    rate = rep.get("success_rate", 0.0)
    ok = rep["recorded"] == a.runs and not lost and rate >= a.min_rate
    print("reduced campaign %s: %d runs, status %s, passed %.1f %% (min %.1f %%): %s"
          % (rep["campaign"], rep["recorded"], flown, 100 * rate, 100 * a.min_rate, "ok" if ok else "FAIL"))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
