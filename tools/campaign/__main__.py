"""python -m tools.campaign {check | run | report | replay | compare} (from the repo root; README
"Campaigns"):

    check  CAMPAIGN.yaml [--sil SIL]                      validate before any run (runner.check)
    run    CAMPAIGN.yaml --out DIR [--workers N | --scheduler tcp://HOST:8786] [--resume]
           [--runs N] [--sil SIL] [--stop-after N] [--no-report]
    report CAMPAIGN.yaml --out DIR [--no-plots]
    replay CAMPAIGN.yaml RUN --out DIR [--udpm PORT] [--sil SIL]   one run in the LCM SIL, with its
           log, summary, report and plots (memq in one process, or three udpm processes)
    compare DIR_A DIR_B                                   two stores, run by run (wall time aside)

Exit: 0 done (a campaign with failed runs is a result, not an error: see its report), 1 a run
could not be recorded or compare found a difference, 2 a campaign or usage error (nothing flown).
"""
import argparse
import os
import subprocess
import sys


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m tools.campaign")
    sub = ap.add_subparsers(dest="cmd", required=True)
    k = sub.add_parser("check", help="validate a campaign before any run")
    k.add_argument("campaign")
    k.add_argument("--sil")
    r = sub.add_parser("run", help="fly a campaign (Dask) into a store, then write its report")
    r.add_argument("campaign")
    r.add_argument("--out", required=True)
    r.add_argument("--workers", type=int, help="LocalCluster processes (default: all cores)")
    r.add_argument("--scheduler", help="an existing Dask scheduler, tcp://HOST:8786")
    r.add_argument("--resume", action="store_true", help="continue the store's campaign: fly only the runs it lacks")
    r.add_argument("--runs", type=int, help="fly the first N runs only (the inputs of run i do not change)")
    r.add_argument("--sil", help="the sil executable (default: build/host-release, else build/host)")
    r.add_argument("--stop-after", type=int, help="stop after N runs are recorded (an interruption, for tests)")
    r.add_argument("--no-report", action="store_true")
    r.add_argument("--no-progress", action="store_true")
    p = sub.add_parser("report", help="the report of a store")
    p.add_argument("campaign")
    p.add_argument("--out", required=True)
    p.add_argument("--no-plots", action="store_true")
    y = sub.add_parser("replay", help="one run in the LCM SIL with log, summary, report and plots")
    y.add_argument("campaign")
    y.add_argument("run", type=int)
    y.add_argument("--out", required=True)
    y.add_argument("--udpm", type=int, metavar="PORT", help="three udpm processes on loopback (tools/sil/run_udpm.sh)")
    y.add_argument("--sil")
    c = sub.add_parser("compare", help="two stores, run by run")
    c.add_argument("a")
    c.add_argument("b")
    a = ap.parse_args(argv)

    from . import report, runner
    from .spec import Campaign, CampaignError
    if a.cmd == "compare":
        return compare(a.a, a.b)
    sil = os.path.abspath(a.sil) if getattr(a, "sil", None) else runner.default_sil()
    try:
        camp = Campaign(a.campaign)
        if a.cmd == "run" and a.runs is not None:
            if not 0 < a.runs <= camp.runs:
                raise CampaignError("--runs %d: between 1 and the campaign's %d" % (a.runs, camp.runs))
            camp.runs = a.runs
        runner.check(camp, sil)
    except CampaignError as e:
        print("campaign: %s" % e, file=sys.stderr)
        return 2
    if a.cmd == "check":
        print("campaign %s: %s, %d runs, %d dispersions (%d grid combinations), table %s: ok"
              % (camp.name, camp.mission, camp.runs, len(camp.dispersions), camp.grid_size, camp.table_name))
        return 0
    if a.cmd == "run":
        runner.run(camp, a.out, sil, workers=a.workers, scheduler=a.scheduler, resume=a.resume,
                   stop_after=a.stop_after, progress=not a.no_progress)
        if not a.no_report:
            report.main(camp, a.out)
        return 0
    if a.cmd == "report":
        return report.main(camp, a.out, plots=not a.no_plots)
    return replay(camp, a.run, a.out, sil, a.udpm)


def replay(c, i, out, sil, port):
    from . import worker
    os.makedirs(out, exist_ok=True)
    if not 0 <= i < c.runs:
        print("campaign: run %d is not in 0..%d" % (i, c.runs - 1), file=sys.stderr)
        return 2
    path, values = worker.materialise(c, i, out)
    print("run %d inputs: %s" % (i, ", ".join("%s=%s" % kv for kv in values.items())))
    root = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
    if port:
        cmd = ["bash", os.path.join(root, "tools", "sil", "run_udpm.sh"), path, out, str(port), sil]
    else:
        cmd = [sil, "run", "--scenario", path, "--log", os.path.join(out, "run.lcmlog"),
               "--summary", os.path.join(out, "summary.txt"), "--summary-json", os.path.join(out, "summary.json")]
    print("$ " + " ".join(cmd), flush=True)
    rc = subprocess.run(cmd, stdout=subprocess.DEVNULL).returncode
    if rc != 0:
        return rc
    cmd = [sys.executable, "-m", "tools.sil", "report", os.path.join(out, "run.lcmlog"), "--out", out,
           "--summary", os.path.join(out, "summary.json")]
    print("$ " + " ".join(cmd), flush=True)
    return subprocess.run(cmd, cwd=root).returncode


def compare(a, b):
    from .store import Store
    da, db = Store(a).load(), Store(b).load()
    keep = lambda d: d[[x for x in d.columns if x != "wall_s"]].reset_index(drop=True)
    da, db = keep(da), keep(db)
    if list(da.columns) != list(db.columns) and set(da.columns) == set(db.columns):
        db = db[list(da.columns)]
    same = da.shape == db.shape and list(da.columns) == list(db.columns) and da.equals(db)
    print("compare: %s %d runs, %s %d runs: %s" % (a, len(da), b, len(db), "identical (wall time aside)" if same
                                                   else "DIFFERENT"))
    if not same and da.shape == db.shape and list(da.columns) == list(db.columns):
        diff = (da != db) & ~(da.isna() & db.isna())
        rows = diff.any(axis=1)
        print("  differing runs: %s" % da.loc[rows, "run"].tolist()[:20])
    return 0 if same else 1


if __name__ == "__main__":
    sys.exit(main())
