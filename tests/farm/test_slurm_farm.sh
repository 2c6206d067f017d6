#!/usr/bin/env bash
# The render farm end to end on one machine: starts munge, slurmctld and slurmd on localhost (their own
# configuration, ports and directories under a temporary directory; nothing of the system's is touched),
# renders a small shot locally as the reference, submits the same shot with scripts/farm-submit, kills one
# task's renderer mid-frame with SIGKILL, and checks that every frame arrives exactly once, complete and
# bit-identical to the local render. Stops everything it started, by pid, whatever happens.
#   tests/farm/test_slurm_farm.sh SPINDRIFT_BINARY
set -euo pipefail
source_dir="$(cd "$(dirname "$0")/../.." && pwd)"
spindrift="$(realpath "$1")"
frames=12 chunk=3 killed_task=1
work="$(mktemp -d /tmp/spindrift-slurm-XXXXXX)"
chmod 755 "$work"  # munged insists that every directory above its socket is searchable by all
daemons=()
job=""
export SLURM_CONF="$work/slurm.conf"

log() { echo "slurm-farm: $*"; }
fail() {
  log "FAILED: $*"
  for file in "$work"/logs/*.log "$work/slurmctld.log" "$work/slurmd.log"; do
    [ -f "$file" ] && { echo "--- $file"; tail -n 25 "$file"; }
  done
  exit 1
}
cleanup() {
  if [ -n "$job" ]; then
    scancel "$job" 2>/dev/null || true
    for _ in $(seq 50); do [ -z "$(squeue -h -j "$job" 2>/dev/null)" ] && break; sleep 0.2; done
  fi
  for pid in "${daemons[@]}"; do kill "$pid" 2>/dev/null || true; done
  for pid in "${daemons[@]}"; do wait "$pid" 2>/dev/null || true; done
  rm -rf "$work"
}
trap cleanup EXIT

command -v slurmctld > /dev/null && command -v munged > /dev/null || fail "slurm-wlm and munge are not installed"
start=$SECONDS

# --- a one-node cluster -------------------------------------------------------------------------------
dd if=/dev/urandom of="$work/munge.key" bs=1024 count=1 status=none
chmod 400 "$work/munge.key"
/usr/sbin/munged --foreground --key-file="$work/munge.key" --socket="$work/munge.socket" \
  --pid-file="$work/munged.pid" --log-file="$work/munged.log" --seed-file="$work/munged.seed" > /dev/null 2>&1 &
daemons+=($!)
for _ in $(seq 50); do [ -S "$work/munge.socket" ] && break; sleep 0.1; done
[ -S "$work/munge.socket" ] || fail "munged did not start"

host="$(hostname -s)"
port=$((20000 + RANDOM % 20000))  # Two runs at once (or a real Slurm on this host) must not collide.
mkdir -p "$work/state" "$work/spool" "$work/logs"
cat > "$SLURM_CONF" <<CONF
ClusterName=spindrift-test
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=$(id -un)
SlurmdUser=$(id -un)
AuthType=auth/munge
AuthInfo=socket=$work/munge.socket
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
SelectTypeParameters=CR_Core
SchedulerType=sched/builtin
JobRequeue=1
MpiDefault=none
ReturnToService=2
KillWait=5
MinJobAge=300
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
JobAcctGatherType=jobacct_gather/none
NodeName=$host NodeAddr=127.0.0.1 CPUs=2 State=UNKNOWN
PartitionName=render Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
slurmctld -D -i > "$work/slurmctld.out" 2>&1 &
daemons+=($!)
slurmd -D > "$work/slurmd.out" 2>&1 &
daemons+=($!)
for _ in $(seq 100); do [ "$(sinfo -h -o %T 2>/dev/null)" = idle ] && break; sleep 0.2; done
[ "$(sinfo -h -o %T 2>/dev/null)" = idle ] || fail "the node did not come up: $(sinfo 2>&1 | tail -n 1)"
log "cluster up in $((SECONDS - start)) s"

# --- the shot, rendered locally as the reference --------------------------------------------------------
/usr/bin/python3 "$source_dir/tests/farm/make_shot.py" "$work/shot" "$frames" 320 240
"$spindrift" render "$work/shot/scene.json" --frames "1-$frames" -q -o "$work/reference/f_####.exr" \
  || fail "local reference render"

# --- the same shot on the farm, one task's renderer killed mid-frame -------------------------------------
job="$("$source_dir/scripts/farm-submit" "$work/shot/scene.json" --frames "1-$frames" --chunk "$chunk" \
        --retries 2 -o "$work/farm/f_####.exr" --spindrift "$spindrift" --logs "$work/logs")" \
  || fail "farm-submit"
log "submitted job $job ($(( (frames + chunk - 1) / chunk )) tasks of $chunk frames)"
killed_log="$work/logs/${job}_${killed_task}.log"
first_of_chunk=$((1 + killed_task * chunk))
deadline=$((SECONDS + 120))
until grep -q "^frame $first_of_chunk done" "$killed_log" 2>/dev/null; do
  [ $SECONDS -lt $deadline ] || fail "task $killed_task never finished its first frame"
  sleep 0.05
done
renderer="$(sed -n 's/^farm-task: .* renderer pid \([0-9]*\)$/\1/p' "$killed_log" | head -n 1)"
kill -KILL "$renderer"
log "killed task $killed_task's renderer (pid $renderer) after frame $first_of_chunk"

# Slurm holds a requeued job for about two minutes before it may start again (so that a node can clean
# up); the test, being the administrator, lets it start at once.
deadline=$((SECONDS + 240))
while [ -n "$(squeue -h -j "$job" 2>/dev/null)" ]; do
  [ $SECONDS -lt $deadline ] || fail "the job did not finish"
  if squeue -h -j "$job" -t PD -o "%i %r" 2>/dev/null | grep -q BeginTime; then
    for id in $(squeue -h -j "$job" -t PD -o "%i"); do scontrol update JobId="$id" StartTime=now 2>/dev/null || true; done
  fi
  sleep 0.3
done
log "job finished at $((SECONDS - start)) s"

# --- every frame exactly once, complete, identical ------------------------------------------------------
grep -q "attempt 2" "$killed_log" || fail "the killed task was not requeued"
grep -q "^frame $first_of_chunk skipped" "$killed_log" || fail "the rerun did not skip the frame already written"
expected="$(for f in $(seq 1 $frames); do printf 'f_%04d.exr\n' "$f"; done)"
actual="$(ls -A "$work/farm")"
[ "$actual" = "$expected" ] || fail "the farm's output directory holds: $(echo $actual)"
for f in $(seq 1 $frames); do
  name="$(printf 'f_%04d.exr' "$f")"
  cmp -s "$work/farm/$name" "$work/reference/$name" || fail "$name differs from the local render"
  renders="$(cat "$work"/logs/*.log | grep -c "^frame $f done")"
  [ "$renders" -eq 1 ] || fail "frame $f was written $renders times"
done
interrupted="$(grep -c "^frame .* done" "$killed_log")"
[ "$interrupted" -eq "$chunk" ] || fail "the killed task wrote $interrupted frames in all"
log "PASS: $frames frames, each written once, bit-identical to the local render; one task killed and" \
    "requeued; $((SECONDS - start)) s"
