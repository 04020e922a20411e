#!/bin/bash
# Session 7, call 6: why planned_frame/planner_steady_auto_cuda grew (1.97-2.03 -> 2.12-2.22 ms
# in call 5): deepvox-lean old (main + owner_of_item: a warp per 32 pixels of a row) and new
# (a warp per half raster tile) on knecht-planner (480x270, 7 lights) with --shadows auto and
# dsm, and fig56 with none, 8 frames at orbit 0 (maps built once), three interleaved rounds;
# fragment_ms and raster_ms per frame from --stats. spread: new with the tiles taken in a
# golden-section stride order (tile k shades tile k * stride mod tiles).
set -u
G=$PWD/.gpu; W=$(mktemp -d); mkdir -p $W/bin
export LD_LIBRARY_PATH=$G/lib:${LD_LIBRARY_PATH:-}
for f in $G/bin/*.xz; do b=$W/bin/$(basename $f .xz); xz -dc $f > $b; chmod +x $b; done
L=$W/p6; mkdir -p $L
trap 'tar -czf $OUT/p6.tar.gz -C $L --exclude=*.png .' EXIT
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $L/gpu.txt 2>&1; cat $L/gpu.txt
for round in 1 2 3; do
 for c in planner:auto planner:dsm full:none; do
  v=${c%:*}; sh=${c#*:}; P=''; [ $sh = none ] || P='--param res=1024'
  for b in old new spread; do
    n=$v-$sh-$b-$round
    timeout 60 $W/bin/deepvox-lean-$b render $G/scenes/$v.json --out $L/$n.png --shadows $sh $P --backend cuda --frames 8 --orbit 0 --stats $L/$n.json > $L/$n.log 2>&1
    echo "$n rc=$? $(python3 -c "
import json,sys; j=json.load(open('$L/$n.json')); f=j['frames']
print('frag', ' '.join('%.3f'%x['fragment_ms'] for x in f[2:]), 'raster', ' '.join('%.3f'%x['raster_ms'] for x in f[2:]), 'ms', ' '.join('%.3f'%x['milliseconds'] for x in f[2:]))" 2>&1)"
  done
 done
done
