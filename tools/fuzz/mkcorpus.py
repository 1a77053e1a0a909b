#!/usr/bin/env python3
"""mkcorpus.py - seed corpus for tests/fuzz/fuzz_table_loader (spec 00 §8 "Fuzzing").

Writes valid and near-valid inputs in the harness's input format (tests/fuzz/README.md):
    u8 ctrl, u16 total_raw (LE), staging image bytes, then op bytes with operands.
The images come from tools/table/mktable.py (good, one defect each, random bit flips), so the
corpus starts at the deep states: complete uploads in order, reversed, re-sent, interleaved
with end/commit/scrub/abort/veto, and near misses (one chunk missing, overlap, wrong id,
changed total or revision, oversize). Plain python3, standard library only; deterministic.

Usage: mkcorpus.py OUT_DIR      (the build tree; nothing generated is committed)
"""
import argparse
import importlib.util
import os
import struct
import sys

sys.dont_write_bytecode = True   # build-time tool: leave no __pycache__ in the source tree
HERE = os.path.dirname(os.path.abspath(__file__))
_spec = importlib.util.spec_from_file_location(
    "mktable", os.path.join(HERE, "..", "table", "mktable.py"))
mktable = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(mktable)

# ctrl bits
FIX_HDR, FIX_CRC, TOTAL_TT, SWAP_ID, BUMP_VER = 1, 2, 4, 8, 16
# ops
END, COMMIT, SCRUB, ABORT, VETO = 3, 4, 5, 6, 6 | 8
UPLOAD = 7


def upload(step, backward=False, end_commit=True):
    op = UPLOAD | (8 if backward else 0) | (16 if end_commit else 0)
    return bytes([op, step - 1])


def chunk(off, n, flip=None, wrong_id=False, bump_total=False, bump_rev=False, raw_off=False):
    op = 0
    wide = n > 256
    if wide:
        op |= 0x40
    if flip is not None:
        op |= 0x20
    if wrong_id:
        op |= 0x10
    if bump_total or bump_rev:
        op |= 0x08
    if bump_rev or raw_off:
        op |= 0x80
    out = bytes([op]) + struct.pack("<H", off) + bytes([n - (45 if wide else 1)])
    if flip is not None:
        out += bytes([flip & 0xFF])
    return out


def chunks(total, step, order=None):
    offs = list(range(0, total, step))
    if order is not None:
        offs = [offs[i] for i in order(len(offs))]
    return b"".join(chunk(o, min(step, total - o)) for o in offs)


def entry(img, ctrl=0, total=None):
    total = len(img) if total is None else total
    return bytes([ctrl]) + struct.pack("<H", total) + img


def main(argv=None):
    ap = argparse.ArgumentParser(description="Seed corpus for tests/fuzz/fuzz_table_loader (deterministic).")
    ap.add_argument("out", metavar="OUT_DIR", help="corpus directory, created if missing; its *.bin are replaced "
                                                   "(the build tree: nothing generated is committed)")
    out = ap.parse_args(argv).out
    os.makedirs(out, exist_ok=True)
    for name in os.listdir(out):          # regenerate from scratch
        if name.endswith(".bin"):
            os.remove(os.path.join(out, name))
    lay = mktable.TEST_LAYOUT
    cases = dict(mktable.suite(lay))
    good = cases["good"]
    tail = bytes([END, COMMIT, SCRUB, 0x21])
    seeds = {}

    # every mktable image, uploaded whole in 13-byte chunks then end, commit, scrub (+ probe)
    for name, img in sorted(cases.items()):
        seeds["suite_" + name] = entry(img) + upload(13) + tail
    # good images, many chunkings and orders
    for step in (1, 7, 16, 40, 256):
        seeds["good_fwd_%d" % step] = entry(good) + upload(step) + tail
        seeds["good_rev_%d" % step] = entry(good) + upload(step, backward=True) + tail
    seeds["good_shuffled"] = (entry(good) + chunks(len(good), 5, lambda n: [3, 0, 7, 1, 5, 2, 6, 4][:n])
                              + tail)
    seeds["good_resend"] = entry(good) + chunk(0, 20) + chunk(10, 20) + chunk(20, 20) + tail
    seeds["good_twice"] = entry(good) + upload(8) + upload(9, backward=True) + tail
    seeds["good_busy"] = entry(good) + upload(40, end_commit=False) + chunk(0, 4) + END.to_bytes(1, "little") + bytes([COMMIT])
    seeds["good_abort"] = entry(good) + upload(40, end_commit=False) + bytes([ABORT, COMMIT]) + upload(40)
    seeds["good_veto"] = entry(good) + upload(40, end_commit=False) + bytes([VETO, 0x33, COMMIT]) + upload(20)
    seeds["good_fixed_hdr"] = entry(good, ctrl=FIX_HDR | FIX_CRC | TOTAL_TT) + upload(11) + tail
    seeds["good_max"] = entry(cases["good_max"]) + upload(40) + tail
    seeds["good_min"] = entry(cases["good_min"]) + upload(40) + tail
    # near misses
    seeds["miss_one_chunk"] = entry(good) + chunk(0, 16) + chunk(24, 16) + tail
    seeds["miss_overlap"] = entry(good) + chunk(0, 20) + chunk(10, 20, flip=3) + tail
    seeds["miss_wrong_id"] = entry(good) + chunk(0, 20) + chunk(20, 20, wrong_id=True) + tail
    seeds["miss_total"] = entry(good) + chunk(0, 20) + chunk(20, 20, bump_total=True) + tail
    seeds["miss_rev"] = entry(good) + chunk(0, 20) + chunk(20, 20, bump_rev=True) + tail
    seeds["miss_offset"] = entry(good) + chunk(0, 20) + chunk(30, 20, raw_off=True) + tail
    seeds["miss_n300"] = entry(good) + chunk(0, 300) + upload(40) + tail
    seeds["miss_null_chunks"] = (entry(good) + bytes([END | 0x20, COMMIT | 0x60, SCRUB | 0xA0, 1])
                                 + upload(40) + tail)
    seeds["miss_swap_id"] = entry(good, ctrl=FIX_HDR | FIX_CRC | SWAP_ID) + upload(40) + tail
    seeds["miss_bump_ver"] = entry(good, ctrl=FIX_HDR | FIX_CRC | BUMP_VER) + upload(40) + tail
    # sizes: empty, header only, longer payload, the 4096 cap and just past it
    seeds["size_hdr_only"] = entry(good[:16], ctrl=FIX_HDR | FIX_CRC) + upload(16) + tail
    big = mktable.image(bytes(range(256)) * 15 + bytes(4096 - 16 - 3840), lay["id"], lay["version"])
    seeds["size_cap"] = entry(big) + upload(256) + tail
    seeds["size_cap_plus1"] = entry(big + b"\0", ctrl=FIX_HDR | FIX_CRC) + upload(256) + tail
    seeds["size_small"] = entry(good[:9]) + upload(3) + tail
    seeds["size_empty"] = b""
    for name, data in sorted(seeds.items()):
        with open(os.path.join(out, name + ".bin"), "wb") as f:
            f.write(data)
    print("mkcorpus: %d seeds in %s" % (len(seeds), out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
