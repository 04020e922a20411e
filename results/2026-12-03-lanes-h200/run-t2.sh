#!/bin/bash
# Session 8, call 4: the per-warp timeline of the fragment pass with two lanes per pixel in
# volume tiles (1c02151 + the trace instrumentation), knecht-fig56, shadows none and shadowmap.
set -u
G=$PWD/.gpu; W=$(mktemp -d); mkdir -p $W/bin
export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/assets
xz -dc $G/bin/deepvox-lean-trace2.xz > $W/bin/dl; chmod +x $W/bin/dl
L=$OUT/t2; mkdir -p $L
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $L/gpu.txt 2>&1; cat $L/gpu.txt
for sh in none shadowmap; do
  rm -f $W/tr.*
  DV_FRAG_TRACE=$W/tr timeout 60 $W/bin/dl render $G/scenes/full.json --out $W/$sh.png --shadows $sh --backend cuda --frames 6 --orbit 0 --stats $L/trace-$sh.json > $L/trace-$sh.log 2>&1
  echo "trace $sh rc=$? $(python3 -c "
import json; j=json.load(open('$L/trace-$sh.json')); f=j['frames']
print('frag', ' '.join('%.3f'%x['fragment_ms'] for x in f[1:]))" 2>&1)"
  python3 $G/trace_report2.py $W/tr.5 > $L/report-$sh.txt 2>&1; cat $L/report-$sh.txt
done
