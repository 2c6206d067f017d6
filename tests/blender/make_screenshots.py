"""Screenshots of the real add-on for docs/blender.md, taken in Blender's interface under Xvfb: the Physics
panel, the viewport preview, the Render panel and the compositor's node tree after Set Up Compositing.

Run (from the repository root, after scripts/build-addon and a ctest run that baked the fixture):
    tests/blender/run_blender.py --xvfb --screen 1280x2400 --zip build/spindrift-addon.zip \
        tests/blender/make_screenshots.py -- build/fixtures/addon_scene docs/images/blender
(a tall screen, so the properties show the add-on's panels below Blender's own without scrolling).
"""

import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import bpy  # noqa: E402

from blender_test_common import (arguments, exit_on_failure, image_pixels, preview_ready,  # noqa: E402
                                 run_in_interface)

FRAME = 5
state = {"step": 0, "started": time.time()}


def areas(kind):
    window = bpy.context.window_manager.windows[0]
    return window, [a for a in window.screen.areas if a.type == kind]


def trim(pixels, keep_last_rows=None, margin=12):
    """Crops an area's screenshot to what is drawn on its background (the tall screen leaves it mostly
    empty); with keep_last_rows, only the end of the content (where the add-on's panels are). Rows bottom
    first, as Blender's pixels."""
    import numpy as np

    background = pixels[2, pixels.shape[1] // 2]
    content = np.abs(pixels[..., :3] - background[:3]).max(axis=2) > 0.02
    content[:, :48] = False  # the properties editor's tab column is not content
    content[:6], content[-6:], content[:, -6:] = False, False, False  # nor the area's borders
    rows, columns = np.where(content.any(axis=1))[0], np.where(content.any(axis=0))[0]
    if len(rows) == 0:
        return pixels
    bottom, top = max(rows.min() - margin, 0), min(rows.max() + margin, pixels.shape[0])
    if keep_last_rows:
        top = min(top, bottom + keep_last_rows)
    left, right = max(columns.min() - margin, 0), min(columns.max() + margin, pixels.shape[1])
    return pixels[bottom:top, left:right]


def shoot(area, name, keep_last_rows=None, crop_to_content=True):
    """The window's screenshot (screen.screenshot; screenshot_area saves an empty image under Xvfb), cropped
    to the area."""
    import numpy as np

    window = bpy.context.window_manager.windows[0]
    path = os.path.join(arguments()[1], name)
    full = path + ".window.png"
    with bpy.context.temp_override(window=window, area=area):
        bpy.ops.wm.redraw_timer(type="DRAW_WIN_SWAP", iterations=1)
        bpy.ops.screen.screenshot(filepath=full)
    pixels = image_pixels(full)
    os.remove(full)
    crop = pixels[area.y:area.y + area.height, area.x:area.x + area.width]
    if crop_to_content:
        crop = trim(crop, keep_last_rows)
    else:  # the viewport: its middle, where the camera frame is
        middle = crop.shape[0] // 2
        crop = crop[max(middle - 360, 0):middle + 360]
    crop = np.ascontiguousarray(crop)
    out = bpy.data.images.new(name, crop.shape[1], crop.shape[0], alpha=crop.shape[2] == 4)
    out.pixels.foreach_set(crop.ravel()) if crop.shape[2] == 4 else out.pixels.foreach_set(
        np.concatenate([crop, np.ones(crop.shape[:2] + (1,), np.float32)], axis=2).ravel())
    out.filepath_raw = path
    out.file_format = "PNG"
    out.save()
    print(f"screenshot {path}", flush=True)


def setup():
    scene = bpy.context.scene
    scene.frame_set(FRAME)
    domain = bpy.data.objects["Domain"]
    domain.spindrift.enabled = True
    for obj in bpy.context.view_layer.objects:
        obj.select_set(obj == domain)
    bpy.context.view_layer.objects.active = domain
    bpy.ops.spindrift.setup_compositing(mode="OVER")
    _, views = areas("VIEW_3D")
    view = max(views, key=lambda a: a.width * a.height)
    space = view.spaces.active
    space.region_3d.view_perspective = "CAMERA"
    space.shading.type = "SOLID"
    space.overlay.show_overlays = False
    scene.spindrift.preview = True
    _, properties = areas("PROPERTIES")
    properties[0].spaces.active.context = "PHYSICS"


def step():
    try:
        if state["step"] == 0:
            setup()
            state["step"] = 1
            return 1.0
        if state["step"] == 1:
            _, views = areas("VIEW_3D")
            view = max(views, key=lambda a: a.width * a.height)
            view.tag_redraw()
            region = next(r for r in view.regions if r.type == "WINDOW")
            if not preview_ready(region) and time.time() - state["started"] < 300:
                return 1.0
            shoot(view, "blender_viewport.png", crop_to_content=False)
            bpy.context.scene.spindrift.preview = False
            # The panels in the large area (the add-on's come after Blender's own).
            view.ui_type = "PROPERTIES"
            state["big"] = view
            state["step"] = 1.5
            return 1.0
        if state["step"] == 1.5:
            state["big"].spaces.active.context = "PHYSICS"
            state["step"] = 2
            return 1.0
        if state["step"] == 2:
            shoot(state["big"], "blender_physics_panel.png", keep_last_rows=420)
            state["big"].spaces.active.context = "RENDER"
            state["step"] = 3
            return 1.0
        if state["step"] == 3:
            shoot(state["big"], "blender_render_panel.png", keep_last_rows=520)
            state["big"].ui_type = "CompositorNodeTree"
            state["step"] = 5
            return 1.0
        if state["step"] == 5:
            window, editors = areas("NODE_EDITOR")
            editor = editors[0]
            region = next(r for r in editor.regions if r.type == "WINDOW")
            with bpy.context.temp_override(window=window, area=editor, region=region):
                bpy.ops.node.view_all()
            shoot(editor, "blender_compositor.png", crop_to_content=False)
            tree = bpy.data.node_groups["Spindrift Over"]
            editor.spaces.active.path.append(tree, node=bpy.context.scene.node_tree.nodes["Spindrift"])
            state["step"] = 6
            return 1.0
        if state["step"] == 6:
            window, editors = areas("NODE_EDITOR")
            editor = editors[0]
            region = next(r for r in editor.regions if r.type == "WINDOW")
            with bpy.context.temp_override(window=window, area=editor, region=region):
                bpy.ops.node.view_all()
            shoot(editor, "blender_node_group.png", crop_to_content=False)
            os._exit(0)
    except Exception:  # noqa: BLE001 - any failure ends the run with exit code 1
        exit_on_failure()
    return None


run_in_interface(step)
