"""Table images of the relay boot tables, packed with Python struct (an independent oracle for
the flight codec, fsw/relay/rly_table.c):

    python -m tools.relay image --table NAME [--revision N] [--set FIELD=INT ...] -o FILE
    python -m tools.relay image --all DIR

--set replaces a field's raw integer before the CRC; hdr.* fields replace header words after
it (for tests of the loader's header and CRC checks). tools/table/image_writer.py does the work.
"""
from tools import iface
from tools.table import image_writer

from . import design

I32MAX = 2 ** 31 - 1
U32MAX = 2 ** 32 - 1
XF = 1 << 23
CM = 1 << 29
AM = 1 << 30
# (field, struct code, count, lo, hi) in wire order, with the flight loader's limits (RLY_LIMS)
PAYLOAD = [("period_us", "I", 1, 1000, 1000000), ("x_max_q24", "i", 1, 1, XF), ("eps_q24", "i", 1, 1, XF),
           ("gamma_q24", "i", 1, 2, XF), ("tau_max_ticks", "I", 1, 1, 1 << 24), ("win_ticks", "I", 1, 1, 1 << 21),
           ("seed", "I", 1, 1, U32MAX), ("env_alarm_q40", "I", 1, 1, U32MAX), ("lost_ticks", "H", 1, 1, 65535),
           ("tmin_windows", "H", 1, 1, 65535), ("dk_q16", "H", 1, 1, 65535), ("kt0_q16", "H", 1, 1, 65535),
           ("kt_min_q16", "H", 1, 1, 65535), ("kt_max_q16", "H", 1, 1, 65535), ("n_modes", "B", 1, 0, 4),
           ("adapt_mode", "B", 1, 0, 3), ("delta0_num", "B", 1, 1, 255), ("delta0_den", "B", 1, 1, 255),
           ("n_small", "B", 1, 1, 255), ("n_ignore", "B", 1, 0, 255), ("count_before_tmin", "B", 1, 0, 1),
           ("learn_after_tmin", "B", 1, 0, 1), ("gate_dk", "B", 1, 1, 255), ("probe_settle", "B", 1, 0, 15),
           ("cliff_num", "B", 1, 1, 255), ("cliff_den", "B", 1, 1, 255), ("retreat_dk", "B", 1, 0, 255),
           ("unfreeze_num", "B", 1, 1, 255), ("unfreeze_den", "B", 1, 1, 255), ("unfreeze_windows", "B", 1, 1, 255),
           ("dphi_lo", "I", 4, 0, U32MAX), ("dphi_hi", "I", 4, 0, (1 << 30) - 1), ("f_lo", "I", 4, 0, U32MAX),
           ("f_hi", "I", 4, 0, U32MAX), ("cu_q40", "i", 4, -CM, CM), ("ce_q40", "i", 4, -CM, CM),
           ("q0_q40", "i", 4, -AM, AM), ("p0_q40", "i", 4, -AM, AM)]
# value[a] + margin <= value[b] (RLY_RELS)
RELS = [("gamma_q24", "eps_q24", 1), ("eps_q24", "x_max_q24", 0), ("kt_min_q16", "kt0_q16", 0),
        ("kt0_q16", "kt_max_q16", 0)]
_MOD = iface.mission("RELAY").iface
LAYOUT = image_writer.Layout(_MOD.table_id, _MOD.table_layout, PAYLOAD, 188, RELS, "fsw/relay/rly_table.c")
NAMES = [n for n, _, _ in design.TABLES]


def params(name):
    """Raw integer fields of a boot table (the campaign runner's table dispersions start here)."""
    return design.table(name)


def build(name, revision=1, sets=None):
    """The image of boot table `name` with --set style overrides."""
    return LAYOUT.build(params(name), revision, sets)


def main(args):
    return image_writer.main(args, LAYOUT, NAMES, params)
