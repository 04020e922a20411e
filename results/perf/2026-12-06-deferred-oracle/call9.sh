#!/usr/bin/env bash
# Device call 9: four builds of the deferred oracle that differ only in the answer pass:
# v0 queries in pixel order (by light), v1 v0 with a 128-register budget, v2 queries sorted by
# (light, occupied-brick length of the shadow ray, heaviest first), v3 v2 with the budget.
# Two interleaved rounds of four frames each; the PNGs of every variant must equal v0's.
set -uo pipefail
W=$(mktemp -d); mkdir -p .gpu/x && for f in .gpu/bin/*.xz; do xz -dc "$f" > .gpu/x/$(basename "$f" .xz); done; chmod +x .gpu/x/*
B=$PWD/.gpu/x; export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/experiments/assets; S=$PWD/experiments/scenes
nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.max.sm --format=csv,noheader | tee $W/gpu.txt
pack() { tar -czf $OUT/call9.tar.gz -C $W . 2>/dev/null; }
one() { local v=$1 r=$2 name=$3; shift 3
  (cd $W && timeout 60 $B/deepvox-lean-$v render "$@" --backend cuda --shadows reference --stats $W/$v-$name-r$r.json --out $W/$v-$name-r$r.png > $W/$v-$name-r$r.log 2>&1) || echo "$v $name r$r rc=$?"; }
for r in 1 2; do
  if [ $r = 1 ]; then order="v0 v1 v2 v3"; else order="v3 v2 v1 v0"; fi
  for v in $order; do
    one $v $r fig56 $S/knecht-fig56.json --frames 4
    one $v $r fig56-1080 $S/knecht-fig56.json --width 1920 --height 1080 --frames 3
    one $v $r lights32 $S/knecht-32-lights.json --frames 2
    one $v $r ct-raytrace $S/ct-phantom.json --renderer raytrace --frames 3
  done
  pack
done
for f in $W/v0-*_0000.png; do b=$(basename $f); for v in v1 v2 v3; do cmp -s $f $W/${b/v0/$v} || echo "png ${b/v0/$v} DIFFERS from v0"; done; done
echo png-check-done
rm -f $W/*.png; pack
NCU=/usr/local/cuda/bin/ncu
for v in v0 v2 v3; do (cd $W && timeout 60 $NCU --kernel-name-base demangled -k regex:'answer_oracle_queries' --launch-skip 0 --launch-count 2 --section SpeedOfLight --section Occupancy --section LaunchStats --section WarpStateStats -o answers-$v $B/deepvox-lean-$v render $S/knecht-fig56.json --backend cuda --shadows reference --frames 1 --out o.png > ncu-$v.log 2>&1); echo "ncu $v rc=$?"; timeout 20 $NCU --import $W/answers-$v.ncu-rep --page details > $W/answers-$v.txt 2>&1; done
rm -f $W/o.png; pack
echo all-done $(date +%T)
