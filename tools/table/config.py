"""Mission configuration files (YAML) for the table generators: loading, the schema helper, errors.

A module's configuration is a pydantic model (tools/observer/config.py, tools/impulse/config.py)
built on `Config`: strict types (no string-to-number or float-to-int coercion, booleans are
true/false), no unknown keys, and every key declared with `key()`: default, allowed range, unit
and a one-line meaning. `load(path, cls)` reads the YAML file and returns the model or raises
`ConfigError`, whose message names each offending key with its value, unit and allowed range.

YAML notes: the loader is PyYAML's safe loader plus YAML 1.2 floats (`8e-4` is a number, not the
string YAML 1.1 makes of it) and duplicate keys are an error (YAML 1.1 silently keeps the last).
"""
import difflib
import math
import re
import typing

import yaml
from pydantic import BaseModel, ConfigDict, Field, ValidationError


class ConfigError(Exception):
    """A configuration file that cannot become a table; str() is one line per problem."""

    def __init__(self, path, problems):
        self.path = path
        self.problems = list(problems)
        super().__init__("\n".join("%s: %s" % (path, p) for p in self.problems))


class _Loader(yaml.SafeLoader):
    pass


# YAML 1.2 floats (1e-3, 8E-4 without a dot), as PyYAML's own float pattern otherwise.
_Loader.add_implicit_resolver(
    "tag:yaml.org,2002:float",
    re.compile(r"""^(?:[-+]?(?:[0-9][0-9_]*)\.[0-9_]*(?:[eE][-+]?[0-9]+)?
                   |[-+]?(?:[0-9][0-9_]*)(?:[eE][-+]?[0-9]+)
                   |\.[0-9_]+(?:[eE][-+]?[0-9]+)?
                   |[-+]?\.(?:inf|Inf|INF)
                   |\.(?:nan|NaN|NAN))$""", re.X),
    list("-+0123456789."))


def _mapping_no_duplicates(loader, node, deep=False):
    seen = {}
    for k, _ in node.value:
        key_ = loader.construct_object(k, deep=deep)
        if key_ in seen:
            raise yaml.constructor.ConstructorError(
                None, None, "duplicate key %r (first at line %d)" % (key_, seen[key_] + 1), k.start_mark)
        seen[key_] = k.start_mark.line
    return loader.construct_mapping(node, deep=deep)


_Loader.add_constructor(yaml.resolver.BaseResolver.DEFAULT_MAPPING_TAG, _mapping_no_duplicates)


class Config(BaseModel):
    """Base of a module's configuration: strict, closed, immutable."""
    model_config = ConfigDict(extra="forbid", strict=True, frozen=True)


def key(default, lo=None, hi=None, unit="", doc="", *, lo_open=False, hi_open=False, each=False):
    """One configuration key: default (`...` = required), range [lo, hi] (open ends with
    lo_open / hi_open), unit ("" = dimensionless) and meaning. each=True: a list whose entries
    carry the range (put the bounds on the entry type as well; this records them for messages)."""
    kw = {}
    if not each:
        if lo is not None:
            kw["gt" if lo_open else "ge"] = lo
        if hi is not None:
            kw["lt" if hi_open else "le"] = hi
    extra = {"unit": unit, "lo": lo, "hi": hi, "lo_open": lo_open, "hi_open": hi_open, "each": each}
    return Field(default, description=doc, json_schema_extra=extra, **kw)


def _num(x):
    if isinstance(x, bool) or not isinstance(x, (int, float)):
        return repr(x)
    return repr(x) if isinstance(x, int) else "%.10g" % x


def range_text(cls, name):
    """'[lo, hi] unit' (or a description of the allowed values) of key `name` of model cls."""
    f = cls.model_fields[name]
    ex = f.json_schema_extra or {}
    unit = ex.get("unit", "")
    lo, hi = ex.get("lo"), ex.get("hi")
    ann = f.annotation
    args = typing.get_args(ann)
    if typing.get_origin(ann) is typing.Literal:
        return "one of " + ", ".join(repr(a) for a in args)
    if ann is bool:
        return "true or false"
    if lo is None and hi is None:
        return "any" + (" (%s)" % unit if unit else "")
    s = "%s%s, %s%s" % ("(" if ex.get("lo_open") else "[", _num(lo) if lo is not None else "-inf",
                        _num(hi) if hi is not None else "inf", ")" if ex.get("hi_open") else "]")
    if ex.get("each"):
        s = "each in " + s
    return s + (" " + unit if unit else "")


def _kind(cls, name):
    ann = cls.model_fields[name].annotation
    base = [a for a in (typing.get_args(ann) or (ann,)) if a is not type(None)]
    base = base[0] if base else ann
    org = typing.get_origin(base)
    if org is list or base is list:
        item = typing.get_args(base)[0] if typing.get_args(base) else None
        item = typing.get_args(item)[0] if typing.get_origin(item) is typing.Annotated else item
        return "a list of %s" % ("integers" if item is int else "numbers")
    return {float: "a number", int: "an integer", bool: "true or false", str: "a string"}.get(base, str(base))


def describe(cls, name):
    """'meaning, allowed RANGE' of a key, for messages and the key listing."""
    f = cls.model_fields[name]
    return "%s; allowed %s" % (f.description or name, range_text(cls, name))


def _problem(cls, err):
    loc = err["loc"]
    typ = err["type"]
    if not loc:   # a model-level validator
        return err["msg"].replace("Value error, ", "")
    name = str(loc[0])
    where = name + "".join("[%s]" % i for i in loc[1:])
    val = err.get("input")
    if typ == "extra_forbidden":
        near = difflib.get_close_matches(name, list(cls.model_fields), n=1)
        return "unknown key '%s'%s; known keys: %s" % (
            name, (" (did you mean '%s'?)" % near[0]) if near else "", ", ".join(cls.model_fields))
    if name not in cls.model_fields:
        return "%s: %s" % (where, err["msg"])
    if typ == "missing":
        return "missing required key '%s': %s" % (name, describe(cls, name))
    if typ in ("greater_than_equal", "less_than_equal", "greater_than", "less_than"):
        return "%s = %r is out of range: %s" % (where, val, describe(cls, name))
    if typ in ("too_short", "too_long"):
        n = err["ctx"].get("min_length", err["ctx"].get("max_length"))
        return "%s has %d entries, expected %s: %s" % (where, err["ctx"]["actual_length"], n, describe(cls, name))
    if typ == "literal_error":
        return "%s = %r is not allowed: %s" % (where, val, describe(cls, name))
    if typ.endswith("_type") or typ.endswith("_parsing") or typ == "finite_number":
        return "%s = %r has the wrong type (%s): expected %s; %s" % (
            where, val, type(val).__name__, _kind(cls, name), describe(cls, name))
    return "%s = %r: %s; %s" % (where, val, err["msg"], describe(cls, name))


def read_yaml(path):
    """The YAML mapping of a configuration file; ConfigError if unreadable or not a mapping."""
    try:
        with open(path, encoding="utf-8") as fh:
            data = yaml.load(fh, Loader=_Loader)
    except OSError as e:
        raise ConfigError(path, ["cannot read: %s" % e.strerror])
    except yaml.YAMLError as e:
        raise ConfigError(path, ["not valid YAML: %s" % str(e).replace("\n", " ")])
    if not isinstance(data, dict):
        raise ConfigError(path, ["expected a mapping of keys to values at the top level, got %s"
                                 % type(data).__name__])
    return data


def validate(cls, data, path="<config>"):
    """The model of `data` (a dict), or ConfigError naming every offending key."""
    bad = [k for k in data if not isinstance(k, str)]
    if bad:
        raise ConfigError(path, ["key %r is not a name" % k for k in bad])
    try:
        cfg = cls.model_validate(data)
    except ValidationError as e:
        raise ConfigError(path, [_problem(cls, err) for err in e.errors()])
    problems = cfg.cross_checks() if hasattr(cfg, "cross_checks") else []
    if problems:
        raise ConfigError(path, problems)
    return cfg


def load(path, cls):
    return validate(cls, read_yaml(path), path)


def _default_text(v):
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (list, tuple)):
        return "[%s]" % ", ".join(_default_text(x) for x in v)
    if isinstance(v, str):
        return repr(v)
    return repr(v)


def keys_table(cls):
    """Markdown table of a model's keys: key, allowed values, default, meaning."""
    rows = ["| key | allowed | default | meaning |", "|---|---|---|---|"]
    for name, f in cls.model_fields.items():
        d = "required" if f.is_required() else ("—" if f.default is None else _default_text(f.default))
        rows.append("| `%s` | %s | %s | %s |" % (name, range_text(cls, name), d,
                                                 (f.description or "").replace("|", "\\|")))
    return "\n".join(rows)


def whole_steps(value_s, period_us, name, problems, minimum=0):
    """value_s as a whole number of periods (>= minimum), or a problem naming the key."""
    n = value_s * 1e6 / period_us
    k = int(math.floor(n + 0.5))
    if abs(n - k) > 1e-6 * max(1.0, abs(n)):
        problems.append("%s = %s s is not a whole number of periods (period_us = %d us): %.6g periods"
                        % (name, _num(value_s), period_us, n))
    elif k < minimum:
        problems.append("%s = %s s is %d periods, at least %d needed (period_us = %d us)"
                        % (name, _num(value_s), k, minimum, period_us))
    return k
