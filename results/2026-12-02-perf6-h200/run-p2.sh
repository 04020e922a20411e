#!/bin/bash
# Session 7, call 2: per-sample costs of the fragment pass: deepvox-lean base (main +
# owner_of_item), v1 (one exp per grey step, same values), and two ablations of v1 measured
# only (nopow: highlights without pow; noshade: volume samples unshaded), on fig56 variants,
# 6 frames at orbit 0, none and shadowmap, three interleaved rounds; GPU PNGs base vs v1.
set -u
G=$PWD/.gpu; W=$(mktemp -d); mkdir -p $W/bin
export LD_LIBRARY_PATH=$G/lib:${LD_LIBRARY_PATH:-}
for f in $G/bin/*.xz; do b=$W/bin/$(basename $f .xz); xz -dc $f > $b; chmod +x $b; done
L=$W/p2; mkdir -p $L
trap 'tar -czf $OUT/p2.tar.gz -C $L .' EXIT
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $L/gpu.txt 2>&1; cat $L/gpu.txt
t0=$(date +%s)
for round in 1 2 3; do
 for v in full volonly; do
  for sh in none shadowmap; do
   for b in base v1 nopow noshade; do
    n=$v-$sh-$b-$round
    timeout 60 $W/bin/deepvox-lean-$b render $G/scenes/$v.json --out $L/$n.png --shadows $sh --backend cuda --frames 6 --orbit 0 --stats $L/$n.json > $L/$n.log 2>&1
    echo "$n rc=$? $(python3 -c "
import json,sys; j=json.load(open('$L/$n.json')); f=j['frames']
print('frag', ' '.join('%.3f'%x['fragment_ms'] for x in f[1:]), 'samples', f[-1].get('volume_samples'))" 2>&1)"
   done
  done
 done
done
for v in full volonly; do for sh in none shadowmap; do cmp $L/$v-$sh-base-1.png $L/$v-$sh-v1-1.png && echo "$v $sh png base = v1"; done; done
echo "total $(( $(date +%s)-t0 ))s"
