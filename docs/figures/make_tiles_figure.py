#!/usr/bin/python3
"""Makes docs/images/pixel_tiles.png for docs/frame-cost.md: the pixel tiles a frame shades
(liquid.skip_empty_tiles, foam.skip_empty_tiles) drawn over its composite.

    docs/figures/make_tiles_figure.py [--scene examples/dam_break/scene.json] [--output docs/images/pixel_tiles.png]
    (after scripts/build; uses build/bin/spindrift)

Renders the scene's frame with `--intermediate`, marks on the CPU every 16 x 16 tile that holds a pixel of a
liquid depth layer as drawn (splash and aggregate, front and back) and every tile with foam (the foam layer's
alpha is its intensity), checks both counts against the renderer's own (`liquid.tiles_shaded`,
`foam.tiles_shaded` in the stats) and writes the composite with the liquid's tiles tinted blue and the foam's
outlined in orange (docs/frame-cost.md).
"""

import argparse
import json
import pathlib
import subprocess
import sys
import tempfile

import numpy as np
import OpenImageIO as oiio

ROOT = pathlib.Path(__file__).resolve().parents[2]
SPINDRIFT = ROOT / "build" / "bin" / "spindrift"

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


def channels(path, names):
    """The named channels of an EXR as one H x W x len(names) float32 array, rows from the top."""
    image = oiio.ImageInput.open(str(path))
    if image is None:
        sys.exit(f"make_tiles_figure: cannot open {path}: {oiio.geterror()}")
    spec = image.spec()
    pixels = image.read_image(0, 0, 0, spec.nchannels, oiio.FLOAT)
    image.close()
    return np.stack([pixels[:, :, spec.channelnames.index(name)] for name in names], axis=2)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--scene", default=str(ROOT / "examples" / "dam_break" / "scene.json"))
    parser.add_argument("--output", default=str(ROOT / "docs" / "images" / "pixel_tiles.png"))
    arguments = parser.parse_args()
    with tempfile.TemporaryDirectory() as work:
        exr, stats_path = pathlib.Path(work) / "frame.exr", pathlib.Path(work) / "stats.json"
        subprocess.run([str(SPINDRIFT), "render", arguments.scene, "-q", "--intermediate", "-o", str(exr),
                        "--stats", str(stats_path)], check=True)
        with open(stats_path) as handle:
            stats = json.load(handle)
        depths = channels(exr, LAYERS)
        liquid = ((depths > 0) & (depths < 5e9)).any(axis=2)
        foam = channels(exr, ["foam.A"])[..., 0] > 0
        composite = channels(exr, ["composite.R", "composite.G", "composite.B"])
    liquid_tiles, foam_tiles = marked_tiles(liquid), marked_tiles(foam)
    counts = {"liquid": (int(liquid_tiles.sum()), stats["liquid"]["tiles_shaded"], stats["liquid"]["tiles"]),
              "foam": (int(foam_tiles.sum()), stats["foam"]["tiles_shaded"], stats["foam"]["tiles"])}
    for name, (cpu, gpu, total) in counts.items():
        print(f"{name}: {cpu} tiles marked on the CPU, {gpu} by the renderer, of {total}")
    if any(cpu != gpu for cpu, gpu, _ in counts.values()):
        sys.exit("make_tiles_figure: the renderer's tile counts differ from the layers'")

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
    output = oiio.ImageOutput.create(arguments.output)
    output.open(arguments.output, oiio.ImageSpec(width, height, 3, "uint8"))
    if not output.write_image(np.ascontiguousarray((picture * 255 + 0.5).astype(np.uint8))):
        sys.exit(f"make_tiles_figure: {output.geterror()}")
    output.close()
    print(f"wrote {arguments.output}")


if __name__ == "__main__":
    main()
