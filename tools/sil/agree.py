"""Do the report's own derivation and the run's live metrics agree? (one SIL run, any mission)

    python -m tools.sil agree SUMMARY.json REPORT.json [--quiet] [--nudge KEY]

SUMMARY.json: `sil run|plant --summary-json` (C++: hil_host/sil/metrics.cpp and the mission's
hil_host/missions/<module>/*_metrics.cpp). REPORT.json: `python -m tools.sil report LOG --json`
of the same run's log WITHOUT --summary, i.e. every figure derived from the log in Python.
The key map is tools.sil.report.CORE_KEYS plus the mission's tools.<module>.report.SUMMARY_KEYS:
every figure present in both is compared, exactly where both compute it the same way from the
same doubles, within the key's written tolerance where they do not; an entry of the map that is
missing on either side (a renamed key) is a failure too. Exit 0 iff everything agrees.

--nudge KEY also proves that the check can fail: after the real comparison it moves the
summary's KEY (a number) by one unit in the last place and requires a disagreement. Exit 0 iff
the real comparison agrees and the nudged one does not.
"""
import json
import math

from tools import iface

from . import report


def load(path):
    with open(path) as fh:
        return json.load(fh)


def check(s, r, mod, mission, quiet):
    rows, missing = report.compare(r, s, report.key_map(mod))
    w = max([len(x[0]) for x in rows] + [10])
    nbad = 0
    for rp, sk, rv, sv, tol, ok, why in rows:
        nbad += not ok
        if ok and quiet:
            continue
        if isinstance(rv, (int, float)) and isinstance(sv, (int, float)) and not isinstance(rv, bool):
            d = "|d| %.3g" % abs(float(rv) - float(sv))
        else:
            d = ""
        print("%-4s %-*s %-26s log %-24r run %-24r %-12s %s" % (
            "ok" if ok else "BAD", w, rp, sk, rv, sv, d, "exact" if tol is None else "tol %g (%s)" % (tol, why)))
    for x in missing:
        print("MISSING %s" % x)
    n = len(rows)
    exact = sum(1 for x in rows if x[4] is None)
    print("agree %s: %d figures compared (%d exact, %d within a tolerance), %d disagree, %d key-map entries missing"
          % (mission.name, n, exact, n - exact, nbad, len(missing)))
    return nbad == 0 and not missing and n > 0


def main(args):
    s, r = load(args.summary), load(args.report)
    src = r.get("figures_from", {})
    if src.get("summary"):
        print("agree: %s was written with --summary %s: its figures are the summary's, not a derivation"
              % (args.report, src["summary"]))
        return 1
    try:
        mission = iface.mission(r["mission"])
    except (KeyError, iface.IfaceError) as e:
        print("agree: %s names no registered mission (%s)" % (args.report, e))
        return 1
    if s.get("mission") != mission.name:
        print("agree: the summary is a %s run, the report a %s run" % (s.get("mission"), mission.name))
        return 1
    mod = report.report_module(mission)
    ok = check(s, r, mod, mission, args.quiet)
    if not args.nudge:
        return 0 if ok else 1
    v = s.get(args.nudge)
    if isinstance(v, bool) or not isinstance(v, (int, float)):
        print("agree: --nudge %s: not a number in the summary" % args.nudge)
        return 1
    s[args.nudge] = math.nextafter(float(v), math.inf)
    print("agree: self-test, summary %s moved by one ulp (%r -> %r):" % (args.nudge, v, s[args.nudge]))
    caught = not check(s, r, mod, mission, True)
    print("agree: the nudge was %s" % ("caught" if caught else "NOT caught: the check cannot fail"))
    return 0 if (ok and caught) else 1
