#!/usr/bin/python3
"""The pixel tiles a frame shades (liquid.skip_empty_tiles, foam.skip_empty_tiles) drawn over its composite.

    tests/bench/pixel_tiles_picture.py [--scene examples/dam_break/scene.json] [--output docs/images/pixel_tiles.png]

Renders the scene's frame with `--intermediate`, marks on the CPU every 16 x 16 tile that holds a pixel of a
liquid depth layer as drawn (splash and aggregate, front and back) and every tile with foam (the foam layer's
alpha is its intensity), checks both counts against the renderer's own (`liquid.tiles_shaded`,
`foam.tiles_shaded` in the stats) and writes the composite with the liquid's tiles tinted blue and the foam's
outlined in orange (docs/frame-cost.md).
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import metrics  # noqa: E402
import runs  # noqa: E402

TILE = 16  # kPixelTileSize (native/src/framedata/PixelTiles.h)
LAYERS = [f"{body}_{side}_depth.Z" for body in ("splash", "aggregate") for side in ("front", "back")]


def marked_tiles(mask):
    """Per tile, whether any pixel of `mask` lies in it. The mask's rows run from the top, as in the EXR; the
    renderer's tiles start at the bottom left (GL's window origin), so the mask is flipped for them."""
    mask = mask[::-1]
    height, width = mask.shape
    rows, columns = -(-height // TILE), -(-width // TILE)
    padded = np.zeros((rows * TILE, columns * TILE), bool)
    padded[:height, :width] = mask
    return padded.reshape(rows, TILE, columns, TILE).any(axis=(1, 3))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--scene", default=os.path.join(runs.REPOSITORY, "examples", "dam_break", "scene.json"))
    parser.add_argument("--output", default=os.path.join(runs.REPOSITORY, "docs", "images", "pixel_tiles.png"))
    arguments = parser.parse_args()
    with tempfile.TemporaryDirectory() as work:
        exr, stats_path = os.path.join(work, "frame.exr"), os.path.join(work, "stats.json")
        subprocess.run([os.path.join(runs.REPOSITORY, "build", "bin", "spindrift"), "render", arguments.scene,
                        "-q", "--intermediate", "-o", exr, "--stats", stats_path], check=True)
        with open(stats_path) as handle:
            stats = json.load(handle)
        depths = metrics.read_channels(exr, LAYERS)
        liquid = ((depths > 0) & (depths < 5e9)).any(axis=2)
        foam = metrics.read_channels(exr, ["foam.A"])[..., 0] > 0
        composite = metrics.read_channels(exr, ["composite.R", "composite.G", "composite.B"])
    liquid_tiles, foam_tiles = marked_tiles(liquid), marked_tiles(foam)
    counts = {"liquid": (int(liquid_tiles.sum()), stats["liquid"]["tiles_shaded"], stats["liquid"]["tiles"]),
              "foam": (int(foam_tiles.sum()), stats["foam"]["tiles_shaded"], stats["foam"]["tiles"])}
    for name, (cpu, gpu, total) in counts.items():
        print(f"{name}: {cpu} tiles marked on the CPU, {gpu} by the renderer, of {total}")
    if any(cpu != gpu for cpu, gpu, _ in counts.values()):
        sys.exit("pixel_tiles_picture: the renderer's tile counts differ from the layers'")

    picture = np.clip(composite, 0, 1) ** (1 / 2.2)
    height, width = liquid.shape
    expand = lambda tiles: np.kron(tiles, np.ones((TILE, TILE), bool))[:height, :width][::-1]  # noqa: E731
    liquid_pixels, foam_pixels = expand(liquid_tiles), expand(foam_tiles)
    picture[liquid_pixels] = 0.6 * picture[liquid_pixels] + 0.4 * np.array([0.2, 0.45, 1.0])
    edge = foam_pixels & ~(np.roll(foam_pixels, 1, 0) & np.roll(foam_pixels, -1, 0) & np.roll(foam_pixels, 1, 1)
                           & np.roll(foam_pixels, -1, 1))
    picture[edge] = [1.0, 0.55, 0.1]
    grid = np.zeros_like(liquid)
    grid[height - 1::-TILE, :] = grid[:, ::TILE] = True
    picture[grid & ~liquid_pixels] *= 0.85
    import OpenImageIO as oiio
    output = oiio.ImageOutput.create(arguments.output)
    output.open(arguments.output, oiio.ImageSpec(width, height, 3, "uint8"))
    if not output.write_image(np.ascontiguousarray((picture * 255 + 0.5).astype(np.uint8))):
        sys.exit(f"pixel_tiles_picture: {output.geterror()}")
    output.close()
    print(f"wrote {arguments.output}")


if __name__ == "__main__":
    main()
