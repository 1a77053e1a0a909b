#!/usr/bin/env python3
"""Self-test of the build-time proofs of spec 00 §4 (CTest label `lint`).

Copies fsw/ into a scratch directory, injects ONE defect, and asserts that the checker meant
to catch it fails with a clear message, while an unmodified copy passes every checker:

  case           defect appended to a flight source      must fail
  clean          none                                    nothing (every check passes)
  double         a `double` local variable               scan_float, guard compile, host and
                                                         M4 -mgeneral-regs-only, nm (soft float)
  float_literal  `if (a > 0.5)`                          scan_float (guard and nm cannot see it)
  malloc         a malloc call in an initialiser         guard compile, nm
  printf         #include <stdio.h> + printf             check_includes, freestanding compile,
                                                         nm (when compiled against newlib)
  global         `int g;`                                nm no-mutable-globals
  recursion      a doubly recursive function             stack_sum (cycle), clang-tidy

The binary checks compile the copy for soft-float Cortex-M3 with arm-none-eabi-gcc WITHOUT the
guard header, so that nm and stack_sum are shown to catch the defect on their own.

Usage: selftest.py --case NAME [--src REPO] [--parts source,binary] [--host-cc gcc]
                   [--arm-cc arm-none-eabi-gcc] [--cflags "FLAGS"] [--workdir DIR] [--keep]
Exit status: 0 every expectation met, 1 an expectation failed, 2 setup error.
"""
import argparse
import glob
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_SRC = os.path.dirname(os.path.dirname(HERE))
DEFAULT_CFLAGS = ("-Wall -Wextra -Wpedantic -Wconversion -Wsign-conversion -Wshadow -Wdouble-promotion "
                  "-Wfloat-equal -Wcast-align -Wstrict-prototypes -Wmissing-prototypes -Wvla -Wundef "
                  "-Werror -ffunction-sections -fdata-sections -fno-common")
M3 = ["-mcpu=cortex-m3", "-mthumb", "-mfloat-abi=soft"]
M4 = ["-mcpu=cortex-m4", "-mthumb", "-mfloat-abi=hard", "-mfpu=fpv4-sp-d16", "-mgeneral-regs-only"]

DEFECTS = {
    "double": """
/* selftest defect: floating-point variable */
int32_t fx_selftest_defect(int32_t a);
int32_t fx_selftest_defect(int32_t a)
{
    double d = (double)a;
    d = d / 3;
    return (int32_t)d;
}
""",
    "float_literal": """
/* selftest defect: floating literal that GCC folds into an integer compare */
int32_t fx_selftest_defect(int32_t a);
int32_t fx_selftest_defect(int32_t a)
{
    int32_t r = 0;
    if (a > 0.5) {
        r = 1;
    }
    return r;
}
""",
    "malloc": """
/* selftest defect: heap allocation in an initialiser */
extern void *malloc(size_t n);
int32_t fx_selftest_defect(int32_t a);
int32_t fx_selftest_defect(int32_t a)
{
    int32_t *p = malloc(sizeof(int32_t));
    *p = a;
    return *p;
}
""",
    "printf": """
/* selftest defect: C library I/O */
#include <stdio.h>
int32_t fx_selftest_defect(int32_t a);
int32_t fx_selftest_defect(int32_t a)
{
    return (int32_t)printf("%ld\\n", (long)a);
}
""",
    "global": """
/* selftest defect: mutable global */
int g;
int32_t fx_selftest_defect(int32_t a);
int32_t fx_selftest_defect(int32_t a)
{
    g = (int)a;
    return (int32_t)g;
}
""",
    "recursion": """
/* selftest defect: recursion (two self-calls, so GCC cannot turn it into a loop) */
uint32_t fx_selftest_defect(uint32_t n);
uint32_t fx_selftest_defect(uint32_t n)
{
    uint32_t r = n;
    if (n > 1u) {
        r = fx_selftest_defect(n - 1u) + fx_selftest_defect(n - 2u);
    }
    return r;
}
""",
}

# check -> expectation per case: ("fail", regex) | ("pass", None) | ("any", why)
EXPECT = {
    "clean": {
        "scan_float": ("pass", None), "check_includes": ("pass", None),
        "guard_compile": ("pass", None), "host_general_regs_only": ("pass", None),
        "m3_freestanding_compile": ("pass", None), "nm_undefined": ("pass", None),
        "nm_globals": ("pass", None), "stack_sum": ("pass", None),
        "m4_general_regs_only": ("pass", None),
    },
    "double": {
        "scan_float": ("fail", r"floating type keyword 'double'"),
        "guard_compile": ("fail", r'attempt to use poisoned "double"'),
        "host_general_regs_only": ("fail", r"SSE register return with SSE disabled"),
        "m4_general_regs_only": ("fail", r"argument of type 'double' not permitted with '-mgeneral-regs-only'"),
        "m3_freestanding_compile": ("pass", None),
        "nm_undefined": ("fail", r"FORBIDDEN undefined symbol '__aeabi_\w*d\w*'.*soft-float"),
    },
    "float_literal": {
        "scan_float": ("fail", r"floating literal '0\.5'"),
        "guard_compile": ("any", "the poison pragma cannot see literals"),
        "m3_freestanding_compile": ("pass", None),
        "nm_undefined": ("any", "GCC folds a > 0.5 into an integer compare"),
    },
    "malloc": {
        "guard_compile": ("fail", r'attempt to use poisoned "malloc"'),
        "m3_freestanding_compile": ("pass", None),
        "nm_undefined": ("fail", r"FORBIDDEN undefined symbol 'malloc'.*heap"),
    },
    "printf": {
        "check_includes": ("fail", r"forbidden system header <stdio\.h>"),
        "m3_freestanding_compile": ("fail", r"stdio\.h: No such file or directory"),
        "m3_newlib_compile": ("pass", None),
        "nm_undefined": ("fail", r"FORBIDDEN undefined symbol 'printf'.*I/O"),
    },
    "global": {
        "m3_freestanding_compile": ("pass", None),
        "nm_globals": ("fail", r"MUTABLE object 'g' in .*nm type B"),
    },
    "recursion": {
        "m3_freestanding_compile": ("pass", None),
        "stack_sum": ("fail", r"recursion \(call cycle\): fx_selftest_defect -> fx_selftest_defect"),
        "clang_tidy": ("fail", r"misc-no-recursion"),
    },
}
SOURCE_CHECKS = ("scan_float", "check_includes", "guard_compile", "host_general_regs_only", "clang_tidy")
INJECT_PREFERENCE = ("fx/fx_crc.c", "fx/fx_core.c")


def run(cmd, cwd=None):
    try:
        res = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                             universal_newlines=True, check=False)
    except OSError as e:
        return 127, "cannot run %s: %s" % (cmd[0], e)
    return res.returncode, res.stdout


class Copy:
    def __init__(self, args, work):
        self.args = args
        self.work = work
        self.fsw = os.path.join(work, "fsw")
        shutil.copytree(os.path.join(args.src, "fsw"), self.fsw,
                        ignore=shutil.ignore_patterns("*.o", "*.obj", "*.ci", "*.su", "__pycache__"))
        # The mission dispatch is generated into a build tree; the copy gets its own, inside the
        # copied fsw/, so that every checker sees the complete flight library.
        rc, out = run([sys.executable, "-B", "-m", "tools.iface", "build", "--missions", "all",
                       "--out", os.path.join(self.fsw, "gen"), "--no-host"], cwd=args.src)
        if rc != 0:
            raise SystemExit("selftest: cannot generate the mission dispatch: %s" % out)
        # The flight library: everything but the board (fsw/target) and the modules' benchmark
        # images (fsw/<m>/bench/, built against the board by fsw/target/CMakeLists.txt).
        self.sources = sorted(p for p in glob.glob(os.path.join(self.fsw, "**", "*.c"), recursive=True)
                              if self._library(p))
        hdr_dirs = {os.path.dirname(p) for p in glob.glob(os.path.join(self.fsw, "**", "*.h"), recursive=True)
                    if self._library(p)}
        self.incs = ["-I" + d for d in sorted(hdr_dirs | {self.fsw})]
        self.guard = os.path.join(self.fsw, "fx", "fx_guard.h")
        self.cflags = shlex.split(args.cflags)
        self.lib = None
        self.injected = None

    def _library(self, path):
        parts = os.path.relpath(path, self.fsw).split(os.sep)
        return parts[0] != "target" and not (len(parts) > 2 and parts[1] == "bench")

    def inject(self, case):
        if case == "clean":
            return None
        target = None
        for rel in INJECT_PREFERENCE:
            if os.path.isfile(os.path.join(self.fsw, rel)):
                target = os.path.join(self.fsw, rel)
                break
        if target is None:
            if not self.sources:
                raise SystemExit("selftest: ERROR: no flight source to inject into")
            target = self.sources[0]
        with open(target, encoding="utf-8") as fh:
            lines = fh.read().count("\n")
        with open(target, "a", encoding="utf-8") as fh:
            fh.write(DEFECTS[case])
        self.injected = target
        return "%s (appended after line %d)" % (os.path.relpath(target, self.work), lines)

    # ------------------------------------------------------------------ source checks
    def scan_float(self):
        return run([sys.executable, os.path.join(self.args.src, "tools", "lint", "scan_float.py"),
                    "--fsw", self.fsw, "--cc", self.args.host_cc])

    def check_includes(self):
        return run([sys.executable, os.path.join(self.args.src, "tools", "lint", "check_includes.py"),
                    "--fsw", self.fsw])

    def _host_compile(self, guard):
        out, rc = [], 0
        for src in self.sources:
            cmd = ([self.args.host_cc, "-std=c99"] + self.cflags + self.incs
                   + (["-include", self.guard] if guard else []) + ["-mgeneral-regs-only",
                   "-c", src, "-o", os.devnull])
            r, o = run(cmd)
            if r != 0:
                rc = r
                out.append(o)
        return rc, "".join(out) or "compiled %d sources" % len(self.sources)

    def guard_compile(self):
        """The real host compile line: -include fx_guard.h -mgeneral-regs-only."""
        return self._host_compile(True)

    def host_general_regs_only(self):
        """Host compile with -mgeneral-regs-only but no guard header."""
        return self._host_compile(False)

    def clang_tidy(self):
        tidy = shutil.which("clang-tidy-14") or shutil.which("clang-tidy")
        if not tidy:
            return 127, "clang-tidy not found (tools/bootstrap.sh installs clang-tidy)"
        src = self.injected or self.sources[0]
        return run([tidy, "--config-file=" + os.path.join(self.args.src, ".clang-tidy"), "--quiet",
                    "--warnings-as-errors=*", src, "--", "-std=c99"] + self.incs
                   + ["-include", self.guard])

    # ------------------------------------------------------------------ binary checks
    def _arm(self):
        cc = shutil.which(self.args.arm_cc)
        if not cc:
            raise RuntimeError("%s not found (tools/bootstrap.sh installs gcc-arm-none-eabi)" % self.args.arm_cc)
        return cc

    def _arm_tool(self, name):
        rc, out = run([self._arm(), "-print-prog-name=" + name])
        return out.strip() if rc == 0 and out.strip() else "arm-none-eabi-" + name

    def _m3_build(self, freestanding):
        cc = self._arm()
        objdir = os.path.join(self.work, "obj-m3")
        shutil.rmtree(objdir, ignore_errors=True)
        os.makedirs(objdir)
        flags = M3 + ["-Os", "-std=c99"] + self.cflags + self.incs + ["-ffreestanding",
                "-fstack-usage", "-fcallgraph-info=su", "-Wstack-usage=256"]
        if self.injected:
            flags.append("-Wno-error")      # the defect itself may warn; its binary is what we check
        if freestanding:
            inc = run([cc, "-print-file-name=include"])[1].strip()
            incf = run([cc, "-print-file-name=include-fixed"])[1].strip()
            flags += ["-nostdinc", "-isystem", inc, "-isystem", incf]
        objs, out = [], []
        for src in self.sources:
            rel = os.path.relpath(src, self.fsw)
            obj = os.path.join(objdir, rel + ".obj")
            os.makedirs(os.path.dirname(obj), exist_ok=True)
            rc, o = run([cc] + flags + ["-c", src, "-o", obj])
            if rc != 0:
                return rc, o
            out.append(o)
            objs.append(obj)
        lib = os.path.join(objdir, "libfsw.a")
        rc, o = run([self._arm_tool("ar"), "rcs", lib] + objs)
        if rc != 0:
            return rc, o
        self.lib = lib
        return 0, "".join(out) + "built %s from %d sources" % (os.path.relpath(lib, self.work), len(objs))

    def m3_freestanding_compile(self):
        """Cortex-M3 compile as in the cross build: -ffreestanding -nostdinc -isystem <gcc>."""
        return self._m3_build(True)

    def m3_newlib_compile(self):
        """Cortex-M3 compile with newlib headers reachable, so nm can see what libc calls remain."""
        return self._m3_build(False)

    def _need_lib(self):
        if self.lib is None:
            rc, out = self._m3_build(True)
            if rc != 0:
                return "the Cortex-M3 copy did not compile:\n" + out
        return None

    def nm_undefined(self):
        err = self._need_lib()
        if err:
            return 2, err
        return run([sys.executable, os.path.join(self.args.src, "tools", "check_nm.py"),
                    "--nm", self._arm_tool("nm"), "--check", "undefined", self.lib])

    def nm_globals(self):
        err = self._need_lib()
        if err:
            return 2, err
        return run([sys.executable, os.path.join(self.args.src, "tools", "check_nm.py"),
                    "--nm", self._arm_tool("nm"), "--check", "globals", self.lib])

    def stack_sum(self):
        err = self._need_lib()
        if err:
            return 2, err
        return run([sys.executable, os.path.join(self.args.src, "tools", "stack_sum.py"),
                    "--lib", "%s=%s" % (self.lib, os.path.dirname(self.lib))])

    def m4_general_regs_only(self):
        cc = self._arm()
        out, rc = [], 0
        for src in self.sources:
            r, o = run([cc] + M4 + ["-Os", "-std=c99"] + self.cflags + self.incs
                       + ["-ffreestanding", "-c", src, "-o", os.devnull])
            if r != 0:
                rc = r
                out.append(o)
        return rc, "".join(out) or "compiled %d sources" % len(self.sources)


def first_match(text, rx):
    for line in text.splitlines():
        if re.search(rx, line):
            return line.strip()
    return None


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--case", required=True, choices=sorted(EXPECT))
    ap.add_argument("--src", default=DEFAULT_SRC, help="repository root (holds fsw/ and tools/)")
    ap.add_argument("--parts", default="source,binary",
                    help="comma list: source (host checks), binary (Cortex-M checks)")
    ap.add_argument("--host-cc", default="gcc")
    ap.add_argument("--arm-cc", default="arm-none-eabi-gcc")
    ap.add_argument("--cflags", default=DEFAULT_CFLAGS, help="project warning and flight flags")
    ap.add_argument("--workdir", default=None, help="parent of the scratch copy (default: system tmp)")
    ap.add_argument("--keep", action="store_true", help="keep the scratch copy")
    args = ap.parse_args()
    args.src = os.path.abspath(args.src)
    parts = set(p.strip() for p in args.parts.split(",") if p.strip())
    if not os.path.isdir(os.path.join(args.src, "fsw")):
        print("selftest: ERROR: %s has no fsw/" % args.src, file=sys.stderr)
        return 2

    if args.workdir:
        os.makedirs(args.workdir, exist_ok=True)
    work = tempfile.mkdtemp(prefix="proof-%s-" % args.case, dir=args.workdir)
    copy = Copy(args, work)
    where = copy.inject(args.case)
    print("selftest[%s]: scratch copy %s%s" % (args.case, work, ("; defect in " + where) if where else ""))

    failures, ran = [], 0
    for check, (want, detail) in EXPECT[args.case].items():
        part = "source" if check in SOURCE_CHECKS else "binary"
        if part not in parts:
            continue
        ran += 1
        try:
            rc, out = getattr(copy, check)()
        except RuntimeError as e:
            rc, out = 127, str(e)
        failed = rc != 0
        if want == "any":
            print("  info  %-24s %s (%s; not asserted)" % (check, "FAILED" if failed else "passed", detail))
            continue
        if want == "pass":
            if failed:
                failures.append(check)
                print("  FAIL  %-24s expected to pass on this copy, but it failed (exit %d):" % (check, rc))
                print("\n".join("        " + l for l in out.rstrip().splitlines()[-25:]))
            else:
                print("  ok    %-24s passes" % check)
            continue
        hit = first_match(out, detail) if failed else None
        if hit:
            print("  ok    %-24s caught it: %s" % (check, hit))
        else:
            failures.append(check)
            why = ("it passed (exit 0)" if not failed
                   else "it failed (exit %d) without the expected message /%s/" % (rc, detail))
            print("  FAIL  %-24s should have rejected the %s defect, but %s:" % (check, args.case, why))
            print("\n".join("        " + l for l in out.rstrip().splitlines()[-25:]))
    if ran == 0:
        print("selftest[%s]: ERROR: no check selected by --parts %s" % (args.case, args.parts))
        return 2
    if failures:
        print("selftest[%s]: FAIL: %s (scratch copy kept in %s)" % (args.case, " ".join(failures), work))
        return 1
    if not args.keep:
        shutil.rmtree(work, ignore_errors=True)
    print("selftest[%s]: OK: %d check(s) behaved as expected" % (args.case, ran))
    return 0


if __name__ == "__main__":
    sys.exit(main())
