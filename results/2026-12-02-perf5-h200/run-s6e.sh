#!/bin/bash
# Session 6, call 5: the final tile rasterizer (ff1ebcd) with the tile binning's bandwidth floor
# (raster_floor_ms / raster_floor_x in bench_dsm and bench_renderer): generate/<every
# storage>/cuda/1024, render_bilinear/compact/cuda/1024 and the fig56 renderer cases, 3
# repetitions.
set -u
G=$PWD/.gpu; W=$(mktemp -d); mkdir -p $W/bin
export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/assets LD_LIBRARY_PATH=$G/lib:${LD_LIBRARY_PATH:-}
for f in $G/bin/*.xz; do b=$W/bin/$(basename $f .xz); xz -dc $f > $b; chmod +x $b; done
L=$W/s6e; mkdir -p $L
trap 'tar -czf $OUT/s6e.tar.gz -C $L .' EXIT
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $L/gpu.txt 2>&1; cat $L/gpu.txt
t0=$(date +%s)
A="--benchmark_repetitions=3 --benchmark_report_aggregates_only=true"
D='^(generate/[a-z0-9:=]+/cuda/1024|render_bilinear/compact/cuda/1024)/'
R='raster_render/fig56_(none|shadowmap)_cuda'
timeout 150 $W/bin/bench_dsm $A --benchmark_filter="$D" --benchmark_out=$L/bench_dsm.json > $L/bench_dsm.log 2>&1; echo "bench_dsm rc=$? $(( $(date +%s)-t0 ))s"
timeout 100 $W/bin/bench_renderer $A --benchmark_filter="$R" --benchmark_out=$L/bench_renderer.json > $L/bench_renderer.log 2>&1; echo "bench_renderer rc=$? $(( $(date +%s)-t0 ))s"
grep -h median $L/bench_dsm.log $L/bench_renderer.log | grep -oE "^[^ ]+ +[0-9.]+ ms|raster_ms=[^ ]+|raster_floor_[a-z]+=[^ ]+" | paste - - - -
