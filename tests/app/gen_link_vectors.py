#!/usr/bin/env python3
"""Independent oracle for tests/app/test_fsw_link.c: the spec 00 §6.1 frames built with Python's
struct, zlib.crc32 and a COBS encoder written from the COBS paper (Cheshire & Baker 1999), not
from fsw/app/fsw_link.c. Prints the C arrays the test embeds:
    python3 tests/app/gen_link_vectors.py
"""
import struct
import zlib


def cobs(data: bytes) -> bytes:
    out = bytearray()
    block = bytearray()
    for b in data:
        if b == 0:
            out.append(len(block) + 1)
            out += block
            block = bytearray()
        else:
            block.append(b)
            if len(block) == 254:
                out.append(255)
                out += block
                block = bytearray()
    out.append(len(block) + 1)   # the final block, also after a full one
    out += block
    return bytes(out)


def frame(typ: int, seq: int, payload: bytes) -> bytes:
    body = struct.pack("<BBHH", 1, typ, seq, len(payload)) + payload
    body += struct.pack("<I", zlib.crc32(body) & 0xFFFFFFFF)
    return cobs(body) + b"\x00"


VECTORS = [
    ("sensor_with_zero", 2, 0x1234, b"hello\x00world"),
    ("ping_empty", 8, 0, b""),
    ("tlm_300_no_zero", 4, 0xFFFF, bytes((i % 255) + 1 for i in range(300))),
    # after len's zero high byte, 250 payload bytes and a CRC without zeros: exactly one full block
    # of 254, so the encoding ends with a 0xFF block and the closing empty block (0x01)
    ("cmd_full_block_end", 3, 0x0707, bytes([1]) * 250),
]

if __name__ == "__main__":
    for name, t, s, p in VECTORS:
        w = frame(t, s, p)
        print("static const uint8_t V_%s[%d] = {" % (name.upper(), len(w)))
        for i in range(0, len(w), 16):
            print("    " + ", ".join("0x%02X" % b for b in w[i:i + 16]) + ",")
        print("};")
