#!/usr/bin/env bash
# Device call 16b: one-light frames (knecht-fig56, no shadows and a shadow map, 720x480 and
# 3840x2160) with cee = cee8710, new = 817ce72 + shared tables, nest = new with cee8710's light
# loop: does the nested loop cost the one-light pass? Two interleaved rounds, fragment_ms medians.
set -uo pipefail
G=$PWD/.gpu4; W=$(mktemp -d); [ -x $G/x/deepvox-lean-nest ] || { mkdir -p $G/x && for f in $G/bin/deepvox-lean-*.xz; do xz -T4 -dc "$f" > $G/x/$(basename "$f" .xz) & done; wait; chmod +x $G/x/*; }
B=$G/x; export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/experiments/assets; S=$PWD/experiments/scenes
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $W/gpu.txt
for r in 1 2; do case $r in 1) order="cee new nest";; 2) order="nest new cee";; esac
  for side in $order; do for sh in none shadowmap; do for wh in "720 480" "3840 2160"; do set -- $wh
    (cd $W && timeout 30 $B/deepvox-lean-$side render $S/knecht-fig56.json --backend cuda --shadows $sh --width $1 --height $2 --frames 12 --stats $W/f56-$side-$sh-$1-r$r.json --out l.png > $W/f56-$side-$sh-$1-r$r.log 2>&1); echo "$side $sh $1 r$r rc=$? $(python3 -c "import json,statistics as s;f=json.load(open('$W/f56-$side-$sh-$1-r$r.json'))['frames'];print(round(s.median([x['fragment_ms'] for x in f[2:]]),3))" 2>&1) t=$SECONDS"
  done; done; done
done
rm -f $W/*.png; tar -cJf $OUT/call16b.tar.xz -C $W .; echo done t=$SECONDS
