#!/bin/bash
# Ninth round, call 3: why the first pass that keeps the nodes (0.72 ms at 1024^2) is slower than
# the counting pass it replaced (0.57 ms). bench_dsm's count/range pass of compact, moments and
# blocked for fin (before the replay), rpc (call 2's design) and three variants of rpc:
# va (the keeping part of the sink's emit out of line, __noinline__), vb (the first pass stores
# no error bound or final visibility: every texel marked lost, so the write pass walks again),
# vc (no node written, every texel lost, the error bound and visibility stored). Five builds
# interleaved, three rounds of 3 repetitions. And the CUDA suites test_dsm, test_hard, test_core
# of va, should it be kept.
set -u
G=$PWD/.gpu; W=$(mktemp -d); mkdir -p $W/bin
export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/assets LD_LIBRARY_PATH=$G/lib:${LD_LIBRARY_PATH:-}
for f in $G/bin/*.xz; do b=$W/bin/$(basename $f .xz); xz -dc $f > $b; chmod +x $b; done
L=$W/r3; mkdir -p $L
trap 'tar -czf $OUT/r3.tar.gz -C $L .' EXIT
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $L/gpu.txt 2>&1; cat $L/gpu.txt
t0=$(date +%s)
for t in test_dsm test_core test_hard; do
  timeout 240 $W/bin/$t-va > $L/$t.log 2>&1; echo "$t rc=$? $(grep -E '^\[  (PASSED|FAILED) ' $L/$t.log | tr '\n' ' ') skipped=$(grep -cE '^\[  SKIPPED \] .*\(' $L/$t.log) $(( $(date +%s)-t0 ))s"
done
grep -h "^\[  FAILED  \]" $L/test_*.log | sort -u | head
A="--benchmark_repetitions=3 --benchmark_report_aggregates_only=true"
D='^generate/(compact|moments|blocked)/cuda/1024/'
for round in 1 2 3; do
  for v in fin rpc va vb vc; do
    timeout 100 $W/bin/bench_dsm-$v $A --benchmark_filter="$D" --benchmark_out=$L/bench_dsm-$v-$round.json > $L/bench_dsm-$v-$round.log 2>&1
    echo "bench_dsm $v $round rc=$? $(( $(date +%s)-t0 ))s"
  done
done
python3 - $L <<'PY'
import json, statistics as st, sys
L = sys.argv[1]
for case in ['compact', 'moments', 'blocked']:
    for v in ['fin', 'rpc', 'va', 'vb', 'vc']:
        first, total = [], []
        for r in [1, 2, 3]:
            for b in json.load(open(f'{L}/bench_dsm-{v}-{r}.json'))['benchmarks']:
                if b.get('aggregate_name') == 'median' and f'/{case}/' in b['name']:
                    first.append(b.get('count_ms', b.get('range_ms', 0.0)))
                    total.append(b['real_time'])
        print(f'{case:8s} {v:4s} first pass {st.median(first):.3f} ({min(first):.3f}-{max(first):.3f})  generation {st.median(total):.3f}')
PY
echo "total $(( $(date +%s)-t0 ))s"
