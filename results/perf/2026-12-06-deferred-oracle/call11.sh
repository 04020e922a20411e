#!/usr/bin/env bash
# Device call 11: the final build (answer pass at 64 registers): test_frame's CUDA cases,
# memcheck of DeferredOracle.Cuda*, and the oracle goal benchmarks.
set -uo pipefail
W=$(mktemp -d); mkdir -p .gpu/x && for f in .gpu/bin/*.xz; do xz -dc "$f" > .gpu/x/$(basename "$f" .xz); done; chmod +x .gpu/x/*
B=$PWD/.gpu/x; export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/experiments/assets LD_LIBRARY_PATH=$PWD/.gpu/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.max.sm --format=csv,noheader | tee $W/gpu.txt
pack() { tar -czf $OUT/call11.tar.gz -C $W . 2>/dev/null; }
(cd $W && timeout 100 $B/test_frame > $W/test_frame.log 2>&1); echo "test_frame rc=$? $(grep -E '^\[  (PASSED|FAILED) ' $W/test_frame.log | tr '\n' ' ') skipped=$(grep -c '^\[  SKIPPED \] ' $W/test_frame.log)"
(cd $W && timeout 60 /usr/local/cuda/bin/compute-sanitizer --tool memcheck --error-exitcode 9 $B/test_frame --gtest_filter='DeferredOracle.Cuda*' > $W/cs-memcheck.log 2>&1); echo "memcheck rc=$? $(grep -E 'ERROR SUMMARY' $W/cs-memcheck.log)"
pack
timeout 60 $B/bench_renderer --benchmark_filter='goal/.*reference' --benchmark_out=$W/goal-reference.json > $W/goal-reference.log 2>&1; echo "goal rc=$?"; grep -E "^goal" $W/goal-reference.log | cut -c1-200
pack; echo all-done $(date +%T)
