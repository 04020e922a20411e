#!/usr/bin/env bash
# Device call 12a: Nsight Compute (full set, roofline) of the goal frames' heavy kernels (main
# f7abaa7 plus light culling), the exact oracle's probe answers of d95fcec and this build on CUDA
# at every committed scene's 400 seeded points, test_frame's culling and deferred-oracle cases,
# racecheck.
set -uo pipefail
W=$(mktemp -d); mkdir -p .gpu/x && for f in .gpu/bin/*.xz; do xz -dc "$f" > .gpu/x/$(basename "$f" .xz); done; chmod +x .gpu/x/*
B=$PWD/.gpu/x; export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/experiments/assets; S=$PWD/experiments/scenes
nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.max.sm --format=csv,noheader | tee $W/gpu.txt
pack() { tar -czf $OUT/call12a.tar.gz -C $W . 2>/dev/null; }
NCU=/usr/local/cuda/bin/ncu
prof() { # name kernel-regex launch-skip args...
  local n=$1 k=$2 skip=$3; shift 3
  (cd $W && timeout 120 $NCU --set full --kernel-name-base demangled -k regex:"$k" --launch-skip $skip --launch-count 1 -o $n $B/deepvox-lean render "$@" --backend cuda --frames 1 --out o.png > ncu-$n.log 2>&1); echo "ncu $n rc=$? $(date +%T)"
  timeout 30 $NCU --import $W/$n.ncu-rep --page details > $W/$n-details.txt 2>&1
  timeout 30 $NCU --import $W/$n.ncu-rep --page raw --csv > $W/$n-raw.csv 2>&1
  grep -E "^  [a-z].*Context|Duration|Registers Per|Achieved Occupancy|Compute \(SM\) Throughput|Memory Throughput|DRAM Throughput|Executed Ipc A|Local Memory Spilling|Stack Size" $W/$n-details.txt | head -14 | cut -c1-160
}
prof fig56-4k-none shade_fragment_threads 0 $S/knecht-fig56.json --shadows none --width 3840 --height 2160
prof fig56-4k-shadowmap shade_fragment_threads 0 $S/knecht-fig56.json --shadows shadowmap --width 3840 --height 2160
prof fig56-4k-dsm shade_fragment_threads 0 $S/knecht-fig56.json --shadows dsm --width 3840 --height 2160
prof fig56-1080-dsm shade_fragment_threads 0 $S/knecht-fig56.json --shadows dsm --width 1920 --height 1080
pack
prof fig56-720-answers answer_oracle_queries 0 $S/knecht-fig56.json --shadows reference
prof fig56-1080-answers answer_oracle_queries 0 $S/knecht-fig56.json --shadows reference --width 1920 --height 1080
prof ct-raytrace-answers answer_oracle_queries 0 $S/ct-phantom.json --shadows reference --renderer raytrace
prof lights32-4k-shadowmap shade_fragment_threads 0 $S/knecht-32-lights.json --shadows shadowmap --width 3840 --height 2160
prof lights32-count-nodes count_nodes 0 $S/knecht-32-lights.json --shadows dsm --dsm-res 512
rm -f $W/*.ncu-rep $W/o.png; pack
(cd $W && timeout 150 $B/test_frame --gtest_filter='LightCulling.*:DeferredOracle.*' > $W/test_frame-culling.log 2>&1); echo "test_frame culling+deferred rc=$? $(grep -E '^\[  (PASSED|FAILED) ' $W/test_frame-culling.log | tr '\n' ' ') skipped=$(grep -c '^\[  SKIPPED \] ' $W/test_frame-culling.log)"
pack
(cd $W && timeout 200 /usr/local/cuda/bin/compute-sanitizer --tool racecheck --error-exitcode 9 $B/test_frame --gtest_filter='DeferredOracle.CudaGives*:LightCulling.CudaExact*' > $W/cs-racecheck.log 2>&1); echo "racecheck rc=$? $(grep -E 'RACECHECK SUMMARY|ERROR SUMMARY' $W/cs-racecheck.log | head -2 | tr '\n' ' ')"
(timeout 240 .gpu/probe_compare.sh $B/deepvox-lean-old $B/deepvox-lean cuda $W/probe > $W/probe-summary.txt 2>&1); echo "probe rc=$?"; tail -2 $W/probe-summary.txt
tar -czf $W/probe.tgz -C $W probe && rm -rf $W/probe
pack
echo all-done $(date +%T)
