#!/bin/bash
# Eighth round, call 4: the committed code (d96508d: srt3 plus refactors, brick_flag_index and a
# NaN guard on the key): the CUDA suites test_raster, test_render, test_dsm, test_hard, and
# deepvox-lean on the four cases of call s3 (one round), its PNGs compared with srt3's (s3/png).
set -u
G=$PWD/.gpu; W=$(mktemp -d); mkdir -p $W/bin; R=$PWD/results/2026-12-03-order-h200
export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/assets LD_LIBRARY_PATH=$G/lib:${LD_LIBRARY_PATH:-}
for f in $G/bin/*.xz; do b=$W/bin/$(basename $f .xz); xz -dc $f > $b; chmod +x $b; done
L=$W/s4; mkdir -p $L
trap 'tar -czf $OUT/s4.tar.gz -C $L .' EXIT
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $L/gpu.txt 2>&1; cat $L/gpu.txt
t0=$(date +%s)
for t in test_raster test_render test_dsm test_hard; do
  timeout 200 $W/bin/$t-fin > $L/$t.log 2>&1; echo "$t rc=$? $(grep -E '^\[  (PASSED|FAILED) ' $L/$t.log | tr '\n' ' ') skipped=$(grep -cE '^\[  SKIPPED \] .*\(' $L/$t.log) $(( $(date +%s)-t0 ))s"
done
grep -h "^\[  FAILED  \]" $L/test_*.log | sort -u | head
grep -h "VolumeLanes" $L/test_render.log | grep -E "OK|FAILED|SKIPPED"
for c in full:none full:shadowmap full:dsm planner:auto; do
  v=${c%:*}; sh=${c#*:}; P=''; [ $sh = dsm ] && P='--param res=1024'; [ $v = planner ] && P='--param res=1024'
  n=$v-$sh-fin-1
  timeout 60 $W/bin/deepvox-lean-fin render $G/scenes/$v.json --out $W/$n.png --shadows $sh $P --backend cuda --frames 8 --orbit 0 --stats $L/$n.json > $L/$n.log 2>&1
  echo "$n rc=$? $(python3 -c "
import json,sys; j=json.load(open('$L/$n.json')); f=j['frames']
print('frag', ' '.join('%.3f'%x['fragment_ms'] for x in f[2:]), 'samples', f[-1].get('volume_samples'), 'volume_tiles', f[-1].get('volume_tiles'))" 2>&1)"
  cmp $W/${n}_0007.png $R/s3/png/$v-$sh-srt3-1.png && echo "$v-$sh: PNG byte-identical to srt3's"
done
echo "total $(( $(date +%s)-t0 ))s"
