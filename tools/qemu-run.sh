#!/bin/sh
# Run a Cortex-M image under QEMU with semihosting; the exit status is the guest's code
# (spec 00 §6.2, §6.3). CTest calls this as CMAKE_CROSSCOMPILING_EMULATOR.
#
#   tools/qemu-run.sh <machine> <elf> [args...]
#
#   <machine>      mps2-an385 | mps2-an386
#   [args...]      guest command line (semihosting SYS_GET_CMDLINE returns "<elf> args...")
#   QEMU_TIMEOUT   seconds before the run is killed (default 120); a hang exits 124
#   QEMU_ARGS      extra QEMU options, word-split (e.g. "-icount shift=3", "-serial ...")
#   QEMU_SEMI_LOG  write the semihosting console to this file instead of stdout
#
# Exit status: the guest's code (0 pass, 1..127 failed tests, 236 stack canary, 238 fault),
# 124 on timeout, 125..127 from timeout/exec itself, 2 for a usage error.
# Guest console output goes to stdout; QEMU writes the semihosting console to its stderr when
# no chardev is given, so stderr is folded into stdout (QEMU's own diagnostics come along).
set -u

if [ $# -lt 2 ]; then
    echo "usage: $0 <machine> <elf> [args...]" >&2
    exit 2
fi
machine=$1
elf=$2
shift 2

if [ ! -f "$elf" ]; then
    echo "qemu-run: no such image: $elf" >&2
    exit 2
fi

QEMU=${QEMU:-qemu-system-arm}
timeout_s=${QEMU_TIMEOUT:-120}

semi="enable=on,target=native"
if [ -n "${QEMU_SEMI_LOG:-}" ]; then
    semi="$semi,chardev=qemu_run_semi"
    chardev="-chardev file,id=qemu_run_semi,path=$QEMU_SEMI_LOG"
else
    chardev=""
fi

# -append carries the guest arguments; without arguments it is left out so the command line
# is just the image name.
if [ $# -gt 0 ]; then
    # shellcheck disable=SC2086  # QEMU_ARGS and chardev are option lists, split on purpose
    exec timeout --kill-after=10 "$timeout_s" "$QEMU" -M "$machine" -display none -monitor none \
        -semihosting-config "$semi" $chardev ${QEMU_ARGS:-} \
        -kernel "$elf" -append "$*" </dev/null 2>&1
else
    # shellcheck disable=SC2086
    exec timeout --kill-after=10 "$timeout_s" "$QEMU" -M "$machine" -display none -monitor none \
        -semihosting-config "$semi" $chardev ${QEMU_ARGS:-} \
        -kernel "$elf" </dev/null 2>&1
fi
