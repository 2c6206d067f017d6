"""The world's light alone (light.sky_without_lamps): the light benchmark's thick bodies lit by their sky alone,
with no lamp, as a Blender scene lit by its world or an HDRI is. thick_report.py runs it and puts its section
into docs/light-benchmark.md.

The Cycles references are tests/bench/thick_bodies.py's frames rendered with --sky-only (no sun; the world's
colour and strength as before) under build/bench/thick_sky/: the background with Cycles' light passes and the
full render of the water (its shadow of the sky and the light it lets through, by path tracing). Spindrift
renders each frame's scene, which names no lamp, with its default (the world's light alone taken) and with
light.sky_without_lamps off (the background left as it is, as before the parameter), and both are scored
against the full reference: over the water, over the floor the water changes (outside the water, where the
reference differs from the background; thick_report.regions) and over the whole image. The cost is the
steady frame (thick_report.steady_frame_ms) with it against without it.
"""

import json
import os

import numpy as np

import metrics
import runs

OUTPUT = os.path.join(runs.REPOSITORY, "build", "bench", "thick_sky")
OFF = runs.WORLD_LIGHT_OFF
IMAGES_NEEDED = ("background.exr", "reference_full.exr", "water_mask.exr", "scene.json", "shape.json")


def ensure_renders(report, frames, samples, background_samples):
    """Renders the sky-only frames that are missing or were rendered at other sample counts. `report`: the
    thick_report module (render_thick_bodies)."""
    missing = []
    for frame in frames:
        directory = os.path.join(OUTPUT, frame)
        timings_path = os.path.join(directory, "timings.json")
        timings = json.load(open(timings_path)) if os.path.isfile(timings_path) else {}
        same_samples = (timings.get("samples"), timings.get("background_samples")) == (samples, background_samples)
        if not same_samples or not all(os.path.isfile(os.path.join(directory, name)) for name in IMAGES_NEEDED):
            missing.append(frame)
    if missing:
        report.render_thick_bodies(OUTPUT, missing, samples, background_samples, "--sky-only")


def measure(report, frames):
    """Scores and steady frame times of every sky-only frame, with the world's light alone and without it.
    `report`: the thick_report module (regions, scene_variant, rgb, mae, steady_frame_ms, strip)."""
    results = {}
    for frame in frames:
        directory = os.path.join(OUTPUT, frame)
        water, changed = report.regions(directory)
        everything = np.ones(water.shape, bool)
        full = report.rgb(os.path.join(directory, "reference_full.exr"))
        scene = report.scene_variant(directory, False, True)
        composites, row = [], {"pixels": {"water": int(water.sum()), "changed": int(changed.sum())}}
        for name, settings in (("off", OFF), ("world alone", {})):
            exr = os.path.join(directory, f"spindrift_{name.replace(' ', '_')}.exr")
            runs.run_spindrift(scene, exr, settings, exr + ".stats.json")
            test = metrics.read_channels(exr, ["composite.R", "composite.G", "composite.B"])
            composites.append(test)
            row[name] = {"water": report.mae(test, full, water), "changed": report.mae(test, full, changed),
                         "image": report.mae(test, full, everything),
                         "water_signed": np.mean((test - full)[water], axis=0).tolist()}
        times = {"off": [], "world alone": []}
        for _ in range(2):  # interleaved
            times["off"].append(report.steady_frame_ms(scene, OFF, directory))
            times["world alone"].append(report.steady_frame_ms(scene, {}, directory))
        row["frame_ms"] = {name: float(np.median(values)) for name, values in times.items()}
        report.strip([full, composites[0], composites[1]], os.path.join(report.IMAGES, f"world_{frame}.png"))
        results[frame] = row
    return results


def change(after, before):
    return f"{100 * (after / before - 1):+.0f} %" if np.isfinite(before) and before > 0 else "–"


def section(results, number):
    """The page's section, from measure's results; `number` formats an error."""
    lines = ["## The world's light alone", "",
             "The frames above lit by their sky alone, with no lamp (`thick_bodies.py --sky-only`, under "
             "`build/bench/thick_sky/`): a Blender scene lit by its world or an HDRI. Spindrift's scene names no "
             "lamp; by default it takes the world's light alone (`light.sky_without_lamps`: the sky's view, the "
             "sky occlusion and the lit background run, and the whole background counts as sky light; "
             "docs/liquid.md, \"The world's light alone\"), and *off* leaves the background as it is, as every "
             "scene without lamps was before. Both against Cycles' full render of the sky-lit water. *Floor the "
             "water changes*: outside the water, where that reference differs from the background (as "
             "*shadowed floor* above). *Frame*: the steady frame (frames 3 to 8 of a sequence, each frame's "
             "particles shaped anew), twice, interleaved; the median.", "",
             "| Frame | Water: off | world alone | change | Floor the water changes: off | world alone | "
             "change | Whole image: off | world alone | Frame ms: off | world alone |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for frame, row in results.items():
        off, on = row["off"], row["world alone"]
        lines.append(f"| {frame} | {number(off['water'])} | {number(on['water'])} | "
                     f"{change(on['water'], off['water'])} | {number(off['changed'])} | {number(on['changed'])} | "
                     f"{change(on['changed'], off['changed'])} | {number(off['image'])} | {number(on['image'])} | "
                     f"{row['frame_ms']['off']:.0f} | {row['frame_ms']['world alone']:.0f} |")
    lines += ["", "Left to right: Cycles lit by the sky alone; Spindrift with `light.sky_without_lamps` off; "
              "Spindrift's default, the world's light alone.", ""]
    lines += [f"![{frame}: the sky alone](images/world_{frame}.png)" for frame in results]
    return lines + [""]
