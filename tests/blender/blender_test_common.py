"""Helpers for the add-on's Blender tests (imported inside Blender by the test scripts run by run_blender.py)."""

import os
import shutil
import sys
import traceback

import bpy
import numpy as np


def arguments():
    return sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []


def scratch(*parts):
    path = os.path.join(os.environ["SPINDRIFT_TEST_DIR"], *parts)
    os.makedirs(os.path.dirname(path) if os.path.splitext(path)[1] else path, exist_ok=True)
    return path


def check(condition, message):
    if not condition:
        raise AssertionError(message)
    print(f"ok: {message}", flush=True)


def exit_on_failure():
    """Ends Blender with exit code 1 after printing the exception being handled: a failed check must fail the
    test even where Blender would only log it (timers, handlers)."""
    traceback.print_exc()
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(1)


def run(main):
    """Runs a test's main and ends Blender with its exit code: 0 when it returned, 1 when it raised."""
    try:
        main()
    except Exception:  # noqa: BLE001 - any failure ends the test with exit code 1
        exit_on_failure()
    os._exit(0)


def run_in_interface(step):
    """Installs the add-on, opens the fixture scene named first on the command line and calls `step` from a
    timer, so the interface draws between its calls (`step` returns the seconds until the next one)."""
    install_addon()
    open_fixture_scene(arguments()[0])
    bpy.app.timers.register(step, first_interval=1.0)


def install_addon():
    """Installs the add-on from its zip into the temporary user directory and enables it, as a user would."""
    zip_path = os.environ["SPINDRIFT_ADDON_ZIP"]
    result = bpy.ops.preferences.addon_install(filepath=zip_path, overwrite=True)
    check(result == {"FINISHED"}, f"addon_install of {zip_path}")
    result = bpy.ops.preferences.addon_enable(module="spindrift")
    check(result == {"FINISHED"}, "addon_enable spindrift")
    check(hasattr(bpy.types.Object, "spindrift"), "the add-on registered obj.spindrift")
    installed = os.path.join(os.environ["BLENDER_USER_SCRIPTS"], "addons", "spindrift")
    check(os.path.isdir(installed), f"installed into the temporary user directory {installed}")


def open_fixture_scene(fixture_dir):
    """Opens a copy of the baked fixture scene; its cache (`//cache`, relative to the .blend) is linked, not
    copied, and the tests never change the domain's settings (which would free the bake)."""
    blend = scratch("scene.blend")
    shutil.copy(os.path.join(fixture_dir, "scene.blend"), blend)
    cache = os.path.join(os.environ["SPINDRIFT_TEST_DIR"], "cache")
    if not os.path.exists(cache):
        os.symlink(os.path.join(fixture_dir, "cache"), cache)
    bpy.ops.wm.open_mainfile(filepath=blend)
    scene = bpy.context.scene
    scene.render.filepath = scratch("render") + "/frame_"
    return scene


def read_exr_layers(path):
    """{layer: (H, W, C) float32} of an EXR (OpenImageIO), with channel names grouped by their prefix."""
    import OpenImageIO as oiio

    source = oiio.ImageInput.open(path)
    if source is None:
        raise AssertionError(f"cannot open {path}: {oiio.geterror()}")
    layers = {}
    subimage = 0
    while source.seek_subimage(subimage, 0):
        spec = source.spec()
        pixels = source.read_image(0, spec.nchannels, oiio.FLOAT)
        for index, name in enumerate(spec.channelnames):
            layer, _, channel = name.rpartition(".")
            layers.setdefault(layer, {})[channel] = pixels[:, :, index]
        subimage += 1
    source.close()
    order = "RGBAXYZ"
    return {layer: np.stack([channels[c] for c in sorted(channels, key=lambda c: (order.find(c), c))], axis=2)
            for layer, channels in layers.items()}


def largest_view3d():
    """(window, area, region) of the largest 3D viewport of the first window, its WINDOW region."""
    window = bpy.context.window_manager.windows[0]
    area = max((a for a in window.screen.areas if a.type == "VIEW_3D"), key=lambda a: a.width * a.height)
    return window, area, next(r for r in area.regions if r.type == "WINDOW")


def preview_ready(region):
    """Whether the viewport preview has finished the frame last handed for `region`; raises when it
    failed (the region's result is then the error's text)."""
    from spindrift import viewport

    previews = viewport._state["previews"]
    image = previews.latest(region.as_pointer()) if previews else None
    if isinstance(image, str):
        raise AssertionError(f"the preview failed: {image}")
    return image is not None and image.key == viewport._state["submitted"].get(region.as_pointer())


def image_pixels(path):
    """An image file's pixels as float32 (H, W, channels), rows bottom first, as Blender loads them."""
    image = bpy.data.images.load(path)
    pixels = np.array(image.pixels[:], dtype=np.float32).reshape(image.size[1], image.size[0], image.channels)
    bpy.data.images.remove(image)
    return pixels


def spindrift_module():
    import spindrift

    return spindrift
