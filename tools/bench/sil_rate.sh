#!/usr/bin/env bash
# Benchmark (spec 00 §9, never a test): SIL lock-step rate of the full loop (plant + bridge +
# fsw_step) over 10^4 steps, beside the raw LCM round-trip ceiling on the same transports and
# machine, measured in the same run. Median and minimum of REPS repetitions.
#
#   tools/bench/sil_rate.sh [BUILD_DIR] [REPS]      default build/host-release (the Release preset:
#                                                   benchmark figures are Release figures), 5
#
# Writes bench/sil_rate.md (and prints it). Transports: memq (one process), udpm with both nodes
# in one process, udpm as separate processes (tools/sil/run_udpm.sh, process start-up and the
# logger included).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
cd "$ROOT"
B=${1:-build/host-release}
REPS=${2:-5}
SIL="$B/hil_host/sil/sil"
PP="$B/hil_host/tools/lcm_pingpong"
[ -x "$SIL" ] && [ -x "$PP" ] || { echo "sil_rate: build $B first (cmake --preset host-release && cmake --build --preset host-release; build/host for a Debug figure)" >&2; exit 1; }
mkdir -p bench
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# S0-5 nominal (M-paper, 50 Hz) stretched to 200 s = 10^4 steps.
sed 's/^duration_s:.*/duration_s: 200/' sim/observer/scenarios/s0-5_nominal_mpaper.yaml > "$tmp/s.yaml"
port=$((7400 + RANDOM % 200))

stats() { sort -n | awk '{a[NR]=$1} END {printf "%.0f %.0f\n", a[int((NR+1)/2)], a[1]}'; }

memq=(); udpm=(); proc=(); pp_memq=(); pp_udpm=()
for r in $(seq "$REPS"); do
    memq+=("$("$SIL" run --scenario "$tmp/s.yaml" | sed -n 's/^steps_per_s = //p')")
    udpm+=("$("$SIL" run --scenario "$tmp/s.yaml" --url "udpm://239.255.76.67:$port?ttl=0" | sed -n 's/^steps_per_s = //p')")
    t0=$(date +%s%N)
    tools/sil/run_udpm.sh "$tmp/s.yaml" "$tmp/p" $((port + 1)) "$SIL" 2>/dev/null
    ms=$(( ($(date +%s%N) - t0) / 1000000 ))
    proc+=("$(( 10000 * 1000 / ms ))")
    pp_memq+=("$("$PP" --transport memq --n 10000 --reps 1 2>/dev/null | sed -n 's/.*rate_median=\([0-9]*\).*/\1/p')")
    pp_udpm+=("$("$PP" --transport udpm --url "udpm://239.255.76.67:$((port + 2))?ttl=0" --n 10000 --reps 1 2>/dev/null | sed -n 's/.*rate_median=\([0-9]*\).*/\1/p')")
done
read -r m_med m_min < <(printf '%s\n' "${memq[@]}" | stats)
read -r u_med u_min < <(printf '%s\n' "${udpm[@]}" | stats)
read -r p_med p_min < <(printf '%s\n' "${proc[@]}" | stats)
read -r c_med c_min < <(printf '%s\n' "${pp_memq[@]}" | stats)
read -r d_med d_min < <(printf '%s\n' "${pp_udpm[@]}" | stats)
{
    echo "# SIL lock-step rate ($(date -u +%Y-%m-%d), commit $(git rev-parse --short HEAD 2>/dev/null || echo '?'))"
    echo
    echo "Machine: $(nproc) cores, $(sed -n 's/^model name\s*: //p' /proc/cpuinfo | head -1). S0-5 nominal, 10^4 steps, $REPS repetitions (median / min)."
    echo
    echo "| transport | SIL steps/s | LCM ping-pong round trips/s | SIL / ceiling |"
    echo "|---|---|---|---|"
    echo "| memq, one process | $m_med / $m_min | $c_med / $c_min | $(awk "BEGIN{printf \"%.2f\", $m_med/$c_med}") |"
    echo "| udpm loopback, nodes in one process | $u_med / $u_min | $d_med / $d_min | $(awk "BEGIN{printf \"%.2f\", $u_med/$d_med}") |"
    echo "| udpm loopback, 3 processes (logger, bridge, plant; start-up included) | $p_med / $p_min | $d_med / $d_min | $(awk "BEGIN{printf \"%.2f\", $p_med/$d_med}") |"
} | tee bench/sil_rate.md
