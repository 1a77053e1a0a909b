"""A3-6 (spec 40 §7) for yaw over the SIL campaign stores: the adaptive yaw channel against the same
plant and seed at constant k2_cold, with R3 (the lowest tone) and R5 of the estimator per run.

    .venv/bin/python -m tools.pd.a3_6 --out build/campaigns [--check]

reads OUT/pd_a3_6_yaw and OUT/pd_a3_6_yaw_cold (tools/pd/campaigns/pd_a3_6_yaw{,_cold}.yaml; any subset
of the runs, joined on (f, seed)), prints the table and a summary, writes OUT/a3_6_yaw.csv, and with
--check exits 1 when a run misses: its campaign criteria (R3, R5, no FAULT), or t* <= t*(k2_cold) + 10 s
where the constant run settles within the horizon (a t* of -1 is "not settled", i.e. infinite).
"""
import argparse
import os
import sys

import numpy as np
import pandas as pd

from tools.pd.a3_5 import load, settle

SLACK_S = 10.0   # A3-6: t* <= t*(k2_cold) + 10 s


def judge(out):
    ad, cold = load(out, "pd_a3_6_yaw"), load(out, "pd_a3_6_yaw_cold")
    if ad is None or cold is None:
        raise SystemExit("a3_6: %s needs pd_a3_6_yaw and pd_a3_6_yaw_cold stores (tools/pd/campaigns)" % out)
    c = cold[["f_hz", "seed", "m.t_settle_yaw_s"]].rename(columns={"m.t_settle_yaw_s": "t_cold_s"})
    j = ad.merge(c, on=["f_hz", "seed"], how="inner")
    t = settle(j["m.t_settle_yaw_s"].to_numpy())
    tc = settle(j["t_cold_s"].to_numpy())
    judged = np.isfinite(tc)
    return pd.DataFrame({
        "f_hz": j.f_hz, "seed": j.seed.astype(int), "t_star_s": j["m.t_settle_yaw_s"], "t_cold_s": j.t_cold_s,
        "judged": judged, "t_ok": np.where(judged, t <= tc + SLACK_S, True), "run_passed": j.passed.astype(bool),
        "reason": j.reason, "err300": j["m.fest_err300_yaw"], "err1200": j["m.fest_err1200_yaw"],
        "conf_ratio_max": j["m.fest_conf_ratio_max_yaw"], "resets": j["m.fest_resets_yaw"],
        "k2_final_s": j["m.k2_final_yaw_s"]})


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m tools.pd.a3_6", description=__doc__.split("\n")[0])
    ap.add_argument("--out", required=True, help="folder holding the two campaign stores")
    ap.add_argument("--check", action="store_true", help="exit 1 when a run misses a criterion")
    a = ap.parse_args(argv)
    t = judge(a.out).sort_values(["f_hz", "seed"])
    pd.set_option("display.width", 200)
    pd.set_option("display.max_rows", 500)
    print(t.drop(columns=["reason"]).to_string(index=False, float_format="%.4g"))
    ok = t.t_ok & t.run_passed
    w3, w12 = t.loc[t.err300.idxmax()], t.loc[t.err1200.idxmax()]
    gain = (t.t_cold_s - t.t_star_s)[t.judged & (t.t_star_s > 0)]
    print("A3-6 yaw: %d runs, t* criterion %d/%d (constant not settled: %d), run criteria %d/%d, both %d/%d; "
          "t*(k2_cold) - t* median %.2f s, worst %.2f s"
          % (len(t), int(t.t_ok.sum()), len(t), int((~t.judged).sum()), int(t.run_passed.sum()), len(t),
             int(ok.sum()), len(t), gain.median() if len(gain) else float("nan"),
             gain.min() if len(gain) else float("nan")))
    print("  R3 worst |f^/f - 1|: %.2f %% at 300 s (%.3f Hz seed %d), %.2f %% at 1 200 s (%.3f Hz seed %d); "
          "R5 max confident f^/f %.4f; FAULTs %d"
          % (100 * w3.err300, w3.f_hz, w3.seed, 100 * w12.err1200, w12.f_hz, w12.seed, t.conf_ratio_max.max(),
             int(t.resets.sum())))
    for _, r in t[~ok].iterrows():
        print("  FAIL %.3f Hz seed %d: t* %.2f s, k2_cold constant %.2f s%s"
              % (r.f_hz, r.seed, r.t_star_s, r.t_cold_s, "" if r.run_passed else "; run: " + str(r.reason)))
    t.to_csv(os.path.join(a.out, "a3_6_yaw.csv"), index=False)
    print("wrote %s" % os.path.join(a.out, "a3_6_yaw.csv"))
    return 1 if (a.check and not ok.all()) else 0


if __name__ == "__main__":
    sys.exit(main())
