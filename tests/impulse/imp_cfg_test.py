"""`python -m tools.impulse table --config` (CTest imp_cfg_tables, label unit).

    python tests/impulse/imp_cfg_test.py [--c-limits DUMP.txt]

- the shipped configurations that describe built-in tables reproduce their images byte for byte
  (default.yaml = imp_default, tick_1s.yaml = imp_1s, subtick_1ms.yaml = imp_sub1ms; revision 1
  and another revision);
- the other shipped configurations build images that decode and pass the loader's limits;
- invalid configurations (unknown key, out of range, wrong type, missing key, rules between keys,
  a derived field outside the flight loader's limits, bad YAML) exit 2 without an image and name
  the key, its unit and its allowed range;
- with --c-limits: the Python writer's mirror of the loader's limits equals the C descriptor
  (tests/common/tbl_desc_dump.c output).
"""
import argparse
import glob
import os
import sys

from tools.impulse import image
from tools.table import cfgcheck

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
CFG = os.path.join(ROOT, "tools", "impulse", "configs")
BASE = "mission: rendezvous\nomega_radps: 1.107e-3\na_nom_mps2: 0.04\nperiod_us: 100000\n"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--c-limits", help="the C descriptor as printed by tbl_desc_dump (imp_tbl_desc_dump)")
    a = ap.parse_args(argv)
    s = cfgcheck.Suite("impulse")

    for cfg, name in (("default.yaml", "imp_default"), ("tick_1s.yaml", "imp_1s"), ("subtick_1ms.yaml", "imp_sub1ms")):
        s.same_as_builtin(os.path.join(CFG, cfg), name)
    s.same_as_builtin(os.path.join(CFG, "default.yaml"), "imp_default", revision=9)
    builtin = {"default.yaml", "tick_1s.yaml", "subtick_1ms.yaml"}
    for cfg in sorted(glob.glob(os.path.join(CFG, "*.yaml"))):
        if os.path.basename(cfg) in builtin:
            continue
        img = s.builds(cfg)
        if img is not None:
            hdr, p = image.decode(img)
            s.check("%s: header and CRC" % os.path.basename(cfg),
                    hdr["table_id"] == image.TABLE_ID and hdr["crc_ok"] and hdr["revision"] == 1)
            s.check("%s: every field within the loader's limits" % os.path.basename(cfg),
                    image.LAYOUT.check_limits(p) == [], str(image.LAYOUT.check_limits(p)))

    # YAML 1.2 numbers (8e-4 without a dot) and the altitude form are accepted
    ok = s.path("ok.yaml")
    with open(ok, "w") as fh:
        fh.write("mission: rendezvous\nomega_radps: 9e-4\na_nom_mps2: 4E-2\nperiod_us: 100000\n")
    s.builds(ok)

    s.bad("an unknown key", BASE + "omega: 1.1e-3\n",
          [r"unknown key 'omega' \(did you mean 'omega_radps'\?\); known keys: mission, "])
    s.bad("an out-of-range orbit rate", BASE.replace("1.107e-3", "2.0e-3"),
          [r"omega_radps = 0.002 is out of range: orbit rate; .*allowed \[0.0008, 0.0012\] rad/s"])
    s.bad("an out-of-range altitude", BASE.replace("omega_radps: 1.107e-3", "altitude_km: 100"),
          [r"altitude_km = 100 is out of range: .*allowed \[150, 2000\] km"])
    s.bad("a negative minimum on-time", BASE + "t_min_us: -5\n",
          [r"t_min_us = -5 is out of range: minimum valve on-time .*allowed \[0, 10000000\] us"])
    s.bad("a thrust factor out of range", BASE + "alpha_init: [1, 1, 1.3, 1, 1, 1]\n",
          [r"alpha_init\[2\] = 1.3 is out of range: .*allowed each in \[0.8, 1.2\]"])
    s.bad("a float for an integer key", BASE.replace("period_us: 100000", "period_us: 100000.0"),
          [r"period_us = 100000.0 has the wrong type \(float\): expected an integer; .*allowed \[1000, 10000000\] us"])
    s.bad("a string for a number", BASE.replace("a_nom_mps2: 0.04", "a_nom_mps2: '0.04'"),
          [r"a_nom_mps2 = '0.04' has the wrong type \(str\): expected a number; .*allowed \[0.0001, 10\] m/s\^2"])
    s.bad("0/1 for a boolean", BASE + "cal_enable: 1\n",
          [r"cal_enable = 1 has the wrong type \(int\): expected true or false"])
    s.bad("a list of the wrong length", BASE + "alpha_init: [1, 1, 1]\n",
          [r"alpha_init has 3 entries, expected 6"])
    s.bad("a missing key", BASE.replace("a_nom_mps2: 0.04\n", ""),
          [r"missing required key 'a_nom_mps2': nominal acceleration of one thruster; allowed \[0.0001, 10\] m/s\^2"])
    s.bad("another mission's configuration", BASE.replace("rendezvous", "detumble"),
          [r"mission = 'detumble' is not allowed: .*allowed one of 'rendezvous'"])
    s.bad("both orbit keys", BASE + "altitude_km: 500\n",
          [r"give exactly one of omega_radps \(\[0.0008, 0.0012\] rad/s\) or altitude_km \(\[150, 2000\] km\), not both"])
    s.bad("a minimum on-time above the tick", BASE + "t_min_us: 200000\n",
          [r"t_min_us = 200000 us is longer than period_us = 100000 us"])
    s.bad("a sub-tick that does not divide the tick", BASE + "subtick_us: 3000\n",
          [r"subtick_us = 3000 us does not divide period_us = 100000 us"])
    s.bad("a plan lead off the tick grid", BASE + "plan_lead_s: 0.25\n",
          [r"plan_lead_s = 0.25 s is not a whole number of periods \(period_us = 100000 us\)"])
    s.bad("a plan lead of one tick", BASE + "plan_lead_s: 0.1\n",
          [r"plan_lead_s = 0.1 s is 1 periods, at least 2 needed \(period_us = 100000 us\)"])
    s.bad("a derived field outside the flight loader's limits", BASE.replace("a_nom_mps2: 0.04", "a_nom_mps2: 0.001")
          + "dv_cal_min_mps: 5\n",
          [r"table field dv_cal_min_q28 = \d+ is outside the flight loader's limits \[0, 268435456\] "
           r"\(fsw/impulse/imp_table.c\); derived from dv_cal_min_mps"])
    s.bad("a duplicate key", BASE + "period_us: 200000\n", [r"duplicate key 'period_us'"])
    s.bad("a file that is not a mapping", "- 1\n- 2\n", [r"expected a mapping of keys to values"])

    rc, out = cfgcheck.run(["tools.impulse", "table", "--keys"])
    s.check("--keys lists every key with its range", rc == 0 and "| `omega_radps` | [0.0008, 0.0012] rad/s |" in out, out)

    if a.c_limits:
        c = open(a.c_limits).read()
        py = image.LAYOUT.descriptor_text()
        s.check("the writer's limits mirror IMP_TBL_DESC exactly (%d lines)" % len(py.splitlines()), c == py,
                "C:\n%sPython:\n%s" % (c, py))
    return s.done()


if __name__ == "__main__":
    sys.exit(main())
