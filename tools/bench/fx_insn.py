#!/usr/bin/env python3
"""Instruction counts of the fx kernels on the emulated Cortex-M (spec 00 §6.4, §9).

    .venv/bin/python -m tools.bench.fx_insn [BUILD_DIR ...] [--out-dir bench] [--reps 5]
    (or .venv/bin/python tools/bench/fx_insn.py ...: the project venv has the `tools` package)

Builds nothing: it runs <BUILD_DIR>/fsw/target/fx_bench.elf (from fsw/target/bench/fx_bench.c,
part of every cortex-m3/m4 build) under `qemu-system-arm -icount shift=3` through
tools/qemu-run.sh, and writes <out-dir>/fx_insn.md and <out-dir>/fx_insn.json. BUILD_DIR
defaults to build/cortex-m3; give several (e.g. build/cortex-m3 build/cortex-m4) for one column
per board. The QEMU machine comes from the build's toolchain file (m3 -> mps2-an385,
m4 -> mps2-an386) unless --machine is given.

Method (details in fx_bench.c): -icount shift=3 advances virtual time 8 ns per instruction and
MPS2's SysTick counts 25 MHz, so 1 tick = 5 instructions. The bench's hand-written bracket
makes the count exact rather than +-5: five identical calls plus 4 NOPs between the two SysTick
reads. This script checks, and the report records:
  * calibration: NOP sleds of N = 0..1000 give exactly N + 4 at all five tick phases;
  * ticks per instruction: a plain bracket around 10 000 / 50 000 NOPs gives N / 5 ticks;
  * every null twin (bench_null_*) is a single 16-bit instruction (nm size 2);
  * cross-check: QEMU's own per-instruction trace (-singlestep -d exec,nochain -dfilter) of
    fx_crc32, a leaf, must equal the SysTick figure times the number of calls;
  * repeatability: --reps runs must print identical counts (QEMU icount is deterministic).
Nothing here is pass/fail for CTest; the script exits non-zero only if a check fails.

Impulse scheduler (spec 50 §4.7): the report compares the imp_* entries with the spec's regression
budgets and flags the entries over budget (never a failure). One Newton iteration is derived per
sample as imp_attempt(max_iter 1) - imp_attempt(max_iter 0) from the same start: the two runs
share every instruction except one solve + update + evaluation (trig of every switching time,
residual, Jacobian).
"""
import argparse
import datetime
import json
import os
import statistics
import subprocess
import sys
import tempfile

from tools.bench import provenance

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
QEMU_RUN = os.path.join(ROOT, "tools", "qemu-run.sh")
ELF_REL = os.path.join("fsw", "target", "fx_bench.elf")
CALLS_PER_BRACKET = 5
MACHINES = {"cortex-m3": "mps2-an385", "cortex-m4": "mps2-an386"}
IMP_WORST_ITERS = 240   # spec 50 §4.7: warm + rule + 16 (x-y), warm + rule + 4 (z), 10 iterations each


def sh(cmd, **kw):
    return subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, **kw)


def cache_value(build, key):
    try:
        with open(os.path.join(build, "CMakeCache.txt"), encoding="utf-8") as f:
            for line in f:
                if line.startswith(key + ":"):
                    return line.split("=", 1)[1].strip()
    except OSError:
        pass
    return ""


def board_of(build, machine):
    tc = os.path.basename(cache_value(build, "CMAKE_TOOLCHAIN_FILE"))
    name = next((b for b in MACHINES if b in tc), None)
    if machine:
        return name or machine, machine
    if not name:
        sys.exit(f"fx_insn: cannot tell the board of {build} (toolchain '{tc}'); pass --machine")
    return name, MACHINES[name]


def run_bench(elf, machine):
    env = dict(os.environ, QEMU_ARGS="-icount shift=3", QEMU_TIMEOUT=os.environ.get("QEMU_TIMEOUT", "300"))
    r = sh([QEMU_RUN, machine, elf], env=env)
    if r.returncode != 0:
        sys.exit(f"fx_insn: {elf} on {machine} exited {r.returncode}:\n{r.stdout[-2000:]}")
    return r.stdout


def parse(out):
    d = {"cal": [], "tick": {}, "k": {}, "call": {}, "imp": {}, "cpuid": None, "empty": None, "end": False}
    for line in out.splitlines():
        p = line.split()
        if not p:
            continue
        if p[0] == "fx_bench" and len(p) >= 4:
            d["cpuid"] = p[3]
        elif p[0] == "cal" and len(p) == 4:
            d["cal"].append(tuple(int(x) for x in p[1:]))
        elif p[0] == "tick" and len(p) == 3:
            d["tick"].setdefault(int(p[1]), []).append(int(p[2]))
        elif p[0] == "empty" and len(p) == 2:
            d["empty"] = int(p[1])
        elif p[0] == "k" and len(p) == 5:
            d["k"].setdefault(p[1], []).append(int(p[3]))
            d["call"].setdefault(p[1], []).append(int(p[4]))
        elif p[0] == "imp" and len(p) == 8:
            d["imp"].setdefault(p[1], []).append({"sample": int(p[2]), "iters_total": int(p[3]), "outcome": int(p[4]),
                                                  "how_xy": int(p[5]), "how_z": int(p[6]), "pattern": int(p[7])})
        elif p[0] == "end":
            d["end"] = True
    return d


def check(d):
    errs = []
    if not d["end"]:
        errs.append("bench output truncated (no 'end' line)")
    bad = [c for c in d["cal"] if c[2] != c[0] + 4]
    if not d["cal"] or bad:
        errs.append(f"calibration: expected N+4 at every phase, got {bad[:5]}")
    if d["empty"] != 4:
        errs.append(f"empty wrapper bracket is {d['empty']}, expected 4")
    return errs


def ticks_per_insn(d):
    t0 = d["tick"].get(0, [])
    res = {}
    for n in (10000, 50000):
        tn = d["tick"].get(n, [])
        if tn and t0:
            dt = [a - b for a, b in zip(tn, t0)]
            res[n] = {"ticks": tn, "insn_per_tick": n / statistics.mean(dt)}
    return res


def nm_symbols(build):
    nm = cache_value(build, "CMAKE_NM") or "arm-none-eabi-nm"
    r = sh([nm, "-S", os.path.join(build, ELF_REL)])
    syms = {}
    for line in r.stdout.splitlines():
        p = line.split()
        if len(p) == 4:
            syms[p[3]] = (int(p[0], 16), int(p[1], 16))
    return syms


def nm_range(build, sym):
    s = nm_symbols(build).get(sym)
    return None if s is None else (s[0], s[0] + s[1] - 1)


def null_twin_sizes(build):
    return {k: v[1] for k, v in nm_symbols(build).items() if k.startswith("bench_null_")}


def trace_count(build, machine, sym):
    """Instructions QEMU executes inside `sym` (a leaf), counted by QEMU's own exec trace."""
    rng = nm_range(build, sym)
    if rng is None:
        return None, f"{sym} not found by nm"
    with tempfile.TemporaryDirectory() as td:
        log = os.path.join(td, "trace.log")
        env = dict(os.environ, QEMU_ARGS=f"-singlestep -d exec,nochain -dfilter 0x{rng[0]:x}..0x{rng[1]:x} -D {log}")
        r = sh([QEMU_RUN, machine, os.path.join(build, ELF_REL)], env=env)
        if r.returncode != 0 or not os.path.exists(log):
            return None, f"trace run failed ({r.returncode})"
        n = 0
        with open(log, encoding="utf-8", errors="replace") as f:
            for line in f:
                if line.startswith("Trace "):
                    n += 1
        return n, ""


def stats(v):
    return {"n": len(v), "min": min(v), "median": statistics.median(v), "max": max(v)}


def imp_budgets(d):
    """Spec 50 §4.7 budget rows from the imp_* entries: (item, budget, measured stats or None, note)."""
    k, info = d["k"], d["imp"]
    if "imp_solve_example" not in k:
        return []
    rows = []

    def diff(a, b):
        return [x - y for x, y in zip(k.get(a, []), k.get(b, []))]

    it_xy, it_z = diff("imp_attempt_xy_max1", "imp_attempt_xy_max0"), diff("imp_attempt_z_max1", "imp_attempt_z_max0")
    rows.append(("angle -> derived trig (`imp_trig`, sigma in [0, 2.2])", 250, stats(k["imp_trig"]),
                 "two paths: sigma - sin sigma by series below 0.5 (max) or from sin (min)"))
    rows.append(("Newton iteration, x-y (4 angles, residual, 4x4 solve)", 2500, stats(it_xy) if it_xy else None,
                 "imp_attempt max_iter 1 - max_iter 0, 32 nominal states"))
    rows.append(("Newton iteration, z", 800, stats(it_z) if it_z else None, "the same, z subsystem"))
    ex = k["imp_solve_example"]
    exi = info.get("imp_solve_example", [{}])[0]
    rows.append(("nominal plan: `imp_solve`, paper's example", 30000, stats(ex),
                 f"{exi.get('iters_total', '?')} Newton iterations in the accepted attempts, how x-y/z "
                 f"{exi.get('how_xy', '?')}/{exi.get('how_z', '?')} (2 = rule)"))
    nom, ninfo = k.get("imp_solve_nominal", []), info.get("imp_solve_nominal", [])
    rule = [v for v, m in zip(nom, ninfo) if m["how_xy"] == 2 and m["how_z"] == 2]
    srch = [v for v, m in zip(nom, ninfo) if not (m["how_xy"] == 2 and m["how_z"] == 2)]
    if rule:
        rows.append((f"nominal plan: `imp_solve`, random nominal states, rule valid ({len(rule)} of {len(nom)})",
                     30000, stats(rule), "+-5 km / +-1 m/s, bench RNG"))
    if srch:
        rows.append((f"nominal box, rule invalid -> search ({len(srch)} of {len(nom)})", None, stats(srch),
                     "no separate budget; counts towards the worst case"))
    rnd = k.get("imp_round_best_nominal")
    if rnd:
        rows.append(("best rounding `imp_round_best` (part of the nominal plan)", None, stats(rnd),
                     "nominal states, whole-step grid"))
    if rule and rnd:
        rows.append(("nominal plan: solve (rule valid) + rounding, min/median/max added", 30000,
                     {"n": len(rule), "min": min(rule) + min(rnd),
                      "median": statistics.median(rule) + statistics.median(rnd), "max": max(rule) + max(rnd)},
                     "the calibration update runs in a nav step (imp_step_nav row), not in the plan"))
    for name, what in (("imp_solve_search_all", "hard wide-box states, every pattern tried"),
                       ("imp_solve_search_all_rtol0", "the same with r_tol = 0 (attempts run to max_iter)")):
        if name in k:
            its = [m["iters_total"] for m in info.get(name, [])]
            per = [v / m for v, m in zip(k[name], its) if m]
            rows.append((f"worst-case plan: `imp_solve`, {what}", 600000, stats(k[name]),
                         f"{min(its)}-{max(its)} Newton iterations; {min(per):.0f}-{max(per):.0f} instructions per "
                         f"iteration including attempt set-up"))
    if it_xy:
        est = IMP_WORST_ITERS * max(it_xy)
        rows.append((f"worst-case plan, extrapolated: {IMP_WORST_ITERS} x the largest x-y iteration", 600000,
                     {"n": 1, "min": est, "median": est, "max": est}, "estimate, not a measurement"))
    if "imp_step_idle" in k:
        rows.append(("a step with no planning work (timeline, fault monitor): `imp_step_idle`", 1500,
                     stats(k["imp_step_idle"]), "FIRING, 2.6 s into the first burns, no new nav sample"))
    else:
        rows.append(("a step with no planning work (timeline, fault monitor)", 1500, None,
                     "not measured (no imp_step entry)"))
    if "imp_step_nav" in k:
        rows.append(("(a step that takes a new nav sample: `imp_step_nav`)", None, stats(k["imp_step_nav"]),
                     "the same step with an accepted sample: prediction through 3 logged burns, gate, monitor"))
    return rows


def tool_version(cmd):
    try:
        return sh(cmd).stdout.splitlines()[0].strip()
    except (OSError, IndexError):
        return "unknown"


def fmt_med(x):
    return str(int(x)) if float(x).is_integer() else f"{x:.1f}"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("builds", nargs="*", default=[os.path.join(ROOT, "build", "cortex-m3")])
    ap.add_argument("--machine", help="QEMU machine (default: from the build's toolchain file)")
    ap.add_argument("--out-dir", default=os.path.join(ROOT, "bench"))
    ap.add_argument("--reps", type=int, default=5, help="runs that must agree (default 5)")
    ap.add_argument("--no-trace-check", action="store_true", help="skip the QEMU exec-trace cross-check")
    a = ap.parse_args()

    report = {"generated": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
              "commit": provenance.commit(), "machine": provenance.machine_description(),
              "qemu": tool_version([os.environ.get("QEMU", "qemu-system-arm"), "--version"]),
              "method": "qemu -icount shift=3; SysTick 25 MHz (1 tick = 5 insns); bracket of 5 identical "
                        "calls + 4 NOPs makes counts exact; kernel = entry..return inclusive; "
                        "call = kernel + argument setup and result stores",
              "boards": {}}
    failed = []
    order = []
    for build in a.builds:
        build = os.path.abspath(build)
        elf = os.path.join(build, ELF_REL)
        if not os.path.isfile(elf):
            sys.exit(f"fx_insn: {elf} not found: build the cortex-m preset first "
                     f"(cmake --workflow --preset cortex-m3, or cmake --build {build})")
        board, machine = board_of(build, a.machine)
        outs = [run_bench(elf, machine) for _ in range(max(1, a.reps))]
        d = parse(outs[0])
        errs = check(d)
        nulls = null_twin_sizes(build)
        if not nulls or any(v != 2 for v in nulls.values()):
            errs.append(f"null twins must be one 16-bit instruction each: {nulls}")
        same = all(parse(o)["k"] == d["k"] for o in outs[1:])
        if not same:
            errs.append("runs disagree: counts are not deterministic")
        xcheck = {"skipped": True}
        if not a.no_trace_check and "fx_crc32_64B" in d["k"]:
            n, why = trace_count(build, machine, "fx_crc32")
            expect = CALLS_PER_BRACKET * sum(d["k"]["fx_crc32_64B"])
            xcheck = {"symbol": "fx_crc32", "trace_insns": n, "systick_insns": expect,
                      "calls": CALLS_PER_BRACKET * len(d["k"]["fx_crc32_64B"]), "note": why}
            if n is not None and n != expect:
                errs.append(f"trace cross-check: QEMU trace {n} insns in fx_crc32, SysTick method {expect}")
        kernels = {k: {"kernel": stats(v), "call": stats(d["call"][k]), "samples": v}
                   for k, v in d["k"].items()}
        for k in d["k"]:
            if k not in order:
                order.append(k)
        report["boards"][board] = {
            "build": os.path.relpath(build, ROOT), "machine": machine, "cpuid": d["cpuid"],
            "compiler": tool_version([cache_value(build, "CMAKE_C_COMPILER") or "arm-none-eabi-gcc", "--version"]),
            "build_type": cache_value(build, "CMAKE_BUILD_TYPE"),
            "calibration": {"phase_invariant": not any(c[2] != c[0] + 4 for c in d["cal"]),
                            "sleds": sorted({c[0] for c in d["cal"]}),
                            "ticks": {str(k): v for k, v in ticks_per_insn(d).items()},
                            "null_twins_single_insn": bool(nulls) and all(v == 2 for v in nulls.values())},
            "cross_check": xcheck, "repetitions": len(outs), "repeatable": same,
            "kernels": kernels, "imp_solutions": d["imp"],
            "imp_budgets": [{"item": it, "budget": bu, "measured": st, "note": no,
                             "over": bool(bu is not None and st is not None and st["max"] > bu)}
                            for it, bu, st, no in imp_budgets(d)],
            "errors": errs}
        failed += [f"{board}: {e}" for e in errs]

    os.makedirs(a.out_dir, exist_ok=True)
    with open(os.path.join(a.out_dir, "fx_insn.json"), "w", encoding="utf-8") as f:
        json.dump(report, f, indent=1)
        f.write("\n")
    boards = list(report["boards"])
    md = ["# fx kernel instruction counts (QEMU, -icount shift=3)", "",
          f"- generated {report['generated']}, commit `{report['commit']}`",
          f"- host: {report['machine']['cpu']}, {report['machine']['cores']} cores, {report['machine']['os']}",
          f"- {report['qemu']}"]
    for b in boards:
        r = report["boards"][b]
        md.append(f"- {b}: `{r['build']}` ({r['build_type']}), {r['machine']}, CPUID {r['cpuid']}, {r['compiler']}")
    md += ["", "Instructions per call, over varied inputs (random of varied magnitude plus edge cases: "
           "saturation, divide by zero, domain errors, a singular system). **kernel** counts from the "
           "kernel's first instruction through its return; **call** adds the argument setup and "
           "result stores of a typical caller. Instructions are not cycles (spec 00 §6.4).", ""]
    head = "| kernel | n |" + "".join(f" {b} min | {b} median | {b} max | {b} call median |" for b in boards)
    md += [head, "|---|---:|" + "---:|---:|---:|---:|" * len(boards)]
    for k in order:
        row = f"| `{k}` |"
        n = next((report["boards"][b]["kernels"][k]["kernel"]["n"] for b in boards
                  if k in report["boards"][b]["kernels"]), 0)
        row += f" {n} |"
        for b in boards:
            kk = report["boards"][b]["kernels"].get(k)
            if kk is None:
                row += " – | – | – | – |"
            else:
                s = kk["kernel"]
                row += f" {s['min']} | {fmt_med(s['median'])} | {s['max']} | {fmt_med(kk['call']['median'])} |"
        md.append(row)
    if any(report["boards"][b]["imp_budgets"] for b in boards):
        md += ["", "## Impulse scheduler against spec 50 §4.7 (regression budgets, instructions)", "",
               "Over-budget entries are flagged, never failed (spec 00 §9).", ""]
        for b in boards:
            rows = report["boards"][b]["imp_budgets"]
            if not rows:
                continue
            md += [f"**{b}**", "", "| item | budget | min | median | max | status | note |",
                   "|---|---:|---:|---:|---:|---|---|"]
            for r in rows:
                st, bu = r["measured"], r["budget"]
                vals = " – | – | – |" if st is None else f" {st['min']} | {fmt_med(st['median'])} | {st['max']} |"
                if st is None or bu is None:
                    status = "–"
                elif st["max"] > bu:
                    status = f"**OVER** ({st['max'] / bu:.1f}x)"
                else:
                    status = "ok"
                md.append(f"| {r['item']} | {bu if bu is not None else '–'} |{vals} {status} | {r['note']} |")
            md.append("")
    md += ["", "## Calibration", ""]
    for b in boards:
        r = report["boards"][b]
        c = r["calibration"]
        tk = "; ".join(f"{n} NOPs -> ticks {v['ticks']} ({v['insn_per_tick']:.4f} insn/tick)"
                       for n, v in c["ticks"].items())
        x = r["cross_check"]
        xs = ("skipped" if x.get("skipped") else
              f"QEMU exec trace counted {x['trace_insns']} instructions in `fx_crc32` over {x['calls']} calls; "
              f"SysTick method {x['systick_insns']}" + (" (equal)" if x["trace_insns"] == x["systick_insns"] else " (DIFFERENT)"))
        md += [f"- **{b}**: NOP sleds {c['sleds']} measure exactly N + 4 at all 5 tick phases: "
               f"{'yes' if c['phase_invariant'] else 'NO'}; null twins single-instruction: "
               f"{'yes' if c['null_twins_single_insn'] else 'NO'}; {r['repetitions']} runs identical: "
               f"{'yes' if r['repeatable'] else 'NO'}.",
               f"  - plain bracket: {tk}.",
               f"  - cross-check: {xs}."]
        for e in r["errors"]:
            md.append(f"  - **error**: {e}")
    with open(os.path.join(a.out_dir, "fx_insn.md"), "w", encoding="utf-8") as f:
        f.write("\n".join(md) + "\n")
    print("\n".join(md))
    if failed:
        print("fx_insn: checks failed:\n  " + "\n  ".join(failed), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
