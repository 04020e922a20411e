#!/usr/bin/env bash
# Checks the include layers and that no code comment names an issue number, builds everything
# (tests included) and runs the test suite with CTest. GPU tests skip with their reason on
# machines without a GPU.
set -euo pipefail
cd "$(dirname "$0")/.."
python3 scripts/check_layers.py
python3 scripts/check_comments.py
bash scripts/build.sh
ctest --test-dir build --output-on-failure -j "${DEEPVOX_JOBS:-$(nproc)}" "$@"
