#!/usr/bin/env python3
"""Freestanding-only proof, source half (spec 00 §4 "freestanding only").

Every `#include <...>` in fsw/ may name only <stdint.h> <stdbool.h> <stddef.h> <limits.h>.
Also rejected, because they would defeat the rule:
  - `#include "x.h"` that does not resolve to a file inside fsw/ (a quoted include that is not
    found locally falls back to the system search path, so "stdio.h" would reach libc);
  - computed includes (`#include MACRO`), `#include_next` and `#import`.
fsw/target may include its own BSP headers with quotes; it gets no extra system headers
(TARGET_EXTRA_SYSTEM below is the place to add one, with a reason, if a board ever needs it).

Usage: check_includes.py [--fsw DIR]      (default: <repo>/fsw)
Exit status: 0 clean, 1 findings, 2 usage or I/O error.
"""
import argparse
import os
import re
import sys

sys.dont_write_bytecode = True      # no __pycache__ in the source tree
import clex  # noqa: E402  (sibling module: a script's directory is on sys.path; see lintpaths.py)

ALLOWED_SYSTEM = ("stdint.h", "stdbool.h", "stddef.h", "limits.h")
TARGET_EXTRA_SYSTEM = ()          # system headers fsw/target alone may add (none today)
SOURCE_EXT = (".c", ".h", ".inc", ".def")

_HDR_ANGLE = re.compile(r"^\s*<([^>]*)>\s*$")
_HDR_QUOTE = re.compile(r'^\s*"([^"]*)"\s*$')


from lintpaths import inside, repo_root  # noqa: E402  (shared helpers)


def source_files(fsw):
    for d, subdirs, files in os.walk(fsw):
        subdirs.sort()
        for f in sorted(files):
            if f.endswith(SOURCE_EXT):
                yield os.path.join(d, f)


def resolve_quoted(name, including_file, roots, fsw_dirs):
    """Path of a quoted include inside fsw/ (or the generated flight code), or None. Search order:
    the including file's directory, then every directory of fsw/ (a superset of the build's -I
    list)."""
    for d in [os.path.dirname(including_file)] + fsw_dirs:
        cand = os.path.normpath(os.path.join(d, name))
        if os.path.isfile(cand) and any(inside(cand, r) for r in roots):
            return cand
    return None


def check_file(path, fsw, roots, fsw_dirs, display):
    findings = []
    try:
        with open(path, encoding="utf-8", errors="replace") as fh:
            text = clex.strip_comments(fh.read())
    except OSError as e:
        raise SystemExit("check_includes: cannot read %s: %s" % (path, e))
    in_target = inside(path, os.path.join(fsw, "target"))
    allowed = ALLOWED_SYSTEM + (TARGET_EXTRA_SYSTEM if in_target else ())
    for lineno, line in enumerate(text.split("\n"), start=1):
        d = clex.directive(line)
        if d is None:
            continue
        name, rest = d
        where = "%s:%d" % (display(path), lineno)
        if name in ("include_next", "import"):
            findings.append("%s: '#%s' is not allowed in flight code" % (where, name))
            continue
        if name != "include":
            continue
        m = _HDR_ANGLE.match(rest)
        if m:
            hdr = m.group(1).strip()
            if hdr not in allowed:
                findings.append(
                    "%s: forbidden system header <%s>; fsw/ may include only %s"
                    % (where, hdr, " ".join("<%s>" % h for h in allowed)))
            continue
        m = _HDR_QUOTE.match(rest)
        if m:
            hdr = m.group(1)
            if resolve_quoted(hdr, path, roots, fsw_dirs) is None:
                findings.append(
                    '%s: quoted include "%s" does not resolve to a file inside fsw/ '
                    "(the compiler would fall back to the system search path)" % (where, hdr))
            continue
        findings.append("%s: computed or malformed include '#include%s' cannot be verified"
                        % (where, rest.rstrip()))
    return findings


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--fsw", default=os.path.join(repo_root(), "fsw"),
                    help="flight source tree to check (default: <repo>/fsw)")
    ap.add_argument("--gen", action="append", default=[],
                    help="a directory of generated flight code (the mission dispatch in the build "
                         "tree): its C files are checked as flight code too")
    args = ap.parse_args()
    fsw = os.path.abspath(args.fsw)
    gens = [os.path.abspath(g) for g in args.gen]
    roots = [fsw] + gens
    if not os.path.isdir(fsw):
        print("check_includes: ERROR: %s is not a directory" % fsw, file=sys.stderr)
        return 2
    base = os.path.dirname(fsw)

    def display(p):
        return os.path.relpath(p, base) if inside(p, base) else p

    files = list(source_files(fsw))
    for g in gens:
        files += list(source_files(g))
    fsw_dirs = sorted({os.path.dirname(p) for p in files} | {fsw})
    if not files:
        print("check_includes: ERROR: no C sources under %s" % fsw, file=sys.stderr)
        return 2
    findings = []
    for f in files:
        findings.extend(check_file(f, fsw, roots, fsw_dirs, display))
    if findings:
        for f in findings:
            print(f)
        print("check_includes: FAIL: %d forbidden include(s) in %s (spec 00 §4 'freestanding only')"
              % (len(findings), display(fsw)))
        return 1
    print("check_includes: OK: %d files under %s include only %s and headers inside fsw/"
          % (len(files), display(fsw), " ".join("<%s>" % h for h in ALLOWED_SYSTEM)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
