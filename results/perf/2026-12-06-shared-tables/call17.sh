#!/usr/bin/env bash
# Device call 17 (session 6): the final tree (2cdee6c + shade_phong's plain loop for passes
# without light lists, every light listed when culling is off). CUDA tests and memcheck of the
# light loops; bench_renderer goal/, fig56 and feature/ cases of final against new (817ce72 +
# shared tables with 817ce72's loop), interleaved; knecht-32-lights shadow maps at 720x480 with
# culling on and off; bench_oracle render/ct_cuda (the CT volume's oracle frame).
set -uo pipefail
LIMIT=${LIMIT:-175}
G=$PWD/.gpu5; W=$(mktemp -d); mkdir -p $G/x && for f in $G/bin/*.xz; do xz -T4 -dc "$f" > $G/x/$(basename "$f" .xz) & done; wait; chmod +x $G/x/*
B=$G/x; export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/experiments/assets LD_LIBRARY_PATH=$G/lib; S=$PWD/experiments/scenes
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $W/gpu.txt
pack() { tar -cJf $OUT/call17.tar.xz -C $W . 2>/dev/null; }
summ() { echo "$(grep -E '^\[  (PASSED|FAILED) |ERROR SUMMARY' $1 | tr '\n' ' ') skipped=$(grep -c '^\[  SKIPPED \] ' $1)"; }
(cd $W && timeout 60 $B/test_frame --gtest_filter='LightCulling.*:DeferredOracle.*:RasterRender.*' > $W/test_frame.log 2>&1); echo "test_frame rc=$? $(summ $W/test_frame.log) t=$SECONDS"
(cd $W && timeout 60 /usr/local/cuda/bin/compute-sanitizer --tool memcheck --error-exitcode 9 $B/test_frame --gtest_filter='LightCulling.CudaPlain*' > $W/memcheck.log 2>&1); echo "memcheck rc=$? $(summ $W/memcheck.log) t=$SECONDS"
for cull in on off; do a=; [ $cull = off ] && a=--no-light-culling
  (cd $W && timeout 30 $B/deepvox-lean render $S/knecht-32-lights.json --backend cuda --shadows shadowmap --dsm-res 512 --width 720 --height 480 --frames 4 $a --stats $W/sm-$cull.json --out l.png > $W/sm-$cull.log 2>&1); echo "l32 shadowmap 720 $cull rc=$? $(python3 -c "import json,statistics as s;f=json.load(open('$W/sm-$cull.json'))['frames'];print(round(s.median([x['fragment_ms'] for x in f[1:]]),3),'lpp',f[-1]['lights_per_pixel_mean'])" 2>&1) t=$SECONDS"
done
pack
F='^(goal/knecht-fig56/(none|shadowmap)/|goal/knecht-32-lights/(dsm_res=512|shadowmap)/|raster_render/fig56_(none|shadowmap)_cuda|feature/)'
for r in 1 2; do [ $SECONDS -lt $((LIMIT-40)) ] || break
  case $r in 2) order="new final";; *) order="final new";; esac
  for side in $order; do s=; n=new; [ $side = new ] && s=-new && n=old
    timeout 60 $B/bench_renderer$s --benchmark_filter="$F" --benchmark_out=$W/$n-bench_renderer-r$r.json > $W/$n-r$r.log 2>&1; echo "renderer $side r$r rc=$? t=$SECONDS"
  done; pack
done
python3 scripts/bench_summary.py $W > $W/summary.txt 2>&1; cut -c1-160 $W/summary.txt | grep -v "counter\|_ms" | head -40
[ $SECONDS -lt $LIMIT ] && { timeout 40 $B/bench_oracle --benchmark_filter='render/ct_cuda' --benchmark_repetitions=5 --benchmark_report_aggregates_only=true --benchmark_out=$W/bench_oracle.json > $W/bench_oracle.log 2>&1; echo "bench_oracle rc=$? t=$SECONDS"; grep -E "median" $W/bench_oracle.log | cut -c1-120; }
rm -f $W/*.png; pack; echo all-done t=$SECONDS
