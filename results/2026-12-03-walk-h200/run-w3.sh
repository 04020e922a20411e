#!/bin/bash
# Tenth round, call 3: the committed design (nf: the write pass as two kernels, the kept texels
# replayed by one that carries no walk, the lost ones walked by persistent threads over the first
# pass's list of them, dsm/storage/replay_write.h) against hd (HEAD 23998b2). CUDA suites
# test_dsm and test_hard of nf; deepvox-lean nf rendering knecht-fig56 with DSM shadows (1024^2)
# for the storages of the ninth round's PNGs (.gpu/ref), compared byte for byte; a kernel-timing
# round of nf; bench_dsm hd and nf interleaved, three rounds of 3 repetitions of the generation at
# 1024^2 of the storages with a replay and of beer (without one).
set -u
G=$PWD/.gpu; W=$(mktemp -d); mkdir -p $W/bin
export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/assets LD_LIBRARY_PATH=$G/lib:${LD_LIBRARY_PATH:-}
for f in $G/bin/*.xz; do b=$W/bin/$(basename $f .xz); xz -dc $f > $b; chmod +x $b; done
L=$W/w3; mkdir -p $L $L/png
trap 'tar -czf $OUT/w3.tar.gz -C $L .' EXIT
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $L/gpu.txt 2>&1; cat $L/gpu.txt
t0=$(date +%s)
for t in test_dsm test_hard; do
  timeout 240 $W/bin/$t-nf > $L/$t.log 2>&1; echo "$t rc=$? $(grep -E '^\[  (PASSED|FAILED) ' $L/$t.log | tr '\n' ' ') skipped=$(grep -cE '^\[  SKIPPED \] .*\(' $L/$t.log) $(( $(date +%s)-t0 ))s"
done
grep -h "^\[  FAILED  \]" $L/test_*.log | sort -u | head
grep -hE "NodeReplay" $L/test_*.log | grep -E "OK|FAILED|SKIPPED"
for s in compact moments fourier occupancy blocked chunked chunked:alloc=thesis compact:bilinear; do
  st=${s%%:*}; P="--storage $st --dsm-res 1024"
  case $s in *alloc=thesis) P="$P --param storage.alloc=thesis";; *bilinear) P="$P --filter bilinear";; esac
  n=$(echo $s | tr ':=' '--')
  timeout 60 $W/bin/deepvox-lean-nf render $G/scenes/full.json --out $W/$n-nf.png --shadows dsm $P --backend cuda --frames 4 --orbit 0 --stats $L/$n-nf.json > $L/$n-nf.log 2>&1
  echo "$n nf rc=$? $(python3 -c "
import json,re; j=json.load(open('$L/$n-nf.json')); f=j['frames'][-1]; s=json.dumps(j)
print('frame ms %.3f'%f['milliseconds'], re.findall(r'\"replay_walked_texels\": [0-9]+', s)[-1:])" 2>&1)"
  cp $W/$n-nf_0003.png $L/png/$n-nf.png 2>/dev/null
  cmp $G/ref/$n-fin.png $L/png/$n-nf.png && echo "$n: ninth round fin and nf PNGs byte-identical"
done
md5sum $L/png/*.png > $L/png-md5.txt
A="--benchmark_repetitions=3 --benchmark_report_aggregates_only=true"
D='^generate/(compact|blocked|chunked|moments|fourier|occupancy|chunked:alloc=thesis|beer)/cuda/1024/'
DEEPVOX_KERNEL_TIMING=1 timeout 150 $W/bin/bench_dsm-nf --benchmark_repetitions=1 --benchmark_filter="$D" --benchmark_out=$L/bench_dsm-nf-kernels.json > $L/bench_dsm-nf-kernels.log 2>&1
echo "kernel timing rc=$? $(( $(date +%s)-t0 ))s"
for round in 1 2 3; do
  for v in hd nf; do
    timeout 150 $W/bin/bench_dsm-$v $A --benchmark_filter="$D" --benchmark_out=$L/bench_dsm-$v-$round.json > $L/bench_dsm-$v-$round.log 2>&1
    echo "bench_dsm $v $round rc=$? $(( $(date +%s)-t0 ))s"
  done
done
for v in hd nf; do echo "== $v"; grep -h median $L/bench_dsm-$v-3.log | awk '{print $1, $2, $3}'; done
echo "total $(( $(date +%s)-t0 ))s"
