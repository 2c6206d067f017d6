"""Blender's lamps handed to the renderer: each lamp type in the scene format's terms (docs/scene-format.md),
the frame's EXR with the liquid's shadow where the sun's light crosses the liquid, and the compositing group
applying the light layers; the scene's Light settings (scene.spindrift.light) reaching the renderer: caustics
off, the group's direct fraction; the film's pixel filter as liquid.pixel_filter_width; without lamps, the world's light alone, none with Sky without lamps off, and
under a black world no light at all. The composite itself is compared with the command line's (which gets the
same lamps) by test_render_compare.py.

Run: run_blender.py --zip ZIP test_lamps.py -- FIXTURE_DIR
"""

import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import bpy  # noqa: E402
import numpy as np  # noqa: E402

from blender_test_common import (arguments, check, install_addon, open_fixture_scene, read_exr_layers,  # noqa: E402
                                 run, spindrift_module)


def add_lamp(kind, name, location, rotation=(0.0, 0.0, 0.0), energy=100.0, hide_render=False):
    data = bpy.data.lights.new(name, kind)
    data.energy = energy
    data.color = (1.0, 0.5, 0.25)
    obj = bpy.data.objects.new(name, data)
    obj.location, obj.rotation_euler, obj.hide_render = location, rotation, hide_render
    bpy.context.scene.collection.objects.link(obj)
    return obj


def check_conversions(scene, module):
    spot = add_lamp("SPOT", "Spot", (1.0, -2.0, 3.0), (0.3, 0.0, 0.2), energy=800.0)
    spot.data.spot_size = math.radians(60.0)
    add_lamp("POINT", "Point", (0.0, 1.0, 2.0), energy=250.0)
    add_lamp("AREA", "Area", (2.0, 0.0, 2.0), energy=40.0)
    add_lamp("POINT", "Hidden", (0.0, 0.0, 5.0), hide_render=True)
    bpy.context.view_layer.update()
    lights = {light["type"] + str(i): light for i, light in
              enumerate(module.export.scene_lights(bpy.context.evaluated_depsgraph_get()))}
    check(len(lights) == 4, f"four lamps are handed, the one hidden from the render is not ({len(lights)})")
    by_strength = {light["strength"]: light for light in lights.values()}
    sun_object = bpy.data.objects["Sun"]
    sun = by_strength[sun_object.data.energy]
    travels = -np.asarray(sun_object.matrix_world)[:3, 2]
    check(sun["type"] == "sun" and np.allclose(sun["direction"], travels, atol=1e-6) and "position" not in sun,
          "the sun shines down its local -Z")
    spot_light = by_strength[800.0]
    check(spot_light["type"] == "spot" and abs(spot_light["spot_angle_deg"] - 60.0) < 1e-4
          and np.allclose(spot_light["position"], spot.matrix_world.translation, atol=1e-6)
          and np.allclose(spot_light["direction"], -np.asarray(spot.matrix_world)[:3, 2], atol=1e-6),
          "the spot keeps its position, direction and cone")
    check(by_strength[250.0]["type"] == "point" and by_strength[250.0]["color"] == [1.0, 0.5, 0.25],
          "the point light keeps its power and colour")
    check(by_strength[160.0]["type"] == "point" and np.allclose(by_strength[160.0]["position"], (2, 0, 2)),
          "the area lamp becomes a point light of 4x its power at its centre")
    for name in ("Spot", "Point", "Area", "Hidden"):
        bpy.data.objects.remove(bpy.data.objects[name])


def render_frame(scene, module):
    """Frame 5 as a final frame renders it: (its scene document, {skipped pass: reason}, the EXR's layers)."""
    path = module.render_layer.layer_path(scene, 5)
    result, inputs, _ = module.render_layer.render_frame(scene, bpy.context.evaluated_depsgraph_get(), 5, path)
    skipped = {entry["name"]: entry["reason"] for entry in result["stats"]["skipped"]}
    return inputs.document, skipped, read_exr_layers(path)


def check_light_settings_with_the_sun(scene, module):
    """The scene's Light settings reach the renderer and the group: caustics off, another direct fraction."""
    light = scene.spindrift.light
    document, skipped, layers = render_frame(scene, module)
    check("light" not in document, "the Light settings at their defaults leave the scene file's group out")
    check("caustics" not in skipped and layers["caustics"][..., :3].any(), "the sun's caustics are splatted")
    light.caustics = False
    document, skipped, layers = render_frame(scene, module)
    written = document.get("light")
    check(written == {"caustics": False}, f"Caustics off reaches the scene file ({written})")
    check(skipped.get("caustics") == "light.caustics is off", f"the renderer skips the caustics ({skipped})")
    check(not layers["caustics"][..., :3].any(), "and the caustics layer is black")
    check((layers["liquid_shadow"][..., :3].min(axis=2) < 0.5).any(), "while the liquid still shadows the floor")
    light.caustics = True

    share = bpy.data.node_groups["Spindrift Over"].nodes[module.compositing.DIRECT_SHARE_NODE]
    check(abs(share.inputs["Fac"].default_value - 0.6) < 1e-6, "the group's direct share is the default 0.6")
    light.direct_fraction = 0.25
    check(abs(share.inputs["Fac"].default_value - 0.25) < 1e-6, "and follows the scene's Direct fraction")
    document, _, _ = render_frame(scene, module)
    check(document.get("light") == {"direct_fraction": 0.25}, "which the scene file carries to the renderer")
    light.direct_fraction = 0.6
    check(abs(share.inputs["Fac"].default_value - 0.6) < 1e-6, "back to the default")


def check_film_pixel_filter(scene, module):
    """liquid.pixel_filter_width is the render's Film > Pixel Filter (parameters.FROM_BLENDER): left out at
    Cycles' default Blackman-Harris 1.5, a box of 1.2 px written as the Blackman-Harris width of its spread."""
    cycles = scene.cycles
    check((cycles.pixel_filter_type, cycles.filter_width) == ("BLACKMAN_HARRIS", 1.5), "Cycles' default filter")
    document, skipped, _ = render_frame(scene, module)
    check("pixel_filter_width" not in document.get("liquid", {}), "the default film writes no width")
    check("refraction_footprint" not in skipped, f"the footprint pass runs ({skipped})")
    cycles.pixel_filter_type, cycles.filter_width = "BOX", 1.2
    document, _, _ = render_frame(scene, module)
    width = document.get("liquid", {}).get("pixel_filter_width")
    check(width is not None and abs(width - 1.25) < 1e-4, f"a 1.2 px box reaches the scene file as 1.25 ({width})")
    cycles.pixel_filter_type, cycles.filter_width = "BLACKMAN_HARRIS", 1.5


def main():
    install_addon()
    scene = open_fixture_scene(arguments()[0])
    scene.render.resolution_x, scene.render.resolution_y, scene.render.resolution_percentage = 160, 120, 100
    bpy.data.objects["Domain"].spindrift.enabled = True
    scene.frame_set(5)
    module = spindrift_module()
    check_conversions(scene, module)

    check(bpy.ops.spindrift.setup_compositing(mode="OVER") == {"FINISHED"}, "set up compositing with the sun")
    layers = read_exr_layers(module.render_layer.layer_path(scene, 5))
    check(set(module.compositing.LIGHT_LAYERS) <= set(layers), f"the EXR has the light layers ({sorted(layers)})")
    shadow = layers["liquid_shadow"][..., :3].min(axis=2)
    shadowed = float((shadow < 0.5).mean())
    check(0.001 < shadowed < 0.5, f"the liquid shadows part of the floor ({shadowed:.1%} of the pixels)")
    check(float(np.median(shadow)) > 0.99, "and the rest of the floor keeps the sun's light")
    group = bpy.data.node_groups["Spindrift Over"]
    lit = next((node for node in group.nodes if node.label == "Lamps through the liquid"), None)
    check(lit is not None and lit.outputs["Image"].is_linked, "the group multiplies the render by the light layers")
    image_node = scene.node_tree.nodes[module.compositing.IMAGE_NODE]
    for name in module.compositing.LIGHT_LAYERS:
        check(image_node.outputs[name].is_linked, f"the group reads {name}")
    check_light_settings_with_the_sun(scene, module)
    check_film_pixel_filter(scene, module)

    # Without lamps the world's light alone is taken (light.sky_without_lamps): the liquid takes the sky light
    # of the floor under and beside it, and liquid_shadow carries the same multiplier as liquid_sky.
    bpy.data.objects.remove(bpy.data.objects["Sun"])
    check(bpy.ops.spindrift.setup_compositing(mode="OVER") == {"FINISHED"}, "set up again without lamps")
    layers = read_exr_layers(module.render_layer.layer_path(scene, 5))
    check(set(module.compositing.LIGHT_LAYERS) <= set(layers), f"the world's light layers ({sorted(layers)})")
    sky = layers["liquid_sky"][..., :3]
    check(np.array_equal(layers["liquid_shadow"][..., :3], sky), "liquid_shadow is the world's multiplier")
    check(not layers["caustics"][..., :3].any(), "and there are no caustics")
    darkened = float((sky.min(axis=2) < 0.95).mean())
    check(0.001 < darkened < 0.9, f"the liquid takes sky light from part of the floor ({darkened:.1%})")
    group = bpy.data.node_groups["Spindrift Over"]
    check(any(node.label == "Lamps through the liquid" for node in group.nodes), "and the group applies them")
    _, skipped, _ = render_frame(scene, module)
    check("lit_background" not in skipped, "the renderer lights the background with the world's light")

    # Sky without lamps off (light.sky_without_lamps): nothing lights a scene without lamps.
    scene.spindrift.light.sky_without_lamps = False
    check(bpy.ops.spindrift.setup_compositing(mode="OVER") == {"FINISHED"}, "set up again without the sky")
    layers = read_exr_layers(module.render_layer.layer_path(scene, 5))
    check(not set(module.compositing.LIGHT_LAYERS) & set(layers), "no light layers without the world's light")
    group = bpy.data.node_groups["Spindrift Over"]
    check(all(node.label != "Lamps through the liquid" for node in group.nodes), "and the group does not apply them")
    document, skipped, _ = render_frame(scene, module)
    check(document.get("light") == {"sky_without_lamps": False}, "the scene file says so")
    check(skipped.get("lit_background") == "no lights in the scene", f"the renderer lights nothing ({skipped})")
    scene.spindrift.light.sky_without_lamps = True

    world = scene.world.node_tree.nodes["Background"]
    world.inputs["Strength"].default_value = 0.0
    check(bpy.ops.spindrift.setup_compositing(mode="OVER") == {"FINISHED"}, "set up again under a black world")
    layers = read_exr_layers(module.render_layer.layer_path(scene, 5))
    check(not set(module.compositing.LIGHT_LAYERS) & set(layers), "no light layers without any light")
    group = bpy.data.node_groups["Spindrift Over"]
    check(all(node.label != "Lamps through the liquid" for node in group.nodes), "and the group does not apply them")
    print("test_lamps: passed", flush=True)


run(main)
