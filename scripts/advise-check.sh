#!/usr/bin/env bash
# The check of `deepvox advise` and `auto --error-budget`, in one call: every scene's
# exhaustive sweep, then per error bound advise (timed, pick verified at fresh points) and auto's
# choice, with a pass/fail summary (scripts/advise_check.py says what is checked).
#   scripts/advise-check.sh [--backend cuda] [--out out/advise-check]   # H200
#   scripts/advise-check.sh --backend cpu --width 48 --probes 200 --repeat 1 --max-res 256 \
#     --scenes experiments/scenes/heldout/glass-stack.json --bounds 0.05   # 2 CPU cores
set -euo pipefail
cd "$(dirname "$0")/.."
deepvox=build/bin/deepvox
[ -x "$deepvox" ] || deepvox=build-cpu/bin/deepvox
exec python3 scripts/advise_check.py --deepvox "$deepvox" "$@"
