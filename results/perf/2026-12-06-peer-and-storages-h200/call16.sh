#!/usr/bin/env bash
# Device call 16 (session 6): (1) knecht-32-lights with shadow maps at 720x480 (31.6 ms in call
# 15b against 13.4 in call 13): cee = cee8710, new = 817ce72 + shared tables, nest = new with
# shade_phong's light loop as in cee8710; renders with culling on and off, interleaved.
# (2) the peer (cuda_voxelizer v0.6 from source) against bench_voxelizer sat, three interleaved
# rounds; bench_dsm's nine storages at 1024^2 and bench_renderer's fig56 and feature/ cases.
# (4) the scale suite's lights axes (lights-spot, lights-omni) with the faster of new and nest
# for the rest of the call (resumable).
# (3) branch satlean (764ce70: warp-combined, pair-wise 64-bit grid writes, one clear launch):
# test_voxelizer on CUDA, its bench_voxelizer (tip) interleaved with 817ce72's (cur).
set -uo pipefail
LIMIT=${LIMIT:-555}
G=$PWD/.gpu4; W=$(mktemp -d); mkdir -p $G/x && for f in $G/bin/*.xz; do xz -T4 -dc "$f" > $G/x/$(basename "$f" .xz) & done; wait; chmod +x $G/x/*
B=$G/x; export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/experiments/assets; S=$PWD/experiments/scenes
nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.max.sm --format=csv,noheader | tee $W/gpu.txt
pack() { tar -czf $OUT/call16.tar.gz -C $W . 2>/dev/null; }
left() { [ $SECONDS -lt $1 ]; }
for r in 1 2; do case $r in 1) order="cee new nest";; 2) order="nest new cee";; esac
  for side in $order; do for cull in on off; do a=; [ $cull = off ] && a=--no-light-culling
    (cd $W && timeout 30 $B/deepvox-lean-$side render $S/knecht-32-lights.json --backend cuda --shadows shadowmap --dsm-res 512 --width 720 --height 480 --frames 4 $a --stats $W/sm-$side-$cull-r$r.json --out l.png > $W/sm-$side-$cull-r$r.log 2>&1); echo "$side $cull r$r rc=$? $(python3 -c "import json,statistics as s;f=json.load(open('$W/sm-$side-$cull-r$r.json'))['frames'];print(round(s.median([x['fragment_ms'] for x in f[1:]]),2))" 2>&1) t=$SECONDS"
  done; done
done
pack
(cd $W && timeout 120 $B/test_voxelizer-tip > $W/test_voxelizer.log 2>&1); echo "test_voxelizer-tip rc=$? $(grep -E '^\[  (PASSED|FAILED) ' $W/test_voxelizer.log | tr '\n' ' ') skipped=$(grep -c '^\[  SKIPPED \] ' $W/test_voxelizer.log) t=$SECONDS"
mkdir -p $W/peer $W/vox && tar -xJf $G/bin/meshes.tar.xz -C $W/peer
for r in 1 2 3; do left $((LIMIT-300)) || break
  (cd $W/peer/meshes && LD_LIBRARY_PATH=$G/bin timeout 60 $G/bin/peer_voxelizer_bench --grids 512,1024 --bounds cubic bunny2.obj bunny3.obj cube.obj > $W/vox/peer-r$r.jsonl 2> $W/vox/peer-r$r.err); echo "peer r$r rc=$? t=$SECONDS"
  case $r in 2) order="tip cur";; *) order="cur tip";; esac
  for side in $order; do s=; n=old; [ $side = tip ] && s=-tip && n=new
    LD_LIBRARY_PATH=$G/lib timeout 60 $B/bench_voxelizer$s --benchmark_filter='^sat/' --benchmark_repetitions=3 --benchmark_min_time=0.1 --benchmark_report_aggregates_only=true --benchmark_out=$W/vox/$n-bench_voxelizer-r$r.json > $W/vox/$side-sat-r$r.log 2>&1; echo "sat $side r$r rc=$? t=$SECONDS"
  done
done
pack
mkdir -p $W/bench
for r in 1; do left $((LIMIT-200)) || break
  LD_LIBRARY_PATH=$G/lib timeout 100 $B/bench_dsm --benchmark_filter='^(generate|render_bilinear)/[a-z0-9]+/cuda/1024' --benchmark_repetitions=5 --benchmark_report_aggregates_only=true --benchmark_out=$W/bench/new-bench_dsm-r$r.json > $W/bench/dsm-r$r.log 2>&1; echo "dsm r$r rc=$? t=$SECONDS"
  LD_LIBRARY_PATH=$G/lib timeout 60 $B/bench_renderer --benchmark_filter='^(raster_render/fig56_(none|shadowmap)_cuda|feature/)' --benchmark_repetitions=5 --benchmark_report_aggregates_only=true --benchmark_out=$W/bench/new-bench_renderer-r$r.json > $W/bench/renderer-r$r.log 2>&1; echo "renderer r$r rc=$? t=$SECONDS"
  pack
done
python3 scripts/bench_summary.py $W/bench > $W/bench/summary.txt 2>&1; cut -c1-150 $W/bench/summary.txt | head -50
python3 scripts/bench_summary.py $W/vox > $W/vox/summary.txt 2>&1; grep -E "with_clear|sat/" $W/vox/summary.txt | cut -c1-150 | head -30
cut -c1-400 $W/vox/peer-r1.jsonl | head -8
python3 - $W > $W/pick.txt <<'PY'
import glob, json, statistics, sys, collections
v = collections.defaultdict(list)
for f in glob.glob(sys.argv[1] + "/sm-*-on-r*.json"):
    side = f.split("/sm-")[1].split("-")[0]
    try: fr = json.load(open(f))["frames"]
    except Exception: continue
    v[side].append(statistics.median(x["fragment_ms"] for x in fr[1:]))
m = {k: statistics.median(x) for k, x in v.items()}
print("nest" if m.get("nest", 1e9) < 0.97 * m.get("new", 1e9) else "new", m)
PY
PICK=$(cut -d' ' -f1 $W/pick.txt); echo "suite build: $(cat $W/pick.txt) t=$SECONDS"
mkdir -p $W/suites
(cd $W && timeout $((LIMIT-SECONDS-15)) $B/deepvox-lean-$PICK suite scale --only lights --backend cuda --out $W/suites > $W/suite.log 2>&1); echo "suite rc=$? t=$SECONDS"; tail -3 $W/suite.log | cut -c1-200
rm -f $W/*.png; pack; echo all-done t=$SECONDS $(date +%T)
