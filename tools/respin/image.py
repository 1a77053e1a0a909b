"""Table images of the respin boot tables, packed with Python struct (an independent oracle for
the flight codec, fsw/respin/rsp_table.c):

    python -m tools.respin image --table NAME [--revision N] [--set FIELD=INT ...] -o FILE
    python -m tools.respin image --all DIR

--set replaces a field's raw integer before the CRC; hdr.* fields replace header words after
it (for tests of the loader's header and CRC checks). tools/table/image_writer.py does the work.
"""
from tools import iface
from tools.table import image_writer

from . import design

I32MAX = 2 ** 31 - 1
U32MAX = 2 ** 32 - 1
Q30 = 1 << 30
# (field, struct code, count, lo, hi) in wire order, with the flight loader's limits (RSP_LIMS)
PAYLOAD = [("period_us", "I", 1, 1000, 1000000), ("mode", "I", 1, 0, 1), ("act_kind", "I", 1, 0, 1),
           ("j_q19", "i", 3, 1, I32MAX), ("iw_q30", "i", 1, 1, I32MAX), ("eps1_q30", "i", 1, 1, Q30),
           ("eps2_q30", "i", 1, 1, Q30), ("heps_q30", "i", 1, 1, Q30), ("m_q24", "i", 1, 1, I32MAX),
           ("k_q30", "i", 1, 1, I32MAX), ("mstar_q24", "i", 1, 1, I32MAX), ("mmax_q24", "i", 1, 1, I32MAX),
           ("hlim_q20", "i", 1, 1, I32MAX), ("inv_ts_q16", "i", 1, 1, I32MAX), ("gguard_q20", "i", 1, 1, I32MAX),
           ("gmin_q20", "i", 1, 1, I32MAX), ("n_g0", "I", 1, 1, 1024), ("gyro_max_cnt", "i", 1, 1, 1 << 22),
           ("whl_max_cnt", "i", 1, 1, I32MAX), ("n_fault", "I", 1, 1, 65535), ("n_stale", "I", 1, 1, 65535),
           ("n_whl_est", "I", 1, 1, 65535), ("outlier_q20", "i", 1, 1, I32MAX),
           ("outlier_rel_q16", "I", 1, 1, 65536), ("drift_q30", "i", 1, 1, Q30), ("drift_sh", "I", 1, 1, 20),
           ("ealarm_q32", "I", 1, 1, U32MAX), ("done_xi_q30", "i", 1, 1, Q30), ("done_h_q20", "i", 1, 1, I32MAX),
           ("done_ticks", "I", 1, 1, 1 << 24), ("gfilt_alpha_q30", "i", 1, 0, 1 << 29),
           ("hg_q20", "i", 1, 1, I32MAX), ("lambda_q28", "i", 1, 1, 1 << 28), ("umax_cnt", "i", 1, 1, 32767),
           ("ms_sing_q28", "i", 1, 1, 1 << 30), ("rotor_nom_cnt", "i", 1, 1, I32MAX),
           ("rotor_tol_q16", "I", 1, 1, 65536)]
# value[a] + margin <= value[b] (RSP_RELS)
RELS = [("eps1_q30", "eps2_q30", 1), ("gmin_q20", "gguard_q20", 0)]
_MOD = iface.mission("RESPIN").iface
LAYOUT = image_writer.Layout(_MOD.table_id, _MOD.table_layout, PAYLOAD, 156, RELS, "fsw/respin/rsp_table.c")
NAMES = [n for n, _, _ in design.TABLES]


def params(name):
    """Raw integer fields of a boot table (the campaign runner's table dispersions start here)."""
    return design.table(name)


def build(name, revision=1, sets=None):
    """The image of boot table `name` with --set style overrides."""
    return LAYOUT.build(params(name), revision, sets)


def main(args):
    return image_writer.main(args, LAYOUT, NAMES, params)
