#!/usr/bin/env python3
"""mkcorpus_link.py - seed corpus for tests/fuzz/fuzz_link_decoder and fuzz_pil_board (spec 00 §8 "Fuzzing").

Byte streams of spec 00 §6.1 frames built by the independent oracle of tests/app/gen_link_vectors.py
(Python struct, zlib.crc32, COBS from the paper): every packet type, empty and maximal payloads,
payloads with zeros and with full 254-byte COBS blocks, frames back to back, frames behind noise,
a leading delimiter, and corrupted copies (a bit flip, a truncation, a wrong version or length).
Valid CRCs are what random bytes never reach; these seeds start the fuzzer past them.

Usage: mkcorpus_link.py OUT_DIR      (the build tree; nothing generated is committed)
"""
import os
import random
import struct
import sys
import zlib

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tests", "app"))
from gen_link_vectors import cobs, frame  # noqa: E402


def body_frame(ver, typ, seq, len_field, payload):
    body = struct.pack("<BBHH", ver, typ, seq, len_field) + payload
    return cobs(body + struct.pack("<I", zlib.crc32(body) & 0xFFFFFFFF)) + b"\x00"


def main():
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    rng = random.Random(20261205)
    seeds = {}
    for t in range(1, 15):
        seeds["type%02d" % t] = frame(t, rng.randrange(65536), bytes(rng.randrange(256) for _ in range(rng.randrange(40))))
    seeds["empty_payload"] = frame(8, 0, b"")
    seeds["max_payload"] = frame(4, 1, bytes(rng.randrange(1, 256) for _ in range(512)))
    seeds["max_payload_zeros"] = frame(4, 2, bytes(512))
    seeds["full_block_end"] = frame(3, 0x0707, bytes([1]) * 250)
    seeds["back_to_back"] = b"".join(frame(2, k, struct.pack("<I", k)) for k in range(8))
    seeds["leading_delimiter"] = b"\x00" + frame(9, 3, b"pong")
    seeds["noise_then_frame"] = bytes(rng.randrange(1, 256) for _ in range(37)) + b"\x00" + frame(2, 5, b"abc")
    f = bytearray(frame(2, 6, b"flip me"))
    f[4] ^= 0x20
    seeds["bit_flip"] = bytes(f) + frame(2, 7, b"next")
    seeds["truncated"] = frame(4, 8, bytes(range(1, 60)))[:30] + b"\x00" + frame(2, 9, b"after")
    seeds["wrong_version"] = body_frame(2, 2, 1, 3, b"abc")
    seeds["wrong_len"] = body_frame(1, 2, 1, 4, b"abc")
    seeds["type_zero"] = body_frame(1, 0, 1, 3, b"abc")
    seeds["oversize"] = bytes([0x42]) * 600 + b"\x00" + frame(2, 10, b"ok")
    # PIL session seeds (fsw/app/fsw_pil.h layouts): a boot without a table, then flight steps,
    # a duplicate and an old frame, a staged boot image's first chunk, an upload chunk, stats, END.
    boot = struct.pack("<IIHHIII", 0, 20000, 50, 0, 2, 0, 0)

    def sensor(k, counts=(1000, -2000), mode=0xFFFFFFFF, tc=0):
        c = list(counts) + [0] * (16 - len(counts))
        return struct.pack("<qqI16i16BIIII8i", k * 20000, k, len(counts), *c, *([0] * 16), mode, 0, 0, tc, *([0] * 8))
    chunk = struct.pack("<HHIII", 0x0B5E, 40, 1, 300, 0) + bytes(range(1, 41))
    seeds["pil_boot_steps"] = frame(12, 1, boot) + b"".join(frame(2, k, sensor(k)) for k in range(1, 6))
    seeds["pil_dup_stale"] = (frame(12, 1, boot) + frame(2, 3, sensor(3)) + frame(2, 3, sensor(3)) +
                              frame(2, 2, sensor(2)) + frame(2, 4, sensor(4, mode=1)))
    seeds["pil_stage_chunk"] = frame(5, 9, chunk) + frame(12, 10, boot)
    seeds["pil_upload_stats_end"] = (frame(12, 1, boot) + frame(5, 2, chunk) + frame(10, 3, b"") +
                                     frame(8, 4, b"ping") + frame(1, 5, b"") + frame(7, 6, struct.pack("<I", 1)))
    for name, data in seeds.items():
        with open(os.path.join(out, name), "wb") as fh:
            fh.write(data)


if __name__ == "__main__":
    main()
