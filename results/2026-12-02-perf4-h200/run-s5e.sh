#!/bin/bash
# Session 5, call 5: the walk's tests combined with & instead of && (no branch between them;
# bench_voxelizer-and) and, on top, two columns walked at a time with their steps interleaved
# (bench_voxelizer-pair), each with its test_voxel, against the committed 8e318ed
# (bench_voxelizer-flat). '^sat/' rows, 3 repetitions, interleaved, three rounds.
set -u
G=$PWD/.gpu; W=$(mktemp -d); mkdir -p $W/bin
export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/assets LD_LIBRARY_PATH=$G/lib:${LD_LIBRARY_PATH:-}
for f in $G/bin/*.xz; do b=$W/bin/$(basename $f .xz); xz -dc $f > $b; chmod +x $b; done
L=$W/s5e; mkdir -p $L
trap 'tar -czf $OUT/s5e.tar.gz -C $L .' EXIT
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $L/gpu.txt 2>&1; cat $L/gpu.txt
t0=$(date +%s)
for t in test_voxel-and test_voxel-pair; do
  timeout 120 $W/bin/$t > $L/$t.log 2>&1; echo "$t rc=$? $(grep -E '^\[  (PASSED|FAILED|SKIPPED) ' $L/$t.log | tr '\n' ' ') $(( $(date +%s)-t0 ))s"
done
grep -h "^\[  FAILED  \]" $L/test_*.log | sort -u | head
A="--benchmark_repetitions=3 --benchmark_min_time=0.1 --benchmark_report_aggregates_only=true --benchmark_filter=^sat/"
for round in 1 2 3; do
  for b in bench_voxelizer-flat bench_voxelizer-and bench_voxelizer-pair; do
    timeout 100 $W/bin/$b $A --benchmark_out=$L/$b-$round.json > $L/$b-$round.log 2>&1
    echo "$b round $round rc=$? $(( $(date +%s)-t0 ))s"
  done
done
for b in bench_voxelizer-flat bench_voxelizer-and bench_voxelizer-pair; do
  echo "== $b"; grep median $L/$b-3.log | grep -oE "^[^ ]+|small_ms=[^ ]+|large_ms=[^ ]+|with_clear_ms=[^ ]+" | paste - - - -
done
