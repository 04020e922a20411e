#!/usr/bin/env bash
# Configures (once) and builds deepvox with the default preset into build/ (CUDA when nvcc is
# found). Extra arguments go to `cmake --build`, e.g. `--target deepvox`. A build folder whose
# configure did not finish (a CMakeCache.txt but no generated build system) is configured again.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
jobs=${DEEPVOX_JOBS:-$(nproc)}
if [ ! -f build/Makefile ] && [ ! -f build/build.ninja ]; then
  cmake --preset default
fi
cmake --build build -j "$jobs" "$@"
