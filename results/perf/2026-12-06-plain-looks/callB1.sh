#!/usr/bin/env bash
# Device call B1 (session 7): the camera pass's kernel for plain surface looks. CUDA tests (test_frame
# whole, SurfaceLooks.* among them) and memcheck of the new kernels; bench_renderer looks/ (fitted
# against general kernel in one binary, repetitions randomly interleaved); old (923724f) against new
# bench_renderer on fig56's goal rows, the feature/ rows and knecht-32-lights' goal rows, rounds
# old new new old; the issue-52 table with render --stats on this card.
set -uo pipefail
LIMIT=${LIMIT:-560}
G=$PWD/.gpu7; W=$(mktemp -d); mkdir -p $G/x && for f in $G/bin/*.xz; do xz -T4 -dc "$f" > $G/x/$(basename "$f" .xz) & done; wait; chmod +x $G/x/*
B=$G/x; export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/experiments/assets LD_LIBRARY_PATH=$G/lib; S=$PWD/experiments/scenes
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm,persistence_mode --format=csv,noheader | tee $W/gpu.txt
pack() { tar -cJf $OUT/callB1.tar.xz -C $W . 2>/dev/null; }
summ() { echo "$(grep -E '^\[  (PASSED|FAILED) |ERROR SUMMARY' $1 | tr '\n' ' ') skipped=$(grep -c '^\[  SKIPPED \] ' $1)"; }
left() { [ $SECONDS -lt $1 ]; }
(cd $W && timeout 150 $B/test_frame > $W/test_frame.log 2>&1); echo "test_frame rc=$? $(summ $W/test_frame.log) t=$SECONDS"; grep -E "^\[  FAILED" $W/test_frame.log | head
(cd $W && timeout 90 /usr/local/cuda/bin/compute-sanitizer --tool memcheck --error-exitcode 9 $B/test_frame --gtest_filter='SurfaceLooks.Cuda*' > $W/memcheck.log 2>&1); echo "memcheck SurfaceLooks.Cuda* rc=$? $(summ $W/memcheck.log) t=$SECONDS"
pack
timeout 100 $B/bench_renderer --benchmark_filter='^looks/' --benchmark_repetitions=5 --benchmark_enable_random_interleaving=true --benchmark_out=$W/looks.json > $W/looks.log 2>&1; echo "looks rc=$? t=$SECONDS"; grep -E "_median" $W/looks.log | cut -c1-100
pack
F='^(goal/knecht-fig56/(none|shadowmap)/scene|goal/knecht-32-lights/(dsm_res=512|shadowmap)/|raster_render/fig56_(none|shadowmap)_cuda|feature/)'
r=0; for side in old new new old; do r=$((r+1)); left $((LIMIT-70)) || break
  s=; [ $side = old ] && s=-old
  timeout 90 $B/bench_renderer$s --benchmark_filter="$F" --benchmark_out=$W/$side-bench_renderer-r$r.json > $W/$side-r$r.log 2>&1; echo "renderer $side r$r rc=$? t=$SECONDS"
  pack
done
python3 scripts/bench_summary.py $W > $W/summary.txt 2>&1; cut -c1-150 $W/summary.txt | grep -v "counter\|_ms" | head -40
for res in 512 1024; do left $((LIMIT-15)) || break
  (cd $W && timeout 30 $B/deepvox-lean render $S/knecht-32-lights.json --backend cuda --shadows dsm --dsm-res $res --frames 4 --stats $W/fp-$res.json --out $W/fp.png > $W/fp-$res.log 2>&1); echo "l32 dsm $res rc=$? $(python3 -c "
import json,statistics as s;j=json.load(open('$W/fp-$res.json'));st=j['shadows']['stats'];f=j['frames']
print('peak_used',j['device_memory']['peak_used_bytes'],'gen_ms',round(st['generation_ms'],2),'passes',[(p['pass'],round(p['ms'],2)) for p in st['passes']],'frame_ms med',round(s.median([x['milliseconds'] for x in f[1:]]),2))" 2>&1 | cut -c1-250) t=$SECONDS"
done
rm -f $W/*.png; pack; echo all-done t=$SECONDS
