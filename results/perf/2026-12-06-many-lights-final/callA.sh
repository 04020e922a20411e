#!/usr/bin/env bash
# Device call A (session 7): issue 52 on the final tree (923724f). CUDA tests of the light loops,
# shared tables, face sets and device out-of-memory; memcheck of the light loops and the face-set
# generation; the issue's table on this card (render --stats as the issue measured it, bench_dsm
# lights32, bench_renderer goal rows of knecht-32-lights and fig56); one Nsight Compute profile of
# the counting walk (dsm_compact_count) at 512^2.
set -uo pipefail
LIMIT=${LIMIT:-540}
G=$PWD/.gpu6; W=$(mktemp -d); mkdir -p $G/x && for f in $G/bin/*.xz; do xz -T4 -dc "$f" > $G/x/$(basename "$f" .xz) & done; wait; chmod +x $G/x/*
B=$G/x; export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/experiments/assets LD_LIBRARY_PATH=$G/lib; S=$PWD/experiments/scenes
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm,persistence_mode --format=csv,noheader | tee $W/gpu.txt
pack() { tar -cJf $OUT/callA.tar.xz -C $W . 2>/dev/null; }
summ() { echo "$(grep -E '^\[  (PASSED|FAILED) |ERROR SUMMARY' $1 | tr '\n' ' ') skipped=$(grep -c '^\[  SKIPPED \] ' $1)"; }
left() { [ $SECONDS -lt $1 ]; }
(cd $W && timeout 150 $B/test_frame > $W/test_frame.log 2>&1); echo "test_frame rc=$? $(summ $W/test_frame.log) t=$SECONDS"
(cd $W && timeout 90 $B/test_storage --gtest_filter='CompactFaceSets.*' > $W/test_storage.log 2>&1); echo "test_storage rc=$? $(summ $W/test_storage.log) t=$SECONDS"
(cd $W && timeout 60 $B/test_core --gtest_filter='DeviceOutOfMemory.*:SharedTables.*:Backends.*' > $W/test_core.log 2>&1); echo "test_core rc=$? $(summ $W/test_core.log) t=$SECONDS"
(cd $W && timeout 90 /usr/local/cuda/bin/compute-sanitizer --tool memcheck --error-exitcode 9 $B/test_frame --gtest_filter='LightCulling.Cuda*' > $W/memcheck-frame.log 2>&1); echo "memcheck test_frame LightCulling.Cuda* rc=$? $(summ $W/memcheck-frame.log) t=$SECONDS"
(cd $W && timeout 120 /usr/local/cuda/bin/compute-sanitizer --tool memcheck --error-exitcode 9 $B/test_storage --gtest_filter='CompactFaceSets.*' > $W/memcheck-storage.log 2>&1); echo "memcheck test_storage CompactFaceSets.* rc=$? $(summ $W/memcheck-storage.log) t=$SECONDS"
pack
for res in 512 1024; do
  (cd $W && timeout 40 $B/deepvox-lean render $S/knecht-32-lights.json --backend cuda --shadows dsm --dsm-res $res --frames 4 --stats $W/fp-$res.json --out $W/fp.png > $W/fp-$res.log 2>&1); echo "l32 dsm $res 720x480 rc=$? $(python3 -c "
import json,statistics as s;j=json.load(open('$W/fp-$res.json'));st=j['shadows']['stats'];f=j['frames']
print('peak_used',j['device_memory']['peak_used_bytes'],'gen_ms',round(st['generation_ms'],2),'bytes',st['storage']['bytes_allocated'],'frame_ms med',round(s.median([x['milliseconds'] for x in f[1:]]),2),'lpp',round(f[-1].get('lights_per_pixel_mean',0),2))" 2>&1 | cut -c1-220) t=$SECONDS"
done
for sh in dsm shadowmap; do for wh in "1920 1080" "3840 2160"; do set -- $wh
  (cd $W && timeout 60 $B/deepvox-lean render $S/knecht-32-lights.json --backend cuda --shadows $sh --dsm-res 512 --width $1 --height $2 --frames 4 --stats $W/l32-$sh-$1.json --out $W/fp.png > $W/l32-$sh-$1.log 2>&1); echo "l32 $sh $1 rc=$? $(python3 -c "import json,statistics as s;f=json.load(open('$W/l32-$sh-$1.json'))['frames'];print(round(s.median([x['milliseconds'] for x in f[1:]]),2),'ms lpp',round(f[-1].get('lights_per_pixel_mean',0),2))" 2>&1) t=$SECONDS"
done; done
rm -f $W/*.png; pack
left $((LIMIT-150)) && { timeout 120 $B/bench_dsm --benchmark_filter='lights32/cuda' --benchmark_repetitions=3 --benchmark_out=$W/bench_dsm.json > $W/bench_dsm.log 2>&1; echo "bench_dsm rc=$? t=$SECONDS"; grep -E "median" $W/bench_dsm.log | cut -c1-200; }
F='^(goal/knecht-fig56/(none|shadowmap)/scene|goal/knecht-32-lights/(dsm_res=512|shadowmap)/|raster_render/fig56_(none|shadowmap)_cuda)'
left $((LIMIT-120)) && { timeout 150 $B/bench_renderer --benchmark_filter="$F" --benchmark_repetitions=3 --benchmark_out=$W/bench_renderer.json > $W/bench_renderer.log 2>&1; echo "bench_renderer rc=$? t=$SECONDS"; grep -E "median" $W/bench_renderer.log | cut -c1-110; }
pack
left $((LIMIT-90)) && { (cd $W && timeout 90 /usr/local/cuda/bin/ncu --set full --kernel-name-base demangled -k regex:count_nodes --launch-skip 0 --launch-count 1 -o $W/count512 $B/deepvox-lean render $S/knecht-32-lights.json --backend cuda --shadows dsm --dsm-res 512 --frames 1 --out $W/n.png > $W/ncu.log 2>&1); echo "ncu rc=$? t=$SECONDS"; /usr/local/cuda/bin/ncu --import $W/count512.ncu-rep --page details > $W/count512-details.txt 2>&1; /usr/local/cuda/bin/ncu --import $W/count512.ncu-rep --page raw --csv > $W/count512-raw.csv 2>&1; grep -E "Duration|Registers Per|Achieved Occupancy|Compute \(SM\) Throughput|Memory Throughput|DRAM Throughput" $W/count512-details.txt | head -12; }
rm -f $W/*.png $W/*.ncu-rep; pack; echo all-done t=$SECONDS
