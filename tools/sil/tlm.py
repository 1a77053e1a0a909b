"""Decode the flight telemetry fsw_tlm_t carried in fsw_tlm_frame_t.tlm[0:tlm_len].

The layout (field order, types, Q formats, units) comes only from fsw/app/fsw_tlm_formats.json,
the same file the C encoder is tested against. Real value = raw / 2^q.

    from tools.sil import tlm
    d = tlm.decode(buf)        # raw integers, by field name
    s = tlm.scaled(d)          # real values (fields without q are returned unchanged, as int)
    a = tlm.decode_many(bufs)  # numpy arrays of raw values, one per field (fast path for long logs)
"""
import json
import os
import struct

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
FORMATS = os.path.join(ROOT, "fsw", "app", "fsw_tlm_formats.json")

_TYPES = {  # json type -> (struct code, numpy code)
    "i8": ("b", "i1"), "u8": ("B", "u1"), "i16": ("h", "i2"), "u16": ("H", "u2"),
    "i32": ("i", "i4"), "u32": ("I", "u4"), "i64": ("q", "i8"), "u64": ("Q", "u8"),
}


class TlmError(ValueError):
    """Telemetry buffer does not match fsw_tlm_formats.json."""


class Layout(object):
    def __init__(self, path=FORMATS):
        with open(path) as fh:
            spec = json.load(fh)
        if spec.get("byte_order", "little") != "little":
            raise TlmError("%s: byte_order %r, expected 'little'" % (path, spec.get("byte_order")))
        self.path = path
        self.layout_version = spec.get("layout_version")
        self.nbytes = int(spec["bytes"])
        self.fields = spec["fields"]
        self.names = [f["name"] for f in self.fields]
        self.q = {f["name"]: f["q"] for f in self.fields if "q" in f}
        self.unit = {f["name"]: f.get("unit", "") for f in self.fields}
        try:
            codes = [_TYPES[f["type"]] for f in self.fields]
        except KeyError as e:
            raise TlmError("%s: unknown field type %s" % (path, e))
        self.struct = struct.Struct("<" + "".join(c[0] for c in codes))
        self.dtype = np.dtype([(f["name"], "<" + c[1]) for f, c in zip(self.fields, codes)])
        if self.struct.size != self.nbytes or self.dtype.itemsize != self.nbytes:
            raise TlmError("%s: fields pack to %d bytes but \"bytes\" is %d"
                           % (path, self.struct.size, self.nbytes))

    def decode(self, buf):
        buf = bytes(buf)
        if len(buf) != self.nbytes:
            raise TlmError("fsw_tlm_t buffer is %d bytes, %s says %d (layout_version %s)"
                           % (len(buf), os.path.relpath(self.path, ROOT), self.nbytes, self.layout_version))
        return dict(zip(self.names, self.struct.unpack(buf)))

    def scaled(self, d):
        out = {}
        for k, v in d.items():
            q = self.q.get(k)
            out[k] = (v / float(1 << q) if q >= 0 else v * float(1 << -q)) if q is not None else v
        return out

    def decode_many(self, bufs):
        """bufs: iterable of bytes, each exactly nbytes long -> dict of numpy raw arrays."""
        blob = bytearray()
        for i, b in enumerate(bufs):
            if len(b) != self.nbytes:
                raise TlmError("telemetry message %d: fsw_tlm_t buffer is %d bytes, expected %d"
                               % (i, len(b), self.nbytes))
            blob += b
        arr = np.frombuffer(bytes(blob), dtype=self.dtype)
        return {n: arr[n].copy() for n in self.names}

    def scaled_many(self, raw):
        return {k: (v.astype(np.float64) * 2.0 ** -self.q[k]) if k in self.q else v for k, v in raw.items()}


_LAYOUT = None


def layout():
    global _LAYOUT
    if _LAYOUT is None:
        _LAYOUT = Layout()
    return _LAYOUT


def decode(buf):
    """bytes -> {field: raw int}; raises TlmError unless len(buf) equals the JSON "bytes"."""
    return layout().decode(buf)


def scaled(d):
    """{field: raw} -> {field: real value} (raw / 2^q; fields without q unchanged)."""
    return layout().scaled(d)


def decode_many(bufs):
    return layout().decode_many(bufs)
