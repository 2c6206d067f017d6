"""Measures the add-on's per-final-frame overhead against Spindrift's own frame time (docs/blender.md):
the fixture's frame 5 at 960x540, layers rendered as the render handler does. First the previous way (every
layer, float32, ZIP) and each EXR compression with the group's layers in half float, RUNS times each, then the
add-on's defaults five times.

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

RUNS = 3
COMPRESSIONS = ("none", "zips", "zip", "piz")


def measure(scene, runs, exr_options, all_layers):
    from spindrift import render_layer, reports

    render_layer.EXR_OPTIONS = exr_options
    scene.spindrift.all_layers = all_layers
    timings = []
    for _ in range(runs):
        render_layer.render_layers_now(scene, bpy.context.evaluated_depsgraph_get(), 5)
        timings.append(dict(reports.last_render["timing"]))
    summary = {key: statistics.median(run[key] for run in timings) for key in timings[0]}
    summary["overhead_fraction"] = summary["overhead_ms"] / summary["spindrift_ms"]
    summary["exr_bytes"] = os.path.getsize(render_layer.layer_path(scene, 5))
    summary["runs"] = timings
    print("overhead:", exr_options, "all layers" if all_layers else "group layers",
          json.dumps({k: round(v, 3) for k, v in summary.items() if k != "runs"}), flush=True)
    return summary


def main():
    fixture, output = arguments()[:2]
    install_addon()
    scene = open_fixture_scene(fixture)
    scene.render.resolution_x, scene.render.resolution_y = 960, 540
    bpy.data.objects["Domain"].spindrift.enabled = True
    scene.frame_set(5)
    bpy.ops.spindrift.setup_compositing(mode="OVER")
    from spindrift import render_layer

    defaults = dict(render_layer.EXR_OPTIONS)
    results = {"resolution": [960, 540], "load_before": os.getloadavg()[0]}
    results["previous"] = measure(scene, RUNS, {"exr_half_color": False, "exr_compression": "zip"}, True)
    for compression in COMPRESSIONS:
        results[compression] = measure(scene, RUNS, {"exr_half_color": True, "exr_compression": compression}, False)
    results["defaults"] = measure(scene, 5, defaults, False)
    results["load_after"] = os.getloadavg()[0]
    with open(output, "w") as file:
        json.dump(results, file, indent=1)


main()
