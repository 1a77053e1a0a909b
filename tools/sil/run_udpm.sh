#!/usr/bin/env bash
# One SIL scenario as separate processes over udpm on loopback (spec 00 §5.3): `sil logger`,
# `sil bridge` (fixed-point flight code) and `sil plant` (simulator, owns the clock).
# SIL_LOGGER=lcm-logger uses Debian's lcm-logger instead; it drops messages under load (its
# subscription queue is LCM's default 30 messages: ~120 of 6000 lost in 1 run of 5, measured),
# so the project's logger, which writes the same event-log format, is the default.
#
#   tools/sil/run_udpm.sh SCENARIO OUT_DIR PORT [SIL_BIN]
#
# Writes OUT_DIR/run.lcmlog (standard LCM event log, replayable with lcm-logplayer) and the
# run's live metrics from the plant process (C++: plant, executive, bridge and mission figures),
# OUT_DIR/summary.txt (key = value) and OUT_DIR/summary.json (the same; `python -m tools.sil
# report --summary` reads it); prints the plant's progress on stderr. Exit status: the plant's
# (0 = run completed in control, 3 = loss of control: hil_host/sil/README.md), or 1 if a node failed.
set -euo pipefail
[ $# -ge 3 ] || { echo "usage: $0 SCENARIO OUT_DIR PORT [SIL_BIN]" >&2; exit 2; }
scn=$1
out=$2
port=$3
sil=${4:-build/host/hil_host/sil/sil}
url="udpm://239.255.76.67:${port}?ttl=0"
log="$out/run.lcmlog"
mkdir -p "$out"
rm -f "$log" "$out/summary.txt" "$out/summary.json"
[ -x "$sil" ] || { echo "run_udpm: $sil not built" >&2; exit 1; }

lp=""
bp=""
cleanup() {
    [ -n "$bp" ] && kill "$bp" 2>/dev/null || true
    [ -n "$lp" ] && kill -INT "$lp" 2>/dev/null || true
}
trap cleanup EXIT

if [ "${SIL_LOGGER:-sil}" = lcm-logger ]; then
    command -v lcm-logger >/dev/null || { echo "run_udpm: lcm-logger not found (liblcm-bin)" >&2; exit 1; }
    lcm-logger --lcm-url="${url}&recv_buf_size=4194304" --flush-interval=20 -q "$log" 2>"$out/logger.err" &
else
    # The receive buffer is raised (capped by net.core.rmem_max) so bursts wait in the kernel.
    "$sil" logger --url "${url}&recv_buf_size=4194304" --log "$log" --idle-timeout-ms 60000 2>"$out/logger.err" &
fi
lp=$!
# Handshake: a runner heartbeat until the log holds it, so the logger hears frame 0.
for _ in $(seq 200); do
    "$sil" ping --url "$url" || { echo "run_udpm: cannot publish on $url" >&2; exit 1; }
    [ -s "$log" ] && break
    sleep 0.05
done
[ -s "$log" ] || { echo "run_udpm: the logger wrote nothing to $log within 10 s" >&2; exit 1; }

"$sil" bridge --scenario "$scn" --url "$url" --idle-timeout-ms 30000 &
bp=$!
rc=0
"$sil" plant --scenario "$scn" --url "$url" --progress --ready-timeout-ms 10000 \
    --summary "$out/summary.txt" --summary-json "$out/summary.json" >/dev/null || rc=$?
brc=0
wait "$bp" || brc=$?
bp=""
if [ "${SIL_LOGGER:-sil}" = lcm-logger ]; then
    sleep 0.3   # its last flush
    kill -INT "$lp" 2>/dev/null || true
fi
wait "$lp" 2>/dev/null || true   # sil logger ends 0.5 s after the plant's STOP
lp=""
if [ "$brc" -ne 0 ]; then
    echo "run_udpm: bridge exited with $brc" >&2
    exit 1
fi
exit "$rc"
