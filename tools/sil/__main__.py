"""python -m tools.sil {report LOG --out DIR | compare LOG_A LOG_B [--channel CH ...] | gen-tlm-rdv [--check]}
(from the repo root)."""
import argparse
import sys

from .lcmio import DEFAULT_LCM_PY


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m tools.sil")
    sub = ap.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("report", help="summary, fault counters and plots of one SIL log")
    r.add_argument("log")
    r.add_argument("--out", required=True, help="output directory (summary.txt, summary.json, *.png)")
    r.add_argument("--lcm-py", default=DEFAULT_LCM_PY,
                   help="lcm-gen Python bindings dir (default %(default)s; generated if missing)")
    r.add_argument("--json", help="also write the summary JSON to this file")
    r.add_argument("--no-plots", action="store_true", help="skip the PNG plots")
    g = sub.add_parser("gen-tlm-rdv", help="write (or --check) the RENDEZVOUS telemetry encoder, JSON and decoder table")
    g.add_argument("--check", action="store_true")
    c = sub.add_parser("compare", help="byte-compare the messages of channels between two logs")
    c.add_argument("log_a")
    c.add_argument("log_b")
    c.add_argument("--channel", action="append",
                   help="channel to compare (repeatable; default GNC_TLM and GNC_CMD)")
    c.add_argument("--dedup", action="store_true",
                   help="drop a message equal to the previous one on its channel (udpm re-publications)")
    c.add_argument("--lcm-py", default=DEFAULT_LCM_PY, help="bindings, only for the field diff of a mismatch")
    a = ap.parse_args(argv)
    if a.cmd == "gen-tlm-rdv":
        from . import gen_tlm_rdv
        return gen_tlm_rdv.main(a.check)
    if a.cmd == "report":
        from tools.impulse import report as report_rdv
        if report_rdv.is_rdv_log(a.log, a.lcm_py):
            return report_rdv.main(a)
        from tools.observer import report
        return report.main(a)
    from . import compare
    return compare.main(a)


if __name__ == "__main__":
    sys.exit(main())
