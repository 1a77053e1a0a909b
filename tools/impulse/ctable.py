"""Generate fsw/impulse/imp_tables.[ch]: the impulse-scheduler tables (spec 50 §5.7).

Every derived integer comes from w, a_nom, the nav LSBs, the period and the valve grid, with its
real value in a comment. Three tables:
  IMP_TBL_DEFAULT  0.1 s tick, whole steps (the flight default)
  IMP_TBL_1S       1 s tick, whole steps (spec 50 §5.4 / A4-4 at 1 s)
  IMP_TBL_SUB1MS   0.1 s tick, 1 ms valve sub-ticks (spec 50 §2.4, §5.3)
`--check` regenerates in memory and requires byte identity with the committed files."""
import dataclasses
import math
import os

from . import model as m

HDR_NAME = "imp_tables.h"
OMEGA = m.OMEGA
A_NOM = m.A_NOM
POS_LSB = 1e-3      # m
VEL_LSB = 1e-5      # m/s


def worst_units(max_iter):
    """IMP_JOB_UNITS(max_iter) + IMP_ROUND_UNITS (fsw/impulse/imp.h): the worst plan's work units."""
    return 3 + 20 * (max_iter + 1) + 4


WORST_UNITS = worst_units(10)
WORST_ITER = 240    # IMP_PLAN_WORST_ITER: spec 50 §4.7, plan_lead >= ceil(240 / plan_iter_per_step)


@dataclasses.dataclass(frozen=True)
class Inputs:
    """What one impulse table is derived from: physics, hardware, timing and tuning in SI units.
    The defaults are the flight default table IMP_TBL_DEFAULT (spec 50 §5.7)."""
    omega_radps: float = OMEGA          # orbit rate
    a_nom_mps2: float = A_NOM           # nominal acceleration per thruster
    period_us: int = 100_000            # valve tick = fsw period
    subtick_us: int = 0                 # valve grid inside a tick (0: whole steps)
    t_min_us: int = 20_000              # minimum on-time
    nav_pos_lsb_m: float = POS_LSB      # nav position count
    nav_vel_lsb_mps: float = VEL_LSB    # nav velocity count
    plan_lead_s: float = 5.0
    replan_period_s: float = 100.0      # 0: never
    t_stop_s: float = 60.0
    nav_timeout_s: float = 5.0
    max_iter: int = 10
    pivot_ratio_sh: int = 12
    r_tol_lsb: int = 32
    pivot_min_log2: int = -10
    rho_warn: float = 0.38
    rho_reject: float = 0.55
    dv_tie_mps: float = 1e-3
    tauf_min_rad: float = 0.2
    tauf_max_rad: float = 2.0
    cost_weight_time_s: float = 100.0   # t_w of the rounding cost
    alpha_init: tuple = (1.0,) * 6
    cal_enable: bool = True
    cal_pool: bool = True
    dv_cal_min_mps: float = 0.5
    cal_gate: float = 0.2
    u_uncal: float = 0.03
    u_cal: float = 0.005
    miss_flag_m: float = 10.0
    fd_window_s: float = 10.0
    fd_frac: float = 0.5
    fd_persist: int = 2
    nav_gate_pos_m: float = 2.5
    nav_gate_vel_mps: float = 0.025
    nav_gate_acc: float = 1.5           # x a_nom
    replan_gain: float = 0.5


DEFAULT = Inputs()

# name, tick [us], sub-tick [us], comment. The tau shift of each grid (tick, sub-tick) keeps both
# mantissas of the reciprocal pair below 2^31 (shifts sum to 60).
TABLES = [
    ("IMP_TBL_DEFAULT", 100_000, 0, "default: tick 0.1 s, whole steps"),
    ("IMP_TBL_1S", 1_000_000, 0, "tick 1 s, whole steps"),
    ("IMP_TBL_SUB1MS", 100_000, 1_000, "tick 0.1 s, 1 ms valve sub-ticks"),
]


def rnd(x):
    """Round half away from zero (the project rule)."""
    return int(math.copysign(math.floor(abs(x) + 0.5), x))


def q(x, n):
    return rnd(x * 2.0 ** n)


def shifts(rate):
    """(tau shift, tick shift) of a grid of `rate` rad per grid unit: the smallest tau shift whose
    reciprocal (tick) mantissa is below 2^31, i.e. the most significant bits on the tick side
    (n = tau K, spec 50 §5.2), with the tau mantissa below 2^31 as well; the shifts sum to 60."""
    for sh in range(0, 61):
        if q(1.0 / rate / 2 ** 29, 60 - sh) < 2 ** 31:
            if q(rate * 2 ** 29, sh) >= 2 ** 31:
                break
            return sh, 60 - sh
    raise ValueError("no reciprocal scale pair for %.6e rad per grid unit" % rate)


def count_shift(k):
    """Largest shift (<= 62) that keeps round(k 2^shift) below 2^31: the count scale mantissa."""
    sh = 62
    while sh > 0 and q(k, sh) >= 2 ** 31:
        sh -= 1
    return sh


def plan_iter_per_step(lead, max_iter=10):
    """Work units per step so that the worst plan ends within the plan lead (imp_params_check):
    plan_lead >= ceil(worst / it) + 1 and >= ceil(240 / it); None if no it <= 255 does."""
    pips = 10
    while math.ceil(worst_units(max_iter) / pips) + 1 > lead or math.ceil(WORST_ITER / pips) > lead:
        pips += 1
        if pips > 255:
            return None
    return pips


def _g(x):
    return "%g" % x


def fields(period_us, subtick_us, omega=OMEGA, a_nom=A_NOM, inp=None):
    """(imp_params_t field, C initialiser, comment) of one table, from inp (Inputs; period_us,
    subtick_us, omega and a_nom are taken from the arguments, the rest from inp or the defaults)."""
    inp = dataclasses.replace(inp or DEFAULT, period_us=period_us, subtick_us=subtick_us, omega_radps=omega,
                              a_nom_mps2=a_nom)
    dflt = DEFAULT
    L, V = a_nom / omega ** 2, a_nom / omega
    h = period_us * 1e-6
    grid = (subtick_us if subtick_us else period_us) * 1e-6
    tau_sh, tick_sh = shifts(omega * h)
    gtau_sh, gtick_sh = shifts(omega * grid)
    steps = lambda s: rnd(s / h)   # seconds -> steps
    lead = steps(inp.plan_lead_s)
    pips = plan_iter_per_step(lead, inp.max_iter)
    if pips is None:
        raise ValueError("plan lead %d steps is too short for the worst plan at plan_iter_per_step <= 255" % lead)
    k_pos, k_vel = inp.nav_pos_lsb_m / L * 2 ** 28, inp.nav_vel_lsb_mps / V * 2 ** 28
    k_pos_sh, k_vel_sh = count_shift(k_pos), count_shift(k_vel)
    why = lambda x, d, text: text if x == d else ""   # the default's rationale, only for the default
    alpha = list(inp.alpha_init)
    f = [
        ("period_us", "%du" % period_us, "%.3f s valve tick" % h),
        ("subtick_us", "%du" % subtick_us, ("%.3f ms valve grid" % (subtick_us * 1e-3)) if subtick_us else "whole steps"),
        ("t_min_us", "%du" % inp.t_min_us, "%g ms minimum on-time" % (inp.t_min_us * 1e-3)),
        ("plan_lead", "%du" % lead, "%g s" % inp.plan_lead_s),
        ("replan_period", "%du" % steps(inp.replan_period_s),
         ("%g s" % inp.replan_period_s) if inp.replan_period_s else "never"),
        ("t_stop", "%du" % steps(inp.t_stop_s), "%g s" % inp.t_stop_s),
        ("nav_timeout", "%du" % steps(inp.nav_timeout_s), "%g s" % inp.nav_timeout_s),
        ("max_iter", "%du" % inp.max_iter, None),
        ("plan_iter_per_step", "%du" % pips, "work units per step: plan_lead >= ceil(%d / it) + 1, ceil(240 / it)"
         % worst_units(inp.max_iter)),
        ("pivot_ratio_sh", "%du" % inp.pivot_ratio_sh, "smallest/largest pivot >= 2^-%d" % inp.pivot_ratio_sh),
        ("k_tau_sh", "%du" % tau_sh, None),
        ("r_tol_lsb", "%d" % inp.r_tol_lsb, "%.2f mm, %.2f um/s" % (inp.r_tol_lsb * 2.0 ** -28 * L * 1e3,
                                                                   inp.r_tol_lsb * 2.0 ** -28 * V * 1e6)),
        ("pivot_min_q26", "%d" % q(2.0 ** inp.pivot_min_log2, 26), "2^%d" % inp.pivot_min_log2),
        ("rho_warn_q28", "%d" % q(inp.rho_warn, 28), _g(inp.rho_warn)),
        ("rho_reject_q28", "%d" % q(inp.rho_reject, 28), _g(inp.rho_reject)),
        ("dv_tie_q28", "%d" % q(inp.dv_tie_mps / V, 28), "%g mm/s = %.6e V" % (inp.dv_tie_mps * 1e3, inp.dv_tie_mps / V)),
        ("tauf_min_q29", "%d" % q(inp.tauf_min_rad, 29), "%.1f rad" % inp.tauf_min_rad),
        ("tauf_max_q29", "%d" % q(inp.tauf_max_rad, 29), "%.1f rad" % inp.tauf_max_rad),
        ("w_v_q28", "%d" % q(omega * inp.cost_weight_time_s, 28),
         "w t_w = %.7f (t_w = %g s)" % (omega * inp.cost_weight_time_s, inp.cost_weight_time_s)),
        ("alpha_q30", "{%s}" % ", ".join("%d" % q(a, 30) for a in alpha),
         ("%.1f each" % alpha[0]) if len(set(alpha)) == 1 else ", ".join(_g(a) for a in alpha)),
        ("k_pos_m", "%d" % q(k_pos, k_pos_sh), "%g mm = %.9f q28 LSB, / 2^%d" % (inp.nav_pos_lsb_m * 1e3, k_pos, k_pos_sh)),
        ("k_pos_sh", "%du" % k_pos_sh, None),
        ("k_vel_sh", "%du" % k_vel_sh, None),
        ("k_tick_sh", "%du" % tick_sh, None),
        ("spare", "0u", None),
        ("k_vel_m", "%d" % q(k_vel, k_vel_sh), "%g um/s = %.9f q28 LSB, / 2^%d" % (inp.nav_vel_lsb_mps * 1e6, k_vel, k_vel_sh)),
        ("k_tau_m", "%d" % q(omega * h * 2 ** 29, tau_sh), "w h = %.9e rad per step, q29 / 2^%d" % (omega * h, tau_sh)),
        ("k_tick_m", "%d" % q(1.0 / (omega * h) / 2 ** 29, tick_sh), "1/(w h) = %.6f steps per rad, / 2^%d from q29" % (1 / (omega * h), tick_sh)),
        ("omega_nradps", "%du" % rnd(omega * 1e9), "%.6e rad/s" % omega),
        ("a_nom_umps2", "%du" % rnd(a_nom * 1e6), "%.3f m/s^2" % a_nom),
        ("k_gtau_m", "%d" % q(omega * grid * 2 ** 29, gtau_sh), "w delta = %.9e rad per grid unit, q29 / 2^%d" % (omega * grid, gtau_sh)),
        ("k_gtick_m", "%d" % q(1.0 / (omega * grid) / 2 ** 29, gtick_sh), "1/(w delta) = %.6f grid units per rad, / 2^%d from q29" % (1 / (omega * grid), gtick_sh)),
        ("k_gtau_sh", "%du" % gtau_sh, None),
        ("k_gtick_sh", "%du" % gtick_sh, None),
        ("cal_enable", "%du" % int(inp.cal_enable), "calibration %s" % ("on" if inp.cal_enable else "off")),
        ("cal_pool", "%du" % int(inp.cal_pool),
         "pooled mean for thrusters without a window" if inp.cal_pool else "no pooling: uncalibrated thrusters keep alpha"),
        ("dv_cal_min_q28", "%d" % q(inp.dv_cal_min_mps / V, 28), "%g m/s" % inp.dv_cal_min_mps),
        ("cal_gate_q30", "%d" % q(inp.cal_gate, 30), _g(inp.cal_gate)),
        ("u_uncal_q30", "%d" % q(inp.u_uncal, 30), _g(inp.u_uncal)),
        ("u_cal_q30", "%d" % q(inp.u_cal, 30), _g(inp.u_cal)),
        ("miss_flag_q28", "%d" % q(inp.miss_flag_m / L, 28), "%g m" % inp.miss_flag_m),
        ("fd_window", "%du" % steps(inp.fd_window_s), "%g s" % inp.fd_window_s),
        ("fd_frac_q30", "%d" % q(inp.fd_frac, 30), _g(inp.fd_frac)),
        ("fd_persist", "%du" % inp.fd_persist, "windows in a row"),
        ("spare2", "{0u, 0u, 0u}", None),
        ("nav_gate_pos_q28", "%d" % q(inp.nav_gate_pos_m / L, 28),
         "%g m" % inp.nav_gate_pos_m + why(inp.nav_gate_pos_m, dflt.nav_gate_pos_m, " (5 sigma_p, degraded profile)")),
        ("nav_gate_vel_q28", "%d" % q(inp.nav_gate_vel_mps / V, 28),
         "%g mm/s" % (inp.nav_gate_vel_mps * 1e3) + why(inp.nav_gate_vel_mps, dflt.nav_gate_vel_mps,
                                                       " (5 sigma_v, degraded profile)")),
        ("nav_gate_acc_q28", "%d" % q(inp.nav_gate_acc, 28),
         "%g a_nom" % inp.nav_gate_acc + why(inp.nav_gate_acc, dflt.nav_gate_acc,
                                             ": one thruster off or on, plus level error")),
        ("replan_gain_q30", "%d" % q(inp.replan_gain, 30),
         _g(inp.replan_gain) + why(inp.replan_gain, dflt.replan_gain, ": replace only if the predicted cost halves")),
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
