#!/usr/bin/python3
"""Makes the pictures and the timing table of docs/raymarch.md from the dam-break example.

    docs/figures/make_raymarch_figures.py [--width 480]   (after scripts/render-example; uses build/bin/spindrift)

Renders the example's frame four times, interleaved `--repeats` times for the timings: the screen-space
surface (the default), and the ray-marched surface with adaptive steps at full resolution, uniform steps at full
resolution (one ray per pixel each, so their step counts compare ray for ray) and the defaults (adaptive steps
and adaptive tiles). Writes the step-count heat maps on one colour scale, the tile resolution map over the
composite, the composites side by side, and prints the timing table in Markdown.
"""
import argparse
import json
import os
import pathlib
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import OpenImageIO as oiio  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]
SPINDRIFT = ROOT / "build" / "bin" / "spindrift"
SCENE = ROOT / "examples" / "dam_break" / "scene.json"
WORK = ROOT / "out" / "raymarch_figures"
IMAGES = ROOT / "docs" / "images"

RUNS = {
    "screen": {},
    "raymarch_adaptive_full": {"liquid.surface": "raymarch", "liquid.raymarch_resolution": "full"},
    "raymarch_uniform_full": {"liquid.surface": "raymarch", "liquid.raymarch_resolution": "full",
                              "liquid.raymarch_stepping": "uniform"},
    "raymarch": {"liquid.surface": "raymarch"},
}


def read_layers(path):
    image = oiio.ImageBuf(str(path))
    pixels = image.get_pixels(oiio.FLOAT)
    layers = {}
    for index, name in enumerate(image.spec().channelnames):
        layer, _, channel = name.rpartition(".")
        layers.setdefault(layer, {})[channel] = pixels[:, :, index]
    return layers


def srgb(linear):
    linear = np.clip(linear, 0.0, 1.0)
    return np.where(linear <= 0.0031308, 12.92 * linear, 1.055 * np.power(linear, 1 / 2.4) - 0.055)


def composite(layers):
    return srgb(np.stack([layers["composite"][c] for c in "RGB"], axis=2))


def scene_at_width(width):
    """The example's scene at `width` pixels wide (same aspect), its paths made absolute, under WORK."""
    description = json.loads(SCENE.read_text())
    camera = description["camera"]
    camera["height"] = round(camera["height"] * width / camera["width"])
    camera["width"] = width
    for source in description["particles"]:
        source["path"] = str(SCENE.parent / source["path"])
    if "image" in description.get("background", {}):
        description["background"]["image"] = str(SCENE.parent / description["background"]["image"])
    path = WORK / f"scene_{width}.json"
    path.write_text(json.dumps(description, indent=1))
    return path


def render(scene, name, settings, repeat):
    exr, stats = WORK / f"{name}.exr", WORK / f"{name}_{repeat}.json"
    command = [str(SPINDRIFT), "render", str(scene), "-o", str(exr), "--stats", str(stats), "--intermediate", "-q"]
    for key, value in settings.items():
        command += ["--set", f"{key}={json.dumps(value)}"]
    subprocess.run(command, check=True)
    return json.loads(stats.read_text())


def heat_map(steps, title, path, vmax):
    figure, axis = plt.subplots(figsize=(6.4, 3.9), dpi=100)
    shown = np.ma.masked_where(steps <= 0, steps)
    # Logarithmic: most rays take a few steps, rays that cross to a body behind take hundreds.
    image = axis.imshow(shown, cmap="inferno", norm=matplotlib.colors.LogNorm(vmin=1, vmax=vmax),
                        interpolation="nearest")
    axis.set_facecolor("black")
    axis.set_title(title, fontsize=10)
    axis.set_xticks([])
    axis.set_yticks([])
    figure.colorbar(image, ax=axis, fraction=0.03, pad=0.02, label="steps of the pixel's ray")
    figure.tight_layout()
    figure.savefig(path)
    plt.close(figure)
    print("wrote", path)


def tile_map(background, spacing, path, title):
    colours = {1: (0.85, 0.15, 0.1), 2: (0.95, 0.75, 0.1), 4: (0.2, 0.75, 0.3)}
    overlay = background.copy()
    for value, colour in colours.items():
        overlay[spacing == value] = 0.45 * overlay[spacing == value] + 0.55 * np.array(colour)
    figure, axis = plt.subplots(figsize=(6.4, 3.9), dpi=100)
    axis.imshow(overlay, interpolation="nearest")
    axis.set_title(title, fontsize=10)
    axis.set_xticks([])
    axis.set_yticks([])
    handles = [plt.Rectangle((0, 0), 1, 1, color=c) for c in colours.values()]
    axis.legend(handles, ["full", "half", "quarter"], loc="lower right", fontsize=8)
    figure.tight_layout()
    figure.savefig(path)
    plt.close(figure)
    print("wrote", path)


def write_png(array, path):
    height, width = array.shape[:2]
    buffer = oiio.ImageBuf(oiio.ImageSpec(width, height, 3, oiio.FLOAT))
    buffer.set_pixels(oiio.ROI(), np.ascontiguousarray(array, dtype=np.float32))
    buffer.write(str(path), "uint8")
    print("wrote", path)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--width", type=int, default=480)
    parser.add_argument("--repeats", type=int, default=3)
    arguments = parser.parse_args()
    WORK.mkdir(parents=True, exist_ok=True)
    IMAGES.mkdir(parents=True, exist_ok=True)
    scene = scene_at_width(arguments.width)
    load_before = os.getloadavg()
    stats = {name: [] for name in RUNS}
    for repeat in range(arguments.repeats):  # interleaved, so load changes hit every mode alike
        for name, settings in RUNS.items():
            stats[name].append(render(scene, name, settings, repeat))
    load_after = os.getloadavg()
    layers = {name: read_layers(WORK / f"{name}.exr") for name in RUNS}

    adaptive, uniform = layers["raymarch_adaptive_full"], layers["raymarch_uniform_full"]
    vmax = float(np.percentile(uniform["raymarch_steps"]["Y"][uniform["raymarch_steps"]["Y"] > 0], 99))
    for name, label in (("raymarch_uniform_full", "uniform"), ("raymarch_adaptive_full", "adaptive")):
        frame = stats[name][-1]["raymarch"]
        heat_map(layers[name]["raymarch_steps"]["Y"],
                 f"{label} steps, one ray per pixel: {frame['average_steps_per_ray']:.2f} steps, "
                 f"{frame['density_evaluations_per_ray']:.2f} densities per ray",
                 IMAGES / f"raymarch_steps_{label}.png", vmax)
    frame = stats["raymarch"][-1]["raymarch"]
    tiles = frame["tiles"]
    tile_map(composite(layers["raymarch"]), layers["raymarch"]["raymarch_ray_spacing"]["Y"],
             IMAGES / "raymarch_tiles.png",
             f"ray spacing per tile: {tiles['full']} full, {tiles['half']} half, {tiles['quarter']} quarter; "
             f"{frame['rays_cast']:,} rays")
    write_png(np.concatenate([composite(layers["screen"]), composite(layers["raymarch"])], axis=1),
              IMAGES / "raymarch_composite_screen_vs_raymarch.png")

    names = []
    for name in RUNS:
        for entry in stats[name][-1]["passes"]:
            if entry["name"] not in names:
                names.append(entry["name"])
    median = lambda values: float(np.median(values))  # noqa: E731
    print(f"\n{stats['screen'][-1]['gl_renderer']}, {arguments.width} px wide, median of {arguments.repeats} "
          f"interleaved runs; load average {load_before[0]:.1f} before, {load_after[0]:.1f} after\n")
    print("| pass (GPU ms) | " + " | ".join(RUNS) + " |\n|---|" + "---|" * len(RUNS))
    for pass_name in names:
        cells = []
        for name in RUNS:
            values = [e["gpu_ms"] for s in stats[name] for e in s["passes"] if e["name"] == pass_name]
            cells.append(f"{median(values):.1f}" if values else "")
        print(f"| {pass_name} | " + " | ".join(cells) + " |")
    for key, label in (("prepare_ms", "CPU preparation"), ("total_ms", "whole frame")):
        print(f"| {label} | " + " | ".join(f"{median([s[key] for s in stats[n]]):.1f}" for n in RUNS) + " |")
    for name in RUNS:
        if stats[name][-1].get("raymarch"):
            print(name, json.dumps(stats[name][-1]["raymarch"]))


if __name__ == "__main__":
    sys.exit(main())
