"""Builds and bakes the add-on tests' scene: a tiny Mantaflow liquid (resolution 24, frames 1-6, FLIP with
spray, foam and bubbles, the liquid mesh), a floor, a cube between the camera and part of the liquid, a camera,
a sun and a plain world. Saves OUTPUT/scene.blend with its cache in OUTPUT/cache.

Run: blender -b --factory-startup --python make_scene.py -- OUTPUT
"""

import os
import sys

import bpy
from mathutils import Vector

RESOLUTION = 24
FRAME_END = 6
WIDTH, HEIGHT = 160, 120


def clear():
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)


def material(name, color):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    mat.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = (*color, 1.0)
    return mat


def checker(name, color_a, color_b, scale):
    """Tiles in object coordinates: what the liquid refracts shows as a bent pattern."""
    mat = material(name, color_a)
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    texture = nodes.new("ShaderNodeTexChecker")
    texture.inputs["Color1"].default_value = (*color_a, 1.0)
    texture.inputs["Color2"].default_value = (*color_b, 1.0)
    texture.inputs["Scale"].default_value = scale
    links.new(nodes.new("ShaderNodeTexCoord").outputs["Object"], texture.inputs["Vector"])
    links.new(texture.outputs["Color"], nodes["Principled BSDF"].inputs["Base Color"])
    return mat


def main():
    output = os.path.abspath(sys.argv[sys.argv.index("--") + 1])
    cache = os.path.join(output, "cache")
    os.makedirs(cache, exist_ok=True)
    clear()
    scene = bpy.context.scene
    scene.frame_start, scene.frame_end = 1, FRAME_END

    bpy.ops.mesh.primitive_plane_add(size=12, location=(0, 0, 0))
    bpy.context.object.name = "Floor"
    bpy.context.object.data.materials.append(checker("Floor", (0.35, 0.3, 0.25), (0.06, 0.06, 0.07), 8.0))

    # The domain: a cube of size 2 standing on the floor; the liquid falls from a sphere near its top.
    bpy.ops.mesh.primitive_cube_add(size=2, location=(0, 0, 1))
    domain = bpy.context.object
    domain.name = "Domain"
    bpy.ops.mesh.primitive_uv_sphere_add(radius=0.5, location=(0, 0, 1.2))
    flow = bpy.context.object
    flow.name = "Flow"
    modifier = flow.modifiers.new("Fluid", "FLUID")
    modifier.fluid_type = "FLOW"
    modifier.flow_settings.flow_type = "LIQUID"
    modifier.flow_settings.flow_behavior = "GEOMETRY"
    flow.hide_render = True
    flow.display_type = "WIRE"

    modifier = domain.modifiers.new("Fluid", "FLUID")
    modifier.fluid_type = "DOMAIN"
    settings = modifier.domain_settings
    settings.domain_type = "LIQUID"
    settings.resolution_max = RESOLUTION
    settings.use_adaptive_domain = False
    settings.use_mesh = True
    settings.use_spray_particles = True
    settings.use_foam_particles = True
    settings.use_bubble_particles = True
    settings.cache_type = "ALL"
    settings.cache_data_format = "OPENVDB"
    settings.cache_frame_start = 1
    settings.cache_frame_end = FRAME_END
    settings.cache_directory = cache
    domain.display_type = "WIRE"

    # The occluder: a cube between the camera and the left part of the liquid.
    bpy.ops.mesh.primitive_cube_add(size=0.45, location=(-0.3, -1.6, 0.95))
    cube = bpy.context.object
    cube.name = "Occluder"
    cube.data.materials.append(material("Occluder", (0.8, 0.2, 0.1)))

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

    with bpy.context.temp_override(active_object=domain, object=domain, scene=scene,
                                   view_layer=bpy.context.view_layer):
        result = bpy.ops.fluid.bake_all()
    if result != {"FINISHED"}:
        raise RuntimeError(f"bake returned {result}")
    for frame in range(1, FRAME_END + 1):
        path = os.path.join(cache, "data", f"fluid_data_{frame:04d}.vdb")
        if not os.path.isfile(path):
            raise RuntimeError(f"the bake did not write {path}")
    bpy.ops.wm.save_as_mainfile(filepath=os.path.join(output, "scene.blend"))
    print(f"make_scene: baked and saved {output}/scene.blend", flush=True)


main()
