#!/usr/bin/env python3
"""expect_run.py - runs a `sil run ... --summary-json F` command and checks its exit status and
summary keys: the PIL fault tests assert what was detected and counted, not only that it failed.

Usage: expect_run.py --rc N [--summary F] [--key K=V]... [--min K=V]... [--stderr TEXT]... -- CMD...
  --rc       the exit status the command must give
  --summary  the summary JSON the command writes (must exist afterwards; without it no key checks)
  --key      summary[K] == V (numbers compared as numbers)
  --min      summary[K] >= V
  --stderr   TEXT must appear in the command's stderr
Exit 0 when everything holds; 1 otherwise, naming each mismatch.
"""
import argparse
import json
import os
import subprocess
import sys


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--rc", type=int, required=True)
    ap.add_argument("--summary", default=None)
    ap.add_argument("--key", action="append", default=[])
    ap.add_argument("--min", action="append", default=[])
    ap.add_argument("--stderr", action="append", default=[])
    ap.add_argument("cmd", nargs=argparse.REMAINDER)
    a = ap.parse_args()
    cmd = a.cmd[1:] if a.cmd and a.cmd[0] == "--" else a.cmd
    if a.summary and os.path.exists(a.summary):
        os.unlink(a.summary)
    p = subprocess.run(cmd, capture_output=True, text=True)
    sys.stdout.write(p.stdout)
    sys.stderr.write(p.stderr)
    bad = []
    if p.returncode != a.rc:
        bad.append("exit status %d, expected %d" % (p.returncode, a.rc))
    s = {}
    if a.summary and os.path.exists(a.summary):
        with open(a.summary) as fh:
            s = json.load(fh)
    elif a.summary:
        bad.append("no summary %s" % a.summary)
    for kv, cmp in [(x, "==") for x in a.key] + [(x, ">=") for x in a.min]:
        k, v = kv.split("=", 1)
        got = s.get(k)
        try:
            ok = got is not None and (float(got) == float(v) if cmp == "==" else float(got) >= float(v))
        except (TypeError, ValueError):
            ok = str(got) == v
        if not ok:
            bad.append("summary %s = %r, expected %s %s" % (k, got, cmp, v))
    for t in a.stderr:
        if t not in p.stderr:
            bad.append("stderr lacks %r" % t)
    for b in bad:
        print("expect_run: " + b)
    print("expect_run: %s" % ("ok" if not bad else "FAILED"))
    return 0 if not bad else 1


if __name__ == "__main__":
    sys.exit(main())
