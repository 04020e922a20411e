#!/usr/bin/env bash
# Builds the `asan` preset (build-asan/: Debug -O1, CPU only, AddressSanitizer + UBSan, every
# report fatal) and runs CPU tests under it: by default the hard cases (`-L hard`, which hold
# the loaders' bad-input tests, the malformed-file corpus and the fuzz regression inputs) and
# the loader and core suites (SANITIZE_LABELS, a ctest label regex; "." runs everything).
# Extra arguments go to ctest. .ci/run calls it after scripts/test.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
labels=${SANITIZE_LABELS:-hard|test_meshes|test_gltf|test_volumes|test_core|test_fuzz_replay}
jobs=${DEEPVOX_JOBS:-$(nproc)}
cmake --preset asan > /dev/null
if [ "$labels" = "." ]; then
  cmake --build build-asan -j "$jobs"
else
  # Only the executables whose tests carry a selected label (plus deepvox for the CLI tests).
  cmake --build build-asan -j "$jobs" --target deepvox test_hard test_cli test_meshes test_gltf \
    test_volumes test_core test_fuzz_replay test_dsm test_raster test_oracle test_render test_voxel
fi
# Leaks are reported too; UBSan prints the stack and stops at the first report.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
ctest --test-dir build-asan --output-on-failure -j "$jobs" -L "$labels" "$@"
