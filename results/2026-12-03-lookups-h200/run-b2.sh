#!/bin/bash
# Eleventh round, call 2: where a bilinear DSM frame's lookup time goes, and two ways to read the
# taps. Builds differ only in frame/raster_render.cpp's object (the camera pass's kernels),
# linked into bench_dsm: lk (main at 6d26c4a), abproj (ablation: face_visibility returns 1 after
# the projection, the reader not called), abcall (ablation: the reader's out-of-line call made,
# no texel read), u4 (the four taps unrolled, a tap off the map reading texel 0 and set lit),
# inl (the reader call inlined, one call site per face lookup). bench_dsm
# render_bilinear/<storage>/cuda/1024, three rounds of 3 repetitions, builds interleaved.
set -u
G=$PWD/.gpu; W=$(mktemp -d); mkdir -p $W/bin
export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/assets LD_LIBRARY_PATH=$G/lib:${LD_LIBRARY_PATH:-}
for f in $G/bin/*.xz; do b=$W/bin/$(basename $f .xz); xz -dc $f > $b; chmod +x $b; done
L=$W/b2; mkdir -p $L
trap 'tar -czf $OUT/b2.tar.gz -C $L .' EXIT
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $L/gpu.txt 2>&1; cat $L/gpu.txt
t0=$(date +%s)
A="--benchmark_repetitions=3 --benchmark_report_aggregates_only=true"
ALL='^render_bilinear/(compact|beer|texture3d|blocked|occupancy|fourier|moments)/cuda/1024/'
ONE='^render_bilinear/compact/cuda/1024/'
for round in 1 2 3; do
  for v in lk u4 inl abproj abcall; do
    D=$ALL; case $v in ab*) D=$ONE;; esac
    timeout 120 $W/bin/bench_dsm-$v $A --benchmark_filter="$D" --benchmark_out=$L/bench_dsm-$v-$round.json > $L/bench_dsm-$v-$round.log 2>&1
    echo "bench_dsm $v $round rc=$? $(( $(date +%s)-t0 ))s"
  done
done
for v in lk u4 inl abproj abcall; do echo "== $v"; grep -h median $L/bench_dsm-$v-3.log | awk '{print $1, $2, $3}'; done
echo "total $(( $(date +%s)-t0 ))s"
