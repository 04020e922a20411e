#!/usr/bin/env bash
# Device call 8 (call 7 ran test_frame and the sanitizers; its benches lacked libbenchmark):
# A/B of the
# oracle goal benchmarks (old = d95fcec build, new = this tree) in interleaved rounds, the
# lean render's stats and PNGs of both, and an Nsight Compute look at the new passes.
set -uo pipefail
W=$(mktemp -d); mkdir -p .gpu/x && for f in .gpu/bin/*.xz; do xz -dc "$f" > .gpu/x/$(basename "$f" .xz); done; chmod +x .gpu/x/*
B=$PWD/.gpu/x; export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/experiments/assets LD_LIBRARY_PATH=$PWD/.gpu/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}; S=$PWD/experiments/scenes
nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.max.sm --format=csv,noheader | tee $W/gpu.txt
pack() { tar -czf $OUT/call8.tar.gz -C $W . 2>/dev/null; }
F='goal/.*reference'; mkdir -p $W/ab
for r in 1 2 3; do
  if [ $r = 2 ]; then order="new old"; else order="old new"; fi
  for side in $order; do
    if [ $side = old ]; then s=-old; else s=; fi
    timeout 60 $B/bench_renderer$s --benchmark_filter="$F" --benchmark_out=$W/ab/$side-bench_renderer-r$r.json > $W/ab/$side-bench_renderer-r$r.log 2>&1; echo "renderer $side r$r rc=$?"
    timeout 30 $B/bench_oracle$s --benchmark_filter='render/ct_cuda' --benchmark_repetitions=3 --benchmark_out=$W/ab/$side-bench_oracle-r$r.json > $W/ab/$side-bench_oracle-r$r.log 2>&1; echo "oracle $side r$r rc=$?"
  done
  pack
done
python3 scripts/bench_summary.py $W/ab > $W/ab/summary.txt 2>&1; grep -E "real_time|goal|render" $W/ab/summary.txt | head -30
for side in old new; do if [ $side = old ]; then s=-old; else s=; fi
  for sc in knecht-fig56 knecht-32-lights ct-phantom; do
    (cd $W && timeout 60 $B/deepvox-lean$s render $S/$sc.json --backend cuda --shadows reference --frames 3 --stats $W/stats-$side-$sc.json --out $W/$side-$sc.png > $W/render-$side-$sc.log 2>&1); echo "render $side $sc rc=$?"
  done
  (cd $W && timeout 60 $B/deepvox-lean$s render $S/ct-phantom.json --renderer raytrace --backend cuda --shadows reference --frames 3 --stats $W/stats-$side-ct-raytrace.json --out $W/$side-ct-raytrace.png > $W/render-$side-ct-raytrace.log 2>&1); echo "render $side ct raytrace rc=$?"
done
for sc in knecht-fig56 knecht-32-lights ct-phantom ct-raytrace; do cmp -s $W/old-$sc.png $W/new-$sc.png && echo "png $sc identical" || echo "png $sc DIFFERS"; done
pack
for res in 512 1024; do (cd $W && timeout 60 $B/deepvox-lean render $S/knecht-32-lights.json --backend cuda --shadows dsm --dsm-res $res --frames 2 --stats $W/stats-lights32-dsm$res.json --out l.png > $W/render-lights32-dsm$res.log 2>&1); echo "lights32 dsm $res rc=$? $(grep -A2 '"device_memory"' $W/stats-lights32-dsm$res.json | tr -d ' \n')"; done
timeout 100 $B/bench_renderer --benchmark_filter='goal/.*/(none|shadowmap|dsm)' --benchmark_repetitions=3 --benchmark_report_aggregates_only=true --benchmark_out=$W/goal-new.json > $W/goal-new.log 2>&1; echo "goal rc=$?"; grep -E "_median" $W/goal-new.log | cut -c1-120
timeout 90 $B/bench_renderer --benchmark_filter='feature/' --benchmark_repetitions=3 --benchmark_report_aggregates_only=true --benchmark_out=$W/feature-new.json > $W/feature-new.log 2>&1; echo "feature rc=$?"; grep -E "_median" $W/feature-new.log | cut -c1-110
pack
NCU=/usr/local/cuda/bin/ncu
(cd $W && timeout 90 $NCU --kernel-name-base demangled -k regex:'answer_oracle_queries|shade_fragment_threads' --launch-count 4 --section SpeedOfLight --section Occupancy --section LaunchStats --section WarpStateStats --section MemoryWorkloadAnalysis -o deferred-720 $B/deepvox-lean render $S/knecht-fig56.json --backend cuda --shadows reference --frames 1 --out o.png > ncu.log 2>&1); echo "ncu rc=$?"
timeout 20 $NCU --import $W/deferred-720.ncu-rep --page details > $W/deferred-720-details.txt 2>&1
rm -f $W/o.png $W/l*.png; pack
echo all-done $(date +%T)
