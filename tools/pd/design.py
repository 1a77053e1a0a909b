"""The pd mission table from physical design values and the host-synthesised schedules: the one
place its integers are derived (spec 40 §4.1 item 5, §5).

Schedules: tools/pd/schedule/<channel>_<law>.json, written by `python -m tools.pd schedule`
(tools/pd/pd_analysis synth on the reconstructed model; CTest golden_pd_schedule_regen re-runs it and
compares). Every k2 is uq22 (k2 * 2^22, rounded half away from zero), f uq32 Hz, 1/df uq16 1/Hz,
1/Ty uq22 1/s, y / dy q30 rad, torques q28 N m, gimbal angles q24 rad (the encoder's counts).

Change DESIGN / CHANNELS (or add a table to TABLES) and run `python -m tools.pd ctable` to rewrite the
C boot tables; CTest golden_pd_tables_regen fails while they disagree.

Estimator blocks: tools/pd/fest/<channel>.json (each channel's pd_fest_params_t, already integers),
written by `python -m tools.pd fest` (pd_analysis fest-params: the double design on the channel's
nominal model through sim/pd/pd_fest_quant; CTest golden_pd_fest_regen re-runs it and compares). Every
channel carries its block; yaw's (n_sec 2) is refused by pd_fest_check, so yaw cannot fly ADAPTIVE.
"""
import json
import math
import os

from . import fest as _fest

HERE = os.path.dirname(os.path.abspath(__file__))
CHANNELS = ("yaw", "roll", "pitch")
LAWS = {"fast": 0, "fast_avgp": 1, "literal": 2}
SRCS = {"fixed": 0, "ground": 1, "adaptive": 2}
N_NODES = 19

DESIGN = dict(
    period_s=0.25,          # Ty = n_div period: the attitude sample (spec 40 §2.4)
    n_div=1,
    law="fast",             # PD_LAW_FAST, the shipped law (§3.2)
    src="fixed",            # at boot: k2_nom; SET_SOURCE / SET_F select GROUND or ADAPTIVE (pd_adaptive: from boot)
    sched="fast",           # the law the schedule was synthesised for
    ch_mask=7,
    n_y=16,                 # T0 = 4 s
    n_bad_max=4,            # §8 bad control period
    n_hold=1,               # §8 missing sample: hold one sample, then coast
    n_frozen=40,
    y_lim_rad=0.5,
    dy_max_rad=2.0 ** -6,
    m_max_nm=2.0,           # [U] 3x the largest command (§2.4)
    m_frozen_nm=0.01,
    beta_warn_rad=0.5,
    beta_lim_rad=math.pi / 4.0,
    f_ground_hz=0.05,       # GROUND before any SET_F: the estimator's prior f0 (§4.3 R3)
)

# k0, k1 nominal (§2.4); k2_nom: the boot FIXED gain = k2_cold, the slow-first constant admissible at
# every f (§4.2: never cold-start at the nominal 150); k2_max: the hard cap (§3.4: roll 150; yaw:
# lifted rho < 1 up to 820 at 0.10 Hz, the largest node is 805; pitch stable beyond 1200).
CHANNELS_DESIGN = {
    "yaw": dict(k0=2.0, k1=20.0, k2_min=0.0, k2_max=815.0),
    "roll": dict(k0=2.0, k1=15.0, k2_min=0.0, k2_max=150.0),
    "pitch": dict(k0=2.0, k1=20.0, k2_min=0.0, k2_max=1000.0),
}

# (name in scenarios and tools, C symbol, overrides of DESIGN)
TABLES = [("pd_default", "PD_TBL_DEFAULT", {}),
          ("pd_literal", "PD_TBL_LITERAL", {"law": "literal"}),
          ("pd_avgp", "PD_TBL_AVGP", {"law": "fast_avgp"}),
          # ADAPTIVE from boot on roll and pitch (ch_mask 6: the run command's scenario is pitch's cold
          # start; the A3-6 yaw campaign flies yaw too by dispersing ch_mask to 7)
          ("pd_adaptive", "PD_TBL_ADAPTIVE", {"src": "adaptive", "ch_mask": 6})]


def rnd(v):
    """Round half away from zero (as the flight code's fx rounding)."""
    return int(math.floor(abs(v) + 0.5)) * (1 if v >= 0 else -1)


def schedule(channel, law="fast"):
    with open(os.path.join(HERE, "schedule", "%s_%s.json" % (channel, law))) as fh:
        d = json.load(fh)
    fs = [n["f"] for n in d["nodes"]]
    if len(fs) != N_NODES or any(abs(fs[i] - (0.010 + 0.005 * i)) > 1e-12 for i in range(N_NODES)):
        raise ValueError("%s: the schedule nodes must be 0.010 .. 0.100 Hz at 0.005 Hz" % channel)
    return d


def design(name):
    for n, _, over in TABLES:
        if n == name:
            d = dict(DESIGN)
            d.update(over)
            return d
    raise KeyError(name)


def params(d):
    """Raw integer table fields in wire order: (common dict, [channel dict] x 3), revision excluded."""
    ty_us = rnd(d["period_s"] * 1e6) * d["n_div"]
    c = {
        "period_us": rnd(d["period_s"] * 1e6),
        "inv_ty_q22": rnd(2.0 ** 22 * 1e6 / ty_us),
        "law": LAWS[d["law"]], "src": SRCS[d["src"]],
        "sched_law": LAWS[d["sched"]],   # the law the nodes were synthesised for (§3.3)
        "ch_mask": d["ch_mask"], "n_y": d["n_y"], "n_bad_max": d["n_bad_max"], "n_div": d["n_div"],
        "n_hold": d["n_hold"], "n_frozen": d["n_frozen"],
        "y_lim_q30": rnd(d["y_lim_rad"] * 2.0 ** 30), "dy_max_q30": rnd(d["dy_max_rad"] * 2.0 ** 30),
        "m_max_q28": rnd(d["m_max_nm"] * 2.0 ** 28), "m_frozen_q28": rnd(d["m_frozen_nm"] * 2.0 ** 28),
        "beta_warn_q24": rnd(d["beta_warn_rad"] * 2.0 ** 24), "beta_lim_q24": rnd(d["beta_lim_rad"] * 2.0 ** 24),
        "f0_q32": rnd(0.010 * 2.0 ** 32), "df_inv_q16": rnd(2.0 ** 16 / 0.005),
        "f_ground_q32": rnd(d["f_ground_hz"] * 2.0 ** 32),
    }
    chans = []
    for ch in CHANNELS:
        g = CHANNELS_DESIGN[ch]
        s = schedule(ch, d["sched"])
        q = lambda v: rnd(v * 2.0 ** 22)  # noqa: E731
        chans.append({"k0_q22": q(g["k0"]), "k1_q22": q(g["k1"]), "k2_nom_q22": q(s["k2_cold"]),
                      "k2_cold_q22": q(s["k2_cold"]), "k2_min_q22": q(g["k2_min"]), "k2_max_q22": q(g["k2_max"]),
                      "k2_node_q22": [q(n["k2"]) for n in s["nodes"]],
                      "fest": _fest.load(ch),
                      "_nodes": s["nodes"]})
    return c, chans


def table(name):
    return params(design(name))


def flat(name):
    """Every raw field by its wire name (channel fields prefixed yaw_ / roll_ / pitch_; the estimator
    block's prefixed <channel>_fest_, its matrices flattened row-major, with the two reserved bytes the
    wire carries after n_reg)."""
    c, chans = table(name)
    out = dict(c)
    for ch, g in zip(CHANNELS, chans):
        for k, v in g.items():
            if k == "fest":
                for f, fv in v.items():
                    out["%s_fest_%s" % (ch, f)] = _fest.flatten(fv)
                out["%s_fest_reserved0" % ch] = 0
                out["%s_fest_reserved1" % ch] = 0
            elif not k.startswith("_"):
                out["%s_%s" % (ch, k)] = v
    return out
