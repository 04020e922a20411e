#!/usr/bin/env bash
# The check of `deepvox advise` and `auto --error-budget` (issue 41), in one call: every scene's
# exhaustive sweep, then per error bound advise (timed, pick verified at fresh points) and auto's
# choice, with a pass/fail summary (scripts/advise_check.py says what is checked).
#   scripts/advise-check.sh [--backend cuda] [--out out/advise-check]   # H200
#   scripts/advise-check.sh --backend cpu --width 96 --probes 400 --max-res 512   # 2 CPU cores
set -euo pipefail
cd "$(dirname "$0")/.."
deepvox=build/bin/deepvox
[ -x "$deepvox" ] || deepvox=build-cpu/bin/deepvox
exec python3 scripts/advise_check.py --deepvox "$deepvox" "$@"
