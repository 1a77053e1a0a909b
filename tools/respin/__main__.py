"""python -m tools.respin {ctable [--check] | image (--table NAME [--revision N] [--set FIELD=INT ...] -o FILE
   | --all DIR) | stats STORE [--compare STORE]} (from the repo root)."""
import argparse
import sys


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m tools.respin")
    sub = ap.add_subparsers(dest="cmd", required=True)
    t = sub.add_parser("ctable", help="write (or --check) the C boot tables fsw/respin/rsp_tables.[ch]")
    t.add_argument("--check", action="store_true")
    im = sub.add_parser("image", help="write binary table images (header + payload) of the boot tables")
    im.add_argument("--table", help="boot table name (design.TABLES)")
    im.add_argument("--all", metavar="DIR", help="write DIR/<name>.bin for every boot table")
    im.add_argument("-o", metavar="FILE", help="output image (with --table)")
    im.add_argument("--revision", type=int, default=1, help="header revision (default 1, as the boot tables)")
    im.add_argument("--set", action="append", metavar="FIELD=INT", help="override a raw field (repeatable)")
    st = sub.add_parser("stats", help="spec 30 §7 figures of a campaign store (A4, A6, A7)")
    st.add_argument("store", help="the campaign's --out directory")
    st.add_argument("--compare", metavar="STORE", help="a second store; also the first restricted to its runs")
    a = ap.parse_args(argv)
    if a.cmd == "stats":
        from . import stats
        return stats.main(a)
    if a.cmd == "ctable":
        from . import ctable
        return ctable.main(a.check)
    from . import image
    return image.main(a)


if __name__ == "__main__":
    sys.exit(main())
