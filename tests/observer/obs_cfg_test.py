"""`python -m tools.observer table --config` (CTest obs_cfg_tables, label unit).

    python tests/observer/obs_cfg_test.py [--c-limits DUMP.txt]

- the shipped configurations that describe built-in tables reproduce their images byte for byte
  (default.yaml = obs_50hz_phys, mpaper_50hz.yaml = obs_50hz_paper; revision 1 and another);
- the other shipped configurations build images that decode, pass the loader's limits and carry
  the model of their own inertia (heavy_platform_j110.yaml: Phi0 = exact ZOH at J = 1320 kg m^2);
- invalid configurations (unknown key, out of range, wrong type, missing key, rules between keys)
  exit 2 without an image and name the key, its unit and its allowed range;
- with --c-limits: the Python writer's mirror of the loader's limits equals the C descriptor.
"""
import argparse
import glob
import os
import sys

import numpy as np

from tools.observer import image
from tools.observer import model as m
from tools.table import cfgcheck

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
CFG = os.path.join(ROOT, "tools", "observer", "configs")
BASE = "mission: detumble\nmodel: M-phys\nperiod_us: 20000\n"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--c-limits", help="the C descriptor as printed by tbl_desc_dump (obs_tbl_desc_dump)")
    a = ap.parse_args(argv)
    s = cfgcheck.Suite("observer")

    s.same_as_builtin(os.path.join(CFG, "default.yaml"), "obs_50hz_phys")
    s.same_as_builtin(os.path.join(CFG, "default.yaml"), "obs_50hz_phys", revision=9)
    s.same_as_builtin(os.path.join(CFG, "mpaper_50hz.yaml"), "obs_50hz_paper")
    builtin = {"default.yaml", "mpaper_50hz.yaml"}
    for cfg in sorted(glob.glob(os.path.join(CFG, "*.yaml"))):
        if os.path.basename(cfg) in builtin:
            continue
        img = s.builds(cfg)
        if img is None:
            continue
        hdr, p = image.decode(img)
        name = os.path.basename(cfg)
        s.check("%s: header and CRC" % name, hdr["table_id"] == image.TABLE_ID and hdr["crc_ok"])
        s.check("%s: every field within the loader's limits" % name, image.LAYOUT.check_limits(p) == [],
                str(image.LAYOUT.check_limits(p)))
        if name == "heavy_platform_j110.yaml":
            phi0 = np.array(p["phi0"], float).reshape(6, 6) * 2.0 ** -p["q_phi0"]
            want, _ = m.zoh(m.K_REF, +1, 0.02, 1.1 * m.J0)
            nominal, _ = m.zoh(m.K_REF, +1, 0.02, m.J0)
            err = np.abs(phi0 - want).max()
            s.check("%s: Phi0 is the exact ZOH at J = 1320 kg m^2 (max error %.2e, %.2e from the nominal J's)"
                    % (name, err, np.abs(phi0 - nominal).max()),
                    err <= 2.0 ** -p["q_phi0"] and np.abs(phi0 - nominal).max() > 1e-3)

    s.bad("an unknown key", BASE + "j_fator: 1.1\n",
          [r"unknown key 'j_fator' \(did you mean 'j_factor'\?\); known keys: mission, "])
    s.bad("an out-of-range inertia factor", BASE + "j_factor: 3.0\n",
          [r"j_factor = 3.0 is out of range: platform transverse inertia J / 1200 kg m\^2 .*allowed \[0.5, 2\]"])
    s.bad("an out-of-range inertia", BASE + "platform_inertia_kgm2: 5000\n",
          [r"platform_inertia_kgm2 = 5000 is out of range: .*allowed \[600, 2400\] kg m\^2"])
    s.bad("an out-of-range period", BASE.replace("20000", "2000000"),
          [r"period_us = 2000000 is out of range: control period .*allowed \[1000, 1000000\] us"])
    s.bad("an out-of-range stiffness", BASE + "k2_design_per_s2: 0.5\n",
          [r"k2_design_per_s2 = 0.5 is out of range: .*allowed \[0.005, 0.02\] 1/s\^2"])
    s.bad("an EKF scale out of range", BASE + "ekf_scale_log2: [-13, -13, -9, -10, -9, -10, 3]\n",
          [r"ekf_scale_log2\[6\] = 3 is out of range: .*allowed each in \[-20, 0\]"])
    s.bad("an EKF scale list of the wrong length", BASE + "ekf_scale_log2: [-13, -13]\n",
          [r"ekf_scale_log2 has 2 entries, expected 7"])
    s.bad("an unknown model", BASE.replace("M-phys", "phys"),
          [r"model = 'phys' is not allowed: .*allowed one of 'M-phys', 'M-paper'"])
    s.bad("a string for an integer", BASE.replace("period_us: 20000", "period_us: '20000'"),
          [r"period_us = '20000' has the wrong type \(str\): expected an integer; .*allowed \[1000, 1000000\] us"])
    s.bad("a float for an integer", BASE + "gyro_lsb_shift: 20.0\n",
          [r"gyro_lsb_shift = 20.0 has the wrong type \(float\): expected an integer; .*allowed \[0, 29\]"])
    s.bad("a number for a boolean", BASE + "d2_reject: 0\n",
          [r"d2_reject = 0 has the wrong type \(int\): expected true or false"])
    s.bad("a missing key", "mission: detumble\nperiod_us: 20000\n",
          [r"missing required key 'model': plant model sign: M-phys .*allowed one of 'M-phys', 'M-paper'"])
    s.bad("both inertia keys", BASE + "j_factor: 1.1\nplatform_inertia_kgm2: 1320\n",
          [r"give j_factor \(\[0.5, 2\]\) or platform_inertia_kgm2 \(\[600, 2400\] kg m\^2\), not both"])
    s.bad("zeta_s on M-paper", BASE.replace("M-phys", "M-paper") + "zeta_s: 0.1\n",
          [r"zeta_s applies to model M-phys only"])
    s.bad("a command limit above the hardware", BASE + "bdot_max_radps: 0.4\n",
          [r"bdot_max_radps = 0.4 rad/s is above gimbal_hw_limit_radps = 0.35 rad/s"])
    s.bad("K-hat(0) outside its band", BASE + "k_hat0_per_s2: 0.03\n",
          [r"k_hat0_per_s2 = 0.03 1/s\^2 is outside the band \[k_hat_min_per_s2, k_hat_max_per_s2\] = \[0.005, 0.02\]"])
    s.bad("a band without the linearisation point", BASE + "k_hat_min_per_s2: 0.011\nk_hat0_per_s2: 0.0115\n",
          [r"k_hat_min_per_s2 = 0.011 and k_hat_max_per_s2 = 0.02 1/s\^2 must bracket the linearisation point 0.01"])
    s.bad("a gyro full scale beyond the rate format", BASE + "gyro_max_cnt: 5000000\n",
          [r"gyro_max_cnt = 5000000 counts at gyro_lsb_shift = 20 is a full scale of 4.76837 rad/s: the flight rate "
           r"format \(q29\) holds less than 4 rad/s"])
    s.bad("another mission's configuration", "mission: rendezvous\nmodel: M-phys\nperiod_us: 20000\n",
          [r"mission = 'rendezvous' is not allowed: .*allowed one of 'detumble'"])

    rc, out = cfgcheck.run(["tools.observer", "table", "--keys"])
    s.check("--keys lists every key with its range", rc == 0 and "| `j_factor` | [0.5, 2] |" in out, out)

    if a.c_limits:
        c = open(a.c_limits).read()
        py = image.LAYOUT.descriptor_text()
        s.check("the writer's limits mirror OBS_TBL_DESC exactly (%d lines)" % len(py.splitlines()), c == py,
                "C:\n%sPython:\n%s" % (c, py))
    return s.done()


if __name__ == "__main__":
    sys.exit(main())
