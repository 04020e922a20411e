#!/usr/bin/env bash
# Runs on a GPU node from the repository root, with a CUDA build's bin/ carried along: the
# CUDA smoke test, CPU/CUDA parity, the oracle tests, renders of the committed scenes on both
# backends, and the oracle benchmark. Logs and outputs go to $OUT (or ./gpu-out).
# Usage: scripts/gpu-check.sh BUILD_DIR [LIB_DIR]
set -uo pipefail
build=${1:?build dir}
out=${OUT:-gpu-out}
mkdir -p "$out"
[ -n "${2:-}" ] && export LD_LIBRARY_PATH="$PWD/$2:${LD_LIBRARY_PATH:-}"
export DEEPVOX_SOURCE_DIR="$PWD" DEEPVOX_ASSETS="$PWD/assets"
nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.sm,clocks.mem --format=csv > "$out/gpu.txt" 2>&1
cat "$out/gpu.txt"
status=0
for t in test_core test_render test_oracle; do
  "$build/bin/$t" --gtest_output="json:$out/$t.json" > "$out/$t.log" 2>&1 || status=1
  tail -4 "$out/$t.log"
done
bin="$build/bin/deepvox-lean"
[ -x "$bin" ] || bin="$build/bin/deepvox"
for scene in demo ct-phantom intersecting-volumes; do
  for backend in cuda cpu; do
    "$bin" render "scenes/$scene.json" --backend "$backend" --out "$out/$scene-$backend.png" \
      --stats "$out/$scene-$backend.json" >> "$out/render.log" 2>&1 || status=1
  done
done
grep -h "milliseconds" "$out"/*-cuda.json "$out"/*-cpu.json | head -12
"$build/bin/bench_oracle" --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
  --benchmark_out="$out/bench_oracle.json" --benchmark_out_format=json > "$out/bench_oracle.log" 2>&1 || status=1
tail -30 "$out/bench_oracle.log"
echo "gpu-check status $status"
exit $status
