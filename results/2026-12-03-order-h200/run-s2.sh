#!/bin/bash
# Eighth round, call 2: srt2 (the probes of a tile in parallel threads, each walking the bricks
# with additions only) against srt (call 1's build: one thread per tile walks its five probes,
# three divisions per brick) and ln (1c02151, two lanes in tile order). test_render of srt2;
# deepvox-lean ln, srt, srt2 on knecht-fig56 (none, shadowmap, dsm at 1024^2) and knecht-planner
# (auto), 8 frames at orbit 0: one round with DEEPVOX_KERNEL_TIMING=1 (every kernel timed by
# events and waited for: per-kernel times, not frame times), then two interleaved plain rounds;
# bench_renderer and bench_dsm ln and srt2 interleaved, three rounds of 3 repetitions.
set -u
G=$PWD/.gpu; W=$(mktemp -d); mkdir -p $W/bin
export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/assets LD_LIBRARY_PATH=$G/lib:${LD_LIBRARY_PATH:-}
for f in $G/bin/*.xz; do b=$W/bin/$(basename $f .xz); xz -dc $f > $b; chmod +x $b; done
L=$W/s2; mkdir -p $L $L/png
trap 'tar -czf $OUT/s2.tar.gz -C $L .' EXIT
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $L/gpu.txt 2>&1; cat $L/gpu.txt
t0=$(date +%s)
timeout 200 $W/bin/test_render-srt2 > $L/test_render.log 2>&1; echo "test_render rc=$? $(grep -E '^\[  (PASSED|FAILED) ' $L/test_render.log | tr '\n' ' ') skipped=$(grep -cE '^\[  SKIPPED \] .*\(' $L/test_render.log) $(( $(date +%s)-t0 ))s"
grep -h "^\[  FAILED  \]" $L/test_render.log | sort -u | head
grep -h "VolumeLanes" $L/test_render.log | grep -E "OK|FAILED|SKIPPED"
for round in kt 1 2; do
 E=''; [ $round = kt ] && E='DEEPVOX_KERNEL_TIMING=1'
 for c in full:none full:shadowmap full:dsm planner:auto; do
  v=${c%:*}; sh=${c#*:}; P=''; [ $sh = dsm ] && P='--param res=1024'; [ $v = planner ] && P='--param res=1024'
  for b in ln srt srt2; do
    n=$v-$sh-$b-$round
    env $E timeout 60 $W/bin/deepvox-lean-$b render $G/scenes/$v.json --out $W/$n.png --shadows $sh $P --backend cuda --frames 8 --orbit 0 --stats $L/$n.json > $L/$n.log 2>&1
    echo "$n rc=$? $(python3 -c "
import json,sys; j=json.load(open('$L/$n.json')); f=j['frames']
print('frag', ' '.join('%.3f'%x['fragment_ms'] for x in f[2:]), 'ms', ' '.join('%.3f'%x['milliseconds'] for x in f[2:]), 'samples', f[-1].get('volume_samples'), 'volume_tiles', f[-1].get('volume_tiles'))
k=j.get('kernels')
if k: print('   kernels per launch', ' '.join('%s=%.4f'%(x['name'],x['ms']/x['launches']) for x in k if x['name'].startswith(('raster_','eye'))))" 2>&1)"
    [ $round = 1 ] && cp $W/${n}_0007.png $L/png/$n.png
  done
 done
done
A="--benchmark_repetitions=3 --benchmark_report_aggregates_only=true"
R='(raster_render/fig56_(none|shadowmap)_cuda|planned_frame/planner_steady_(auto|dsm)_cuda)'
D='^(render_bilinear/[a-z0-9]+/cuda/1024|generate/(beer|compact)/cuda/1024)/'
for round in 1 2 3; do
  for v in ln srt2; do
    timeout 100 $W/bin/bench_renderer-$v $A --benchmark_filter="$R" --benchmark_out=$L/bench_renderer-$v-$round.json > $L/bench_renderer-$v-$round.log 2>&1
    echo "bench_renderer $v $round rc=$? $(( $(date +%s)-t0 ))s"
    timeout 150 $W/bin/bench_dsm-$v $A --benchmark_filter="$D" --benchmark_out=$L/bench_dsm-$v-$round.json > $L/bench_dsm-$v-$round.log 2>&1
    echo "bench_dsm $v $round rc=$? $(( $(date +%s)-t0 ))s"
  done
done
for v in ln srt2; do echo "== $v"; grep -h median $L/bench_renderer-$v-3.log $L/bench_dsm-$v-3.log | awk '{print $1, $2, $3}'; done
echo "total $(( $(date +%s)-t0 ))s"
