#!/usr/bin/python3
"""Compares the pixels of same-named images in two directories, every channel, exactly: prints one line per
file with the largest difference and exits 1 if any differs. Metadata (Blender stamps the render time into
each frame's header) is not compared.   usage: compare_images.py REFERENCE_DIR OTHER_DIR NAME..."""
import sys

import numpy as np
import OpenImageIO as oiio


def pixels(path):
    buffer = oiio.ImageBuf(path)
    if buffer.has_error:
        sys.exit(f"compare_images: cannot read {path}: {buffer.geterror()}")
    array = buffer.get_pixels(oiio.FLOAT)
    if buffer.has_error or array is None:
        sys.exit(f"compare_images: cannot read the pixels of {path}: {buffer.geterror()}")
    return list(buffer.spec().channelnames), array


def main():
    reference, other, names = sys.argv[1], sys.argv[2], sys.argv[3:]
    status = 0
    for name in names:
        (channels_a, a), (channels_b, b) = pixels(f"{reference}/{name}"), pixels(f"{other}/{name}")
        if channels_a != channels_b or a.shape != b.shape:
            print(f"{name}: channels {channels_a} {a.shape} against {channels_b} {b.shape}")
            status = 1
            continue
        same = np.array_equal(a, b, equal_nan=True)
        difference = float(np.nanmax(np.abs(a - b))) if a.size else 0.0
        print(f"{name}: {len(channels_a)} channels {a.shape[1]}x{a.shape[0]}: "
              f"{'identical' if same else f'differs, max |difference| {difference:.3g}'}")
        status |= not same
    return status


if __name__ == "__main__":
    sys.exit(main())
