"""A campaign definition (YAML): what to fly, how to disperse it, what to collect and what passes.

    name: rdv-box                        # required
    base: ../../../sim/impulse/scenarios/rendezvous_example.yaml   # the base scenario (relative to this file)
    runs: 1000                           # > 0; a multiple of the grid's size when there is a grid
    seed: 20261202                       # master seed: run i's inputs depend only on (seed, i)
    timeout_s: 600                       # per run: a run that takes longer is recorded as timeout
    driver: memq                         # memq (default) or batch: `sil run --batch`, the same streams
                                         #   without LCM (3x faster); fault-free scenarios only
    set: {duration_s: 1061}              # fixed overrides of the base scenario (optional)
    dispersions:                         # in this order; a path is a scenario key (dots, [i] for a list
      cw.x0[0]: {uniform: [-5000, 5000]}   #   entry) or table.<field>[i] (a raw table integer)
      cw.eps_c: {normal: [0.0, 0.01], clip: [-0.03, 0.03]}
      cw.nav.profile: {choice: [ideal, nominal]}
      cw.t_min_us: {grid: [20000, 40000]}  # every value for every random draw: runs cycle through the grid
      table.t_min_cnt: {grid: [2, 4], with: cw.t_min_us}   # zipped: the partner grid's i-th value with
                                         #   this one's i-th (same length; not a factor of the product)
      cw.nav.seed: seed                  # a fresh 63-bit seed per run
      table.alpha_q30[0]: {uniform_int: [1020054733, 1127428915]}
    metrics: [miss_r_m, dv_used_mps]     # summary.json keys kept per run (numbers)
    pass: [miss_r_m <= 1.0, fsw_n_safe == 0]   # every criterion must hold: KEY OP NUMBER

Inputs of run i: the grid values are the cartesian product of the grid parameters in their order
(a zipped grid follows its partner's index),
run i taking combination i mod (product of the grid sizes); every random parameter is drawn, in
the definition's order, from numpy's PCG64 seeded with SeedSequence([seed, i]). So a run's inputs
never depend on the worker count, the chunking or the order of completion.
"""
import copy
import math
import os
import re

import numpy as np
import yaml

KINDS = ("uniform", "uniform_int", "normal", "choice", "grid", "seed")
OPS = {"<=": lambda a, b: a <= b, "<": lambda a, b: a < b, ">=": lambda a, b: a >= b, ">": lambda a, b: a > b,
       "==": lambda a, b: a == b, "!=": lambda a, b: a != b}
CRIT = re.compile(r"\s*([A-Za-z_][\w.]*)\s*(<=|>=|==|!=|<|>)\s*(-?[0-9.eE+-]+)\s*$")
PATH = re.compile(r"^([A-Za-z_]\w*)(\[\d+\])?(\.[A-Za-z_]\w*(\[\d+\])?)*$")
KEYS = {"name", "base", "runs", "seed", "timeout_s", "driver", "set", "dispersions", "metrics", "pass", "description"}


class CampaignError(ValueError):
    """A campaign file problem, named: file, key and what is wrong."""


class Dispersion(object):
    def __init__(self, path, kind, args, clip=None, zip_with=None):
        self.path, self.kind, self.args, self.clip = path, kind, args, clip
        self.zip_with = zip_with   # a grid that takes its values at this grid's index

    @property
    def table(self):
        return self.path.startswith("table.")

    def draw(self, rng):
        k, a = self.kind, self.args
        if k == "uniform":
            v = float(rng.uniform(a[0], a[1]))
        elif k == "uniform_int":
            v = int(rng.integers(a[0], a[1], endpoint=True))
        elif k == "normal":
            v = float(rng.normal(a[0], a[1]))
        elif k == "choice":
            v = a[int(rng.integers(0, len(a)))]
        elif k == "seed":
            v = int(rng.integers(0, 2 ** 63 - 1, endpoint=True))
        else:
            raise AssertionError(k)
        if self.clip is not None:
            v = min(max(v, self.clip[0]), self.clip[1])
        return v

    def extremes(self):
        """The values a campaign check flies before any run: the support's ends (a normal: its clip,
        or mean +- 4 sigma), every choice and grid value; none for a seed."""
        k, a = self.kind, self.args
        if k in ("uniform", "uniform_int"):
            return [a[0], a[1]]
        if k == "normal":
            return list(self.clip) if self.clip is not None else [a[0] - 4 * a[1], a[0] + 4 * a[1]]
        if k in ("choice", "grid"):
            return list(a)
        return []


class Campaign(object):
    def __init__(self, path):
        self.path = os.path.abspath(path)
        where = os.path.relpath(self.path)
        try:
            with open(self.path, encoding="utf-8") as fh:
                d = yaml.safe_load(fh)
        except (OSError, yaml.YAMLError) as e:
            raise CampaignError("%s: cannot read: %s" % (where, e))
        if not isinstance(d, dict):
            raise CampaignError("%s: not a mapping" % where)
        self.raw = d
        self.mission = self.module = self.table_name = None   # set by runner.check (sil check)

        def fail(key, what):
            raise CampaignError("%s: key '%s': %s" % (where, key, what))

        for k in d:
            if k not in KEYS:
                fail(k, "unknown key (known: %s)" % ", ".join(sorted(KEYS)))
        for k in ("name", "base", "runs", "seed", "dispersions", "metrics", "pass"):
            if k not in d:
                fail(k, "missing required key")
        self.name = str(d["name"])
        if not re.fullmatch(r"[A-Za-z0-9_.-]+", self.name):
            fail("name", "letters, digits, '_', '-', '.' only")
        runs = d["runs"]
        if not isinstance(runs, int) or isinstance(runs, bool) or runs <= 0:
            fail("runs", "%r is not a positive integer" % (runs,))
        self.runs = runs
        seed = d["seed"]
        if not isinstance(seed, int) or isinstance(seed, bool) or seed < 0:
            fail("seed", "%r is not a non-negative integer" % (seed,))
        self.seed = seed
        t = d.get("timeout_s", 600)
        if not isinstance(t, (int, float)) or isinstance(t, bool) or not t > 0:
            fail("timeout_s", "%r is not a positive number of seconds" % (t,))
        self.timeout_s = float(t)
        self.driver = d.get("driver", "memq")
        if self.driver not in ("memq", "batch"):
            fail("driver", "%r is not memq or batch" % (self.driver,))
        self.base = os.path.normpath(os.path.join(os.path.dirname(self.path), str(d["base"])))
        if not os.path.isfile(self.base):
            fail("base", "no scenario file %s" % os.path.relpath(self.base))
        with open(self.base, encoding="utf-8") as fh:
            self.base_scenario = yaml.safe_load(fh)
        self.fixed = d.get("set") or {}
        if not isinstance(self.fixed, dict):
            fail("set", "a mapping of scenario paths to values")
        for p in self.fixed:
            if not PATH.match(str(p)) or str(p).startswith("table."):
                fail("set", "%r is not a scenario path (key.key[i])" % (p,))
        disp = d["dispersions"]
        if not isinstance(disp, dict) or not disp:
            fail("dispersions", "a non-empty mapping of path: dispersion")
        self.dispersions = []
        for p, spec in disp.items():
            self.dispersions.append(self._dispersion(str(p), spec, lambda what, p=p: fail("dispersions.%s" % p, what)))
        seen = {}
        for x in self.dispersions:
            if x.zip_with is not None:
                partner = seen.get(x.zip_with)
                if partner is None or partner.kind != "grid" or partner.zip_with is not None:
                    fail("dispersions.%s" % x.path, "with: %r is not a grid defined before it (and not zipped itself)"
                         % x.zip_with)
                if len(partner.args) != len(x.args):
                    fail("dispersions.%s" % x.path, "with: %d values, %s has %d" % (len(x.args), x.zip_with,
                                                                                   len(partner.args)))
            seen[x.path] = x
        self.grid = [x for x in self.dispersions if x.kind == "grid" and x.zip_with is None]
        self.grid_size = 1
        for g in self.grid:
            self.grid_size *= len(g.args)
        if self.driver == "batch" and (self.base_scenario.get("faults") or any(
                str(p).startswith("faults") for p in list(self.fixed) + [x.path for x in self.dispersions])):
            fail("driver", "batch flies fault-free scenarios only (faults act on the transport): use memq")
        if self.runs % self.grid_size:
            fail("runs", "%d is not a multiple of the grid's %d combinations" % (self.runs, self.grid_size))
        m = d["metrics"]
        if not isinstance(m, list) or not m or not all(isinstance(x, str) for x in m):
            fail("metrics", "a non-empty list of summary keys")
        self.metrics = list(m)
        self.criteria = []
        crit = d["pass"]
        if not isinstance(crit, list):
            fail("pass", "a list of criteria KEY OP NUMBER")
        for c in crit:
            mm = CRIT.match(str(c))
            if mm is None:
                fail("pass", "%r: expected KEY OP NUMBER with OP one of %s" % (c, " ".join(OPS)))
            try:
                val = float(mm.group(3))
            except ValueError:
                fail("pass", "%r: %r is not a number" % (c, mm.group(3)))
            self.criteria.append((mm.group(1), mm.group(2), val, str(c).strip()))

    @staticmethod
    def _dispersion(path, spec, fail):
        if not PATH.match(path):
            fail("not a path: key.key[i] (scenario) or table.field[i] (table)")
        if spec == "seed":
            return Dispersion(path, "seed", None)
        if not isinstance(spec, dict):
            fail("a dispersion is 'seed' or a mapping {KIND: ARGS[, clip: [lo, hi]]}, KIND one of %s" % ", ".join(KINDS))
        kinds = [k for k in spec if k in KINDS]
        other = [k for k in spec if k not in KINDS and k not in ("clip", "with")]
        if len(kinds) != 1 or other:
            fail("exactly one of %s (and optionally clip); got %s" % (", ".join(KINDS), ", ".join(map(str, spec))))
        kind, a = kinds[0], spec[kinds[0]]
        num = lambda v: isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)
        if kind in ("uniform", "uniform_int", "normal"):
            if not isinstance(a, list) or len(a) != 2 or not all(num(v) for v in a):
                fail("%s takes [%s]" % (kind, "mean, sigma" if kind == "normal" else "lo, hi"))
            if kind == "normal" and not a[1] > 0:
                fail("normal: sigma %r must be > 0" % a[1])
            if kind != "normal" and not a[0] < a[1]:
                fail("%s: lo %r must be below hi %r" % (kind, a[0], a[1]))
            if kind == "uniform_int" and not all(isinstance(v, int) for v in a):
                fail("uniform_int: integer bounds")
        elif kind in ("choice", "grid"):
            if not isinstance(a, list) or not a:
                fail("%s takes a non-empty list of values" % kind)
        clip = spec.get("clip")
        if clip is not None:
            if kind not in ("uniform", "normal") or not isinstance(clip, list) or len(clip) != 2 or \
                    not all(num(v) for v in clip) or not clip[0] < clip[1]:
                fail("clip: [lo, hi] with lo < hi, for uniform or normal")
        zip_with = spec.get("with")
        if zip_with is not None and (kind != "grid" or not PATH.match(str(zip_with))):
            fail("with: a grid's partner grid path (key.key[i] or table.field[i])")
        return Dispersion(path, kind, a, clip, None if zip_with is None else str(zip_with))

    # ------------------------------------------------------------------------ inputs of a run

    def inputs(self, i):
        """{path: value} of run i (grid combination, then the random draws in order)."""
        if not 0 <= i < self.runs:
            raise IndexError(i)
        out = {}
        k = i % self.grid_size
        index = {}
        for g in reversed(self.grid):           # mixed radix, the first grid parameter slowest
            index[g.path] = k % len(g.args)
            out[g.path] = g.args[index[g.path]]
            k //= len(g.args)
        for x in self.dispersions:
            if x.zip_with is not None:
                out[x.path] = x.args[index[x.zip_with]]
        rng = np.random.Generator(np.random.PCG64(np.random.SeedSequence([self.seed, i])))
        for x in self.dispersions:
            if x.kind != "grid":
                out[x.path] = x.draw(rng)
        return {x.path: out[x.path] for x in self.dispersions}

    def scenario(self, values, name_suffix=""):
        """The base scenario with the fixed overrides and the scenario values applied (a dict)."""
        s = copy.deepcopy(self.base_scenario)
        for p, v in list(self.fixed.items()) + [(p, v) for p, v in values.items() if not p.startswith("table.")]:
            set_path(s, p, v, self.base)
        if name_suffix:
            s["name"] = "%s-%s" % (s.get("name", self.name), name_suffix)
        return s

    def table_sets(self, values):
        """The table dispersions as image-tool --set strings (FIELD=INT, FIELD[i]=INT)."""
        out = []
        for p, v in values.items():
            if p.startswith("table."):
                if not float(v).is_integer():
                    raise CampaignError("%s = %r: table fields are raw integers" % (p, v))
                out.append("%s=%d" % (p[len("table."):], int(v)))
        return out

    def passed(self, metrics):
        """(passed, reason) of a run's summary values."""
        for key, op, val, text in self.criteria:
            if key not in metrics or metrics[key] is None or (isinstance(metrics[key], float) and math.isnan(metrics[key])):
                return False, "%s: no value" % key
            if not OPS[op](float(metrics[key]), val):
                return False, "%s (%s = %.6g)" % (text, key, float(metrics[key]))
        return True, ""

    def columns(self):
        """Input column name of each dispersion in the store."""
        return {x.path: "in." + x.path for x in self.dispersions}


def set_path(d, path, value, where):
    """d[key][key][i] = value for path 'key.key[i]', creating missing mappings; a list index must
    exist already (in the base scenario or `set`)."""
    parts = path.split(".")
    cur = d
    for n, part in enumerate(parts):
        m = re.fullmatch(r"(\w+)(?:\[(\d+)\])?", part)
        key, idx = m.group(1), m.group(2)
        last = n == len(parts) - 1
        if idx is None:
            if last:
                cur[key] = value
                return
            if key not in cur or cur[key] is None:
                cur[key] = {}
            if not isinstance(cur[key], dict):
                raise CampaignError("%s: '%s' is not a mapping in %s" % (path, key, os.path.relpath(where)))
            cur = cur[key]
        else:
            lst = cur.get(key) if isinstance(cur, dict) else None
            i = int(idx)
            if not isinstance(lst, list) or i >= len(lst):
                raise CampaignError("%s: the base scenario %s has no list '%s' with an entry %d (give the whole list "
                                    "in `set`)" % (path, os.path.relpath(where), key, i))
            if last:
                lst[i] = value
                return
            if not isinstance(lst[i], dict):
                raise CampaignError("%s: '%s[%d]' is not a mapping" % (path, key, i))
            cur = lst[i]
