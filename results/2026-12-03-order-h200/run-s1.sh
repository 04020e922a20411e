#!/bin/bash
# Eighth round, call 1: the volume tiles heaviest first (srt, e06bf18) against two lanes in tile
# order (ln, 1c02151). CUDA suites of srt (test_raster, test_render, test_dsm, test_hard);
# deepvox-lean ln, srt and hv (srt plus heavy-lanes-variant.patch: the volume tiles with a cost
# key >= DV_HEAVY_COST get DV_HEAVY_LANES lanes) on knecht-fig56 (none, shadowmap, dsm at 1024^2)
# and knecht-planner (auto), 8 frames at orbit 0, two interleaved rounds; bench_renderer and
# bench_dsm ln and srt interleaved, three rounds of 3 repetitions.
set -u
G=$PWD/.gpu; W=$(mktemp -d); mkdir -p $W/bin
export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/assets LD_LIBRARY_PATH=$G/lib:${LD_LIBRARY_PATH:-}
for f in $G/bin/*.xz; do b=$W/bin/$(basename $f .xz); xz -dc $f > $b; chmod +x $b; done
L=$W/s1; mkdir -p $L $L/png
trap 'tar -czf $OUT/s1.tar.gz -C $L .' EXIT
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $L/gpu.txt 2>&1; cat $L/gpu.txt
t0=$(date +%s)
for t in test_raster test_render test_dsm test_hard; do
  timeout 200 $W/bin/$t-srt > $L/$t.log 2>&1; echo "$t rc=$? $(grep -E '^\[  (PASSED|FAILED) ' $L/$t.log | tr '\n' ' ') skipped=$(grep -cE '^\[  SKIPPED \] .*\(' $L/$t.log) $(( $(date +%s)-t0 ))s"
done
grep -h "^\[  FAILED  \]" $L/test_*.log | sort -u | head
grep -h "VolumeLanes" $L/test_render.log | grep -E "OK|FAILED|SKIPPED"
for round in 1 2; do
 for c in full:none full:shadowmap full:dsm planner:auto; do
  v=${c%:*}; sh=${c#*:}; P=''; [ $sh = dsm ] && P='--param res=1024'; [ $v = planner ] && P='--param res=1024'
  for b in ln srt hv:50:4 hv:100:4 hv:150:4 hv:100:8; do
    bin=${b%%:*}; E=''; [ $bin = hv ] && E="DV_HEAVY_COST=$(echo $b | cut -d: -f2) DV_HEAVY_LANES=$(echo $b | cut -d: -f3)"
    n=$v-$sh-$(echo $b | tr ':' '-')-$round
    env $E timeout 60 $W/bin/deepvox-lean-$bin render $G/scenes/$v.json --out $W/$n.png --shadows $sh $P --backend cuda --frames 8 --orbit 0 --stats $L/$n.json > $L/$n.log 2>&1
    echo "$n rc=$? $(python3 -c "
import json,sys; j=json.load(open('$L/$n.json')); f=j['frames']
print('frag', ' '.join('%.3f'%x['fragment_ms'] for x in f[2:]), 'ms', ' '.join('%.3f'%x['milliseconds'] for x in f[2:]), 'samples', f[-1].get('volume_samples'), 'volume_tiles', f[-1].get('volume_tiles'))" 2>&1)"
    [ $round = 1 ] && cp $W/${n}_0007.png $L/png/$n.png
  done
 done
done
A="--benchmark_repetitions=3 --benchmark_report_aggregates_only=true"
R='(raster_render/fig56_(none|shadowmap)_cuda|planned_frame/planner_steady_(auto|dsm)_cuda)'
D='^(render_bilinear/[a-z0-9]+/cuda/1024|generate/(beer|compact)/cuda/1024)/'
for round in 1 2 3; do
  for v in ln srt; do
    timeout 100 $W/bin/bench_renderer-$v $A --benchmark_filter="$R" --benchmark_out=$L/bench_renderer-$v-$round.json > $L/bench_renderer-$v-$round.log 2>&1
    echo "bench_renderer $v $round rc=$? $(( $(date +%s)-t0 ))s"
    timeout 150 $W/bin/bench_dsm-$v $A --benchmark_filter="$D" --benchmark_out=$L/bench_dsm-$v-$round.json > $L/bench_dsm-$v-$round.log 2>&1
    echo "bench_dsm $v $round rc=$? $(( $(date +%s)-t0 ))s"
  done
done
for v in ln srt; do echo "== $v"; grep -h median $L/bench_renderer-$v-3.log $L/bench_dsm-$v-3.log | awk '{print $1, $2, $3}'; done
echo "total $(( $(date +%s)-t0 ))s"
