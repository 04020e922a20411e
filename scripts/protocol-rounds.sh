#!/usr/bin/env bash
# One session of the replicate protocol on a machine whose commands have a time limit (a lent
# GPU machine with 10 minutes a command, a batch slot): rounds FIRST..LAST of SUITE, round k one
# fresh `deepvox suite` process with order seed SEED + k - 1 (the seed `--protocol replicate
# --order-seed SEED` gives its round k) into OUT/<suite>/, logs beside as round<k>.log. A round
# that would end past DEADLINE seconds from the start is not begun (the last round's time is the
# estimate), so that the command ends inside its limit; a later command on the same machine (the
# same lease: one session) goes on with FIRST = the next round. Then, on the host,
# `deepvox report ROUND1 ROUND2...` joins the rounds and builds the report (docs/suites.md).
# Usage: scripts/protocol-rounds.sh DEEPVOX SUITE OUT SEED FIRST LAST DEADLINE [SUITE ARGS...]
#   scripts/protocol-rounds.sh .gpu/deepvox accuracy /tmp/s1 7001 1 5 540 --backend cuda
set -uo pipefail
if [ $# -lt 7 ]; then
  sed -n '2,12p' "$0" >&2
  exit 2
fi
deepvox=$1 suite=$2 out=$3 seed=$4 first=$5 last=$6 deadline=$7
shift 7
mkdir -p "$out"
start=$(date +%s)
last_s=0
status=0
for ((k = first; k <= last; ++k)); do
  now=$(($(date +%s) - start))
  if [ "$k" -gt "$first" ] && [ $((now + last_s * 11 / 10)) -gt "$deadline" ]; then
    echo "protocol-rounds: stop before round $k at ${now} s (the last round took ${last_s} s)"
    exit "$status"
  fi
  began=$(date +%s)
  "$deepvox" suite "$suite" --no-report --order-seed $((seed + k - 1)) --out "$out" "$@" \
    > "$out/round$k.log" 2>&1
  rc=$?
  last_s=$(($(date +%s) - began))
  echo "protocol-rounds: round $k (order seed $((seed + k - 1))) exit $rc in ${last_s} s"
  [ "$rc" -eq 0 ] || status=$rc
done
exit "$status"
