#!/bin/bash
# Tenth round, call 2: where the rest of a generation goes, at HEAD 23998b2 (hd). nw: hd with the
# replay's fallback walk taken out of NodeReplay::generate (no-walk-in-replay-measurement.patch;
# a measurement only: right while no texel is lost, which fig56's repeated generations keep),
# to see what the write pass pays for carrying the walk's code. r168 / r128: hd with the compact,
# beer and texture3d storages compiled at -maxrregcount 168 / 128 (their walks at 239 registers
# hold 8 warps an SM). A kernel-timing round of each, then bench_dsm interleaved, three rounds of
# 3 repetitions of six storages' generation at 1024^2.
set -u
G=$PWD/.gpu; W=$(mktemp -d); mkdir -p $W/bin
export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/assets LD_LIBRARY_PATH=$G/lib:${LD_LIBRARY_PATH:-}
for f in $G/bin/*.xz; do b=$W/bin/$(basename $f .xz); xz -dc $f > $b; chmod +x $b; done
L=$W/w2; mkdir -p $L
trap 'tar -czf $OUT/w2.tar.gz -C $L .' EXIT
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $L/gpu.txt 2>&1; cat $L/gpu.txt
t0=$(date +%s)
A="--benchmark_repetitions=3 --benchmark_report_aggregates_only=true"
D='^generate/(compact|beer|texture3d|blocked|chunked|occupancy)/cuda/1024/'
for v in hd nw r168 r128; do
  DEEPVOX_KERNEL_TIMING=1 timeout 100 $W/bin/bench_dsm-$v --benchmark_repetitions=1 --benchmark_filter="$D" --benchmark_out=$L/bench_dsm-$v-kernels.json > $L/bench_dsm-$v-kernels.log 2>&1
  echo "kernel timing $v rc=$? $(( $(date +%s)-t0 ))s"
done
for round in 1 2 3; do
  for v in hd nw r168 r128; do
    timeout 100 $W/bin/bench_dsm-$v $A --benchmark_filter="$D" --benchmark_out=$L/bench_dsm-$v-$round.json > $L/bench_dsm-$v-$round.log 2>&1
    echo "bench_dsm $v $round rc=$? $(( $(date +%s)-t0 ))s"
  done
done
for v in hd nw r168 r128; do echo "== $v"; grep -h median $L/bench_dsm-$v-3.log | awk '{print $1, $2, $3}'; done
echo "total $(( $(date +%s)-t0 ))s"
