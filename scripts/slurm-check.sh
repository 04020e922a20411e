#!/usr/bin/env bash
# The SLURM scale-out for real on this machine: installs Debian's slurm-wlm and munge when
# missing, starts a one-node cluster on localhost (munged, slurmctld, slurmd as root; 2 CPUs,
# CPU backend, no cgroups), submits `deepvox suite quick --slurm --gpus 2 --backend cpu
# --submit` (a 2-task job array plus the merge job, afterany), waits with a bounded timeout,
# and checks that the merged rows equal an unsharded run's rows (timings aside) and that the
# report names the 2 workers. Then the requeue check: a second submission whose task
# 1 has its deepvox killed with SIGKILL (found through `scontrol listpids`) once the shard's
# first experiment is complete; the task must requeue itself and resume the same folder, and the
# merge must again equal the unsharded run. Stops the daemons at the end (trap). Needs root.
# Usage: scripts/slurm-check.sh [--install-only]; DEEPVOX=path/to/deepvox (default: build/bin,
# else build-cpu/bin), SUITE=quick, SLURM_CHECK_TIMEOUT=900 seconds.
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$PWD

if ! command -v slurmctld > /dev/null || ! command -v munged > /dev/null; then
  echo "slurm-check: installing slurm-wlm and munge"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -q
  apt-get install -y -q --no-install-recommends slurm-wlm munge
fi
[ "${1:-}" = "--install-only" ] && exit 0

deepvox=${DEEPVOX:-}
for candidate in build/bin/deepvox build-cpu/bin/deepvox; do
  [ -z "$deepvox" ] && [ -x "$candidate" ] && deepvox=$repo/$candidate
done
[ -x "$deepvox" ] || { echo "slurm-check: no deepvox binary (build first or set DEEPVOX)"; exit 2; }
suite=${SUITE:-quick}
timeout_s=${SLURM_CHECK_TIMEOUT:-900}
work=$(mktemp -d /tmp/deepvox-slurm.XXXXXX)
host=$(hostname -s)
pids=()
stop() {
  for pid_file in "$work"/slurmd.pid "$work"/slurmctld.pid "$work"/munged.pid; do
    [ -s "$pid_file" ] && kill "$(cat "$pid_file")" 2> /dev/null || true
  done
  for pid in "${pids[@]}"; do kill "$pid" 2> /dev/null || true; done
}
trap stop EXIT

mkdir -p "$work"/{state,spool,munge,out}
dd if=/dev/urandom of="$work/munge/munge.key" bs=1024 count=1 status=none
chmod 700 "$work/munge" && chmod 400 "$work/munge/munge.key"
munged --force --key-file="$work/munge/munge.key" --socket="$work/munge/munge.socket" \
  --pid-file="$work/munged.pid" --log-file="$work/munged.log" --seed-file="$work/munge/seed"
cat > "$work/slurm.conf" << CONF
ClusterName=deepvox-check
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$work/munge/munge.socket
CredType=cred/munge
SlurmctldPort=16817
SlurmdPort=16818
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
ReturnToService=2
NodeName=$host NodeAddr=127.0.0.1 CPUs=2 State=UNKNOWN
PartitionName=debug Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$work/slurm.conf
slurmctld
slurmd
for _ in $(seq 60); do
  sinfo -h -o %T 2> /dev/null | grep -q idle && break
  sleep 1
done
sinfo -h -o "%P %D %T %c" || true
sinfo -h -o %T | grep -q idle || { echo "slurm-check: node not idle"; tail "$work"/*.log; exit 1; }

# Waits until the jobs of a submission log ("job N" ...) left the queue (bounded).
wait_for_jobs() {
  local jobs
  jobs=$(grep -oE 'job [0-9]+' "$1" | awk '{print $2}' | paste -sd,)
  while squeue -h -j "$jobs" 2> /dev/null | grep -q .; do
    if [ $(($(date +%s) - start)) -gt "$timeout_s" ]; then
      echo "slurm-check: jobs $jobs still queued after ${timeout_s}s"
      squeue
      exit 1
    fi
    sleep 2
  done
  echo "slurm-check: jobs $jobs done after $(($(date +%s) - start))s"
}

# The untimed rows of two rows.csv files must be equal (and not few).
same_rows() {
  python3 - "$1" "$2" "$3" << 'PY'
import csv, sys
def untimed(path):
    return [r for r in csv.DictReader(open(path, newline="")) if r["unit"] != "ms"]
a, b = untimed(sys.argv[1]), untimed(sys.argv[2])
if a != b or len(a) < 10:
    print(f"slurm-check: FAIL rows differ ({len(a)} unsharded vs {len(b)} {sys.argv[3]})")
    sys.exit(1)
print(f"slurm-check: {len(a)} untimed rows of the {sys.argv[3]} run equal the unsharded run's")
PY
}

start=$(date +%s)
# The unsharded reference runs beside the cluster's jobs (timings are not compared).
"$deepvox" suite "$suite" --backend cpu --costs estimate --out "$work/plain" > "$work/plain.log" 2>&1 &
pids+=($!)
plain_pid=$!
"$deepvox" suite "$suite" --backend cpu --slurm --gpus 2 --submit --costs estimate \
  --out "$work/out" | tee "$work/submit.log"
wait_for_jobs "$work/submit.log"
wait "$plain_pid"
cat "$work"/out/"$suite"/*-slurm/slurm/merge.log
merged=$(ls -d "$work"/out/"$suite"/*-merged | head -1)
plain=$(ls -d "$work"/plain/"$suite"/*/ | head -1)
same_rows "$plain/rows.csv" "$merged/rows.csv" "merged SLURM"
grep -- "- scale-out: 2 CPU workers on 1 host" "$merged/report.md"
grep -c '"host"' "$merged/meta.json" > /dev/null
echo "slurm-check: OK in $(($(date +%s) - start))s (merged: $merged)"

# Requeue: kill task 1's deepvox (not its batch shell) after its first complete experiment; the
# task requeues itself and resumes its shard's folder.
start=$(date +%s)
"$deepvox" suite "$suite" --backend cpu --slurm --gpus 2 --submit --costs estimate \
  --out "$work/requeue" | tee "$work/submit-requeue.log"
array_job=$(grep -oE 'array job [0-9]+' "$work/submit-requeue.log" | awk '{print $3}')
session=$(ls -d "$work"/requeue/"$suite"/*-slurm | head -1)
killed=""
while [ -z "$killed" ]; do
  if [ $(($(date +%s) - start)) -gt "$timeout_s" ]; then
    echo "slurm-check: FAIL task 1 never had a complete experiment to kill after"
    squeue
    exit 1
  fi
  folder=$(ls -d "$session"/shards/"$suite"/*-shard1of2 2> /dev/null | head -1 || true)
  task_job=$(squeue -h -r -j "$array_job" -o "%K %A" 2> /dev/null | awk '$1 == 1 {print $2}')
  if [ -n "$folder" ] && [ -s "$folder/progress.jsonl" ] && [ -n "$task_job" ]; then
    for pid in $(scontrol listpids "$task_job" 2> /dev/null | awk 'NR > 1 {print $1}'); do
      if [ "$(cat "/proc/$pid/comm" 2> /dev/null)" = deepvox ]; then
        kill -KILL "$pid" && killed=$pid
        echo "slurm-check: killed deepvox (pid $pid) of task 1 (job $task_job) after" \
          "$(wc -l < "$folder/progress.jsonl") complete experiment(s)"
      fi
    done
  fi
  sleep 0.5
done
wait_for_jobs "$work/submit-requeue.log"
cat "$session"/slurm/shard-1.log
grep -q "requeueing it to resume" "$session"/slurm/shard-1.log ||
  { echo "slurm-check: FAIL task 1 did not requeue itself"; exit 1; }
shard_folders=$(ls -d "$session"/shards/"$suite"/*-shard1of2* | wc -l)
[ "$shard_folders" = 1 ] ||
  { echo "slurm-check: FAIL task 1 left $shard_folders folders, not one resumed"; exit 1; }
python3 - "$folder/meta.json" << 'PY'
import json, sys
meta = json.load(open(sys.argv[1]))
attempts = len(meta.get("attempts", []))
if meta.get("state") != "finished" or attempts < 2:
    print(f"slurm-check: FAIL shard 1 is {meta.get('state')} after {attempts} attempt(s)")
    sys.exit(1)
print(f"slurm-check: shard 1 finished in its first folder after {attempts} attempts")
PY
merged=$(ls -d "$work"/requeue/"$suite"/*-merged | head -1)
same_rows "$plain/rows.csv" "$merged/rows.csv" "merged, requeued SLURM"
echo "slurm-check: requeue OK in $(($(date +%s) - start))s (merged: $merged)"
