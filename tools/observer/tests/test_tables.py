"""Table generator test: determinism, per-matrix q rule, int32 round trip, EKF scaled Q floor (10-observer 4.5/4.6).

Run from the repository root: python -m tools.observer.tests.test_tables
"""
import json
import math
import sys
import tempfile
import numpy as np
from tools.observer import design

NAMES = ("obs_50hz_phys", "obs_50hz_paper", "obs_5hz_paper", "obs_paper_printed")


def main():
    bad = []

    def check(name, ok, msg):
        print("%-4s %s: %s" % ("ok" if ok else "FAIL", name, msg))
        if not ok:
            bad.append(name)

    with tempfile.TemporaryDirectory() as a, tempfile.TemporaryDirectory() as b:
        design.write(a)
        design.write(b)
        for n in NAMES:
            ta = open("%s/%s.json" % (a, n)).read()
            tb = open("%s/%s.json" % (b, n)).read()
            check("deterministic " + n, ta == tb, "%d bytes" % len(ta))
            t = json.loads(ta)
            for mname, e in t["matrices"].items():
                X = np.array(e["double"])
                I = np.array(e["int32"], dtype=np.int64)
                mx = np.abs(X).max()
                qexp = 30 if mx == 0 else min(40, 30 - math.floor(math.log2(2 * mx)))
                err = np.abs(I / 2.0 ** e["q"] - X).max() * 2.0 ** e["q"]
                ok = (e["q"] == qexp and e["q"] >= 16 and np.abs(I).max() <= 2 ** 31 - 1 and err <= 0.5 + 1e-9
                      and (mx == 0 or np.abs(I).max() >= 2 ** 29 or e["q"] == 40))
                check("%s.%s" % (n, mname), ok, "q=%d max|x|=%.6g max|int|=%d round-trip err %.3f LSB"
                      % (e["q"], mx, np.abs(I).max(), err))
            if n.startswith("obs_50hz"):
                qs = [t["matrices"][k]["q"] for k in ("Phi0", "Gam0", "D", "W")]
                check(n + " 50 Hz Phi,Gam,D,W fit q28 (+-8)", min(qs) >= 28, str(qs))
            if t["ekf"]:
                ek = t["ekf"]
                lsb = ek["Q_scaled_unfloored_lsb"]
                qi = ek["Q_scaled_int32"]
                check(n + " EKF Q_w ~7 LSB, Q_mu raised to 4 LSB, Q_K ~43 LSB",
                      round(lsb[0]) == 7 and qi[:2] == [7, 7] and qi[2:6] == [4] * 4 and lsb[2] < 4
                      and qi[6] == 43, "unfloored %s -> %s" % (np.round(lsb, 3).tolist(), qi))
                p0 = ek["P0_scaled"]
                check(n + " EKF P0 scaled in (0, 2) (q30)", min(p0) > 0 and max(p0) < 2, str(np.round(p0, 5).tolist()))
                check(n + " EKF R scaled = (1e-5 * 2^13)^2", abs(ek["R_scaled"][0] - (1e-5 * 2 ** 13) ** 2) < 1e-15,
                      str(ek["R_scaled"]))
    print("%d failure(s)" % len(bad) if bad else "all table checks passed")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
