"""python -m tools.sil {report LOG --out DIR [--summary S.json] | agree S.json R.json |
compare LOG_A LOG_B [--channel CH ...]} (from the repo root). No command names a mission: the
report finds it from the log (tools/sil/report.py)."""
import argparse
import sys

from .lcmio import DEFAULT_LCM_PY


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m tools.sil")
    sub = ap.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("report", help="summary, fault counters and plots of one SIL log (any mission)")
    r.add_argument("log")
    r.add_argument("--out", required=True, help="output directory (report.txt, report.json, *.png)")
    r.add_argument("--summary", metavar="SUMMARY.json",
                   help="the run's own summary (sil run|plant --summary-json): its figures replace the "
                        "report's re-derivation; without it every figure is derived from the log")
    r.add_argument("--lcm-py", default=DEFAULT_LCM_PY,
                   help="lcm-gen Python bindings dir (default %(default)s; generated if missing)")
    r.add_argument("--json", help="also write the report JSON to this file")
    r.add_argument("--no-plots", action="store_true", help="skip the PNG plots")
    g = sub.add_parser("agree", help="compare a report's own derivation (report --json, no --summary) "
                                     "with the run's summary.json; exit 1 on any disagreement")
    g.add_argument("summary", metavar="SUMMARY.json")
    g.add_argument("report", metavar="REPORT.json")
    g.add_argument("--quiet", action="store_true", help="print only the disagreements and the verdict")
    g.add_argument("--nudge", metavar="KEY",
                   help="self-test: then move the summary's KEY by one ulp and require a disagreement")
    c = sub.add_parser("compare", help="byte-compare the messages of channels between two logs")
    c.add_argument("log_a")
    c.add_argument("log_b")
    c.add_argument("--channel", action="append",
                   help="channel to compare (repeatable; default GNC_TLM and GNC_CMD)")
    c.add_argument("--dedup", action="store_true",
                   help="drop a message equal to the previous one on its channel (udpm re-publications)")
    c.add_argument("--lcm-py", default=DEFAULT_LCM_PY, help="bindings, only for the field diff of a mismatch")
    a = ap.parse_args(argv)
    if a.cmd == "report":
        from . import report
        return report.main(a)
    if a.cmd == "agree":
        from . import agree
        return agree.main(a)
    from . import compare
    return compare.main(a)


if __name__ == "__main__":
    sys.exit(main())
