#!/usr/bin/env python3
"""Binary proofs on the soft-float Cortex-M3 libfsw.a (spec 00 §4).

  undefined  "no heap, libc or FP routines": the symbols the archive needs from outside itself
             (`nm -u`, minus what another member defines) may only be
             __aeabi_ldivmod __aeabi_uldivmod memcpy memset memmove memcmp.
             On soft-float M3 every floating-point operation becomes an __aeabi_[fd]* or
             __aeabi_*2[fd] call, so this also proves that no float code reached the binary.
  globals    "no mutable globals": no B b D d C (nor G g S s) symbols, i.e. nothing in
             .bss/.data/common; only text and read-only data. fsw/target objects are excluded
             with --exclude-object.

Usage: check_nm.py [--nm NM] [--check undefined|globals|all] [--exclude-object GLOB]... LIB
Exit status: 0 clean, 1 findings, 2 usage or tool error.
"""
import argparse
import fnmatch
import os
import re
import subprocess
import sys

ALLOWED_UNDEFINED = ("__aeabi_ldivmod", "__aeabi_uldivmod", "memcpy", "memset", "memmove", "memcmp")
MUTABLE_TYPES = {
    "B": ".bss (zero-initialised data)", "b": ".bss (zero-initialised data, file/function static)",
    "D": ".data (initialised data)", "d": ".data (initialised data, file/function static)",
    "C": "common (tentative definition)",
    "G": "small initialised data", "g": "small initialised data (static)",
    "S": "small zero-initialised data", "s": "small zero-initialised data (static)",
}
# Global definitions, which satisfy another member's reference (local t/d/b/r cannot).
DEFINED_TYPES = set("TDBRCGSVWAI")
# References: U, plus weak undefined w/v (they would bind to a library definition if one exists).
REFERENCE_TYPES = set("Uwv")

HEAP = {"malloc", "calloc", "realloc", "free", "reallocarray", "aligned_alloc", "memalign",
        "posix_memalign", "valloc", "pvalloc", "_sbrk", "sbrk", "_sbrk_r", "brk", "alloca"}
LIBM = {"sqrt", "sin", "cos", "tan", "asin", "acos", "atan", "atan2", "sinh", "cosh", "tanh",
        "exp", "exp2", "expm1", "log", "log2", "log10", "log1p", "pow", "fabs", "floor", "ceil",
        "round", "lround", "llround", "trunc", "fmod", "remainder", "hypot", "cbrt", "ldexp",
        "frexp", "modf", "scalbn", "rint", "lrint", "nearbyint", "copysign", "fmin", "fmax",
        "fma", "erf", "erfc", "tgamma", "lgamma", "sincos"}
STDIO_RE = re.compile(r"printf|scanf|puts|putchar|getchar|fopen|fclose|fread|fwrite|fflush|fputs|"
                      r"fgets|fputc|fgetc|perror|^_?write$|^_?read$|^_?open$|^_?close$|^_?lseek$|"
                      r"^_?isatty$|^_?fstat$|^__sf|^_impure_ptr$|^_reent")
SOFTFP_RE = re.compile(r"^__aeabi_[fd]|^__aeabi_\w*2[fd]|^__aeabi_[dfl]?cmp|"
                       r"^__(add|sub|mul|div|neg|eq|ne|lt|le|gt|ge|unord|cmp)[sdtx]f[23]$|"
                       r"^__(float|fix|fixuns|extend|trunc)\w*[sdtx]f\w*$|^__pow[isdx]f2$")


def classify(sym):
    base = re.sub(r"[fl]$", "", sym)
    if sym in HEAP or re.match(r"^_?(malloc|calloc|realloc|free|sbrk|memalign)(_r)?$", sym) \
            or sym.startswith("_malloc"):
        return "heap allocation; flight code has no heap"
    if STDIO_RE.search(sym):
        return "C library I/O; flight code does no I/O"
    if SOFTFP_RE.search(sym):
        return "soft-float library routine: floating-point arithmetic reached the binary"
    if sym in LIBM or base in LIBM:
        return "libm function: floating-point maths in flight code"
    if sym.startswith("__stack_chk"):
        return "stack-protector runtime; flight code does not link it"
    if sym.startswith("__aeabi_") or sym.startswith("__gnu_") or re.match(r"^__\w+[sd]i[23]$", sym):
        return "libgcc helper outside the allowance (only 64-bit division may call libgcc)"
    return "not defined in the archive and not in the allowed list"


def run_nm(nm, lib):
    try:
        res = subprocess.run([nm, "-A", "--format=posix", lib], stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, universal_newlines=True, check=False)
    except OSError as e:
        raise SystemExit("check_nm: ERROR: cannot run %s: %s" % (nm, e))
    if res.returncode != 0:
        sys.stderr.write(res.stderr)
        raise SystemExit("check_nm: ERROR: %s failed on %s (exit %d)" % (nm, lib, res.returncode))
    syms = []   # (member, name, type)
    pat = re.compile(r"^(.*?)\[([^\]]+)\]: (\S+) (\S)")
    for line in res.stdout.splitlines():
        m = pat.match(line)
        if m:
            syms.append((m.group(2), m.group(3), m.group(4)))
        elif line.strip():
            # non-archive input: "file: name type ..."
            m2 = re.match(r"^(.*?): (\S+) (\S)", line)
            if m2:
                syms.append((os.path.basename(m2.group(1)), m2.group(2), m2.group(3)))
    return syms


def check_undefined(syms, allowed):
    defined = {name for _, name, t in syms if t in DEFINED_TYPES}
    bad = []
    for member, name, t in syms:
        if t in REFERENCE_TYPES and name not in defined and name not in allowed:
            bad.append((name, member))
    return sorted(set(bad))


def check_globals(syms, excludes):
    bad = []
    for member, name, t in syms:
        if any(fnmatch.fnmatch(member, g) for g in excludes):
            continue
        if t in MUTABLE_TYPES:
            bad.append((name, member, t))
    return sorted(set(bad))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("lib", help="libfsw.a (or an object file)")
    ap.add_argument("--nm", default="arm-none-eabi-nm", help="nm to use (default arm-none-eabi-nm)")
    ap.add_argument("--check", choices=("undefined", "globals", "all"), default="all")
    ap.add_argument("--exclude-object", action="append", default=[], metavar="GLOB",
                    help="archive members exempt from the globals check (fsw/target objects)")
    ap.add_argument("--allow", action="append", default=[], metavar="SYM",
                    help="extra allowed undefined symbol (documented deviation only)")
    args = ap.parse_args()

    if not os.path.isfile(args.lib):
        print("check_nm: ERROR: %s does not exist; build the library first" % args.lib, file=sys.stderr)
        return 2
    syms = run_nm(args.nm, args.lib)
    lib = os.path.basename(args.lib)
    members = sorted({m for m, _, _ in syms})
    if not syms:
        print("check_nm: ERROR: %s has no symbols" % args.lib, file=sys.stderr)
        return 2
    rc = 0
    if args.check in ("undefined", "all"):
        allowed = set(ALLOWED_UNDEFINED) | set(args.allow)
        bad = check_undefined(syms, allowed)
        for name, member in bad:
            print("check_nm: FORBIDDEN undefined symbol '%s' referenced by %s in %s: %s"
                  % (name, member, lib, classify(name)))
        if bad:
            print("check_nm: FAIL: %d forbidden external reference(s); %s may need only %s "
                  "(spec 00 §4 'no heap, libc or FP routines')"
                  % (len(bad), lib, " ".join(ALLOWED_UNDEFINED)))
            rc = 1
        else:
            ext = sorted({n for _, n, t in syms if t in REFERENCE_TYPES}
                         - {n for _, n, t in syms if t in DEFINED_TYPES})
            print("check_nm: OK: %s (%d members) references only %s from outside"
                  % (lib, len(members), " ".join(ext) if ext else "nothing"))
    if args.check in ("globals", "all"):
        bad = check_globals(syms, args.exclude_object)
        for name, member, t in bad:
            kind = "function-local static" if re.search(r"\.\d+$", name) else "object"
            print("check_nm: MUTABLE %s '%s' in %s of %s: nm type %s = %s"
                  % (kind, name, member, lib, t, MUTABLE_TYPES[t]))
        if bad:
            print("check_nm: FAIL: %d mutable global/static object(s); flight state is caller-owned "
                  "(spec 00 §4 'no mutable globals', §3.1)" % len(bad))
            rc = 1
        else:
            checked = [m for m in members if not any(fnmatch.fnmatch(m, g) for g in args.exclude_object)]
            print("check_nm: OK: no B b D d C symbols in %d member(s) of %s%s"
                  % (len(checked), lib,
                     (" (excluded: %s)" % " ".join(args.exclude_object)) if args.exclude_object else ""))
    return rc


if __name__ == "__main__":
    sys.exit(main())
