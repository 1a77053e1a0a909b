#!/usr/bin/env bash
# README command 1: the main job. Installs what is missing, builds the host tools, and runs SIL
# scenarios as separate processes over udpm LCM on loopback (logger, bridge with the fixed-point
# flight code, plant), then writes the summary and the plots.
#
#   tools/run.sh [--pil [M3|M4]] [SCENARIO.yaml ...]
#       --pil: processor in the loop instead: the flight software on the emulated board (QEMU
#              mps2-an385 = M3, the default, or mps2-an386 = M4), built by the Cortex-M preset, behind
#              the serial link (hil_host/pil); each scenario is flown in SIL too and the command and
#              telemetry streams must be byte-identical. Output: build/run-pil/<scenario>/ (the same
#              summary, report and plots, plus the board's per-step instruction counts insn.csv).
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

pil=""
if (($# > 0)) && [[ $1 == --pil ]]; then
    shift
    pil=M3
    if (($# > 0)) && [[ $1 == M3 || $1 == M4 ]]; then
        pil=$1
        shift
    fi
fi
scenarios=("$@")
if ((${#scenarios[@]} == 0)); then
    # each registered mission's main-job scenarios ("run" in missions.json): a new module adds its own
    mapfile -t scenarios < <("$ROOT/.venv/bin/python" -B -c \
        'import tools.iface as i; print("\n".join(s for m in i.missions() for s in m.run))')
fi

echo "=== build (host preset: the SIL executable and the LCM Python bindings)"
cmake --preset host >/dev/null
cmake --build --preset host -j "${FSW_RUN_JOBS:-$(nproc)}" --target sil gnc_lcmtypes_gen
py="$ROOT/.venv/bin/python"
if [[ -n $pil ]]; then
    preset=cortex-m3; machine=mps2-an385
    if [[ $pil == M4 ]]; then preset=cortex-m4; machine=mps2-an386; fi
    echo "=== build ($preset preset: the board image fsw_pil.elf)"
    cmake --preset "$preset" >/dev/null
    cmake --build --preset "$preset" -j "${FSW_RUN_JOBS:-$(nproc)}" --target fsw_pil
    for scn in "${scenarios[@]}"; do
        name=$(basename "$scn" .yaml)
        out="build/run-pil/$name"
        mkdir -p "$out"
        echo "=== PIL $name on $machine (QEMU, -icount shift=3) and SIL, streams compared"
        build/host/hil_host/sil/sil run --scenario "$scn" --pil "build/$preset/fsw/target/fsw_pil.elf" \
            --pil-machine "$machine" --pil-dir "$out" --compare-sil --progress --log "$out/run.lcmlog" \
            --summary "$out/summary.txt" --summary-json "$out/summary.json" --pil-insn "$out/insn.csv" \
            | grep -E '^(pil_|plant_steps|loss_of_control|stream_digest)'
        echo "=== report: $out"
        "$py" -m tools.sil report "$out/run.lcmlog" --out "$out" --summary "$out/summary.json" \
            --lcm-py build/host/lcmtypes/python
    done
    echo "=== done: summaries and plots in build/run-pil/"
    exit 0
fi

port=${SIL_PORT:-7667}
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
