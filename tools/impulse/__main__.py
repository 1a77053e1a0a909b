"""python -m tools.impulse {paper [--check] | ctable [--check] | mc ... |
   image (--table NAME [--revision N] [--set FIELD=INT ...] -o FILE | --all DIR) |
   table (--config CFG.yaml -o FILE [--revision N] | --keys)} (from the repo root)."""
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
    im = sub.add_parser("image", help="write binary impulse-table images (header + payload) of the boot tables")
    im.add_argument("--table", choices=["imp_default", "imp_1s", "imp_sub1ms"])
    im.add_argument("--all", metavar="DIR", help="write DIR/<name>.bin for all three tables")
    im.add_argument("-o", metavar="FILE", help="output image (with --table)")
    im.add_argument("--revision", type=int, default=1, help="header revision (default 1, as the boot tables)")
    im.add_argument("--set", action="append", metavar="FIELD=INT",
                    help="override an imp_params_t field with a raw integer before the CRC (repeatable; "
                         "FIELD[i]=INT for one vector entry, hdr.FIELD=INT for a header word)")
    tb = sub.add_parser("table", help="write the impulse-table image of a rendezvous mission configuration (YAML)")
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
    if a.cmd == "paper":
        from . import paper
        return paper.check() if a.check else paper.run()
    if a.cmd == "mc":
        return mc.main(a)
    from . import ctable
    return ctable.main(a)


if __name__ == "__main__":
    sys.exit(main())
