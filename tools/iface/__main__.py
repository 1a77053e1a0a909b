"""python -m tools.iface {c [--check] | build --missions A,B|all --out DIR [--no-host] |
   pattern --missions A,B|all --out FILE | show [MISSION]}
(from the repo root). README 'Design: one module, one folder'."""
import argparse
import sys


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m tools.iface")
    sub = ap.add_subparsers(dest="cmd", required=True)
    c = sub.add_parser("c", help="write (or --check) the committed C generated from the descriptions")
    c.add_argument("--check", action="store_true")
    b = sub.add_parser("build", help="write the build-tree dispatch and host tables for a configuration")
    b.add_argument("--missions", required=True, help="comma-separated mission names, or 'all'")
    b.add_argument("--out", required=True)
    b.add_argument("--no-host", action="store_true", help="flight dispatch only (cross builds)")
    b.add_argument("--cmake", action="store_true", help="also write missions.cmake (the configured lists)")
    t = sub.add_parser("pattern", help="write the telemetry layout test's field filler (tests/iface)")
    t.add_argument("--missions", required=True, help="comma-separated mission names, or 'all'")
    t.add_argument("--out", required=True, help="the C file to write")
    s = sub.add_parser("show", help="print a mission's telemetry layout (or the registry)")
    s.add_argument("mission", nargs="?")
    a = ap.parse_args(argv)
    from . import IfaceError
    try:
        if a.cmd == "c":
            from . import gen_c
            return gen_c.main(a.check)
        if a.cmd in ("build", "pattern"):
            from . import gen_build
            names = None if a.missions.strip().lower() == "all" else [x.strip() for x in a.missions.split(",") if x.strip()]
            if a.cmd == "pattern":
                return gen_build.write_pattern(names, a.out)
            return gen_build.main(names, a.out, host=not a.no_host, with_cmake=a.cmake)
        from . import missions, mission
        if a.mission is None:
            for m in missions():
                print("%-12s id %d mode %d module %-10s layout 0x%08X %4d bytes, table 0x%04X"
                      % (m.name, m.id, m.mode, m.module, m.layout_version, m.layout.nbytes, m.iface.table_id))
            return 0
        m = mission(a.mission)
        for f in m.layout.fields:
            print("%4d  %-24s %-4s %4s  %-10s %s" % (m.layout.offset[f.name], f.name, f.type,
                                                      "" if f.q is None else "q%d" % f.q, f.unit, f.note))
        return 0
    except IfaceError as e:
        print("iface: %s" % e, file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
