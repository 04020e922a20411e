#!/bin/bash
# Session 5, call 1: the sat walk picked by selects (one code path for the three walk axes,
# no window widening, stop after the run): test_voxel on the GPU; bench_voxelizer '^sat/'
# old (f2033e6 CI build) and new, interleaved, 5 repetitions each; the small-threshold sweep.
set -u
G=$PWD/.gpu; W=$(mktemp -d); mkdir -p $W/bin
export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/assets LD_LIBRARY_PATH=$G/lib:${LD_LIBRARY_PATH:-}
for f in $G/bin/*.xz; do b=$W/bin/$(basename $f .xz); xz -dc $f > $b; chmod +x $b; done
L=$W/s5a; mkdir -p $L
trap 'tar -czf $OUT/s5a.tar.gz -C $L .' EXIT
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $L/gpu.txt 2>&1; cat $L/gpu.txt
t0=$(date +%s)
timeout 120 $W/bin/test_voxel > $L/test_voxel.log 2>&1; echo "test_voxel rc=$? $(grep -E '^\[  (PASSED|FAILED|SKIPPED) ' $L/test_voxel.log | tr '\n' ' ') $(( $(date +%s)-t0 ))s"
grep -h "^\[  FAILED  \]" $L/test_*.log | sort -u | head
A="--benchmark_repetitions=5 --benchmark_report_aggregates_only=true --benchmark_filter=^sat/"
for round in 1 2; do
  for b in bench_voxelizer-old bench_voxelizer; do
    timeout 100 $W/bin/$b $A --benchmark_out=$L/$b-$round.json > $L/$b-$round.log 2>&1
    echo "$b round $round rc=$? $(( $(date +%s)-t0 ))s"
  done
done
for b in bench_voxelizer-old bench_voxelizer; do
  echo "== $b"; grep median $L/$b-2.log | sed -E 's/ +/ /g' | cut -c1-230
done
timeout 150 $W/bin/bench_voxelizer --benchmark_min_time=0.2 --benchmark_filter='^sat_small/bunny' > $L/sweep.log 2>&1
echo "sweep rc=$? $(( $(date +%s)-t0 ))s"; grep -E "^sat_small" $L/sweep.log | awk '{print $1, $2}'
