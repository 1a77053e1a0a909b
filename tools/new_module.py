"""Creates a flight module in every layer from the module template (tools/template/README.md).

    python tools/new_module.py NAME [--prefix P] [--mission M] [--dry-run]

NAME is the module (folder) name, e.g. relay; P the C prefix (default: NAME's first three
letters), M the mission name (default: NAME in upper case). The module gets its own folders

    fsw/NAME  sim/NAME (+ scenarios/)  hil_host/missions/NAME  tools/NAME  tests/NAME

holding a working single-axis rate damper (flight law + mission adapter + table, plant, double
reference, scenario section, metrics, report, unit/golden/SIL tests), and one line in
missions.json with the next free mission id, mode number and table id. Then the generated files
are written (`python -m tools.iface c`, `python -m tools.NAME ctable`). Nothing else in the tree
changes: configure, build and run `ctest -R P` and the new mission flies in SIL.
"""
import argparse
import json
import os
import re
import subprocess
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
TEMPLATE = os.path.join(ROOT, "tools", "template", "module")
REGISTRY = os.path.join(ROOT, "missions.json")
# Names a module may not take: the shared folders of every layer and the executive's own.
RESERVED = {"app", "fx", "common", "plant", "scenario", "sensors", "bridge", "sil", "missions", "lint", "bench",
            "iface", "table", "template", "cli", "fuzz", "golden", "unit", "target", "proofs", "lcm", "sim"}


def fail(msg):
    raise SystemExit("new_module: " + msg)


def camel(name):
    return "".join(p[:1].upper() + p[1:] for p in name.split("_"))


def plan(name, prefix, mission):
    """The substitutions and the registry entry of a new module (checks everything first)."""
    if not re.fullmatch(r"[a-z][a-z0-9_]{1,23}", name) or name in RESERVED:
        fail("module name %r: lower case letters, digits and _, 2..24 characters, not one of the shared "
             "folders (%s)" % (name, ", ".join(sorted(RESERVED))))
    if not re.fullmatch(r"[a-z][a-z0-9]{1,5}", prefix) or prefix in ("fsw", "fx", "gv", "ut", "sim"):
        fail("prefix %r: 2..6 lower case letters/digits, not fsw, fx, gv, ut or sim" % prefix)
    if not re.fullmatch(r"[A-Z][A-Z0-9_]{1,23}", mission):
        fail("mission %r: upper case letters, digits and _" % mission)
    with open(REGISTRY) as fh:
        reg = json.load(fh)
    sys.path.insert(0, ROOT)   # the tree's own tools.iface, whether or not the venv installed it
    from tools import iface
    exec_modes = [v for _, v, _ in iface.exec_iface().MODES.values]
    for e in reg["missions"]:
        for k, v in (("module", name), ("prefix", prefix), ("mission", mission)):
            if e[k].lower() == v.lower():
                fail("%s %r is taken by mission %s" % (k, v, e["mission"]))
        if mission in [n for n, _, _ in iface.exec_iface().MODES.values]:
            fail("mission %r is an executive mode name" % mission)
    tables = [m.iface.table_id for m in iface.missions()]
    entry = {"mission": mission, "module": name, "prefix": prefix,
             "id": max([e["id"] for e in reg["missions"]] + [-1]) + 1,
             "mode": max([e["mode"] for e in reg["missions"]] + exec_modes) + 1}
    subs = {"@module@": name, "@prefix@": prefix, "@PREFIX@": prefix.upper(), "@MISSION@": mission,
            "@mission@": mission.lower(), "@Class@": camel(name),
            "@TABLE_ID@": "0x%04X" % (max(tables + [0x0B00]) + 1)}
    return reg, entry, subs


def files(subs):
    """(template file, destination) pairs; refuses to overwrite anything."""
    out = []
    for d, _, fs in os.walk(TEMPLATE):
        for f in sorted(fs):
            src = os.path.join(d, f)
            rel = os.path.relpath(src, TEMPLATE)
            for k, v in subs.items():
                rel = rel.replace(k, v)
            dst = os.path.join(ROOT, rel)
            if os.path.exists(dst):
                fail("%s exists already" % rel)
            out.append((src, dst))
    return sorted(out)


def registry_text(reg, entry):
    """missions.json with the entry appended, one line per mission as the file keeps them."""
    lines = ['  %s' % json.dumps(e) for e in reg["missions"] + [entry]]
    return '{\n "doc": %s,\n "missions": [\n%s\n ]\n}\n' % (json.dumps(reg["doc"]), ",\n".join(lines))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("name")
    ap.add_argument("--prefix", help="C prefix (default: the name's first three letters)")
    ap.add_argument("--mission", help="mission name (default: NAME in upper case)")
    ap.add_argument("--dry-run", action="store_true", help="print what would be written and stop")
    a = ap.parse_args(argv)
    prefix = a.prefix or a.name.replace("_", "")[:3]
    reg, entry, subs = plan(a.name, prefix, a.mission or a.name.upper())
    todo = files(subs)
    print("new module %s: prefix %s, mission %s (id %d, mode %d, table id %s)"
          % (a.name, prefix, entry["mission"], entry["id"], entry["mode"], subs["@TABLE_ID@"]))
    for _, dst in todo:
        print("  %s" % os.path.relpath(dst, ROOT))
    print("  missions.json: + %s" % json.dumps(entry))
    if a.dry_run:
        return 0
    for src, dst in todo:
        with open(src) as fh:
            text = fh.read()
        for k, v in subs.items():
            text = text.replace(k, v)
        os.makedirs(os.path.dirname(dst), exist_ok=True)
        with open(dst, "w") as fh:
            fh.write(text)
    with open(REGISTRY, "w") as fh:
        fh.write(registry_text(reg, entry))
    py = sys.executable
    for cmd in ([py, "-B", "-m", "tools.iface", "c"], [py, "-B", "-m", "tools.%s" % a.name, "ctable"]):
        subprocess.run(cmd, cwd=ROOT, check=True)
    print("\nnext: cmake --preset host && cmake --build --preset host -j2 && ctest --preset host -R '%s|%s'\n"
          "      then replace the law in fsw/%s/%s.c and grow each layer (tools/template/README.md)."
          % (prefix, a.name, a.name, prefix))
    return 0


if __name__ == "__main__":
    sys.exit(main())
