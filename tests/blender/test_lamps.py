"""Blender's lamps handed to the renderer: each lamp type in the scene format's terms (docs/scene-format.md),
the frame's EXR with the liquid's shadow where the sun's light crosses the liquid, and the compositing group
applying the light layers; without lamps, the world's light alone, and under a black world no light at all. The composite itself is compared with the command line's (which gets the same
lamps) by test_render_compare.py.

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

    world = scene.world.node_tree.nodes["Background"]
    world.inputs["Strength"].default_value = 0.0
    check(bpy.ops.spindrift.setup_compositing(mode="OVER") == {"FINISHED"}, "set up again under a black world")
    layers = read_exr_layers(module.render_layer.layer_path(scene, 5))
    check(not set(module.compositing.LIGHT_LAYERS) & set(layers), "no light layers without any light")
    group = bpy.data.node_groups["Spindrift Over"]
    check(all(node.label != "Lamps through the liquid" for node in group.nodes), "and the group does not apply them")
    print("test_lamps: passed", flush=True)


run(main)
