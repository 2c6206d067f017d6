"""The benchmark's metrics: every number in docs/benchmarks.md that compares a render with a reference.

Conventions (docs/benchmarks.md, "Metrics"):
- Depth is planar eye depth, as Cycles' Depth pass and Spindrift's depth.Z; a pixel is liquid where its depth
  is below EMPTY_DEPTH (both write 1e10 where there is none).
- Depth errors are in units of the particle radius r, signed as test minus reference (positive: the test
  surface lies behind the reference surface).
- Normals are world-space unit vectors; their error is the angle between them, in degrees.
- Colours are linear RGB. The perceptual metric is SSIM (scikit-image) on the sRGB-encoded images, averaged
  over the reference's liquid pixels.
"""

import numpy as np
from scipy import ndimage
from skimage.metrics import structural_similarity

EMPTY_DEPTH = 1e9
EDGE_BAND_PIXELS = 3


def liquid_mask(depth):
    return np.isfinite(depth) & (depth < EMPTY_DEPTH)


def visible_depth(depth, solid_depth):
    """`depth` where it lies in front of the scene's solids (`solid_depth`: the background render's depth
    pass), EMPTY elsewhere. Liquid behind an opaque solid (the pool behind the drop example's stone rim) is in
    no user's render, and Spindrift hides it as Cycles does; Mantaflow's mesh rendered alone still has it, so
    every metric compares the visible liquid of both."""
    return np.where(depth < solid_depth, depth, np.float32(1e10))


def silhouette_iou(test_mask, reference_mask):
    """Intersection over union of two coverage masks; 1.0 when both are empty."""
    union = np.count_nonzero(test_mask | reference_mask)
    if union == 0:
        return 1.0
    return np.count_nonzero(test_mask & reference_mask) / union


def depth_errors(test_depth, reference_depth, radius):
    """Median and 95th percentile of |depth error| / r over the pixels both cover (NaN where none)."""
    both = liquid_mask(test_depth) & liquid_mask(reference_depth)
    if not both.any():
        return float("nan"), float("nan")
    error = np.abs(test_depth[both] - reference_depth[both]) / radius
    return float(np.median(error)), float(np.percentile(error, 95))


def edge_band(mask, width=EDGE_BAND_PIXELS):
    """The pixels of `mask` within `width` pixels (8-connected steps) of a pixel outside it."""
    inner = ndimage.binary_erosion(mask, structure=np.ones((3, 3), bool), iterations=width, border_value=0)
    return mask & ~inner


def silhouette_bias(test_depth, reference_depth, radius):
    """Mean signed depth error / r within EDGE_BAND_PIXELS of the reference liquid's edge, where both cover.

    Negative means the test surface is pulled towards the camera at its silhouette, the liquid paper's
    Problem 2 (filtering warps the depth towards the viewer at depth boundaries).
    """
    reference = liquid_mask(reference_depth)
    pixels = edge_band(reference) & liquid_mask(test_depth)
    if not pixels.any():
        return float("nan")
    return float(np.mean(test_depth[pixels] - reference_depth[pixels]) / radius)


def normal_angles(test_normals, reference_normals):
    """The angle, in degrees, between two arrays of normals (... x 3, any length), pixel by pixel."""
    a = test_normals.astype(np.float64)
    b = reference_normals.astype(np.float64)
    a /= np.maximum(np.linalg.norm(a, axis=-1, keepdims=True), 1e-12)
    b /= np.maximum(np.linalg.norm(b, axis=-1, keepdims=True), 1e-12)
    return np.degrees(np.arccos(np.clip(np.sum(a * b, axis=-1), -1.0, 1.0)))


def normal_angle_errors(test_normals, reference_normals, mask):
    """Median and 95th percentile angle, in degrees, between two H x W x 3 normal images over `mask`."""
    if not mask.any():
        return float("nan"), float("nan")
    angles = normal_angles(test_normals[mask], reference_normals[mask])
    return float(np.median(angles)), float(np.percentile(angles, 95))


def srgb_encode(linear):
    linear = np.clip(linear, 0.0, 1.0)
    return np.where(linear <= 0.0031308, 12.92 * linear, 1.055 * np.power(linear, 1 / 2.4) - 0.055)


def image_errors(test_rgb, reference_rgb, mask):
    """Mean absolute error (linear RGB, mean over channels) and mean SSIM over the pixels of `mask`."""
    if not mask.any():
        return float("nan"), float("nan")
    mae = float(np.mean(np.abs(test_rgb[mask] - reference_rgb[mask])))
    _, ssim_map = structural_similarity(srgb_encode(test_rgb), srgb_encode(reference_rgb), channel_axis=2,
                                        data_range=1.0, full=True)
    return mae, float(np.mean(ssim_map[mask]))


def geometry_metrics(test_depth, test_normals, reference_depth, reference_normals, radius):
    """Every geometric metric of one frame, as a dict keyed as the benchmark's tables are."""
    test, reference = liquid_mask(test_depth), liquid_mask(reference_depth)
    depth_median, depth_p95 = depth_errors(test_depth, reference_depth, radius)
    normal_median, normal_p95 = normal_angle_errors(test_normals, reference_normals, test & reference)
    return {
        "iou": silhouette_iou(test, reference),
        "depth_median_r": depth_median,
        "depth_p95_r": depth_p95,
        "silhouette_bias_r": silhouette_bias(test_depth, reference_depth, radius),
        "normal_median_deg": normal_median,
        "normal_p95_deg": normal_p95,
    }


def read_channels(path, names):
    """The named channels of an EXR as one H x W x len(names) float32 array (missing names are an error).

    A name may be given as a suffix ("Depth.Z" finds Blender's "ViewLayer.Depth.Z").
    """
    import OpenImageIO as oiio
    image = oiio.ImageInput.open(path)
    if image is None:
        raise RuntimeError(f"cannot open {path}: {oiio.geterror()}")
    try:
        spec = image.spec()
        pixels = image.read_image(0, 0, 0, spec.nchannels, oiio.FLOAT)
    finally:
        image.close()
    if pixels is None:
        raise RuntimeError(f"cannot read {path}")
    pixels = pixels.reshape(spec.height, spec.width, spec.nchannels)
    indices = []
    for name in names:
        matches = [i for i, channel in enumerate(spec.channelnames)
                   if channel == name or channel.endswith("." + name)]
        if not matches:
            raise RuntimeError(f"{path}: no channel {name} in {list(spec.channelnames)}")
        indices.append(matches[0])
    return pixels[:, :, indices]
