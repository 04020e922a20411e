#!/bin/bash
# Session 5, call 2: what bounds the sat small pass now: the new build against a diagnostic
# build of the same code whose grid writes are compiled out (or_word's atomic guarded by a mask
# value that never occurs), '^sat/bunny' rows, 3 repetitions each, interleaved, twice.
set -u
G=$PWD/.gpu; W=$(mktemp -d); mkdir -p $W/bin
export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/assets LD_LIBRARY_PATH=$G/lib:${LD_LIBRARY_PATH:-}
for f in $G/bin/*.xz; do b=$W/bin/$(basename $f .xz); xz -dc $f > $b; chmod +x $b; done
L=$W/s5b; mkdir -p $L
trap 'tar -czf $OUT/s5b.tar.gz -C $L .' EXIT
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $L/gpu.txt 2>&1; cat $L/gpu.txt
t0=$(date +%s)
A="--benchmark_repetitions=3 --benchmark_min_time=0.1 --benchmark_report_aggregates_only=true --benchmark_filter=^sat/bunny"
for round in 1 2; do
  for b in bench_voxelizer bench_voxelizer-noatomic; do
    timeout 120 $W/bin/$b $A --benchmark_out=$L/$b-$round.json > $L/$b-$round.log 2>&1
    echo "$b round $round rc=$? $(( $(date +%s)-t0 ))s"
  done
done
for b in bench_voxelizer bench_voxelizer-noatomic; do
  echo "== $b"; grep median $L/$b-2.log | grep -oE "^[^ ]+|small_ms=[^ ]+|with_clear_ms=[^ ]+" | paste - - -
done
