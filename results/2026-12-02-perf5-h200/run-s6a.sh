#!/bin/bash
# Session 6, call 1 (cb49148 + kernel counters): test_hard (the degenerate rule's new hard
# case on CUDA); where the DSM generation, the renderer and the bilinear render spend their
# time: each case once normally (3 repetitions) and once with DEEPVOX_KERNEL_TIMING=1 (a
# counter per kernel, each launch waited for).
set -u
G=$PWD/.gpu; W=$(mktemp -d); mkdir -p $W/bin
export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/assets LD_LIBRARY_PATH=$G/lib:${LD_LIBRARY_PATH:-}
for f in $G/bin/*.xz; do b=$W/bin/$(basename $f .xz); xz -dc $f > $b; chmod +x $b; done
L=$W/s6a; mkdir -p $L
trap 'tar -czf $OUT/s6a.tar.gz -C $L .' EXIT
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $L/gpu.txt 2>&1; cat $L/gpu.txt
t0=$(date +%s)
timeout 150 $W/bin/test_hard > $L/test_hard.log 2>&1; echo "test_hard rc=$? $(grep -E '^\[  (PASSED|FAILED|SKIPPED) ' $L/test_hard.log | tr '\n' ' ') $(( $(date +%s)-t0 ))s"
A="--benchmark_repetitions=3 --benchmark_report_aggregates_only=true"
D='^(generate/(beer|texture3d|compact|chunked)/cuda/1024|render_bilinear/compact/cuda/1024)$'
R='raster_render/fig56_(none|shadowmap)_cuda'
timeout 150 $W/bin/bench_dsm $A --benchmark_filter="$D" --benchmark_out=$L/bench_dsm.json > $L/bench_dsm.log 2>&1; echo "bench_dsm rc=$? $(( $(date +%s)-t0 ))s"
timeout 100 $W/bin/bench_renderer $A --benchmark_filter="$R" --benchmark_out=$L/bench_renderer.json > $L/bench_renderer.log 2>&1; echo "bench_renderer rc=$? $(( $(date +%s)-t0 ))s"
export DEEPVOX_KERNEL_TIMING=1
timeout 150 $W/bin/bench_dsm --benchmark_filter="$D" --benchmark_out=$L/bench_dsm-kernels.json > $L/bench_dsm-kernels.log 2>&1; echo "bench_dsm kernels rc=$? $(( $(date +%s)-t0 ))s"
timeout 100 $W/bin/bench_renderer --benchmark_filter="$R" --benchmark_out=$L/bench_renderer-kernels.json > $L/bench_renderer-kernels.log 2>&1; echo "bench_renderer kernels rc=$? $(( $(date +%s)-t0 ))s"
grep median $L/bench_dsm.log $L/bench_renderer.log | cut -c1-400
