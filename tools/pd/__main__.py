"""python -m tools.pd {ctable [--check] | schedule --analysis BIN [--check] | fest --analysis BIN [--check] | image (--table NAME [--revision N] [--set FIELD=INT ...] -o FILE
   | --all DIR)} (from the repo root)."""
import argparse
import sys


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m tools.pd")
    sub = ap.add_subparsers(dest="cmd", required=True)
    t = sub.add_parser("ctable", help="write (or --check) the C boot tables fsw/pd/pd_tables.[ch]")
    t.add_argument("--check", action="store_true")
    sc = sub.add_parser("schedule", help="write (or --check) tools/pd/schedule/*.json with pd_analysis synth")
    sc.add_argument("--analysis", required=True, help="the pd_analysis executable")
    sc.add_argument("--check", action="store_true")
    fe = sub.add_parser("fest", help="write (or --check) tools/pd/fest/*.json with pd_analysis fest-params")
    fe.add_argument("--analysis", required=True, help="the pd_analysis executable")
    fe.add_argument("--check", action="store_true")
    im = sub.add_parser("image", help="write binary table images (header + payload) of the boot tables")
    im.add_argument("--table", help="boot table name (design.TABLES)")
    im.add_argument("--all", metavar="DIR", help="write DIR/<name>.bin for every boot table")
    im.add_argument("-o", metavar="FILE", help="output image (with --table)")
    im.add_argument("--revision", type=int, default=1, help="header revision (default 1, as the boot tables)")
    im.add_argument("--set", action="append", metavar="FIELD=INT", help="override a raw field (repeatable)")
    a = ap.parse_args(argv)
    if a.cmd == "ctable":
        from . import ctable
        return ctable.main(a.check)
    if a.cmd == "schedule":
        from . import schedule
        return schedule.main(a.analysis, a.check)
    if a.cmd == "fest":
        from . import fest
        return fest.main(a.analysis, a.check)
    from . import image
    return image.main(a)


if __name__ == "__main__":
    sys.exit(main())
