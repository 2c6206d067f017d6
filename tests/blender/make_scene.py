"""Builds and bakes the add-on tests' scene: a tiny Mantaflow liquid (resolution 24, frames 1-6, FLIP with
spray, foam and bubbles, the liquid mesh), a floor, a cube between the camera and part of the liquid, a camera,
a sun and a plain world. Saves OUTPUT/scene.blend with its cache in OUTPUT/cache.

Run: blender -b --factory-startup --python make_scene.py -- OUTPUT
"""

import os
import sys

import bpy
from mathutils import Vector

# The Mantaflow domain, flow, materials and bake are the examples' own (examples/bakelib).
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                                "examples"))
from bakelib import blender_scene, mantaflow  # noqa: E402 (Blender runs this file by path)

RESOLUTION = 24
FRAME_END = 6
WIDTH, HEIGHT = 160, 120


def main():
    output = os.path.abspath(sys.argv[sys.argv.index("--") + 1])
    cache = os.path.join(output, "cache")
    os.makedirs(cache, exist_ok=True)
    blender_scene.clear_scene()
    scene = bpy.context.scene
    scene.frame_start, scene.frame_end = 1, FRAME_END

    bpy.ops.mesh.primitive_plane_add(size=12, location=(0, 0, 0))
    bpy.context.object.name = "Floor"
    bpy.context.object.data.materials.append(blender_scene.make_checker_material(
        "Floor", (0.35, 0.3, 0.25), (0.06, 0.06, 0.07), 8.0))

    # The domain: a cube of size 2 standing on the floor; the liquid falls from a sphere near its top.
    bpy.ops.mesh.primitive_cube_add(size=2, location=(0, 0, 1))
    domain = bpy.context.object
    domain.name = "Domain"
    bpy.ops.mesh.primitive_uv_sphere_add(radius=0.5, location=(0, 0, 1.2))
    flow = bpy.context.object
    flow.name = "Flow"
    mantaflow.add_liquid_flow(flow)

    # Blender's default mesh settings (mesh_scale 2) and secondary particles, as a user's first liquid has.
    mantaflow.configure_liquid_domain(domain, cache, RESOLUTION, 1, FRAME_END)
    domain.display_type = "WIRE"

    # The occluder: a cube between the camera and the left part of the liquid.
    bpy.ops.mesh.primitive_cube_add(size=0.45, location=(-0.3, -1.6, 0.95))
    cube = bpy.context.object
    cube.name = "Occluder"
    cube.data.materials.append(blender_scene.make_material("Occluder", (0.8, 0.2, 0.1), roughness=0.5))

    camera_data = bpy.data.cameras.new("Camera")
    camera_data.lens = 32
    camera_data.clip_start, camera_data.clip_end = 0.1, 100
    camera = bpy.data.objects.new("Camera", camera_data)
    camera.location = (0.0, -5.2, 2.4)
    camera.rotation_euler = (Vector((0, 0, 0.6)) - camera.location).to_track_quat("-Z", "Y").to_euler()
    scene.collection.objects.link(camera)
    scene.camera = camera
    sun_data = bpy.data.lights.new("Sun", "SUN")
    sun_data.energy = 1.5
    sun = bpy.data.objects.new("Sun", sun_data)
    sun.rotation_euler = (0.6, 0.2, -0.5)
    scene.collection.objects.link(sun)
    world = bpy.data.worlds.new("World")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.5, 0.6, 0.75, 1)
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.6
    scene.world = world

    scene.render.engine = "CYCLES"
    scene.cycles.samples = 4
    scene.cycles.use_denoising = False
    scene.cycles.device = "CPU"
    scene.render.resolution_x, scene.render.resolution_y = WIDTH, HEIGHT
    scene.render.resolution_percentage = 100
    scene.view_settings.view_transform = "Standard"
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.filepath = "//render/frame_"
    bpy.context.view_layer.update()

    mantaflow.bake(domain)
    for frame in range(1, FRAME_END + 1):
        path = os.path.join(cache, "data", f"fluid_data_{frame:04d}.vdb")
        if not os.path.isfile(path):
            raise RuntimeError(f"the bake did not write {path}")
    bpy.ops.wm.save_as_mainfile(filepath=os.path.join(output, "scene.blend"))
    print(f"make_scene: baked and saved {output}/scene.blend", flush=True)


main()
