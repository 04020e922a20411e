#!/usr/bin/env bash
# Device call 15b (session 6): the final build of session 5 (cur = 817ce72) and this session's
# shared-memory tables (new = 817ce72 + lights and face headers in shared memory) on the GPU.
# CUDA tests, memcheck and racecheck of the new launch; interleaved A/B of bench_renderer goal/
# (old = d95fcec, cur, new); knecht-32-lights frames of new with and without light culling;
# generation time and peak device memory of its 512^2 and 1024^2 maps.
set -uo pipefail
LIMIT=${LIMIT:-540}
W=$(mktemp -d); mkdir -p .gpu/x && for f in .gpu/bin/*.xz; do xz -T4 -dc "$f" > .gpu/x/$(basename "$f" .xz) & done; wait; chmod +x .gpu/x/*
B=$PWD/.gpu/x; export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/experiments/assets LD_LIBRARY_PATH=$PWD/.gpu/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}; S=$PWD/experiments/scenes
nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.max.sm --format=csv,noheader | tee $W/gpu.txt
pack() { tar -czf $OUT/call15b.tar.gz -C $W . 2>/dev/null; }
left() { [ $SECONDS -lt $1 ]; }
CS=/usr/local/cuda/bin/compute-sanitizer
summ() { echo "$(grep -E '^\[  (PASSED|FAILED) |ERROR SUMMARY|RACECHECK SUMMARY' $1 | tr '\n' ' ') skipped=$(grep -c '^\[  SKIPPED \] ' $1)"; }
echo "decompressed t=$SECONDS"
(cd $W && timeout 60 $B/test_core --gtest_filter='SharedTables.*:Backends.*' > $W/test_core.log 2>&1); echo "test_core rc=$? $(summ $W/test_core.log) t=$SECONDS"
(cd $W && timeout 120 $B/test_frame --gtest_filter='LightCulling.*:DeferredOracle.*:RasterRender.*' > $W/test_frame.log 2>&1); echo "test_frame rc=$? $(summ $W/test_frame.log) t=$SECONDS"
pack
(cd $W && timeout 60 $CS --tool memcheck --error-exitcode 9 $B/test_core --gtest_filter='SharedTables.Cuda*' > $W/memcheck-core.log 2>&1); echo "memcheck core rc=$? $(summ $W/memcheck-core.log) t=$SECONDS"
(cd $W && timeout 60 $CS --tool racecheck --error-exitcode 9 $B/test_core --gtest_filter='SharedTables.Cuda*' > $W/racecheck-core.log 2>&1); echo "racecheck core rc=$? $(summ $W/racecheck-core.log) t=$SECONDS"
(cd $W && timeout 120 $CS --tool memcheck --error-exitcode 9 $B/test_frame --gtest_filter='LightCulling.Cuda*' > $W/memcheck-frame.log 2>&1); echo "memcheck frame rc=$? $(summ $W/memcheck-frame.log) t=$SECONDS"
left 200 && { (cd $W && timeout 100 $CS --tool racecheck --error-exitcode 9 $B/test_frame --gtest_filter='LightCulling.CudaExact*' > $W/racecheck-frame.log 2>&1); echo "racecheck frame rc=$? $(summ $W/racecheck-frame.log) t=$SECONDS"; }
pack
mkdir -p $W/ab
for r in 1 2; do left $((LIMIT-150)) || break
  case $r in 2) order="new cur old";; *) order="old cur new";; esac
  for side in $order; do s=; [ $side != new ] && s=-$side
    timeout 100 $B/bench_renderer$s --benchmark_filter='goal/' --benchmark_out=$W/ab/$side-bench_renderer-r$r.json > $W/ab/$side-bench_renderer-r$r.log 2>&1; echo "renderer $side r$r rc=$? t=$SECONDS"
  done; pack
done
python3 - $W/ab <<'PY' | tee $W/ab/summary3.txt
import glob, json, os, statistics, sys, collections
v = collections.defaultdict(list)
for f in glob.glob(os.path.join(sys.argv[1], "*-bench_renderer-r*.json")):
    side = os.path.basename(f).split("-")[0]
    try: bs = json.load(open(f))["benchmarks"]
    except Exception: continue
    for b in bs: v[(b["name"].split("/iterations")[0], side)].append(b["real_time"])
for name in sorted({k[0] for k in v}):
    row = [f"{s} {statistics.median(v[(name, s)]):.3f} [{min(v[(name, s)]):.3f}-{max(v[(name, s)]):.3f}]" for s in ("old", "cur", "new") if (name, s) in v]
    print(name, "|", " | ".join(row))
PY
for cull in on off; do a=; [ $cull = off ] && a=--no-light-culling
  for sh in shadowmap dsm; do for wh in "720 480" "3840 2160"; do set -- $wh; left $((LIMIT-35)) || continue
    (cd $W && timeout 40 $B/deepvox-lean render $S/knecht-32-lights.json --backend cuda --shadows $sh --dsm-res 512 --width $1 --height $2 --frames 4 $a --stats $W/l32-$sh-$1-$cull.json --out l.png > $W/l32-$sh-$1-$cull.log 2>&1); echo "l32 $sh $1 $cull rc=$? $(python3 -c "import json,statistics as s;f=json.load(open('$W/l32-$sh-$1-$cull.json'))['frames'];print(round(s.median([x['milliseconds'] for x in f[1:]]),2),'ms lpp',round(f[-1].get('lights_per_pixel_mean',0),2))" 2>&1)"
  done; done
done
pack
for res in 512 1024; do left $((LIMIT-12)) || break
  (cd $W && timeout 40 $B/deepvox-lean render $S/knecht-32-lights.json --backend cuda --shadows dsm --dsm-res $res --frames 3 --stats $W/fp-$res.json --out $W/fp-$res.png > $W/fp-$res.log 2>&1); echo "footprint $res rc=$? $(python3 -c "
import json;j=json.load(open('$W/fp-$res.json'));st=j['shadows']['stats']
print('peak_used',j['device_memory']['peak_used_bytes'],'gen_ms',round(st['generation_ms'],2),'sets',st.get('face_sets'),'frame_ms',[round(x['milliseconds'],2) for x in j['frames']])" 2>&1 | cut -c1-200)"
done
rm -f $W/l*.png $W/fp-*.png; pack; echo all-done t=$SECONDS $(date +%T)
