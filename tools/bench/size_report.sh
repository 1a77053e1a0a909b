#!/usr/bin/env bash
# Image size per libfsw.a member and per board image (spec 00 §4 "image size", §9).
#
#   tools/bench/size_report.sh [BUILD_DIR] [OUT]     defaults: build/cortex-m3, bench/size.md
#
# Builds nothing. Reads BUILD_DIR/fsw/libfsw.a with `arm-none-eabi-size -A` and sorts every
# section into code (.text*), rodata (.rodata*), data (.data*) and bss (.bss*, COMMON); debug
# and note sections are not part of the image and are left out. Board images found in the
# build (fsw_pil.elf, fx_bench.elf) get the same breakdown, with the vector table and unwind
# tables counted as code. Reported only, never gated.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
BUILD="${1:-$ROOT/build/cortex-m3}"
OUT="${2:-$ROOT/bench/size.md}"
SIZE="${SIZE:-arm-none-eabi-size}"
LIB="$BUILD/fsw/libfsw.a"

if [ ! -f "$LIB" ]; then
    echo "size_report: $LIB not found: build a cortex-m preset first" >&2
    exit 1
fi
mkdir -p "$(dirname "$OUT")"

# "size -A" on an archive prints one block per member headed "<member> (ex <archive>):".
classify='
function flush() {
    if (name != "") {
        printf "| `%s` | %d | %d | %d | %d | %d |\n", name, code, ro, dt, bs, code + ro + dt
        tc += code; tr += ro; td += dt; tb += bs
    }
    code = ro = dt = bs = 0
}
/^[^ ]+ +\(ex .*\):$/ { flush(); name = $1; next }
/^[^ ]+ +:$/          { flush(); name = $1; sub(/.*\//, "", name); next }
$1 ~ /^\.(text|vectors|ARM\.exidx|ARM\.extab)/ { code += $2; next }
$1 ~ /^\.rodata/                              { ro += $2; next }
$1 ~ /^\.data/                                { dt += $2; next }
$1 ~ /^\.bss/ || $1 == "COMMON"               { bs += $2; next }
END {
    flush()
    if (totals) printf "| **total** | **%d** | **%d** | **%d** | **%d** | **%d** |\n", tc, tr, td, tb, tc + tr + td
}'

board="$(grep -E '^CMAKE_TOOLCHAIN_FILE:' "$BUILD/CMakeCache.txt" 2>/dev/null | sed -E 's/.*toolchain-(.*)\.cmake/\1/' || true)"
{
    echo "# Image size (${board:-unknown board}, \`${BUILD#"$ROOT"/}\`)"
    echo
    echo "Bytes per section class from \`$("$SIZE" --version | head -1)\`. flash = code + rodata + data"
    echo "(the .data initialiser lives in flash); RAM = data + bss, plus the stack region."
    echo
    echo "## libfsw.a members"
    echo
    echo "| member | code | rodata | data | bss | flash |"
    echo "|---|---:|---:|---:|---:|---:|"
    "$SIZE" -A "$LIB" | awk -v totals=1 "$classify"
    for elf in "$BUILD/fsw_pil.elf" "$BUILD"/*/fsw_pil.elf "$BUILD"/*/*/fsw_pil.elf "$BUILD/fsw/target/fx_bench.elf"; do
        [ -f "$elf" ] || continue
        echo
        echo "## $(basename "$elf")"
        echo
        echo "| image | code | rodata | data | bss | flash |"
        echo "|---|---:|---:|---:|---:|---:|"
        "$SIZE" -A "$elf" | awk -v totals=0 "$classify"
        stack="$(grep -E '^FSW_BOARD_STACK_SIZE:' "$BUILD/CMakeCache.txt" | cut -d= -f2 || true)"
        [ -n "$stack" ] && echo && echo "Stack region: $stack bytes at the top of RAM."
    done
} > "$OUT"
cat "$OUT"
