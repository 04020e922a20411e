#!/bin/bash
# usage: cpu-check.sh <deepvox-lean of main> <deepvox-lean of a variant>: the 22 CPU binvox grids
# of the sat voxelizer (bunny at four grids x four `small` values, three scenes at two grids)
# written by both and compared byte for byte.
cd "$(git rev-parse --show-toplevel)"
A=$1; V=$2; D=$(mktemp -d)
n=0; bad=0
run() { # name args...
  local name=$1; shift
  $A voxelize "$@" --backend cpu --out $D/a-$name.binvox >/dev/null 2>&1 || echo "main failed $name"
  $V voxelize "$@" --backend cpu --out $D/v-$name.binvox >/dev/null 2>&1 || echo "variant failed $name"
  n=$((n+1)); cmp -s $D/a-$name.binvox $D/v-$name.binvox || { bad=$((bad+1)); echo "DIFF $name"; }
}
for r in 256x256x256 300x200x96 512x512x512 64x512x32; do for s in 0 4 64 1024; do
  run bunny-$r-$s assets/meshes/stanford-bunny-lowres.obj --method sat --param small=$s --res $r; done; done
for sc in knecht-fig56 many-objects translucent-boxes; do for r in 128x96x64 512x512x512; do
  run $sc-$r scenes/$sc.json --method sat --res $r; done; done
echo "files $n differing $bad, distinct grids $(md5sum $D/a-* | cut -d" " -f1 | sort -u | wc -l)"
