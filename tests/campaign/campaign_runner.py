"""The campaign runner's guarantees on a reduced campaign (CTest campaign_runner, label sil).

    python tests/campaign/campaign_runner.py --campaign C.yaml --runs N --sil SIL --out DIR --port P

1. one LocalCluster worker, the first N runs: the reference store A;
2. two workers, stopped after N/2 recorded runs (an interruption), then --resume: store B — every
   run recorded exactly once, and A == B run by run (inputs, status, metrics; wall time aside);
3. a separately started `dask scheduler` and two `dask worker` processes (--scheduler): store C == A;
4. run 1 of A replayed in the LCM SIL as three udpm processes (`replay --udpm P`): its summary's
   metrics equal A's record of run 1 exactly.
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import time

import pandas as pd

PY = sys.executable


def campaign(*args):
    cmd = [PY, "-m", "tools.campaign"] + list(args)
    print("$ " + " ".join(cmd), flush=True)
    r = subprocess.run(cmd, capture_output=True, text=True)
    tail = (r.stdout + r.stderr).strip().splitlines()[-3:]
    for line in tail:
        print("  " + line)
    if r.returncode != 0:
        raise SystemExit("campaign_runner: %s exited %d" % (args[0], r.returncode))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--campaign", required=True)
    ap.add_argument("--runs", type=int, default=6)
    ap.add_argument("--sil", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--port", type=int, required=True, help="udpm port of the replay")
    a = ap.parse_args(argv)
    shutil.rmtree(a.out, ignore_errors=True)
    os.makedirs(a.out)
    A, B, C = (os.path.join(a.out, x) for x in "ABC")
    common = [a.campaign, "--runs", str(a.runs), "--sil", a.sil, "--no-progress", "--no-report"]
    bad = []

    campaign("run", *common, "--out", A, "--workers", "1")
    campaign("run", *common, "--out", B, "--workers", "2", "--stop-after", str(a.runs // 2))
    parts_before = len(os.listdir(os.path.join(B, "results")))
    campaign("run", *common, "--out", B, "--workers", "2", "--resume")
    for raw in [pd.concat([pd.read_parquet(os.path.join(B, "results", p))
                           for p in sorted(os.listdir(os.path.join(B, "results")))])]:
        if sorted(raw["run"].tolist()) != list(range(a.runs)):
            bad.append("store B after resume holds runs %s, expected each of 0..%d once"
                       % (sorted(raw["run"].tolist()), a.runs - 1))
    print("B: %d parts before --resume, every run once" % parts_before)
    if subprocess.run([PY, "-m", "tools.campaign", "compare", A, B]).returncode != 0:
        bad.append("A (1 worker) != B (2 workers, interrupted and resumed)")

    sched = os.path.join(a.out, "scheduler.json")
    dask = os.path.join(os.path.dirname(PY), "dask")
    procs = [subprocess.Popen([dask, "scheduler", "--port", "0", "--dashboard-address", ":0", "--scheduler-file", sched],
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)]
    try:
        for _ in range(200):
            if os.path.exists(sched):
                break
            time.sleep(0.1)
        for _ in range(2):
            procs.append(subprocess.Popen([dask, "worker", "--scheduler-file", sched, "--nthreads", "1",
                                           "--dashboard-address", ":0"],
                                          stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
        with open(sched, encoding="utf-8") as fh:
            addr = json.load(fh)["address"]
        from dask.distributed import Client
        with Client(addr, timeout=30) as cl:
            cl.wait_for_workers(2, timeout=60)
        campaign("run", *common, "--out", C, "--scheduler", addr)
    finally:
        for p in procs[::-1]:
            p.terminate()
        for p in procs:
            try:
                p.wait(timeout=10)
            except subprocess.TimeoutExpired:
                p.kill()
    if subprocess.run([PY, "-m", "tools.campaign", "compare", A, C]).returncode != 0:
        bad.append("A (LocalCluster) != C (separate scheduler, two worker processes)")

    R = os.path.join(a.out, "replay")
    campaign("replay", a.campaign, "1", "--out", R, "--udpm", str(a.port), "--sil", a.sil)
    with open(os.path.join(R, "summary.json"), encoding="utf-8") as fh:
        s = json.load(fh)
    rec = pd.read_parquet(os.path.join(A, "results")).set_index("run").loc[1]
    for col in [c for c in rec.index if c.startswith("m.")]:
        k = col[2:]
        same = k in s and (float(s[k]) == float(rec[col]) or (pd.isna(rec[col]) and pd.isna(s[k])))
        print("  replay run 1 %-28s udpm %-14s campaign %-14s %s" % (k, s.get(k), rec[col], "same" if same else "DIFF"))
        if not same:
            bad.append("replayed run 1: %s udpm %s, campaign %s" % (k, s.get(k), rec[col]))
    for b in bad:
        print("FAIL: " + b)
    print("campaign_runner: %s" % ("ok" if not bad else "%d failure(s)" % len(bad)))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
