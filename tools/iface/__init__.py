"""The mission registry and the interface descriptions, as Python sees them.

    from tools import iface
    for m in iface.missions():             # missions.json, in id order
        m.name, m.module, m.id, m.mode, m.layout_version, m.iface   # iface: schema.Module
    iface.mission("RENDEZVOUS")            # by name (case-insensitive), id or telemetry layout version
    lay = iface.mission("DETUMBLE").layout # full telemetry layout: head + actuators + health + block
    lay.decode(buf), lay.decode_many(bufs), lay.scaled(d)
    iface.exec_iface()                     # fsw/app/fsw_iface.py (modes, health bits, reasons, header)

missions.json is the one registration line per mission; fsw/<module>/<prefix>_iface.py the one
source of a module's names and telemetry. Nothing here parses C.
"""
import importlib.util
import json
import os
import struct

from .schema import WIRE_BYTES, Field

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
REGISTRY = os.path.join(ROOT, "missions.json")
EXEC_IFACE = os.path.join(ROOT, "fsw", "app", "fsw_iface.py")

TC_NS_SHIFT = 8          # wire telecommand id = ((mission id + 1) << 8) | local id
CMD_MODE = 1             # gnc.fsw_cmd_v2_t CMD_MODE: args[0] = target mode
TLM_MAX_BYTES = 512      # gnc.fsw_tlm_frame_t tlm[512]


class IfaceError(ValueError):
    """The registry or a description is inconsistent."""


_CACHE = {}


def _load_py(path, name):
    if path not in _CACHE:
        if not os.path.exists(path):
            raise IfaceError("%s: interface description not found" % os.path.relpath(path, ROOT))
        spec = importlib.util.spec_from_file_location(name, path)
        mod = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(mod)
        _CACHE[path] = mod
    return _CACHE[path]


def exec_iface():
    return _load_py(EXEC_IFACE, "fsw_iface")


class Layout(object):
    """A telemetry layout: ordered fields with wire types, Q formats and units. Real = raw / 2^q."""

    _CODES = {"u8": ("B", "u1"), "u16": ("H", "u2"), "u32": ("I", "u4"), "i32": ("i", "i4"), "i64": ("q", "i8")}

    def __init__(self, version, fields, what):
        self.layout_version = version
        self.fields = list(fields)
        self.what = what
        self.names = [f.name for f in self.fields]
        if len(set(self.names)) != len(self.names):
            dup = sorted(n for n in set(self.names) if self.names.count(n) > 1)
            raise IfaceError("%s: duplicate telemetry field names %s" % (what, dup))
        self.q = {f.name: f.q for f in self.fields if f.q is not None}
        self.unit = {f.name: f.unit for f in self.fields}
        self.offset = {}
        off = 0
        for f in self.fields:
            self.offset[f.name] = off
            off += WIRE_BYTES[f.type]
        self.nbytes = off
        self.struct = struct.Struct("<" + "".join(self._CODES[f.type][0] for f in self.fields))

    def decode(self, buf):
        buf = bytes(buf)
        if len(buf) != self.nbytes:
            raise IfaceError("%s: telemetry buffer is %d bytes, layout 0x%08X has %d"
                             % (self.what, len(buf), self.layout_version, self.nbytes))
        return dict(zip(self.names, self.struct.unpack(buf)))

    def scaled(self, d):
        return {k: (v / float(1 << self.q[k]) if k in self.q else v) for k, v in d.items()}

    def decode_many(self, bufs):
        """bufs: iterable of bytes, each exactly nbytes long -> dict of numpy raw arrays."""
        import numpy as np
        dtype = np.dtype([(f.name, "<" + self._CODES[f.type][1]) for f in self.fields])
        blob = bytearray()
        for i, b in enumerate(bufs):
            if len(b) != self.nbytes:
                raise IfaceError("%s: telemetry message %d is %d bytes, expected %d" % (self.what, i, len(b), self.nbytes))
            blob += b
        arr = np.frombuffer(bytes(blob), dtype=dtype)
        return {n: arr[n].copy() for n in self.names}

    def scaled_many(self, raw):
        return {k: (v.astype("float64") * 2.0 ** -self.q[k]) if k in self.q else v for k, v in raw.items()}


class Mission(object):
    """One registered mission: its registry line and its module's interface description."""

    def __init__(self, entry):
        for k in ("mission", "module", "prefix", "id", "mode"):
            if k not in entry:
                raise IfaceError("missions.json: entry %r lacks %r" % (entry, k))
        self.name = entry["mission"]
        self.module = entry["module"]
        self.prefix = entry["prefix"]
        self.id = int(entry["id"])
        self.mode = int(entry["mode"])
        self.run = [str(x) for x in entry.get("run", [])]   # scenarios of the main job (tools/run.sh)
        # the PIL equivalence test's scenario and reduced duration (tests/pil), or None
        pil = entry.get("pil")
        self.pil = None if pil is None else (str(pil["scenario"]), float(pil["duration_s"]))
        self.iface_path = os.path.join(ROOT, "fsw", self.module, self.prefix + "_iface.py")
        self.iface = getattr(_load_py(self.iface_path, self.prefix + "_iface"), "MODULE")
        if self.iface.prefix != self.prefix or self.iface.module != self.module:
            raise IfaceError("%s: MODULE says %s/%s, missions.json %s/%s" % (
                os.path.relpath(self.iface_path, ROOT), self.iface.module, self.iface.prefix, self.module, self.prefix))
        ex = exec_iface()
        self.layout_version = ((self.id + 1) << 16) | (ex.LAYOUT_REV << 8) | self.iface.tlm_layout
        self.tc_ns = (self.id + 1) << TC_NS_SHIFT
        head = list(ex.HEAD)
        act = [Field(c.name, "i32", "t->act_cnt[%du]" % i, unit=c.unit, note=c.note)
               for i, c in enumerate(self.iface.actuators)]
        health = [Field(self.prefix + "_health", "u32", "t->mod_health",
                        note="%s health of this step (0 when not run)" % self.module)]
        block = [Field(self.prefix + "_" + f.name, f.type, f.c, f.q, f.unit, f.note) for f in self.iface.tlm]
        self.layout = Layout(self.layout_version, head + act + health + block, "mission %s" % self.name)
        if self.layout.nbytes > TLM_MAX_BYTES:
            raise IfaceError("mission %s: telemetry of %d bytes does not fit fsw_tlm_frame_t.tlm[%d]"
                             % (self.name, self.layout.nbytes, TLM_MAX_BYTES))

    @property
    def block_bytes(self):
        return sum(WIRE_BYTES[f.type] for f in self.iface.tlm)

    def tc_id(self, name):
        """Wire id of a telecommand given as PREFIX_NAME (IMP_START) or NAME (START)."""
        for t in self.iface.commands:
            if name in (t.name, "%s_%s" % (self.prefix.upper(), t.name)):
                return self.tc_ns | t.local
        raise KeyError(name)

    def modes(self):
        """Every mode number of this mission's executive -> name."""
        d = {v: n for n, v, _ in exec_iface().MODES.values}
        d[self.mode] = self.name
        return d


def registry():
    """missions.json as a list of Mission, validated: unique names, ids, modes, prefixes, tables."""
    with open(REGISTRY) as fh:
        entries = json.load(fh)["missions"]
    ms = [Mission(e) for e in entries]
    exec_modes = {v for _, v, _ in exec_iface().MODES.values}
    for key in ("name", "id", "mode", "prefix", "module"):
        vals = [getattr(m, key) for m in ms]
        if len(set(vals)) != len(vals):
            raise IfaceError("missions.json: duplicate %s in %s" % (key, vals))
    tids = [m.iface.table_id for m in ms]
    if len(set(tids)) != len(tids):
        raise IfaceError("duplicate table ids %s" % [hex(t) for t in tids])
    for m in ms:
        if m.mode in exec_modes:
            raise IfaceError("missions.json: mission %s mode %d is an executive mode" % (m.name, m.mode))
        if not 0 <= m.id < 255:
            raise IfaceError("missions.json: mission %s id %d outside 0..254" % (m.name, m.id))
    return sorted(ms, key=lambda m: m.id)


def missions(names=None):
    """The registered missions (all, or those named, in registry order)."""
    ms = registry()
    if names is None:
        return ms
    want = [n.upper() for n in names]
    unknown = [n for n in want if n not in {m.name for m in ms}]
    if unknown:
        raise IfaceError("unknown mission(s) %s; registered: %s" % (unknown, [m.name for m in ms]))
    return [m for m in ms if m.name in want]


def mission(key):
    """A mission by name (case-insensitive), id, or telemetry layout version."""
    for m in registry():
        if (isinstance(key, str) and m.name == key.upper()) or (
                isinstance(key, int) and (m.id == key or m.layout_version == key)):
            return m
    raise IfaceError("no registered mission %r" % (key,))
