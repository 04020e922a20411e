#!/bin/bash
# Session 4, call 2: process wall time of the f2033e6 binary (old) against this round's (new:
# driver started in the background while the input loads, no driver teardown at exit, PNG bytes
# through the display encoding's thresholds, word-level binvox writer, one grid read-back),
# 21 runs each (first dropped), interleaved; the new binary's phase marks; the outputs compared.
set -u
G=$PWD/.gpu; W=$(mktemp -d); mkdir -p $W/bin
export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/assets LD_LIBRARY_PATH=$G/lib:${LD_LIBRARY_PATH:-}
for f in $G/bin/*.xz; do b=$W/bin/$(basename $f .xz); xz -dc $f > $b; chmod +x $b; done
L=$W/s4b; mkdir -p $L
trap 'tar -czf $OUT/s4b.tar.gz -C $L .' EXIT
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $L/gpu.txt 2>&1; cat $L/gpu.txt
nproc >> $L/gpu.txt; lscpu | grep -E "Model name" >> $L/gpu.txt
t0=$(date +%s)
for i in 1 2 3 4 5 6; do python3 $G/cuda_init_probe.py; done > $L/cuda-init.txt 2>&1
M=assets/meshes/stanford-bunny-lowres.obj; S=scenes/knecht-fig56.json
declare -A C
C[info]="info $S"
C[render_dsm]="render $S --backend cuda --shadows dsm --out $W/OUTPNG"
C[render_none]="render $S --backend cuda --shadows none --out $W/OUTPNG"
C[voxelize]="voxelize $M --method sat --res 512x512x512 --backend cuda --out $W/OUTBINVOX"
for name in info render_dsm render_none voxelize; do
  for i in $(seq 1 21); do
    for bin in deepvox-lean-old deepvox-lean; do
      c=${C[$name]//OUTPNG/$bin-$name.png}; c=${c//OUTBINVOX/$bin-$name.binvox}
      s=$(date +%s%N); timeout 10 $W/bin/$bin $c > /dev/null 2>&1; rc=$?; e=$(date +%s%N)
      echo "$name $bin $i $(( (e-s)/1000000 )) rc=$rc" >> $L/wall-raw.txt
    done
  done
done
python3 - $L/wall-raw.txt <<'PY' | tee $L/wall-summary.txt
import sys, statistics as st
rows = [l.split() for l in open(sys.argv[1])]
for name in ["info", "render_dsm", "render_none", "voxelize"]:
    for b in ["deepvox-lean-old", "deepvox-lean"]:
        v = sorted(int(r[3]) for r in rows if r[0] == name and r[1] == b and r[2] != "1")
        rc = set(r[4] for r in rows if r[0] == name and r[1] == b)
        print(f"{name:12s} {b:17s} median {st.median(v):6.1f} ms  min {v[0]}  max {v[-1]}  n {len(v)}  {','.join(sorted(rc))}")
PY
for name in render_dsm render_none voxelize; do
  ext=png; [ $name = voxelize ] && ext=binvox
  cmp $W/deepvox-lean-old-$name.$ext $W/deepvox-lean-$name.$ext && echo "$name: old and new outputs byte-identical" | tee -a $L/outputs.txt || echo "$name: outputs DIFFER" | tee -a $L/outputs.txt
done
echo "elapsed $(( $(date +%s)-t0 ))s"
for name in render_dsm render_none voxelize; do
  for i in 1 2 3 4 5; do
    c=${C[$name]//OUTPNG/p.png}; c=${c//OUTBINVOX/p.binvox}
    s=$(date +%s%N); $W/bin/deepvox-lean $c --stats $L/phases-$name-$i.json > $L/phases-$name-$i.log 2>&1; e=$(date +%s%N)
    echo "$name $i external $(( (e-s)/1000000 ))" >> $L/phases-external.txt
  done
done
cat $L/phases-external.txt | tail -3
c=${C[render_dsm]//OUTPNG/f.png}; $W/bin/deepvox-lean $c --frames 4 --stats $L/frames4-dsm.json > $L/frames4-dsm.log 2>&1
echo "elapsed $(( $(date +%s)-t0 ))s"
