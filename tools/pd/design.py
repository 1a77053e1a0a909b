"""The pd table from physical design values: the one place its integers are derived.

    K = J / tau          rate-damping gain [N m s]: the closed loop omega' = -omega / tau
    gain_q16 = K * 2^12  torque counts (2^-16 N m) per rate count (2^-20 rad/s), q16:
                         u = K omega / 2^-16 = K rate 2^-20 / 2^-16 = (K 2^12) rate / 2^16
    u_max_cnt = torque_max / 2^-16, rate_max_cnt = rate full scale / 2^-20,
    n_sat = sat_persist_s / period_s

Change DESIGN (or add a table to TABLES) and run `python -m tools.pd ctable` to rewrite the
C boot tables; CTest golden_pd_tables_regen fails while they disagree.
"""
import math

RATE_LSB_RADPS = 2.0 ** -20      # sensor channel 0 (fsw/pd/pd_iface.py)
TORQUE_LSB_NM = 2.0 ** -16       # actuator channel 0

DESIGN = dict(
    period_s=0.1,                # 10 Hz
    inertia_kgm2=10.0,           # single-axis inertia of the plant the table is designed for
    tau_s=20.0,                  # closed-loop time constant
    torque_max_nm=0.05,          # actuator authority
    rate_full_scale_radps=0.5,   # gyro full scale
    sat_persist_s=60.0,          # limiting this long raises CMD_LIMIT_PERSIST
)

# (name in scenarios and tools, C symbol, design)
TABLES = [("pd_default", "PD_TBL_DEFAULT", DESIGN)]


def rnd(v):
    """Round half away from zero (as the flight code's fx rounding)."""
    return int(math.floor(abs(v) + 0.5)) * (1 if v >= 0 else -1)


def params(d):
    """Raw integer table fields (pd_params_t names, revision excluded) of design d."""
    k = d["inertia_kgm2"] / d["tau_s"]
    return {
        "period_us": rnd(d["period_s"] * 1e6),
        "rate_max_cnt": rnd(d["rate_full_scale_radps"] / RATE_LSB_RADPS),
        "gain_q16": rnd(k * TORQUE_LSB_NM ** -1 * RATE_LSB_RADPS * 65536.0),
        "u_max_cnt": rnd(d["torque_max_nm"] / TORQUE_LSB_NM),
        "n_sat": rnd(d["sat_persist_s"] / d["period_s"]),
        "spare": 0,
    }


def table(name):
    for n, _, d in TABLES:
        if n == name:
            return params(d)
    raise KeyError(name)
