#!/bin/bash
# Twelfth round, call 3 (a measurement for the next round, not landed): the camera pass's
# kernels (frame/raster_render.cpp) compiled with a register cap, -maxrregcount 168 (r168) and
# 128 (r128), against un (main, 2016eae). bench_dsm render_bilinear/<storage>/cuda/1024, three
# rounds of 3 repetitions, builds interleaved.
set -u
G=$PWD/.gpu; W=$(mktemp -d); mkdir -p $W/bin
export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/assets LD_LIBRARY_PATH=$G/lib:${LD_LIBRARY_PATH:-}
for f in $G/bin/*.xz; do b=$W/bin/$(basename $f .xz); xz -dc $f > $b; chmod +x $b; done
L=$W/c3; mkdir -p $L
trap 'tar -czf $OUT/c3.tar.gz -C $L .' EXIT
exec > >(tee $L/run.log) 2>&1
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $L/gpu.txt 2>&1; cat $L/gpu.txt
t0=$(date +%s)
A="--benchmark_repetitions=3 --benchmark_report_aggregates_only=true"
D='^render_bilinear/(compact|beer|texture3d|blocked|moments)/cuda/1024/'
for round in 1 2 3; do
  for v in un r168 r128; do
    timeout 120 $W/bin/bench_dsm-$v $A --benchmark_filter="$D" --benchmark_out=$L/bench_dsm-$v-$round.json > $L/bench_dsm-$v-$round.log 2>&1
    echo "bench_dsm $v $round rc=$? $(( $(date +%s)-t0 ))s"
  done
done
for v in un r168 r128; do echo "== $v"; grep -h median $L/bench_dsm-$v-3.log | awk '{print $1, $2, $3}'; done
echo "total $(( $(date +%s)-t0 ))s"
