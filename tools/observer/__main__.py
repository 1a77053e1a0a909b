"""python -m tools.observer {design --out DIR | check [GROUP ...]} (run from the repository root)."""
import argparse
import sys


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m tools.observer")
    sub = ap.add_subparsers(dest="cmd", required=True)
    d = sub.add_parser("design", help="write the observer tables as JSON")
    d.add_argument("--out", required=True)
    c = sub.add_parser("check", help="run acceptance checks and print measured vs spec")
    c.add_argument("groups", nargs="*", help="s01 s02 s03 flight s06 ranges (default: all)")
    a = ap.parse_args(argv)
    if a.cmd == "design":
        from . import design
        for pth in design.write(a.out):
            print(pth)
        return 0
    from . import checks
    groups = a.groups or list(checks.GROUPS)
    unknown = [g for g in groups if g not in checks.GROUPS]
    if unknown:
        ap.error("unknown check group(s) %s; choose from %s" % (unknown, list(checks.GROUPS)))
    return checks.run(groups)


if __name__ == "__main__":
    sys.exit(main())
