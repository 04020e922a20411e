#!/usr/bin/env bash
# Device call 1: baseline (bfa885f) vs dsm_figures change vs register-bounded fragment/count
# kernels (DEEPVOX_EXP_MIN_BLOCKS 1/2/3), interleaved rounds; plus the CUDA tests of the main build.
set -uo pipefail
W=$(mktemp -d); mkdir -p $W/stats $W/logs
cd .gpu && for f in *.xz; do xz -dk "$f"; done; chmod +x base-* exp-* 2>/dev/null; cd ..
nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.sm,clocks.mem --format=csv | tee $W/gpu.txt
export LD_LIBRARY_PATH=$PWD/.gpu/lib:${LD_LIBRARY_PATH:-}
export DEEPVOX_SOURCE_DIR=$PWD DEEPVOX_ASSETS=$PWD/experiments/assets
S=experiments/scenes
run() { # tag bin env args...
  local tag=$1 bin=$2 envv=$3; shift 3
  env $envv timeout 120 .gpu/$bin render "$@" --backend cuda --frames ${FR:-4} --out $W/img.png --stats $W/stats/$tag.json > $W/logs/$tag.log 2>&1 || echo "FAIL $tag"
}
configs=(
 "f56-720-none|$S/knecht-fig56.json --shadows none"
 "f56-720-dsm|$S/knecht-fig56.json --shadows dsm"
 "f56-1080-dsm|$S/knecht-fig56.json --shadows dsm --width 1920 --height 1080"
 "f56-4k-none|$S/knecht-fig56.json --shadows none --width 3840 --height 2160"
 "f56-4k-sm|$S/knecht-fig56.json --shadows shadowmap --width 3840 --height 2160"
 "f56-4k-dsm|$S/knecht-fig56.json --shadows dsm --width 3840 --height 2160"
 "f56-720-ref|$S/knecht-fig56.json --shadows reference"
 "k32-720-dsm512|$S/knecht-32-lights.json --shadows dsm --dsm-res 512"
 "k32-4k-dsm512|$S/knecht-32-lights.json --shadows dsm --dsm-res 512 --width 3840 --height 2160"
 "k32-4k-sm|$S/knecht-32-lights.json --shadows shadowmap --width 3840 --height 2160"
)
variants=("base|base-lean|X=0" "new|exp-lean|DEEPVOX_EXP_MIN_BLOCKS=1" "b2|exp-lean|DEEPVOX_EXP_MIN_BLOCKS=2")
for r in 1 2; do
  for c in "${configs[@]}"; do
    name=${c%%|*}; args=${c#*|}
    if [ $((r % 2)) -eq 1 ]; then order=(0 1 2); else order=(2 1 0); fi
    for k in "${order[@]}"; do
      v=${variants[$k]}; vt=${v%%|*}; rest=${v#*|}; vb=${rest%%|*}; ve=${rest#*|}
      run "$name-$vt-r$r" $vb "$ve" $args
    done
  done
  echo "round $r done $(date +%T)"
done
tar -czf $OUT/call1-timing.tar.gz -C $W .
# the oracle for 32 lights once per variant
for v in "${variants[@]}"; do vt=${v%%|*}; rest=${v#*|}; vb=${rest%%|*}; ve=${rest#*|}
  FR=2 run "k32-720-ref-$vt" $vb "$ve" $S/knecht-32-lights.json --shadows reference; done
tar -czf $OUT/call1-timing.tar.gz -C $W .
echo timing-done
echo all-done $(date +%T)
