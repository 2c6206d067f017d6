"""The benchmark's metrics on synthetic images whose answers are known in closed form."""

import math
import os
import sys

import numpy as np
import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import metrics  # noqa: E402

EMPTY = 1e10


def disc(size, centre, radius):
    y, x = np.mgrid[0:size, 0:size] + 0.5
    return (x - centre[0]) ** 2 + (y - centre[1]) ** 2 <= radius ** 2


def test_iou_of_two_discs_matches_the_lens_formula():
    size, radius, distance = 800, 150.0, 100.0
    a = disc(size, (400 - distance / 2, 400), radius)
    b = disc(size, (400 + distance / 2, 400), radius)
    lens = 2 * radius ** 2 * math.acos(distance / (2 * radius)) - distance / 2 * math.sqrt(
        4 * radius ** 2 - distance ** 2)
    expected = lens / (2 * math.pi * radius ** 2 - lens)
    assert metrics.silhouette_iou(a, b) == pytest.approx(expected, rel=2e-3)


def test_iou_of_identical_and_empty_masks():
    mask = disc(64, (32, 32), 10)
    assert metrics.silhouette_iou(mask, mask) == 1.0
    assert metrics.silhouette_iou(mask, np.zeros_like(mask)) == 0.0
    assert metrics.silhouette_iou(np.zeros_like(mask), np.zeros_like(mask)) == 1.0


def test_depth_offset_by_k_radii_gives_median_k():
    radius, k = 0.02, 2.5
    reference = np.full((50, 60), EMPTY)
    reference[10:40, 10:50] = np.linspace(3, 4, 40)[None, :]
    test = np.where(reference < EMPTY, reference + k * radius, EMPTY)
    median, p95 = metrics.depth_errors(test, reference, radius)
    assert median == pytest.approx(k, rel=1e-6)
    assert p95 == pytest.approx(k, rel=1e-6)


def test_depth_errors_count_only_pixels_both_cover():
    reference = np.full((20, 20), EMPTY)
    reference[:, :10] = 5.0
    test = np.full((20, 20), EMPTY)
    test[:, 5:15] = 5.1
    median, _ = metrics.depth_errors(test, reference, 0.1)
    assert median == pytest.approx(1.0, rel=1e-5)
    assert math.isnan(metrics.depth_errors(np.full((4, 4), EMPTY), reference[:4, :4], 1.0)[0])


def test_silhouette_bias_sees_only_the_edge_band():
    radius = 0.1
    reference = np.where(disc(100, (50, 50), 30), 4.0, EMPTY)
    band = metrics.edge_band(metrics.liquid_mask(reference))
    # Pulled 2 r towards the camera on the three-pixel band at the edge, and 5 r behind it inside.
    test = np.where(band, reference - 2 * radius, reference + 5 * radius)
    test[reference >= EMPTY] = EMPTY
    assert metrics.silhouette_bias(test, reference, radius) == pytest.approx(-2.0, rel=1e-6)
    inner = metrics.liquid_mask(reference) & ~band
    assert np.count_nonzero(inner) > 0
    # The band is three pixels wide: a pixel four steps from the outside is not in it.
    assert band[50, 20 + 0] and band[50, 22] and not band[50, 24]


def tilted(normals, angle_degrees):
    """Rotates unit normals about the x axis."""
    c, s = math.cos(math.radians(angle_degrees)), math.sin(math.radians(angle_degrees))
    rotation = np.array([[1, 0, 0], [0, c, -s], [0, s, c]])
    return normals @ rotation.T


def test_normal_tilted_by_theta_gives_theta():
    generator = np.random.default_rng(3)
    normals = np.zeros((30, 40, 3))
    # Vectors in the plane orthogonal to the rotation axis, so the rotation turns each by exactly theta.
    angle = generator.uniform(0, 2 * math.pi, (30, 40))
    normals[..., 1], normals[..., 2] = np.cos(angle), np.sin(angle)
    mask = np.ones((30, 40), bool)
    median, p95 = metrics.normal_angle_errors(tilted(normals, 17.0) * 3.0, normals, mask)
    assert median == pytest.approx(17.0, abs=1e-6)
    assert p95 == pytest.approx(17.0, abs=1e-6)


def test_image_errors_of_a_constant_offset():
    generator = np.random.default_rng(5)
    reference = generator.uniform(0.1, 0.8, (64, 64, 3))
    mask = disc(64, (32, 32), 20)
    mae, ssim = metrics.image_errors(reference + 0.05, reference, mask)
    assert mae == pytest.approx(0.05, rel=1e-9)
    assert ssim < 1.0
    mae, ssim = metrics.image_errors(reference, reference, mask)
    assert mae == 0.0
    assert ssim == pytest.approx(1.0)


def test_geometry_metrics_of_a_perfect_match():
    reference = np.where(disc(40, (20, 20), 12), 3.0, EMPTY)
    normals = np.zeros((40, 40, 3))
    normals[..., 2] = 1.0
    result = metrics.geometry_metrics(reference, normals, reference, normals, 0.05)
    assert result["iou"] == 1.0
    assert result["depth_median_r"] == 0.0
    assert result["silhouette_bias_r"] == 0.0
    assert result["normal_p95_deg"] == pytest.approx(0.0, abs=1e-6)


def test_visible_depth_leaves_out_liquid_behind_solids():
    depth = np.array([[1.0, 2.0, 1e10]], np.float32)
    solids = np.array([[1.5, 1.5, 3.0]], np.float32)
    visible = metrics.visible_depth(depth, solids)
    assert visible[0, 0] == 1.0
    assert not metrics.liquid_mask(visible)[0, 1]  # behind the solid
    assert not metrics.liquid_mask(visible)[0, 2]  # no liquid at all
