#!/bin/bash
# Thirteenth round, call 1. f4: main (bb8edb5) plus the node search reading a texel of at most
# kFewNodes = 4 nodes whole (all its nodes loaded at once, no chain of dependent search probes);
# f2 and f3: the same with kFewNodes = 2 and 3 (frame/raster_render.cpp compiled with that
# constant, linked with f4's other objects). un: main (the twelfth round's build of 714ed79's
# code, the same lookups). CUDA suites test_dsm, test_render, test_hard of f4; deepvox-lean f4
# and f2 rendering knecht-fig56 with DSM shadows (1024^2) for every storage, filter none and
# bilinear, PNG MD5 sums compared with lk's of the eleventh round (main's, byte-identical);
# bench_dsm un, f4, f2, f3 interleaved, three rounds of 3 repetitions of
# render_bilinear/<storage>/cuda/1024 for the storages that search nodes and beer.
set -u
G=$PWD/.gpu; W=$(mktemp -d); mkdir -p $W/bin
export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/assets LD_LIBRARY_PATH=$G/lib:${LD_LIBRARY_PATH:-}
for f in $G/bin/*.xz; do b=$W/bin/$(basename $f .xz); xz -dc $f > $b; chmod +x $b; done
L=$W/d1; mkdir -p $L $L/png
trap 'tar -czf $OUT/d1.tar.gz -C $L .' EXIT
exec > >(tee $L/run.log) 2>&1
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $L/gpu.txt 2>&1; cat $L/gpu.txt
t0=$(date +%s)
for t in test_dsm-f4 test_render-f4 test_hard-f4; do
  timeout 200 $W/bin/$t > $L/$t.log 2>&1; echo "$t rc=$? $(grep -E '^\[  (PASSED|FAILED) ' $L/$t.log | tr '\n' ' ') skipped=$(grep -cE '^\[  SKIPPED \] .*\(' $L/$t.log) $(( $(date +%s)-t0 ))s"
done
grep -h "^\[  FAILED  \]" $L/test_*.log | sort -u | head
for v in f4 f2; do
  for st in compact texture3d chunked blocked beer avsm moments fourier occupancy; do
    for fl in none bilinear; do
      n=$st-$fl-$v
      timeout 60 $W/bin/deepvox-lean-$v render $G/scenes/full.json --out $W/$n.png --shadows dsm --storage $st --dsm-res 1024 --filter $fl --backend cuda --frames 2 --orbit 0 --stats $L/$n.json > $L/$n.log 2>&1 || echo "$n rc=$?"
      cp $W/${n}_0001.png $L/png/$n.png 2>/dev/null
      want=$(grep "/$st-$fl-lk.png$" $G/lk-png-md5.txt | cut -d' ' -f1)
      got=$(md5sum < $L/png/$n.png | cut -d' ' -f1)
      [ "$want" = "$got" ] && echo "$n: PNG byte-identical to lk's" || echo "$n: PNG DIFFERS ($got, lk $want)"
    done
  done
done
(cd $L/png && md5sum *.png) > $L/png-md5.txt
echo "renders $(( $(date +%s)-t0 ))s"
A="--benchmark_repetitions=3 --benchmark_report_aggregates_only=true"
D='^render_bilinear/(compact|beer|texture3d|blocked|avsm)/cuda/1024/'
for round in 1 2 3; do
  for v in un f4 f2 f3; do
    timeout 100 $W/bin/bench_dsm-$v $A --benchmark_filter="$D" --benchmark_out=$L/bench_dsm-$v-$round.json > $L/bench_dsm-$v-$round.log 2>&1
    echo "bench_dsm $v $round rc=$? $(( $(date +%s)-t0 ))s"
  done
done
for v in un f4 f2 f3; do echo "== $v"; grep -h median $L/bench_dsm-$v-3.log | awk '{print $1, $2, $3}'; done
echo "total $(( $(date +%s)-t0 ))s"
