#!/usr/bin/env bash
# The Blender route of the render farm end to end on one machine (docs/farm.md): a one-node Slurm cluster
# (tests/farm/slurm_cluster.sh), a small .blend shot of the add-on tests' baked Mantaflow fixture with
# Spindrift composited over Cycles, rendered once locally with a plain `blender -b shot.blend -a` as the
# reference, then submitted with scripts/farm-submit. One task's Blender is SIGKILLed after its first frame,
# a truncated file (what a write cut short leaves) waits at another frame's output, and a layer file's
# temporary (what a kill between the module's write and its rename leaves) beside a third. Checks that every
# frame arrives exactly once, that the truncated file was replaced, and that the Spindrift layer EXRs are
# byte-identical and the composited frames pixel-identical to the local render. Then deletes one frame's
# layer file and submits the shot again: only that frame is rendered again.
#   tests/farm/test_slurm_blender.sh ADDON_ZIP FIXTURE_DIR
set -euo pipefail
source_dir="$(cd "$(dirname "$0")/../.." && pwd)"
addon_zip="$(realpath "$1")" fixture="$(realpath "$2")"
first=3 last=6 chunk=2 killed_task=0 truncated_frame=6 lost_layers_frame=5 stale_temporary_frame=5
test_name=slurm-blender
work="$(mktemp -d /tmp/spindrift-slurm-blender-XXXXXX)"
# shellcheck source=tests/farm/slurm_cluster.sh
source "$source_dir/tests/farm/slurm_cluster.sh"
start=$SECONDS
start_cluster
log "cluster up in $((SECONDS - start)) s"

# --- the shot, rendered locally with a plain `blender -b -a` as the reference -----------------------------
/usr/bin/python3 "$source_dir/tests/blender/run_blender.py" --zip "$addon_zip" \
  "$source_dir/tests/farm/make_blender_shot.py" -- "$fixture" "$work/shot" "$first" "$last" > "$work/make_shot.log" 2>&1 \
  || { tail -n 30 "$work/make_shot.log"; fail "making the shot"; }
mkdir -p "$work/reference-scripts/addons"
/usr/bin/python3 -m zipfile -e "$addon_zip" "$work/reference-scripts/addons/"
reference_start=$SECONDS
BLENDER_USER_SCRIPTS="$work/reference-scripts" blender -b --factory-startup --addons spindrift "$work/shot/shot.blend" \
  -o "$work/reference/frame_####" -a > "$work/reference.log" 2>&1 || { tail -n 30 "$work/reference.log"; fail "local render"; }
log "local render of frames $first-$last in $((SECONDS - reference_start)) s"
names=()
for f in $(seq "$first" "$last"); do names+=("$(printf 'frame_%04d.exr' "$f")" "$(printf 'spindrift_%04d.exr' "$f")"); done
for name in "${names[@]}"; do [ -f "$work/reference/$name" ] || fail "the local render did not write $name"; done

# --- the farm: a truncated frame waiting at one output, one task's Blender killed mid-frame ---------------
mkdir -p "$work/farm"
truncated="$(printf 'frame_%04d.exr' "$truncated_frame")"
head -c "$(( $(stat -c %s "$work/reference/$truncated") / 2 ))" "$work/reference/$truncated" > "$work/farm/$truncated"
stale_temporary="$(printf '.spindrift_%04d.exr.tmp-99999-0' "$stale_temporary_frame")"
echo "half a layer file" > "$work/farm/$stale_temporary"
job="$("$source_dir/scripts/farm-submit" "$work/shot/shot.blend" --frames "$first-$last" --chunk "$chunk" \
        --retries 2 --addon-zip "$addon_zip" -o "$work/farm/frame_####" --logs "$work/logs")" || fail "farm-submit"
log "submitted job $job ($(( (last - first) / chunk + 1 )) tasks of $chunk frames)"
killed_log="$work/logs/${job}_${killed_task}.log"
first_of_chunk=$((first + killed_task * chunk))
kill_renderer_after "$killed_log" "^frame $first_of_chunk done" 300
log "killed task $killed_task's Blender (pid $killed_pid) after frame $first_of_chunk"
wait_for_job 600 $(( (last - first) / chunk + 1 ))
wait_for_task_logs 60 $(( (last - first) / chunk + 1 ))
log "job finished at $((SECONDS - start)) s"

# --- every frame exactly once, the truncated one replaced, identical to the local render ------------------
grep -q "attempt 2" "$killed_log" || fail "the killed task was not requeued"
grep -q "^frame $first_of_chunk skipped" "$killed_log" || fail "the rerun did not skip the frame already written"
grep -q "frame $truncated_frame: removed .*$truncated: no record" "$work"/logs/*.log \
  || fail "the truncated $truncated was not removed before rendering"
grep -q "frame $stale_temporary_frame: removed .*$stale_temporary: a killed task's" "$work"/logs/*.log \
  || fail "the stale $stale_temporary was not removed before rendering"
expected="$(printf '%s\n' "${names[@]}" | sort)"
actual="$(ls -A "$work/farm")"
[ "$actual" = "$expected" ] || fail "the farm's output directory holds: $(echo $actual)"
for f in $(seq "$first" "$last"); do
  renders="$(cat "$work"/logs/*.log | grep -c "^frame $f done" || true)"
  [ "$renders" -eq 1 ] || fail "frame $f was written $renders times"
  layers="$(printf 'spindrift_%04d.exr' "$f")"
  cmp -s "$work/farm/$layers" "$work/reference/$layers" || fail "$layers differs from the local render's"
done
/usr/bin/python3 "$source_dir/tests/farm/compare_images.py" "$work/reference" "$work/farm" "${names[@]}" \
  || fail "the farm's frames differ from the local render's"

# --- a resubmission with the same logs renders only what is missing: a frame whose layer file was deleted --
rm "$work/farm/$(printf 'spindrift_%04d.exr' "$lost_layers_frame")"
first_job="$job"
job="$("$source_dir/scripts/farm-submit" "$work/shot/shot.blend" --frames "$first-$last" --chunk "$chunk" \
        --retries 0 --addon-zip "$addon_zip" -o "$work/farm/frame_####" --logs "$work/logs")" || fail "resubmitting"
wait_for_job 300 $(( (last - first) / chunk + 1 ))
wait_for_task_logs 60 $(( (last - first) / chunk + 1 ))
resubmitted="$(cat "$work"/logs/"${job}"_*.log)"
for f in $(seq "$first" "$last"); do
  if [ "$f" -eq "$lost_layers_frame" ]; then
    grep -q "frame $f: removed .*: its Spindrift layers .* are missing" <<< "$resubmitted" \
      || fail "the resubmission did not notice frame $f's missing layers"
    grep -q "^frame $f done" <<< "$resubmitted" || fail "the resubmission did not render frame $f again"
  else
    grep -q "^frame $f skipped" <<< "$resubmitted" || fail "the resubmission did not skip frame $f"
    ! grep -q "^frame $f done" <<< "$resubmitted" || fail "the resubmission rendered frame $f again"
  fi
done
[ "$(ls -A "$work/farm")" = "$expected" ] || fail "after the resubmission the output directory holds: $(ls -A "$work/farm" | xargs)"
/usr/bin/python3 "$source_dir/tests/farm/compare_images.py" "$work/reference" "$work/farm" "${names[@]}" > /dev/null \
  || fail "after the resubmission the frames differ from the local render's"
log "resubmitted as job $job (first was $first_job): frame $lost_layers_frame, whose layers were deleted," \
    "rendered again; the others skipped"
log "PASS: frames $first-$last, each written once; Spindrift layers byte-identical and composites" \
    "pixel-identical to the local render; one task killed and requeued, a truncated frame replaced, a frame" \
    "with lost layers rendered again on resubmission;" \
    "$((SECONDS - start)) s"
echo "--- the killed task's log (both attempts):"
grep -E '^(farm-task|farm-blender|frame [0-9]+ )' "$killed_log" | sed 's/^/  /'
