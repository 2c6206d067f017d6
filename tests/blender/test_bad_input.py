""""Bad input from Blender": each case is reported (console under -b, the operator's report, the panel's last
frame), the frame goes on without the layer or stops as the user chose, and Blender keeps running.

Run: run_blender.py --zip ZIP test_bad_input.py -- FIXTURE_DIR CASE
"""

import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import addon_utils  # noqa: E402
import bpy  # noqa: E402
import numpy as np  # noqa: E402

from blender_test_common import (arguments, check, install_addon, open_fixture_scene, read_exr_layers,  # noqa: E402
                                 scratch)


def spindrift():
    import spindrift as module

    return module


def operator_error(operator, **keywords):
    """Runs an operator that must fail: Blender turns its ERROR report into a RuntimeError for scripts."""
    try:
        result = operator(**keywords)
    except RuntimeError as error:
        return str(error)
    raise AssertionError(f"{operator} returned {result} instead of reporting an error")


def render_layers(scene, expect="FINISHED"):
    if expect == "CANCELLED":
        message = operator_error(bpy.ops.spindrift.render_layers)
        check(message, f"render_layers reports: {message}")
    else:
        result = bpy.ops.spindrift.render_layers()
        check(result == {expect}, f"render_layers returned {result}, expected {{{expect!r}}}")
    return spindrift().reports.last_render


def issues_mention(record, text):
    found = [issue for issue in record["issues"] if text in issue]
    check(found, f"an issue says '{text}' (issues: {record['issues']})")
    return found[0]


def layers_path(scene):
    return spindrift().render_layer.layer_path(scene, scene.frame_current)


def case_empty_particle_system(scene):
    bpy.ops.mesh.primitive_ico_sphere_add(radius=0.3, location=(0, 0, 1))
    emitter = bpy.context.object
    emitter.modifiers.new("Particles", "PARTICLE_SYSTEM")
    emitter.particle_systems[0].settings.count = 0
    emitter.spindrift.enabled = True
    scene.frame_set(3)
    record = render_layers(scene)
    issues_mention(record, "no particles at this frame")
    liquid = read_exr_layers(layers_path(scene))["liquid"]
    check(np.isfinite(liquid).all() and liquid[..., 3].max() == 0, "the layers exist, finite and empty")


def case_nan_locations(scene):
    mesh = bpy.data.meshes.new("Points")
    mesh.from_pydata([(0, 0, 0.8), (float("nan"), 0, 0.8), (0.2, 0, 0.8)], [], [])
    points = bpy.data.objects.new("Points", mesh)
    scene.collection.objects.link(points)
    points.spindrift.enabled = True
    points.spindrift.radius = 0.2
    record = render_layers(scene)
    issues_mention(record, "1 of 3 particles have a non-finite location")
    liquid = read_exr_layers(layers_path(scene))["liquid"]
    check(np.isfinite(liquid).all(), "every liquid pixel is finite")
    check((liquid[..., 3] > 0.5).sum() > 20, "the two finite particles are drawn")
    # The module itself drops non-finite positions (the contract), whatever the add-on does.
    module = spindrift()
    text = module.frame.collect(scene, bpy.context.evaluated_depsgraph_get(), scene.frame_current,
                                module.export.scene_camera(scene, bpy.context.evaluated_depsgraph_get()),
                                occluders=False).scene_text
    positions = np.array([[0, 0, 0.8], [np.nan, 0, 0.8], [0.2, 0, np.inf]], dtype=np.float32)
    result = module.native.renderer().render(text, 1, particles={
        "positions": positions, "radii": np.full(3, 0.2, np.float32), "kinds": np.zeros(3, np.uint8)},
        layers=["liquid"])
    channels, data = result["layers"]["liquid"]
    check(np.isfinite(np.frombuffer(data, np.float32)).all(), "the module renders NaN positions without harm")


def case_no_baked_cache(scene):
    bpy.ops.mesh.primitive_cube_add(size=1, location=(2, 0, 1))
    domain = bpy.context.object
    domain.name = "Unbaked"
    modifier = domain.modifiers.new("Fluid", "FLUID")
    modifier.fluid_type = "DOMAIN"
    modifier.domain_settings.domain_type = "LIQUID"
    modifier.domain_settings.cache_data_format = "OPENVDB"
    modifier.domain_settings.cache_directory = scratch("empty_cache")
    domain.spindrift.enabled = True
    record = render_layers(scene)
    message = issues_mention(record, "domain Unbaked: no baked cache for frame")
    check("bake the domain" in message, "the message says what to do")


def case_missing_cache_frame(scene):
    bpy.data.objects["Domain"].spindrift.enabled = True
    scene.frame_set(9)  # the fixture's cache holds frames 1-6
    record = render_layers(scene)
    issues_mention(record, "domain Domain: no baked cache for frame 9")
    scene.frame_set(3)
    record = render_layers(scene)
    check(not any("no baked cache" in issue for issue in record["issues"]), "frame 3 has its cache")


def case_no_camera(scene):
    bpy.data.objects["Domain"].spindrift.enabled = True
    scene.camera = None
    message = operator_error(bpy.ops.spindrift.setup_compositing, mode="OVER")
    check("has no camera" in message, f"setup_compositing reports: {message}")
    record = render_layers(scene, expect="CANCELLED")
    check("has no camera" in record["message"], f"the report names the problem: {record['message']}")
    # (Blender itself refuses to render without a camera, and then exits -b with code 1: not tried here.)
    check(bpy.ops.mesh.primitive_cube_add() == {"FINISHED"}, "Blender keeps running")


def case_zero_size_region(_scene):
    viewport = spindrift().viewport
    bad_input = spindrift().scene_json.BadInput
    for size in ((0, 800, 0.5), (1280, 1, 0.5), (0, 0, 1.0)):
        try:
            viewport.preview_size(*size)
        except bad_input as error:
            check("too small to preview" in str(error), f"{size}: {error}")
        else:
            raise AssertionError(f"preview_size{size} accepted a zero-size preview")
    check(viewport.preview_size(1280, 800, 0.5) == (640, 400), "a real region previews at half size")


def case_disabled_mid_render(scene):
    bpy.data.objects["Domain"].spindrift.enabled = True
    scene.frame_set(1)
    check(bpy.ops.spindrift.setup_compositing(mode="OVER") == {"FINISHED"}, "set up")
    scene.frame_start, scene.frame_end = 1, 3
    scene.render.image_settings.file_format = "PNG"

    def disable_at_frame_2(scene, _depsgraph=None):
        if scene.frame_current == 2:
            print("test: disabling the add-on in the middle of the render", flush=True)
            addon_utils.disable("spindrift")

    bpy.app.handlers.frame_change_post.append(disable_at_frame_2)
    bpy.ops.render.render(animation=True)
    bpy.app.handlers.frame_change_post.remove(disable_at_frame_2)
    directory = os.path.dirname(layers_path_for(scene, 1))
    for frame in (1, 2, 3):
        check(os.path.isfile(os.path.join(directory, f"frame_{frame:04d}.png")), f"frame {frame} was rendered")
    check(os.path.isfile(layers_path_for(scene, 2)), "frame 2 has its layers (rendered before the disable)")
    check(not os.path.isfile(layers_path_for(scene, 3)), "frame 3 has none")
    check(scene.node_tree.nodes["Spindrift"].mute, "the Spindrift nodes are bypassed, not showing stale layers")
    check(not hasattr(bpy.types.Object, "spindrift"), "the add-on is unregistered")
    check(bpy.ops.mesh.primitive_cube_add() == {"FINISHED"}, "Blender keeps running")


def layers_path_for(scene, frame):
    return os.path.join(bpy.path.abspath(os.path.dirname(scene.render.frame_path(frame=frame))),
                        f"spindrift_{frame:04d}.exr")


def case_stop_on_error(scene):
    """An orthographic camera cannot be rendered by Spindrift: SKIP renders the frame without the layer,
    STOP ends blender -b with exit code 1."""
    bpy.data.objects["Domain"].spindrift.enabled = True
    scene.frame_set(3)
    check(bpy.ops.spindrift.setup_compositing(mode="OVER") == {"FINISHED"}, "set up")
    scene.camera.data.type = "ORTHO"
    scene.render.image_settings.file_format = "PNG"
    bpy.ops.wm.save_userpref()
    outcomes = {}
    for choice in ("SKIP", "STOP"):
        scene.spindrift.on_error = choice
        blend = scratch(f"{choice.lower()}.blend")
        scene.render.filepath = scratch(choice.lower()) + "/frame_"
        bpy.ops.wm.save_as_mainfile(filepath=blend, copy=True)
        run = subprocess.run([bpy.app.binary_path, "-b", blend, "-f", "3"], capture_output=True, text=True,
                             timeout=300)
        print(run.stdout[-1500:], run.stderr[-1500:])
        check("orthographic" in run.stderr, f"{choice}: the console names the problem")
        outcomes[choice] = (run.returncode, os.path.isfile(os.path.join(scratch(choice.lower()), "frame_0003.png")))
    check(outcomes["SKIP"] == (0, True), f"SKIP renders the frame without the layer: {outcomes['SKIP']}")
    check(outcomes["STOP"][0] == 1, f"STOP exits with code 1: {outcomes['STOP']}")


def case_foam_only_workflow(scene):
    """Not bad input: the second compositing mode. Foam over a render that contains the domain's liquid mesh;
    the foam's occlusion and fade take the liquid's depth from that mesh, handed over as triangles."""
    domain = bpy.data.objects["Domain"]
    domain.spindrift.enabled = True
    domain.spindrift.foam_radius_cells = 1.5  # the tiny bake's foam, large enough to cover some pixels
    scene.frame_set(5)
    check(bpy.ops.spindrift.setup_compositing(mode="FOAM_ONLY") == {"FINISHED"}, "setup_compositing FOAM_ONLY")
    check(not domain.hide_render, "the domain's mesh stays in the render")
    group = scene.node_tree.nodes["Spindrift"]
    check(group.node_tree.name == "Spindrift Foam Only" and not group.mute, "the Foam Only group is wired")
    bpy.ops.render.render()
    record = spindrift().reports.last_render
    passes = [p["name"] for p in record["stats"]["passes"]]
    check("liquid_mesh_depth" in passes, f"the liquid mesh was drawn for the foam ({passes})")
    check(record["stats"]["particles"]["liquid"] == 0, "no liquid particles are rendered")
    settings = scene.render.image_settings
    settings.file_format, settings.color_depth = "OPEN_EXR_MULTILAYER", "32"
    result_path = scratch("foam_only_result.exr")
    bpy.data.images["Render Result"].save_render(result_path, scene=scene)
    result = read_exr_layers(result_path)
    foam = read_exr_layers(layers_path(scene))["foam"]
    render, composite = result["ViewLayer.Combined"], result["Composite.Combined"]
    check((foam[..., 3] > 0.05).sum() > 10, f"{(foam[..., 3] > 0.05).sum()} pixels of foam")
    expected = foam[..., :3] + (1 - foam[..., 3:4]) * render[..., :3]
    difference = float(np.abs(composite[..., :3] - expected).max())
    check(difference < 2e-3, f"the composite is the foam over the render (max difference {difference:.2e})")
    # The scene's sun lights the foam (foam.lit_by_lights) and nothing else: no liquid particle sees it.
    check(record["stats"]["foam"]["lights"] == 1, f"the sun lights the foam ({record['stats']['foam']})")
    skipped = {entry["name"]: entry["reason"] for entry in record["stats"]["skipped"]}
    check(skipped.get("lit_background") == "no light sees the liquid", f"the light passes are skipped ({skipped})")
    sun = bpy.data.objects["Sun"]
    sun.hide_render = True
    bpy.ops.render.render()
    unlit = read_exr_layers(layers_path(scene))["foam"]
    sun.hide_render = False
    shown = (foam[..., 3] > 0.05) & (unlit[..., 3] > 0.05)
    lit_mean, unlit_mean = (float((f[..., :3].mean(axis=2) / f[..., 3])[shown].mean()) for f in (foam, unlit))
    check(lit_mean > unlit_mean + 0.05, f"the sunlit foam is brighter ({lit_mean:.3f} against {unlit_mean:.3f})")


CASES = {name[len("case_"):]: function for name, function in globals().items() if name.startswith("case_")}


def main():
    fixture, case = arguments()[:2]
    if case not in CASES:
        raise SystemExit(f"unknown case {case}; cases: {sorted(CASES)}")
    install_addon()
    scene = open_fixture_scene(fixture)
    scene.frame_set(3)
    CASES[case](scene)
    print(f"test_bad_input {case}: passed", flush=True)


main()
