"""Makes the Blender farm test's shot from the add-on tests' baked fixture (tests/blender/make_scene.py): a copy
of its .blend with Spindrift enabled on the domain and composited over the render (Set Up Compositing, mode
OVER), frames FIRST-LAST, saved as OUTPUT/shot.blend (its cache stays the fixture's, by absolute path).

Run with the add-on installed: tests/blender/run_blender.py --zip ZIP make_blender_shot.py -- FIXTURE OUTPUT FIRST LAST
"""

import os
import sys

import bpy

sys.path.insert(0, os.path.join(os.environ["SPINDRIFT_SOURCE_DIR"], "tests", "blender"))
from blender_test_common import arguments, check, install_addon, open_fixture_scene  # noqa: E402


def main():
    fixture, output, first, last = arguments()
    install_addon()
    scene = open_fixture_scene(fixture)
    domain = bpy.data.objects["Domain"]
    domain.spindrift.enabled = True
    scene.frame_start, scene.frame_end = int(first), int(last)
    scene.frame_set(int(first))
    result = bpy.ops.spindrift.setup_compositing(mode="OVER")
    check(result == {"FINISHED"}, "Set Up Compositing (Liquid and Foam Over)")
    # The composite as a plain EXR; the farm and the reference both give -o, so this is only a default.
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.filepath = "//render/frame_####"
    os.makedirs(output, exist_ok=True)
    bpy.ops.wm.save_as_mainfile(filepath=os.path.join(output, "shot.blend"))
    print(f"make_blender_shot: saved {output}/shot.blend, frames {first}-{last}", flush=True)


main()
