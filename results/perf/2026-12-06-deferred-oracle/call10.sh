#!/usr/bin/env bash
# Device call 10: the final deferred oracle (answers sorted by light and cost, 128-register
# budget): test_frame's CUDA cases and memcheck/racecheck of DeferredOracle.Cuda*; the answer
# pass's register budget b2 (final) against b3, b4 and v0 (the first deferred build: pixel
# order, no budget) in two interleaved rounds, PNGs equal to v0's; then the oracle goal
# benchmarks of d95fcec (old) and this tree (new), interleaved old, new, new, old.
set -uo pipefail
W=$(mktemp -d); mkdir -p .gpu/x && for f in .gpu/bin/*.xz; do xz -dc "$f" > .gpu/x/$(basename "$f" .xz); done; chmod +x .gpu/x/*
B=$PWD/.gpu/x; export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/experiments/assets LD_LIBRARY_PATH=$PWD/.gpu/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}; S=$PWD/experiments/scenes
nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.max.sm --format=csv,noheader | tee $W/gpu.txt
pack() { tar -czf $OUT/call10.tar.gz -C $W . 2>/dev/null; }
(cd $W && timeout 150 $B/test_frame > $W/test_frame.log 2>&1); echo "test_frame rc=$? $(grep -E '^\[  (PASSED|FAILED) ' $W/test_frame.log | tr '\n' ' ') skipped=$(grep -c '^\[  SKIPPED \] ' $W/test_frame.log)"
grep -E '^\[  FAILED  \]|^\[  SKIPPED \]' $W/test_frame.log | head -12
CS=/usr/local/cuda/bin/compute-sanitizer
for tool in memcheck racecheck; do (cd $W && timeout 100 $CS --tool $tool --error-exitcode 9 $B/test_frame --gtest_filter='DeferredOracle.Cuda*' > $W/cs-$tool.log 2>&1); echo "$tool rc=$? $(grep -E 'ERROR SUMMARY|RACECHECK SUMMARY' $W/cs-$tool.log | tr '\n' ' ')"; done
pack
one() { local v=$1 r=$2 name=$3; shift 3
  (cd $W && timeout 60 $B/deepvox-lean-$v render "$@" --backend cuda --shadows reference --stats $W/$v-$name-r$r.json --out $W/$v-$name-r$r.png > $W/$v-$name-r$r.log 2>&1) || echo "$v $name r$r rc=$?"; }
for r in 1 2; do
  if [ $r = 1 ]; then order="v0 b2 b3 b4"; else order="b4 b3 b2 v0"; fi
  for v in $order; do
    one $v $r fig56 $S/knecht-fig56.json --frames 4
    one $v $r fig56-1080 $S/knecht-fig56.json --width 1920 --height 1080 --frames 3
    one $v $r lights32 $S/knecht-32-lights.json --frames 2
    one $v $r ct-raytrace $S/ct-phantom.json --renderer raytrace --frames 3
  done
  pack
done
for f in $W/v0-*_0000.png; do b=$(basename $f); for v in b2 b3 b4; do cmp -s $f $W/${b/v0/$v} || echo "png ${b/v0/$v} DIFFERS from v0"; done; done
echo png-check-done; rm -f $W/*.png; pack
mkdir -p $W/ab; F='goal/.*reference'
for side in old new new old; do if [ $side = old ]; then s=-old; r=$([ -e $W/ab/old-bench_renderer-r1.json ] && echo 2 || echo 1); else s=; r=$([ -e $W/ab/new-bench_renderer-r1.json ] && echo 2 || echo 1); fi
  timeout 60 $B/bench_renderer$s --benchmark_filter="$F" --benchmark_out=$W/ab/$side-bench_renderer-r$r.json > $W/ab/$side-bench_renderer-r$r.log 2>&1; echo "renderer $side r$r rc=$?"; done
python3 scripts/bench_summary.py $W/ab > $W/ab/summary.txt 2>&1; cat $W/ab/summary.txt | head -12
pack; echo all-done $(date +%T)
