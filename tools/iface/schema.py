"""Building blocks of an interface description (fsw/app/fsw_iface.py, fsw/<module>/<prefix>_iface.py).

A description is plain data written with these constructors. It is the single source of every
name a flight module shows the outside world: health bits, module enums, telecommands with their
arguments, sensor and actuator channels, and the telemetry block with its wire types, Q formats
and units. Generators (tools/iface/gen_*.py) turn it into the C ids header and telemetry writer
(committed), the host's C++ tables (build tree); Python tools read it through tools.iface.
"""
from dataclasses import dataclass, field as _field
from typing import List, Optional, Tuple

# Wire types of the telemetry and their byte sizes.
WIRE_BYTES = {"u8": 1, "u16": 2, "u32": 4, "i32": 4, "i64": 8}


@dataclass(frozen=True)
class Field:
    """One telemetry field. c is the C expression of its value relative to the block pointer
    `t` (e.g. "t->x_q29[0u]"); q is the number of fraction bits (real = raw / 2^q)."""
    name: str
    type: str
    c: str
    q: Optional[int] = None
    unit: str = ""
    note: str = ""

    def __post_init__(self):
        if self.type not in WIRE_BYTES:
            raise ValueError("field %s: unknown wire type %r" % (self.name, self.type))


@dataclass(frozen=True)
class Bit:
    """A named bit or multi-bit field of a health word: mask, and shift for a multi-bit field."""
    name: str
    mask: int
    note: str = ""

    @property
    def shift(self):
        return (self.mask & -self.mask).bit_length() - 1

    @property
    def single(self):
        return self.mask & (self.mask - 1) == 0


@dataclass(frozen=True)
class Enum:
    """A named set of integer values (module modes, failure causes, ...). c_prefix names the C
    macros: c_prefix + value name (IMP_MODE_ + IDLE)."""
    name: str
    c_prefix: str
    values: Tuple[Tuple[str, int, str], ...]
    note: str = ""

    def by_value(self):
        return {v: n for n, v, _ in self.values}


def enum(name, c_prefix, values, note=""):
    """values: list of (name, value[, note])."""
    vs = tuple((v[0], int(v[1]), v[2] if len(v) > 2 else "") for v in values)
    return Enum(name, c_prefix, vs, note)


@dataclass(frozen=True)
class Arg:
    """A telecommand argument as a scenario writes it (SI units), and its conversion to the
    flight's int32 argument words: kind "steps" = round(value / period), kind "scaled" =
    round(value * scale). n > 1: a list of n values in consecutive words."""
    name: str
    kind: str = "scaled"
    scale: float = 1.0
    lo: float = 0.0
    hi: float = 0.0
    n: int = 1
    required: bool = False
    unit: str = ""

    def __post_init__(self):
        if self.kind not in ("steps", "scaled"):
            raise ValueError("arg %s: kind must be steps or scaled" % self.name)


@dataclass(frozen=True)
class Tc:
    """A module telecommand: its name (as scenarios and ground tools write it), its local id
    (1..255; the wire id is the mission's namespace | local id) and its arguments."""
    name: str
    local: int
    note: str = ""
    args: Tuple[Arg, ...] = ()


def tc(name, local, note="", args=()):
    return Tc(name, local, note, tuple(args))


@dataclass(frozen=True)
class Chan:
    """A sensor or actuator channel: name, unit of one count, and a note."""
    name: str
    unit: str = ""
    note: str = ""


@dataclass
class Module:
    """What a module description defines (fsw/observer/obs_iface.py is a complete example). The C
    macros are named from the prefix: <P>_H_<bit> (health), <P>_WHY_<bit> (table check reasons),
    <P>_CMD_<tc> (telecommand local ids, <P>_CMD_NONE = 0), and each enum's own c_prefix."""
    module: str
    prefix: str
    doc: str
    tlm_type: str                       # C type of the telemetry block (obs_tlm_t)
    tlm_layout: int                     # layout revision (low byte of the telemetry layout version)
    tlm: List[Field]
    sensors: List[Chan]                 # consumed sensor channels, in counts[] order
    actuators: List[Chan]               # driven actuator channels, in counts[] order
    health: List[Bit] = _field(default_factory=list)     # module health bits 8..31
    why: List[Bit] = _field(default_factory=list)        # <p>_params_check reason bits
    enums: List[Enum] = _field(default_factory=list)
    commands: List[Tc] = _field(default_factory=list)
    table_id: int = 0
    table_layout: int = 1
    table_fields: List[str] = _field(default_factory=list)   # names by limits-descriptor index

    @property
    def P(self):
        return self.prefix.upper()
