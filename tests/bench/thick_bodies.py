"""Thick bodies of water for the light benchmark (issue 10), rendered with Cycles.

Run inside Blender (tests/bench/thick_report.py does this when a render is missing):

    blender -b --factory-startup --python-exit-code 1 --python tests/bench/thick_bodies.py -- \
        --output build/bench/thick [--width 480 --height 270 --samples 128]

Six frames of compact water a metre across over the dam-break example's checker floor, lit by a sun and a
sky: a block resting on the floor, a ball floating just above it, a pool in a tank seen from above, from the
side and from inside (the camera under its surface), and the block seen from five times as far. The water is
an exact mesh (a box, a sphere), so the references measure Spindrift's light, not a simulation's surface;
Spindrift gets a lattice of particles filling the same shapes. One more frame, `ball_baked`, is the ball as a
user's simulation has it: Mantaflow fills the sphere with FLIP particles (its first frame, without gravity),
Cycles renders Mantaflow's own mesh of them and Spindrift reads the same bake (OUTPUT/ball_baked/cache). For
every frame it writes into OUTPUT/FRAME/:

- background.exr: everything but the water, with planar depth and Cycles' light passes (DiffDir, DiffInd,
  DiffCol, GlossDir, GlossInd, GlossCol), which Spindrift's lit background uses;
- reference_noshadow.exr: the water as glass with Beer-Lambert absorption casting no shadow (the benchmark's
  reference until now);
- reference_full.exr: the same water casting its shadow and caustics, a full render (what a user's render
  has). Caustics come from plain path tracing: Cycles' shadow caustics (manifold next-event estimation) were
  tried and add no sun light through the water in Blender 3.4 (the pool's floor came out at half the
  path-traced brightness), so the sun keeps the dam-break example's 3 degree disc, which a path tracer's
  caustics converge on at affordable sample counts;
- reference_full_seed2.exr: reference_full.exr again with another sampling seed. The two differ by the
  references' own noise only, so their difference is the error floor that no renderer can go below at these
  samples (the pool's floor, lit only by caustics through the surface, is very noisy);
- water_mask.exr: the water alone, one sample through each pixel's centre, alpha = coverage;
- particles.ply, shape.json (the water's exact shape) and scene.json (with the sun in `lights`), and
  timings.json.

With --sky-only the sun is left out: the world alone lights the scene, as it does a Blender scene lit by its
sky or an HDRI without lamps, and scene.json has no `lights`. Only background.exr, water_mask.exr and
reference_full.exr are rendered (the light benchmark's "the world alone" section, `thick_report.py`).
"""

import argparse
import importlib.util
import json
import math
import os
import sys
import time

import bpy
from mathutils import Vector

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))


def load(path, name):
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


references = load(os.path.join(HERE, "references.py"), "bench_references")
# The dam-break example's floor, lighting and render settings (examples/bakelib, imported as its bake.py does).
dam_break = load(os.path.join(ROOT, "examples", "dam_break", "bake.py"), "dam_break_bake")
from bakelib import blender_scene, mantaflow, render, scene_file as scene_files  # noqa: E402 (on the path bake.py set)

SUN_ROTATION = (math.radians(35.0), 0.0, math.radians(30.0))  # elevation 55 degrees
SUN_STRENGTH = 3.0
PARTICLE_SPACING = 0.04
PARTICLE_RADIUS = 0.03
ABSORPTION_RGB = (0.9, 0.3, 0.15)  # liquid.absorption_rgb's default

# Each frame: the water's shape, the tank (or none) and the camera (location, target, focal length in mm). Water
# that rests on the floor reaches 2 cm below it, so the floor lies inside the water (no coplanar faces).
FRAMES = {
    "block": {"shape": ("box", (-0.5, -0.5, -0.02), (0.5, 0.5, 0.8)), "tank": False,
              "camera": ((2.3, -2.5, 1.7), (0.0, 0.0, 0.35), 35.0)},
    "ball": {"shape": ("sphere", (0.0, 0.0, 0.65), 0.5), "tank": False,
             "camera": ((2.3, -2.5, 1.7), (0.0, 0.0, 0.45), 35.0)},
    "pool_above": {"shape": ("box", (-0.8, -0.8, -0.02), (0.8, 0.8, 0.45)), "tank": True,
                   "camera": ((1.3, -1.9, 3.2), (0.0, 0.0, 0.2), 30.0)},
    "pool_side": {"shape": ("box", (-0.8, -0.8, -0.02), (0.8, 0.8, 0.45)), "tank": True,
                  "camera": ((2.8, -0.6, 1.0), (0.0, 0.0, 0.3), 35.0)},
    # The camera in the pool, a quarter metre under its surface, looking across it and a little up: the surface
    # seen from below (the sky through Snell's window, the pool mirrored beyond it) and the tank's far walls.
    "underwater": {"shape": ("box", (-0.8, -0.8, -0.02), (0.8, 0.8, 0.45)), "tank": True,
                   "camera": ((0.55, -0.6, 0.2), (-0.5, 0.55, 0.36), 18.0)},
    # The block five times as far: about 45 pixels across, its particles under a pixel and a half.
    "far": {"shape": ("box", (-0.5, -0.5, -0.02), (0.5, 0.5, 0.8)), "tank": False,
            "camera": ((11.5, -12.5, 8.5), (0.0, 0.0, 0.35), 35.0)},
    # The ball as Mantaflow bakes it (BAKED_*): its mesh in Cycles, its particles in Spindrift.
    "ball_baked": {"shape": ("sphere", (0.0, 0.0, 0.65), 0.5), "tank": False,
                   "camera": ((2.3, -2.5, 1.7), (0.0, 0.0, 0.45), 35.0), "baked": True},
}
# The baked ball's domain: a cube around the sphere, its cells 4.4 cm (about the lattice's 4 cm spacing); its
# 21,503 particles are 2.9 cm apart on average. Frame 1 holds the sphere as the flow object fills it;
# without gravity it stays a sphere. The bake runs on to BAKED_LAST_FRAME: the light benchmark's steady
# timings render a sequence of frames.
BAKED_DOMAIN_SIDE = 1.4
BAKED_RESOLUTION = 32
BAKED_FRAME = 1
BAKED_LAST_FRAME = 8
TANK_WALL = 0.08
TANK_HEIGHT = 0.6


def parse_arguments():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    parser = argparse.ArgumentParser(prog="thick_bodies.py", description=__doc__.split("\n")[0])
    parser.add_argument("--output", required=True)
    parser.add_argument("--frames", default=",".join(FRAMES))
    parser.add_argument("--width", type=int, default=480)
    parser.add_argument("--height", type=int, default=270)
    parser.add_argument("--background-samples", type=int, default=16)
    parser.add_argument("--samples", type=int, default=48)
    parser.add_argument("--sky-only", action="store_true", help="no sun: the world alone lights the scene")
    return parser.parse_args(argv)


def inside(shape, point):
    kind = shape[0]
    if kind == "box":
        return all(shape[1][i] <= point[i] <= shape[2][i] for i in range(3))
    return (Vector(point) - Vector(shape[1])).length <= shape[2]


def lattice(shape):
    """Particle centres filling the shape, half a spacing in from its surface."""
    if shape[0] == "box":
        low, high = Vector(shape[1]), Vector(shape[2])
    else:
        low, high = Vector(shape[1]) - Vector((shape[2],) * 3), Vector(shape[1]) + Vector((shape[2],) * 3)
    inset = PARTICLE_SPACING / 2
    low.z = max(low.z, 0.0)  # particles stay above the floor
    counts = [int(math.floor((high[i] - low[i] - 2 * inset) / PARTICLE_SPACING + 1e-6)) + 1 for i in range(3)]
    points = []
    for k in range(counts[2]):
        for j in range(counts[1]):
            for i in range(counts[0]):
                point = (low.x + inset + i * PARTICLE_SPACING, low.y + inset + j * PARTICLE_SPACING,
                         low.z + inset + k * PARTICLE_SPACING)
                if shape[0] == "box" or (Vector(point) - Vector(shape[1])).length <= shape[2] - inset:
                    points.append(point)
    return points


def write_ply(path, points):
    with open(path, "w", encoding="utf-8") as handle:
        handle.write(f"ply\nformat ascii 1.0\nelement vertex {len(points)}\nproperty float x\nproperty float y\n"
                     "property float z\nend_header\n")
        for x, y, z in points:
            handle.write(f"{x:.5f} {y:.5f} {z:.5f}\n")


def add_water(shape):
    if shape[0] == "box":
        water = blender_scene.add_box("Water", Vector(shape[1]), Vector(shape[2]))
    else:
        bpy.ops.mesh.primitive_uv_sphere_add(segments=96, ring_count=48, radius=shape[2], location=shape[1])
        water = bpy.context.active_object
        water.name = "Water"
        bpy.ops.object.shade_smooth()
    water.data.materials.append(references.make_water_material(ABSORPTION_RGB))
    return water


def bake_ball(shape, directory):
    """Mantaflow's liquid filling the sphere, baked into directory/cache once; returns the domain."""
    centre, half = Vector(shape[1]), Vector((BAKED_DOMAIN_SIDE / 2,) * 3)
    cache = os.path.join(directory, "cache")
    scene = bpy.context.scene
    scene.frame_start, scene.frame_end = BAKED_FRAME, BAKED_LAST_FRAME
    scene.use_gravity = False
    domain = blender_scene.add_box("LiquidDomain", centre - half, centre + half)
    mantaflow.configure_liquid_domain(domain, cache, BAKED_RESOLUTION, BAKED_FRAME, BAKED_LAST_FRAME,
                                      use_mesh=True)
    domain.modifiers["Fluid"].domain_settings.gravity = (0.0, 0.0, 0.0)
    domain.hide_render = True
    bpy.ops.mesh.primitive_uv_sphere_add(segments=96, ring_count=48, radius=shape[2], location=shape[1])
    mantaflow.add_liquid_flow(bpy.context.active_object)
    if not os.path.isfile(os.path.join(cache, "mesh", f"fluid_mesh_{BAKED_LAST_FRAME:04d}.bobj.gz")):
        mantaflow.bake_clean(domain, cache, BAKED_FRAME, BAKED_LAST_FRAME, log=lambda m: print(f"[thick_bodies] {m}"))
    return domain


def add_baked_water(shape, domain):
    """Mantaflow's liquid mesh of the baked frame as the water, casting its shadow as the exact meshes do."""
    cache = domain.modifiers["Fluid"].domain_settings.cache_directory
    return references.add_mantaflow_mesh(cache, BAKED_FRAME, Vector(shape[1]), BAKED_DOMAIN_SIDE, ABSORPTION_RGB)


def add_tank(shape):
    low, high = Vector(shape[1]), Vector(shape[2])
    material = blender_scene.make_material("TankWall", (0.72, 0.7, 0.66), roughness=0.8)
    t = TANK_WALL
    walls = [((low.x - t, low.y - t, 0), (high.x + t, low.y, TANK_HEIGHT)),
             ((low.x - t, high.y, 0), (high.x + t, high.y + t, TANK_HEIGHT)),
             ((low.x - t, low.y, 0), (low.x, high.y, TANK_HEIGHT)),
             ((high.x, low.y, 0), (high.x + t, high.y, TANK_HEIGHT))]
    for index, (box_min, box_max) in enumerate(walls):
        blender_scene.add_box(f"Tank{index}", Vector(box_min), Vector(box_max)).data.materials.append(material)


def build_frame(definition, directory, width, height, sky_only=False):
    blender_scene.clear_scene()
    floor = blender_scene.add_plane("Floor", 24.0, (0.0, 0.0, 0.0))
    floor.data.materials.append(blender_scene.make_checker_material("FloorTiles", (0.62, 0.6, 0.56),
                                                                    (0.36, 0.35, 0.33), scale=12.0))
    if definition["tank"]:
        add_tank(definition["shape"])
    domain = bake_ball(definition["shape"], directory) if definition.get("baked") else None
    water = add_baked_water(definition["shape"], domain) if domain else add_water(definition["shape"])
    location, target, lens = definition["camera"]
    camera = blender_scene.build_camera(Vector(location), Vector(target), lens)
    layout = dam_break.LAYOUT
    sun = blender_scene.build_lighting(layout.world_color, layout.world_strength, sun_energy=SUN_STRENGTH,
                                       sun_rotation=SUN_ROTATION)
    if sky_only:
        bpy.data.objects.remove(sun)
        sun = None
    scene = bpy.context.scene
    scene.render.resolution_x, scene.render.resolution_y = width, height
    bpy.context.view_layer.update()
    return water, camera, sun, domain


def configure(output_directory, width, height):
    scene = bpy.context.scene
    render.configure_background_render(scene, output_directory, width, height, dam_break.LAYOUT.render_samples)
    scene.cycles.use_adaptive_sampling = False
    references.set_water_bounces(scene)
    layer = scene.view_layers[0]
    for name in ("use_pass_diffuse_direct", "use_pass_diffuse_indirect", "use_pass_diffuse_color",
                 "use_pass_glossy_direct", "use_pass_glossy_indirect", "use_pass_glossy_color"):
        setattr(layer, name, True)


def scene_file(camera, sun, width, height, domain=None):
    # A baked frame's particles are its cache's, shaped as Mantaflow's domain settings say.
    particles = [{"path": "cache/data/fluid_data_####.vdb", "grid": "particles", "role": "liquid",
                  "domain": scene_files.domain_description(domain)}] if domain else \
        [{"path": "particles.ply", "role": "liquid", "radius": PARTICLE_RADIUS}]
    description = {
        "version": 1,
        "camera": scene_files.camera_description(camera, width, height),
        "particles": particles,
        "background": {"image": "background.exr",
                       "color": list(dam_break.LAYOUT.world_radiance)},
        "lights": [{"type": "sun",
                    "direction": [scene_files.clean_number(-c) for c in sun.matrix_world.col[2][:3]],
                    "color": list(sun.data.color), "strength": sun.data.energy}] if sun else [],
    }
    if domain:
        description["frame"] = BAKED_FRAME
    return description


def main():
    arguments = parse_arguments()
    output = os.path.abspath(arguments.output)
    for name in arguments.frames.split(","):
        definition = FRAMES[name]
        directory = os.path.join(output, name)
        os.makedirs(directory, exist_ok=True)
        water, camera, sun, domain = build_frame(definition, directory, arguments.width, arguments.height,
                                                 arguments.sky_only)
        configure(directory, arguments.width, arguments.height)
        if not domain:
            write_ply(os.path.join(directory, "particles.ply"), lattice(definition["shape"]))
        with open(os.path.join(directory, "shape.json"), "w", encoding="utf-8") as handle:
            json.dump({"shape": definition["shape"], "tank": definition["tank"]}, handle)
        with open(os.path.join(directory, "scene.json"), "w", encoding="utf-8") as handle:
            json.dump(scene_file(camera, sun, arguments.width, arguments.height, domain), handle, indent=1)
        timings_path = os.path.join(directory, "timings.json")
        timings = json.load(open(timings_path)) if os.path.isfile(timings_path) else {}

        def missing(file_name):
            return not os.path.isfile(os.path.join(directory, file_name))

        if missing("background.exr"):
            water.hide_render = True
            timings["background"] = references.render(os.path.join(directory, "background.exr"),
                                                      arguments.background_samples)
            water.hide_render = False
        if missing("water_mask.exr"):
            solids = [obj for obj in bpy.context.scene.objects
                      if obj.type == 'MESH' and obj != water and not obj.hide_render]
            references.set_visible(solids, False)
            scene = bpy.context.scene
            scene.render.film_transparent = True
            scene.cycles.filter_width = 0.01
            references.render(os.path.join(directory, "water_mask.exr"), 1)
            scene.cycles.filter_width = 1.5
            scene.render.film_transparent = False
            references.set_visible(solids, True)
        if missing("reference_noshadow.exr") and not arguments.sky_only:
            water.visible_shadow = False
            timings["reference_noshadow"] = references.render(os.path.join(directory, "reference_noshadow.exr"),
                                                              arguments.samples)
            water.visible_shadow = True
        if missing("reference_full.exr"):
            timings["reference_full"] = references.render(os.path.join(directory, "reference_full.exr"),
                                                          arguments.samples)
        if missing("reference_full_seed2.exr") and not arguments.sky_only:
            timings["reference_full_seed2"] = references.render(
                os.path.join(directory, "reference_full_seed2.exr"), arguments.samples, seed=2)
        timings["samples"] = arguments.samples
        timings["background_samples"] = arguments.background_samples
        with open(timings_path, "w", encoding="utf-8") as handle:
            json.dump(timings, handle, indent=1)
        print(f"[thick_bodies] {name}: {json.dumps(timings)}", flush=True)


if __name__ == "__main__":
    main()
