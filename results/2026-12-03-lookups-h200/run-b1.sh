#!/bin/bash
# Eleventh round, call 1: lk (main plus one reader call per DSM lookup for all its taps, and the
# moments resolve as a template on the moment count) against nf (c590b7b). CUDA suites test_dsm,
# test_render, test_hard of lk; deepvox-lean nf and lk rendering knecht-fig56 with DSM shadows
# (1024^2) for every storage, filter none and bilinear, PNGs compared byte for byte; bench_dsm nf and
# lk interleaved, three rounds of 3 repetitions of render_bilinear/<storage>/cuda/1024.
set -u
G=$PWD/.gpu; W=$(mktemp -d); mkdir -p $W/bin
export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/assets LD_LIBRARY_PATH=$G/lib:${LD_LIBRARY_PATH:-}
for f in $G/bin/*.xz; do b=$W/bin/$(basename $f .xz); xz -dc $f > $b; chmod +x $b; done
L=$W/b1; mkdir -p $L $L/png
trap 'tar -czf $OUT/b1.tar.gz -C $L .' EXIT
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $L/gpu.txt 2>&1; cat $L/gpu.txt
t0=$(date +%s)
for t in test_dsm test_render test_hard; do
  timeout 200 $W/bin/$t-lk > $L/$t.log 2>&1; echo "$t rc=$? $(grep -E '^\[  (PASSED|FAILED) ' $L/$t.log | tr '\n' ' ') skipped=$(grep -cE '^\[  SKIPPED \] .*\(' $L/$t.log) $(( $(date +%s)-t0 ))s"
done
grep -h "^\[  FAILED  \]" $L/test_*.log | sort -u | head
for st in compact texture3d chunked blocked beer avsm moments fourier occupancy; do
  for fl in none bilinear; do
    for b in nf lk; do
      n=$st-$fl-$b
      timeout 60 $W/bin/deepvox-lean-$b render $G/scenes/full.json --out $W/$n.png --shadows dsm --storage $st --dsm-res 1024 --filter $fl --backend cuda --frames 2 --orbit 0 --stats $L/$n.json > $L/$n.log 2>&1 || echo "$n rc=$?"
      cp $W/${n}_0001.png $L/png/$n.png 2>/dev/null
    done
    cmp -s $L/png/$st-$fl-nf.png $L/png/$st-$fl-lk.png && echo "$st $fl: nf and lk PNGs byte-identical" || echo "$st $fl: PNGs DIFFER"
  done
done
md5sum $L/png/*.png > $L/png-md5.txt
echo "renders $(( $(date +%s)-t0 ))s"
A="--benchmark_repetitions=3 --benchmark_report_aggregates_only=true"
D='^render_bilinear/[a-z0-9]+/cuda/1024/'
for round in 1 2 3; do
  for v in nf lk; do
    timeout 150 $W/bin/bench_dsm-$v $A --benchmark_filter="$D" --benchmark_out=$L/bench_dsm-$v-$round.json > $L/bench_dsm-$v-$round.log 2>&1
    echo "bench_dsm $v $round rc=$? $(( $(date +%s)-t0 ))s"
  done
done
for v in nf lk; do echo "== $v"; grep -h median $L/bench_dsm-$v-3.log | awk '{print $1, $2, $3}'; done
echo "total $(( $(date +%s)-t0 ))s"
