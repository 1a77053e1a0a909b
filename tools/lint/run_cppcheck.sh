#!/usr/bin/env bash
# MISRA C:2012 proof of spec 00 §4: cppcheck with the misra addon over fsw/.
#
# Usage: tools/lint/run_cppcheck.sh [--src ROOT] [--cppcheck-build-dir DIR] [PATH...]
#   ROOT   tree that holds fsw/ (default: this repository); PATH defaults to fsw/
#   DIR    cppcheck's work directory (default: a temporary one, removed afterwards)
# Environment: CPPCHECK (default cppcheck).
#
# Runs, from ROOT:
#   cppcheck --std=c99 --platform=unix32 --addon=misra --enable=warning,style,information
#            --inline-suppr --error-exitcode=2 -I tools/lint/stdinc
#            --suppress='*:tools/lint/stdinc/*' --suppressions-list=tools/lint/misra.supp fsw/
# plus -I for every header directory of fsw/ and a one-line output template.
# Fails (exit 1) on any finding and on any noValidConfiguration, toomanyconfigs or
# missingInclude line: cppcheck exits 0 when it silently skips a file or a configuration.
# The only post-filters are the tool-defect deviations T1 and T2 (tools/lint/cppcheck_filter.py,
# fsw/MISRA_DEVIATIONS.md); each dropped report is still printed as a note.
# Exit status: 0 clean, 1 findings or skips, 2 usage or tool error.
set -u
die() { echo "run_cppcheck: ERROR: $*" >&2; exit 2; }

lint=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$lint/../.." && pwd)
builddir=""
gens=()
paths=()
while [ $# -gt 0 ]; do
    case "$1" in
        --src) root=$(cd "$2" 2>/dev/null && pwd) || die "bad --src $2"; shift 2 ;;
        --cppcheck-build-dir) builddir=$2; shift 2 ;;
        --gen) gens+=("$(cd "$2" 2>/dev/null && pwd)") || die "bad --gen $2"; shift 2 ;;
        -h|--help) sed -n '2,18p' "$0"; exit 0 ;;
        -*) die "unknown option $1" ;;
        *) paths+=("$1"); shift ;;
    esac
done
[ ${#paths[@]} -gt 0 ] || paths=(fsw/)
cd "$root" || die "cannot cd to $root"
[ -d fsw ] || die "$root/fsw does not exist"
cppcheck=${CPPCHECK:-cppcheck}
command -v "$cppcheck" >/dev/null 2>&1 || die "cppcheck not found (tools/bootstrap.sh installs it)"
command -v python3 >/dev/null 2>&1 || die "python3 not found"

# Paths relative to ROOT when the lint directory lives inside it (the spec's command line),
# absolute otherwise (the self-test runs on a copy of fsw/).
case "$lint" in
    "$root"/*) rel=${lint#"$root"/} ;;
    *) rel=$lint ;;
esac
stdinc="$rel/stdinc"
supp="$rel/misra.supp"
[ -f "$supp" ] || die "$supp not found"

incs=()
while IFS= read -r d; do incs+=(-I "$d"); done < <(find fsw -name '*.h' -printf '%h\n' | sort -u)
# Generated flight code (the mission dispatch in the build tree, --gen): checked like fsw/.
for g in "${gens[@]}"; do
    incs+=(-I "$g")
    while IFS= read -r f; do paths+=("$f"); done < <(find "$g" -maxdepth 1 -name '*.c' | sort)
done

args=(--std=c99 --platform=unix32 --addon=misra --enable=warning,style,information
      --inline-suppr --error-exitcode=2 -I "$stdinc" "${incs[@]}"
      "--suppress=*:$stdinc/*" "--suppressions-list=$supp" -q
      "--template={file}:{line}:{column}: {severity}: {id}: {message}")
# A cppcheck build directory keeps the addon's .dump/.ctu-info files out of the source tree
# (and apart from a concurrent run in another build). A fresh one per run: no stale cache.
if [ -z "$builddir" ]; then
    builddir=$(mktemp -d "${TMPDIR:-/tmp}/run_cppcheck.XXXXXX") || die "mktemp failed"
    trap 'rm -rf "$builddir"' EXIT
fi
mkdir -p "$builddir" || die "cannot create $builddir"
args+=("--cppcheck-build-dir=$builddir")

echo "run_cppcheck: $cppcheck ${args[*]} ${paths[*]}  (in $root)"
out=$("$cppcheck" "${args[@]}" "${paths[@]}" 2>&1)
rc=$?
result=$(printf '%s\n' "$out" | python3 "$lint/cppcheck_filter.py")
frc=$?
[ -n "$result" ] && printf '%s\n' "$result"
if printf '%s\n' "$result" | grep -q 'missingInclude'; then
    echo "run_cppcheck: missing includes (cppcheck --check-config):"
    "$cppcheck" "${args[@]}" --check-config "${paths[@]}" 2>&1 | grep -E 'missingInclude' | grep -v '^nofile' | sed 's/^/  /'
fi
if [ $frc -ne 0 ]; then
    exit 1
fi
if [ $rc -ne 0 ] && [ $rc -ne 2 ]; then
    printf '%s\n' "$out" >&2
    die "cppcheck failed with exit status $rc"
fi
echo "run_cppcheck: OK: no MISRA C:2012 or cppcheck finding in ${paths[*]} (deviations: fsw/MISRA_DEVIATIONS.md)"
exit 0
