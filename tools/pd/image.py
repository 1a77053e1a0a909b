"""Table images of the pd boot tables, packed with Python struct (an independent oracle for
the flight codec, fsw/pd/pd_table.c):

    python -m tools.pd image --table NAME [--revision N] [--set FIELD=INT ...] -o FILE
    python -m tools.pd image --all DIR

--set replaces a field's raw integer before the CRC (channel fields are prefixed: pitch_k2_nom_q22,
pitch_k2_node_q22[4]); hdr.* fields replace header words after it (for tests of the loader's header
and CRC checks). tools/table/image_writer.py does the work.
"""
from tools import iface
from tools.table import image_writer

from . import design

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
for _ch in design.CHANNELS:
    PAYLOAD += [("%s_%s" % (_ch, f), "I", 1, 0, K_MAX)
                for f in ("k0_q22", "k1_q22", "k2_nom_q22", "k2_cold_q22", "k2_min_q22", "k2_max_q22")]
    PAYLOAD += [("%s_k2_node_q22" % _ch, "I", design.N_NODES)]
_MOD = iface.mission("HOLD").iface
LAYOUT = image_writer.Layout(_MOD.table_id, _MOD.table_layout, PAYLOAD, 356, (), "fsw/pd/pd_table.c")
NAMES = [n for n, _, _ in design.TABLES]


def params(name):
    """Raw integer fields of a boot table (the campaign runner's table dispersions start here)."""
    return design.flat(name)


def build(name, revision=1, sets=None):
    """The image of boot table `name` with --set style overrides."""
    return LAYOUT.build(params(name), revision, sets)


def main(args):
    return image_writer.main(args, LAYOUT, NAMES, params)
