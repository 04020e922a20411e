#!/bin/bash
# Session 8, call 1: per-warp timeline of the fragment pass on knecht-fig56 (globaltimer at each
# thread's start and end, its volume samples), shadows none and shadowmap, plus the uninstrumented
# build's fragment_ms for comparison.
set -u
G=$PWD/.gpu; W=$(mktemp -d); mkdir -p $W/bin
export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/assets
for f in $G/bin/*.xz; do b=$W/bin/$(basename $f .xz); xz -dc $f > $b; chmod +x $b; done
L=$OUT/t1; mkdir -p $L
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $L/gpu.txt 2>&1; cat $L/gpu.txt
for sh in none shadowmap; do
  for b in new trace; do
    rm -f $W/tr.*
    DV_FRAG_TRACE=$W/tr timeout 60 $W/bin/deepvox-lean-$b render $G/scenes/full.json --out $W/$b-$sh.png --shadows $sh --backend cuda --frames 6 --orbit 0 --stats $L/$b-$sh.json > $L/$b-$sh.log 2>&1
    echo "$b $sh rc=$? $(python3 -c "
import json; j=json.load(open('$L/$b-$sh.json')); f=j['frames']
print('frag', ' '.join('%.3f'%x['fragment_ms'] for x in f[1:]))" 2>&1)"
    if [ $b = trace ]; then python3 $G/trace_report.py $W/tr.1 $W/tr.5 > $L/report-$sh.txt 2>&1; cat $L/report-$sh.txt; xz -c $W/tr.5 > $L/trace-$sh.5.xz; fi
  done
done
cmp $W/new-none.png $W/trace-none.png && echo "same png none"
