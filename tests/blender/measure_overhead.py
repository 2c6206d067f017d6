"""Measures the add-on's per-final-frame overhead against Spindrift's own frame time (docs/blender.md):
the fixture's frame 5 at 960x540, layers rendered as the render handler does, five times.

Run: tests/blender/run_blender.py --zip build/spindrift-addon.zip tests/blender/measure_overhead.py -- \
         build/fixtures/addon_scene OUTPUT_JSON
"""

import json
import os
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import bpy  # noqa: E402

from blender_test_common import arguments, install_addon, open_fixture_scene  # noqa: E402


def main():
    fixture, output = arguments()[:2]
    install_addon()
    scene = open_fixture_scene(fixture)
    scene.render.resolution_x, scene.render.resolution_y = 960, 540
    bpy.data.objects["Domain"].spindrift.enabled = True
    scene.frame_set(5)
    bpy.ops.spindrift.setup_compositing(mode="OVER")
    from spindrift import render_layer, reports

    runs = []
    for _ in range(5):
        render_layer.render_layers_now(scene, bpy.context.evaluated_depsgraph_get(), 5)
        runs.append(dict(reports.last_render["timing"]))
    summary = {key: statistics.median(run[key] for run in runs) for key in runs[0]}
    summary["overhead_fraction"] = summary["overhead_ms"] / summary["spindrift_ms"]
    summary["resolution"] = [960, 540]
    summary["load"] = os.getloadavg()[0]
    summary["runs"] = runs
    with open(output, "w") as file:
        json.dump(summary, file, indent=1)
    print("overhead:", json.dumps({k: v for k, v in summary.items() if k != "runs"}), flush=True)


main()
