#!/usr/bin/python3
"""The light benchmark (issue 10): Spindrift against Cycles on thick bodies of water, with and without the
water's shadows and caustics. Regenerates the "Light through the liquid: measured" section's table and
pictures (docs/light-benchmark.md, docs/images/light_*.png).

    tests/bench/thick_report.py [--samples 512] [--background-samples 128]

Renders whatever is missing under build/bench/thick/ with tests/bench/thick_bodies.py in Blender (once; the
files are kept), then runs `build/bin/spindrift render` for each frame and setting, and VTK's fluid mapper,
and scores every composite against both Cycles references: over the water (Cycles' own coverage of it) and
over the floor the water shadows (outside the water, where the full reference differs from the background
by more than 0.02 in any channel).
"""

import argparse
import json
import os
import subprocess
import sys

import numpy as np
from scipy import ndimage

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import metrics  # noqa: E402
import runs  # noqa: E402
import world_light  # noqa: E402

REPOSITORY = runs.REPOSITORY
OUTPUT = os.path.join(REPOSITORY, "build", "bench", "thick")
FRAMES = ["block", "ball", "pool_above", "pool_side", "underwater", "far", "ball_baked"]
PAGE = os.path.join(REPOSITORY, "docs", "light-benchmark.md")
IMAGES = os.path.join(REPOSITORY, "docs", "images")
ABSORPTION_RGB = (0.9, 0.3, 0.15)
# The full reference rendered again with another seed: its error is the references' own noise.
NOISE_FLOOR = "Cycles, another seed (noise floor)"

# Each Spindrift setting: a name, whether the scene's sun is kept, whether the background keeps Cycles'
# light passes, and --set overrides.
# Without the sun the scene names no lamp, and Spindrift's default takes the world's light alone
# (light.sky_without_lamps): the rows "before" leave it off, as there were no light passes then.
NO_LIGHT = runs.WORLD_LIGHT_OFF
SETTINGS = [
    ("no lights (before)", False, True, NO_LIGHT),
    ("sun, light passes", True, True, {}),
    ("sun, no light passes", True, False, {}),
    ("sun, light passes, no sky occlusion", True, True, {"light.sky_occlusion_directions": 0}),
    ("no lights, absorption x2.5", False, True, {**NO_LIGHT, "liquid.absorption": 2.5}),
    ("sun, light passes, fixed 512-texel light views", True, True, {"light.texels_per_radius": 0}),
    ("sun, light passes, lights' views at 3 texels per radius", True, True, {"light.texels_per_radius": 3}),
    # The marches' step before session 36 (docs/frame-cost.md): what the cheaper default costs here.
    ("sun, light passes, marches in steps of 1.5 px", True, True, {"liquid.trace_step_pixels": 1.5}),
    # The front normals near a silhouette as smoothing leaves them (docs/liquid.md, "Rim normals").
    ("sun, light passes, no rim normals", True, True, {"liquid.rim_normals": False}),
    # The sun left out of a scene it lights: the defaults then take the background's light, the sun's with
    # it, for the world's (docs/liquid.md, "The world's light alone").
    ("no lamps: the world's light alone", False, True, {}),
]


CYCLES_IMAGES = ("background.exr", "background_plain.exr", "reference_noshadow.exr", "reference_full.exr",
                 "reference_full_seed2.exr")


def ensure_renders(samples, background_samples):
    """Renders what is missing; a frame rendered at other sample counts is rendered again."""
    missing = []
    for frame in FRAMES:
        directory = os.path.join(OUTPUT, frame)
        timings_path = os.path.join(directory, "timings.json")
        timings = json.load(open(timings_path)) if os.path.isfile(timings_path) else {}
        if (timings.get("samples"), timings.get("background_samples")) != (samples, background_samples):
            for name in CYCLES_IMAGES:
                if os.path.isfile(os.path.join(directory, name)):
                    os.remove(os.path.join(directory, name))
        if not all(os.path.isfile(os.path.join(directory, name))
                   for name in ("background.exr", "reference_noshadow.exr", "reference_full.exr",
                                "reference_full_seed2.exr", "water_mask.exr", "scene.json", "shape.json")):
            missing.append(frame)
    if missing:
        render_thick_bodies(OUTPUT, missing, samples, background_samples)


def render_thick_bodies(output, frames, samples, background_samples, *options):
    """Renders `frames` with thick_bodies.py in Blender into `output` (`options`: its own, e.g. --sky-only)."""
    subprocess.run(["nice", "-n", "5", "blender", "-b", "--factory-startup", "-t", "2", "--python-exit-code", "1",
                    "--python", os.path.join(os.path.dirname(os.path.abspath(__file__)), "thick_bodies.py"), "--",
                    "--output", output, "--frames", ",".join(frames), "--samples", str(samples),
                    "--background-samples", str(background_samples), *options],
                   check=True)


LIGHT_PASS_NAMES = ("light_depth_layers", "liquid_shadow", "caustics", "sky_depth_layers", "sky_occlusion",
                    "lit_tiles", "lit_background")


def light_cost(stats):
    """GPU milliseconds of the light passes and of the whole frame, from one frame's stats."""
    return (sum(p["gpu_ms"] for p in stats["passes"] if p["name"] in LIGHT_PASS_NAMES),
            sum(p["gpu_ms"] for p in stats["passes"]))


# The steady measures render one frame again and again; a sequence's frames hold new particles, which a
# renderer shapes anew (liquid.reuse_shapes keeps the shapes of unchanged particles, as a viewport orbiting a
# paused frame has them). So that a steady frame costs what a sequence's does, every frame shapes anew.
SEQUENCE_SETTINGS = {"liquid.reuse_shapes": False}


def steady_cost(scene, settings, directory):
    """The light passes' cost in a sequence of one renderer, frames 3 to 6 (median): llvmpipe compiles each
    shader's machine code when it first draws with it, which a single-frame process pays inside its frame. Each
    pass is finished before the next starts (SPINDRIFT_FINISH_PASSES): llvmpipe otherwise rasterises a pass's
    draws when a later pass reads them, and charges them to that pass (the background's to the lights').
    Every frame shapes its particles anew, as a sequence's new particles are (SEQUENCE_SETTINGS)."""
    command = [runs.SPINDRIFT, "render", scene, "-o", os.path.join(directory, "steady_####.exr"), "--stats",
               os.path.join(directory, "steady_####.json"), "--frames", "1-6", "-q",
               *runs.set_arguments({**SEQUENCE_SETTINGS, **settings})]
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL, env=dict(os.environ, SPINDRIFT_FINISH_PASSES="1"))
    costs = []
    for frame in range(3, 7):
        with open(os.path.join(directory, f"steady_{frame:04d}.json")) as handle:
            stats = json.load(handle)
        costs.append(light_cost(stats) + (stats["light"]["prepare_ms"],))
    return tuple(float(np.median([c[k] for c in costs])) for k in range(3))


def steady_frame_ms(scene, settings, directory, written=True):
    """The median whole-frame time (total_ms) of frames 3 to 8 of a `--frames 1-8` sequence, the passes not
    finished one by one (as a user's render runs), each frame's particles shaped anew (SEQUENCE_SETTINGS).
    `written`: each frame's EXR is written (every layer, the command line's defaults), on a thread of its own
    while the next frame renders, whose CPU it shares; else the frames are rendered alone."""
    output = ["-o", os.path.join(directory, "frames_####.exr")] if written else []
    command = [runs.SPINDRIFT, "render", scene, *output, "--stats",
               os.path.join(directory, "frames_####.json"), "--frames", "1-8", "-q",
               *runs.set_arguments({**SEQUENCE_SETTINGS, **settings})]
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
    totals = []
    for frame in range(3, 9):
        with open(os.path.join(directory, f"frames_{frame:04d}.json")) as handle:
            totals.append(json.load(handle)["total_ms"])
    return float(np.median(totals))


def marginal_cost(directory, settings):
    """What the scene's lights add to a steady frame: the frame with them against the same frame without any
    light (the same background with its light passes) and against the frame without the sun that takes the
    world's light alone, each sequence run twice, interleaved; the medians. Then the frames with and without
    any light rendered alone, their EXRs written nowhere: writing every layer in 32-bit float takes about a
    third of the thick bodies' frames (docs/frame-cost.md, session 62)."""
    lit, unlit = scene_variant(directory, True, True), scene_variant(directory, False, True)
    no_light = {**settings, **NO_LIGHT}
    runs_of = {"with_lights_ms": [], "without_lights_ms": [], "world_alone_ms": [], "with_lights_alone_ms": [],
               "without_lights_alone_ms": []}
    for _ in range(2):
        runs_of["with_lights_ms"].append(steady_frame_ms(lit, settings, directory))
        runs_of["without_lights_ms"].append(steady_frame_ms(unlit, no_light, directory))
        runs_of["world_alone_ms"].append(steady_frame_ms(unlit, settings, directory))
        runs_of["with_lights_alone_ms"].append(steady_frame_ms(lit, settings, directory, written=False))
        runs_of["without_lights_alone_ms"].append(steady_frame_ms(unlit, no_light, directory, written=False))
    return {key: float(np.median(values)) for key, values in runs_of.items()}


def write_plain_background(directory):
    """The background without its light passes, as a render without them would be."""
    path = os.path.join(directory, "background_plain.exr")
    if os.path.isfile(path):
        return path
    import OpenImageIO as oiio
    source = oiio.ImageBuf(os.path.join(directory, "background.exr"))
    names = list(source.spec().channelnames)
    keep = [names.index(name) for name in ("ViewLayer.Combined.R", "ViewLayer.Combined.G", "ViewLayer.Combined.B",
                                           "ViewLayer.Combined.A", "ViewLayer.Depth.Z")]
    plain = oiio.ImageBufAlgo.channels(source, tuple(keep), newchannelnames=tuple(names[i] for i in keep))
    plain.write(path)
    return path


def scene_variant(directory, keep_lights, light_passes):
    with open(os.path.join(directory, "scene.json")) as handle:
        scene = json.load(handle)
    if not keep_lights:
        scene.pop("lights", None)
    if not light_passes:
        scene["background"]["image"] = os.path.basename(write_plain_background(directory))
    scene["particles"][0]["path"] = os.path.join(directory, scene["particles"][0]["path"])
    name = f"scene_{'lit' if keep_lights else 'unlit'}_{'passes' if light_passes else 'plain'}.json"
    path = os.path.join(directory, name)
    with open(path, "w") as handle:
        json.dump(scene, handle, indent=1)
    return path


def rgb(path):
    """A Cycles render's Combined colour."""
    return metrics.read_channels(path, ["Combined.R", "Combined.G", "Combined.B"])


def contains(shape, point):
    """Whether a point lies inside the water's exact shape (shape.json's: a box or a sphere)."""
    if shape[0] == "box":
        return bool(np.all(np.array(shape[1]) < point) and np.all(point < np.array(shape[2])))
    return bool(np.linalg.norm(point - np.array(shape[1])) < shape[2])


def camera_in_water(directory):
    """Whether the frame's camera lies inside the water's exact shape."""
    with open(os.path.join(directory, "scene.json")) as handle, \
            open(os.path.join(directory, "shape.json")) as shape_file:
        world_from_camera = np.array(json.load(handle)["camera"]["world_from_camera"]).reshape(4, 4)
        return contains(json.load(shape_file)["shape"], world_from_camera[:3, 3])


def regions(directory):
    if camera_in_water(directory):
        # Every pixel sees through the water, and no floor outside it.
        shape = metrics.read_channels(os.path.join(directory, "background.exr"), ["Depth.Z"])[..., 0].shape
        return np.ones(shape, bool), np.zeros(shape, bool)
    mask = os.path.join(directory, "water_mask.exr")
    silhouette = metrics.read_channels(mask, ["Combined.A"])[..., 0] > 0.5
    # The water where no solid hides it: the mask is the water rendered alone, so from the pool's side it also
    # covers the tank's near wall, which both renders show (until 2026-12-02 those pixels were scored, and
    # held 89 % of that frame's "water").
    water_depth = metrics.read_channels(mask, ["Depth.Z"])[..., 0]
    solid_depth = metrics.read_channels(os.path.join(directory, "background.exr"), ["Depth.Z"])[..., 0]
    water = silhouette & (water_depth < solid_depth)
    background = rgb(os.path.join(directory, "background.exr"))
    full = rgb(os.path.join(directory, "reference_full.exr"))
    # Blurred first, so that the references' sampling noise does not count as shadow.
    blur = [ndimage.gaussian_filter(image, sigma=(2, 2, 0)) for image in (full, background)]
    shadowed = ~ndimage.binary_dilation(silhouette, iterations=3) & (np.abs(blur[0] - blur[1]).max(axis=2) > 0.03)
    return water, shadowed


def mae(test, reference, mask):
    return float(np.mean(np.abs(test[mask] - reference[mask]))) if mask.any() else float("nan")


def blurred(image):
    """A Gaussian blur of 2 px: what is left of an error once the references' zero-mean sampling noise is
    averaged away (and with it detail finer than a few pixels, in both images alike)."""
    return ndimage.gaussian_filter(image, sigma=(2, 2, 0))


def score(test, directory, water, shadowed):
    noshadow = rgb(os.path.join(directory, "reference_noshadow.exr"))
    full = rgb(os.path.join(directory, "reference_full.exr"))
    return {"water_vs_noshadow": mae(test, noshadow, water), "water_vs_full": mae(test, full, water),
            "water_vs_full_blurred": mae(blurred(test), blurred(full), water),
            "shadow_vs_full": mae(test, full, shadowed)}


def camera_rays(scene):
    """World origin and unit directions of every pixel's centre ray (row 0 at the top), from a scene file."""
    camera = scene["camera"]
    width, height = camera["width"], camera["height"]
    world_from_camera = np.array(camera["world_from_camera"], dtype=np.float64).reshape(4, 4)
    tan_y = np.tan(np.radians(camera["fov_y_deg"]) / 2)
    columns, rows = np.meshgrid(np.arange(width) + 0.5, np.arange(height) + 0.5)
    x = (columns / width * 2 - 1) * tan_y * width / height
    y = (1 - rows / height * 2) * tan_y
    local = np.stack([x, y, -np.ones_like(x)], axis=-1)
    directions = local @ world_from_camera[:3, :3].T
    directions /= np.linalg.norm(directions, axis=-1, keepdims=True)
    return world_from_camera[:3, 3], directions


def first_path_length(scene, shape, ior=1.33):
    """The exact length of each pixel's first refracted path in the water (to where it leaves the shape or meets
    the floor, z = 0), NaN where the ray misses the water: what Spindrift's thickness layer estimates."""
    origin, directions = camera_rays(scene)
    kind = shape[0]
    if kind == "box":
        low, high = np.array(shape[1]), np.array(shape[2])
        with np.errstate(divide="ignore", invalid="ignore"):
            t0, t1 = (low - origin) / directions, (high - origin) / directions
        near, far = np.minimum(t0, t1), np.maximum(t0, t1)
        t_in = near.max(axis=-1)
        hit = (t_in < far.min(axis=-1)) & (t_in > 0)
        axis = near.argmax(axis=-1)
        normal = np.zeros_like(directions)
        np.put_along_axis(normal, axis[..., None], -np.sign(np.take_along_axis(directions, axis[..., None], -1)), -1)
    else:
        centre, radius = np.array(shape[1]), shape[2]
        offset = origin - centre
        b = directions @ offset
        c = offset @ offset - radius * radius
        disc = b * b - c
        hit = disc > 0
        t_in = -b - np.sqrt(np.maximum(disc, 0))
        normal = (origin + t_in[..., None] * directions - centre) / radius
    entry = origin + t_in[..., None] * directions
    cosine = -(normal * directions).sum(-1)
    ratio = 1 / ior
    k = 1 - ratio * ratio * (1 - cosine * cosine)
    inside = ratio * directions + (ratio * cosine - np.sqrt(np.maximum(k, 0)))[..., None] * normal
    if contains(shape, origin):
        # The camera in the water: every ray starts in it, unbent.
        hit = np.ones(directions.shape[:-1], bool)
        entry, inside = np.broadcast_to(origin, directions.shape), directions
    if kind == "box":
        with np.errstate(divide="ignore", invalid="ignore"):
            t0, t1 = (low - entry) / inside, (high - entry) / inside
        length = np.where(np.isnan(t0), np.inf, np.maximum(t0, t1)).min(axis=-1)
    else:
        offset = entry - centre
        b = (inside * offset).sum(-1)
        length = -b + np.sqrt(np.maximum(b * b - ((offset * offset).sum(-1) - radius * radius), 0))
    with np.errstate(divide="ignore", invalid="ignore"):
        to_floor = np.where(inside[..., 2] < 0, -entry[..., 2] / inside[..., 2], np.inf)
    length = np.minimum(length, to_floor)
    return np.where(hit, length, np.nan)


def strip(images, path):
    """Images side by side, sRGB-encoded, as one PNG."""
    import OpenImageIO as oiio
    row = np.ascontiguousarray(np.concatenate([metrics.srgb_encode(image) for image in images], axis=1), np.float32)
    buffer = oiio.ImageBuf(oiio.ImageSpec(row.shape[1], row.shape[0], 3, oiio.FLOAT))
    buffer.set_pixels(oiio.ROI.All, row)
    buffer.write(path, "uint8")


def passes_strip(exr, path):
    """The light passes of a render (liquid_shadow, caustics, liquid_sky; red channel, 0 to 1 as black to white)
    and its composite, side by side."""
    grey = [np.repeat(metrics.read_channels(exr, [f"{name}.R"]), 3, axis=2).clip(0, 1) for name in
            ("liquid_shadow", "caustics", "liquid_sky")]
    strip([*grey, metrics.read_channels(exr, ["composite.R", "composite.G", "composite.B"])], path)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--samples", type=int, default=512, help="Cycles samples of the water references")
    parser.add_argument("--background-samples", type=int, default=128)
    arguments = parser.parse_args()
    ensure_renders(arguments.samples, arguments.background_samples)
    world_light.ensure_renders(sys.modules[__name__], FRAMES, arguments.samples, arguments.background_samples)
    results, timings = {}, {}
    renderer = runs.gl_renderer()
    load_before = os.getloadavg()[0]
    for frame in FRAMES:
        directory = os.path.join(OUTPUT, frame)
        water, shadowed = regions(directory)
        results[frame] = {"pixels": {"water": int(water.sum()), "shadowed": int(shadowed.sum())},
                          "in_water": camera_in_water(directory)}
        composites = {}
        for name, keep_lights, light_passes, settings in SETTINGS:
            scene = scene_variant(directory, keep_lights, light_passes)
            exr = os.path.join(directory, f"spindrift_{len(composites)}.exr")
            _, stats, _, _ = runs.run_spindrift(scene, exr, settings, exr + ".stats.json")
            composites[name] = metrics.read_channels(exr, ["composite.R", "composite.G", "composite.B"])
            if name == "no lights (before)":
                with open(scene) as handle, open(os.path.join(directory, "shape.json")) as shape_file:
                    exact = first_path_length(json.load(handle), json.load(shape_file)["shape"])
                thickness = metrics.read_channels(exr, ["thickness.Y"])[..., 0]
                both = water & np.isfinite(exact) & (thickness > 0)
                results[frame]["path"] = {
                    "exact_median": float(np.median(exact[both])),
                    "spindrift_median": float(np.median(thickness[both])),
                    "ratio_median": float(np.median(thickness[both] / exact[both])),
                    "exits_off_screen": stats["liquid"].get("exits_off_screen", 0),
                    "exits_behind_solids": stats["liquid"].get("exits_behind_solids", 0),
                    "total_internal_reflections": stats["liquid"]["total_internal_reflections"],
                    "liquid_pixels": stats["liquid"]["liquid_pixels"]}
            results[frame][name] = score(composites[name], directory, water, shadowed)
            timed = {"sun, light passes": frame, "sun, light passes, fixed 512-texel light views":
                     frame + " (fixed 512 texels)"}
            if name in timed:
                key = timed[name]
                light_passes_ms, frame_ms = light_cost(stats)
                steady_light_ms, steady_frame_gpu_ms, steady_prepare_ms = steady_cost(scene, settings, directory)
                frame_times = marginal_cost(directory, settings)
                sky_occlusion_ms = sum(p["gpu_ms"] for p in stats["passes"] if p["name"] == "sky_occlusion")
                timings[key] = {"light_gpu_ms": light_passes_ms, "frame_gpu_ms": frame_ms,
                                "sky_occlusion_gpu_ms": sky_occlusion_ms,
                                "steady_light_gpu_ms": steady_light_ms, "steady_frame_gpu_ms": steady_frame_gpu_ms,
                                "steady_light_prepare_ms": steady_prepare_ms,
                                **frame_times,
                                "view_size": stats["light"]["view_size"],
                                "view_particles": stats["light"]["view_particles"],
                                "view_particles_left_out": stats["light"]["view_particles_left_out"],
                                  "light_prepare_ms": stats["light"]["prepare_ms"], "total_ms": stats["total_ms"],
                                  "prepare_ms": stats["prepare_ms"]}
        ply = runs.export_particles(scene_variant(directory, False, True), 1, os.path.join(directory, "export.ply"))
        vtk, _, _, _ = runs.run_vtk(scene_variant(directory, False, True), ply, os.path.join(directory, "vtk.npz"), 1,
                                    "narrow_range", ABSORPTION_RGB)
        results[frame]["VTK fluid mapper"] = score(vtk, directory, water, shadowed)
        if results[frame]["in_water"]:
            results[frame]["under_water_ratios"] = under_water_ratios(directory, composites["sun, light passes"])
        results[frame][NOISE_FLOOR] = score(rgb(os.path.join(directory, "reference_full_seed2.exr")), directory,
                                            water, shadowed)
        strip([rgb(os.path.join(directory, "reference_full.exr")), composites["no lights (before)"],
               composites["sun, light passes"], rgb(os.path.join(directory, "reference_noshadow.exr"))],
              os.path.join(IMAGES, f"light_{frame}.png"))
        passes_strip(os.path.join(directory, "spindrift_1.exr"), os.path.join(IMAGES, f"light_{frame}_passes.png"))
    world = world_light.measure(sys.modules[__name__], FRAMES)
    with open(os.path.join(OUTPUT, "results.json"), "w") as handle:
        json.dump({"results": results, "timings": timings, "renderer": renderer, "world_alone": world}, handle,
                  indent=1)
    loads = (load_before, os.getloadavg()[0])
    write_page(results, timings, renderer, arguments.samples, arguments.background_samples, loads, world)


def ratios(values):
    return " / ".join(f"{value:.2f}" for value in values)


def under_water_ratios(directory, test):
    """Per channel, the mean of `test` over the full reference's, where a camera in a box of water sees the
    floor and where it sees the walls straight through the water (no surface in between)."""
    with open(os.path.join(directory, "scene.json")) as handle, \
            open(os.path.join(directory, "shape.json")) as shape_file:
        scene, shape = json.load(handle), json.load(shape_file)["shape"]
    origin, directions = camera_rays(scene)
    forward = -np.array(scene["camera"]["world_from_camera"]).reshape(4, 4)[:3, 2]
    depth = metrics.read_channels(os.path.join(directory, "background.exr"), ["Depth.Z"])[..., 0]
    point = origin + (depth / (directions @ forward))[..., None] * directions
    low, high = np.array(shape[1]), np.array(shape[2])
    floor = (np.abs(point[..., 2]) < 0.01) & np.all(np.abs(point[..., :2]) < high[:2] - 0.02, axis=-1)
    on_side = np.any(np.abs(np.abs(point[..., :2]) - high[:2]) < 0.01, axis=-1)
    walls = on_side & (point[..., 2] > 0.02) & (point[..., 2] < high[2] - 0.05)
    full = rgb(os.path.join(directory, "reference_full.exr"))
    return {name: (test[mask].mean(axis=0) / full[mask].mean(axis=0)).tolist()
            for name, mask in (("floor", floor), ("walls", walls))}


def number(value):
    return "–" if not np.isfinite(value) else f"{value:.4f}"


def cost_cell(with_ms, without_ms):
    """What the frame of `with_ms` costs over that of `without_ms`, and its share of the former: "36 ms, 23 %"."""
    return f"{with_ms - without_ms:.0f} ms, {100 * (with_ms - without_ms) / with_ms:.0f} %"


def write_page(results, timings, renderer, samples, background_samples, loads, world):
    names = [name for name, *_ in SETTINGS] + ["VTK fluid mapper", NOISE_FLOOR]
    lines = ["# Light through the liquid: measured", "",
             "Generated by `tests/bench/thick_report.py` (do not edit by hand). Seven frames of thick water (a block",
             "resting on the floor, a ball floating above it, a pool in a tank from above, from the side and from",
             "inside, the camera under its surface, the block from five times as far, and the ball as Mantaflow",
             "bakes it; `tests/bench/thick_bodies.py`) at 480x270, Cycles at " + str(samples) +
             f" samples (background {background_samples}),",
             "the water an exact mesh with the same IOR and absorption as Spindrift's defaults, Spindrift a lattice",
             "of particles filling it; for `ball_baked`, Mantaflow's FLIP particles filling the sphere (its first",
             "frame, without gravity) and Cycles rendering Mantaflow's own mesh of them, as a user's render has it.",
             f"Spindrift ran on {renderer}.", "",
             "Image error is the mean absolute error of linear RGB. *Water*: over Cycles' own coverage of the water",
             "where no solid stands in front of it (the pool's near wall hides most of it from the side);",
             "*no-shadow* is the benchmark's old reference (the water casts no shadow), *full* a complete render",
             "(shadows and caustics by path tracing). *Shadowed floor*: outside the water, where the",
             "full reference differs from the background by more than 0.03 after a Gaussian blur of 2 px (so the",
             "references' sampling noise is not counted), 3 px or more from the water. *Blurred*: both images",
             "blurred by a Gaussian of 2 px first, which averages the references' sampling noise away. The last row",
             "is the full reference rendered again with another seed: at these samples no renderer's error can be",
             "expected below it. *Change* is against the first row (before the light passes).", ""]
    for frame in FRAMES:
        pixels = results[frame]["pixels"]
        lines += [f"## {frame}", "", f"![{frame}: full reference, before, with the sun, no-shadow reference]"
                  f"(images/light_{frame}.png)", "",
                  "Left to right: full Cycles reference; Spindrift without lights (before); Spindrift with the sun "
                  "and Cycles' light passes; the no-shadow reference.", "",
                  f"| Setting | Water vs no-shadow | Water vs full | change | Water vs full, blurred | change | "
                  f"Shadowed floor vs full ({pixels['shadowed']} px) | change |",
                  "|---|---|---|---|---|---|---|---|"]
        before = results[frame][SETTINGS[0][0]]

        def change(r, key):
            return f"{100 * (r[key] / before[key] - 1):+.0f} %" if before[key] > 0 else ""

        for name in names:
            r = results[frame][name]
            lines.append(f"| {name} | {number(r['water_vs_noshadow'])} | {number(r['water_vs_full'])} | "
                         f"{change(r, 'water_vs_full')} | {number(r['water_vs_full_blurred'])} | "
                         f"{change(r, 'water_vs_full_blurred')} | {number(r['shadow_vs_full'])} | "
                         f"{change(r, 'shadow_vs_full')} |")
        lines.append("")
        if results[frame]["in_water"]:
            lines += ["The camera is in the water: every pixel is scored, and there is no floor outside it. Cycles "
                      "renders what lies under water, lit from above it, darker than geometric optics does: a "
                      "Lambertian floor under a flat surface, lit by a uniform sky, 0.42–0.54 of the dry floor where "
                      "optics gives 1.03–1.50 (albedo 0.2 and 0.8; `tests/bench/cycles_underwater_sky.py`): 1/n² "
                      "(light that enters the water keeps its radiance instead of gaining n²) times about 0.73. "
                      "Spindrift sees a submerged solid at its lit radiance over n², from air and from under water "
                      "alike, as Cycles does (docs/liquid.md, \"Radiance under water\"). Spindrift's image (with the "
                      "sun and light passes) over Cycles', R/G/B, where the camera sees the pool's floor: "
                      f"{ratios(results[frame]['under_water_ratios']['floor'])}; its walls: "
                      f"{ratios(results[frame]['under_water_ratios']['walls'])} (their sky light: docs/liquid.md).", ""]
    lines += world_light.section(world, number)
    lines += ["## Light passes", "", "Spindrift's `liquid_shadow`, `caustics` and `liquid_sky` (red channel, black 0, white 1) "
              "and its composite, with the sun and Cycles' light passes:", ""]
    lines += [f"![{frame}: light passes](images/light_{frame}_passes.png)" for frame in FRAMES]
    lines += ["", "## Cost", "",
              "GPU time of the light passes (the lights' and the sky's depth layers, `liquid_shadow`, `caustics`, "
              "`sky_occlusion`, `lit_tiles`, `lit_background` with the sky light submerged points keep) against the whole frame's: in a one-frame process "
              "(as the "
              "tables above ran; llvmpipe compiles each shader's machine code at its first draw, inside the "
              "frame) and, *steady*, in frames 3 to 6 of a `--frames 1-6` sequence (a renderer kept alive, as the "
              "add-on and farm sequences run; the median, each pass finished before the next starts, so that "
              "llvmpipe's deferred rasterisation charges no pass with another's work). *View*: the lights' views' side in texels and the particles drawn into "
              "them (all views) of those shaped. *Sky occlusion*: that pass's part of the light passes' time "
              "(one-frame process). *Lights' CPU*: their views' preparation (shaping, culling; `light.prepare_ms`), "
              "steady. *What the lights cost a frame*: the whole frame (`total_ms`: loading, every preparation, "
              "every pass, the readback; frames 3 to 8 of a `--frames 1-8` sequence, passes not finished one by "
              "one) with the sun against the same frame without it, over the same background, each run twice, "
              "interleaved: the difference and its share of the frame with the sun. Finishing each pass (the GPU "
              "columns) adds a wait to each of the lights' many small passes, so the GPU shares overstate them. "
              "*Without*: no light at all (`light.sky_without_lamps` off), so the difference is every light pass, "
              "the sky's with the sun's. *The world alone*: the frame without the sun that takes the world's light "
              "alone (the default for a scene without lamps), which runs the sky's passes; *what the sun adds* to "
              "it is the sun's own view, shadow and caustics, what the issue's target names. Each of those frames "
              "shares the CPU with the writing of the frame before's EXR (every layer in 32-bit float, the command "
              "line's defaults), about a third of a frame here; *rendered alone*: the frames with the sun and "
              "without any light again, their EXRs written nowhere, and what the lights cost those.",
              "",
              "| Frame | View | Particles drawn | Light passes, GPU ms | Sky occlusion, GPU ms | Whole frame, GPU ms | "
              "Share | Steady: light ms | Steady: frame GPU ms | Steady share | Steady: lights' CPU ms | "
              "Frame with the sun, ms | Without, ms | What the lights cost a frame | The world alone, ms | "
              "What the sun adds to it | Rendered alone: with the sun, without, ms | What the lights cost it |",
              "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for frame in sorted(timings):
        t = timings[frame]
        drawn = t["view_particles"] - t["view_particles_left_out"]
        lines.append(f"| {frame} | {t['view_size']} | {drawn} of {t['view_particles']} | {t['light_gpu_ms']:.1f} | "
                     f"{t['sky_occlusion_gpu_ms']:.1f} | {t['frame_gpu_ms']:.1f} | {100 * t['light_gpu_ms'] / t['frame_gpu_ms']:.0f} % | "
                     f"{t['steady_light_gpu_ms']:.1f} | {t['steady_frame_gpu_ms']:.1f} | "
                     f"{100 * t['steady_light_gpu_ms'] / t['steady_frame_gpu_ms']:.0f} % | "
                     f"{t['steady_light_prepare_ms']:.1f} | {t['with_lights_ms']:.0f} | {t['without_lights_ms']:.0f} | "
                     f"{cost_cell(t['with_lights_ms'], t['without_lights_ms'])} | {t['world_alone_ms']:.0f} | "
                     f"{cost_cell(t['with_lights_ms'], t['world_alone_ms'])} | "
                     f"{t['with_lights_alone_ms']:.0f}, {t['without_lights_alone_ms']:.0f} | "
                     f"{cost_cell(t['with_lights_alone_ms'], t['without_lights_alone_ms'])} |")
    lines += ["", f"Load average (1 min) on the 2-core machine: {loads[0]:.1f} before, {loads[1]:.1f} after: the "
              "milliseconds are those of a loaded llvmpipe; the shares are what compares.", "",
              "## Path length in the water", "",
              "Spindrift's `thickness` (the whole path in liquid) against the exact length of the first refracted",
              "path through the water's true shape (to where it leaves the shape or meets the floor), median over",
              "the water's pixels, without lights:", "",
              "| Frame | Exact first path | Spindrift | Ratio (median) | Total internal reflections / liquid pixels | "
              "Paths that went on behind a solid |",
              "|---|---|---|---|---|---|"]
    for frame in FRAMES:
        p = results[frame]["path"]
        lines.append(f"| {frame}{' (camera in the water)' if results[frame]['in_water'] else ''} | "
                     f"{p['exact_median']:.3f} | {p['spindrift_median']:.3f} | {p['ratio_median']:.2f} | "
                     f"{p['total_internal_reflections']} / {p['liquid_pixels']} | {p['exits_behind_solids']} |")
    with open(PAGE, "w") as handle:
        handle.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
