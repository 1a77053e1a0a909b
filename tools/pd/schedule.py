"""The committed schedules tools/pd/schedule/<channel>_fast.json, written (or --check'ed) by running the
host synthesis `pd_analysis synth` (spec 40 §4.1 steps 1-4, tools/pd/pd_analysis.cpp) for each channel.
The wall time and thread count of the run are dropped, so a re-run on any machine writes the same bytes.

    python -m tools.pd schedule --analysis build/host/tools/pd/pd_analysis [--check]
"""
import json
import os
import subprocess
import sys
import tempfile

from . import design

HERE = os.path.dirname(os.path.abspath(__file__))


def render(analysis, channel, law="fast"):
    with tempfile.TemporaryDirectory() as d:
        out = os.path.join(d, "s.json")
        subprocess.run([analysis, "synth", "--channel", channel, "--threads", "1", "--json", out],
                       check=True, stdout=subprocess.DEVNULL)
        with open(out) as fh:
            s = json.load(fh)
    s.pop("wall_s", None)
    s.pop("threads", None)
    s["law"] = law
    return json.dumps(s, indent=1, sort_keys=True) + "\n"


def main(analysis, check=False):
    bad = 0
    for ch in design.CHANNELS:
        path = os.path.join(HERE, "schedule", "%s_fast.json" % ch)
        text = render(analysis, ch)
        old = open(path).read() if os.path.exists(path) else None
        if check:
            if old != text:
                print("%s: differs from `pd_analysis synth --channel %s`" % (os.path.relpath(path), ch))
                bad += 1
        elif old != text:
            with open(path, "w") as fh:
                fh.write(text)
            print("wrote %s" % os.path.relpath(path))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], "--check" in sys.argv))
