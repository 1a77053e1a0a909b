#!/usr/bin/env python3
"""Instruction counts of a mission module's step on the emulated Cortex-M (spec 00 §6.4, §9).

    .venv/bin/python -m tools.bench.module_insn [BUILD_DIR ...] [--module M ...] [--out-dir bench]
                                                [--reps 2] [--machine MACHINE]

Builds nothing: for each module M (name or prefix from missions.json; default: every
<BUILD_DIR>/fsw/target/<m>_bench.elf of the first BUILD_DIR) it runs <BUILD_DIR>/fsw/target/
<m>_bench.elf (from fsw/<m>/bench/<prefix or m>_bench.c, built by fsw/target/CMakeLists.txt in every
cortex-m3/m4 build) under `qemu-system-arm -icount shift=3` through tools/qemu-run.sh, exactly as
fx_insn.py runs fx_bench, and writes <out-dir>/<m>_insn.md and <out-dir>/<m>_insn.json with
min / median / max and the number of samples per class, one column group per BUILD_DIR (default
build/cortex-m3; e.g. build/cortex-m3 build/cortex-m4). The QEMU machine comes from the build's
toolchain file (m3 -> mps2-an385, m4 -> mps2-an386) unless --machine is given.

The module bench protocol (one line each, fsw/target/bench/bench_common.h for the shared parts):
    bench <module> 1 cpuid <hex>            first line
    cal <N> <phase> <value> / tick <N> <t>  calibration (bench_calibrate): must be N + 4 at every phase
    class <name> <description...>           the sample classes, in report order (optional)
    twin <value> 0                          bracket value of the null twin (informative)
    m <class> <sub> <insns> [<index>]       one measured sample: class, sub-class ("-" for none),
                                            instructions, and where it was taken (e.g. the tick)
    sum <key> <value>                       a summary figure, copied into the report
    err <text...>                           a check inside the image failed
    end                                     last line (a missing one means a truncated run)
Checks (exit status 1 if any fails; the figures are a report, never a test): calibration exact at
every phase, no err line, an end line, every bench_null_* a single 16-bit instruction, and --reps
runs printing identical samples (QEMU icount is deterministic).
"""
import argparse
import datetime
import json
import os
import sys

from tools.bench import provenance
from tools.bench.fx_insn import MACHINES, cache_value, fmt_med, sh, stats, ticks_per_insn, tool_version

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
QEMU_RUN = os.path.join(ROOT, "tools", "qemu-run.sh")
TARGET_REL = os.path.join("fsw", "target")


def missions():
    with open(os.path.join(ROOT, "missions.json"), encoding="utf-8") as f:
        return json.load(f)["missions"]


def module_of(name):
    """Module folder name of a module name or prefix (missions.json)."""
    for m in missions():
        if name in (m["module"], m["prefix"], m["mission"].lower()):
            return m["module"]
    sys.exit(f"module_insn: no module or prefix '{name}' in missions.json")


def elf_of(build, module):
    return os.path.join(build, TARGET_REL, f"{module}_bench.elf")


def benches_in(build):
    d = os.path.join(build, TARGET_REL)
    try:
        names = sorted(os.listdir(d))
    except OSError:
        return []
    return [n[:-len("_bench.elf")] for n in names if n.endswith("_bench.elf") and n != "fx_bench.elf"]


def board_of(build, machine):
    tc = os.path.basename(cache_value(build, "CMAKE_TOOLCHAIN_FILE"))
    name = next((b for b in MACHINES if b in tc), None)
    if machine:
        return name or machine, machine
    if not name:
        sys.exit(f"module_insn: cannot tell the board of {build} (toolchain '{tc}'); pass --machine")
    return name, MACHINES[name]


def run_bench(elf, machine):
    env = dict(os.environ, QEMU_ARGS="-icount shift=3", QEMU_TIMEOUT=os.environ.get("QEMU_TIMEOUT", "300"))
    r = sh([QEMU_RUN, machine, elf], env=env)
    if r.returncode != 0:
        sys.exit(f"module_insn: {elf} on {machine} exited {r.returncode}:\n{r.stdout[-2000:]}")
    return r.stdout


def parse(out):
    d = {"cpuid": None, "module": None, "cal": [], "tick": {}, "classes": {}, "twin": None,
         "m": [], "sum": {}, "err": [], "end": False}
    for line in out.splitlines():
        p = line.split()
        if not p:
            continue
        if p[0] == "bench" and len(p) >= 5:
            d["module"], d["cpuid"] = p[1], p[4]
        elif p[0] == "cal" and len(p) == 4:
            d["cal"].append(tuple(int(x) for x in p[1:]))
        elif p[0] == "tick" and len(p) == 3:
            d["tick"].setdefault(int(p[1]), []).append(int(p[2]))
        elif p[0] == "class" and len(p) >= 2:
            d["classes"][p[1]] = " ".join(p[2:])
        elif p[0] == "twin" and len(p) >= 2:
            d["twin"] = int(p[1])
        elif p[0] == "m" and len(p) >= 4:
            d["m"].append((p[1], p[2], int(p[3]), p[4] if len(p) > 4 else ""))
        elif p[0] == "sum" and len(p) == 3:
            d["sum"][p[1]] = int(p[2])
        elif p[0] == "err":
            d["err"].append(" ".join(p[1:]))
        elif p[0] == "end":
            d["end"] = True
    return d


def null_twin_sizes(build, elf):
    nm = cache_value(build, "CMAKE_NM") or "arm-none-eabi-nm"
    r = sh([nm, "-S", elf])
    sizes = {}
    for line in r.stdout.splitlines():
        p = line.split()
        if len(p) == 4 and p[3].startswith("bench_null_"):
            sizes[p[3]] = int(p[1], 16)
    return sizes


def check(d, nulls):
    errs = [f"image: {e}" for e in d["err"]]
    if not d["end"]:
        errs.append("bench output truncated (no 'end' line)")
    bad = [c for c in d["cal"] if c[2] != c[0] + 4]
    if not d["cal"] or bad:
        errs.append(f"calibration: expected N+4 at every phase, got {bad[:5]}")
    if not d["m"]:
        errs.append("no samples ('m' lines)")
    if not nulls or any(v != 2 for v in nulls.values()):
        errs.append(f"null twins must be one 16-bit instruction each: {nulls}")
    return errs


def summarise(samples):
    """{class: {"all": stats + where, "sub": {sub: stats}}} in order of first appearance."""
    out = {}
    for cls, sub, n, where in samples:
        c = out.setdefault(cls, {"values": [], "where": [], "sub": {}})
        c["values"].append(n)
        c["where"].append(where)
        c["sub"].setdefault(sub, []).append(n)
    res = {}
    for cls, c in out.items():
        v = c["values"]
        s = stats(v)
        s["min_at"] = c["where"][v.index(s["min"])]
        s["max_at"] = c["where"][v.index(s["max"])]
        res[cls] = {"all": s, "sub": {k: stats(x) for k, x in sorted(c["sub"].items())}}
    return res


def report_one(module, builds, a):
    report = {"module": module,
              "generated": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
              "commit": provenance.commit(), "machine": provenance.machine_description(),
              "qemu": tool_version([os.environ.get("QEMU", "qemu-system-arm"), "--version"]),
              "method": "qemu -icount shift=3; SysTick 25 MHz (1 tick = 5 insns); each sample is "
                        "bracket5(wrapper) - bracket5(null twin) + 1 (exact when the image repeats the "
                        "call identically, see its source); counts from the function's entry through "
                        "its return",
              "boards": {}}
    failed, order, classes = [], [], {}
    for build in builds:
        elf = elf_of(build, module)
        if not os.path.isfile(elf):
            sys.exit(f"module_insn: {elf} not found: build the cortex-m preset first (cmake --build {build}); "
                     f"a module gets it by having fsw/{module}/bench/<prefix or {module}>_bench.c")
        board, machine = board_of(build, a.machine)
        outs = [run_bench(elf, machine) for _ in range(max(1, a.reps))]
        d = parse(outs[0])
        nulls = null_twin_sizes(build, elf)
        errs = check(d, nulls)
        same = all(parse(o)["m"] == d["m"] for o in outs[1:])
        if not same:
            errs.append("runs disagree: counts are not deterministic")
        summ = summarise(d["m"])
        for c in list(d["classes"]) + list(summ):
            if c not in order and c in summ:
                order.append(c)
        classes.update(d["classes"])
        report["boards"][board] = {
            "build": os.path.relpath(build, ROOT), "machine": machine, "cpuid": d["cpuid"],
            "elf": os.path.relpath(elf, ROOT),
            "compiler": tool_version([cache_value(build, "CMAKE_C_COMPILER") or "arm-none-eabi-gcc", "--version"]),
            "build_type": cache_value(build, "CMAKE_BUILD_TYPE"),
            "calibration": {"phase_invariant": bool(d["cal"]) and not any(c[2] != c[0] + 4 for c in d["cal"]),
                            "sleds": sorted({c[0] for c in d["cal"]}),
                            "ticks": {str(k): v for k, v in ticks_per_insn(d).items()},
                            "null_twins_single_insn": bool(nulls) and all(v == 2 for v in nulls.values()),
                            "twin_bracket": d["twin"]},
            "repetitions": len(outs), "repeatable": same,
            "classes": summ, "summary": d["sum"], "errors": errs}
        failed += [f"{board}: {e}" for e in errs]
    report["class_descriptions"] = {c: classes.get(c, "") for c in order}

    os.makedirs(a.out_dir, exist_ok=True)
    base = os.path.join(a.out_dir, f"{module}_insn")
    with open(base + ".json", "w", encoding="utf-8") as f:
        json.dump(report, f, indent=1)
        f.write("\n")
    boards = list(report["boards"])
    md = [f"# {module}: instructions per step (QEMU, -icount shift=3)", "",
          f"- generated {report['generated']}, commit `{report['commit']}`",
          f"- host: {report['machine']['cpu']}, {report['machine']['cores']} cores, {report['machine']['os']}",
          f"- {report['qemu']}"]
    for b in boards:
        r = report["boards"][b]
        md.append(f"- {b}: `{r['elf']}` ({r['build_type']}), {r['machine']}, CPUID {r['cpuid']}, {r['compiler']}")
    md += ["", "Instructions from the step's entry through its return, per class of sample; n = samples. "
           "Instructions are not cycles (spec 00 §6.4).", ""]
    head = "| class |" + "".join(f" {b} n | {b} min | {b} median | {b} max |" for b in boards)
    md += [head, "|---|" + "---:|---:|---:|---:|" * len(boards)]

    def cells(st):
        return f" {st['n']} | {st['min']} | {fmt_med(st['median'])} | {st['max']} |"

    for c in order:
        row = f"| {c} |"
        for b in boards:
            cc = report["boards"][b]["classes"].get(c)
            row += " – | – | – | – |" if cc is None else cells(cc["all"])
        md.append(row)
    md += [""]
    for c in order:
        desc = report["class_descriptions"].get(c)
        if desc:
            md.append(f"- **{c}**: {desc}")
    md += ["", "## By sub-class", "", head.replace("| class |", "| class | sub-class |"),
           "|---|---|" + "---:|---:|---:|---:|" * len(boards)]
    for c in order:
        subs = []
        for b in boards:
            for s in report["boards"][b]["classes"].get(c, {}).get("sub", {}):
                if s not in subs:
                    subs.append(s)
        for s in subs:
            row = f"| {c} | `{s}` |"
            for b in boards:
                st = report["boards"][b]["classes"].get(c, {}).get("sub", {}).get(s)
                row += " – | – | – | – |" if st is None else cells(st)
            md.append(row)
    md += ["", "## Where the extremes are (sample index as the image prints it)", ""]
    for b in boards:
        for c in order:
            st = report["boards"][b]["classes"].get(c)
            if st:
                md.append(f"- {b} {c}: min {st['all']['min']} at {st['all']['min_at']}, "
                          f"max {st['all']['max']} at {st['all']['max_at']}")
    md += ["", "## Image summary", ""]
    keys = []
    for b in boards:
        for k in report["boards"][b]["summary"]:
            if k not in keys:
                keys.append(k)
    if keys:
        md += ["| key |" + "".join(f" {b} |" for b in boards), "|---|" + "---:|" * len(boards)]
        for k in keys:
            md.append(f"| {k} |" + "".join(f" {report['boards'][b]['summary'].get(k, '–')} |" for b in boards))
    md += ["", "## Calibration", ""]
    for b in boards:
        r = report["boards"][b]
        c = r["calibration"]
        tk = "; ".join(f"{n} NOPs -> ticks {v['ticks']} ({v['insn_per_tick']:.4f} insn/tick)"
                       for n, v in c["ticks"].items())
        md += [f"- **{b}**: NOP sleds {c['sleds']} measure exactly N + 4 at all 5 tick phases: "
               f"{'yes' if c['phase_invariant'] else 'NO'}; null twins single-instruction: "
               f"{'yes' if c['null_twins_single_insn'] else 'NO'}; twin bracket {c['twin_bracket']}; "
               f"{r['repetitions']} runs identical: {'yes' if r['repeatable'] else 'NO'}.",
               f"  - plain bracket: {tk}."]
        for e in r["errors"]:
            md.append(f"  - **error**: {e}")
    with open(base + ".md", "w", encoding="utf-8") as f:
        f.write("\n".join(md) + "\n")
    print("\n".join(md))
    return failed


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("builds", nargs="*", default=[os.path.join(ROOT, "build", "cortex-m3")])
    ap.add_argument("--module", action="append", default=[],
                    help="module name or prefix (repeatable; default: every module bench of the first build)")
    ap.add_argument("--machine", help="QEMU machine (default: from the build's toolchain)")
    ap.add_argument("--out-dir", default=os.path.join(ROOT, "bench"))
    ap.add_argument("--reps", type=int, default=2, help="runs that must agree (default 2)")
    a = ap.parse_args()
    builds = [os.path.abspath(b) for b in a.builds]
    modules = [module_of(m) for m in a.module] or benches_in(builds[0])
    if not modules:
        sys.exit(f"module_insn: no <module>_bench.elf in {os.path.join(builds[0], TARGET_REL)}")
    failed = []
    for m in modules:
        failed += [f"{m}: {e}" for e in report_one(m, builds, a)]
    if failed:
        print("module_insn: checks failed:\n  " + "\n  ".join(failed), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
