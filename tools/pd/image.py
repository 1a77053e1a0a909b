"""Table images of the pd boot tables, packed with Python struct (an independent oracle for
the flight codec, fsw/pd/pd_table.c):

    python -m tools.pd image --table NAME [--revision N] [--set FIELD=INT ...] -o FILE
    python -m tools.pd image --all DIR

--set replaces a field's raw integer before the CRC; hdr.* fields replace header words after
it (for tests of the loader's header and CRC checks). tools/table/image_writer.py does the work.
"""
from tools import iface
from tools.table import image_writer

from . import design

I32MAX = 2 ** 31 - 1
# (field, struct code, count, lo, hi) in wire order, with the flight loader's limits (PD_LIMS)
PAYLOAD = [("period_us", "I", 1, 1000, 1000000), ("rate_max_cnt", "i", 1, 1, I32MAX),
           ("gain_q16", "i", 1, 1, 1 << 24), ("u_max_cnt", "i", 1, 1, 1 << 24), ("n_sat", "H", 1, 1, 65535),
           ("spare", "H", 1, 0, 0)]
_MOD = iface.mission("HOLD").iface
LAYOUT = image_writer.Layout(_MOD.table_id, _MOD.table_layout, PAYLOAD, 20, (), "fsw/pd/pd_table.c")
NAMES = [n for n, _, _ in design.TABLES]


def params(name):
    """Raw integer fields of a boot table (the campaign runner's table dispersions start here)."""
    return design.table(name)


def build(name, revision=1, sets=None):
    """The image of boot table `name` with --set style overrides."""
    return LAYOUT.build(params(name), revision, sets)


def main(args):
    return image_writer.main(args, LAYOUT, NAMES, params)
