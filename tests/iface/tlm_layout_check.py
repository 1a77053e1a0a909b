"""The Python side of the telemetry layout test (CTest golden_tlm_layout): decodes each
OUT_DIR/<MISSION>.bin that test_tlm_layout wrote with tools.iface (the decoder the reports and
tools/sil use) and compares every field by name with the pattern tests/iface/tlm_pattern.h wrote.

    python tests/iface/tlm_layout_check.py OUT_DIR
"""
import argparse
import os
import sys

from tools import iface

M64 = (1 << 64) - 1


def pattern(i, typ):
    z = ((i + 1) * 0x9E3779B97F4A7C15) & M64
    z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & M64
    z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & M64
    z ^= z >> 31
    bits = {"u8": 8, "u16": 16, "u32": 32, "i32": 32, "i64": 64}[typ]
    v = z & ((1 << bits) - 1)
    if typ.startswith("i") and v >= 1 << (bits - 1):
        v -= 1 << bits
    return v


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out_dir")
    a = ap.parse_args(argv)
    files = sorted(f for f in os.listdir(a.out_dir) if f.endswith(".bin"))
    if not files:
        print("no layout files in %s" % a.out_dir)
        return 1
    bad = 0
    for fn in files:
        m = iface.mission(fn[:-4])
        with open(os.path.join(a.out_dir, fn), "rb") as fh:
            d = m.layout.decode(fh.read())
        for i, f in enumerate(m.layout.fields):
            want = pattern(i, f.type)
            if d[f.name] != want:
                print("%s field %d %s (offset %d): decoded %d, written %d"
                      % (m.name, i, f.name, m.layout.offset[f.name], d[f.name], want))
                bad += 1
        print("%s: %d fields, %d bytes, layout 0x%08X: %s" % (m.name, len(m.layout.fields), m.layout.nbytes,
                                                              m.layout_version, "every field decoded" if not bad else "MISMATCH"))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
