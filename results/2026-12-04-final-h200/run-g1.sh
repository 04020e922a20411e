#!/bin/bash
# Fourteenth round, call 1. (a) sat's walk with a float filter and the double test near the
# boundary: f1 (float(s) per voxel) and f2 (a float counter beside s) against main (un,
# b7e7935): test_voxel of each variant on the GPU, then bench_voxelizer '^sat/' interleaved,
# three rounds of 3 repetitions. (b) every goal of issue 13 on main (un) in one call:
# bench_renderer fig56 none/shadowmap, bench_dsm generate and render_bilinear at 1024^2 (every
# storage), 5 repetitions; process wall time of render/voxelize/info, 11 runs (first dropped).
set -u
G=$PWD/.gpu; W=$(mktemp -d); mkdir -p $W/bin
export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/assets LD_LIBRARY_PATH=$G/lib:${LD_LIBRARY_PATH:-}
for f in $G/bin/*.xz; do b=$W/bin/$(basename $f .xz); xz -dc $f > $b; chmod +x $b; done
L=$W/g1; mkdir -p $L
trap 'tar -czf $OUT/g1.tar.gz -C $L .' EXIT
exec > >(tee $L/run.log) 2>&1
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $L/gpu.txt 2>&1; cat $L/gpu.txt
t0=$(date +%s)
for t in test_voxel-f1 test_voxel-f2; do
  timeout 150 $W/bin/$t > $L/$t.log 2>&1; echo "$t rc=$? $(grep -E '^\[  (PASSED|FAILED|SKIPPED) ' $L/$t.log | tr '\n' ' ') $(( $(date +%s)-t0 ))s"
done
grep -h "^\[  FAILED  \]" $L/test_*.log | sort -u | head
A="--benchmark_repetitions=3 --benchmark_min_time=0.1 --benchmark_report_aggregates_only=true --benchmark_filter=^sat/"
for round in 1 2 3; do
  for v in un f1 f2; do
    timeout 100 $W/bin/bench_voxelizer-$v $A --benchmark_out=$L/bench_voxelizer-$v-$round.json > $L/bench_voxelizer-$v-$round.log 2>&1
    echo "bench_voxelizer $v round $round rc=$? $(( $(date +%s)-t0 ))s"
  done
done
for v in un f1 f2; do
  echo "== $v"; grep median $L/bench_voxelizer-$v-3.log | grep -oE "^[^ ]+|small_ms=[^ ]+|with_clear_ms=[^ ]+" | paste - - -
done
R="--benchmark_repetitions=5 --benchmark_report_aggregates_only=true"
timeout 60 $W/bin/bench_renderer-un $R --benchmark_filter='raster_render/fig56_(none|shadowmap)_cuda' --benchmark_out=$L/bench_renderer-un.json > $L/bench_renderer-un.log 2>&1
echo "bench_renderer rc=$? $(( $(date +%s)-t0 ))s"
timeout 150 $W/bin/bench_dsm-un $R --benchmark_filter='^(generate|render_bilinear)/[a-z0-9:=]+/cuda/1024/' --benchmark_out=$L/bench_dsm-un.json > $L/bench_dsm-un.log 2>&1
echo "bench_dsm rc=$? $(( $(date +%s)-t0 ))s"
M=assets/meshes/stanford-bunny-lowres.obj; S=scenes/knecht-fig56.json
declare -A C
C[info]="info $S"
C[render_dsm]="render $S --backend cuda --shadows dsm --out $W/p.png"
C[render_none]="render $S --backend cuda --shadows none --out $W/p.png"
C[voxelize]="voxelize $M --method sat --res 512x512x512 --backend cuda --out $W/g.binvox"
for i in $(seq 1 11); do
  for name in info render_dsm render_none voxelize; do
    s=$(date +%s%N); timeout 10 $W/bin/deepvox-lean-un ${C[$name]} > /dev/null 2>&1; rc=$?; e=$(date +%s%N)
    echo "$name $i $(( (e-s)/1000000 )) rc=$rc" >> $L/wall-raw.txt
  done
done
python3 - $L/wall-raw.txt <<'PY' | tee $L/wall-summary.txt
import sys, statistics as st
rows = [l.split() for l in open(sys.argv[1])]
for name in ["info", "render_dsm", "render_none", "voxelize"]:
    v = sorted(int(r[2]) for r in rows if r[0] == name and r[1] != "1")
    rc = set(r[3] for r in rows if r[0] == name)
    print(f"{name:12s} median {st.median(v):6.1f} ms  min {v[0]}  max {v[-1]}  n {len(v)}  {','.join(sorted(rc))}")
PY
echo "total $(( $(date +%s)-t0 ))s"
