#!/bin/bash
# Session 4, call 1: where a render or voxelize process's wall time goes on the GPU machine:
# external wall of 11 runs (first dropped) for the f2033e6 binary (old) and the phase-marked one
# (new: background driver start, word-level binvox writer), the new binary's phase marks from
# --stats, frame 0 against warm frames, eager module loading, and the CUDA driver alone.
set -u
G=$PWD/.gpu; W=$(mktemp -d); mkdir -p $W/bin
export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/assets LD_LIBRARY_PATH=$G/lib:${LD_LIBRARY_PATH:-}
for f in $G/bin/*.xz; do b=$W/bin/$(basename $f .xz); xz -dc $f > $b; chmod +x $b; done
L=$W/s4a; mkdir -p $L
trap 'tar -czf $OUT/s4a.tar.gz -C $L .' EXIT
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $L/gpu.txt 2>&1; cat $L/gpu.txt
nproc >> $L/gpu.txt; lscpu | grep -E "Model name|MHz" >> $L/gpu.txt
t0=$(date +%s)
for i in 1 2 3 4 5 6; do python3 $G/cuda_init_probe.py; done > $L/cuda-init.txt 2>&1; tail -2 $L/cuda-init.txt
M=assets/meshes/stanford-bunny-lowres.obj; S=scenes/knecht-fig56.json
declare -A C
C[info]="info $S"
C[render_dsm]="render $S --backend cuda --shadows dsm --out $W/x.png"
C[render_none]="render $S --backend cuda --shadows none --out $W/x.png"
C[voxelize]="voxelize $M --method sat --res 512x512x512 --backend cuda --out $W/g.binvox"
for name in info render_dsm render_none voxelize; do
  for bin in deepvox-lean-old deepvox-lean; do
    for i in $(seq 1 11); do s=$(date +%s%N); timeout 10 $W/bin/$bin ${C[$name]} > /dev/null 2>&1; e=$(date +%s%N); echo "$(( (e-s)/1000000 ))"; done | tail -10 | sort -n | tr '\n' ' ' > $L/tmp.txt
    echo "$name $bin: $(cat $L/tmp.txt)" | tee -a $L/startup.txt
  done
done
echo "elapsed $(( $(date +%s)-t0 ))s"
for name in render_dsm render_none voxelize; do
  for i in 1 2 3 4 5; do
    s=$(date +%s%N); $W/bin/deepvox-lean ${C[$name]} --stats $L/phases-$name-$i.json > $L/phases-$name-$i.log 2>&1; e=$(date +%s%N)
    echo "$name $i external $(( (e-s)/1000000 ))" >> $L/phases-external.txt
  done
done
cat $L/phases-external.txt
for i in 1 2 3; do $W/bin/deepvox-lean ${C[render_dsm]} --frames 4 --stats $L/frames4-dsm-$i.json > $L/frames4-dsm-$i.log 2>&1; done
for i in 1 2 3; do s=$(date +%s%N); CUDA_MODULE_LOADING=EAGER $W/bin/deepvox-lean ${C[render_dsm]} --stats $L/eager-dsm-$i.json > /dev/null 2>&1; e=$(date +%s%N); echo "eager render_dsm $(( (e-s)/1000000 ))" >> $L/eager.txt; done
for i in 1 2 3; do s=$(date +%s%N); CUDA_MODULE_LOADING=EAGER $W/bin/deepvox-lean ${C[voxelize]} --stats $L/eager-vox-$i.json > /dev/null 2>&1; e=$(date +%s%N); echo "eager voxelize $(( (e-s)/1000000 ))" >> $L/eager.txt; done
cat $L/eager.txt
echo "elapsed $(( $(date +%s)-t0 ))s"
