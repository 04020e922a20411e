#!/usr/bin/env bash
# Soak: does a long process keep its memory flat? Runs `deepvox render --frames N` (the camera
# orbits the DSM-shadowed scene) and then one `deepvox suite` process of about 100
# experiments, and samples the process's host RSS (/proc/PID/status VmRSS) and, on CUDA, its
# device memory (nvidia-smi's used_memory for the pid) every EVERY frames and every
# SUITE_EVERY experiments. Writes OUT/soak.csv (kind, step, elapsed_s, rss_kib, device_mib),
# OUT/summary.md (flat within 1 % after the warm-up, or not, per kind and quantity) and
# OUT/soak.svg (the curves), through scripts/soak_summary.py. Exit 1 when a curve is not flat.
# Usage: scripts/soak.sh OUT [--backend cpu|cuda] [--frames N] [--size WxH] [--every N]
#        [--items N] [--scene FILE] [--shadows NAME] [--bin DEEPVOX]
# Frames go to a scratch folder that is emptied as the run goes (only the last PNG is kept).
set -euo pipefail
out=${1:?usage: scripts/soak.sh OUT [--backend cpu|cuda] [--frames N] ...}
shift
backend=cpu frames=1000 size=96x64 every=100 items=100 suite_every=10
scene=experiments/scenes/demo.json shadows=dsm bin=build/bin/deepvox
while [ $# -gt 0 ]; do
  case "$1" in
    --backend) backend=$2 ;;
    --frames) frames=$2 ;;
    --size) size=$2 ;;
    --every) every=$2 ;;
    --items) items=$2 ;;
    --scene) scene=$2 ;;
    --shadows) shadows=$2 ;;
    --bin) bin=$2 ;;
    *) echo "soak.sh: unknown option $1" >&2; exit 2 ;;
  esac
  shift 2
done
width=${size%x*} height=${size#*x}
mkdir -p "$out"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
csv="$out/soak.csv"
echo "kind,step,elapsed_s,rss_kib,device_mib" > "$csv"

# One sample of process $1 at step $3 of kind $2, $4 seconds after its start.
sample() {
  local rss device=""
  rss=$(awk '/^VmRSS:/ {print $2}' "/proc/$1/status" 2> /dev/null) || return 0
  [ -n "$rss" ] || return 0
  if [ "$backend" = cuda ]; then
    device=$(nvidia-smi --query-compute-apps=pid,used_memory --format=csv,noheader,nounits \
      2> /dev/null | awk -F', *' -v pid="$1" '$1 == pid {print $2}')
  fi
  echo "$2,$3,$4,$rss,$device" >> "$csv"
}

# Watches process $1 until it ends: `$2` prints its progress (a count), sampled each time it
# reaches the next multiple of $3; $4 names the kind.
watch() {
  local pid=$1 progress=$2 step=$3 kind=$4 next=1 now start
  start=$(date +%s.%N)
  while kill -0 "$pid" 2> /dev/null; do
    now=$($progress)
    if [ -n "$now" ] && [ "$now" -ge "$next" ]; then
      sample "$pid" "$kind" "$now" "$(awk -v a="$(date +%s.%N)" -v b="$start" 'BEGIN {printf "%.2f", a - b}')"
      next=$(( (now / step + 1) * step ))
      find "$work/frames" -name 'frame_*.png' ! -newer "$work/frames/.mark" -delete 2> /dev/null || true
      touch "$work/frames/.mark"
    fi
    sleep 0.02
  done
}

# Frames rendered so far: the last "render: frame K" line is frame K + 1.
frames_done() { tail -c 4096 "$work/render.log" | grep -o 'render: frame [0-9]*' | tail -n 1 | awk '{print $3 + 1}' || true; }
mkdir -p "$work/frames" && touch "$work/frames/.mark"
"$bin" render "$scene" --backend "$backend" --shadows "$shadows" --frames "$frames" --orbit 360 \
  --width "$width" --height "$height" --out "$work/frames/frame.png" 2> "$work/render.log" &
render_pid=$!
watch "$render_pid" frames_done "$every" render
wait "$render_pid" || { echo "soak.sh: render failed:"; tail -n 5 "$work/render.log"; exit 1; }

# A suite of `items` DSM experiments (an eps sweep at one small size) in one process.
eps=$(python3 -c "print(', '.join(str(round(0.001 + 0.3 * k / $items, 5)) for k in range($items)))")
cat > "$work/soak-suite.json" << EOF
{"suite": "soak", "repeat": 1, "experiments": [
  {"name": "soak", "kind": "shadow", "scene": "$(realpath "$scene")", "strategy": "dsm",
   "params": {"res": 64}, "sweep": {"eps": [$eps]},
   "settings": {"width": $width, "height": $height, "probe_points": 50, "seed": 1, "images": 0}}]}
EOF
items_done() { cat "$work"/suites/soak/*/progress.jsonl 2> /dev/null | wc -l || true; }
"$bin" suite "$work/soak-suite.json" --backend "$backend" --costs estimate --no-report \
  --out "$work/suites" > "$work/suite.log" 2>&1 &
suite_pid=$!
watch "$suite_pid" items_done "$suite_every" suite
wait "$suite_pid" || { echo "soak.sh: suite failed:"; tail -n 5 "$work/suite.log"; exit 1; }

python3 "$(dirname "$0")/soak_summary.py" "$csv" "$out" \
  --title "deepvox soak: $backend, $frames frames at ${size}, $items suite experiments"
