"""Generate fsw/impulse/imp_tables.[ch]: the impulse-scheduler tables (spec 50 §5.7).

Every derived integer comes from w, a_nom, the nav LSBs, the period and the valve grid, with its
real value in a comment. Three tables:
  IMP_TBL_DEFAULT  0.1 s tick, whole steps (the flight default)
  IMP_TBL_1S       1 s tick, whole steps (spec 50 §5.4 / A4-4 at 1 s)
  IMP_TBL_SUB1MS   0.1 s tick, 1 ms valve sub-ticks (spec 50 §2.4, §5.3)
`--check` regenerates in memory and requires byte identity with the committed files."""
import math
import os

from . import model as m

HDR_NAME = "imp_tables.h"
OMEGA = m.OMEGA
A_NOM = m.A_NOM
POS_LSB = 1e-3      # m
VEL_LSB = 1e-5      # m/s
K_POS_SH, K_VEL_SH = 27, 24
WORST_UNITS = 3 + 20 * (10 + 1) + 4    # IMP_JOB_UNITS(10) + IMP_ROUND_UNITS (fsw/impulse/imp.h)

# name, tick [us], sub-tick [us], comment. The tau shift of each grid (tick, sub-tick) keeps both
# mantissas of the reciprocal pair below 2^31 (shifts sum to 60).
TABLES = [
    ("IMP_TBL_DEFAULT", 100_000, 0, "default: tick 0.1 s, whole steps"),
    ("IMP_TBL_1S", 1_000_000, 0, "tick 1 s, whole steps"),
    ("IMP_TBL_SUB1MS", 100_000, 1_000, "tick 0.1 s, 1 ms valve sub-ticks"),
]
TAU_SH = {100_000: 14, 1_000_000: 10, 1_000: 20}   # grid unit [us] -> tau shift


def rnd(x):
    """Round half away from zero (the project rule)."""
    return int(math.copysign(math.floor(abs(x) + 0.5), x))


def q(x, n):
    return rnd(x * 2.0 ** n)


def shifts(unit_us, rate):
    """(tau shift, tick shift) of a grid of unit_us (rate rad per unit); both mantissas < 2^31."""
    sh = TAU_SH[unit_us]
    assert q(rate * 2 ** 29, sh) < 2 ** 31 and q(1.0 / rate / 2 ** 29, 60 - sh) < 2 ** 31
    return sh, 60 - sh


def fields(period_us, subtick_us, omega=OMEGA, a_nom=A_NOM):
    L, V = a_nom / omega ** 2, a_nom / omega
    h = period_us * 1e-6
    grid = (subtick_us if subtick_us else period_us) * 1e-6
    tau_sh, tick_sh = shifts(period_us, omega * h)
    gtau_sh, gtick_sh = shifts(subtick_us if subtick_us else period_us, omega * grid)
    steps = lambda s: rnd(s / h)   # seconds -> steps
    lead = steps(5.0)
    pips = 10
    while math.ceil(WORST_UNITS / pips) + 1 > lead or math.ceil(240 / pips) > lead:
        pips += 1
    f = [
        ("period_us", "%du" % period_us, "%.3f s valve tick" % h),
        ("subtick_us", "%du" % subtick_us, ("%.3f ms valve grid" % (subtick_us * 1e-3)) if subtick_us else "whole steps"),
        ("t_min_us", "20000u", "20 ms minimum on-time"),
        ("plan_lead", "%du" % lead, "5 s"),
        ("replan_period", "%du" % steps(100.0), "100 s"),
        ("t_stop", "%du" % steps(60.0), "60 s"),
        ("nav_timeout", "%du" % steps(5.0), "5 s"),
        ("max_iter", "10u", None),
        ("plan_iter_per_step", "%du" % pips, "work units per step: plan_lead >= ceil(%d / it) + 1, ceil(240 / it)"
         % WORST_UNITS),
        ("pivot_ratio_sh", "12u", "smallest/largest pivot >= 2^-12"),
        ("k_tau_sh", "%du" % tau_sh, None),
        ("r_tol_lsb", "32", "%.2f mm, %.2f um/s" % (32 * 2.0 ** -28 * L * 1e3, 32 * 2.0 ** -28 * V * 1e6)),
        ("pivot_min_q26", "%d" % q(2.0 ** -10, 26), "2^-10"),
        ("rho_warn_q28", "%d" % q(0.38, 28), "0.38"),
        ("rho_reject_q28", "%d" % q(0.55, 28), "0.55"),
        ("dv_tie_q28", "%d" % q(1e-3 / V, 28), "1 mm/s = %.6e V" % (1e-3 / V)),
        ("tauf_min_q29", "%d" % q(0.2, 29), "0.2 rad"),
        ("tauf_max_q29", "%d" % q(2.0, 29), "2.0 rad"),
        ("w_v_q28", "%d" % q(omega * 100.0, 28), "w t_w = %.7f (t_w = 100 s)" % (omega * 100.0)),
        ("alpha_q30", "{%s}" % ", ".join(["%d" % q(1.0, 30)] * 6), "1.0 each"),
        ("k_pos_m", "%d" % q(POS_LSB / L * 2 ** 28, K_POS_SH), "1 mm = %.9f q28 LSB, / 2^%d" % (POS_LSB / L * 2 ** 28, K_POS_SH)),
        ("k_pos_sh", "%du" % K_POS_SH, None),
        ("k_vel_sh", "%du" % K_VEL_SH, None),
        ("k_tick_sh", "%du" % tick_sh, None),
        ("spare", "0u", None),
        ("k_vel_m", "%d" % q(VEL_LSB / V * 2 ** 28, K_VEL_SH), "10 um/s = %.9f q28 LSB, / 2^%d" % (VEL_LSB / V * 2 ** 28, K_VEL_SH)),
        ("k_tau_m", "%d" % q(omega * h * 2 ** 29, tau_sh), "w h = %.9e rad per step, q29 / 2^%d" % (omega * h, tau_sh)),
        ("k_tick_m", "%d" % q(1.0 / (omega * h) / 2 ** 29, tick_sh), "1/(w h) = %.6f steps per rad, / 2^%d from q29" % (1 / (omega * h), tick_sh)),
        ("omega_nradps", "%du" % rnd(omega * 1e9), "%.6e rad/s" % omega),
        ("a_nom_umps2", "%du" % rnd(a_nom * 1e6), "%.3f m/s^2" % a_nom),
        ("k_gtau_m", "%d" % q(omega * grid * 2 ** 29, gtau_sh), "w delta = %.9e rad per grid unit, q29 / 2^%d" % (omega * grid, gtau_sh)),
        ("k_gtick_m", "%d" % q(1.0 / (omega * grid) / 2 ** 29, gtick_sh), "1/(w delta) = %.6f grid units per rad, / 2^%d from q29" % (1 / (omega * grid), gtick_sh)),
        ("k_gtau_sh", "%du" % gtau_sh, None),
        ("k_gtick_sh", "%du" % gtick_sh, None),
        ("cal_enable", "1u", "calibration on"),
        ("cal_pool", "1u", "pooled mean for thrusters without a window"),
        ("dv_cal_min_q28", "%d" % q(0.5 / V, 28), "0.5 m/s"),
        ("cal_gate_q30", "%d" % q(0.2, 30), "0.2"),
        ("u_uncal_q30", "%d" % q(0.03, 30), "0.03"),
        ("u_cal_q30", "%d" % q(0.005, 30), "0.005"),
        ("miss_flag_q28", "%d" % q(10.0 / L, 28), "10 m"),
        ("fd_window", "%du" % steps(10.0), "10 s"),
        ("fd_frac_q30", "%d" % q(0.5, 30), "0.5"),
        ("fd_persist", "2u", "windows in a row"),
        ("spare2", "{0u, 0u, 0u}", None),
        ("nav_gate_pos_q28", "%d" % q(2.5 / L, 28), "2.5 m (5 sigma_p, degraded profile)"),
        ("nav_gate_vel_q28", "%d" % q(0.025 / V, 28), "25 mm/s (5 sigma_v, degraded profile)"),
        ("nav_gate_acc_q28", "%d" % q(1.5, 28), "1.5 a_nom: one thruster off or on, plus level error"),
        ("replan_gain_q30", "%d" % q(0.5, 30), "0.5: replace only if the predicted cost halves"),
        ("revision", "1u", None),
    ]
    return f


def render():
    cmd = "python -m tools.impulse ctable"
    head = ("/* GENERATED by `%s` (tools/impulse/ctable.py): do not edit.\n"
            " * Impulse-scheduler tables, spec 50-impulse §5.7: w = %.6e rad/s (400 km),\n"
            " * a_nom = %.3f m/s^2. Units: time 1/w = %.3f s, length a_nom/w^2 = %.2f m,\n"
            " * velocity a_nom/w = %.4f m/s. */\n" % (cmd, OMEGA, A_NOM, 1 / OMEGA, A_NOM / OMEGA ** 2, A_NOM / OMEGA))
    decl = "".join("extern const imp_params_t %s;   /* %s */\n" % (n, c) for n, _, _, c in TABLES)
    h = head + ("#ifndef FSW_IMP_TABLES_H\n#define FSW_IMP_TABLES_H\n\n#include \"imp.h\"\n\n" + decl +
                "\n#endif /* FSW_IMP_TABLES_H */\n")
    lines = [head, "#include \"imp_tables.h\"\n"]
    for name, period_us, subtick_us, com in TABLES:
        lines.append("\n/* %s */\nconst imp_params_t %s = {\n" % (com, name))
        for fname, val, fcom in fields(period_us, subtick_us):
            lines.append("    .%s = %s,%s\n" % (fname, val, ("  /* %s */" % fcom) if fcom else ""))
        lines.append("};\n")
    return {"imp_tables.h": h, "imp_tables.c": "".join(lines)}


def main(a):
    out_dir = os.path.dirname(a.out) or "."
    files = render()
    bad = 0
    for name, text in files.items():
        path = os.path.join(out_dir, name)
        if a.check:
            cur = open(path).read() if os.path.exists(path) else None
            if cur != text:
                print("differs: %s" % path)
                bad = 1
        else:
            with open(path, "w") as fh:
                fh.write(text)
            print(path)
    return bad
