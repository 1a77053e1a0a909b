"""The relay tables from physical parameters (spec 20 §2.1, §5.7, §9): the one place their
integers are derived, with exact decimal arithmetic for the phase increments.

    eps_q24 = round(eps 2^24), gamma_q24 = round(gamma 2^24)     (eps - gamma formed on board)
    f_q64_i = round(omega_i / 2 pi 2^64)                          turns/s, Q0.64
    dphi_i  = round(omega_i h / 2 pi 2^64)                        BAM per tick
    C_u,i   = round(k_i m_u / omega_i^2 2^40), C_eps,i likewise   q40 rad
    q0_i    = round(x~_i(0) 2^40), p0_i = round(x~_i'(0) / omega_i 2^40)
    k_t     = round(k_t 2^16)                                     Q0.16

Change a design (or add one to TABLES) and run `python -m tools.relay ctable` to rewrite the C boot
tables; CTest golden_rly_tables_regen fails while they disagree.
"""
from decimal import Decimal, getcontext

getcontext().prec = 60
# pi to 60 digits: the phase increments must not depend on a float pi (their last bits are flown)
PI = Decimal("3.14159265358979323846264338327950288419716939937510582097494")
MAX_MODES = 4

# The source's example (spec 20 §2.1) and the adaptation defaults (§5.7), except adapt_mode: the flight
# default is IMPROVED_UP (3), §5.6's IMPROVED with two amendments (fsw/relay/README.md "k_t adaptation").
PAPER_PLANT = dict(
    period_s=0.001,
    eps_rad=5e-4, gamma_rad=1e-4, x_max_rad=0.5,
    m_u_radps2=4e-5, m_eps_radps2=1e-6,
    omega_radps=[0.44, 0.755], k=[0.0213, 0.0216],
    xt0_rad=[2.75e-6, 0.0], xtdot0_radps=[0.0, 0.0],
    tau_max_s=60.0, lost_s=0.1, env_alarm_rad=3e-5,
)
ADAPT = dict(adapt_mode=3, win_s=500.0, tmin_windows=20, dk=0.002, kt0=0.31, kt_min=0.28, kt_max=0.40,
             delta0=(1, 20), n_small=6, n_ignore=4, count_before_tmin=1, learn_after_tmin=1, seed=1,
             gate_dk=2, probe_settle=1, cliff=(3, 2), retreat_dk=2, unfreeze=(3, 2), unfreeze_windows=3)


def design(**over):
    d = dict(PAPER_PLANT)
    d.update(ADAPT)
    d.update(over)
    return d


# (name in scenarios and tools, C symbol, design)
TABLES = [
    ("rly_default", "RLY_TBL_DEFAULT", design()),                          # IMPROVED_UP (flight default)
    ("rly_improved", "RLY_TBL_IMPROVED", design(adapt_mode=2)),            # IMPROVED as spec 20 §5.6 prints it
    ("rly_paper", "RLY_TBL_PAPER", design(adapt_mode=1)),                  # PAPER (the source's rule)
    ("rly_fixed_031", "RLY_TBL_FIXED_031", design(adapt_mode=0)),          # k_t = 0.31 held (S2, S3)
    ("rly_fixed_03389", "RLY_TBL_FIXED_03389", design(adapt_mode=0, kt0=0.3389)),   # S4
]


def rnd(v):
    """Round half away from zero (the flight code's rule) of a Decimal or float."""
    v = Decimal(v)
    r = int((abs(v) + Decimal("0.5")).to_integral_value(rounding="ROUND_FLOOR"))
    return r if v >= 0 else -r


def params(d):
    """Raw integer table fields (rly_params_t wire names, revision excluded) of design d."""
    n = len(d["omega_radps"])
    if n > MAX_MODES:
        raise ValueError("at most %d modes" % MAX_MODES)
    pad = lambda v: list(v) + [0] * (MAX_MODES - len(v))
    h = Decimal(repr(d["period_s"]))
    f64, dphi, cu, ce, q0, p0 = [], [], [], [], [], []
    for i in range(n):
        w = Decimal(repr(d["omega_radps"][i]))
        k = Decimal(repr(d["k"][i]))
        f64.append(rnd(w / (2 * PI) * 2 ** 64))
        dphi.append(rnd(w * h / (2 * PI) * 2 ** 64))
        cu.append(rnd(k * Decimal(repr(d["m_u_radps2"])) / (w * w) * 2 ** 40))
        ce.append(rnd(k * Decimal(repr(d["m_eps_radps2"])) / (w * w) * 2 ** 40))
        q0.append(rnd(Decimal(repr(d["xt0_rad"][i])) * 2 ** 40))
        p0.append(rnd(Decimal(repr(d["xtdot0_radps"][i])) / w * 2 ** 40))
    f64, dphi = pad(f64), pad(dphi)
    ticks = lambda s: rnd(Decimal(repr(s)) / h)
    return {
        "period_us": rnd(h * 10 ** 6),
        "x_max_q24": rnd(Decimal(repr(d["x_max_rad"])) * 2 ** 24),
        "eps_q24": rnd(Decimal(repr(d["eps_rad"])) * 2 ** 24),
        "gamma_q24": rnd(Decimal(repr(d["gamma_rad"])) * 2 ** 24),
        "tau_max_ticks": ticks(d["tau_max_s"]),
        "win_ticks": ticks(d["win_s"]),
        "seed": d["seed"],
        "env_alarm_q40": rnd(Decimal(repr(d["env_alarm_rad"])) * 2 ** 40),
        "lost_ticks": ticks(d["lost_s"]),
        "tmin_windows": d["tmin_windows"],
        "dk_q16": rnd(Decimal(repr(d["dk"])) * 2 ** 16),
        "kt0_q16": rnd(Decimal(repr(d["kt0"])) * 2 ** 16),
        "kt_min_q16": rnd(Decimal(repr(d["kt_min"])) * 2 ** 16),
        "kt_max_q16": rnd(Decimal(repr(d["kt_max"])) * 2 ** 16),
        "n_modes": n,
        "adapt_mode": d["adapt_mode"],
        "delta0_num": d["delta0"][0], "delta0_den": d["delta0"][1],
        "n_small": d["n_small"], "n_ignore": d["n_ignore"],
        "count_before_tmin": d["count_before_tmin"], "learn_after_tmin": d["learn_after_tmin"],
        "gate_dk": d["gate_dk"], "probe_settle": d["probe_settle"],
        "cliff_num": d["cliff"][0], "cliff_den": d["cliff"][1], "retreat_dk": d["retreat_dk"],
        "unfreeze_num": d["unfreeze"][0], "unfreeze_den": d["unfreeze"][1],
        "unfreeze_windows": d["unfreeze_windows"],
        "dphi_lo": [v & 0xFFFFFFFF for v in dphi], "dphi_hi": [v >> 32 for v in dphi],
        "f_lo": [v & 0xFFFFFFFF for v in f64], "f_hi": [v >> 32 for v in f64],
        "cu_q40": pad(cu), "ce_q40": pad(ce), "q0_q40": pad(q0), "p0_q40": pad(p0),
    }


def table(name):
    for n, _, d in TABLES:
        if n == name:
            return params(d)
    raise KeyError(name)


def physical(name):
    """The design (SI values) of a boot table, for the plant and the reference."""
    for n, _, d in TABLES:
        if n == name:
            return dict(d)
    raise KeyError(name)
