"""Shared machinery of the module table-image writers (tools/observer/image.py, tools/impulse/image.py).

An image is the spec 00 §3.2 header + payload:
    header  <HHIII  table_id, layout_version, payload length, revision, zlib.crc32(payload)
    payload little-endian, field by field, in the layout's order (a list of
            (field, struct code, count) entries)

Everything here uses Python struct and zlib only, never the C encoder, so each writer stays an
independent oracle for the flight decoder. A writer supplies its layout, table id and version and
a `params(name)` function giving the boot table's raw integers; this module does the `--set`
overrides (`FIELD=INT`, `FIELD[i]=INT`, header pseudo-fields `hdr.table_id`,
`hdr.layout_version`, `hdr.length`, `hdr.revision`, `hdr.crc` applied after the CRC), packing,
decoding and the command line.
"""
import os
import re
import struct
import zlib

HDR = struct.Struct("<HHIII")
HDR_FIELDS = ("table_id", "layout_version", "length", "revision", "crc")


def q_rat(num, den, q):
    """FX_Q_RAT(num, den, q) of fsw/fx/fx.h: num/den in qN, rounded half away from zero."""
    sign = -1 if num < 0 else 1
    return sign * ((abs(num) * (1 << q) + den // 2) // den)


class Layout(object):
    """payload: (field, struct code, count) or (field, struct code, count, lo, hi) entries in wire
    order; lo/hi are the flight loader's limits for every entry of the field (its limits
    descriptor), absent where the loader range-checks nothing. rels: (a, b, margin) meaning
    value[a] + margin <= value[b] (the descriptor's relations). source names the C file they mirror."""

    def __init__(self, table_id, layout_version, payload, payload_bytes, rels=(), source=""):
        self.table_id = table_id
        self.layout_version = layout_version
        self.payload = [tuple(e[:3]) for e in payload]
        self.limits = {e[0]: (e[3], e[4]) for e in payload if len(e) == 5}
        self.rels = list(rels)
        self.source = source
        self.struct = struct.Struct("<" + "".join("%d%s" % (n, c) for _, c, n in self.payload))
        if self.struct.size != payload_bytes:
            raise AssertionError("image layout packs to %d bytes, not %d" % (self.struct.size, payload_bytes))
        self.payload_bytes = payload_bytes
        self.fields = {f: (c, n) for f, c, n in self.payload}

    def apply_sets(self, p, hdr, sets):
        """Apply --set overrides to the params dict p and the header override dict hdr."""
        for s in sets or ():
            m = re.fullmatch(r"\s*([\w.]+)(?:\[(\d+)\])?\s*=\s*(-?(?:0[xX][0-9a-fA-F]+|\d+))\s*", s)
            if m is None:
                raise SystemExit("image: --set %r: expected FIELD=INT or FIELD[i]=INT" % s)
            f, idx, v = m.group(1), m.group(2), int(m.group(3), 0)
            if f == "revision":   # the params' revision travels in the header, not the payload
                f = "hdr.revision"
            if f.startswith("hdr."):
                if f[4:] not in HDR_FIELDS or idx is not None:
                    raise SystemExit("image: --set %r: header fields are %s"
                                     % (s, ", ".join("hdr." + h for h in HDR_FIELDS)))
                hdr[f[4:]] = v
                continue
            if f not in self.fields:
                raise SystemExit("image: --set %r: no field %r; fields: %s" % (s, f, ", ".join(self.fields)))
            n = self.fields[f][1]
            if idx is None:
                if n != 1:
                    raise SystemExit("image: --set %r: %s has %d entries; use %s[i]=INT" % (s, f, n, f))
                p[f] = v
            else:
                i = int(idx)
                if n == 1 or i >= n:
                    raise SystemExit("image: --set %r: index out of range for %s (%d entries)" % (s, f, n))
                p[f] = list(p[f])
                p[f][i] = v

    def check_limits(self, p, sources=None):
        """Problems of params dict p against the flight loader's per-field limits and relations
        (one line each, naming the field, its value and the allowed range); [] if it would pass.
        sources: {field: (configuration keys it comes from)} for the messages."""
        out = []
        src = (" (%s)" % self.source) if self.source else ""
        sources = sources or {}
        frm = lambda f: ("; derived from %s" % ", ".join(sources[f])) if f in sources else ""
        for f, _, n in self.payload:
            if f not in self.limits:
                continue
            lo, hi = self.limits[f]
            vals = list(p[f]) if n > 1 else [p[f]]
            for i, v in enumerate(vals):
                if not lo <= v <= hi:
                    out.append("table field %s%s = %d is outside the flight loader's limits [%d, %d]%s%s"
                               % (f, ("[%d]" % i) if n > 1 else "", v, lo, hi, src, frm(f)))
        for a, b, margin in self.rels:
            if p[a] + margin > p[b]:
                out.append("table fields %s = %d and %s = %d break the flight loader's relation %s%s <= %s%s%s"
                           % (a, p[a], b, p[b], a, (" + %d" % margin) if margin else "", b, src, frm(a)))
        return out

    def descriptor_text(self):
        """The limits descriptor this layout mirrors, in the format of tests/common/tbl_desc_dump.c
        (the C descriptor printed by the flight build): a text diff proves the mirror exact."""
        ftype = {"B": 1, "H": 2, "I": 3, "i": 4}
        lims, index = [], {}
        off = 0
        for f, c, n in self.payload:
            size = struct.calcsize("<" + c)
            if f in self.limits:
                index[f] = len(lims)
                lims += ["lim %d %d %d %d" % (off + k * size, ftype[c], self.limits[f][0], self.limits[f][1])
                         for k in range(n)]
            off += n * size
        rels = ["rel %d %d %d" % (index[a], index[b], m) for a, b, m in self.rels]
        head = "desc %d %d %d %d %d" % (self.table_id, self.layout_version, self.payload_bytes, len(lims), len(rels))
        return "\n".join([head] + lims + rels) + "\n"

    def pack_payload(self, p):
        flat = []
        for f, _, n in self.payload:
            v = p[f]
            flat += (list(v) if n > 1 else [v])
        try:
            return self.struct.pack(*flat)
        except struct.error as e:
            raise SystemExit("image: a field value does not fit its wire type: %s" % e)

    def build(self, p, revision=1, sets=None):
        """Complete image (header + payload) of the params dict p (a copy is modified)."""
        p = dict(p)
        hdr_over = {}
        self.apply_sets(p, hdr_over, sets)
        pl = self.pack_payload(p)
        hdr = {"table_id": self.table_id, "layout_version": self.layout_version, "length": len(pl),
               "revision": revision, "crc": zlib.crc32(pl) & 0xFFFFFFFF}
        hdr.update(hdr_over)
        try:
            head = HDR.pack(*(hdr[k] for k in HDR_FIELDS))
        except struct.error as e:
            raise SystemExit("image: a header value does not fit its wire type: %s" % e)
        return head + pl

    def decode(self, img):
        """(header dict, params dict) of an image; raises ValueError if malformed."""
        if len(img) < HDR.size:
            raise ValueError("image shorter than its %d-byte header" % HDR.size)
        hdr = dict(zip(HDR_FIELDS, HDR.unpack_from(img)))
        pl = img[HDR.size:]
        if hdr["length"] != len(pl) or len(pl) != self.payload_bytes:
            raise ValueError("payload is %d bytes, header says %d, layout %d" % (len(pl), hdr["length"],
                                                                                self.payload_bytes))
        hdr["crc_ok"] = (zlib.crc32(pl) & 0xFFFFFFFF) == hdr["crc"]
        vals = list(self.struct.unpack(pl))
        p = {}
        for f, _, n in self.payload:
            p[f] = vals[:n] if n > 1 else vals[0]
            del vals[:n]
        return hdr, p


def main(args, layout, names, params):
    """`image --table NAME -o FILE | --all DIR` for one module: params(name) gives the raw fields."""
    if bool(args.all) == bool(args.table):
        raise SystemExit("image: give exactly one of --table NAME (with -o FILE) or --all DIR")
    if args.all:
        if args.set:
            raise SystemExit("image: --set applies to one --table, not --all")
        os.makedirs(args.all, exist_ok=True)
        jobs = [(n, os.path.join(args.all, n + ".bin")) for n in names]
    else:
        if not args.o:
            raise SystemExit("image: --table needs -o FILE")
        jobs = [(args.table, args.o)]
    for name, path in jobs:
        img = layout.build(params(name), args.revision, args.set)
        with open(path, "wb") as fh:
            fh.write(img)
        try:
            hdr, _ = layout.decode(img)
        except ValueError as e:   # a --set hdr.length made it malformed on purpose
            print("%s: %s, %d bytes (malformed on purpose: %s)" % (path, name, len(img), e))
            continue
        print("%s: %s, %d bytes, table_id 0x%04X layout %d length %d revision %d crc 0x%08X%s"
              % (path, name, len(img), hdr["table_id"], hdr["layout_version"], hdr["length"], hdr["revision"],
                 hdr["crc"], "" if hdr["crc_ok"] else " (CRC overridden: does not match the payload)"))
    return 0
