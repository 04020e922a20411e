#!/bin/bash
# Session 7, call 5: the final code (fragment pass tile by tile) against main + owner_of_item
# (old): the CUDA suites test_core, test_voxel, test_raster, test_render, test_dsm, test_hard; then bench_renderer (fig56 none / shadow map / planned
# frames on CUDA) and bench_dsm (render_bilinear at 1024^2 for every storage, generate at
# 1024^2 for beer and compact), old and new interleaved, three rounds of 3 repetitions.
set -u
G=$PWD/.gpu; W=$(mktemp -d); mkdir -p $W/bin
export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/assets LD_LIBRARY_PATH=$G/lib:${LD_LIBRARY_PATH:-}
for f in $G/bin/*.xz; do b=$W/bin/$(basename $f .xz); xz -dc $f > $b; chmod +x $b; done
L=$W/p5; mkdir -p $L
trap 'tar -czf $OUT/p5.tar.gz -C $L .' EXIT
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $L/gpu.txt 2>&1; cat $L/gpu.txt
t0=$(date +%s)
for t in test_core test_voxel test_raster test_render test_dsm test_hard; do
  timeout 200 $W/bin/$t > $L/$t.log 2>&1; echo "$t rc=$? $(grep -E '^\[  (PASSED|FAILED) ' $L/$t.log | tr '\n' ' ') skipped=$(grep -cE '^\[  SKIPPED \] .*\(' $L/$t.log) $(( $(date +%s)-t0 ))s"
done
grep -h "^\[  FAILED  \]" $L/test_*.log | sort -u | head
A="--benchmark_repetitions=3 --benchmark_report_aggregates_only=true"
R='(raster_render/fig56_(none|shadowmap)_cuda|planned_frame/planner_steady_(auto|dsm)_cuda)'
D='^(render_bilinear/[a-z0-9]+/cuda/1024|generate/(beer|compact)/cuda/1024)/'
for round in 1 2 3; do
  for v in old new; do
    timeout 100 $W/bin/bench_renderer-$v $A --benchmark_filter="$R" --benchmark_out=$L/bench_renderer-$v-$round.json > $L/bench_renderer-$v-$round.log 2>&1
    echo "bench_renderer $v $round rc=$? $(( $(date +%s)-t0 ))s"
    timeout 150 $W/bin/bench_dsm-$v $A --benchmark_filter="$D" --benchmark_out=$L/bench_dsm-$v-$round.json > $L/bench_dsm-$v-$round.log 2>&1
    echo "bench_dsm $v $round rc=$? $(( $(date +%s)-t0 ))s"
  done
done
for v in old new; do echo "== $v"; grep -h median $L/bench_renderer-$v-3.log $L/bench_dsm-$v-3.log | awk '{print $1, $2, $3}'; done
