"""The committed estimator blocks tools/pd/fest/<channel>.json (each channel's pd_fest_params_t, the
table's fest block), written (or --check'ed) by running `pd_analysis fest-params` for each channel:
make_fest_params on the channel's nominal model (sim/pd/pd_fest_ref), quantised by the one quantiser
the golden tests use too (sim/pd/pd_fest_quant). The file is that output with the matrices given their
C shape (one row a line), so the block reads as fsw/pd/pd_fest.h declares it; design.py reads it.

Yaw's block has n_sec = 2 (the two-section cascade of fsw/pd/pd_fest.c); its line-logic constants are
compile-time in the port, like the tuning constants common to all channels.

    python -m tools.pd fest --analysis build/host/tools/pd/pd_analysis [--check]
"""
import json
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))

# The block's fields in the order of pd_fest.h (and of the wire), with their C shape; () a scalar.
NX, NR, CF, CK = 4, 2, 13, 11
FIELDS = [("n_sec", ()), ("n_reg", ()), ("inv_m_q30", ()), ("alpha_hp_q30", ()), ("f_hp_min_q32", ()),
          ("beta_kappa_q30", ()), ("kappa_hi_q30", ()), ("sigma_y_q40", ()),
          ("ad_m", (NX, NX)), ("ad_sh", (NX,)), ("bd_m", (NX,)), ("bd_sh", (NX,)), ("l_m", (NX,)), ("l_sh", (NX,)),
          ("dad_m", (NR, NX, NX)), ("dad_sh", (NR, NX)), ("dbd_m", (NR, NX)), ("dbd_sh", (NR, NX)),
          ("aa_b_q29", (3,)), ("aa_a_q29", (2,)), ("cinv_q30", (CF, CK))]
SHAPE = dict(FIELDS)


def path(channel):
    return os.path.join(HERE, "fest", "%s.json" % channel)


def size(shape):
    n = 1
    for d in shape:
        n *= d
    return n


def flatten(v):
    """A nested list as one flat list in row-major order (a scalar stays a scalar)."""
    if not isinstance(v, list):
        return v
    out = []
    for e in v:
        out += flatten(e) if isinstance(e, list) else [e]
    return out


def shaped(flat, shape):
    """A flat row-major list as nested lists of shape."""
    if len(shape) <= 1:
        return list(flat)
    step = size(shape[1:])
    return [shaped(flat[i * step:(i + 1) * step], shape[1:]) for i in range(shape[0])]


def check(block, where):
    """The block has every field of pd_fest.h, in order, each of its shape, all integers."""
    if list(block) != [f for f, _ in FIELDS]:
        raise ValueError("%s: fields %s, expected %s (pd_fest.h order)" % (where, list(block), [f for f, _ in FIELDS]))
    for f, shape in FIELDS:
        v = block[f]
        vals = flatten(v) if shape else [v]
        ok = isinstance(v, list) == bool(shape) and len(vals) == size(shape)
        ok = ok and (not shape or shaped(vals, shape) == v)
        ok = ok and all(isinstance(x, int) and not isinstance(x, bool) for x in vals)
        if not ok:
            raise ValueError("%s: field %s is not %d integers of shape %s" % (where, f, size(shape), shape))
    return block


def render_block(block):
    """The JSON text: one field a line, a matrix one row a line."""
    def rows(v, ind):
        if v and isinstance(v[0], list):
            return "[\n" + ",\n".join(ind + " " + rows(e, ind + " ") for e in v) + "\n" + ind + "]"
        return json.dumps(v)
    lines = [" %s: %s" % (json.dumps(f), rows(block[f], " ") if isinstance(block[f], list) else json.dumps(block[f]))
             for f, _ in FIELDS]
    return "{\n" + ",\n".join(lines) + "\n}\n"


def render(analysis, channel):
    out = subprocess.run([analysis, "fest-params", "--channel", channel], check=True, stdout=subprocess.PIPE,
                         universal_newlines=True).stdout
    flat = json.loads(out)
    block = {f: (shaped(flat[f], shape) if shape else flat[f]) for f, shape in FIELDS}
    if set(flat) != set(block):
        raise ValueError("pd_analysis fest-params --channel %s: fields %s, expected %s"
                         % (channel, sorted(flat), sorted(block)))
    return render_block(check(block, "pd_analysis fest-params --channel %s" % channel))


def load(channel):
    """The committed block of a channel: {field: int or nested lists of int} in pd_fest.h order."""
    p = path(channel)
    with open(p) as fh:
        return check(json.load(fh), os.path.relpath(p))


def main(analysis, check_only=False):
    from . import design   # here, not at the top: design imports this module to read the blocks
    bad = 0
    for ch in design.CHANNELS:
        p = path(ch)
        text = render(analysis, ch)
        old = open(p).read() if os.path.exists(p) else None
        if check_only:
            if old != text:
                print("%s: differs from `pd_analysis fest-params --channel %s`" % (os.path.relpath(p), ch))
                bad += 1
        elif old != text:
            os.makedirs(os.path.dirname(p), exist_ok=True)
            with open(p, "w") as fh:
                fh.write(text)
            print("wrote %s" % os.path.relpath(p))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], "--check" in sys.argv))
