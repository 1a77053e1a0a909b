"""Table images of the pd boot tables, packed with Python struct (an independent oracle for
the flight codec, fsw/pd/pd_table.c):

    python -m tools.pd image --table NAME [--revision N] [--set FIELD=INT ...] -o FILE
    python -m tools.pd image --all DIR

--set replaces a field's raw integer before the CRC (channel fields are prefixed: pitch_k2_nom_q22,
pitch_k2_node_q22[4]; the estimator block's pitch_fest_n_sec, pitch_fest_reserved0, pitch_fest_ad_m[5],
its matrices flattened row-major); hdr.* fields replace header words after it (for tests of the
loader's header and CRC checks). tools/table/image_writer.py does the work.
"""
from tools import iface
from tools.table import image_writer

from . import design
from . import fest

U32MAX = 2 ** 32 - 1
U31 = 2 ** 31 - 1
K_MAX = 1023 << 22
PI_Q24 = 52707179
# (field, struct code, count, lo, hi) in wire order, with the flight loader's limits (PD_LIMS)
PAYLOAD = [("period_us", "I", 1, 1000, 1000000), ("inv_ty_q22", "I", 1, 1, U32MAX), ("law", "B", 1, 0, 2),
           ("src", "B", 1, 0, 2), ("sched_law", "B", 1, 0, 2), ("ch_mask", "B", 1, 0, 7), ("n_y", "B", 1, 2, 64),
           ("n_bad_max", "B", 1, 0, 63), ("n_div", "H", 1, 1, 64), ("n_hold", "H", 1, 0, 1000),
           ("n_frozen", "H", 1, 2, 65535), ("y_lim_q30", "i", 1, 1, 1 << 29), ("dy_max_q30", "i", 1, 1, 1 << 24),
           ("m_max_q28", "i", 1, 1, 1 << 30), ("m_frozen_q28", "i", 1, 0, 1 << 30),
           ("beta_warn_q24", "i", 1, 1, PI_Q24), ("beta_lim_q24", "i", 1, 1, PI_Q24), ("f0_q32", "I", 1, 0, U31),
           ("df_inv_q16", "I", 1, 1, U31), ("f_ground_q32", "I", 1, 0, U31)]
# the estimator block after n_sec, n_reg and the reserved bytes: (field, struct code) in wire order
FEST_CODES = [("inv_m_q30", "I"), ("alpha_hp_q30", "I"), ("f_hp_min_q32", "I"), ("beta_kappa_q30", "I"),
              ("kappa_hi_q30", "I"), ("sigma_y_q40", "I"), ("ad_m", "i"), ("ad_sh", "B"), ("bd_m", "i"),
              ("bd_sh", "B"), ("l_m", "i"), ("l_sh", "B"), ("dad_m", "i"), ("dad_sh", "B"), ("dbd_m", "i"),
              ("dbd_sh", "B"), ("aa_b_q29", "i"), ("aa_a_q29", "i"), ("cinv_q30", "I")]
for _ch in design.CHANNELS:
    PAYLOAD += [("%s_%s" % (_ch, f), "I", 1, 0, K_MAX)
                for f in ("k0_q22", "k1_q22", "k2_nom_q22", "k2_cold_q22", "k2_min_q22", "k2_max_q22")]
    PAYLOAD += [("%s_k2_node_q22" % _ch, "I", design.N_NODES)]
    # the estimator block (pd_fest_params_t, pd_table.c): n_sec and n_reg have loader limits, the two
    # reserved bytes must be 0 (the decoder refuses anything else), the rest pd_fest_check judges
    PAYLOAD += [("%s_fest_n_sec" % _ch, "B", 1, 1, 2), ("%s_fest_n_reg" % _ch, "B", 1, 0, 2),
                ("%s_fest_reserved0" % _ch, "B", 1), ("%s_fest_reserved1" % _ch, "B", 1)]
    PAYLOAD += [("%s_fest_%s" % (_ch, f), c, fest.size(fest.SHAPE[f])) for f, c in FEST_CODES]
FEST_BYTES = 904          # one channel's estimator block on the wire
PAYLOAD_BYTES = 356 + 3 * FEST_BYTES
_MOD = iface.mission("HOLD").iface
LAYOUT = image_writer.Layout(_MOD.table_id, _MOD.table_layout, PAYLOAD, PAYLOAD_BYTES, (), "fsw/pd/pd_table.c")
NAMES = [n for n, _, _ in design.TABLES]


def params(name):
    """Raw integer fields of a boot table (the campaign runner's table dispersions start here)."""
    return design.flat(name)


def build(name, revision=1, sets=None):
    """The image of boot table `name` with --set style overrides."""
    return LAYOUT.build(params(name), revision, sets)


def main(args):
    return image_writer.main(args, LAYOUT, NAMES, params)
