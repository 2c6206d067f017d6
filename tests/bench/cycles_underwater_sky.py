"""How bright Cycles makes a floor under water, seen by a camera in the water, lit by a uniform sky above the
water's flat surface, against geometric optics (docs/liquid.md, "A camera under water").

Run inside Blender:

    blender -b --factory-startup --python-exit-code 1 --python tests/bench/cycles_underwater_sky.py -- \
        [--samples 256] [--albedo 0.8] [--ior 1.33]

A floor (diffuse, albedo `albedo`) under clear water 0.5 deep and 40 wide (no absorption; the references'
water material, tests/bench/references.py), lit by a white world of strength 1 and nothing else. The camera
lies in the water, 0.3 above the floor, and looks straight down. Rendered once with the water and once
without; prints the floor's brightness with the water over that without, and what geometric optics gives:

- the sky's light entering the surface keeps (1 - F) of it, F Fresnel's reflectance, and its radiance is n²
  times the sky's inside the water over a cone n² times narrower, so that a floor facing up gets the dry
  floor's irradiance times the cosine-weighted mean of 1 - F over the sky (0.934 for n = 1.33);
- the floor's own light, going up, leaves through the surface only in part: the rest (the fraction
  1 - 0.934 / n², Fresnel and total internal reflection) comes back down to the floor, which reflects
  `albedo` of it again, so the floor's light is 0.934 / (1 - albedo (1 - 0.934 / n²)) of the dry floor's.

A renderer whose BSDFs are symmetric (radiance unchanged where light refracts, as a path tracer gets when it
leaves out the n² of non-symmetric scattering) finds 1/n² of the first term.
"""

import argparse
import math
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import references  # noqa: E402 (Blender runs this file by path)
from sun_through_mesh import dielectric_fresnel  # noqa: E402


def parse_arguments():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    parser = argparse.ArgumentParser(prog="cycles_underwater_sky.py", description=__doc__.split("\n")[0])
    parser.add_argument("--samples", type=int, default=256)
    parser.add_argument("--albedo", type=float, default=0.8)
    parser.add_argument("--ior", type=float, default=1.33)
    return parser.parse_args(argv)


def build(arguments):
    scene = references.empty_cycles_scene(arguments.samples, 0.0, 64)
    scene.cycles.diffuse_bounces = 64  # the light between the floor and the surface's underside, all of it
    world = bpy.data.worlds.new("White")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 1.0
    scene.world = world

    bpy.ops.mesh.primitive_plane_add(size=200)
    # Lambert's diffuse (the Diffuse BSDF at roughness 0), not the Principled BSDF: its rough diffuse brightens
    # light that arrives at grazing angles, which the sky does above the water and not below it.
    floor_material = bpy.data.materials.new("Floor")
    floor_material.use_nodes = True
    nodes = floor_material.node_tree.nodes
    nodes.remove(nodes["Principled BSDF"])
    diffuse = nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = (arguments.albedo, arguments.albedo, arguments.albedo, 1.0)
    diffuse.inputs["Roughness"].default_value = 0.0
    floor_material.node_tree.links.new(diffuse.outputs["BSDF"], nodes["Material Output"].inputs["Surface"])
    bpy.context.object.data.materials.append(floor_material)

    # The floor lies inside the water (no coplanar faces).
    bpy.ops.mesh.primitive_cube_add(size=1, location=(0.0, 0.0, 0.24))
    water = bpy.context.object
    water.scale = (40.0, 40.0, 0.52)
    material = references.make_water_material([1e-4, 1e-4, 1e-4])
    next(n for n in material.node_tree.nodes if n.type == "BSDF_GLASS").inputs["IOR"].default_value = arguments.ior
    water.data.materials.append(material)

    camera = bpy.data.cameras.new("Camera")
    camera.type = 'ORTHO'
    camera.ortho_scale = 1.0
    camera.clip_start = 0.01
    camera_object = bpy.data.objects.new("Camera", camera)
    camera_object.location = (0.0, 0.0, 0.3)
    scene.collection.objects.link(camera_object)
    scene.camera = camera_object
    return scene, water


def mean_brightness(scene, name):
    path = os.path.join(bpy.app.tempdir, name)
    scene.render.filepath = path
    scene.render.image_settings.file_format = 'OPEN_EXR'
    bpy.ops.render.render(write_still=True)
    pixels = list(bpy.data.images.load(path).pixels)
    values = [pixels[i] for i in range(len(pixels)) if i % 4 != 3]
    return sum(values) / len(values)


def hemispherical_transmittance(ior, steps=20000):
    """The cosine-weighted mean of 1 - F over a uniform sky, light entering a surface of index `ior`."""
    total = 0.0
    for step in range(steps):
        mu = (step + 0.5) / steps  # cos(theta); cosine weighting is uniform in mu squared
        total += (1.0 - dielectric_fresnel(mu, 1.0, ior)[0]) * 2.0 * mu / steps
    return total


def main():
    arguments = parse_arguments()
    scene, water = build(arguments)
    wet = mean_brightness(scene, "cycles_underwater_wet.exr")
    water.hide_render = True
    dry = mean_brightness(scene, "cycles_underwater_dry.exr")
    entering = hemispherical_transmittance(arguments.ior)
    returned = 1.0 - entering / arguments.ior ** 2
    optics = entering / (1.0 - arguments.albedo * returned)
    print(f"[cycles_underwater_sky] samples {arguments.samples}, albedo {arguments.albedo}, IOR {arguments.ior}: "
          f"with water / dry = {wet / dry:.3f}; geometric optics {optics:.3f} (sky kept {entering:.3f}, the "
          f"floor's light returned {returned:.3f}); optics / n^2 = {optics / arguments.ior ** 2:.3f}", flush=True)


if __name__ == "__main__":
    main()
