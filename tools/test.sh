#!/usr/bin/env bash
# The whole test suite (README command 2; .ci/run calls this).
# Installs what is missing, then for each preset configures, builds and runs CTest:
#   host (every host proof + unit/golden tests), asan-ubsan, cortex-m3 and cortex-m4 (QEMU),
#   fuzz (clang-14 + libFuzzer, label fuzz only).
# Usage: tools/test.sh [preset ...]      default: host asan-ubsan cortex-m3 cortex-m4 fuzz
# Environment: FSW_TEST_JOBS (default: nproc), CTEST_ARGS (extra ctest arguments).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"

bash tools/bootstrap.sh

JOBS="${FSW_TEST_JOBS:-$(nproc)}"
PRESETS=("$@")
if ((${#PRESETS[@]} == 0)); then
    # host first: the target presets compare their golden digests with build/host.
    PRESETS=(host asan-ubsan cortex-m3 cortex-m4 fuzz)
fi

total_pass=0
total_fail=0
failed_presets=()
start=$(date +%s)
for p in "${PRESETS[@]}"; do
    echo "=== [$p] configure + build"
    cmake --preset "$p" >/dev/null
    cmake --build --preset "$p" -j "$JOBS"
    echo "=== [$p] test"
    log="build/$p/ctest-summary.log"
    set +e
    # shellcheck disable=SC2086
    ctest --preset "$p" -j "$JOBS" ${CTEST_ARGS:-} 2>&1 | tee "$log"
    rc=${PIPESTATUS[0]}
    set -e
    line=$(grep -E 'tests passed, [0-9]+ tests failed out of [0-9]+' "$log" | tail -1 || true)
    if [[ $line =~ ([0-9]+)\ tests\ failed\ out\ of\ ([0-9]+) ]]; then
        f=${BASH_REMATCH[1]}; n=${BASH_REMATCH[2]}
        total_fail=$((total_fail + f)); total_pass=$((total_pass + n - f))
    fi
    if ((rc != 0)); then
        failed_presets+=("$p")
        # Count a preset that failed before reporting tests as one failure.
        [[ -n $line ]] || total_fail=$((total_fail + 1))
    fi
done
echo "=== suite finished in $(( $(date +%s) - start )) s over presets: ${PRESETS[*]}"
if ((${#failed_presets[@]})); then
    echo "FAILED presets: ${failed_presets[*]}"
fi
echo "${total_pass} passed, ${total_fail} failed"
((${#failed_presets[@]} == 0))
