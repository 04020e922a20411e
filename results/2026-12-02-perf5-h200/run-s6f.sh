#!/bin/bash
# Session 6, call 6: the final code (sat's clear, small and large passes queued back to back
# under one PassTimeline; the launch guard; the raster hardening): the CUDA suites test_core,
# test_voxel, test_raster, test_render, test_dsm, test_hard; then bench_voxelizer '^sat/'
# (3 repetitions) of the final build (new) against 8bd835d's CI build (old: every pass timed
# from a synchronised start), interleaved, three rounds.
set -u
G=$PWD/.gpu; W=$(mktemp -d); mkdir -p $W/bin
export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/assets LD_LIBRARY_PATH=$G/lib:${LD_LIBRARY_PATH:-}
for f in $G/bin/*.xz; do b=$W/bin/$(basename $f .xz); xz -dc $f > $b; chmod +x $b; done
L=$W/s6f; mkdir -p $L
trap 'tar -czf $OUT/s6f.tar.gz -C $L .' EXIT
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $L/gpu.txt 2>&1; cat $L/gpu.txt
t0=$(date +%s)
for t in test_core test_voxel test_raster test_render test_dsm test_hard; do
  timeout 200 $W/bin/$t > $L/$t.log 2>&1; echo "$t rc=$? $(grep -E '^\[  (PASSED|FAILED) ' $L/$t.log | tr '\n' ' ') skipped=$(grep -cE '^\[  SKIPPED \] .*\(' $L/$t.log) $(( $(date +%s)-t0 ))s"
done
grep -h "^\[  FAILED  \]" $L/test_*.log | sort -u | head
A="--benchmark_repetitions=3 --benchmark_min_time=0.1 --benchmark_report_aggregates_only=true --benchmark_filter=^sat/"
for round in 1 2 3; do
  for v in old new; do
    timeout 100 $W/bin/bench_voxelizer-$v $A --benchmark_out=$L/bench_voxelizer-$v-$round.json > $L/bench_voxelizer-$v-$round.log 2>&1
    echo "bench_voxelizer $v round $round rc=$? $(( $(date +%s)-t0 ))s"
  done
done
for v in old new; do
  echo "== $v"; grep median $L/bench_voxelizer-$v-3.log | grep -oE "^[^ ]+|small_ms=[^ ]+|large_ms=[^ ]+|clear_ms=[^ ]+|with_clear_ms=[^ ]+" | paste - - - - -
done
