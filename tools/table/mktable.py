#!/usr/bin/env python3
"""mktable.py - build parameter-table images (spec 00 §3.2), independently of fsw/.

Image = 16-byte little-endian header + payload:
    u16 table_id, u16 layout_version, u32 length (payload bytes), u32 revision,
    u32 crc32 of the payload (zlib.crc32: the zlib/IEEE CRC the flight code uses)

The payload is packed field by field with struct ('<' = little-endian, no padding), never from
a C struct. This file shares no code with fsw/app, so it is an independent oracle for the
loader: `verdict()` re-implements the validation order of spec 00 §3.2 and predicts the
reason code the flight loader must report.

Usage:
    mktable.py --layout test7e57 --suite DIR
        writes DIR/<case>.bin and DIR/manifest.txt ("<case> <REASON> <detail>" per line;
        REASON is the suffix of an FSW_TBL_R_* code, OK for an accepted image)
    mktable.py --layout test7e57 [--set NAME=VALUE]... [--revision N] -o FILE
        writes one image (field values default to the layout's nominal values)
Only the Python standard library is used.
"""
import argparse
import os
import random
import struct
import sys
import zlib

HDR = struct.Struct("<HHIII")
HDR_BYTES = HDR.size  # 16
CAP_BYTES = 4096      # FSW_TABLE_CAP_BYTES

# Wire formats of the limits descriptor types.
FMT = {"u8": "B", "u16": "H", "u32": "I", "i32": "i"}
WIRE_RANGE = {"u8": (0, 0xFF), "u16": (0, 0xFFFF), "u32": (0, 0xFFFFFFFF),
              "i32": (-(1 << 31), (1 << 31) - 1)}

# Test table 0x7E57 layout 3, the same layout as tests/app/tbl_test_desc.h (kept in step by
# hand on purpose: the two are meant to be written independently).
# (name, type, offset, min, max, nominal)
TEST_LAYOUT = {
    "id": 0x7E57,
    "version": 3,
    "fields": [
        ("mode", "u8", 0, 0, 3, 2),
        ("enable", "u8", 1, 0, 1, 1),
        ("period_ms", "u16", 2, 1, 1000, 200),
        ("stale_max", "u32", 4, 1, 1000, 16),
        ("gain_q16", "i32", 8, -262144, 262144, -100),
        ("quant_q16", "i32", 12, 0, 1000, 64),
        ("hyst_q16", "i32", 16, 0, 100000, 1000),
        ("max_count", "u32", 20, 10, 4000000000, 1234),
    ],
    # value[a] + margin <= value[b]
    "rels": [("quant_q16", "hyst_q16", 2), ("stale_max", "max_count", 1)],
}
LAYOUTS = {"test7e57": TEST_LAYOUT}


def payload_len(layout):
    return max(off + struct.calcsize("<" + FMT[t]) for _, t, off, _, _, _ in layout["fields"])


def nominal(layout):
    return {f[0]: f[5] for f in layout["fields"]}


def pack_payload(layout, values):
    buf = bytearray(payload_len(layout))
    for name, t, off, _, _, _ in layout["fields"]:
        struct.pack_into("<" + FMT[t], buf, off, values[name])
    return bytes(buf)


def image(payload, table_id, version, revision=1, length=None, crc=None):
    """Header + payload; length and crc may be forced to wrong values."""
    length = len(payload) if length is None else length
    crc = zlib.crc32(payload) & 0xFFFFFFFF if crc is None else crc
    return HDR.pack(table_id, version, length, revision, crc) + payload


def verdict(layout, img):
    """(REASON, detail) the loader must report for a complete upload of img (spec order)."""
    if len(img) < HDR_BYTES or len(img) > CAP_BYTES:
        return ("OVERSIZE", 0)
    tid, ver, length, _rev, crc = HDR.unpack_from(img, 0)
    payload = img[HDR_BYTES:]
    if length != len(payload):
        return ("DECODE", 0)
    if zlib.crc32(payload) & 0xFFFFFFFF != crc:
        return ("CRC", 0)
    if tid != layout["id"]:
        return ("ID", 0)
    if ver != layout["version"]:
        return ("VERSION", 0)
    if length != payload_len(layout):
        return ("LENGTH", 0)
    vals = {}
    for i, (name, t, off, lo, hi, _) in enumerate(layout["fields"]):
        (v,) = struct.unpack_from("<" + FMT[t], payload, off)
        vals[name] = v
        if v < lo:
            return ("RANGE_LO", i)
        if v > hi:
            return ("RANGE_HI", i)
    for i, (a, b, margin) in enumerate(layout["rels"]):
        if vals[a] + margin > vals[b]:
            return ("INVARIANT", i)
    return ("OK", 0)


def suite(layout):
    """Named test images: good ones, one defect each, and seeded random corruptions."""
    tid, ver = layout["id"], layout["version"]
    nom = nominal(layout)
    good = pack_payload(layout, nom)
    cases = [("good", image(good, tid, ver, revision=2))]
    lows = {f[0]: f[3] for f in layout["fields"]}
    highs = {f[0]: f[4] for f in layout["fields"]}
    cases.append(("good_max", image(pack_payload(layout, highs), tid, ver, revision=3)))
    lo_ok = dict(lows)
    for a, b, m in layout["rels"]:          # raise the right-hand sides until relations hold
        lo_ok[b] = max(lo_ok[b], lo_ok[a] + m)
    cases.append(("good_min", image(pack_payload(layout, lo_ok), tid, ver, revision=4)))
    flipped = bytearray(good)
    flipped[3] ^= 0x20
    cases.append(("bad_crc_payload", image(good, tid, ver, crc=zlib.crc32(good) ^ 1)))
    cases.append(("bad_crc_flip", image(good, tid, ver)[:HDR_BYTES] + bytes(flipped)))
    cases.append(("wrong_id", image(good, tid ^ 0x0001, ver)))
    cases.append(("wrong_version", image(good, tid, ver + 1)))
    cases.append(("length_field", image(good, tid, ver, length=len(good) - 1)))
    cases.append(("length_layout", image(good + b"\0\0\0\0", tid, ver)))
    cases.append(("truncated", image(good, tid, ver)[:HDR_BYTES - 6]))
    for name, t, _off, lo, hi, _ in layout["fields"]:
        wlo, whi = WIRE_RANGE[t]
        for tag, v in (("lo", lo - 1), ("hi", hi + 1), ("wlo", wlo), ("whi", whi)):
            if wlo <= v <= whi:
                vals = dict(nom)
                vals[name] = v
                cases.append(("range_%s_%s" % (name, tag),
                              image(pack_payload(layout, vals), tid, ver)))
    hi_of = {f[0]: f[4] for f in layout["fields"]}
    for i, (a, b, m) in enumerate(layout["rels"]):
        vals = dict(nom)                    # miss the relation by one LSB, ranges kept
        vals[a] = min(hi_of[a], vals[b] - m + 1)
        vals[b] = vals[a] + m - 1
        cases.append(("invariant_%d" % i, image(pack_payload(layout, vals), tid, ver)))
    rng = random.Random(0x7AB1E)
    base = bytearray(image(good, tid, ver))
    for k in range(24):
        b = bytearray(base)
        bit = rng.randrange(len(b) * 8)
        b[bit // 8] ^= 1 << (bit % 8)
        cases.append(("flip_%02d_bit%d" % (k, bit), bytes(b)))
    return cases


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--layout", required=True, choices=sorted(LAYOUTS))
    ap.add_argument("--suite", metavar="DIR", help="write the test suite into DIR")
    ap.add_argument("-o", "--out", help="write one image to this file")
    ap.add_argument("--set", action="append", default=[], metavar="NAME=VALUE")
    ap.add_argument("--revision", type=lambda s: int(s, 0), default=1)
    args = ap.parse_args(argv)
    layout = LAYOUTS[args.layout]
    if args.suite:
        os.makedirs(args.suite, exist_ok=True)
        lines = []
        for name, img in suite(layout):
            with open(os.path.join(args.suite, name + ".bin"), "wb") as f:
                f.write(img)
            reason, detail = verdict(layout, img)
            lines.append("%s %s %d\n" % (name, reason, detail))
        with open(os.path.join(args.suite, "manifest.txt"), "w") as f:
            f.writelines(lines)
        print("mktable: %d images in %s" % (len(lines), args.suite))
        return 0
    if not args.out:
        ap.error("give --suite DIR or -o FILE")
    vals = nominal(layout)
    for s in args.set:
        k, _, v = s.partition("=")
        if k not in vals:
            ap.error("unknown field %s" % k)
        vals[k] = int(v, 0)
    img = image(pack_payload(layout, vals), layout["id"], layout["version"], args.revision)
    with open(args.out, "wb") as f:
        f.write(img)
    print("mktable: %s: %d bytes, verdict %s" % (args.out, len(img), verdict(layout, img)[0]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
