"""Detumbling closed loop from a mission configuration (CTest obs_cfg_sil_*, label sil).

    python tests/observer/obs_cfg_sil.py --config CFG.yaml --template SCENARIO.yaml --sil SIL --out DIR
        [--revision N] [--settle-max-s 150] [--peak-mu-max-deg 7] [--peak-rate-max-degps 6.5]

1. `python -m tools.observer table --config CFG.yaml -o DIR/table.bin --revision N`;
2. DIR/scenario.yaml: the template with the configuration's plant (model, sigma, j_factor,
   period_us, gyro and gimbal scales) and `fsw: {table_file: table.bin}`;
3. `sil run --fsw fixed` and `sil run --fsw ref` (the double reference flying the same image);
4. gates: the upload committed (fsw_n_tbl_acc 1, revision N, no rejection), no fx status bit,
   never SAFE, settled (S0-7 bounds by default: t_s+ <= 150 s, K-hat within 2 % of the true k^2,
   peaks), and fixed vs reference within spec 10 S0-8 (tests/observer/test_obs_sil.cpp
   s08_fixed_vs_double): t_s and t_s+ within 1 % or 2 samples, K-hat 0.5 %, peaks 1 %.
Exit 0 when every gate passes; the table of measured values is printed either way.
"""
import argparse
import os
import sys

import yaml

from tools.observer import config as oc
from tools.sil import closed_loop as cl
from tools.table import config as tc


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--config", required=True)
    ap.add_argument("--template", required=True, help="scenario YAML to take the initial state and duration from")
    ap.add_argument("--sil", required=True, help="the sil executable")
    ap.add_argument("--out", required=True)
    ap.add_argument("--revision", type=int, default=7)
    ap.add_argument("--settle-max-s", type=float, default=150.0, help="bound on t_s+ (S0-7: 150 s)")
    ap.add_argument("--peak-mu-max-deg", type=float, default=7.0, help="bound on peak |mu| (S0-7: 7 deg)")
    ap.add_argument("--peak-rate-max-degps", type=float, default=6.5,
                    help="bound on peak |w| and peak |bdot| (S0-7: 6.5 deg/s)")
    a = ap.parse_args(argv)

    out = cl.out_dir(a.out)
    cfg = tc.load(a.config, oc.ObserverConfig)
    image = os.path.join(out, "table.bin")
    cl.make_image("observer", a.config, image, a.revision)
    with open(a.template, encoding="utf-8") as fh:
        scn = yaml.safe_load(fh)
    scn["name"] = "cfg-" + os.path.splitext(os.path.basename(a.config))[0]
    scn.update(model=cfg.model, sigma=cfg.sigma, j_factor=cfg.J / oc.m.J0, period_us=cfg.period_us)
    scn.setdefault("gyro", {}).update(lsb_shift=cfg.gyro_lsb_shift, max_cnt=cfg.gyro_max_cnt)
    scn.setdefault("gimbal", {}).update(lsb_shift=cfg.gimbal_lsb_shift, hw_limit_radps=cfg.gimbal_hw_limit_radps)
    scn["fsw"] = {"table_file": "table.bin"}   # relative to the scenario
    scenario = os.path.join(out, "scenario.yaml")
    cl.write_scenario(scenario, scn)

    fx = cl.run_sil(a.sil, scenario, "fixed", os.path.join(out, "fixed.json"))
    rf = cl.run_sil(a.sil, scenario, "ref", os.path.join(out, "ref.json"))

    c = cl.Checks("%s: %s, j_factor %.6g, %d us; fixed point vs double reference" %
                  (a.config, cfg.model, cfg.J / oc.m.J0, cfg.period_us))
    for tag, s in (("fx", fx), ("ref", rf)):
        c.eq("%s run completed" % tag, s["plant_end"], "completed")
        c.eq("%s deterministic lock-step" % tag, s["deterministic"], "yes")
        c.eq("%s flew the image" % tag, os.path.basename(s["table"]), "table.bin")
    c.eq("fx upload committed (fsw_n_tbl_acc)", fx["fsw_n_tbl_acc"], 1)
    c.eq("fx no upload rejected (fsw_n_tbl_rej)", fx["fsw_n_tbl_rej"], 0)
    c.eq("fx active revision (fsw_tbl_revision)", fx["fsw_tbl_revision"], a.revision)
    c.eq("fx observer table revision (fsw_obs_revision)", fx["fsw_obs_revision"], a.revision)
    c.add("fx no fx status bit", fx["t_first_fx_status_s"] < 0 and (fx["fsw_health_sticky"] & 0xFF) == 0,
          "t_first %.2f, sticky 0x%08X" % (fx["t_first_fx_status_s"], fx["fsw_health_sticky"]), "none")
    c.eq("fx never SAFE (fsw_n_safe)", fx["fsw_n_safe"], 0)
    c.eq("fx mode DETUMBLE at the end", fx["fsw_mode"], 2)
    for tag, s in (("fx", fx), ("ref", rf)):
        c.le("%s t_s+ [s]" % tag, s["t_s_plus_s"], a.settle_max_s)
        k_true = s["k_true_per_s2"]
        c.near("%s K-hat final vs true k^2 [1/s^2]" % tag, s["k_hat_final_per_s2"], k_true, 0.02 * k_true,
               "within 2 % of the true k^2", labels=("K-hat", "k^2"))
        c.le("%s peak |mu| [deg]" % tag, s["peak_mu_deg"], a.peak_mu_max_deg)
        c.le("%s peak |w| [deg/s]" % tag, s["peak_w_degps"], a.peak_rate_max_degps)
        c.le("%s peak |bdot| [deg/s]" % tag, s["peak_bdot_degps"], a.peak_rate_max_degps)
    h = cfg.period_us * 1e-6
    for k in ("t_s_s", "t_s_plus_s"):
        c.near("S0-8 %s" % k, fx[k], rf[k], max(0.01 * rf[k], 2.0 * h + 1e-9), "1 % or 2 samples")
    c.near("S0-8 k_hat_final_per_s2", fx["k_hat_final_per_s2"], rf["k_hat_final_per_s2"],
           0.005 * rf["k_hat_final_per_s2"], "0.5 %")
    for k in ("peak_bdot_degps", "peak_mu_deg", "peak_w_degps"):
        c.near("S0-8 %s" % k, fx[k], rf[k], 0.01 * rf[k], "1 %")
    return c.report()


if __name__ == "__main__":
    sys.exit(main())
