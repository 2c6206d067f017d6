#!/usr/bin/python3
"""Makes the pictures of docs/liquid.md from the dam-break example: the four depth layers before and after
smoothing, the normals, the thickness and the final image, plus a table of per-pass timings.

    docs/figures/make_liquid_figures.py            (after scripts/render-example; uses build/bin/spindrift)

Depth is shown as grey (near bright, far dark, over the range the liquid covers), normals as RGB = 0.5 + n/2.
"""
import json
import pathlib
import subprocess
import sys

import numpy as np
import OpenImageIO as oiio

ROOT = pathlib.Path(__file__).resolve().parents[2]
SPINDRIFT = ROOT / "build" / "bin" / "spindrift"
SCENE = ROOT / "examples" / "dam_break" / "scene.json"
WORK = ROOT / "out" / "figures"
IMAGES = ROOT / "docs" / "images"
PANEL_WIDTH = 480  # pixels; the example renders at 960x540


def read_layers(path):
    image = oiio.ImageBuf(str(path))
    pixels = image.get_pixels(oiio.FLOAT)
    names = image.spec().channelnames
    layers = {}
    for index, name in enumerate(names):
        layer, _, channel = name.rpartition(".")
        layers.setdefault(layer, {})[channel] = pixels[:, :, index]
    return layers


def write_png(array, name):
    height, width = array.shape[:2]
    buffer = oiio.ImageBuf(oiio.ImageSpec(width, height, array.shape[2], oiio.FLOAT))
    buffer.set_pixels(oiio.ROI(), np.ascontiguousarray(array, dtype=np.float32))
    scaled = oiio.ImageBufAlgo.resize(buffer, roi=oiio.ROI(0, PANEL_WIDTH, 0, PANEL_WIDTH * height // width, 0, 1, 0, array.shape[2]))
    scaled.write(str(IMAGES / name), "uint8")
    print("wrote", IMAGES / name)


def depth_panel(depth, low, high):
    grey = np.where(depth < 1e9, 1.0 - (np.clip(depth, low, high) - low) / max(high - low, 1e-6) * 0.85, 0.0)
    return np.repeat(grey[:, :, None], 3, axis=2)


def normal_panel(layer):
    normal = np.stack([layer["X"], layer["Y"], layer["Z"]], axis=2)
    covered = np.linalg.norm(normal, axis=2, keepdims=True) > 0.5
    return np.where(covered, 0.5 + 0.5 * normal, 0.0)


def srgb(linear):
    linear = np.clip(linear, 0.0, 1.0)
    return np.where(linear <= 0.0031308, 12.92 * linear, 1.055 * np.power(linear, 1 / 2.4) - 0.055)


def main():
    WORK.mkdir(parents=True, exist_ok=True)
    IMAGES.mkdir(parents=True, exist_ok=True)
    exr, stats = WORK / "liquid.exr", WORK / "liquid_stats.json"
    subprocess.run([str(SPINDRIFT), "render", str(SCENE), "-o", str(exr), "--stats", str(stats), "--intermediate", "-q"],
                   check=True)
    layers = read_layers(exr)
    covered = layers["depth"]["Z"][layers["depth"]["Z"] < 1e9]
    low, high = (np.percentile(covered, 1), np.percentile(covered, 99)) if covered.size else (0.0, 1.0)
    for group in ("splash", "aggregate", "aggregate_smoothed"):
        for side in ("front", "back"):
            name = f"{group}_{side}_depth"
            if name in layers:
                write_png(depth_panel(layers[name]["Z"], low, high), f"liquid_{name}.png")
        if f"{group}_front_normal" in layers:
            write_png(normal_panel(layers[f"{group}_front_normal"]), f"liquid_{group}_front_normal.png")
    thickness = layers["thickness"]["Y"]
    write_png(np.repeat((thickness / max(np.percentile(thickness[thickness > 0], 99), 1e-6) if (thickness > 0).any() else thickness)[:, :, None], 3, axis=2), "liquid_thickness.png")
    composite = np.stack([layers["composite"][c] for c in "RGB"], axis=2)
    write_png(srgb(composite), "liquid_composite.png")

    frame = json.loads(stats.read_text())
    print("\n| Pass | GPU ms | CPU ms |\n|---|---|---|")
    for entry in frame["passes"]:
        print(f"| {entry['name']} | {entry['gpu_ms']:.1f} | {entry['cpu_ms']:.1f} |")
    print(f"| CPU preparation | | {frame['prepare_ms']:.1f} |\n| whole frame | | {frame['total_ms']:.1f} |")
    print("\nrenderer:", frame["gl_renderer"], "\nliquid:", json.dumps(frame["liquid"]))


if __name__ == "__main__":
    sys.exit(main())
