#!/usr/bin/python3
"""How much of the sun reaches the floor under the examples' water: Spindrift's liquid_shadow + caustics
against an exact trace through Mantaflow's mesh and against Cycles (docs/liquid.md, "The sun under a
sheet of water").

    tests/bench/sun_report.py [--cameras topdown,oblique] [--rays 4000000] [--samples 256]

For each example and camera of the benchmark's references (build/bench/references/EXAMPLE_480x270_256spp,
made by tests/bench/benchmark.py), renders what is missing in Blender: the floor lit by the sun alone, dry
and under the water the camera does not see (references.py --sun-factor), and the exact trace
(sun_through_mesh.py). Then renders the camera's scene_sun.json with Spindrift and compares, over the
visible floor whose sunlight passes through the water, three estimates of the share of the sun's light the
floor keeps: the exact trace's, Spindrift's (liquid_shadow + caustics), and Cycles' (the two sun-only renders'
ratio). All three are blurred by a Gaussian of 2 pixels first: caustics are sharp, and the trace and Cycles
sample them with noise. Prints a Markdown table; writes docs/images/sun_under_water.png (the first example's
first camera: exact, Spindrift, Cycles; the share linear from black 0 to white 1, grey outside the mask).
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
import thick_report  # noqa: E402

REFERENCES = os.path.join(runs.REPOSITORY, "build", "bench", "references")
IMAGE = os.path.join(runs.REPOSITORY, "docs", "images", "sun_under_water.png")
HERE = os.path.dirname(os.path.abspath(__file__))
BLUR_PIXELS = 2.0
RGB = ["R", "G", "B"]


def parse_arguments():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--examples", default="dam_break,drop")
    parser.add_argument("--cameras", default="topdown,oblique")
    parser.add_argument("--rays", type=int, default=4_000_000)
    parser.add_argument("--samples", type=int, default=256)
    return parser.parse_args()


def blender(script, *arguments):
    subprocess.run(["nice", "-n", "5", "blender", "-b", "--factory-startup", "--python-exit-code", "1", "--python",
                    script, "--", *arguments], check=True, stdout=subprocess.DEVNULL)


def ensure_cycles(example, cameras, samples):
    output = os.path.join(REFERENCES, f"{example}_480x270_256spp")
    if all(os.path.isfile(os.path.join(output, camera, "sun_only_under_water.exr")) for camera in cameras):
        return
    blender(os.path.join(HERE, "references.py"), "--example", os.path.join(runs.REPOSITORY, "examples", example),
            "--output", output, "--cameras", ",".join(cameras), "--reference-spp", str(samples), "--full-references",
            "--sun-factor")


def ensure_trace(example, directory, rays):
    path = os.path.join(directory, f"sun_exact_{rays}.npz")
    if not os.path.isfile(path):
        blender(os.path.join(HERE, "sun_through_mesh.py"), "--example",
                os.path.join(runs.REPOSITORY, "examples", example), "--scene",
                os.path.join(directory, "scene_sun.json"), "--output", path, "--rays", str(rays))
    return np.load(path)


def blurred(image):
    if image.ndim == 2:
        return ndimage.gaussian_filter(image, BLUR_PIXELS)
    return np.stack([ndimage.gaussian_filter(image[..., c], BLUR_PIXELS) for c in range(image.shape[-1])], -1)


def floor_depth(camera):
    """Planar depth of the floor z = 0 through every pixel centre (inf where the ray misses it)."""
    origin, directions = thick_report.camera_rays({"camera": camera})
    forward = -np.array(camera["world_from_camera"], dtype=np.float64).reshape(4, 4)[:3, 2]
    with np.errstate(divide="ignore", invalid="ignore"):
        distance = -origin[2] / directions[..., 2]
    return np.where(distance > 0, distance * (directions @ forward), np.inf)


def compare(example, camera_name, rays):
    directory = os.path.join(REFERENCES, f"{example}_480x270_256spp", camera_name)
    with open(os.path.join(directory, "scene_sun.json"), encoding="utf-8") as handle:
        camera = json.load(handle)["camera"]
    trace = ensure_trace(example, directory, rays)
    wet, dry = trace["wet"], trace["dry"]
    exact = blurred(wet) / np.maximum(blurred(dry), 1e-9)[..., None]

    exr = os.path.join(directory, "spindrift_sun.exr")
    runs.run_spindrift(os.path.join(directory, "scene_sun.json"), exr, {}, exr + ".json")
    passes = metrics.read_channels(exr, [f"liquid_shadow.{c}" for c in RGB] + [f"caustics.{c}" for c in RGB])
    spindrift = blurred(passes[..., :3] + passes[..., 3:])

    sun_dry = metrics.read_channels(os.path.join(directory, "sun_only_dry.exr"), [f"Combined.{c}" for c in RGB])
    sun_wet = metrics.read_channels(os.path.join(directory, "sun_only_under_water.exr"),
                                    [f"Combined.{c}" for c in RGB])
    cycles = blurred(sun_wet) / np.maximum(blurred(sun_dry), 1e-6)

    # The visible floor, lit by the sun when dry, well sampled by the trace, whose sunlight the water dims.
    background_depth = metrics.read_channels(os.path.join(directory, "background.exr"), ["Depth.Z"])[..., 0]
    visible_floor = np.abs(background_depth - floor_depth(camera)) < 0.01 * background_depth
    sampled = blurred(dry) > 0.5 * np.median(dry[dry > 0])
    lit = blurred(sun_dry).mean(-1) > 0.5 * np.median(sun_dry.mean(-1)[visible_floor])
    under_water = exact.mean(-1) < 0.97
    mask = visible_floor & sampled & lit & under_water
    row = {"example": example, "camera": camera_name, "pixels": int(mask.sum())}
    for name, image in (("exact", exact), ("spindrift", spindrift), ("cycles", cycles)):
        row[name] = image[mask].mean(0)
        row[name + "_mae"] = float(np.abs(image - exact)[mask].mean())
    return row, (exact, spindrift, cycles, mask)


def write_image(panels):
    from PIL import Image
    exact, spindrift, cycles, mask = panels
    tiles = []
    for image in (exact, spindrift, cycles):
        # Linear (0 black, 1 white), not sRGB: the shares lie between 0.4 and 1, which sRGB would crowd.
        shown = np.where(mask[..., None], np.clip(image, 0, 1), 0.25)
        tiles.append((shown * 255).astype(np.uint8))
    Image.fromarray(np.concatenate(tiles, 1)).save(IMAGE)


def main():
    arguments = parse_arguments()
    cameras = arguments.cameras.split(",")
    print("| example, camera | floor pixels | exact trace (R, G, B) | Spindrift | Cycles | Spindrift's MAE to the "
          "trace | Cycles' |")
    print("|---|---|---|---|---|---|---|")
    first = None
    for example in arguments.examples.split(","):
        ensure_cycles(example, cameras, arguments.samples)
        for camera in cameras:
            row, panels = compare(example, camera, arguments.rays)
            first = first or panels
            triple = lambda values: "(" + ", ".join(f"{v:.3f}" for v in values) + ")"
            print(f"| {example}, {camera} | {row['pixels']} | {triple(row['exact'])} | {triple(row['spindrift'])} | "
                  f"{triple(row['cycles'])} | {row['spindrift_mae']:.3f} | {row['cycles_mae']:.3f} |", flush=True)
    write_image(first)


if __name__ == "__main__":
    main()
