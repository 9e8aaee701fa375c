#!/bin/bash
# A planned bench on a real Slurm (issue 32): starts a single-node cluster on this machine from Debian's slurm-wlm
# and munge packages (munged, slurmctld and slurmd in a temporary directory, their own socket, ports, state, logs
# and pid files: /etc/munge, /etc/slurm and any system daemon are never touched), submits a small planned bench
# (2 scenes x 3 techniques, each reference split into 4 row tiles) with the plan's submit.sh, waits for the arrays,
# collects, and checks that every configuration's error metrics equal those of the same bench run locally by
# `shadowlab bench` (times aside). Every daemon it started is stopped on exit, whatever happens.
#
# Usage: run_slurm_bench.sh SHADOWLAB DATASETS_DIR
# Exit: 0 passed, 1 failed, 77 skipped (slurm-wlm or munge not installed; ctest's SKIP_RETURN_CODE).
set -euo pipefail
shadowlab=$(realpath "$1")
datasets=$(realpath "$2")

for tool in munged slurmctld slurmd sbatch squeue scontrol python3; do
  if ! command -v "$tool" >/dev/null 2>&1; then
    echo "SKIP: $tool is not installed (apt-get install slurm-wlm munge)"
    exit 77
  fi
done

work=$(mktemp -d /tmp/shadowlab-slurm.XXXXXX)
daemons=()
cleanup() {
  local status=$?
  for pid in "${daemons[@]}"; do
    kill "$pid" 2>/dev/null || true
  done
  for pid in "${daemons[@]}"; do
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -9 "$pid" 2>/dev/null || true
  done
  if [ "$status" -ne 0 ] && [ "$status" -ne 77 ]; then
    for log in "$work"/slurmctld.log "$work"/slurmd.log "$work"/munged.log; do
      [ -f "$log" ] && { echo "--- last lines of $log"; tail -n 15 "$log"; }
    done
  fi
  rm -rf "$work"
  exit "$status"
}
trap cleanup EXIT
trap 'exit 1' INT TERM HUP

# munge: its own key, socket, pid, seed and log files; --force lets it run as root and with the temporary
# directory's permissions.
mkdir -m 700 "$work/munge"
dd if=/dev/urandom of="$work/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$work/munge/munge.key"
socket="$work/munge/munge.socket"
munged --foreground --force --key-file="$work/munge/munge.key" --socket="$socket" \
  --pid-file="$work/munge/munged.pid" --seed-file="$work/munge/munged.seed" --log-file="$work/munged.log" \
  >>"$work/munged.log" 2>&1 &
daemons+=($!)

# Ports no one else on this machine uses (bash's RANDOM keeps two runs side by side apart).
port=$((20000 + RANDOM % 20000))
mkdir -p "$work/state" "$work/spool"
user=$(id -un)
cat > "$work/slurm.conf" <<CONF
ClusterName=shadowlab-test
SlurmctldHost=localhost
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=$user
SlurmdUser=$user
AuthType=auth/munge
AuthInfo=socket=$socket
CredType=cred/munge
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/backfill
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
JobAcctGatherType=jobacct_gather/none
MpiDefault=none
ReturnToService=2
SlurmctldTimeout=30
SlurmdTimeout=30
NodeName=localhost NodeAddr=127.0.0.1 CPUs=2 State=UNKNOWN
PartitionName=debug Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$work/slurm.conf"
for _ in $(seq 50); do [ -S "$socket" ] && break; sleep 0.1; done

slurmctld -D -i -f "$SLURM_CONF" >/dev/null 2>&1 &
daemons+=($!)
slurmd -D -N localhost -f "$SLURM_CONF" >/dev/null 2>&1 &
daemons+=($!)
for i in $(seq 100); do
  state=$(sinfo -h -N -o '%T' 2>/dev/null || true)
  case "$state" in idle*) break ;; esac
  [ "$i" -lt 100 ] || { echo "FAIL: the node did not come up (state '$state')"; exit 1; }
  sleep 0.2
done

scenes=("$datasets/planar-occluder/scene.json" "$datasets/stacked-occluders/scene.json")
bench=(-t hard,pcf,pcss --resolution 48x32 --reference-samples 16 --repeat 1 --quiet)

start=$(date +%s.%N)
"$shadowlab" bench "${scenes[@]}" "${bench[@]}" --cache "$work/slurm-cache" --plan "$work/plan" \
  --reference-tiles 4 --slurm-partition debug --slurm-time 10:00 --slurm-throttle 2
"$work/plan/submit.sh" > "$work/submitted.txt"
cat "$work/submitted.txt"
# No accounting daemon (sacct): the arrays are done when squeue lists none of them.
for i in $(seq 600); do
  [ -z "$(squeue -h -o '%i' 2>/dev/null)" ] && break
  [ "$i" -lt 600 ] || { echo "FAIL: the jobs did not finish in 120 s"; squeue; exit 1; }
  sleep 0.2
done
"$shadowlab" bench --collect "$work/plan" --out "$work/collected" --quiet
slurm_seconds=$(echo "$(date +%s.%N) - $start" | bc)

start=$(date +%s.%N)
"$shadowlab" bench "${scenes[@]}" "${bench[@]}" --cache "$work/local-cache" --out "$work/local"
local_seconds=$(echo "$(date +%s.%N) - $start" | bc)

python3 - "$work/collected/bench.json" "$work/local/bench.json" <<'PY'
import json, sys
collected = json.load(open(sys.argv[1]))["configurations"]
local = json.load(open(sys.argv[2]))["configurations"]
assert len(collected) == len(local) == 6, (len(collected), len(local))
def metrics(row):
    assert row["status"] == "ok", row
    return (row["technique"], row["settings"], row["result"]["error"])
for c, (a, b) in enumerate(zip(collected, local)):
    if metrics(a) != metrics(b):
        sys.exit(f"FAIL: configuration {c}: {metrics(a)} != {metrics(b)}")
print("the 6 configurations' error metrics equal the local bench's")
PY
for entry in "$work/local-cache"/*/; do
  key=$(basename "$entry")
  cmp -s "$entry/buffers.vti" "$work/slurm-cache/$key/buffers.vti" ||
    { echo "FAIL: reference $key merged from 4 Slurm tasks differs from the local one"; exit 1; }
done
printf 'wall time: Slurm (plan, submit, 8 + 2 + 6 tasks, collect) %.1f s; local bench %.1f s\n' "$slurm_seconds" "$local_seconds"
echo "PASS"
