#!/usr/bin/env bash
# The main job: builds deepvox if needed and runs the `quick` experiment suite on the default
# backend (CUDA when a GPU is present, else CPU): every shadow method and DSM storage on a
# Knecht-like scene against the exact oracle, a voxelizer table against exact, an image strip.
# Prints where the report is (out/suites/quick/<date>_<gitsha>/report.md). Extra arguments go
# to `deepvox suite`, e.g. --backend cpu or --repeat 1.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh --target deepvox
./build/bin/deepvox suite quick --out out/suites "$@"
