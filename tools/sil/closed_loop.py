"""Closed loop from a mission configuration: configuration -> table image -> scenario -> SIL runs
of the fixed-point flight code and of the double reference flying the same image.

The pieces the per-mission drivers (tests/observer/obs_cfg_sil.py, tests/impulse/imp_cfg_sil.py)
share: write the image with the module's `table --config` command, write a scenario that names it
(`fsw: {table_file: ...}`, relative to the scenario), run `sil run --summary-json` with
`--fsw fixed` and `--fsw ref`, and gate measured figures with a printed table.
"""
import json
import os
import subprocess
import sys

import yaml


class Checks(object):
    """Named pass/fail rows with the measured value and the bound, printed as a table."""

    def __init__(self, title):
        self.title = title
        self.rows = []

    def add(self, name, ok, measured, bound):
        self.rows.append((name, bool(ok), measured, bound))
        return ok

    def le(self, name, value, bound):
        return self.add(name, value <= bound, "%.6g" % value, "<= %.6g" % bound)

    def eq(self, name, value, want):
        return self.add(name, value == want, repr(value), "== %r" % (want,))

    def near(self, name, a, b, tol, what, labels=("fx", "ref")):
        """|a - b| <= tol (a: fixed point, b: reference, unless labels say otherwise); what: the
        tolerance's text."""
        return self.add(name, abs(a - b) <= tol, "%s %.6g %s %.6g (diff %.3g)" % (labels[0], a, labels[1], b, a - b),
                        what)

    def report(self):
        print("== %s" % self.title)
        w = max(len(r[0]) for r in self.rows)
        for name, ok, meas, bound in self.rows:
            print("  %-4s %-*s  %-44s %s" % ("ok" if ok else "FAIL", w, name, meas, bound))
        bad = sum(1 for r in self.rows if not r[1])
        print("%d passed, %d failed" % (len(self.rows) - bad, bad))
        return 1 if bad else 0


def make_image(module, config, image, revision):
    """`python -m tools.<module> table --config CONFIG -o IMAGE --revision N` (the user's command)."""
    cmd = [sys.executable, "-m", "tools.%s" % module, "table", "--config", config, "-o", image,
           "--revision", str(revision)]
    r = subprocess.run(cmd, capture_output=True, text=True)
    sys.stdout.write(r.stdout)
    if r.returncode != 0:
        raise SystemExit("table command failed (%d): %s\n%s" % (r.returncode, " ".join(cmd), r.stderr))


def write_scenario(path, scn):
    with open(path, "w", encoding="utf-8") as fh:
        yaml.safe_dump(scn, fh, sort_keys=False, default_flow_style=None)


def run_sil(sil, scenario, fsw, summary_json):
    """One `sil run` (memq); its summary JSON as a dict."""
    cmd = [sil, "run", "--scenario", scenario, "--fsw", fsw, "--summary-json", summary_json]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise SystemExit("sil failed (%d): %s\n%s%s" % (r.returncode, " ".join(cmd), r.stdout, r.stderr))
    with open(summary_json, encoding="utf-8") as fh:
        return json.load(fh)


def out_dir(path):
    os.makedirs(path, exist_ok=True)
    return path
