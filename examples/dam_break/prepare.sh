#!/usr/bin/env bash
# Bakes and renders the dam-break example, doing only what is missing: a second run costs nothing.
#   examples/dam_break/prepare.sh            (from anywhere; BLENDER=/path/to/blender to pick another Blender)
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
blender="${BLENDER:-blender}"

# The frame range lives in bake.py's LAYOUT; read it from there so the two never disagree.
frame_start="$(sed -n 's/^ *frame_start=\([0-9]*\),.*/\1/p' "$here/bake.py")"
frame_end="$(sed -n 's/^ *frame_end=\([0-9]*\),.*/\1/p' "$here/bake.py")"
if [[ -z "$frame_start" || -z "$frame_end" ]]; then
  echo "prepare.sh: could not read frame_start/frame_end from the LAYOUT in $here/bake.py" >&2
  exit 1
fi

cache_complete() {
  local frame name
  for ((frame = frame_start; frame <= frame_end; frame++)); do
    printf -v name '%04d' "$frame"
    for file in "data/fluid_data_$name.vdb" "particles/fluid_particles_$name.vdb" "mesh/fluid_mesh_$name.bobj.gz"; do
      [[ -f "$here/cache/$file" ]] || return 1
    done
  done
}

arguments=()
if cache_complete; then
  echo "prepare.sh: cache complete (frames $frame_start-$frame_end in $here/cache), not baking"
  arguments+=(--skip-bake)
else
  echo "prepare.sh: cache missing or incomplete, baking frames $frame_start-$frame_end"
fi
if [[ -f "$here/renders/background.exr" ]]; then
  echo "prepare.sh: $here/renders/background.exr exists, not rendering"
  arguments+=(--skip-render)
else
  echo "prepare.sh: rendering the background"
fi
if [[ -f "$here/renders/with_liquid.exr" ]]; then
  echo "prepare.sh: $here/renders/with_liquid.exr exists, not rendering"
  arguments+=(--skip-liquid-render)
else
  echo "prepare.sh: rendering the frame with the liquid mesh"
fi

if [[ " ${arguments[*]-} " == *" --skip-bake "* && " ${arguments[*]-} " == *" --skip-render "* &&
      " ${arguments[*]-} " == *" --skip-liquid-render "* ]]; then
  echo "prepare.sh: nothing to do"
  exit 0
fi

"$blender" -b --factory-startup --python-exit-code 1 --python "$here/bake.py" -- --output "$here" "${arguments[@]}"
echo "prepare.sh: done"
