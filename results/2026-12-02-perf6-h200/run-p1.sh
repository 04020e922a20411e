#!/bin/bash
# Session 7, call 1: the CUDA suites on main + owner_of_item/tiles_along; then where the
# renderer's fragment pass spends its time: deepvox-lean render of fig56 variants
# (full, no volumes, volumes only, CT only, floor only, volume steps x2), 6 frames each at
# orbit 0, shadows none and shadowmap, fragment_ms per frame from --stats.
set -u
G=$PWD/.gpu; W=$(mktemp -d); mkdir -p $W/bin
export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/assets LD_LIBRARY_PATH=$G/lib:${LD_LIBRARY_PATH:-}
for f in $G/bin/*.xz; do b=$W/bin/$(basename $f .xz); xz -dc $f > $b; chmod +x $b; done
L=$W/p1; mkdir -p $L
trap 'tar -czf $OUT/p1.tar.gz -C $L .' EXIT
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $L/gpu.txt 2>&1; cat $L/gpu.txt
t0=$(date +%s)
for t in test_raster test_render; do
  timeout 200 $W/bin/$t > $L/$t.log 2>&1; echo "$t rc=$? $(grep -E '^\[  (PASSED|FAILED) ' $L/$t.log | tr '\n' ' ') skipped=$(grep -cE '^\[  SKIPPED \] .*\(' $L/$t.log) $(( $(date +%s)-t0 ))s"
done
grep -h "^\[  FAILED  \]" $L/test_*.log | sort -u | head
for v in full novol volonly ctonly empty step2; do
  for sh in none shadowmap; do
    timeout 60 $W/bin/deepvox-lean render $G/scenes/$v.json --out $L/$v-$sh.png --shadows $sh --backend cuda --frames 6 --orbit 0 --stats $L/$v-$sh.json > $L/$v-$sh.log 2>&1
    echo "$v $sh rc=$? $(python3 -c "
import json,sys; j=json.load(open('$L/$v-$sh.json')); f=j['frames']
print('frag', ' '.join('%.3f'%x['fragment_ms'] for x in f[1:]), 'raster', ' '.join('%.3f'%x['raster_ms'] for x in f[1:]), 'samples', f[-1].get('volume_samples'), 'hits', f[-1].get('hits'))" 2>&1)"
  done
done
echo "total $(( $(date +%s)-t0 ))s"
