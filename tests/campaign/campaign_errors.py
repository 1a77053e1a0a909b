"""A bad campaign file gets a clear error before any run starts (CTest campaign_errors, unit).

    python tests/campaign/campaign_errors.py --sil SIL --base SCENARIO.yaml --out DIR

Each case writes a campaign over BASE (a RENDEZVOUS scenario) with one defect and requires
`python -m tools.campaign run` to exit 2 with the given fragments in its message and to leave no
store behind: an unknown parameter, a negative count, a scenario value outside its range (the
C++ scenario parser's message), a table field outside the flight loader's limits, a list entry the
base does not have, a grid that does not divide the runs, a zipped grid without a partner grid before it or of
another length, a criterion that is not KEY OP NUMBER, a metric the summary does not have. And a
good zipped grid: its values follow the partner's index.
"""
import argparse
import os
import subprocess
import sys

GOOD = {"dispersions": "  cw.eps_c: {uniform: [-0.01, 0.01]}\n", "runs": "4", "metrics": "[miss_r_m]",
        "pass": "[miss_r_m <= 1.0]"}
CASES = [
    ("unknown parameter", {"dispersions": "  cw.bogus_gain: {uniform: [0, 1]}\n"},
     ["dispersion cw.bogus_gain at 0", "'cw.bogus_gain'", "unknown key"]),
    ("negative count", {"runs": "-3"}, ["key 'runs'", "-3 is not a positive integer"]),
    ("scenario value out of range", {"dispersions": "  cw.eps_c: {uniform: [-0.6, 0.0]}\n"},
     ["dispersion cw.eps_c at -0.6", "'cw.eps_c'", "out of range"]),
    ("table field out of the loader's range", {"dispersions": "  table.alpha_q30[2]: {uniform_int: [858993459, 1400000000]}\n"},
     ["dispersion table.alpha_q30[2] at 1400000000", "alpha_q30[2] = 1400000000 is outside the flight loader's limits"]),
    ("unknown table field", {"dispersions": "  table.no_such_field: {uniform_int: [1, 2]}\n"},
     ["table.no_such_field", "no field 'no_such_field'"]),
    ("list entry the base lacks", {"dispersions": "  cw.eps[2]: {uniform: [-0.01, 0.01]}\n"},
     ["cw.eps[2]", "has no list 'eps' with an entry 2"]),
    ("grid not dividing the runs", {"dispersions": "  cw.t_min_us: {grid: [20000, 30000, 40000]}\n"},
     ["key 'runs'", "not a multiple of the grid's 3 combinations"]),
    ("zipped grid without its partner", {"dispersions": "  cw.t_min_us: {grid: [20000, 40000], with: cw.nav.f_hz}\n"},
     ["dispersions.cw.t_min_us", "with: 'cw.nav.f_hz' is not a grid defined before it"]),
    ("zipped grid of another length", {"dispersions": "  cw.nav.f_hz: {grid: [1.0, 2.0]}\n"
                                                      "  cw.t_min_us: {grid: [20000, 30000, 40000], with: cw.nav.f_hz}\n"},
     ["dispersions.cw.t_min_us", "with: 3 values, cw.nav.f_hz has 2"]),
    ("criterion syntax", {"pass": "[miss_r_m is small]"}, ["key 'pass'", "expected KEY OP NUMBER"]),
    ("metric the summary lacks", {"metrics": "[miss_r]"}, ["'miss_r' is not in a RENDEZVOUS run's summary"]),
]


def text(base, o):
    v = dict(GOOD, **o)
    return ("name: bad\nbase: %s\nruns: %s\nseed: 1\ndispersions:\n%smetrics: %s\npass: %s\n"
            % (base, v["runs"], v["dispersions"], v["metrics"], v["pass"]))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--sil", required=True)
    ap.add_argument("--base", required=True)
    ap.add_argument("--out", required=True)
    a = ap.parse_args(argv)
    os.makedirs(a.out, exist_ok=True)
    bad = 0
    for name, o, want in [("good", {}, None)] + CASES:
        path = os.path.join(a.out, name.replace(" ", "_").replace("'", "") + ".yaml")
        with open(path, "w", encoding="utf-8") as fh:
            fh.write(text(os.path.abspath(a.base), o))
        store = os.path.join(a.out, "store_" + os.path.basename(path)[:-5])
        cmd = [sys.executable, "-m", "tools.campaign", "check" if want is None else "run", path, "--sil", a.sil]
        if want is not None:
            cmd += ["--out", store, "--no-progress"]
        r = subprocess.run(cmd, capture_output=True, text=True)
        msg = (r.stdout + r.stderr).strip()
        if want is None:
            ok = r.returncode == 0
        else:
            ok = r.returncode == 2 and all(w in msg for w in want) and not os.path.exists(store)
        print("%-4s %-38s rc %d: %s" % ("ok" if ok else "FAIL", name, r.returncode, msg.splitlines()[-1] if msg else ""))
        bad += 0 if ok else 1
    bad += zipped_inputs(a)
    return 1 if bad else 0


def zipped_inputs(a):
    """A zipped grid takes its partner's index: 2 x 2 values are 2 combinations, not 4."""
    from tools.campaign.spec import Campaign
    path = os.path.join(a.out, "zipped.yaml")
    with open(path, "w", encoding="utf-8") as fh:
        fh.write(text(os.path.abspath(a.base), {"dispersions": "  cw.nav.f_hz: {grid: [1.0, 2.0]}\n"
                                                               "  cw.t_min_us: {grid: [20000, 40000], with: cw.nav.f_hz}\n"
                                                               "  cw.eps_c: {uniform: [-0.01, 0.01]}\n"}))
    c = Campaign(path)
    pairs = [(c.inputs(i)["cw.nav.f_hz"], c.inputs(i)["cw.t_min_us"]) for i in range(c.runs)]
    ok = c.grid_size == 2 and pairs == [(1.0, 20000), (2.0, 40000)] * 2
    print("%-4s %-38s grid %d, (f_hz, t_min_us) per run %s" % ("ok" if ok else "FAIL", "zipped grid", c.grid_size, pairs))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
