#!/usr/bin/env bash
# A/B benchmark of two builds: interleaved rounds of their Google Benchmark binaries with the
# machine's metadata, so that a change is measured against its base on one GPU in one call (the
# one script behind results/perf/, in place of the per-round run-*.sh copies).
#
# Usage: scripts/ab-bench.sh OLD_DIR NEW_DIR FILTER ROUNDS [OUT]
#   OLD_DIR, NEW_DIR  folders holding each build's bench_* binaries (e.g. build/bin of two trees);
#                     a file `commit` (or `COMMIT`, `commit.txt`) in a folder names its git commit
#   FILTER            passed to --benchmark_filter (a regular expression; '.' for all)
#   ROUNDS            rounds (a positive integer); round r runs old then new when r is odd,
#                     new then old when r is even, so drift between the two sides cancels out
#   OUT               output folder (default ab-<UTC date>_<time>); it must be empty or new
# Environment:
#   AB_BENCH_ARGS       extra arguments for every binary, e.g. '--benchmark_repetitions=3'
#   DEEPVOX_SOURCE_DIR  where the benchmarks find experiments/scenes/ and experiments/assets/
#                       (default: this folder)
# Writes OUT/meta.txt (date, host, GPU, driver, clocks, commits, binaries' sha256), for every
# round, side and binary OUT/<side>-<bench>-r<r>.json (--benchmark_out) and .log (its console
# output), and OUT/summary.txt: per benchmark and side the median and min-max over the rounds
# of each round's value (its `median` aggregate where repetitions made one, else the median of
# its iterations' real_time), in the JSON's time unit.
set -euo pipefail

usage() {
  sed -n '6,21p' "$0" | sed 's/^# \{0,1\}//' >&2
  exit 2
}

if [ $# -lt 4 ] || [ $# -gt 5 ]; then usage; fi
old_dir=$1
new_dir=$2
filter=$3
rounds=$4
out=${5:-ab-$(date -u +%Y-%m-%d_%H%M%S)}

for d in "$old_dir" "$new_dir"; do
  [ -d "$d" ] || { echo "ab-bench: no folder $d" >&2; exit 2; }
done
if ! [[ $rounds =~ ^[1-9][0-9]*$ ]]; then
  echo "ab-bench: ROUNDS must be a positive integer" >&2
  exit 2
fi
if [ -e "$out" ] && [ -n "$(ls -A "$out")" ]; then
  echo "ab-bench: $out exists and is not empty" >&2
  exit 2
fi
mkdir -p "$out"
if ! command -v python3 >/dev/null; then
  echo "ab-bench: python3 is needed for the summary" >&2
  exit 2
fi

# The benchmark binaries present (and executable) in both builds.
benches=()
for f in "$old_dir"/bench_*; do
  if [ ! -f "$f" ] || [ ! -x "$f" ]; then continue; fi
  b=$(basename "$f")
  [ -f "$new_dir/$b" ] && [ -x "$new_dir/$b" ] && benches+=("$b")
done
[ ${#benches[@]} -gt 0 ] || { echo "ab-bench: no bench_* binary in both folders" >&2; exit 2; }

extra=()
if [ -n "${AB_BENCH_ARGS:-}" ]; then
  read -r -a extra <<< "$AB_BENCH_ARGS"
fi
export DEEPVOX_SOURCE_DIR=${DEEPVOX_SOURCE_DIR:-$PWD}

commit_of() {
  local f
  for f in commit COMMIT commit.txt; do
    if [ -f "$1/$f" ]; then head -n 1 "$1/$f"; return; fi
  done
  echo "(no commit file)"
}

{
  echo "date_utc: $(date -u +%Y-%m-%dT%H:%M:%SZ)"
  echo "host: $(hostname)"
  echo "kernel: $(uname -sr)"
  echo "cpus: $(nproc 2>/dev/null || echo '?')"
  if command -v nvidia-smi >/dev/null; then
    nvidia-smi --format=csv \
      --query-gpu=index,name,driver_version,clocks.sm,clocks.max.sm,clocks.mem,clocks.max.mem \
      2>&1 | sed 's/^/gpu: /'
  else
    echo "gpu: (no nvidia-smi)"
  fi
  echo "command: $0 $*"
  echo "filter: $filter"
  echo "rounds: $rounds (odd rounds old first, even rounds new first)"
  echo "extra_args: ${AB_BENCH_ARGS:-}"
  echo "DEEPVOX_SOURCE_DIR: $DEEPVOX_SOURCE_DIR"
  echo "old: $old_dir commit $(commit_of "$old_dir")"
  echo "new: $new_dir commit $(commit_of "$new_dir")"
  for b in "${benches[@]}"; do
    echo "sha256 old/$b: $(sha256sum < "$old_dir/$b" | cut -d' ' -f1)"
    echo "sha256 new/$b: $(sha256sum < "$new_dir/$b" | cut -d' ' -f1)"
  done
} | tee "$out/meta.txt"

run_side() {  # run_side SIDE DIR ROUND
  local side=$1 dir=$2 r=$3 b
  for b in "${benches[@]}"; do
    echo "round $r: $side $b" >&2
    "$dir/$b" --benchmark_filter="$filter" --benchmark_format=json \
      --benchmark_out="$out/$side-$b-r$r.json" --benchmark_out_format=json \
      ${extra[@]+"${extra[@]}"} > "$out/$side-$b-r$r.log" 2>&1 ||
      echo "ab-bench: $side $b round $r exited with $? (see $out/$side-$b-r$r.log)" >&2
  done
}

for ((r = 1; r <= rounds; r++)); do
  if ((r % 2 == 1)); then
    run_side old "$old_dir" "$r"
    run_side new "$new_dir" "$r"
  else
    run_side new "$new_dir" "$r"
    run_side old "$old_dir" "$r"
  fi
done

python3 - "$out" <<'PY' | tee "$out/summary.txt"
import glob, json, os, re, statistics, sys

out = sys.argv[1]
values = {}  # (bench binary, benchmark name) -> side -> [value per round]
units = {}
for path in sorted(glob.glob(os.path.join(out, '*-r*.json'))):
    m = re.match(r'(old|new)-(.+)-r(\d+)\.json$', os.path.basename(path))
    if not m:
        continue
    side, binary = m.group(1), m.group(2)
    try:
        with open(path) as f:
            data = json.load(f)
    except (OSError, ValueError) as e:
        print(f'# {path}: unreadable ({e})')
        continue
    medians, iterations = {}, {}
    for row in data.get('benchmarks', []):
        name = row.get('run_name', row.get('name'))
        units[(binary, name)] = row.get('time_unit', 'ns')
        if row.get('run_type') == 'aggregate':
            if row.get('aggregate_name') == 'median':
                medians[name] = row['real_time']
        elif 'real_time' in row and not row.get('error_occurred'):
            iterations.setdefault(name, []).append(row['real_time'])
    for name in set(medians) | set(iterations):
        v = medians.get(name)
        if v is None:
            v = statistics.median(iterations[name])
        values.setdefault((binary, name), {}).setdefault(side, []).append(v)

def cell(vs):
    if not vs:
        return '-'
    return f'{statistics.median(vs):.4g} ({min(vs):.4g}-{max(vs):.4g}, n={len(vs)})'

print('| binary | benchmark | unit | old: median (min-max over rounds) | new | new/old |')
print('| --- | --- | --- | --- | --- | --- |')
for key in sorted(values):
    sides = values[key]
    old, new = sides.get('old', []), sides.get('new', [])
    ratio = '-'
    if old and new and statistics.median(old):
        ratio = f'{statistics.median(new) / statistics.median(old):.3f}'
    print(f'| {key[0]} | {key[1]} | {units[key]} | {cell(old)} | {cell(new)} | {ratio} |')
PY
