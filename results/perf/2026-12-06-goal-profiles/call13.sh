#!/usr/bin/env bash
# Device call 13: compact's face sets (merge cee8710) checked on CUDA (tests, image bits against
# bfefef3, peak device memory and generation time of knecht-32-lights), then as time allows an
# interleaved A/B of the goal benchmarks (old = d95fcec, new = cee8710), Nsight Compute of the
# oracle's answer pass, and knecht-32-lights frames with and without light culling.
set -uo pipefail
LIMIT=${LIMIT:-400}
W=$(mktemp -d); mkdir -p .gpu/x && for f in .gpu/bin/*.xz; do xz -dc "$f" > .gpu/x/$(basename "$f" .xz); done; chmod +x .gpu/x/*
B=$PWD/.gpu/x; export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/experiments/assets LD_LIBRARY_PATH=$PWD/.gpu/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}; S=$PWD/experiments/scenes
nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.max.sm --format=csv,noheader | tee $W/gpu.txt
pack() { tar -czf $OUT/call13.tar.gz -C $W . 2>/dev/null; }
left() { [ $SECONDS -lt $1 ]; }
(cd $W && timeout 150 $B/test_storage --gtest_filter='CompactFaceSets.*:StorageBackends.*:Storages/*:StorageSizing.*' > $W/test_storage.log 2>&1); echo "test_storage rc=$? $(grep -E '^\[  (PASSED|FAILED) ' $W/test_storage.log | tr '\n' ' ') skipped=$(grep -c '^\[  SKIPPED \] ' $W/test_storage.log) t=$SECONDS"
(cd $W && timeout 90 $B/test_dsm --gtest_filter='*NodeReplay*:ClusteredMaps.CpuAndCudaAgree' > $W/test_dsm.log 2>&1); echo "test_dsm rc=$? $(grep -E '^\[  (PASSED|FAILED) ' $W/test_dsm.log | tr '\n' ' ') skipped=$(grep -c '^\[  SKIPPED \] ' $W/test_dsm.log) t=$SECONDS"
pack
for res in 512 1024; do for side in before sets; do b=$B/deepvox-lean; [ $side = before ] && b=$B/deepvox-lean-bfefef3
  (cd $W && timeout 60 $b render $S/knecht-32-lights.json --backend cuda --shadows dsm --dsm-res $res --frames 3 --stats $W/fp-$side-$res.json --out $W/fp-$side-$res.png > $W/fp-$side-$res.log 2>&1); echo "footprint $side $res rc=$? $(python3 -c "
import json;j=json.load(open('$W/fp-$side-$res.json'));st=j['shadows']['stats']
print('peak_used',j['device_memory']['peak_used_bytes'],'reserved_now',j['device_memory']['reserved_bytes'],'gen_ms',round(st['generation_ms'],2),'sets',st.get('face_sets'),'frame_ms',[round(x['milliseconds'],2) for x in j['frames']])" 2>&1 | cut -c1-200)"
done; cmp $W/fp-before-$res.png $W/fp-sets-$res.png && echo "png $res identical" || echo "png $res DIFFERS"; done
pack
mkdir -p $W/ab
for r in 1 2; do left $((LIMIT-170)) || break
  if [ $r = 2 ]; then order="new old"; else order="old new"; fi
  for side in $order; do s=; [ $side = old ] && s=-old
    timeout 120 $B/bench_renderer$s --benchmark_filter='goal/' --benchmark_out=$W/ab/$side-bench_renderer-r$r.json > $W/ab/$side-bench_renderer-r$r.log 2>&1; echo "renderer $side r$r rc=$? t=$SECONDS"
  done; pack
done
python3 scripts/bench_summary.py $W/ab > $W/ab/summary.txt 2>&1; cut -c1-160 $W/ab/summary.txt | head -30
NCU=/usr/local/cuda/bin/ncu
prof() { local n=$1 k=$2 skip=$3; shift 3
  (cd $W && timeout 60 $NCU --set full --kernel-name-base demangled -k regex:"$k" --launch-skip $skip --launch-count 1 -o $n $B/deepvox-lean render "$@" --backend cuda --frames 1 --out o.png > ncu-$n.log 2>&1); echo "ncu $n rc=$? t=$SECONDS"
  timeout 30 $NCU --import $W/$n.ncu-rep --page details > $W/$n-details.txt 2>&1; timeout 30 $NCU --import $W/$n.ncu-rep --page raw --csv > $W/$n-raw.csv 2>&1
  grep -E "Duration|Registers Per|Achieved Occupancy|Avg. Active Threads" $W/$n-details.txt | head -4 | cut -c1-120; }
left $((LIMIT-60)) && prof fig56-720-answers answer_oracle_queries 1 $S/knecht-fig56.json --shadows reference
left $((LIMIT-45)) && prof ct-raytrace-answers answer_oracle_queries 1 $S/ct-phantom.json --shadows reference --renderer raytrace
rm -f $W/*.ncu-rep $W/o.png; pack
for cull in on off; do a=; [ $cull = off ] && a=--no-light-culling
  for sh in shadowmap dsm; do for wh in "720 480" "3840 2160"; do set -- $wh; left $((LIMIT-12)) || continue
    (cd $W && timeout 40 $B/deepvox-lean render $S/knecht-32-lights.json --backend cuda --shadows $sh --dsm-res 512 --width $1 --height $2 --frames 4 $a --stats $W/l32-$sh-$1-$cull.json --out l.png > $W/l32-$sh-$1-$cull.log 2>&1); echo "l32 $sh $1 $cull rc=$? $(python3 -c "import json,statistics as s;f=json.load(open('$W/l32-$sh-$1-$cull.json'))['frames'];print(round(s.median([x['milliseconds'] for x in f[1:]]),2),'ms lpp',round(f[-1]['lights_per_pixel_mean'],2))" 2>&1)"
  done; done
done
rm -f $W/l*.png $W/fp-*.png; pack; echo all-done t=$SECONDS $(date +%T)
