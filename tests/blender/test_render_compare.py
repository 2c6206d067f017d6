"""The final-frame workflow end to end, under blender -b with the add-on installed from its zip:

1. enable Spindrift on the baked fixture domain and run bpy.ops.spindrift.setup_compositing(mode='OVER');
2. render frame 5 with Cycles (4 samples) and save the Render Result with save_render as a multilayer EXR:
   the compositor's image, and Render Layers' Combined and Depth (the background without the liquid);
3. export the same frame as a scene file over that background and render it with the CLI;
4. compare the compositor's image with the CLI's composite layer (tolerances in docs/blender.md);
5. save the .blend and run `blender -b shot.blend -a` over frames 4-6: three EXRs of layers.

Run: run_blender.py --zip ZIP test_render_compare.py -- FIXTURE_DIR SPINDRIFT_CLI [RESULTS_JSON]
"""

import json
import os
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import bpy  # noqa: E402
import numpy as np  # noqa: E402

from blender_test_common import (arguments, check, install_addon, open_fixture_scene, read_exr_layers,  # noqa: E402
                                 scratch)

FRAME = 5
# Compositor against CLI (docs/blender.md). The refracted light (the render seen through the liquid, times its
# transmittance) must agree: both read the same background texels, but Blender 3.4's Map UV filters its look-up
# (EWA over the UV's derivatives, about a 3x3 blur here; it has no nearest option), which on this checker floor
# measured 0.022 mean; Map UV left out (the render unrefracted) measures 0.096. The reflected light cannot
# agree exactly: the layers are rendered before Cycles has produced the render, so the liquid's reflections of
# the scene see the world colour where the CLI sees the render; it is measured, not bounded.
MAX_MEAN_ABS_DIFFERENCE = 0.01               # whole image, RGB
MAX_TRANSMITTED_MEAN_ABS_DIFFERENCE = 0.04   # (composite - reflection) over liquid without foam
MAX_TRANSMITTED_FRACTION_OVER_0_05 = 0.2


def render_frame(scene):
    """Renders the frame; returns the compositor's image and a background EXR (Render Layers' Combined and
    Depth, the render without the liquid) written from the same Render Result."""
    scene.frame_set(FRAME)
    started = time.perf_counter()
    bpy.ops.render.render(write_still=False)
    seconds = time.perf_counter() - started
    settings = scene.render.image_settings
    settings.file_format, settings.color_depth = "OPEN_EXR_MULTILAYER", "32"
    result_path = scratch("blender_result.exr")
    bpy.data.images["Render Result"].save_render(result_path, scene=scene)
    layers = read_exr_layers(result_path)
    composite = layers["Composite.Combined"]
    background = np.concatenate([layers["ViewLayer.Combined"], layers["ViewLayer.Depth"]], axis=2)
    background_path = scratch("background.exr")
    write_exr(background_path, background, ["R", "G", "B", "A", "Z"])
    return composite, background, background_path, seconds


def write_exr(path, pixels, channels):
    import OpenImageIO as oiio

    spec = oiio.ImageSpec(pixels.shape[1], pixels.shape[0], len(channels), oiio.FLOAT)
    spec.channelnames = tuple(channels)
    output = oiio.ImageOutput.create(path)
    check(output.open(path, spec) and output.write_image(np.ascontiguousarray(pixels, dtype=np.float32)),
          f"wrote {os.path.basename(path)}")
    output.close()


def compare(blender, cli_path, background, layers):
    """Metrics of the compositor's image against the CLI's composite; `layers` is the EXR the add-on wrote in
    the render (the compositor's inputs)."""
    cli = read_exr_layers(cli_path)
    composite, liquid = cli["composite"], cli["liquid"]
    check(blender.shape == composite.shape, f"same size {blender.shape} and {composite.shape}")
    for name, image in (("blender", blender), ("cli", composite)):
        check(np.isfinite(image).all(), f"{name} composite is finite everywhere")
    difference = np.abs(blender[..., :3] - composite[..., :3]).max(axis=2)
    # Interior liquid pixels without foam, whose final ray reads the background in both renders.
    clean = ((liquid[..., 3] > 0.999) & (cli["foam"][..., 3] < 1e-3) & (layers["foam"][..., 3] < 1e-3)
             & (cli["refraction_uv"][..., 2] > 0.5) & (layers["refraction_uv"][..., 2] > 0.5))
    transmitted_blender = blender[..., :3] - layers["reflection"][..., :3]
    transmitted_cli = composite[..., :3] - cli["reflection"][..., :3]
    transmitted = np.abs(transmitted_blender - transmitted_cli).max(axis=2)[clean]
    reflected = np.abs(layers["reflection"][..., :3] - cli["reflection"][..., :3]).max(axis=2)[clean]
    background_rgb = background[..., :3]
    changed = np.abs(composite[..., :3] - background_rgb).max(axis=2) > 0.02
    blender_changed = np.abs(blender[..., :3] - background_rgb).max(axis=2) > 0.02
    metrics = {
        "liquid_fraction": float((liquid[..., 3] > 0.5).mean()),
        "clean_liquid_pixels": int(clean.sum()),
        "mean_abs_difference": float(difference.mean()),
        "max_abs_difference": float(difference.max()),
        "fraction_over_0_1": float((difference > 0.1).mean()),
        "transmitted_mean_abs_difference": float(transmitted.mean()),
        "transmitted_fraction_over_0_05": float((transmitted > 0.05).mean()),
        "reflected_mean_abs_difference": float(reflected.mean()),
        "changed_pixels_agreement": float((blender_changed & changed).sum() / max(changed.sum(), 1)),
    }
    print("compare:", json.dumps(metrics), flush=True)
    check(metrics["liquid_fraction"] > 0.01, f"the frame shows liquid ({metrics['liquid_fraction']:.3f})")
    check(metrics["clean_liquid_pixels"] > 100, f"{metrics['clean_liquid_pixels']} liquid pixels to compare")
    check(metrics["changed_pixels_agreement"] > 0.8,
          f"the compositor changed the pixels the CLI changed ({metrics['changed_pixels_agreement']:.3f})")
    check(metrics["mean_abs_difference"] < MAX_MEAN_ABS_DIFFERENCE,
          f"mean |difference| {metrics['mean_abs_difference']:.4f}")
    check(metrics["transmitted_mean_abs_difference"] < MAX_TRANSMITTED_MEAN_ABS_DIFFERENCE,
          f"refracted light: mean |difference| {metrics['transmitted_mean_abs_difference']:.4f}")
    check(metrics["transmitted_fraction_over_0_05"] < MAX_TRANSMITTED_FRACTION_OVER_0_05,
          f"refracted light: pixels off by > 0.05: {metrics['transmitted_fraction_over_0_05']:.4f}")
    return metrics


def animation(scene):
    """Saves the .blend and renders frames 4-6 with `blender -b shot.blend -a` (the add-on enabled in the
    saved preferences, nothing clicked)."""
    scene.frame_start, scene.frame_end = 4, 6
    scene.render.filepath = scratch("anim") + "/frame_"
    scene.render.image_settings.file_format = "PNG"
    shot = scratch("shot.blend")
    bpy.ops.wm.save_as_mainfile(filepath=shot)
    bpy.ops.wm.save_userpref()
    started = time.perf_counter()
    run = subprocess.run([bpy.app.binary_path, "-b", shot, "-a"], capture_output=True, text=True, timeout=600)
    seconds = time.perf_counter() - started
    print(run.stdout[-3000:], run.stderr[-2000:], flush=True)
    check(run.returncode == 0, f"blender -b shot.blend -a exited with {run.returncode}")
    layers = [os.path.join(scratch("anim"), f"spindrift_{frame:04d}.exr") for frame in (4, 5, 6)]
    for frame, path in zip((4, 5, 6), layers):
        check(os.path.isfile(path), f"-a wrote {os.path.basename(path)}")
        check(os.path.isfile(os.path.join(scratch("anim"), f"frame_{frame:04d}.png")), f"and frame {frame}")
    for frame in (4, 5, 6):
        check(f"Spindrift: frame {frame}: layers written" in run.stdout, f"the console reports frame {frame}")
    first, last = (read_exr_layers(layers[i]) for i in (0, 2))
    check(np.abs(first["liquid"] - last["liquid"]).max() > 0.05, "the liquid moves between frames 4 and 6")
    # The composited frames follow their own layers: the render without the liquid is the same every frame,
    # so the frames differ exactly where either frame's liquid, foam or the liquid's light on the floor (the
    # fixture's sun: shadow, caustics) is.
    frames = [png_pixels(os.path.join(scratch("anim"), f"frame_{frame:04d}.png")) for frame in (4, 6)]
    differs = np.abs(frames[0] - frames[1]).max(axis=2) > 0.03
    covered = np.zeros_like(differs)
    for exr in (first, last):
        covered |= (exr["liquid"][..., 3] > 0.003) | (exr["foam"][..., 3] > 0.003)
        check("liquid_shadow" in exr, "the fixture's sun gives the frames light layers")
        lit = exr["liquid_shadow"][..., :3] + exr["caustics"][..., :3]
        sky = exr["liquid_sky"][..., :3]
        covered |= (np.abs(lit - 1).max(axis=2) > 0.003) | (np.abs(sky - 1).max(axis=2) > 0.003)
    covered = np.pad(covered, 1)
    covered = covered[:-2, 1:-1] | covered[2:, 1:-1] | covered[1:-1, :-2] | covered[1:-1, 2:] | covered[1:-1, 1:-1]
    check(differs.sum() > 20, f"composited frames 4 and 6 differ ({differs.sum()} pixels)")
    stray = float((differs & ~covered).sum() / max(differs.sum(), 1))
    check(stray < 0.02, f"and only where either frame's layers have liquid, foam or its light ({stray:.4f})")
    return seconds


def png_pixels(path):
    """Rows top first, RGB in 0..1."""
    image = bpy.data.images.load(path)
    pixels = np.array(image.pixels[:], dtype=np.float32).reshape(image.size[1], image.size[0], image.channels)
    bpy.data.images.remove(image)
    return pixels[::-1, :, :3]


def main():
    fixture, cli = arguments()[:2]
    results_path = arguments()[2] if len(arguments()) > 2 else None
    install_addon()
    scene = open_fixture_scene(fixture)
    domain = bpy.data.objects["Domain"]
    domain.spindrift.enabled = True
    check(domain.spindrift.liquid.ior > 1.0, "obj.spindrift.liquid.<name> exists")
    check(hasattr(domain.spindrift.foam, "lifetime_frames"), "obj.spindrift.foam.<name> exists")
    domain.spindrift.foam.lifetime_frames = 0.0
    scene.frame_set(FRAME)

    result = bpy.ops.spindrift.setup_compositing(mode="OVER")
    check(result == {"FINISHED"}, "setup_compositing(mode='OVER')")
    check(domain.hide_render, "OVER hides the domain's mesh from the render")
    group = scene.node_tree.nodes["Spindrift"]
    check(not group.mute and group.node_tree.name == "Spindrift Over", "the Spindrift Over group is in the tree")
    composite, background, background_path, render_seconds = render_frame(scene)
    layers = os.path.join(scratch("render"), f"spindrift_{FRAME:04d}.exr")
    check(os.path.isfile(layers), "the render wrote the frame's layers beside the render output")
    exr = read_exr_layers(layers)
    timing = dict(__import__("spindrift").reports.last_render.get("timing", {}))
    for name in ("liquid", "foam", "depth", "refraction_uv", "transmittance", "reflection"):
        check(name in exr and np.isfinite(exr[name]).all(), f"layer {name} is there and finite")

    scene_file = scratch("cli", "scene.json")
    result = bpy.ops.spindrift.export_scene(filepath=scene_file, frame=FRAME, background=background_path)
    check(result == {"FINISHED"}, "export_scene")
    cli_output = scratch("cli", "cli_####.exr")
    run = subprocess.run([cli, "render", scene_file, "--frames", str(FRAME), "-o", cli_output],
                         capture_output=True, text=True)
    print(run.stdout[-2000:], run.stderr[-2000:])
    check(run.returncode == 0, "the CLI rendered the exported scene")
    metrics = compare(composite, cli_output.replace("####", f"{FRAME:04d}"), background, exr)
    metrics["render_seconds"] = render_seconds
    metrics["addon_timing"] = timing
    metrics["animation_seconds"] = animation(scene)
    if results_path:
        with open(results_path, "w") as file:
            json.dump(metrics, file, indent=1)
    print("test_render_compare: passed", flush=True)


main()
