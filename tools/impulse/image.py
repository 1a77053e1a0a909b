"""Binary impulse-table images from the table generator: an independent oracle for the flight decoder.

    python -m tools.impulse image --table NAME [--revision N] [--set FIELD=INT ...] -o FILE
    python -m tools.impulse image --all DIR [--revision N]

NAME is imp_default, imp_1s or imp_sub1ms (the boot tables IMP_TBL_DEFAULT, IMP_TBL_1S and
IMP_TBL_SUB1MS of fsw/impulse/imp_tables.c). The integers are the ones `ctable` writes into those C
initialisers: `params()` takes them from ctable's own computation (`ctable.fields`, the function
that renders the initialisers) and requires its field list to be exactly this layout plus
`revision`. They are packed here with Python struct, independently of the C encoder, in the wire
layout documented in fsw/impulse/imp_table.c (spec 00 §3.2, 50-impulse §5.7):

    header  <HHIII  table_id 0x0B04, layout_version 1, payload length 176, revision,
                    zlib.crc32(payload)
    payload 176 bytes, little-endian, field by field in imp_params_t order without `revision`
            (PAYLOAD below; the spare bytes are on the wire and must be zero)

`--set FIELD=INT` replaces one field by its imp_params_t name with a raw integer before the CRC
(`FIELD[i]=INT` for one entry of alpha_q30 or spare2). Header pseudo-fields `hdr.table_id`,
`hdr.layout_version`, `hdr.length`, `hdr.revision` and `hdr.crc` replace header words after the
CRC is computed (for tests of the loader's header/CRC checks); `revision` is `hdr.revision`.
"""
import re

from tools.table import image_writer

from . import ctable

TABLE_ID = 0x0B04
LAYOUT_VERSION = 1
PAYLOAD_BYTES = 176
NTHR = 6

I32MAX = 2 ** 31 - 1
US_MAX = 10_000_000        # 10 s
STEPS_MAX = 10_000_000     # step counts: 10^4 s at a 1 ms period
ALPHA_MIN, ALPHA_MAX = image_writer.q_rat(4, 5, 30), image_writer.q_rat(6, 5, 30)
TAU_LO, TAU_HI = image_writer.q_rat(1, 5, 29), 2 << 29
HALF_Q30 = image_writer.q_rat(1, 2, 30)

# (imp_params_t field, struct code, count, lo, hi) in wire order (fsw/impulse/imp_table.c header
# comment), with the flight loader's limits (IMP_LIMS of fsw/impulse/imp_table.c) for every entry.
PAYLOAD = [
    ("period_us", "I", 1, 1000, US_MAX), ("subtick_us", "I", 1, 0, US_MAX), ("t_min_us", "I", 1, 0, US_MAX),
    ("plan_lead", "I", 1, 2, STEPS_MAX), ("replan_period", "I", 1, 0, STEPS_MAX), ("t_stop", "I", 1, 0, STEPS_MAX),
    ("nav_timeout", "I", 1, 1, STEPS_MAX),
    ("max_iter", "B", 1, 1, 16), ("plan_iter_per_step", "B", 1, 4, 255), ("pivot_ratio_sh", "B", 1, 0, 30),
    ("k_tau_sh", "B", 1, 0, 60),
    ("r_tol_lsb", "i", 1, 1, 65536), ("pivot_min_q26", "i", 1, 1, 1 << 26), ("rho_warn_q28", "i", 1, 1, 1 << 28),
    ("rho_reject_q28", "i", 1, 1, 1 << 28), ("dv_tie_q28", "i", 1, 0, 1 << 28),
    ("tauf_min_q29", "i", 1, TAU_LO, TAU_HI), ("tauf_max_q29", "i", 1, TAU_LO, TAU_HI), ("w_v_q28", "i", 1, 1, 1 << 30),
    ("alpha_q30", "i", NTHR, ALPHA_MIN, ALPHA_MAX),
    ("k_pos_m", "i", 1, 1, I32MAX), ("k_pos_sh", "B", 1, 0, 62), ("k_vel_sh", "B", 1, 0, 62),
    ("k_tick_sh", "B", 1, 1, 60), ("spare", "B", 1, 0, 0),
    ("k_vel_m", "i", 1, 1, I32MAX), ("k_tau_m", "i", 1, 1, I32MAX), ("k_tick_m", "i", 1, 1, I32MAX),
    ("omega_nradps", "I", 1, 1000, 2_000_000), ("a_nom_umps2", "I", 1, 1, 10_000_000),
    ("k_gtau_m", "i", 1, 1, I32MAX), ("k_gtick_m", "i", 1, 1, I32MAX), ("k_gtau_sh", "B", 1, 0, 60),
    ("k_gtick_sh", "B", 1, 0, 60),
    ("cal_enable", "B", 1, 0, 1), ("cal_pool", "B", 1, 0, 1),
    ("dv_cal_min_q28", "i", 1, 0, 1 << 28), ("cal_gate_q30", "i", 1, 1, HALF_Q30),
    ("u_uncal_q30", "i", 1, 0, HALF_Q30), ("u_cal_q30", "i", 1, 0, HALF_Q30),
    ("miss_flag_q28", "i", 1, 1, I32MAX),
    ("fd_window", "I", 1, 1, 60000), ("fd_frac_q30", "i", 1, 1, (1 << 30) - 1), ("fd_persist", "B", 1, 1, 255),
    ("spare2", "B", 3, 0, 0),
    ("nav_gate_pos_q28", "i", 1, 1, I32MAX), ("nav_gate_vel_q28", "i", 1, 1, I32MAX),
    ("nav_gate_acc_q28", "i", 1, 0, I32MAX), ("replan_gain_q30", "i", 1, 0, (1 << 30) - 1),
]
# value[a] + margin <= value[b] (IMP_RELS)
RELS = [("t_min_us", "period_us", 0), ("subtick_us", "period_us", 0), ("rho_warn_q28", "rho_reject_q28", 0),
        ("tauf_min_q29", "tauf_max_q29", 0), ("u_cal_q30", "u_uncal_q30", 0)]
LAYOUT = image_writer.Layout(TABLE_ID, LAYOUT_VERSION, PAYLOAD, PAYLOAD_BYTES, RELS, "fsw/impulse/imp_table.c")
FIELDS = LAYOUT.fields
# tool name -> (C name, period_us, subtick_us), in ctable's order
TABLES = {n.lower().replace("imp_tbl_", "imp_"): (n, per, sub) for n, per, sub, _ in ctable.TABLES}
NAMES = list(TABLES)


def _c_value(s):
    """int or [int] of one C initialiser value as ctable writes it ("100000u", "-3", "{1, 2}")."""
    s = s.strip()
    if s.startswith("{"):
        return [_c_value(x) for x in s[1:-1].split(",") if x.strip()]
    m = re.fullmatch(r"(-?\d+)u?", s)
    if m is None:
        raise ValueError("cannot parse initialiser value %r" % s)
    return int(m.group(1))


def params(name):
    """Raw integer fields of boot table NAME, from ctable's computation of the C initialiser."""
    if name not in TABLES:
        raise SystemExit("image: unknown table %r; choose from %s" % (name, ", ".join(NAMES)))
    _, period_us, subtick_us = TABLES[name]
    vals = [(f, _c_value(v)) for f, v, _ in ctable.fields(period_us, subtick_us)]
    names = [f for f, _ in vals]
    if names != [e[0] for e in PAYLOAD] + ["revision"]:
        raise AssertionError("image: ctable's imp_params_t fields %s differ from the wire layout %s + revision"
                             % (names, [e[0] for e in PAYLOAD]))
    p = dict(vals)
    p.pop("revision")
    for f, (_, n) in FIELDS.items():
        if (n > 1) != isinstance(p[f], list) or (n > 1 and len(p[f]) != n):
            raise AssertionError("image: %s: ctable gives %r, the layout has %d entries" % (f, p[f], n))
    return p


def build(name, revision=1, sets=None):
    """Complete image (header + payload) of boot table NAME."""
    return LAYOUT.build(params(name), revision, sets)


def decode(img):
    """(header dict, params dict) of an image, with Python struct only; raises ValueError if malformed."""
    return LAYOUT.decode(img)


def main(args):
    return image_writer.main(args, LAYOUT, NAMES, params)
