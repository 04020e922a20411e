#!/bin/bash
# Ninth round, call 2: the committed design (rpc: chunks written as the compressor emits, a
# first chunk per texel and linked chunks claimed from 64 stripes; the replay reads what the
# first pass wrote and nothing else) against fin (before the replay) and rpa (call 1's rp: a
# 16-node array in the sink, copied to a pool after the walk). The CUDA suites test_dsm,
# test_core, test_raster, test_render and test_hard of rpc; deepvox-lean rpc rendering
# knecht-fig56 with DSM shadows (1024^2) for every storage the replay touches, and compact
# bilinear, PNGs compared with call 1's fin PNGs (r1/png); a kernel-timing round of rpc; bench_dsm
# fin, rpa and rpc interleaved, three rounds of 3 repetitions of every storage's generation at
# 1024^2 and compact's bilinear frame.
set -u
G=$PWD/.gpu; W=$(mktemp -d); mkdir -p $W/bin; R=$PWD/results/2026-12-03-replay-h200
export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/assets LD_LIBRARY_PATH=$G/lib:${LD_LIBRARY_PATH:-}
for f in $G/bin/*.xz; do b=$W/bin/$(basename $f .xz); xz -dc $f > $b; chmod +x $b; done
L=$W/r2; mkdir -p $L $L/png
trap 'tar -czf $OUT/r2.tar.gz -C $L .' EXIT
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $L/gpu.txt 2>&1; cat $L/gpu.txt
t0=$(date +%s)
for t in test_dsm test_core test_raster test_render test_hard; do
  timeout 240 $W/bin/$t-rpc > $L/$t.log 2>&1; echo "$t rc=$? $(grep -E '^\[  (PASSED|FAILED) ' $L/$t.log | tr '\n' ' ') skipped=$(grep -cE '^\[  SKIPPED \] .*\(' $L/$t.log) $(( $(date +%s)-t0 ))s"
done
grep -h "^\[  FAILED  \]" $L/test_*.log | sort -u | head
grep -hE "NodeReplay|CombinedClaims|HardDeterminism" $L/test_*.log | grep -E "OK|FAILED|SKIPPED"
for s in compact moments fourier occupancy blocked chunked chunked:alloc=thesis compact:bilinear; do
  st=${s%%:*}; P="--storage $st --dsm-res 1024"
  case $s in *alloc=thesis) P="$P --param storage.alloc=thesis";; *bilinear) P="$P --filter bilinear";; esac
  n=$(echo $s | tr ':=' '--')
  timeout 60 $W/bin/deepvox-lean-rpc render $G/scenes/full.json --out $W/$n-rpc.png --shadows dsm $P --backend cuda --frames 4 --orbit 0 --stats $L/$n-rpc.json > $L/$n-rpc.log 2>&1
  echo "$n rpc rc=$? $(python3 -c "
import json; j=json.load(open('$L/$n-rpc.json')); f=j['frames'][-1]
print('frame ms %.3f'%f['milliseconds'])" 2>&1)"
  cp $W/$n-rpc_0003.png $L/png/$n-rpc.png 2>/dev/null
  cmp $R/r1/png/$n-fin.png $L/png/$n-rpc.png && echo "$n: fin (call 1) and rpc PNGs byte-identical"
done
md5sum $L/png/*.png > $L/png-md5.txt
A="--benchmark_repetitions=3 --benchmark_report_aggregates_only=true"
D='^(generate/[a-z0-9:=]+/cuda/1024|render_bilinear/compact/cuda/1024)/'
DEEPVOX_KERNEL_TIMING=1 timeout 150 $W/bin/bench_dsm-rpc --benchmark_repetitions=1 --benchmark_filter="$D" --benchmark_out=$L/bench_dsm-rpc-kernels.json > $L/bench_dsm-rpc-kernels.log 2>&1
echo "kernel timing rc=$? $(( $(date +%s)-t0 ))s"
for round in 1 2 3; do
  for v in fin rpa rpc; do
    timeout 150 $W/bin/bench_dsm-$v $A --benchmark_filter="$D" --benchmark_out=$L/bench_dsm-$v-$round.json > $L/bench_dsm-$v-$round.log 2>&1
    echo "bench_dsm $v $round rc=$? $(( $(date +%s)-t0 ))s"
  done
done
for v in fin rpa rpc; do echo "== $v"; grep -h median $L/bench_dsm-$v-3.log | awk '{print $1, $2, $3}'; done
echo "total $(( $(date +%s)-t0 ))s"
