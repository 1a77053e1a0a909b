#!/usr/bin/env python3
"""Guard the compile-line proofs of spec 00 §4 against silent removal.

Some proofs are nothing but a flag on fsw/'s compile line: -mgeneral-regs-only in the host
build ("no float: host") and on Cortex-M4, -ffreestanding -nostdinc in the Cortex-M builds
("freestanding only"). This checks compile_commands.json: every translation unit under
--under (default <repo>/fsw, minus --exclude directories) must carry every --flag.

Usage: check_compile_flags.py -p BUILD_DIR --flag FLAG [--flag FLAG]... [--under DIR]
                              [--exclude DIR]...
Exit status: 0 ok, 1 a flag is missing, 2 usage error or no matching entry.
"""
import argparse
import json
import os
import shlex
import sys


from lintpaths import inside, repo_root  # noqa: E402  (shared helpers)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("-p", dest="build", required=True, help="build dir with compile_commands.json")
    ap.add_argument("--flag", action="append", required=True, help="required flag (repeatable)")
    ap.add_argument("--under", default=os.path.join(repo_root(), "fsw"))
    ap.add_argument("--exclude", action="append", default=[], help="directory to skip")
    ap.add_argument("--why", default="", help="what the flag proves, for the failure message")
    args = ap.parse_args()

    db_path = os.path.join(args.build, "compile_commands.json")
    try:
        with open(db_path, encoding="utf-8") as fh:
            db = json.load(fh)
    except (OSError, ValueError) as e:
        print("check_compile_flags: ERROR: cannot read %s: %s" % (db_path, e), file=sys.stderr)
        return 2
    base = os.path.dirname(os.path.realpath(args.under))
    checked, missing = 0, []
    for e in db:
        f = os.path.join(e.get("directory", ""), e["file"])
        if not inside(f, args.under) or any(inside(f, x) for x in args.exclude):
            continue
        argv = e["arguments"] if "arguments" in e else shlex.split(e["command"])
        checked += 1
        for flag in args.flag:
            if flag not in argv:
                missing.append((os.path.relpath(os.path.realpath(f), base), flag))
    if checked == 0:
        print("check_compile_flags: ERROR: no translation unit under %s in %s"
              % (args.under, db_path), file=sys.stderr)
        return 2
    if missing:
        for f, flag in missing:
            print("check_compile_flags: %s is compiled without %s" % (f, flag))
        print("check_compile_flags: FAIL: %d missing flag(s) on the flight compile line%s"
              % (len(missing), (": " + args.why) if args.why else ""))
        return 1
    print("check_compile_flags: OK: all %d translation unit(s) under %s carry %s"
          % (checked, os.path.relpath(os.path.realpath(args.under), base), " ".join(args.flag)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
