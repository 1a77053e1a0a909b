#!/usr/bin/env python3
"""No-float proof, source half (spec 00 §4 "no float: source").

Rejects `float`, `double` (and the other floating/complex/decimal type names) and every
floating literal in flight code. Two passes:

 1. Preprocessed: every .c under fsw/ is run through `<cc> -E` with the project's flags, taken
    from compile_commands.json of a build when -p is given (so macros from any header are
    seen expanded), or else with `-std=c99 -I<every directory of fsw/>`. The force-included
    guard header (fx_guard.h) is left out, so that its `#pragma GCC poison` does not stop the
    preprocessor before this scan can report. Tokens are attributed to file:line through the
    line markers, and only tokens coming from files inside fsw/ are checked (system headers
    are not flight code). `#pragma` lines are skipped.
 2. Source: every .c/.h under fsw/, comments stripped, so that a floating literal in a macro
    that nothing expands yet (or in an #if 0 block) is also rejected. #pragma, #include,
    #error and #warning lines are skipped.

GCC folds `a > 0.5` into an integer compare even at -O0, so neither binary proof (nm, the
-mgeneral-regs-only compiles) can see such a literal; this scan is the only one that does.

Usage: scan_float.py [--fsw DIR] [-p BUILD_DIR] [--cc CC] [-I DIR]... [-D MACRO]...
Exit status: 0 clean, 1 findings, 2 usage, preprocessing or I/O error.
"""
import argparse
import json
import os
import re
import shlex
import subprocess
import sys

sys.dont_write_bytecode = True      # no __pycache__ in the source tree
import clex  # noqa: E402  (sibling module: a script's directory is on sys.path; see lintpaths.py)

GUARD_NAMES = ("fx_guard.h",)
_LINEMARK = re.compile(r'^#\s*(?:line\s+)?(\d+)\s+"((?:\\.|[^"\\])*)"')


from lintpaths import inside, repo_root  # noqa: E402  (shared helpers)


def walk(fsw, exts):
    for d, subdirs, files in os.walk(fsw):
        subdirs.sort()
        for f in sorted(files):
            if f.endswith(exts):
                yield os.path.join(d, f)


def entry_args(entry):
    if "arguments" in entry:
        return list(entry["arguments"])
    return shlex.split(entry["command"])


def preprocess_args(args, src, cwd):
    """Turn a compile command into a preprocess-to-stdout command."""
    out = []
    skip_next = False
    for i, a in enumerate(args):
        if skip_next:
            skip_next = False
            continue
        if a in ("-o", "-MF", "-MT", "-MQ"):
            skip_next = True
            continue
        if a == "-include" and i + 1 < len(args) and os.path.basename(args[i + 1]) in GUARD_NAMES:
            skip_next = True
            continue
        if a.startswith("-include") and os.path.basename(a[len("-include"):]) in GUARD_NAMES:
            continue
        if a in ("-c", "-MD", "-MMD", "-fstack-usage") or a.startswith(("-fcallgraph-info", "-o")):
            continue
        if (os.path.basename(a) == os.path.basename(src)
                and os.path.realpath(os.path.join(cwd, a)) == os.path.realpath(src)):
            continue
        out.append(a)
    return out + ["-E", src, "-o", "-"]


def scan_preprocessed(text, roots, display, findings):
    cur_file = None
    cur_line = 0
    for raw in text.split("\n"):
        if raw.startswith("#"):
            m = _LINEMARK.match(raw)
            if m:
                cur_line = int(m.group(1))
                cur_file = m.group(2).encode().decode("unicode_escape")
                continue
            cur_line += 1            # #pragma, #ident: not code
            continue
        if cur_file is not None and any(inside(cur_file, r) for r in roots):
            for kind, value, _ in clex.tokens(raw):
                what = clex.float_findings(kind, value)
                if what:
                    findings.setdefault((display(cur_file), cur_line, what), set()).add("preprocessed")
        cur_line += 1


def scan_source(path, display, findings):
    with open(path, encoding="utf-8", errors="replace") as fh:
        text = clex.strip_comments(fh.read())
    for lineno, line in enumerate(text.split("\n"), start=1):
        d = clex.directive(line)
        if d is not None and d[0] in ("pragma", "include", "error", "warning", "ident", "line"):
            continue
        for kind, value, _ in clex.tokens(line):
            what = clex.float_findings(kind, value)
            if what:
                findings.setdefault((display(path), lineno, what), set()).add("source")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--fsw", default=os.path.join(repo_root(), "fsw"),
                    help="flight source tree (default: <repo>/fsw)")
    ap.add_argument("-p", dest="build", help="build directory holding compile_commands.json")
    ap.add_argument("--cc", default=os.environ.get("CC", "gcc"),
                    help="preprocessor driver for files not in compile_commands.json (default gcc)")
    ap.add_argument("-I", dest="incs", action="append", default=[], help="extra include dir")
    ap.add_argument("-D", dest="defs", action="append", default=[], help="extra macro")
    ap.add_argument("--gen", action="append", default=[],
                    help="a directory of generated flight code (the mission dispatch in the build "
                         "tree): scanned as flight code too")
    args = ap.parse_args()

    fsw = os.path.abspath(args.fsw)
    gens = [os.path.abspath(g) for g in args.gen]
    roots = [fsw] + gens
    if not os.path.isdir(fsw):
        print("scan_float: ERROR: %s is not a directory" % fsw, file=sys.stderr)
        return 2
    base = os.path.dirname(fsw)

    def display(p):
        return os.path.relpath(os.path.realpath(p), os.path.realpath(base)) if inside(p, base) else p

    sources = list(walk(fsw, (".c",)))
    for g in gens:
        sources += list(walk(g, (".c",)))
    if not sources:
        print("scan_float: ERROR: no .c files under %s" % fsw, file=sys.stderr)
        return 2

    commands = {}
    if args.build:
        cc_json = os.path.join(args.build, "compile_commands.json")
        try:
            with open(cc_json, encoding="utf-8") as fh:
                db = json.load(fh)
        except (OSError, ValueError) as e:
            print("scan_float: ERROR: cannot read %s: %s" % (cc_json, e), file=sys.stderr)
            return 2
        for e in db:
            f = os.path.join(e.get("directory", ""), e["file"])
            if any(inside(f, r) for r in roots):
                commands[os.path.realpath(f)] = (e.get("directory") or ".", entry_args(e))

    fallback_dirs = sorted({os.path.dirname(p) for r in roots for p in walk(r, (".h",))} | {fsw})
    fallback = ([args.cc, "-std=c99"] + ["-I" + d for d in args.incs + fallback_dirs]
                + ["-D" + d for d in args.defs])

    findings = {}
    notes = []
    from_db = 0
    for src in sources:
        key = os.path.realpath(src)
        if key in commands:
            cwd, cargs = commands[key]
            cmd = preprocess_args(cargs, src, cwd) + ["-I" + d for d in args.incs] + ["-D" + d for d in args.defs]
            from_db += 1
        else:
            cwd, cmd = fsw, fallback + ["-E", src, "-o", "-"]
        try:
            res = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                 universal_newlines=True, check=False)
        except OSError as e:
            print("scan_float: ERROR: cannot run %s: %s" % (cmd[0], e), file=sys.stderr)
            return 2
        if res.returncode != 0 and key not in commands:
            # Not built in this configuration (e.g. fsw/target in the host build, or a board
            # variant guarded by #error): the source pass below still covers it, and the
            # build that compiles it runs this scan with its own compile_commands.json.
            first = (res.stderr.strip().splitlines() or ["?"])[0]
            notes.append("%s: not built in this configuration and does not preprocess with the "
                         "generic flags (%s); scanned as source only" % (display(src), first))
            continue
        if res.returncode != 0:
            print(res.stderr, file=sys.stderr)
            print("scan_float: ERROR: preprocessing %s failed (exit %d): %s"
                  % (display(src), res.returncode, " ".join(shlex.quote(c) for c in cmd)),
                  file=sys.stderr)
            return 2
        scan_preprocessed(res.stdout, roots, display, findings)

    all_files = [f for r in roots for f in walk(r, (".c", ".h", ".inc", ".def"))]
    for f in all_files:
        scan_source(f, display, findings)

    for n in notes:
        print("scan_float: note: " + n)
    if len(notes) == len(sources):
        print("scan_float: ERROR: no translation unit under %s could be preprocessed" % display(fsw),
              file=sys.stderr)
        return 2
    if findings:
        for (f, line, what), passes in sorted(findings.items()):
            print("%s:%d: %s (%s)" % (f, line, what, ", ".join(sorted(passes))))
        print("scan_float: FAIL: %d floating-point token(s) in %s; flight code is fixed point only "
              "(spec 00 §4 'no float: source'; write constants as integer Q literals)"
              % (len(findings), display(fsw)))
        return 1
    print("scan_float: OK: %d translation units preprocessed (%d with compile_commands.json flags), "
          "%d files scanned as source: no float, double or floating literal"
          % (len(sources) - len(notes), from_db, len(all_files)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
