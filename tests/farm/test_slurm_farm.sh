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
# shellcheck source=tests/farm/slurm_cluster.sh
source "$source_dir/tests/farm/slurm_cluster.sh"
start=$SECONDS
start_cluster
log "cluster up in $((SECONDS - start)) s"

# --- the shot, rendered locally as the reference --------------------------------------------------------
# The frames after the one the test kills a renderer after are slow (make_shot.py says why).
/usr/bin/python3 "$source_dir/tests/farm/make_shot.py" "$work/shot" "$frames" 320 240 \
  "$((2 + killed_task * chunk))-$(((killed_task + 1) * chunk))"
"$spindrift" render "$work/shot/scene.json" --frames "1-$frames" -q -o "$work/reference/f_####.exr" \
  || fail "local reference render"

# --- the same shot on the farm, one task's renderer killed mid-frame -------------------------------------
job="$("$source_dir/scripts/farm-submit" "$work/shot/scene.json" --frames "1-$frames" --chunk "$chunk" \
        --retries 2 -o "$work/farm/f_####.exr" --spindrift "$spindrift" --logs "$work/logs")" \
  || fail "farm-submit"
log "submitted job $job ($(( (frames + chunk - 1) / chunk )) tasks of $chunk frames)"
killed_log="$work/logs/${job}_${killed_task}.log"
first_of_chunk=$((1 + killed_task * chunk))
kill_renderer_after "$killed_log" "^frame $first_of_chunk done" 120
log "killed task $killed_task's renderer (pid $killed_pid) after frame $first_of_chunk"
wait_for_job 240 $(( (frames + chunk - 1) / chunk ))
log "job finished at $((SECONDS - start)) s"

# --- every frame exactly once, complete, identical ------------------------------------------------------
grep -q "attempt 2" "$killed_log" || fail "the killed task was not requeued"
grep -q "^frame $first_of_chunk skipped" "$killed_log" || fail "the rerun did not skip the frame already written"
expected="$(for f in $(seq 1 $frames); do printf 'f_%04d.exr\n' "$f"; done)"
actual="$(ls -A "$work/farm")"
[ "$actual" = "$expected" ] || fail "the farm's output directory holds: $(echo $actual)"
# A frame's "done" line is printed when the next frame waits for its write, so the killed renderer may have
# finished a frame's files without saying so; the rerun then skips it. Such a frame was still written once.
silent=0
for f in $(seq 1 $frames); do
  name="$(printf 'f_%04d.exr' "$f")"
  cmp -s "$work/farm/$name" "$work/reference/$name" || fail "$name differs from the local render"
  # grep -c exits 1 when it counts nothing: under `set -e -o pipefail` that would end the test without a word.
  renders="$(cat "$work"/logs/*.log | grep -c "^frame $f done" || true)"
  if [ "$renders" -eq 0 ] && grep -q "^frame $f skipped" "$killed_log"; then
    silent=$((silent + 1))
    continue
  fi
  [ "$renders" -eq 1 ] || fail "frame $f was written $renders times"
done
interrupted="$(grep -c "^frame .* done" "$killed_log" || true)"
[ "$((interrupted + silent))" -eq "$chunk" ] || fail "the killed task wrote $interrupted frames in all (+$silent unannounced)"
log "PASS: $frames frames, each written once, bit-identical to the local render; one task killed and" \
    "requeued; $((SECONDS - start)) s"
