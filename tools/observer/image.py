"""Binary observer-table images from the design tool: an independent oracle for the flight decoder.

    python -m tools.observer image --table NAME [--revision N] [--set FIELD=INT ...] -o FILE
    python -m tools.observer image --all DIR [--revision N]

The integers are the ones `ctable` writes into the C boot tables (fsw/observer/obs_tables.c):
`params()` takes them from ctable's own computation (its constants, q_int and design tables,
as table_c does) and cross-checks every field against the initialiser text table_c renders.
They are packed here with Python struct, independently of the C encoder, in the wire layout
documented in fsw/observer/obs_table.c (spec 00 §3.2, 10-observer §4.6):

    header  <HHIII  table_id 0x0B01, layout_version 2, payload length 652, revision,
                    zlib.crc32(payload)
    payload 652 bytes, little-endian, field by field (PAYLOAD below)

`--set FIELD=INT` replaces one field by its obs_params_t name with a raw integer before the CRC
(`FIELD[i]=INT` for one entry of a vector/matrix). Header pseudo-fields `hdr.table_id`,
`hdr.layout_version`, `hdr.length`, `hdr.revision` and `hdr.crc` replace header words after the
CRC is computed (for tests of the loader's header/CRC checks).
"""
import re

from tools.table import image_writer

from . import ctable
from . import design as dz

TABLE_ID = 0x0B01
LAYOUT_VERSION = 2
PAYLOAD_BYTES = 652
NX, NZ, NU, NY = 6, 7, 2, 2
EST = {"OBS_EST_EKF": 0, "OBS_EST_CONST_W": 2}

I32MAX = 2 ** 31 - 1

# (obs_params_t field, struct code, count[, lo, hi]) in wire order (fsw/observer/obs_table.c header
# comment), with the flight loader's limits (OBS_LIMS of fsw/observer/obs_table.c) where it has
# any: every scalar and the ls/p0/qd vectors; matrix entries span the whole int32 range.
PAYLOAD = [
    ("period_us", "I", 1, 1000, 1_000_000), ("estimator", "B", 1, 0, 2), ("gyro_cnt_shift", "B", 1, 0, 29),
    ("act_cnt_shift", "B", 1, 0, 29), ("d2_reject", "B", 1, 0, 1), ("sigma", "i", 1, -1, 1),
    ("gyro_max_cnt", "i", 1, 1, I32MAX), ("act_max_cnt", "i", 1, 1, I32MAX),
    ("bdot_max_q29", "i", 1, 1, I32MAX), ("bdot_hw_q29", "i", 1, 1, I32MAX),
    ("q_phi0", "B", 1, 16, 40), ("q_phik", "B", 1, 16, 40), ("q_gam0", "B", 1, 16, 40), ("q_gamk", "B", 1, 16, 40),
    ("q_d", "B", 1, 16, 40), ("q_w", "B", 1, 16, 40),
    ("n_lost", "H", 1, 1, 65535), ("n_good", "H", 1, 1, 65535), ("n_sat", "H", 1, 1, 65535),
    ("n_gap_max", "H", 1, 1, 65535),
    ("kappa0_q28", "i", 1, 1, I32MAX), ("kappa_init_q28", "i", 1, 1, I32MAX), ("kappa_lo_q28", "i", 1, 1, I32MAX),
    ("kappa_hi_q28", "i", 1, 1, I32MAX),
    ("r_q30", "i", 1, 1, I32MAX), ("p_floor_q30", "i", 1, 1, I32MAX), ("p_ceil_q30", "i", 1, 1, I32MAX),
    ("d2_max_q16", "i", 1, 1, I32MAX),
    ("ls", "i", NZ, -40, 40), ("p0_q30", "i", NZ, 1, I32MAX), ("qd_q30", "i", NZ, 4, I32MAX),
    ("phi0", "i", NX * NX), ("phik", "i", NX * NX), ("gam0", "i", NX * NU), ("gamk", "i", NX * NU),
    ("d", "i", NU * NX), ("w", "i", NZ * NY),
    ("n_rej_safe", "H", 1, 1, 65535), ("rej_leak_inc", "H", 1, 1, 65535), ("rej_freeze_on", "H", 1, 1, 65535),
]
# value[a] + margin <= value[b] (OBS_RELS)
RELS = [("bdot_max_q29", "bdot_hw_q29", 0), ("kappa_lo_q28", "kappa_hi_q28", 1), ("kappa_lo_q28", "kappa0_q28", 0),
        ("kappa0_q28", "kappa_hi_q28", 0), ("kappa_lo_q28", "kappa_init_q28", 0),
        ("kappa_init_q28", "kappa_hi_q28", 0), ("p_floor_q30", "p_ceil_q30", 1)]
LAYOUT = image_writer.Layout(TABLE_ID, LAYOUT_VERSION, PAYLOAD, PAYLOAD_BYTES, RELS, "fsw/observer/obs_table.c")
FIELDS = LAYOUT.fields
NAMES = [name for name, _ in ctable.TABLES]

_TABS = None


def _tables():
    global _TABS
    if _TABS is None:
        _TABS = {k: dz._clean(v) for k, v in dz.all_tables().items()}   # as ctable.render does
    return _TABS


def _from_design(tab, hw=ctable.HW):
    """The integers of ctable.table_c, from the same constants and helpers (hw: ctable.Hw)."""
    mat, ekf = tab["matrices"], tab["ekf"]
    p = {
        "period_us": int(tab["period_us"]),
        "estimator": EST["OBS_EST_EKF" if tab["estimator"] == "EKF" else "OBS_EST_CONST_W"],
        "sigma": int(tab["sigma"]),
        "gyro_cnt_shift": ctable.X_Q + hw.gyro_lsb_log2,
        "act_cnt_shift": ctable.X_Q + hw.act_lsb_log2,
        "gyro_max_cnt": hw.gyro_max_cnt,
        "act_max_cnt": hw.act_max_cnt(),
        "bdot_max_q29": ctable.q_int(hw.bdot_max, ctable.X_Q),
        "bdot_hw_q29": ctable.q_int(hw.bdot_hw, ctable.X_Q),
    }
    for field, key in (("phi0", "Phi0"), ("phik", "Phi_kappa"), ("gam0", "Gam0"), ("gamk", "Gam_kappa"),
                       ("d", "D"), ("w", "W")):
        p[field] = [int(v) for row in mat[key]["int32"] for v in row]
        p["q_" + field] = int(mat[key]["q"])
    p["kappa0_q28"] = ctable.q_int(tab["kappa0"], ctable.KAPPA_Q)
    p["kappa_init_q28"] = ctable.q_int(tab["kappa_init"], ctable.KAPPA_Q)
    p["kappa_lo_q28"] = ctable.q_int(tab["kappa_band"][0], ctable.KAPPA_Q)
    p["kappa_hi_q28"] = ctable.q_int(tab["kappa_band"][1], ctable.KAPPA_Q)
    if ekf is None:   # neutral CONST_W covariance fields, as table_c writes them
        p["ls"], p["p0_q30"], p["qd_q30"], p["r_q30"] = [-13, -13, -10, -10, -10, -10, -1], [1 << 20] * 7, [4] * 7, 1 << 20
    else:
        p["ls"] = [int(v) for v in ekf["S_log2"]]
        p["p0_q30"] = [int(v) for v in ekf["P0_scaled_int32"]]
        p["qd_q30"] = [int(v) for v in ekf["Q_scaled_int32"]]
        p["r_q30"] = int(ekf["R_scaled_int32"][0])
    p["p_floor_q30"] = hw.p_floor
    p["p_ceil_q30"] = ctable.q_int(hw.p_ceil, ctable.P_Q)
    for k in ("n_lost", "n_good", "n_sat", "n_gap_max", "n_rej_safe", "rej_leak_inc", "rej_freeze_on"):
        p[k] = int(getattr(hw, k))
    p["d2_max_q16"] = ctable.q_int(hw.d2_max, ctable.D2_Q)
    p["d2_reject"] = int(hw.d2_reject)
    return p


def parse_initialiser(text):
    """{field: int or [int]} from one obs_params_t C initialiser (as table_c / obs_tables.c write it)."""
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    text = text[text.index("{") + 1:text.rindex("}")]

    def val(s):
        s = s.strip()
        if s in EST:
            return EST[s]
        m = re.fullmatch(r"INT32_C\((-?\d+)\)|(-?\d+)u?", s)
        if m is None:
            raise ValueError("cannot parse initialiser value %r" % s)
        return int(m.group(1) or m.group(2))

    out = {}
    for m in re.finditer(r"\.(\w+)\s*=\s*(\{[^}]*\}|[^,]+)", text):
        v = m.group(2).strip()
        out[m.group(1)] = [val(x) for x in v[1:-1].split(",") if x.strip()] if v.startswith("{") else val(v)
    return out


def params_of(name, tab, hw=ctable.HW, sym="OBS_TBL"):
    """Raw integer fields of design table `tab` (design.py's dict, _clean'ed) with hardware fields hw,
    checked against the initialiser ctable.table_c renders from the same inputs."""
    p = _from_design(tab, hw)
    c_init = parse_initialiser(ctable.table_c(name, sym, tab, hw))
    c_init.pop("revision", None)
    if set(c_init) != set(FIELDS) or any(c_init[k] != p[k] for k in FIELDS):
        bad = sorted(k for k in set(c_init) | set(FIELDS) if c_init.get(k) != p.get(k))
        raise AssertionError("image: %s differs from ctable's initialiser in %s" % (name, bad))
    return p


def params(name):
    """Raw integer fields of boot table NAME, checked against ctable's rendered initialiser."""
    if name not in NAMES:
        raise SystemExit("image: unknown table %r; choose from %s" % (name, ", ".join(NAMES)))
    return params_of(name, _tables()[name], sym=dict(ctable.TABLES)[name])


def build(name, revision=1, sets=None):
    """Complete image (header + payload) of boot table NAME."""
    return LAYOUT.build(params(name), revision, sets)


def decode(img):
    """(header dict, params dict) of an image, with Python struct only; raises ValueError if malformed."""
    return LAYOUT.decode(img)


def main(args):
    return image_writer.main(args, LAYOUT, NAMES, params)
