#!/usr/bin/python3
"""Makes docs/images/coverage_masks.png for docs/frame-cost.md: which pixels of the dam-break example's frame
the passes limited to the liquid and the foam shade (gl/LayerCoverage.h).

    docs/figures/make_coverage_figure.py   (after scripts/build; uses build/bin/spindrift)

Renders the example's frame once with --stats and shows the composite, the pixels where a refraction path
starts (the refraction and, within them, each smoothing iteration) and the foam's pixels (the foam's blur and
upsampling), each with its share of the frame and the pass's samples_passed from the stats.
"""
import json
import pathlib
import subprocess

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import OpenImageIO as oiio  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]
SPINDRIFT = ROOT / "build" / "bin" / "spindrift"
SCENE = ROOT / "examples" / "dam_break" / "scene.json"
WORK = ROOT / "out" / "coverage_figure"
IMAGE = ROOT / "docs" / "images" / "coverage_masks.png"


def channels(image, names):
    spec = image.spec()
    pixels = image.get_pixels(oiio.FLOAT)
    return np.stack([pixels[:, :, spec.channelnames.index(name)] for name in names], axis=2)


def srgb(linear):
    linear = np.clip(linear, 0.0, 1.0)
    return np.where(linear <= 0.0031308, 12.92 * linear, 1.055 * np.power(linear, 1 / 2.4) - 0.055)


def main():
    WORK.mkdir(parents=True, exist_ok=True)
    exr, stats_path = WORK / "frame.exr", WORK / "frame.json"
    subprocess.run([str(SPINDRIFT), "render", str(SCENE), "-o", str(exr), "--stats", str(stats_path), "-q"],
                   check=True)
    stats = json.loads(stats_path.read_text())
    samples = {entry["name"]: entry["samples_passed"] for entry in stats["passes"]}
    image = oiio.ImageBuf(str(exr))
    colour = srgb(channels(image, ["composite.R", "composite.G", "composite.B"]))
    liquid = channels(image, ["depth.Z"])[:, :, 0] < 1e9
    foam = channels(image, ["foam.A"])[:, :, 0] > 0.0
    pixels = liquid.size

    def shaded(mask, tint):
        shown = 0.35 * colour
        shown[mask] = 0.4 * colour[mask] + 0.6 * np.array(tint)
        return shown

    panels = [
        (colour, "composite"),
        (shaded(liquid, [0.2, 0.6, 1.0]),
         f"refraction and smoothing: {liquid.sum():,} pixels ({100 * liquid.sum() / pixels:.0f} %)\n"
         f"refraction samples_passed {samples['refraction']:,} = packing {pixels:,} + paths"),
        (shaded(foam, [1.0, 0.8, 0.2]),
         f"foam blur and upsampling: {foam.sum():,} pixels ({100 * foam.sum() / pixels:.1f} %)\n"
         f"foam_blur samples_passed {samples['foam_blur']:,} (two runs)"),
    ]
    figure, axes = plt.subplots(1, 3, figsize=(15, 3.8))
    for axis, (picture, title) in zip(axes, panels):
        axis.imshow(picture)
        axis.set_title(title, fontsize=9)
        axis.axis("off")
    figure.tight_layout()
    figure.savefig(IMAGE, dpi=100, bbox_inches="tight")
    print(f"wrote {IMAGE}")


if __name__ == "__main__":
    main()
