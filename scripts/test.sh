#!/usr/bin/env bash
# Builds everything (tests included) and runs the test suite with CTest. GPU tests skip with
# their reason on machines without a GPU.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
ctest --test-dir build --output-on-failure -j "${DEEPVOX_JOBS:-$(nproc)}" "$@"
