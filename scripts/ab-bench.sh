#!/usr/bin/env bash
# A/B benchmark of two builds: interleaved rounds of their Google Benchmark binaries with the
# machine's metadata, so that a change is measured against its base on one GPU in one call (the
# one script behind results/perf/, in place of the per-round run-*.sh copies). With --guard, the
# regression guard: one build's headline benchmarks against their last accepted medians.
#
# Usage: scripts/ab-bench.sh OLD_DIR NEW_DIR FILTER ROUNDS [OUT]
#        scripts/ab-bench.sh --guard [--update] [--baseline FILE] NEW_DIR [ROUNDS [OUT]]
#   OLD_DIR, NEW_DIR  folders holding each build's bench_* binaries (e.g. build/bin of two trees);
#                     a file `commit` (or `COMMIT`, `commit.txt`) in a folder names its git commit
#   FILTER            passed to --benchmark_filter (a regular expression; '.' for all)
#   ROUNDS            rounds (a positive integer); round r runs old then new when r is odd,
#                     new then old when r is even, so drift between the two sides cancels out
#                     (--guard: NEW_DIR alone each round; default 3)
#   OUT               output folder (default ab-<UTC date>_<time>); it must be empty or new
#   --guard           runs the binaries the baseline lists with its arguments and a filter
#                     naming exactly its benchmarks, then prints per benchmark baseline / now /
#                     now/baseline (scripts/perf_guard.py check): exit 1 when one is more than
#                     the baseline's threshold (5 %) slower or was not run, 0 otherwise
#   --baseline FILE   the accepted medians (default results/perf/baseline.json of this checkout)
#   --update          with --guard: after the comparison, rewrite FILE from this run (its GPU,
#                     NEW_DIR's commit file, the date, this command); a run on the baseline's GPU
#                     kind only, every listed benchmark measured
# Environment:
#   AB_BENCH_ARGS       extra arguments for every binary, e.g. '--benchmark_repetitions=3'
#   DEEPVOX_SOURCE_DIR  where the benchmarks find experiments/scenes/ and experiments/assets/
#                       (default: this folder)
# Writes OUT/meta.txt (date, host, GPU, driver, clocks, commits, binaries' sha256), for every
# round, side and binary OUT/<side>-<bench>-r<r>.json (--benchmark_out) and .log (its console
# output), and OUT/summary.txt: per benchmark and side the median and min-max over the rounds
# of each round's value (its `median` aggregate where repetitions made one, else the median of
# its iterations' real_time), in the JSON's time unit (scripts/bench_summary.py); with --guard
# OUT/guard.txt, the comparison, instead.
# Exit status: 0 done (--guard: no benchmark slower); 1 --guard found one slower or not run;
# 2 usage error, a missing folder or binary, a bad baseline, or a --guard run that cannot be
# compared (on another GPU kind than the baseline's, no value of any listed benchmark).
set -euo pipefail

here=$(cd "$(dirname "$0")" && pwd)
usage() {
  sed -n '/^# Usage/,/^# Environment/p' "$0" | sed '$d' | sed 's/^# \{0,1\}//' >&2
  exit 2
}
die() {
  echo "ab-bench: $*" >&2
  exit 2
}

command_line="$0 $*"
guard=0
update=0
baseline="$(cd "$here/.." && pwd)/results/perf/baseline.json"
while [ $# -gt 0 ]; do
  case $1 in
    --guard) guard=1; shift ;;
    --update) update=1; shift ;;
    --baseline) [ $# -ge 2 ] || usage; baseline=$2; shift 2 ;;
    -h | --help) usage ;;
    --*) echo "ab-bench: unknown option '$1'" >&2; usage ;;
    *) break ;;
  esac
done
if [ "$guard" = 1 ]; then
  if [ $# -lt 1 ] || [ $# -gt 3 ]; then usage; fi
  old_dir=
  new_dir=$1
  filter="(the baseline's benchmarks)"
  rounds=${2:-3}
  out=${3:-ab-$(date -u +%Y-%m-%d_%H%M%S)}
  sides=(new)
else
  if [ $# -lt 4 ] || [ $# -gt 5 ] || [ "$update" = 1 ]; then usage; fi
  old_dir=$1
  new_dir=$2
  filter=$3
  rounds=$4
  out=${5:-ab-$(date -u +%Y-%m-%d_%H%M%S)}
  sides=(old new)
fi

for d in ${old_dir:+"$old_dir"} "$new_dir"; do
  [ -d "$d" ] || die "no folder $d"
done
[[ $rounds =~ ^[1-9][0-9]*$ ]] || die "ROUNDS must be a positive integer"
command -v python3 > /dev/null || die "python3 is needed for the summary"
if [ -e "$out" ] && [ -n "$(ls -A "$out")" ]; then
  die "$out exists and is not empty"
fi

# The benchmark binaries to run and, tab-separated, each one's arguments: with --guard those the
# baseline lists; else those present (and executable) in both builds, with FILTER.
benches=()
declare -A bench_args=()
if [ "$guard" = 1 ]; then
  [ -f "$baseline" ] || die "no baseline file $baseline"
  plan=$(python3 "$here/perf_guard.py" plan "$baseline") || exit 2
  while IFS=$'\t' read -r b args; do
    if [ ! -f "$new_dir/$b" ] || [ ! -x "$new_dir/$b" ]; then
      die "$baseline lists $b, which $new_dir does not hold (or is not executable)"
    fi
    benches+=("$b")
    bench_args[$b]=$args
  done <<< "$plan"
else
  for f in "$old_dir"/bench_*; do
    if [ ! -f "$f" ] || [ ! -x "$f" ]; then continue; fi
    b=$(basename "$f")
    if [ -f "$new_dir/$b" ] && [ -x "$new_dir/$b" ]; then
      benches+=("$b")
      bench_args[$b]="--benchmark_filter=$filter"
    fi
  done
  [ ${#benches[@]} -gt 0 ] || die "no bench_* binary in both folders"
fi
mkdir -p "$out"

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
dir_of() {  # side
  if [ "$1" = old ]; then echo "$old_dir"; else echo "$new_dir"; fi
}

{
  echo "date_utc: $(date -u +%Y-%m-%dT%H:%M:%SZ)"
  echo "host: $(hostname)"
  echo "kernel: $(uname -sr)"
  echo "cpus: $(nproc 2> /dev/null || echo '?')"
  if command -v nvidia-smi > /dev/null; then
    nvidia-smi --format=csv \
      --query-gpu=index,name,driver_version,clocks.sm,clocks.max.sm,clocks.mem,clocks.max.mem \
      2>&1 | sed 's/^/gpu: /'
  else
    echo "gpu: (no nvidia-smi)"
  fi
  echo "command: $command_line"
  if [ "$guard" = 1 ]; then
    echo "guard: against $baseline$([ "$update" = 1 ] && echo ', then updating it')"
  fi
  echo "filter: $filter"
  echo "rounds: $rounds (odd rounds old first, even rounds new first)"
  echo "extra_args: ${AB_BENCH_ARGS:-}"
  echo "DEEPVOX_SOURCE_DIR: $DEEPVOX_SOURCE_DIR"
  for side in "${sides[@]}"; do
    echo "$side: $(dir_of "$side") commit $(commit_of "$(dir_of "$side")")"
  done
  for b in "${benches[@]}"; do
    echo "args $b: ${bench_args[$b]//$'\t'/ }"
    for side in "${sides[@]}"; do
      echo "sha256 $side/$b: $(sha256sum < "$(dir_of "$side")/$b" | cut -d' ' -f1)"
    done
  done
} | tee "$out/meta.txt"

run_side() {  # run_side SIDE ROUND
  local side=$1 r=$2 dir b args
  dir=$(dir_of "$side")
  for b in "${benches[@]}"; do
    IFS=$'\t' read -r -a args <<< "${bench_args[$b]}"
    echo "round $r: $side $b" >&2
    "$dir/$b" "${args[@]}" --benchmark_format=json \
      --benchmark_out="$out/$side-$b-r$r.json" --benchmark_out_format=json \
      ${extra[@]+"${extra[@]}"} > "$out/$side-$b-r$r.log" 2>&1 ||
      echo "ab-bench: $side $b round $r exited with $? (see $out/$side-$b-r$r.log)" >&2
  done
}

for ((r = 1; r <= rounds; r++)); do
  if [ "$guard" = 1 ]; then
    run_side new "$r"
  elif ((r % 2 == 1)); then
    run_side old "$r"
    run_side new "$r"
  else
    run_side new "$r"
    run_side old "$r"
  fi
done

if [ "$guard" = 0 ]; then
  python3 "$here/bench_summary.py" "$out" | tee "$out/summary.txt"
  exit 0
fi
status=0
python3 "$here/perf_guard.py" check "$baseline" "$out" > "$out/guard.txt" || status=$?
cat "$out/guard.txt"
if [ "$update" = 1 ] && [ "$status" != 2 ]; then
  how="per binary the baseline's args and a filter naming its benchmarks, $rounds rounds"
  if [ -n "${AB_BENCH_ARGS:-}" ]; then how="$how, AB_BENCH_ARGS=$AB_BENCH_ARGS"; fi
  python3 "$here/perf_guard.py" update "$baseline" "$out" --commit "$(commit_of "$new_dir")" \
    --command "$command_line ($how)"
  exit $?
fi
exit "$status"
