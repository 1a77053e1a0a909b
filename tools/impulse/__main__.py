"""python -m tools.impulse {paper [--check] | ctable [--check] | mc ...} (from the repo root)."""
import argparse
import sys


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m tools.impulse")
    sub = ap.add_subparsers(dest="cmd", required=True)
    pp = sub.add_parser("paper", help="reproduce the paper's example (spec 50 §3.3-3.4)")
    pp.add_argument("--check", action="store_true", help="assert the spec's numbers, exit 1 on mismatch")
    t = sub.add_parser("ctable", help="write (or --check) fsw/impulse/imp_tables.c")
    t.add_argument("--out", default="fsw/impulse/imp_tables.c")
    t.add_argument("--check", action="store_true")
    from . import mc
    mc.add_parser(sub)
    a = ap.parse_args(argv)
    if a.cmd == "paper":
        from . import paper
        return paper.check() if a.check else paper.run()
    if a.cmd == "mc":
        return mc.main(a)
    from . import ctable
    return ctable.main(a)


if __name__ == "__main__":
    sys.exit(main())
