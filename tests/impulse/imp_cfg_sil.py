"""Rendezvous closed loop from a mission configuration (CTest imp_cfg_sil_*, label sil).

    python tests/impulse/imp_cfg_sil.py --config CFG.yaml --template SCENARIO.yaml --sil SIL --out DIR
        [--revision N] [--T 1055] [--nav-seed 7000]

1. `python -m tools.impulse table --config CFG.yaml -o DIR/table.bin --revision N`;
2. DIR/<nav>.yaml: the template (the paper's example state, START at t0 = the plan lead for
   t_f = t0 + T) with the configuration's CW plant (omega_radps, a_nom_mps2, t_min_us,
   subtick_us, period_us) and `fsw: {table_file: table.bin}`, once with ideal navigation and once
   with the nominal profile (spec 50 §2.5, one seed);
3. `sil run --fsw fixed` and `sil run --fsw ref` (the double reference flying the same image);
4. gates (tests/impulse/test_imp_sil.cpp): the upload committed (fsw_n_tbl_acc 1, revision N),
   the scheduler DONE at t_f with no fx status bit, no stuck/thrust-level/interlock flag, no late
   plan, never SAFE, residuals <= r_tol; the A4-4 per-case bounds at a 0.1 s tick (ideal nav:
   |dR| <= 1.0 m, |dV| <= 5 mm/s, dv used <= plan + 0.1 m/s, <= 6 iterations; nominal nav:
   |dR| <= 2.0 m, |dV| <= 10 mm/s); and fixed vs reference: |dR| within 20 % or 0.1 m.
Exit 0 when every gate passes; the table of measured values is printed either way.
"""
import argparse
import copy
import os
import sys

import yaml

from tools.impulse import config as ic
from tools.sil import closed_loop as cl
from tools.table import config as tc

IMP_MODE_DONE = 5
IMP_H_BAD = 0x00010000 | 0x00040000 | 0x00380000 | 0x01C00000   # THRUST_LEVEL, INTERLOCK, STUCK_OFF, STUCK_ON
R_TOL_LSB = 32
# per-case bounds of tests/impulse/test_imp_sil.cpp at a 0.1 s tick: |dR| [m], |dV| [m/s]
BOUNDS = {"ideal": (1.0, 0.005), "nominal": (2.0, 0.01)}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--config", required=True)
    ap.add_argument("--template", required=True, help="rendezvous scenario YAML (initial state, nav rate)")
    ap.add_argument("--sil", required=True, help="the sil executable")
    ap.add_argument("--out", required=True)
    ap.add_argument("--revision", type=int, default=7)
    ap.add_argument("--T", type=float, default=1055.0, help="t_f - t0 [s] (the paper's example: 1055)")
    ap.add_argument("--nav-seed", type=int, default=7000, help="seed of the nominal-navigation run")
    a = ap.parse_args(argv)

    out = cl.out_dir(a.out)
    cfg = tc.load(a.config, ic.ImpulseConfig)
    image = os.path.join(out, "table.bin")
    cl.make_image("impulse", a.config, image, a.revision)
    with open(a.template, encoding="utf-8") as fh:
        base = yaml.safe_load(fh)
    t0 = cfg.plan_lead_s
    tf = t0 + a.T
    base["period_us"] = cfg.period_us
    base["duration_s"] = tf + 1.0
    cw = base.setdefault("cw", {})
    cw.update(omega_radps=cfg.omega, a_nom_mps2=cfg.a_nom_mps2, t_min_us=cfg.t_min_us, x0_epoch_s=t0)
    if cfg.subtick_us:
        cw["subtick_us"] = cfg.subtick_us
    base["fsw"] = {"table_file": "table.bin"}   # relative to the scenario
    for cmd in base.get("commands", []):
        if cmd.get("cmd") == "IMP_START":
            cmd.update(t0_s=t0, tf_s=tf)

    c = cl.Checks("%s: omega %.6e rad/s, a_nom %g m/s^2, tick %d us; fixed point vs double reference"
                  % (a.config, cfg.omega, cfg.a_nom_mps2, cfg.period_us))
    for nav in ("ideal", "nominal"):
        scn = copy.deepcopy(base)
        scn["name"] = "cfg-%s-%s" % (os.path.splitext(os.path.basename(a.config))[0], nav)
        scn["cw"]["nav"] = dict(scn["cw"].get("nav", {}), profile=nav, seed=a.nav_seed)
        scenario = os.path.join(out, "%s.yaml" % nav)
        cl.write_scenario(scenario, scn)
        fx = cl.run_sil(a.sil, scenario, "fixed", os.path.join(out, "%s_fixed.json" % nav))
        rf = cl.run_sil(a.sil, scenario, "ref", os.path.join(out, "%s_ref.json" % nav))
        for tag, s in (("fx", fx), ("ref", rf)):
            c.eq("%s %s run completed" % (nav, tag), s["plant_end"], "completed")
            c.eq("%s %s deterministic lock-step" % (nav, tag), s["deterministic"], "yes")
            c.eq("%s %s flew the image" % (nav, tag), os.path.basename(s["table"]), "table.bin")
            c.eq("%s %s scheduler DONE" % (nav, tag), s["fsw_imp_mode"], IMP_MODE_DONE)
            c.add("%s %s reached t_f" % (nav, tag), s.get("t_first_DONE", -1.0) >= tf - 1e-6,
                  "t_first_DONE %.1f" % s.get("t_first_DONE", -1.0), ">= t_f %.1f" % tf)
            c.add("%s %s no stuck/thrust-level/interlock flag" % (nav, tag), (s["imp_health_sticky"] & IMP_H_BAD) == 0,
                  s["imp_health_sticky_names"], "none of them")
            c.eq("%s %s interlock violations" % (nav, tag), s["interlock_violations"], 0.0)
            r_max, v_max = BOUNDS[nav]
            c.le("%s %s |dR| [m]" % (nav, tag), s["miss_r_m"], r_max)
            c.le("%s %s |dV| [m/s]" % (nav, tag), s["miss_v_mps"], v_max)
        c.eq("%s fx upload committed (fsw_n_tbl_acc)" % nav, fx["fsw_n_tbl_acc"], 1)
        c.eq("%s fx no upload rejected (fsw_n_tbl_rej)" % nav, fx["fsw_n_tbl_rej"], 0)
        c.eq("%s fx active revision (fsw_tbl_revision)" % nav, fx["fsw_tbl_revision"], a.revision)
        c.add("%s fx no fx status bit" % nav, fx["t_first_fx_status_s"] < 0 and (fx["fsw_health_sticky"] & 0xFF) == 0,
              "t_first %.2f, sticky 0x%08X" % (fx["t_first_fx_status_s"], fx["fsw_health_sticky"]), "none")
        c.eq("%s fx never SAFE (fsw_n_safe)" % nav, fx["fsw_n_safe"], 0)
        c.eq("%s fx no late plan" % nav, fx["fsw_imp_plans_late"], 0)
        c.le("%s fx residual x-y [q28 LSB]" % nav, fx["fsw_imp_fres_xy"], R_TOL_LSB)
        c.le("%s fx residual z [q28 LSB]" % nav, fx["fsw_imp_fres_z"], R_TOL_LSB)
        if nav == "ideal":
            c.le("ideal fx dv used - plan [m/s]", fx["dv_used_mps"] - fx["plan_dv_mps"], 0.1)
            c.le("ideal fx iterations x-y", fx["max_iters_xy"], 6)
        c.near("%s |dR| fixed vs reference [m]" % nav, fx["miss_r_m"], rf["miss_r_m"],
               max(0.2 * rf["miss_r_m"], 0.1), "20 % or 0.1 m")
        c.near("%s dv used fixed vs reference [m/s]" % nav, fx["dv_used_mps"], rf["dv_used_mps"],
               0.1, "0.1 m/s (the A4-4 dv overhead bound)")
    return c.report()


if __name__ == "__main__":
    sys.exit(main())
