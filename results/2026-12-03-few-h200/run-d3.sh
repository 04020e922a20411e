#!/bin/bash
# Thirteenth round, call 3: the read-only lookups again, with more rounds. ro: c6c519a (main
# plus the lookups of the node storages through the read-only data path, the build of call d2);
# un: main before it (the twelfth round's build of 714ed79's code). bench_dsm un and ro
# interleaved, five rounds of 3 repetitions of render_bilinear/<storage>/cuda/1024, every storage.
set -u
G=$PWD/.gpu; W=$(mktemp -d); mkdir -p $W/bin
export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/assets LD_LIBRARY_PATH=$G/lib:${LD_LIBRARY_PATH:-}
for f in $G/bin/bench_dsm-*.xz; do b=$W/bin/$(basename $f .xz); xz -dc $f > $b; chmod +x $b; done
L=$W/d3; mkdir -p $L
trap 'tar -czf $OUT/d3.tar.gz -C $L .' EXIT
exec > >(tee $L/run.log) 2>&1
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $L/gpu.txt 2>&1; cat $L/gpu.txt
t0=$(date +%s)
A="--benchmark_repetitions=3 --benchmark_report_aggregates_only=true"
D='^render_bilinear/[a-z0-9]+/cuda/1024/'
for round in 1 2 3 4 5; do
  for v in un ro; do
    timeout 80 $W/bin/bench_dsm-$v $A --benchmark_filter="$D" --benchmark_out=$L/bench_dsm-$v-$round.json > $L/bench_dsm-$v-$round.log 2>&1
    echo "bench_dsm $v $round rc=$? $(( $(date +%s)-t0 ))s"
  done
done
for v in un ro; do echo "== $v"; grep -h median $L/bench_dsm-$v-5.log | awk '{print $1, $2, $3}'; done
echo "total $(( $(date +%s)-t0 ))s"
