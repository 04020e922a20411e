#!/usr/bin/env bash
# Runs on a GPU node from the repository root, with a CUDA build's bin/ carried along: the
# CUDA smoke test, CPU/CUDA parity, the oracle, raster, render, voxel and DSM tests, the hard
# cases (test_hard: CUDA runs of the hard cases and determinism), renders of the
# committed scenes on both backends, and the benchmarks. Logs and outputs are packed into
# $OUT/gpu-check.tar.gz (the device tool returns few files); the summary goes to stdout.
# Usage: scripts/gpu-check.sh BUILD_DIR [LIB_DIR]; SECTIONS="tests renders benches suites" (the
# default) picks what runs. `suites` runs the quick, seeds and accuracy suites on CUDA (rows and
# PNGs, SUITE_TIMEOUT seconds each, default 420; rebuild the reports with plots on the host:
# deepvox report <folder from the tarball>). The paper tables and DSM accuracy that the retired
# dsm_accuracy and voxel_tables programs measured are the seeds and accuracy suites now.
set -uo pipefail
build=${1:?build dir}
out=${OUT:-gpu-out}
work=$(mktemp -d)
[ -n "${2:-}" ] && export LD_LIBRARY_PATH="$PWD/$2:${LD_LIBRARY_PATH:-}"
export DEEPVOX_SOURCE_DIR="$PWD" DEEPVOX_ASSETS="$PWD/experiments/assets"
nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.sm,clocks.mem --format=csv > "$work/gpu.txt" 2>&1
cat "$work/gpu.txt"
status=0
sections=${SECTIONS:-tests renders benches suites}
has() { [[ " $sections " == *" $1 "* ]]; }
# Packs what exists so far: a run cut short by the device's time limit still returns its logs.
pack() { mkdir -p "$out" && tar -czf "$out/gpu-check.tar.gz" -C "$work" .; }
limit=${STEP_TIMEOUT:-240}  # seconds per test binary, benchmark or experiment
has tests && for t in test_core test_frame test_shadow test_oracle test_raster test_voxelizer test_dsm \
    test_storage test_hard; do
  [ -x "$build/bin/$t" ] || continue
  timeout "$limit" "$build/bin/$t" --gtest_output="json:$work/$t.json" > "$work/$t.log" 2>&1 ||
    status=1
  echo "$t: $(grep -E '^\[  (PASSED|FAILED|SKIPPED) ' "$work/$t.log" | tr '\n' ' ')"
  pack
done
bin="$build/bin/deepvox-lean"
[ -x "$bin" ] || bin="$build/bin/deepvox"
has renders && for scene in demo ct-phantom intersecting-volumes knecht-fig56; do
  for shadows in reference shadowmap dsm; do
    for backend in cuda cpu; do
      "$bin" render "experiments/scenes/$scene.json" --backend "$backend" --shadows "$shadows" \
        --out "$work/$scene-$shadows-$backend.png" --stats "$work/$scene-$shadows-$backend.json" \
        >> "$work/render.log" 2>&1 || status=1
    done
  done
done
has renders && grep -h "deepvox: render" "$work/render.log"
has benches && for bench in bench_oracle bench_renderer bench_voxelizer bench_dsm; do
  [ -x "$build/bin/$bench" ] || continue
  timeout "$limit" "$build/bin/$bench" --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
    --benchmark_out="$work/$bench.json" --benchmark_out_format=json > "$work/$bench.log" 2>&1 || status=1
  grep -E "median|stddev" "$work/$bench.log"
  pack
done
if has suites; then
  for suite in quick seeds accuracy; do
    timeout "${SUITE_TIMEOUT:-420}" "$bin" suite "$suite" --backend cuda --out "$work/suites" > "$work/suite-$suite.log" 2>&1 ||
      status=1
    tail -n 3 "$work/suite-$suite.log"
    pack
  done
fi
pack
echo "gpu-check status $status"
exit $status
