"""A camera with lens shift (an off-axis projection) in the final render's layers: the layers must be the
unshifted camera's, moved by the pixel offset Blender's own projection (world_to_camera_view) gives the
liquid, and refraction_uv must point at the same background pixels, re-expressed over the shifted image.

Run: run_blender.py --zip ZIP test_lens_shift.py -- FIXTURE_DIR
"""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import bpy  # noqa: E402
import numpy as np  # noqa: E402
from bpy_extras.object_utils import world_to_camera_view  # noqa: E402
from mathutils import Vector  # noqa: E402

from blender_test_common import (arguments, check, install_addon, open_fixture_scene, read_exr_layers,  # noqa: E402
                                 run, scratch, spindrift_module)

WIDTH, HEIGHT = 160, 120
# Shifts are in units of the larger image side: 0.1 x 160 = 16 px, -0.05 x 160 = -8 px, whole pixels, so the
# shifted window lies exactly on the larger camera's pixel grid and the comparison is pixel for pixel.
SHIFT = (0.1, -0.05)


def render(scene, name):
    module = spindrift_module()
    path = scratch("layers", f"{name}.exr")
    module.render_layer.render_frame(scene, bpy.context.evaluated_depsgraph_get(), 5, path)
    return read_exr_layers(path)


def blender_pixel(scene, point):
    """Pixel coordinates (x right, y down) of a world point by Blender's own camera projection."""
    x, y, _depth = world_to_camera_view(scene, scene.camera, Vector(point))
    return np.array([x * WIDTH, (1.0 - y) * HEIGHT])


def main():
    install_addon()
    scene = open_fixture_scene(arguments()[0])
    scene.render.resolution_x, scene.render.resolution_y, scene.render.resolution_percentage = WIDTH, HEIGHT, 100
    bpy.data.objects["Domain"].spindrift.enabled = True
    scene.spindrift.all_layers = True
    scene.frame_set(5)
    camera = scene.camera.data
    centre = bpy.data.objects["Domain"].matrix_world.translation

    plain = render(scene, "plain")
    before = blender_pixel(scene, centre)
    camera.shift_x, camera.shift_y = SHIFT
    module = spindrift_module()
    description, crop = module.export.render_camera(scene, bpy.context.evaluated_depsgraph_get())
    check(crop is not None and crop[2:] == (WIDTH, HEIGHT), f"a shifted camera renders {description['width']}x"
          f"{description['height']} and is cut to {crop}")
    shifted = render(scene, "shifted")
    offset = blender_pixel(scene, centre) - before
    dx, dy = (int(round(v)) for v in offset)
    check(np.allclose(offset, [dx, dy], atol=1e-3) and (dx, dy) != (0, 0),
          f"Blender's projection moves the image by ({offset[0]:.3f}, {offset[1]:.3f}) px")
    check(shifted["liquid"].shape[:2] == (HEIGHT, WIDTH), "the shifted layers have the render's size")

    # shifted[y, x] sees what plain[y - dy, x - dx] sees: compare over the part both images cover.
    def overlap(image_shifted, image_plain):
        ys, xs = slice(max(dy, 0), HEIGHT + min(dy, 0)), slice(max(dx, 0), WIDTH + min(dx, 0))
        ys_plain, xs_plain = slice(max(-dy, 0), HEIGHT + min(-dy, 0)), slice(max(-dx, 0), WIDTH + min(-dx, 0))
        return image_shifted[ys, xs], image_plain[ys_plain, xs_plain]

    alpha_shifted, alpha_plain = overlap(shifted["liquid"][..., 3], plain["liquid"][..., 3])
    moved = float(np.abs(alpha_shifted - alpha_plain).mean())
    unmoved = float(np.abs(shifted["liquid"][..., 3] - plain["liquid"][..., 3]).mean())
    check((alpha_plain > 0.5).sum() > 200, f"{int((alpha_plain > 0.5).sum())} liquid pixels to compare")
    check(moved < 0.01, f"liquid alpha matches Blender's shifted projection (mean |difference| {moved:.4f})")
    check(unmoved > 5 * max(moved, 1e-3), f"and the shift is visible (unshifted against shifted: {unmoved:.4f})")

    uv_shifted, uv_plain = overlap(shifted["refraction_uv"], plain["refraction_uv"])
    both = (uv_shifted[..., 2] > 0) & (uv_plain[..., 2] > 0)
    # The same background pixel, counted from the shifted image's corner: x - dx, and rows from the bottom.
    expected_u = (uv_plain[..., 0] * WIDTH + dx) / WIDTH
    expected_v = (uv_plain[..., 1] * HEIGHT - dy) / HEIGHT
    inside = both & (expected_u > 1 / WIDTH) & (expected_u < 1 - 1 / WIDTH) & (expected_v > 1 / HEIGHT) & (
        expected_v < 1 - 1 / HEIGHT)
    error_px = np.hypot((uv_shifted[..., 0] - expected_u) * WIDTH, (uv_shifted[..., 1] - expected_v) * HEIGHT)
    check(inside.sum() > 100, f"{int(inside.sum())} refracting pixels to compare")
    median = float(np.median(error_px[inside]))
    check(median < 0.05, f"refraction_uv reads the same background pixel (median error {median:.4f} px)")
    uv = shifted["refraction_uv"]
    valid = uv[..., 2] > 0
    check(((uv[..., :2][valid] > 0) & (uv[..., :2][valid] < 1)).all(), "every shifted UV lies inside the image")
    print("test_lens_shift: passed", flush=True)


run(main)
