#!/usr/bin/env bash
# Renders every committed scene with two deepvox binaries, on each backend and with each shadow
# method, and compares the PNGs byte for byte: the check that a change meant to keep behaviour
# (a refactor, a move of folders) kept every image. Run from the repository root.
# Usage: scripts/render-identity.sh BEFORE_BIN AFTER_BIN [OUT]
#   BACKENDS  backends to render on (default "cpu cuda")
#   SHADOWS   shadow methods (default "auto none shadowmap dsm transmittance-slicemap reference")
#   CPU_SIZE  --width/--height of the CPU renders, e.g. 320x240 (default: the scenes' own)
#   SCENES    scene files (default experiments/scenes/*.json)
#   LIMIT     seconds per render (default 120)
# Writes OUT/identity.csv (scene, backend, shadows, result, md5 before, md5 after) and prints the
# counts; exit 1 when any pair differs or only one binary rendered it.
set -uo pipefail
before=${1:?BEFORE_BIN}
after=${2:?AFTER_BIN}
out=${3:-out/render-identity}
mkdir -p "$out/before" "$out/after"
export DEEPVOX_ASSETS=${DEEPVOX_ASSETS:-$PWD/experiments/assets}
backends=${BACKENDS:-cpu cuda}
shadows=${SHADOWS:-auto none shadowmap dsm transmittance-slicemap reference}
limit=${LIMIT:-120}
csv="$out/identity.csv"
echo "scene,backend,shadows,result,md5_before,md5_after" > "$csv"
same=0 differ=0 failed=0
for scene in ${SCENES:-experiments/scenes/*.json}; do
  name=$(basename "$scene" .json)
  for backend in $backends; do
    size=()
    if [ "$backend" = cpu ] && [ -n "${CPU_SIZE:-}" ]; then
      size=(--width "${CPU_SIZE%x*}" --height "${CPU_SIZE#*x}")
    fi
    for method in $shadows; do
      md5=()
      for side in before after; do
        bin=$before
        [ "$side" = after ] && bin=$after
        png="$out/$side/$name-$backend-$method.png"
        rm -f "$png"
        timeout "$limit" "$bin" render "$scene" --backend "$backend" --shadows "$method" \
          "${size[@]}" --out "$png" > "$out/$side/$name-$backend-$method.log" 2>&1
        if [ -s "$png" ]; then
          md5+=("$(md5sum < "$png" | cut -d' ' -f1)")
        else
          md5+=("-")
        fi
      done
      if [ "${md5[0]}" = - ] && [ "${md5[1]}" = - ]; then
        result="neither rendered"
      elif [ "${md5[0]}" = - ] || [ "${md5[1]}" = - ]; then
        result="one rendered"
        failed=$((failed + 1))
      elif [ "${md5[0]}" = "${md5[1]}" ]; then
        result=identical
        same=$((same + 1))
      else
        result=DIFFERENT
        differ=$((differ + 1))
      fi
      echo "$name,$backend,$method,$result,${md5[0]},${md5[1]}" >> "$csv"
    done
  done
done
grep -c "neither rendered" "$csv" | xargs echo "neither rendered (both binaries failed or timed out):"
echo "identical: $same, different: $differ, rendered by one binary only: $failed"
[ "$differ" -eq 0 ] && [ "$failed" -eq 0 ]
