"""Scene building blocks: boxes, planes, materials, camera and lighting, with nothing example-specific."""

import math

import bmesh
import bpy


def clear_scene():
    """Removes the factory startup's cube, light and camera so the scene is built from nothing."""
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    for mesh in list(bpy.data.meshes):
        bpy.data.meshes.remove(mesh)


def add_box(name, box_min, box_max):
    """A box object whose mesh is centred on its origin and whose transform is a pure translation.

    The vertices carry the size, not the object's scale: Mantaflow's cache is in the domain's local frame,
    and a scaled or rotated domain would make that frame differ from the world by more than a translation.
    """
    size = box_max - box_min
    centre = (box_min + box_max) / 2
    mesh = bpy.data.meshes.new(name)
    bm = bmesh.new()
    bmesh.ops.create_cube(bm, size=1.0)
    bmesh.ops.scale(bm, vec=size, verts=bm.verts)
    bm.to_mesh(mesh)
    bm.free()
    obj = bpy.data.objects.new(name, mesh)
    obj.location = centre
    bpy.context.scene.collection.objects.link(obj)
    return obj


def add_plane(name, size, location):
    mesh = bpy.data.meshes.new(name)
    bm = bmesh.new()
    bmesh.ops.create_grid(bm, x_segments=1, y_segments=1, size=size / 2)
    bm.to_mesh(mesh)
    bm.free()
    obj = bpy.data.objects.new(name, mesh)
    obj.location = location
    bpy.context.scene.collection.objects.link(obj)
    return obj


def add_icosphere(name, centre, radius, subdivisions=3):
    mesh = bpy.data.meshes.new(name)
    sphere = bmesh.new()
    bmesh.ops.create_icosphere(sphere, subdivisions=subdivisions, radius=radius)
    sphere.to_mesh(mesh)
    sphere.free()
    obj = bpy.data.objects.new(name, mesh)
    obj.location = centre
    bpy.context.scene.collection.objects.link(obj)
    return obj


def make_material(name, color, roughness=0.6):
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    principled = material.node_tree.nodes["Principled BSDF"]
    principled.inputs["Base Color"].default_value = (*color, 1.0)
    principled.inputs["Roughness"].default_value = roughness
    return material


def make_checker_material(name, color_a, color_b, scale, roughness=0.5):
    """A tiled floor: the pattern shows how the liquid refracts what lies beneath it."""
    material = make_material(name, color_a, roughness=roughness)
    nodes = material.node_tree.nodes
    checker = nodes.new("ShaderNodeTexChecker")
    checker.inputs["Color1"].default_value = (*color_a, 1.0)
    checker.inputs["Color2"].default_value = (*color_b, 1.0)
    checker.inputs["Scale"].default_value = scale
    coordinates = nodes.new("ShaderNodeTexCoord")
    links = material.node_tree.links
    # Object coordinates, so the tiles are square in world units whatever the plane's UVs.
    links.new(coordinates.outputs["Object"], checker.inputs["Vector"])
    links.new(checker.outputs["Color"], nodes["Principled BSDF"].inputs["Base Color"])
    return material


def build_camera(location, target, lens_mm, sensor_mm=24.0, clip_start=0.05, clip_end=100.0):
    """The scene's camera at `location`, looking at `target` with +Y up."""
    camera_data = bpy.data.cameras.new("Camera")
    camera_data.sensor_fit = 'VERTICAL'  # so angle_y is the vertical field of view scene.json records
    camera_data.sensor_height = sensor_mm
    camera_data.lens = lens_mm
    camera_data.clip_start = clip_start
    camera_data.clip_end = clip_end
    camera = bpy.data.objects.new("Camera", camera_data)
    camera.location = location
    camera.rotation_euler = (target - location).to_track_quat('-Z', 'Y').to_euler()
    bpy.context.scene.collection.objects.link(camera)
    bpy.context.scene.camera = camera
    return camera


def build_lighting(world_color, world_strength, sun_energy=2.2,
                   sun_rotation=(math.radians(40.0), math.radians(15.0), math.radians(-35.0))):
    """A slightly soft sun and a plain world colour, which lights the scene softly and is the background colour
    Spindrift falls back on."""
    sun_data = bpy.data.lights.new("Sun", 'SUN')
    sun_data.energy = sun_energy
    sun_data.angle = math.radians(3.0)
    sun = bpy.data.objects.new("Sun", sun_data)
    sun.rotation_euler = sun_rotation
    bpy.context.scene.collection.objects.link(sun)

    world = bpy.data.worlds.new("World")
    world.use_nodes = True
    background = world.node_tree.nodes["Background"]
    background.inputs["Color"].default_value = (*world_color, 1.0)
    background.inputs["Strength"].default_value = world_strength
    bpy.context.scene.world = world
    return sun
