#!/bin/bash
# Session 6, call 3: the tile rasterizer with one thread per box tile (new) against cb49148
# (old, s6a's binaries): the CUDA tests of the raster, render, DSM and hard suites with the new
# code; generate/<every storage>/cuda/1024, render_bilinear/compact/cuda/1024 and the fig56
# renderer cases, old and new interleaved, two rounds of 3 repetitions; then the new build with
# DEEPVOX_KERNEL_TIMING=1 (a counter per kernel).
set -u
G=$PWD/.gpu; W=$(mktemp -d); mkdir -p $W/bin
export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/assets LD_LIBRARY_PATH=$G/lib:${LD_LIBRARY_PATH:-}
for f in $G/bin/*.xz; do b=$W/bin/$(basename $f .xz); xz -dc $f > $b; chmod +x $b; done
L=$W/s6c; mkdir -p $L
trap 'tar -czf $OUT/s6c.tar.gz -C $L .' EXIT
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $L/gpu.txt 2>&1; cat $L/gpu.txt
t0=$(date +%s)
for t in test_raster test_render test_dsm test_hard; do
  timeout 200 $W/bin/$t > $L/$t.log 2>&1; echo "$t rc=$? $(grep -E '^\[  (PASSED|FAILED|SKIPPED) ' $L/$t.log | tr '\n' ' ') $(( $(date +%s)-t0 ))s"
done
grep -h "^\[  FAILED  \]" $L/test_*.log | sort -u | head
A="--benchmark_repetitions=3 --benchmark_report_aggregates_only=true"
D='^(generate/[a-z0-9:=]+/cuda/1024|render_bilinear/compact/cuda/1024)/'
R='raster_render/fig56_(none|shadowmap)_cuda'
for round in 1 2; do
  for v in old new; do
    s=""; [ $v = old ] && s="-old"
    timeout 150 $W/bin/bench_dsm$s $A --benchmark_filter="$D" --benchmark_out=$L/bench_dsm-$v-$round.json > $L/bench_dsm-$v-$round.log 2>&1; echo "bench_dsm $v $round rc=$? $(( $(date +%s)-t0 ))s"
    timeout 100 $W/bin/bench_renderer$s $A --benchmark_filter="$R" --benchmark_out=$L/bench_renderer-$v-$round.json > $L/bench_renderer-$v-$round.log 2>&1; echo "bench_renderer $v $round rc=$? $(( $(date +%s)-t0 ))s"
  done
done
export DEEPVOX_KERNEL_TIMING=1
timeout 150 $W/bin/bench_dsm --benchmark_filter="$D" --benchmark_out=$L/bench_dsm-kernels.json > $L/bench_dsm-kernels.log 2>&1; echo "bench_dsm kernels rc=$? $(( $(date +%s)-t0 ))s"
timeout 100 $W/bin/bench_renderer --benchmark_filter="$R" --benchmark_out=$L/bench_renderer-kernels.json > $L/bench_renderer-kernels.log 2>&1; echo "bench_renderer kernels rc=$? $(( $(date +%s)-t0 ))s"
for v in old new; do echo "== $v"; grep -h median $L/bench_dsm-$v-2.log $L/bench_renderer-$v-2.log | grep -oE "^[^ ]+ +[0-9.]+ ms|raster_ms=[^ ]+" | paste - - ; done
