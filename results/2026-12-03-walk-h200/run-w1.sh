#!/bin/bash
# Tenth round, call 1: the compressor's single emit site (se: a node noted where it is emitted,
# handed to the sink once per sample) and the heaviest-first block order of generation (w: se plus
# renderer/tile_order.h over the light's faces) against rpc (the ninth round's committed replay).
# CUDA suites test_dsm and test_render of w; deepvox-lean w rendering knecht-fig56 with DSM
# shadows (1024^2) for the storages of the ninth round's PNGs (.gpu/ref: its call 1 fin PNGs),
# compared byte for byte; a kernel-timing round of w; bench_dsm rpc, se and w interleaved, three
# rounds of 3 repetitions of every storage's generation at 1024^2 and compact's bilinear frame;
# bench_renderer w (fig56 frames; the camera pass's order is now renderer/tile_order.h).
set -u
G=$PWD/.gpu; W=$(mktemp -d); mkdir -p $W/bin
export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/assets LD_LIBRARY_PATH=$G/lib:${LD_LIBRARY_PATH:-}
for f in $G/bin/*.xz; do b=$W/bin/$(basename $f .xz); xz -dc $f > $b; chmod +x $b; done
L=$W/w1; mkdir -p $L $L/png
trap 'tar -czf $OUT/w1.tar.gz -C $L .' EXIT
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $L/gpu.txt 2>&1; cat $L/gpu.txt
t0=$(date +%s)
for t in test_dsm test_render; do
  timeout 300 $W/bin/$t-w > $L/$t.log 2>&1; echo "$t rc=$? $(grep -E '^\[  (PASSED|FAILED) ' $L/$t.log | tr '\n' ' ') skipped=$(grep -cE '^\[  SKIPPED \] .*\(' $L/$t.log) $(( $(date +%s)-t0 ))s"
done
grep -h "^\[  FAILED  \]" $L/test_*.log | sort -u | head
grep -hE "NodeReplay|DsmBlockOrder|VolumeLanes" $L/test_*.log | grep -E "OK|FAILED|SKIPPED"
for s in compact moments fourier occupancy blocked chunked chunked:alloc=thesis compact:bilinear; do
  st=${s%%:*}; P="--storage $st --dsm-res 1024"
  case $s in *alloc=thesis) P="$P --param storage.alloc=thesis";; *bilinear) P="$P --filter bilinear";; esac
  n=$(echo $s | tr ':=' '--')
  timeout 60 $W/bin/deepvox-lean-w render $G/scenes/full.json --out $W/$n-w.png --shadows dsm $P --backend cuda --frames 4 --orbit 0 --stats $L/$n-w.json > $L/$n-w.log 2>&1
  echo "$n w rc=$? $(python3 -c "
import json; j=json.load(open('$L/$n-w.json')); f=j['frames'][-1]
print('frame ms %.3f'%f['milliseconds'])" 2>&1)"
  cp $W/$n-w_0003.png $L/png/$n-w.png 2>/dev/null
  cmp $G/ref/$n-fin.png $L/png/$n-w.png && echo "$n: ninth round fin and w PNGs byte-identical"
done
md5sum $L/png/*.png > $L/png-md5.txt
A="--benchmark_repetitions=3 --benchmark_report_aggregates_only=true"
D='^(generate/[a-z0-9:=]+/cuda/1024|render_bilinear/compact/cuda/1024)/'
DEEPVOX_KERNEL_TIMING=1 timeout 150 $W/bin/bench_dsm-w --benchmark_repetitions=1 --benchmark_filter="$D" --benchmark_out=$L/bench_dsm-w-kernels.json > $L/bench_dsm-w-kernels.log 2>&1
echo "kernel timing rc=$? $(( $(date +%s)-t0 ))s"
for round in 1 2 3; do
  for v in rpc se w; do
    timeout 150 $W/bin/bench_dsm-$v $A --benchmark_filter="$D" --benchmark_out=$L/bench_dsm-$v-$round.json > $L/bench_dsm-$v-$round.log 2>&1
    echo "bench_dsm $v $round rc=$? $(( $(date +%s)-t0 ))s"
  done
done
timeout 120 $W/bin/bench_renderer-w $A --benchmark_filter='raster_render/fig56_(none|shadowmap)_cuda' --benchmark_out=$L/bench_renderer-w.json > $L/bench_renderer-w.log 2>&1
echo "bench_renderer rc=$? $(( $(date +%s)-t0 ))s"; grep median $L/bench_renderer-w.log | awk '{print $1, $2, $3}'
for v in rpc se w; do echo "== $v"; grep -h median $L/bench_dsm-$v-3.log | awk '{print $1, $2, $3}'; done
echo "total $(( $(date +%s)-t0 ))s"
