"""What a Blender farm task runs inside Blender (scripts/farm-task, `--python` before `-a`): makes the task's
`-s A -e B -a` restartable, so that every frame is written once and a frame a killed task was writing is
never counted as done.

Blender writes a frame's image straight to its final name (not under a temporary one, checked in 3.4.1), so
a file that exists may be truncated. This script therefore keeps a completion record per frame in DONE_DIR,
written in `render_write` (which Blender calls after the frame's file is closed), and before the render:
- a frame whose output exists and has a record (and its Spindrift layer file, when the shot has layers) is
  left alone (Blender's own Overwrite off skips it);
- an output without a record (a killed write, or a render of unknown origin) is removed, so it is rendered.
Placeholders stay off: a placeholder left by a killed task is an empty file that Overwrite off would skip.
Spindrift's own layer EXR (spindrift_NNNN.exr) is written under a temporary name and renamed by the module,
and before the frame's render: a frame with a record has its layers. The temporary a killed task leaves
beside a layer file (".spindrift_NNNN.exr.tmp-<pid>-<n>") is removed before the task renders. A frame whose
layers fail stops the task (On Error = Stop, exit code 1) instead of rendering a frame without them, so the
task is retried.

  blender -b shot.blend --python farm-blender.py -s A -e B -a -- --done DONE_DIR
"""

import glob
import os
import sys

import addon_utils
import bpy
from bpy.app.handlers import persistent


def arguments():
    args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(args) != 2 or args[0] != "--done":
        sys.exit("farm-blender: usage: ... -- --done DIRECTORY")
    return args[1]


DONE_DIR = arguments()


def say(message):
    print(f"farm-blender: {message}", flush=True)


def output_path(scene, frame):
    return bpy.path.abspath(scene.render.frame_path(frame=frame))


def record_path(output):
    # One record per output file, named after it (a shot's outputs share a directory and differ by name).
    return os.path.join(DONE_DIR, os.path.basename(output) + ".done")


@persistent
def on_render_write(scene, _depsgraph=None):
    frame = scene.frame_current
    output = output_path(scene, frame)
    if not os.path.isfile(output):
        say(f"frame {frame}: Blender reported it written but {output} does not exist")
        return
    record = record_path(output)
    with open(record + ".partial", "w") as stream:
        stream.write(output + "\n")
    os.replace(record + ".partial", record)
    # The same line as `spindrift render` prints, which the farm test counts.
    print(f"frame {frame} done", flush=True)


def layers_missing(scene, frame):
    """The frame's Spindrift layer file when the shot renders layers and it is not there (deleted by hand):
    the composite exists without what it was made of, so the frame is rendered again."""
    from spindrift import render_layer  # The add-on's package (loaded: main() checked).

    if not render_layer._wants_layers(scene):
        return None
    path = render_layer.layer_path(scene, frame)
    return None if os.path.isfile(path) else path


def remove_stale_layer_temporaries(scene, frame):
    """Removes the temporaries a task killed while writing FRAME's layer file left beside it (the module
    writes ".<name>.tmp-<pid>-<n>" and renames it; a SIGKILL between the two leaves it). Only this task
    renders FRAME, so none of them is being written now."""
    from spindrift import render_layer

    if not render_layer._wants_layers(scene):
        return
    path = render_layer.layer_path(scene, frame)
    pattern = os.path.join(os.path.dirname(path), "." + glob.escape(os.path.basename(path)) + ".tmp-*")
    for temporary in glob.glob(pattern):
        os.remove(temporary)
        say(f"frame {frame}: removed {temporary}: a killed task's unfinished layer file")


def prepare(scene, first, last):
    """Removes every output of FIRST..LAST that has no completion record (or lost its layer file); says which
    frames are skipped."""
    os.makedirs(DONE_DIR, exist_ok=True)
    for frame in range(first, last + 1):
        remove_stale_layer_temporaries(scene, frame)
        output = output_path(scene, frame)
        record = record_path(output)
        missing = layers_missing(scene, frame)
        if os.path.isfile(output) and os.path.isfile(record) and not missing:
            print(f"frame {frame} skipped: its files exist", flush=True)
        elif os.path.exists(output):
            os.remove(output)
            reason = (f"its Spindrift layers {missing} are missing" if os.path.isfile(record) and missing else
                      "no record that it was completed (a killed task may have truncated it)")
            say(f"frame {frame}: removed {output}: {reason}")
        if os.path.exists(record) and not os.path.exists(output):
            os.remove(record)  # The output is gone (removed above, or by hand): render it again.


def main():
    scene = bpy.context.scene
    _, loaded = addon_utils.check("spindrift")
    if not loaded or not hasattr(scene, "spindrift"):
        say("the Spindrift add-on is not enabled (run Blender with --addons spindrift and BLENDER_USER_SCRIPTS "
            "naming the directory that holds addons/spindrift)")
        sys.exit(1)
    scene.render.use_overwrite = False
    scene.render.use_placeholder = False
    scene.spindrift.on_error = "STOP"
    if scene.render.is_movie_format:
        say("the output is a movie: a farm renders image sequences (one file per frame)")
        sys.exit(1)
    prepare(scene, scene.frame_start, scene.frame_end)
    bpy.app.handlers.render_write.append(on_render_write)


main()
