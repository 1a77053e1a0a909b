#!/usr/bin/env bash
# README command 1: the main job. Installs what is missing, builds the host tools, and runs SIL
# scenarios as separate processes over udpm LCM on loopback (logger, bridge with the fixed-point
# flight code, plant), then writes the summary and the plots.
#
#   tools/run.sh [SCENARIO.yaml ...]
#       default: every registered mission's "run" scenarios (missions.json): today the sail detumbling
#                (observer), the terminal rendezvous (impulse scheduler) and the nominal wheels respin
#
# Output per scenario: build/run/<scenario file name>/ with run.lcmlog (replay: lcm-logplayer),
# summary.txt and summary.json (the run's live metrics, written by the plant process), the report
# (report.txt, report.json: `python -m tools.sil report`, whose acceptance figures are those of
# summary.json) and the PNG plots. Environment: SIL_PORT (default 7667), FSW_RUN_JOBS (build
# parallelism, default nproc).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
bash tools/bootstrap.sh

scenarios=("$@")
if ((${#scenarios[@]} == 0)); then
    # each registered mission's main-job scenarios ("run" in missions.json): a new module adds its own
    mapfile -t scenarios < <("$ROOT/.venv/bin/python" -B -c \
        'import tools.iface as i; print("\n".join(s for m in i.missions() for s in m.run))')
fi

echo "=== build (host preset: the SIL executable and the LCM Python bindings)"
cmake --preset host >/dev/null
cmake --build --preset host -j "${FSW_RUN_JOBS:-$(nproc)}" --target sil gnc_lcmtypes_gen

port=${SIL_PORT:-7667}
py="$ROOT/.venv/bin/python"
for scn in "${scenarios[@]}"; do
    name=$(basename "$scn" .yaml)
    out="build/run/$name"
    echo "=== SIL $name over udpm (port $port): logger, bridge + fixed-point flight code, plant"
    t0=$(date +%s%N)
    tools/sil/run_udpm.sh "$scn" "$out" "$port" build/host/hil_host/sil/sil
    ms=$(( ($(date +%s%N) - t0) / 1000000 ))
    steps=$(sed -n 's/^plant_steps = //p' "$out/summary.txt")
    echo "    $steps lock-step steps in $((ms / 1000)).$(printf '%03d' $((ms % 1000))) s wall clock" \
         "($(( steps * 1000 / (ms > 0 ? ms : 1) )) steps/s, process start-up included)"
    echo "=== report: $out"
    "$py" -m tools.sil report "$out/run.lcmlog" --out "$out" --summary "$out/summary.json" \
        --lcm-py build/host/lcmtypes/python
    port=$((port + 1))
done
echo "=== done: summaries and plots in build/run/"
