#!/bin/bash
# Fourteenth round, call 2: sat's float filter with the tests' coordinates taken from the
# triangle's first voxel (bounds of a few voxels' terms, not the grid's): f3 decides a close
# test in double from the walk kept on the stack; f7 keeps no double walk and hands a triangle
# with a close test to the large (double) pass. Against main (un, b7e7935): test_voxel-f3/-f7
# on the GPU (f7 fails SatWorkSplit's "no large triangle when all are small", by design), then
# bench_voxelizer '^sat/' interleaved, three rounds of 3 repetitions; f7r is f7 compiled with
# -maxrregcount=128 (ptxas: 32 bytes of spill in the small pass).
set -u
G=$PWD/.gpu; W=$(mktemp -d); mkdir -p $W/bin
export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/assets LD_LIBRARY_PATH=$G/lib:${LD_LIBRARY_PATH:-}
for f in $G/bin/*.xz; do b=$W/bin/$(basename $f .xz); xz -dc $f > $b; chmod +x $b; done
L=$W/g2; mkdir -p $L
trap 'tar -czf $OUT/g2.tar.gz -C $L .' EXIT
exec > >(tee $L/run.log) 2>&1
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $L/gpu.txt 2>&1; cat $L/gpu.txt
t0=$(date +%s)
for t in test_voxel-f3 test_voxel-f7; do
  timeout 150 $W/bin/$t > $L/$t.log 2>&1; echo "$t rc=$? $(grep -E '^\[  (PASSED|FAILED|SKIPPED) ' $L/$t.log | tr '\n' ' ') $(( $(date +%s)-t0 ))s"
done
grep -h "^\[  FAILED  \]" $L/test_*.log | sort -u | head
A="--benchmark_repetitions=3 --benchmark_min_time=0.1 --benchmark_report_aggregates_only=true --benchmark_filter=^sat/"
for round in 1 2 3; do
  for v in un f3 f7 f7r; do
    timeout 100 $W/bin/bench_voxelizer-$v $A --benchmark_out=$L/bench_voxelizer-$v-$round.json > $L/bench_voxelizer-$v-$round.log 2>&1
    echo "bench_voxelizer $v round $round rc=$? $(( $(date +%s)-t0 ))s"
  done
done
for v in un f3 f7 f7r; do
  echo "== $v"; grep median $L/bench_voxelizer-$v-3.log | grep -oE "^[^ ]+|small_ms=[^ ]+|with_clear_ms=[^ ]+" | paste - - -
done
echo "total $(( $(date +%s)-t0 ))s"
