#!/usr/bin/env bash
# clang-tidy proof of spec 00 §4: clang-tidy -p <host build> --warnings-as-errors='*' on every
# fsw/ translation unit of compile_commands.json, with the checks of the top-level .clang-tidy.
#
# Usage: tools/lint/run_clang_tidy.sh BUILD_DIR [--src REPO_ROOT] [--config FILE] [FILE...]
#   BUILD_DIR  a host build (CMAKE_EXPORT_COMPILE_COMMANDS is on in the top-level CMakeLists)
#   FILE...    restrict to these sources (default: every compile_commands entry under fsw/)
# Environment: CLANG_TIDY (default: clang-tidy-14, else clang-tidy).
#
# The compile lines are GCC's. A filtered copy of compile_commands.json (in
# BUILD_DIR/clang-tidy/) drops the GCC-only options clang would reject or warn about
# (-fcallgraph-info=*, -fstack-usage, -Wstack-usage=*, -fno-tree-loop-distribute-patterns);
# -mgeneral-regs-only is kept (clang 14 accepts it on x86-64). hicpp-signed-bitwise is switched
# off for files under fsw/fx, the one place allowed to make signed-shift decisions.
# Exit status: 0 clean, 1 findings, 2 usage or tool error.
set -u

die() { echo "run_clang_tidy: ERROR: $*" >&2; exit 2; }

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd -P)
build=""
config=""
gen=""
files=()
while [ $# -gt 0 ]; do
    case "$1" in
        --src) root=$(cd "$2" && pwd -P) || die "bad --src $2"; shift 2 ;;
        --config) config=$2; shift 2 ;;
        --gen) gen=$(cd "$2" 2>/dev/null && pwd -P) || die "bad --gen $2"; shift 2 ;;
        -h|--help) sed -n '2,16p' "$0"; exit 0 ;;
        -*) die "unknown option $1" ;;
        *) if [ -z "$build" ]; then build=$1; else files+=("$1"); fi; shift ;;
    esac
done
[ -n "$build" ] || die "usage: run_clang_tidy.sh BUILD_DIR [--src REPO_ROOT] [FILE...]"
build=$(cd "$build" 2>/dev/null && pwd) || die "build directory '$build' does not exist"
[ -f "$build/compile_commands.json" ] || die "$build/compile_commands.json missing (configure the host preset first)"
[ -n "$config" ] || config="$root/.clang-tidy"
[ -f "$config" ] || die "clang-tidy configuration $config not found"

tidy=${CLANG_TIDY:-}
if [ -z "$tidy" ]; then
    if command -v clang-tidy-14 >/dev/null 2>&1; then tidy=clang-tidy-14
    elif command -v clang-tidy >/dev/null 2>&1; then tidy=clang-tidy
    else die "clang-tidy not found (tools/bootstrap.sh installs clang-tidy)"; fi
fi
command -v python3 >/dev/null 2>&1 || die "python3 not found"

dbdir="$build/clang-tidy"
mkdir -p "$dbdir" || die "cannot create $dbdir"
# Filtered database + list of fsw/ sources, one per line.
list=$(python3 - "$build/compile_commands.json" "$dbdir/compile_commands.json" "$root/fsw" "$gen" <<'EOF'
import json, os, shlex, sys
src, dst = sys.argv[1], sys.argv[2]
roots = [os.path.realpath(r) for r in sys.argv[3:] if r]
DROP_PREFIX = ("-fcallgraph-info", "-Wstack-usage=")
DROP = {"-fstack-usage", "-fno-tree-loop-distribute-patterns"}
out, files = [], []
for e in json.load(open(src)):
    f = os.path.realpath(os.path.join(e.get("directory", ""), e["file"]))
    if not (any(f.startswith(r + os.sep) for r in roots) and f.endswith(".c")):
        continue
    args = e["arguments"] if "arguments" in e else shlex.split(e["command"])
    args = [a for a in args if a not in DROP and not a.startswith(DROP_PREFIX)]
    out.append({"directory": e.get("directory", ""), "file": e["file"], "arguments": args})
    if f not in files:
        files.append(f)
json.dump(out, open(dst, "w"), indent=1)
print("\n".join(files))
EOF
) || die "cannot read $build/compile_commands.json"

if [ ${#files[@]} -eq 0 ]; then
    mapfile -t files <<<"$list"
fi
[ -n "${files[*]}" ] || die "no fsw/ sources in $build/compile_commands.json"

failed=()
n=0
for f in "${files[@]}"; do
    [ -n "$f" ] || continue
    n=$((n + 1))
    extra=()
    case "$(realpath "$f")" in
        "$root"/fsw/fx/*) extra+=(--checks=-hicpp-signed-bitwise) ;;
    esac
    out=$("$tidy" -p "$dbdir" --config-file="$config" --quiet --warnings-as-errors='*' \
              "${extra[@]}" \
              --extra-arg=-Wno-unknown-warning-option \
              --extra-arg=-Wno-unused-command-line-argument \
              "$f" 2>&1)
    rc=$?
    # clang-tidy prints "N warnings generated." even when all of them are filtered out.
    findings=$(printf '%s\n' "$out" | grep -E ': (warning|error): ' || true)
    if [ $rc -ne 0 ] || [ -n "$findings" ]; then
        printf '%s\n' "$out" | grep -v -E '^[0-9]+ warnings? (generated|treated as errors)\.?$'
        failed+=("${f#"$root"/}")
    fi
done

if [ ${#failed[@]} -ne 0 ]; then
    echo "run_clang_tidy: FAIL: findings in ${#failed[@]} of $n file(s): ${failed[*]} (spec 00 §4 'clang-tidy')"
    exit 1
fi
echo "run_clang_tidy: OK: $n fsw/ translation unit(s) clean with $(basename "$tidy") and ${config#"$root"/}"
exit 0
