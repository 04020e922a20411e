#!/usr/bin/env bash
# Builds the `asan` preset (build-asan/: Debug -O1, CPU only, AddressSanitizer + UBSan, every
# report fatal) and runs CPU tests under it. SANITIZE_LABELS is a ctest label regex: by default
# the loader suites (test_io: OBJ/OFF/PLY/STL and raw volumes, test_scene: mesh topology and ray
# queries, test_load: glTF/glb and the generators), which need the libraries up to deepvox_load
# (no tests of the rest);
# SANITIZE_LABELS=hard adds the hard cases of every area (the bad-input corpus through the
# CLI, the fuzz regression inputs; builds the whole library), "." runs everything. Extra
# arguments go to ctest. .ci/run calls it after scripts/test.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
labels=${SANITIZE_LABELS:-test_io|test_scene|test_load}
jobs=${DEEPVOX_JOBS:-$(nproc)}
cmake --preset asan > /dev/null
if [ "$labels" = "test_io|test_scene|test_load" ]; then
  cmake --build build-asan -j "$jobs" --target test_io test_scene test_load
else
  cmake --build build-asan -j "$jobs"
fi
# Leaks are reported too; UBSan prints the stack and stops at the first report. An allocation
# too large to satisfy returns null from malloc; operator new still aborts under GCC 12's ASan
# (CI of 2026-12-04: OpenVDB reading past the end of a truncated .vdb), so readers refuse such
# input before a library sizes anything from it (render/io/vdb_openvdb.cpp: GridExtentProbe).
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1:allocator_may_return_null=1}
# Leaks inside third-party libraries that deepvox cannot free (each one says why).
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$PWD/scripts/lsan-suppressions.txt:print_suppressions=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
ctest --test-dir build-asan --output-on-failure -j "$jobs" -L "$labels" "$@"
