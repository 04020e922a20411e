#!/bin/bash
# Session 4, call 4: the DSM figures summed on the device (no copy of the per-texel records per
# generation): test_dsm and test_hard on the GPU; bench_dsm generate/*/cuda/1024 with the new
# wall_ms and records_copy_ms counters, and the f2033e6 bench on four storages; the `dsm`
# command's wall, old against new, 11 runs each interleaved (first dropped), and its phases.
set -u
G=$PWD/.gpu; W=$(mktemp -d); mkdir -p $W/bin
export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/assets LD_LIBRARY_PATH=$G/lib:${LD_LIBRARY_PATH:-}
for f in $G/bin/*.xz; do b=$W/bin/$(basename $f .xz); xz -dc $f > $b; chmod +x $b; done
L=$W/s4d; mkdir -p $L
trap 'tar -czf $OUT/s4d.tar.gz -C $L .' EXIT
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $L/gpu.txt 2>&1; cat $L/gpu.txt
t0=$(date +%s)
for t in test_dsm test_hard; do
  timeout 150 $W/bin/$t > $L/$t.log 2>&1; echo "$t rc=$? $(grep -E '^\[  (PASSED|FAILED|SKIPPED) ' $L/$t.log | tr '\n' ' ') $(( $(date +%s)-t0 ))s"
done
grep -h "^\[  FAILED  \]" $L/test_*.log | sort -u | head
S=scenes/knecht-fig56.json
for i in $(seq 1 11); do
  for bin in deepvox-lean-old deepvox-lean; do
    s=$(date +%s%N); timeout 20 $W/bin/$bin dsm $S --backend cuda --heatmap $W/$bin-h.png > /dev/null 2>&1; rc=$?; e=$(date +%s%N)
    echo "dsm $bin $i $(( (e-s)/1000000 )) rc=$rc" >> $L/wall-raw.txt
  done
done
for i in 1 2 3; do $W/bin/deepvox-lean dsm $S --backend cuda --stats $L/dsm-phases-$i.json > $L/dsm-phases-$i.log 2>&1; done
cmp $W/deepvox-lean-old-h.png $W/deepvox-lean-h.png && echo "dsm heatmaps byte-identical" | tee $L/outputs.txt
python3 - $L/wall-raw.txt <<'PY' | tee $L/wall-summary.txt
import sys, statistics as st
rows = [l.split() for l in open(sys.argv[1])]
for b in ["deepvox-lean-old", "deepvox-lean"]:
    v = sorted(int(r[3]) for r in rows if r[1] == b and r[2] != "1")
    print(f"dsm {b:17s} median {st.median(v):6.1f} ms  min {v[0]}  max {v[-1]}  n {len(v)}  {','.join(sorted(set(r[4] for r in rows if r[1] == b)))}")
PY
echo "elapsed $(( $(date +%s)-t0 ))s"
A="--benchmark_repetitions=3 --benchmark_report_aggregates_only=true"
timeout 230 $W/bin/bench_dsm $A --benchmark_filter='generate/.*/cuda/1024' --benchmark_out=$L/bench_dsm.json > $L/bench_dsm.log 2>&1
echo "bench_dsm rc=$? $(( $(date +%s)-t0 ))s"; grep median $L/bench_dsm.log | awk '{print $1, $2, $3, $4, $5}'
timeout 100 $W/bin/bench_dsm-old $A --benchmark_filter='generate/(compact|beer|texture3d|chunked)/cuda/1024' --benchmark_out=$L/bench_dsm-old.json > $L/bench_dsm-old.log 2>&1
echo "bench_dsm-old rc=$? $(( $(date +%s)-t0 ))s"; grep median $L/bench_dsm-old.log | awk '{print $1, $2, $3, $4, $5}'
