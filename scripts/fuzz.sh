#!/usr/bin/env bash
# Builds the libFuzzer targets (preset `fuzz`: clang, ASan + UBSan, build-fuzz/) and runs each
# for SECONDS (default 60) on its corpus: new inputs go to out/fuzz/<target>/corpus, the
# committed seeds (tests/fuzz/corpus/<target>/) are read alongside, crashers land in
# out/fuzz/<target>/ as crash-*/leak-*/timeout-* (copy each into tests/fuzz/corpus/<target>/
# after fixing it: test_fuzz_replay replays them in every build). The targets run in parallel,
# each in JOBS processes (libFuzzer's -fork=JOBS when JOBS > 1, corpora merged); the binaries need only glibc (ldd), so a built
# build-fuzz/bin can be copied to a larger machine and run with FUZZ_BIN=that/bin.
# Usage: scripts/fuzz.sh [SECONDS] [TARGET...]   (targets: scene_json gltf mesh suite)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
shift || true
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(scene_json gltf mesh suite)
bin=${FUZZ_BIN:-build-fuzz/bin}
if [ -z "${FUZZ_BIN:-}" ]; then
  cmake --preset fuzz > /dev/null
  cmake --build build-fuzz -j "${DEEPVOX_JOBS:-$(nproc)}" --target "${targets[@]/#/fuzz_}"
fi
jobs=${JOBS:-1}
parallel=()
[ "$jobs" -gt 1 ] && parallel=(-fork="$jobs")
pids=()
for t in "${targets[@]}"; do
  out="out/fuzz/$t"
  mkdir -p "$out/corpus"
  # -rss_limit_mb: a loader asked for a huge allocation by a few bytes is a finding too.
  "$bin/fuzz_$t" "$out/corpus" "tests/fuzz/corpus/$t" -max_total_time="$seconds" \
    -timeout=10 -rss_limit_mb=2048 -artifact_prefix="$out/" "${parallel[@]}" \
    > "$out/fuzz.log" 2>&1 &
  pids+=($!)
done
status=0
for i in "${!targets[@]}"; do
  wait "${pids[$i]}" || status=1
  t=${targets[$i]}
  runs=$(grep -ao '^#[0-9][0-9]*' "out/fuzz/$t/fuzz.log" | tail -n 1 | tr -d '#' || true)
  crashes=$(find "out/fuzz/$t" -maxdepth 1 \( -name 'crash-*' -o -name 'leak-*' -o -name 'timeout-*' \
    -o -name 'oom-*' \) | wc -l)
  echo "fuzz_$t: ${seconds}s x $jobs, ${runs:-0} inputs run, corpus $(ls "out/fuzz/$t/corpus" | wc -l) new, $crashes findings"
done
exit $status
