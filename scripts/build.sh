#!/usr/bin/env bash
# Configures (once) and builds deepvox with the default preset into build/ (CUDA when nvcc is
# found). Extra arguments go to `cmake --build`, e.g. `--target deepvox`.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
jobs=${DEEPVOX_JOBS:-$(nproc)}
if [ ! -f build/CMakeCache.txt ]; then
  cmake --preset default
fi
cmake --build build -j "$jobs" "$@"
