"""python -m tools.observer {design --out DIR | ctable [--check] | truth --out H | check [GROUP ...] |
   image (--table NAME [--revision N] [--set FIELD=INT ...] -o FILE | --all DIR) |
   table (--config CFG.yaml -o FILE [--revision N] | --keys)} (from the repo root)."""
import argparse
import sys


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m tools.observer")
    sub = ap.add_subparsers(dest="cmd", required=True)
    d = sub.add_parser("design", help="write the observer tables as JSON")
    d.add_argument("--out", required=True)
    t = sub.add_parser("ctable", help="write (or --check) the C boot tables fsw/observer/obs_tables.[ch]")
    t.add_argument("--out-dir", default="fsw/observer")
    t.add_argument("--check", action="store_true")
    u = sub.add_parser("truth", help="write the true-plant ZOH header for host tests")
    u.add_argument("--out", required=True)
    c = sub.add_parser("check", help="run acceptance checks and print measured vs spec")
    c.add_argument("groups", nargs="*", help="s01 s02 s03 flight s06 ranges (default: all)")
    im = sub.add_parser("image", help="write binary observer-table images (header + payload) of the boot tables")
    im.add_argument("--table", choices=["obs_50hz_phys", "obs_50hz_paper", "obs_5hz_paper", "obs_paper_printed"])
    im.add_argument("--all", metavar="DIR", help="write DIR/<name>.bin for all four tables")
    im.add_argument("-o", metavar="FILE", help="output image (with --table)")
    im.add_argument("--revision", type=int, default=1, help="header revision (default 1, as the boot tables)")
    im.add_argument("--set", action="append", metavar="FIELD=INT",
                    help="override an obs_params_t field with a raw integer before the CRC (repeatable; "
                         "FIELD[i]=INT for one vector entry, hdr.FIELD=INT for a header word)")
    tb = sub.add_parser("table", help="design the observer table of a detumbling mission configuration (YAML) "
                                      "and write its image")
    tb.add_argument("--config", metavar="CFG.yaml", help="mission configuration (keys: --keys)")
    tb.add_argument("-o", metavar="IMAGE.bin", help="output image")
    tb.add_argument("--revision", type=int, default=1, help="header revision (default 1)")
    tb.add_argument("--keys", action="store_true", help="print the configuration keys (markdown table) and exit")
    a = ap.parse_args(argv)
    if a.cmd == "table":
        from . import config
        return config.main(a)
    if a.cmd == "image":
        from . import image
        return image.main(a)
    if a.cmd == "design":
        from . import design
        for pth in design.write(a.out):
            print(pth)
        return 0
    if a.cmd in ("ctable", "truth"):
        from . import ctable
        return ctable.main(a)
    from . import checks
    groups = a.groups or list(checks.GROUPS)
    unknown = [g for g in groups if g not in checks.GROUPS]
    if unknown:
        ap.error("unknown check group(s) %s; choose from %s" % (unknown, list(checks.GROUPS)))
    return checks.run(groups)


if __name__ == "__main__":
    sys.exit(main())
