"""RAM of fsw_t, flash of libfsw.a and worst stack of fsw_step on Cortex-M3, per mission build
configuration (missions.json, CMake option FSW_MISSIONS). A benchmark, never a test.

    .venv/bin/python -m tools.bench.mission_sizes [--configs all,DETUMBLE,RENDEZVOUS] [--out FILE.md]
        [--src REPO]   (another tree, e.g. an older commit's worktree: only its default build)

For each configuration it configures build/cfg-<name> with the cortex-m3 toolchain (MinSizeRel,
as the preset), builds the flight library only, and reads:
  sizeof(fsw_t)   a probe translation unit compiled with fsw_exec.c's own flags (-S), whose one
                  constant is sizeof(fsw_t)
  flash           code + rodata + data of every libfsw.a member (arm-none-eabi-size -A), boot
                  tables included; an archive, so unreferenced code counts too
  worst stack     tools/stack_sum.py on the library, root fsw_step (the static whole-call bound)
"""
import argparse
import json
import os
import re
import shlex
import subprocess
import sys
import tempfile


ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PROBE = "#include \"fsw_exec.h\"\nconst unsigned int fsw_sizeof_fsw_t = (unsigned int)sizeof(fsw_t);\n"


def run(cmd, **kw):
    return subprocess.run(cmd, check=True, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, **kw).stdout


def configure_build(src, build, missions):
    args = ["cmake", "-S", src, "-B", build, "-G", "Ninja",
            "-DCMAKE_TOOLCHAIN_FILE=%s/cmake/toolchain-cortex-m3.cmake" % src, "-DCMAKE_BUILD_TYPE=MinSizeRel",
            "-DFSW_HOST_BUILD_DIR=%s/build/host" % src]
    if missions is not None:
        args.append("-DFSW_MISSIONS=%s" % missions)
    run(args)
    run(["cmake", "--build", build, "--target", "fsw", "-j", "2"])


def sizeof_fsw_t(build):
    db = json.load(open(os.path.join(build, "compile_commands.json")))
    entry = next(e for e in db if e["file"].endswith("fsw_exec.c"))
    args = entry["arguments"] if "arguments" in entry else shlex.split(entry["command"])
    with tempfile.TemporaryDirectory() as tmp:
        probe = os.path.join(tmp, "probe.c")
        open(probe, "w").write(PROBE)
        out, skip = [], False
        for a in args:
            if skip:
                skip = False
                continue
            if a in ("-o", "-MF", "-MT", "-c"):
                skip = a != "-c"
                continue
            if a.endswith("fsw_exec.c") or a.startswith(("-fstack-usage", "-fcallgraph-info", "-MD", "-Wstack-usage")):
                continue
            out.append(a)
        asm = run(out + ["-S", probe, "-o", "-"], cwd=entry["directory"])
    m = re.search(r"fsw_sizeof_fsw_t:\s*\n\s*\.(?:word|4byte)\s+(\d+)", asm)
    if not m:
        raise SystemExit("mission_sizes: could not read sizeof(fsw_t) from the probe")
    return int(m.group(1))


def flash(build):
    text = run(["arm-none-eabi-size", "-A", os.path.join(build, "fsw", "libfsw.a")])
    total = 0
    for line in text.splitlines():
        f = line.split()
        if len(f) >= 2 and f[1].isdigit() and re.match(r"^\.(text|rodata|data)", f[0]):
            total += int(f[1])
    return total


def worst_stack(src, build):
    lib = os.path.join(build, "fsw", "libfsw.a")
    objdir = os.path.join(build, "fsw", "CMakeFiles", "fsw.dir")
    js = os.path.join(build, "mission_sizes_stack.json")
    subprocess.run([sys.executable, os.path.join(src, "tools", "stack_sum.py"), "--json", js,
                    "--lib", "%s=%s" % (lib, objdir)], check=True, stdout=subprocess.DEVNULL)
    for r in json.load(open(js))["roots"]:
        if r["function"] == "fsw_step":
            return r["worst"], r["path"]
    raise SystemExit("mission_sizes: no fsw_step in the stack report")


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m tools.bench.mission_sizes", description=__doc__.split("\n")[0])
    ap.add_argument("--configs", default="all,DETUMBLE,RENDEZVOUS",
                    help="comma-separated FSW_MISSIONS values (a build of one mission is its name)")
    ap.add_argument("--src", default=ROOT, help="source tree (default: this one)")
    ap.add_argument("--label", default=None, help="column label of this tree (default: its commit)")
    ap.add_argument("--out", help="also write the markdown table here")
    a = ap.parse_args(argv)
    src = os.path.abspath(a.src)
    legacy = not os.path.exists(os.path.join(src, "missions.json"))
    configs = [None] if legacy else [c.strip() for c in a.configs.split(",") if c.strip()]
    label = a.label or os.path.basename(src)
    rows = []
    for c in configs:
        name = "legacy" if c is None else c.lower()
        build = os.path.join(src, "build", "cfg-" + name)
        configure_build(src, build, c)
        st, path = worst_stack(src, build)
        rows.append((c or "all (no registry)", sizeof_fsw_t(build), flash(build), st, " -> ".join(path[:4]) + " ..."))
        print("%-20s sizeof(fsw_t) %6d B  flash %6d B  fsw_step stack %4d B" % rows[-1][:4], file=sys.stderr)
    lines = ["| build (%s) | sizeof(fsw_t) [B] | libfsw.a flash [B] | fsw_step worst stack [B] | deepest path |" % label,
             "|---|---:|---:|---:|---|"]
    lines += ["| %s | %d | %d | %d | %s |" % r for r in rows]
    text = "\n".join(lines) + "\n"
    print(text)
    if a.out:
        open(a.out, "w").write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
