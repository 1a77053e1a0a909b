#!/usr/bin/env python3
"""PIL benchmark report (spec 00 §9; issue 16 item 6): every registered mission's PIL scenario flown
on the emulated boards, one command.

    .venv/bin/python -m tools.bench.pil_report [BUILD_DIR ...] [--host build/host] [--full]
                                               [--mission NAME ...] [--out-dir bench]

For each Cortex-M BUILD_DIR (default build/cortex-m3 build/cortex-m4, those that exist) and each
mission with a 'pil' entry in missions.json (the scenario and reduced duration its PIL test flies;
--full: the scenario's whole duration) it runs

    <host>/hil_host/sil/sil run --scenario S --duration T --pil <build>/fsw/target/fsw_pil.elf
        --pil-machine <board> --compare-sil --pil-insn insn.csv --summary-json summary.json

and reports, per mission and board: fsw_step instructions (min / median / max over every step, the
SysTick bracket under -icount shift=3: executive + module + telemetry), the painted stack
high-water mark beside the image's static worst path (tools/stack_sum.py over the image's call
graphs, the CTest lint_stack_sum_pil report), PIL steps/s (wall clock, this machine: QEMU's UART
is the bottleneck, about 0.1 ms a byte), the link budget (bytes a step both ways, the 8N1 rate that
needs at the mission's period, against 921 600 baud) and whether the streams equal SIL's. Plus the
board image's size (arm-none-eabi-size: text, data, bss). Writes <out-dir>/pil_report.md and
<out-dir>/pil_report.json with the machine and commit. Instruction counts are deterministic;
steps/s is one wall-clock run (a report, never a test). Exit 1 when a run fails or its streams differ.
"""
import argparse
import csv
import datetime
import json
import os
import subprocess
import sys
import tempfile

import numpy as np

from tools.bench import provenance
from tools.bench.fx_insn import cache_value

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
BOARDS = {"cortex-m3": "mps2-an385", "cortex-m4": "mps2-an386"}


def board_of(build):
    """(name, QEMU machine) of a Cortex-M build, from its toolchain file."""
    tc = os.path.basename(cache_value(build, "CMAKE_TOOLCHAIN_FILE"))
    for name, machine in BOARDS.items():
        if name in tc:
            return name, machine
    sys.exit("pil_report: %s is not a Cortex-M build (toolchain '%s')" % (build, tc))


def pil_missions(names):
    with open(os.path.join(ROOT, "missions.json"), encoding="utf-8") as f:
        ms = [m for m in json.load(f)["missions"] if "pil" in m]
    if names:
        ms = [m for m in ms if m["mission"] in names or m["module"] in names]
    return ms


def image_size(build):
    elf = os.path.join(build, "fsw", "target", "fsw_pil.elf")
    out = subprocess.run(["arm-none-eabi-size", "-A", elf], stdout=subprocess.PIPE, text=True, check=True).stdout
    sec = {}
    for line in out.splitlines():
        p = line.split()
        if len(p) >= 2 and p[0].startswith(".") and p[1].isdigit():
            sec[p[0]] = int(p[1])
    text = sum(v for k, v in sec.items() if k in (".vectors", ".text", ".ARM.extab", ".ARM.exidx"))
    return {"text": text, "rodata": sec.get(".rodata", 0), "data": sec.get(".data", 0), "bss": sec.get(".bss", 0)}


def static_stack(build):
    """The image's static worst path (tools/stack_sum.py, as the CTest lint_stack_sum_pil runs it)."""
    subprocess.run(["ctest", "--test-dir", build, "-R", "^lint_stack_sum_pil$"], stdout=subprocess.DEVNULL,
                   check=False)
    with open(os.path.join(build, "lint_stack_sum_pil.json"), encoding="utf-8") as f:
        roots = {r["function"]: r for r in json.load(f)["roots"]}
    return roots["board_reset_handler"]["worst"]


def fly(host, build, machine, m, full, work):
    scn = os.path.join(ROOT, m["pil"]["scenario"])
    name = m["mission"].lower()
    summ = os.path.join(work, name + ".json")
    insn = os.path.join(work, name + "_insn.csv")
    cmd = [os.path.join(host, "hil_host", "sil", "sil"), "run", "--scenario", scn,
           "--pil", os.path.join(build, "fsw", "target", "fsw_pil.elf"), "--pil-machine", machine,
           "--pil-dir", work, "--compare-sil", "--pil-insn", insn, "--summary-json", summ]
    if not full:
        cmd += ["--duration", str(m["pil"]["duration_s"])]
    p = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, check=False)
    if p.returncode != 0:
        return {"mission": m["mission"], "error": "exit %d: %s" % (p.returncode, p.stderr.strip()[-300:])}
    with open(summ, encoding="utf-8") as f:
        s = json.load(f)
    with open(insn, encoding="utf-8") as f:
        v = np.array([int(r["insn"]) for r in csv.DictReader(f)])
    return {"mission": m["mission"], "scenario": m["pil"]["scenario"], "steps": int(s["plant_steps"]),
            "insn_min": int(v.min()), "insn_median": float(np.median(v)), "insn_max": int(v.max()),
            "stack_painted": int(s["pil_board_stack_used"]), "steps_per_s": float(s["steps_per_s"]),
            "bytes_per_step": float(s["pil_link_bytes_per_step"]),
            "required_baud": float(s["pil_link_required_baud"]), "budget_ok_921600": int(s["pil_link_budget_ok"]),
            "same_streams": int(s["pil_vs_sil_same_streams"]), "retx": int(s["pil_retx"])}


def markdown(rep):
    out = ["# PIL benchmark report", "",
           "Generated %s by `python -m tools.bench.pil_report` on %s (%s, %d cores), commit %s." % (
               rep["date"], rep["machine"]["host"], rep["machine"]["cpu"], rep["machine"]["cores"], rep["commit"]),
           "Instruction counts: SysTick bracket around `fsw_step` under QEMU `-icount shift=3` (deterministic, "
           "resolution 5); not cycles. Steps/s: wall clock, one run, this machine.", ""]
    for b in rep["boards"]:
        out += ["## %s (%s)" % (b["board"], b["machine"]), "",
                "Image `fsw_pil.elf`: text %d B, rodata %d B, data %d B, bss %d B; static worst stack %d B." % (
                    b["size"]["text"], b["size"]["rodata"], b["size"]["data"], b["size"]["bss"], b["static_stack"]),
                "",
                "| mission | steps | insn min | median | max | stack painted / static (B) | steps/s | "
                "bytes/step | 8N1 baud needed | fits 921 600 | streams = SIL |",
                "|---|---|---|---|---|---|---|---|---|---|---|"]
        for r in b["runs"]:
            if "error" in r:
                out.append("| %s | FAILED: %s |" % (r["mission"], r["error"]))
                continue
            out.append("| %s | %d | %d | %.0f | %d | %d / %d | %.0f | %.0f | %.0f | %s | %s |" % (
                r["mission"], r["steps"], r["insn_min"], r["insn_median"], r["insn_max"], r["stack_painted"],
                b["static_stack"], r["steps_per_s"], r["bytes_per_step"], r["required_baud"],
                "yes" if r["budget_ok_921600"] else "no", "yes" if r["same_streams"] else "NO"))
        out.append("")
    return "\n".join(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("builds", nargs="*")
    ap.add_argument("--host", default=os.path.join(ROOT, "build", "host"))
    ap.add_argument("--full", action="store_true", help="the scenarios' whole duration")
    ap.add_argument("--mission", action="append", default=[])
    ap.add_argument("--out-dir", default=os.path.join(ROOT, "bench"))
    a = ap.parse_args()
    builds = a.builds or [os.path.join(ROOT, "build", b) for b in BOARDS
                          if os.path.exists(os.path.join(ROOT, "build", b, "fsw", "target", "fsw_pil.elf"))]
    if not builds:
        sys.exit("pil_report: no Cortex-M build with fsw_pil.elf (cmake --build --preset cortex-m3 --target fsw_pil)")
    rep = {"date": datetime.datetime.now().isoformat(timespec="seconds"), "machine": provenance.machine_description(),
           "commit": provenance.commit(), "full": a.full, "boards": []}
    ok = True
    for build in builds:
        name, machine = board_of(build)
        with tempfile.TemporaryDirectory(prefix="pil-", dir="/tmp") as work:
            runs = []
            for m in pil_missions(a.mission):
                print("pil_report: %s on %s" % (m["mission"], machine), flush=True)
                r = fly(a.host, build, machine, m, a.full, work)
                ok = ok and "error" not in r and r["same_streams"] == 1
                runs.append(r)
        rep["boards"].append({"board": name, "machine": machine, "size": image_size(build),
                              "static_stack": static_stack(build), "runs": runs})
    os.makedirs(a.out_dir, exist_ok=True)
    with open(os.path.join(a.out_dir, "pil_report.json"), "w", encoding="utf-8") as f:
        json.dump(rep, f, indent=1)
    md = markdown(rep)
    with open(os.path.join(a.out_dir, "pil_report.md"), "w", encoding="utf-8") as f:
        f.write(md + "\n")
    print(md)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
