#!/usr/bin/env python3
"""Static worst-case stack from GCC call graphs (spec 00 §4 "stack", §9).

Reads the VCG files written by `-fstack-usage -fcallgraph-info=su` (one <object>.ci per
translation unit) and sums, for each root, the largest own-frame total over every call path.

  * Frame sizes are GCC's (they include the saved registers and LR).
  * libgcc and other <built-in> callees carry no size; ALLOWANCE below supplies them (the 64-bit
    divide path is 48 bytes: 16 in __aeabi_[u]ldivmod + 32 in __udivmoddi4). A built-in that is
    also defined in one of the given .ci files (memcpy from fsw/target) uses the measured frame.
  * FAILS (exit 1) on recursion (a cycle), a `dynamic` frame (alloca, VLA), an indirect call,
    or a callee that is neither defined in the given graphs nor in the allowance table.
  * The sums themselves are reported, not gated (spec 00 §9 compares them with stack painting).

Inputs: .ci files, object files (their sibling .ci is used) and directories (every .ci below),
plus --lib ARCHIVE=DIR: the .ci files under DIR of ARCHIVE's members only, so stale .ci files of
removed sources are ignored; a member without a .ci is an error.
Roots: --root NAME (repeatable), else every externally visible function of the graphs.

Usage: stack_sum.py [--lib ARCHIVE=DIR]... [--root NAME]... [--allow NAME=BYTES]... [--json OUT]
                    [CI_FILE_OR_OBJECT_OR_DIR...]
Exit status: 0 ok, 1 recursion/dynamic/unresolved, 2 usage or input error.
"""
import argparse
import json
import os
import re
import sys

# bytes of stack used by libgcc routines (and fallbacks for the mem* functions when the .ci of
# their fsw/target implementation is not among the inputs).
ALLOWANCE = {
    "__udivmoddi4": (32, "libgcc 64-bit divide core"),
    "__aeabi_ldivmod": (48, "16 own + 32 in __udivmoddi4"),
    "__aeabi_uldivmod": (48, "16 own + 32 in __udivmoddi4"),
    "__divdi3": (48, "generic name of the signed 64-bit divide path"),
    "__moddi3": (48, "generic name of the signed 64-bit modulo path"),
    "__udivdi3": (48, "generic name of the unsigned 64-bit divide path"),
    "__umoddi3": (48, "generic name of the unsigned 64-bit modulo path"),
    "__divmoddi4": (48, "generic name of the signed 64-bit divmod path"),
    "memcpy": (16, "leaf loop; the fsw/target frame is used when its .ci is given"),
    "memset": (16, "leaf loop; the fsw/target frame is used when its .ci is given"),
    "memmove": (16, "leaf loop; the fsw/target frame is used when its .ci is given"),
    "memcmp": (16, "leaf loop; the fsw/target frame is used when its .ci is given"),
}

_KV = re.compile(r'(\w+)\s*:\s*"((?:\\.|[^"\\])*)"')
_SIZE = re.compile(r"^(\d+) bytes \(([^)]*)\)$")


class Func:
    def __init__(self, key, name, title, ci, loc, size, qual):
        self.key, self.name, self.title, self.ci = key, name, title, ci
        self.loc, self.size, self.qual = loc, size, qual
        self.edges = []          # raw target titles, resolved later
        self.callees = []        # resolved keys


def read_archive_members(path):
    """Member names of a System V / GNU ar archive (no external tool needed)."""
    with open(path, "rb") as fh:
        data = fh.read()
    if not data.startswith(b"!<arch>\n"):
        raise ValueError("%s is not an ar archive" % path)
    pos, names, longnames = 8, [], b""
    while pos + 60 <= len(data):
        hdr = data[pos:pos + 60]
        name = hdr[0:16].decode("ascii", "replace").rstrip()
        size = int(hdr[48:58].decode("ascii").strip() or "0")
        body = data[pos + 60:pos + 60 + size]
        if name == "//":
            longnames = body
        elif name in ("/", "/SYM64/", "__.SYMDEF", "__.SYMDEF SORTED"):
            pass
        elif name.startswith("/") and name[1:].isdigit():
            off = int(name[1:])
            end = longnames.find(b"/\n", off)
            names.append(longnames[off:end].decode("utf-8", "replace"))
        elif name.startswith("#1/"):
            n = int(name[3:])
            names.append(body[:n].rstrip(b"\0").decode("utf-8", "replace"))
        else:
            names.append(name[:-1] if name.endswith("/") else name)
        pos += 60 + size + (size & 1)
    return names


def ci_of_object(path):
    return re.sub(r"\.(obj|o)$", "", path) + ".ci"


def find_ci(paths):
    out = []
    # CMake passes $<TARGET_OBJECTS:...> to add_test() as one ;-separated argument.
    paths = [q for p in paths for q in p.split(";") if q]
    for p in paths:
        if os.path.isdir(p):
            for d, subdirs, files in os.walk(p):
                subdirs.sort()
                out.extend(os.path.realpath(os.path.join(d, f)) for f in sorted(files) if f.endswith(".ci"))
        elif p.endswith((".o", ".obj")):
            ci = ci_of_object(p)
            if not os.path.isfile(ci):
                raise SystemExit("stack_sum: ERROR: no call graph %s for %s; compile it with "
                                 "-fstack-usage -fcallgraph-info=su" % (ci, p))
            out.append(os.path.realpath(ci))
        elif os.path.isfile(p):
            out.append(os.path.realpath(p))
        else:
            raise SystemExit("stack_sum: ERROR: %s does not exist" % p)
    return out


def lib_ci(spec):
    """.ci files of the members of ARCHIVE found under DIR (spec is ARCHIVE=DIR)."""
    lib, sep, directory = spec.partition("=")
    if not sep or not directory:
        raise SystemExit("stack_sum: ERROR: --lib expects ARCHIVE=DIR, got %r" % spec)
    if not os.path.isfile(lib):
        raise SystemExit("stack_sum: ERROR: %s does not exist; build it first" % lib)
    by_base = {}
    for c in find_ci([directory]):
        by_base.setdefault(os.path.basename(c), []).append(c)
    chosen, missing = [], []
    for m in read_archive_members(lib):
        cand = by_base.get(os.path.basename(ci_of_object(m)), [])
        if not cand:
            missing.append(m)
        chosen.extend(c for c in cand if c not in chosen)
    if missing:
        raise SystemExit("stack_sum: ERROR: no .ci call graph under %s for member(s) %s of %s; "
                         "compile them with -fstack-usage -fcallgraph-info=su"
                         % (directory, ", ".join(missing), lib))
    return chosen


def parse_ci(path, funcs, builtins, errors):
    """Add the functions defined in one .ci file. Returns (file-local titles, edges)."""
    local = {}
    edges = []
    with open(path, encoding="utf-8", errors="replace") as fh:
        for line in fh:
            line = line.strip()
            kv = dict(_KV.findall(line))
            if line.startswith("node:"):
                title = kv.get("title", "")
                label = kv.get("label", "").split("\\n")
                name = label[0]
                if len(label) >= 3 and _SIZE.match(label[2]):
                    size, qual = _SIZE.match(label[2]).groups()
                    is_static = title != name
                    key = "%s@%s" % (title, path) if is_static else title
                    f = Func(key, name, title, path, label[1], int(size), qual)
                    if is_static:
                        local[title] = key
                        funcs[key] = f
                    elif key in funcs:
                        errors.append("duplicate definition of %s: %s (%s) and %s (%s); pass the "
                                      ".ci files of one image only" % (name, funcs[key].loc, funcs[key].ci,
                                                                       f.loc, path))
                    else:
                        funcs[key] = f
                elif len(label) >= 2 and label[1] == "<built-in>":
                    builtins[title] = name
            elif line.startswith("edge:"):
                edges.append((kv.get("sourcename", ""), kv.get("targetname", ""), kv.get("label", "")))
    return local, edges


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("inputs", nargs="*", help=".ci files, objects, or directories searched recursively")
    ap.add_argument("--lib", action="append", default=[], metavar="ARCHIVE=DIR",
                    help="the .ci files under DIR of ARCHIVE's members (repeatable)")
    ap.add_argument("--root", action="append", default=[], help="root function (repeatable)")
    ap.add_argument("--allow", action="append", default=[], metavar="NAME=BYTES",
                    help="extra allowance for a built-in callee")
    ap.add_argument("--json", help="also write the report as JSON here")
    ap.add_argument("--quiet", action="store_true", help="print only the summary and the errors")
    args = ap.parse_intermixed_args()

    allowance = {k: v[0] for k, v in ALLOWANCE.items()}
    for a in args.allow:
        name, _, val = a.partition("=")
        if not val.isdigit():
            print("stack_sum: ERROR: --allow expects NAME=BYTES, got %r" % a, file=sys.stderr)
            return 2
        allowance[name] = int(val)

    ci_files = []
    for spec in args.lib:
        ci_files.extend(c for c in lib_ci(spec) if c not in ci_files)
    ci_files.extend(c for c in find_ci(args.inputs) if c not in ci_files)
    if not ci_files:
        print("stack_sum: ERROR: no .ci files in the inputs", file=sys.stderr)
        return 2

    funcs, builtins, errors = {}, {}, []
    per_file = []
    for c in ci_files:
        per_file.append((c,) + parse_ci(c, funcs, builtins, errors))

    unresolved = []      # (caller, callee, where)
    for c, local, edges in per_file:
        for src, dst, where in edges:
            skey = local.get(src, src)
            if skey not in funcs:
                continue      # edge from a function GCC did not emit (fully inlined)
            if dst in local:
                dkey = local[dst]
            elif dst in funcs:
                dkey = dst
            elif dst in allowance:
                dkey = "<allowance>" + dst
            else:
                dkey = None
                why = ("indirect call (function pointer)" if dst == "__indirect_call"
                       else "built-in %s without an allowance" % builtins[dst] if dst in builtins
                       else "not defined in the given call graphs")
                unresolved.append((skey, dst, where, why))
            if dkey is not None and dkey not in funcs[skey].callees:
                funcs[skey].callees.append(dkey)

    if args.root:
        roots = []
        for r in args.root:
            if r in funcs:
                roots.append(r)
            else:
                errors.append("root %s is not defined in the given call graphs" % r)
    else:
        roots = sorted(k for k, f in funcs.items() if k == f.name)

    # Depth-first worst path with cycle detection.
    memo, on_stack, cycles = {}, [], []

    def worst(key):
        if key.startswith("<allowance>"):
            name = key[len("<allowance>"):]
            return allowance[name], [name + " [allowance]"]
        if key in memo:
            return memo[key]
        if key in on_stack:
            cyc = on_stack[on_stack.index(key):] + [key]
            cycles.append(" -> ".join(funcs[k].name for k in cyc))
            return 0, [funcs[key].name + " [cycle]"]
        on_stack.append(key)
        f = funcs[key]
        best, best_path = 0, []
        for c in f.callees:
            s, p = worst(c)
            if s > best or not best_path:
                best, best_path = s, p
        on_stack.pop()
        memo[key] = (f.size + best, [f.name] + best_path)
        return memo[key]

    rows = []
    for r in roots:
        total, path = worst(r)
        rows.append((funcs[r].name, funcs[r].size, funcs[r].qual, total, path))
    reachable = {k for k in memo}
    dynamic = sorted((funcs[k].name, funcs[k].loc, funcs[k].qual)
                     for k in reachable if "dynamic" in funcs[k].qual)
    unresolved = [u for u in unresolved if u[0] in reachable]

    rows.sort(key=lambda r: (-r[3], r[0]))
    if not args.quiet:
        w = max([len("function")] + [len(r[0]) for r in rows])
        print("%-*s  %9s  %10s  %s" % (w, "function", "own frame", "worst path", "path"))
        print("%s  %s  %s  %s" % ("-" * w, "-" * 9, "-" * 10, "-" * 4))
        for name, size, qual, total, path in rows:
            print("%-*s  %9d  %10d  %s" % (w, name, size, total, " -> ".join(path)))
        print()
    for c in sorted(set(cycles)):
        errors.append("recursion (call cycle): %s" % c)
    for name, loc, qual in dynamic:
        errors.append("dynamic stack frame (%s) in %s at %s: alloca or a VLA" % (qual, name, loc))
    for skey, dst, where, why in sorted(set(unresolved)):
        errors.append("unresolved callee %s of %s%s: %s"
                      % (dst, funcs[skey].name, (" at " + where) if where else "", why))

    if args.json:
        with open(args.json, "w", encoding="utf-8") as fh:
            json.dump({"roots": [{"function": r[0], "own": r[1], "qualifier": r[2], "worst": r[3],
                                  "path": r[4]} for r in rows],
                       "allowance": allowance, "errors": errors,
                       "ci_files": ci_files}, fh, indent=1)
    top = rows[0] if rows else None
    summary = ("%d root(s) from %d call graph(s); deepest: %s = %d bytes"
               % (len(rows), len(ci_files), top[0], top[3]) if top else "no roots")
    if errors:
        for e in errors:
            print("stack_sum: ERROR: " + e)
        print("stack_sum: FAIL: %d problem(s); %s (spec 00 §4 'stack': no recursion, no dynamic "
              "frames, every callee resolved)" % (len(errors), summary))
        return 1
    print("stack_sum: OK: " + summary)
    return 0


if __name__ == "__main__":
    sys.exit(main())
