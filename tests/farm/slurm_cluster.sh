# A one-node Slurm cluster on localhost for the farm tests (sourced by test_slurm_*.sh): munged, slurmctld and
# slurmd with a configuration of their own (random ports, its own key, state and spool directories under
# $work); nothing of the system's Slurm or munge is touched. The caller sets `work` and `job`; `fail`,
# `wait_for_job` and the cleanup trap stop everything started here, by pid, whatever happens.
set -euo pipefail
daemons=()
job=""
export SLURM_CONF="$work/slurm.conf"
chmod 755 "$work"  # munged insists that every directory above its socket is searchable by all

log() { echo "${test_name:-slurm-farm}: $*"; }
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

start_cluster() {
  command -v slurmctld > /dev/null && command -v munged > /dev/null || fail "slurm-wlm and munge are not installed"
  dd if=/dev/urandom of="$work/munge.key" bs=1024 count=1 status=none
  chmod 400 "$work/munge.key"
  /usr/sbin/munged --foreground --key-file="$work/munge.key" --socket="$work/munge.socket" \
    --pid-file="$work/munged.pid" --log-file="$work/munged.log" --seed-file="$work/munged.seed" > /dev/null 2>&1 &
  daemons+=($!)
  for _ in $(seq 50); do [ -S "$work/munge.socket" ] && break; sleep 0.1; done
  [ -S "$work/munge.socket" ] || fail "munged did not start"

  local host port
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
}

# Waits until a task's LOG has a line matching PATTERN, then SIGKILLs the renderer pid the task logged and
# sets killed_pid (not echoed: `fail` inside $(...) would only end the subshell).
kill_renderer_after() {
  local log_file="$1" pattern="$2" seconds="$3" deadline
  deadline=$((SECONDS + seconds))
  until grep -q "$pattern" "$log_file" 2>/dev/null; do
    [ $SECONDS -lt $deadline ] || fail "no line '$pattern' in $log_file after $seconds s"
    sleep 0.05
  done
  killed_pid="$(sed -n 's/^farm-task: .* renderer pid \([0-9]*\)$/\1/p' "$log_file" | head -n 1)"
  [ -n "$killed_pid" ] || fail "$log_file names no renderer pid"
  kill -KILL "$killed_pid"
}

# Waits until all TASKS tasks of the job have ended: `squeue -t all` lists them with their state (finished
# ones stay listed for MinJobAge), so neither a busy slurmctld (squeue fails, no output) nor the moment a
# requeued task passes between states is taken for the end. Slurm holds a requeued task for about two
# minutes before it may start again (so that a node can clean up); the test, being the administrator, lets
# it start two seconds later. Not at once: slurmd rejects a launch whose credential was made in the same second
# as the old run's revocation ("Job credential revoked": the job then ends with exit 1 and is never rerun,
# seen once in CI when the requeue and the new start fell within one second).
# Every task's log ends with its renderer's exit status (scripts/farm-task): the proof that the task's work,
# and its log, are finished. Under load squeue once reported a resubmitted job's tasks finished while their
# Blender was still starting, and the test read logs without their frames (session 31, CI of f19091c).
wait_for_task_logs() {
  local seconds="$1" tasks="$2" deadline task
  deadline=$((SECONDS + seconds))
  for task in $(seq 0 $((tasks - 1))); do
    until grep -q "^farm-task: ${job}_${task} renderer exited with 0" "$work/logs/${job}_${task}.log" 2>/dev/null; do
      [ $SECONDS -lt $deadline ] || fail "task ${job}_${task}'s log does not say that its renderer finished"
      sleep 0.3
    done
  done
}

wait_for_job() {
  local seconds="$1" tasks="$2" deadline states
  deadline=$((SECONDS + seconds))
  while true; do
    [ $SECONDS -lt $deadline ] || fail "the job did not finish in $seconds s: $(squeue -r -t all -h -j "$job" -o '%i %T' | xargs)"
    if states="$(squeue -r -t all -h -j "$job" -o "%T" 2>/dev/null)" && [ "$(echo "$states" | grep -c .)" -eq "$tasks" ] &&
       ! echo "$states" | grep -qvE '^(COMPLETED|FAILED|CANCELLED|TIMEOUT|NODE_FAIL|OUT_OF_MEMORY|BOOT_FAIL|DEADLINE)$'; then
      break
    fi
    if squeue -h -j "$job" -t PD -o "%i %r" 2>/dev/null | grep -q BeginTime; then
      for id in $(squeue -h -j "$job" -t PD -o "%i"); do scontrol update JobId="$id" StartTime=now+2 2>/dev/null || true; done
    fi
    sleep 0.3
  done
}
