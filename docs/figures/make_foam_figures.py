"""Makes the pictures of docs/foam.md from the dam-break example's EXR files.

    build-foam/bin/spindrift render examples/dam_break/scene.json -o out/foam.exr --stats out/foam.json
    build-foam/bin/spindrift render examples/dam_break/scene_foam_only.json -o out/foam_only.exr
    /usr/bin/python3 docs/figures/make_foam_figures.py out/foam.exr out/foam_only.exr docs/images

Every picture is the region of the frame that holds foam (the bounding box of its pixels, with a margin), the
same region in each, as an 8-bit PNG: thickness in false colour (blue thin, red thick, as the paper's figure
3a), intensity and the inverted shadow in grey, irradiance and the composites in sRGB.
"""

import sys

import numpy as np
import OpenImageIO as oiio


def read_layers(path):
    """{layer name: array (height, width, channels)} of a Spindrift multilayer EXR."""
    image = oiio.ImageBuf(path)
    pixels = image.get_pixels(oiio.FLOAT)
    layers = {}
    for index, name in enumerate(image.spec().channelnames):
        layer, _, channel = name.rpartition(".")
        layers.setdefault(layer, []).append(pixels[:, :, index])
    return {name: np.stack(channels, axis=-1) for name, channels in layers.items()}


def foam_region(alpha, margin=24):
    rows, columns = np.nonzero(alpha > 1e-3)
    height, width = alpha.shape
    if rows.size == 0:
        return slice(0, height), slice(0, width)
    return (slice(max(rows.min() - margin, 0), min(rows.max() + margin, height)),
            slice(max(columns.min() - margin, 0), min(columns.max() + margin, width)))


def srgb(linear):
    linear = np.clip(linear, 0.0, 1.0)
    return np.where(linear <= 0.0031308, 12.92 * linear, 1.055 * np.power(linear, 1.0 / 2.4) - 0.055)


def false_colour(values):
    """Blue (thinnest) through green to red (thickest), black where there is none."""
    positive = values > 0
    scaled = np.zeros_like(values)
    if positive.any():
        scaled[positive] = np.clip(values[positive] / np.percentile(values[positive], 99), 0.0, 1.0)
    rgb = np.stack([np.clip(2 * scaled - 1, 0, 1), 1 - np.abs(2 * scaled - 1), np.clip(1 - 2 * scaled, 0, 1)], -1)
    return rgb * positive[..., None]


def write_png(path, rgb):
    pixels = (np.clip(rgb, 0.0, 1.0) * 255 + 0.5).astype(np.uint8)
    if pixels.ndim == 2:
        pixels = pixels[..., None]
    output = oiio.ImageOutput.create(path)
    output.open(path, oiio.ImageSpec(pixels.shape[1], pixels.shape[0], pixels.shape[2], oiio.UINT8))
    output.write_image(pixels)
    output.close()
    print(f"wrote {path} ({pixels.shape[1]}x{pixels.shape[0]})")


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    both, foam_only, directory = sys.argv[1:]
    layers = read_layers(both)
    region = foam_region(layers["foam"][..., 3])
    crop = lambda image: image[region]
    write_png(f"{directory}/foam_thickness.png", crop(false_colour(layers["foam_thickness"][..., 0])))
    write_png(f"{directory}/foam_intensity.png", crop(layers["foam"][..., 3]))
    # Inverted, as the paper's figure 3c: white is unshadowed, and pixels without foam stay white.
    write_png(f"{directory}/foam_shadow.png", crop(1.0 - layers["foam_shadow"]))
    write_png(f"{directory}/foam_irradiance.png", crop(srgb(layers["foam_irradiance"])))
    write_png(f"{directory}/foam_layer.png", crop(srgb(layers["foam"][..., :3])))
    write_png(f"{directory}/foam_composite.png", crop(srgb(layers["composite"][..., :3])))
    without_foam = layers["composite"][..., :3] - layers["foam"][..., :3]
    without_foam /= np.maximum(1.0 - layers["foam"][..., 3:], 1e-6)
    write_png(f"{directory}/foam_before.png", crop(srgb(without_foam)))
    only = read_layers(foam_only)
    write_png(f"{directory}/foam_only_composite.png", crop(srgb(only["composite"][..., :3])))


if __name__ == "__main__":
    main()
