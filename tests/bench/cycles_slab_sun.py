"""How much of a sun's light Cycles lets through a flat slab of clear water onto the floor below it, against
geometric optics (docs/liquid.md, "The sun under a sheet of water").

Run inside Blender:

    blender -b --factory-startup --python-exit-code 1 --python tests/bench/cycles_slab_sun.py -- \
        [--samples 1024] [--clamp-indirect 10] [--sun-angle 3] [--ior 1.33] [--gap 0.05]

A floor (diffuse, albedo 0.8), a slab of water 0.1 thick (no absorption; the references' water material,
tests/bench/references.py) held `gap` above it (negative: the floor lies inside the water), a sun at 47.7
degrees elevation (the dam break's) and a black world. The camera looks straight down and does not see the
slab, so it sees the floor under it directly. Prints the floor's brightness under the slab over the dry
floor's, and what geometric optics gives: the product of the Fresnel transmittances of the surfaces the sun
crosses (the floor's light reflected back by the slab's underside adds a little more).
"""

import argparse
import math
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import references  # noqa: E402 (Blender runs this file by path)
from sun_through_mesh import dielectric_fresnel  # noqa: E402

ELEVATION_DEG = 47.7


def parse_arguments():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    parser = argparse.ArgumentParser(prog="cycles_slab_sun.py", description=__doc__.split("\n")[0])
    parser.add_argument("--samples", type=int, default=1024)
    parser.add_argument("--clamp-indirect", type=float, default=10.0, help="Cycles' default is 10; 0 is off")
    parser.add_argument("--sun-angle", type=float, default=3.0, help="the sun's angular diameter, degrees")
    parser.add_argument("--ior", type=float, default=1.33)
    parser.add_argument("--gap", type=float, default=0.05)
    return parser.parse_args(argv)


def build(arguments):
    scene = references.empty_cycles_scene(arguments.samples, arguments.clamp_indirect, 96)
    world = bpy.data.worlds.new("Black")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    scene.world = world

    bpy.ops.mesh.primitive_plane_add(size=20)
    floor_material = bpy.data.materials.new("Floor")
    floor_material.use_nodes = True
    bsdf = floor_material.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (0.8, 0.8, 0.8, 1.0)
    bsdf.inputs["Specular"].default_value = 0.0
    bsdf.inputs["Roughness"].default_value = 1.0
    bpy.context.object.data.materials.append(floor_material)

    # The slab covers x in [0, 2]; the camera sees x in [-2, 2].
    bpy.ops.mesh.primitive_cube_add(size=1, location=(1.0, 0.0, arguments.gap + 0.05))
    slab = bpy.context.object
    slab.scale = (2.0, 4.0, 0.1)
    water = references.make_water_material([1e-4, 1e-4, 1e-4])
    next(n for n in water.node_tree.nodes if n.type == "BSDF_GLASS").inputs["IOR"].default_value = arguments.ior
    slab.data.materials.append(water)
    slab.visible_camera = False

    sun = bpy.data.lights.new("Sun", 'SUN')
    sun.energy = 3.0
    sun.angle = math.radians(arguments.sun_angle)
    sun_object = bpy.data.objects.new("Sun", sun)
    sun_object.rotation_euler = (0.0, -(math.pi / 2 - math.radians(ELEVATION_DEG)), 0.0)
    scene.collection.objects.link(sun_object)

    camera = bpy.data.cameras.new("Camera")
    camera.type = 'ORTHO'
    camera.ortho_scale = 4.0
    camera_object = bpy.data.objects.new("Camera", camera)
    camera_object.location = (0.0, 0.0, 5.0)
    scene.collection.objects.link(camera_object)
    scene.camera = camera_object
    return scene


def main():
    arguments = parse_arguments()
    scene = build(arguments)
    path = os.path.join(bpy.app.tempdir, "cycles_slab_sun.exr")
    scene.render.filepath = path
    scene.render.image_settings.file_format = 'OPEN_EXR'
    bpy.ops.render.render(write_still=True)
    image = bpy.data.images.load(path)
    width, height = image.size
    pixels = list(image.pixels)

    def mean(columns):
        values = [pixels[4 * (row * width + column) + channel] for row in range(20, 76) for column in columns
                  for channel in range(3)]
        return sum(values) / len(values)

    dry, under = mean(range(4, 30)), mean(range(66, 92))  # x in [-1.83, -0.75] and [0.75, 1.83]
    incidence = math.cos(math.radians(90.0 - ELEVATION_DEG))
    reflectance, refracted = dielectric_fresnel(incidence, 1.0, arguments.ior)
    optics = 1.0 - reflectance
    if arguments.gap > 0.0:  # out through the underside too, at the incidence it entered with
        optics *= 1.0 - dielectric_fresnel(refracted, arguments.ior, 1.0)[0]
    print(f"[cycles_slab_sun] samples {arguments.samples}, clamp {arguments.clamp_indirect}, sun "
          f"{arguments.sun_angle} deg, IOR {arguments.ior}, gap {arguments.gap}: under the slab / dry = "
          f"{under / dry:.3f}; geometric optics {optics:.3f}", flush=True)


if __name__ == "__main__":
    main()
