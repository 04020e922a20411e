#!/usr/bin/env bash
# Device call 5: bench_renderer's goal/ cases and bench_dsm's lights32 at ef3c985.
set -uo pipefail
W=$(mktemp -d); mkdir -p .gpu/bin && for f in .gpu/bin5/*.xz; do xz -dc "$f" > .gpu/bin/$(basename "$f" .xz); done; chmod +x .gpu/bin/*
B=$PWD/.gpu/bin; export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/experiments/assets LD_LIBRARY_PATH=$PWD/.gpu/lib:${LD_LIBRARY_PATH:-}
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $W/gpu.txt
timeout 300 $B/bench_renderer --benchmark_filter='goal/' --benchmark_repetitions=3 --benchmark_report_aggregates_only=true --benchmark_out=$W/goal.json --benchmark_out_format=json > $W/goal.log 2>&1; echo "goal rc=$?"
grep -E "_median" $W/goal.log | awk '{printf "%s %s %s\n", $1, $2, $3}'
tar -czf $OUT/call5.tar.gz -C $W .
timeout 150 $B/bench_dsm --benchmark_filter='lights32/cuda' --benchmark_out=$W/lights32.json --benchmark_out_format=json > $W/lights32.log 2>&1; echo "lights32 rc=$?"; grep -E "lights32" $W/lights32.log | head -6
tar -czf $OUT/call5.tar.gz -C $W .
