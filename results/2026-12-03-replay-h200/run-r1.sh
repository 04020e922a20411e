#!/bin/bash
# Ninth round, call 1: node replay (rp: the two-pass storages walk each texel once, the write
# pass replays the kept nodes) against the committed code before it (fin: d96508d's design, the
# eighth round's bench_dsm-srt3 and deepvox-lean-fin). The CUDA suites test_dsm, test_core,
# test_raster, test_render and test_hard of
# rp; deepvox-lean fin and rp rendering knecht-fig56 with DSM shadows (1024^2) for every storage
# the replay touches, and compact bilinear, PNGs compared; bench_dsm fin and rp interleaved, a
# kernel-timing round and three rounds of 3 repetitions of every storage's generation at 1024^2.
set -u
G=$PWD/.gpu; W=$(mktemp -d); mkdir -p $W/bin
export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/assets LD_LIBRARY_PATH=$G/lib:${LD_LIBRARY_PATH:-}
for f in $G/bin/*.xz; do b=$W/bin/$(basename $f .xz); xz -dc $f > $b; chmod +x $b; done
L=$W/r1; mkdir -p $L $L/png
trap 'tar -czf $OUT/r1.tar.gz -C $L .' EXIT
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $L/gpu.txt 2>&1; cat $L/gpu.txt
t0=$(date +%s)
for t in test_dsm test_core test_raster test_render test_hard; do
  timeout 240 $W/bin/$t-rp > $L/$t.log 2>&1; echo "$t rc=$? $(grep -E '^\[  (PASSED|FAILED) ' $L/$t.log | tr '\n' ' ') skipped=$(grep -cE '^\[  SKIPPED \] .*\(' $L/$t.log) $(( $(date +%s)-t0 ))s"
done
grep -h "^\[  FAILED  \]" $L/test_*.log | sort -u | head
grep -hE "NodeReplay|CombinedClaims" $L/test_*.log | grep -E "OK|FAILED|SKIPPED"
for s in compact moments fourier occupancy blocked chunked chunked:alloc=thesis compact:bilinear; do
  st=${s%%:*}; P="--storage $st --dsm-res 1024"
  case $s in *alloc=thesis) P="$P --param storage.alloc=thesis";; *bilinear) P="$P --filter bilinear";; esac
  n=$(echo $s | tr ':=' '--')
  for b in fin rp; do
    timeout 60 $W/bin/deepvox-lean-$b render $G/scenes/full.json --out $W/$n-$b.png --shadows dsm $P --backend cuda --frames 4 --orbit 0 --stats $L/$n-$b.json > $L/$n-$b.log 2>&1
    echo "$n $b rc=$? $(python3 -c "
import json; j=json.load(open('$L/$n-$b.json')); f=j['frames'][-1]
print('frame ms %.3f'%f['milliseconds'], {k:v for k,v in f.items() if k.endswith('_ms') or 'replay' in k})" 2>&1 | cut -c1-300)"
    cp $W/$n-${b}_0003.png $L/png/$n-$b.png 2>/dev/null
  done
  cmp $L/png/$n-fin.png $L/png/$n-rp.png && echo "$n: fin and rp PNGs byte-identical"
done
md5sum $L/png/*.png > $L/png-md5.txt
A="--benchmark_repetitions=3 --benchmark_report_aggregates_only=true"
D='^(generate/[a-z0-9:=]+/cuda/1024|render_bilinear/compact/cuda/1024)/'
DEEPVOX_KERNEL_TIMING=1 timeout 150 $W/bin/bench_dsm-rp --benchmark_repetitions=1 --benchmark_filter="$D" --benchmark_out=$L/bench_dsm-rp-kernels.json > $L/bench_dsm-rp-kernels.log 2>&1
echo "kernel timing rc=$? $(( $(date +%s)-t0 ))s"
for round in 1 2 3; do
  for v in fin rp; do
    timeout 150 $W/bin/bench_dsm-$v $A --benchmark_filter="$D" --benchmark_out=$L/bench_dsm-$v-$round.json > $L/bench_dsm-$v-$round.log 2>&1
    echo "bench_dsm $v $round rc=$? $(( $(date +%s)-t0 ))s"
  done
done
for v in fin rp; do echo "== $v"; grep -h median $L/bench_dsm-$v-3.log | awk '{print $1, $2, $3}'; done
echo "total $(( $(date +%s)-t0 ))s"
