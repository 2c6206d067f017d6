"""Builds, bakes and renders Spindrift's dam-break example scene in Blender.

Run headless from the repository root:

    blender -b --factory-startup --python-exit-code 1 --python examples/dam_break/bake.py -- --output examples/dam_break

It builds the scene from an empty file, bakes a Mantaflow FLIP liquid with spray, foam and bubbles into
OUTPUT/cache, renders the background (everything but the liquid, with a Depth pass) into
OUTPUT/renders/background.exr plus a PNG preview, renders the same frame again with Mantaflow's liquid mesh
as water into OUTPUT/renders/with_liquid.exr (for foam composited over a full render), and writes
OUTPUT/scene.json and OUTPUT/scene_foam_only.json, the Spindrift scene files that point at them.
`--skip-bake`, `--skip-render` and `--skip-liquid-render` reuse what is already there
(examples/dam_break/prepare.sh uses them); the scene files are written every time and depend only on the
constants below, so they come out byte-identical on every run.
"""

import argparse
import json
import math
import os
import re
import shutil
import sys
import tempfile
import time

import bmesh
import bpy
from mathutils import Matrix, Vector

# The liquid domain, in world units. Its size is an exact multiple of the cell size (size / RESOLUTION along
# the longest side), so Mantaflow's grid covers the box exactly and the cache's positions, which start at the
# domain's minimum corner, need no correction for a rounded grid.
DOMAIN_MIN = Vector((-1.5, -0.9375, 0.0))
DOMAIN_SIZE = Vector((3.0, 1.875, 1.125))
RESOLUTION = 80
CELL_SIZE = max(DOMAIN_SIZE) / RESOLUTION

FRAME_START = 1
FRAME_END = 48
# The frame scene.json names as the default: the collapsing column has just hit the block and throws a
# splash over it, before the wave reaches the far wall and sheets of liquid climb the domain's walls.
SHOWCASE_FRAME = 16

# The water column, in the back left corner of the domain.
COLUMN_MIN = Vector((-1.5, 0.0, 0.0))
COLUMN_MAX = Vector((-0.95, 0.9375, 0.85))

# A block in the path of the wave, as a Mantaflow collision object and visible geometry.
OBSTACLE_MIN = Vector((0.15, 0.2, 0.0))
OBSTACLE_MAX = Vector((0.45, 0.5, 0.3))

# The longest life of a secondary particle, in frames; scene files pass it on as foam.lifetime_frames, which
# normalises the remaining life the cache stores into the age that fades foam out.
SECONDARY_LIFE_MAX = 16.0

WALL_THICKNESS = 0.08
WALL_HEIGHT = 0.6

RENDER_WIDTH = 960
RENDER_HEIGHT = 540
RENDER_SAMPLES = 48
# The render with the liquid mesh: glass needs a few more bounces than the opaque background (in and out of the
# water, and the floor seen through it), and fewer samples keep it near half a minute on two cores.
LIQUID_RENDER_SAMPLES = 32
LIQUID_RENDER_BOUNCES = 8
WATER_IOR = 1.33

# A plain world colour: it lights the scene softly and is the background colour Spindrift falls back on.
WORLD_COLOR = (0.52, 0.62, 0.78)
WORLD_STRENGTH = 0.55

# The liquid's radius is not written: Spindrift derives it from the domain's settings (particle_number: r is
# 1.1 particle spacings, 0.55 cells here) together with how far Mantaflow's mesh stands off the particles.
# Secondary particles are flecks of foam: the foam pipeline draws particle i at FOAM_RADIUS / ((i mod 5) + 1)
# (bubbles at half that), so radii spread between 0.12 and 0.6 cells and the foam reads as flecks of a few
# pixels at this distance.
FOAM_RADIUS = 0.6 * CELL_SIZE

CAMERA_LOCATION = Vector((2.05, -3.35, 1.6))
CAMERA_TARGET = Vector((-0.1, 0.15, 0.3))
CAMERA_LENS_MM = 32.0
CAMERA_SENSOR_MM = 24.0


def log(message):
    print(f"[dam_break] {message}", flush=True)


def parse_arguments():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    parser = argparse.ArgumentParser(prog="bake.py", description=__doc__.split("\n")[0])
    parser.add_argument("--output", required=True, help="directory for cache/, renders/ and scene.json")
    parser.add_argument("--skip-bake", action="store_true", help="reuse the cache already in OUTPUT/cache")
    parser.add_argument("--skip-render", action="store_true", help="reuse OUTPUT/renders/background.exr")
    parser.add_argument("--skip-liquid-render", action="store_true", help="reuse OUTPUT/renders/with_liquid.exr")
    return parser.parse_args(argv)


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


def make_material(name, color, roughness=0.6):
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    principled = material.node_tree.nodes["Principled BSDF"]
    principled.inputs["Base Color"].default_value = (*color, 1.0)
    principled.inputs["Roughness"].default_value = roughness
    return material


def make_checker_material(name, color_a, color_b, scale):
    """A tiled floor: the pattern shows how the liquid refracts what lies beneath it."""
    material = make_material(name, color_a, roughness=0.5)
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


def build_static_geometry():
    """Floor, three walls around the domain and the obstacle: everything the background render shows."""
    floor = add_plane("Floor", 24.0, (0.0, 0.0, 0.0))
    floor.data.materials.append(make_checker_material("FloorTiles", (0.62, 0.6, 0.56), (0.36, 0.35, 0.33),
                                                      scale=12.0))

    # The walls stand just outside the domain, whose own borders are what the liquid collides with.
    wall_material = make_material("Concrete", (0.72, 0.7, 0.66), roughness=0.8)
    domain_max = DOMAIN_MIN + DOMAIN_SIZE
    t = WALL_THICKNESS
    walls = [
        ("WallBack", Vector((DOMAIN_MIN.x - t, domain_max.y, 0.0)),
         Vector((domain_max.x + t, domain_max.y + t, WALL_HEIGHT))),
        ("WallLeft", Vector((DOMAIN_MIN.x - t, DOMAIN_MIN.y, 0.0)),
         Vector((DOMAIN_MIN.x, domain_max.y, WALL_HEIGHT))),
        ("WallRight", Vector((domain_max.x, DOMAIN_MIN.y, 0.0)),
         Vector((domain_max.x + t, domain_max.y, WALL_HEIGHT))),
    ]
    for name, box_min, box_max in walls:
        add_box(name, box_min, box_max).data.materials.append(wall_material)

    obstacle = add_box("Obstacle", OBSTACLE_MIN, OBSTACLE_MAX)
    obstacle.data.materials.append(make_material("Painted", (0.75, 0.22, 0.08), roughness=0.45))
    return obstacle


def configure_domain(domain, cache_directory):
    modifier = domain.modifiers.new("Fluid", 'FLUID')
    modifier.fluid_type = 'DOMAIN'
    settings = modifier.domain_settings
    settings.domain_type = 'LIQUID'
    settings.simulation_method = 'FLIP'
    settings.resolution_max = RESOLUTION
    settings.use_adaptive_domain = False  # an adaptive domain would move the cache's origin every frame

    settings.cache_type = 'ALL'
    settings.cache_frame_start = FRAME_START
    settings.cache_frame_end = FRAME_END
    settings.cache_data_format = 'OPENVDB'
    settings.cache_mesh_format = 'BOBJECT'

    # The liquid mesh is cached for later comparison and for renderers that want a surface.
    settings.use_mesh = True
    settings.mesh_scale = 1

    settings.use_spray_particles = True
    settings.use_foam_particles = True
    settings.use_bubble_particles = True
    settings.sndparticle_combined_export = 'OFF'
    # Mantaflow's default potentials, with sampling well below its defaults (300 wave crest, 40 trapped air):
    # in trials here trapped-air sampling of 10 already piled up over 100k bubbles by the last frame, and the
    # secondary files grew to ~10 MB a frame. With these values the splash at the default frame has a few
    # thousand particles of each kind and the last frames about 200k in all, mostly bubbles and foam.
    settings.sndparticle_potential_min_wavecrest = 2.0
    settings.sndparticle_potential_max_wavecrest = 8.0
    settings.sndparticle_potential_min_trappedair = 5.0
    settings.sndparticle_potential_max_trappedair = 20.0
    settings.sndparticle_potential_min_energy = 1.0
    settings.sndparticle_potential_max_energy = 5.0
    settings.sndparticle_sampling_wavecrest = 150
    settings.sndparticle_sampling_trappedair = 6
    settings.sndparticle_life_min = 6.0
    settings.sndparticle_life_max = SECONDARY_LIFE_MAX

    # Last: changing almost any domain setting makes Blender free the cache in the domain's cache directory,
    # files on disk included.
    settings.cache_directory = cache_directory
    return settings


def build_fluid_objects(cache_directory, obstacle):
    domain = add_box("LiquidDomain", DOMAIN_MIN, DOMAIN_MIN + DOMAIN_SIZE)
    domain_settings = configure_domain(domain, cache_directory)

    column = add_box("WaterColumn", COLUMN_MIN, COLUMN_MAX)
    flow = column.modifiers.new("Fluid", 'FLUID')
    flow.fluid_type = 'FLOW'
    flow.flow_settings.flow_type = 'LIQUID'
    flow.flow_settings.flow_behavior = 'GEOMETRY'  # fill once at the first frame: a column, not a tap

    collision = obstacle.modifiers.new("Fluid", 'FLUID')
    collision.fluid_type = 'EFFECTOR'
    collision.effector_settings.effector_type = 'COLLISION'

    # The liquid is Spindrift's job: neither the domain nor the flow source appears in the background.
    for obj in (domain, column):
        obj.hide_render = True
        obj.display_type = 'WIRE'
    return domain, domain_settings


def build_camera():
    camera_data = bpy.data.cameras.new("Camera")
    camera_data.sensor_fit = 'VERTICAL'  # so angle_y is the vertical field of view scene.json records
    camera_data.sensor_height = CAMERA_SENSOR_MM
    camera_data.lens = CAMERA_LENS_MM
    camera_data.clip_start = 0.05
    camera_data.clip_end = 100.0
    camera = bpy.data.objects.new("Camera", camera_data)
    camera.location = CAMERA_LOCATION
    camera.rotation_euler = (CAMERA_TARGET - CAMERA_LOCATION).to_track_quat('-Z', 'Y').to_euler()
    bpy.context.scene.collection.objects.link(camera)
    bpy.context.scene.camera = camera
    return camera


def build_lighting():
    sun_data = bpy.data.lights.new("Sun", 'SUN')
    sun_data.energy = 2.2
    sun_data.angle = math.radians(3.0)  # slightly soft shadows
    sun = bpy.data.objects.new("Sun", sun_data)
    sun.rotation_euler = (math.radians(40.0), math.radians(15.0), math.radians(-35.0))
    bpy.context.scene.collection.objects.link(sun)

    world = bpy.data.worlds.new("World")
    world.use_nodes = True
    background = world.node_tree.nodes["Background"]
    background.inputs["Color"].default_value = (*WORLD_COLOR, 1.0)
    background.inputs["Strength"].default_value = WORLD_STRENGTH
    bpy.context.scene.world = world


def build_scene(cache_directory):
    scene = bpy.context.scene
    scene.frame_start = FRAME_START
    scene.frame_end = FRAME_END
    clear_scene()
    obstacle = build_static_geometry()
    domain, domain_settings = build_fluid_objects(cache_directory, obstacle)
    camera = build_camera()
    build_lighting()
    bpy.context.view_layer.update()
    return domain, domain_settings, camera


def bake(domain, cache_directory):
    # A partial cache from an interrupted bake would be mixed with the new frames; start clean.
    if os.path.isdir(cache_directory):
        shutil.rmtree(cache_directory)
    os.makedirs(cache_directory)
    log(f"baking frames {FRAME_START}-{FRAME_END} at resolution {RESOLUTION} "
        f"(cell {CELL_SIZE:.4f}) into {cache_directory}")
    view_layer = bpy.context.view_layer
    view_layer.objects.active = domain
    domain.select_set(True)
    started = time.perf_counter()
    # In background mode the operator's exec runs the bake synchronously (no job, no progress bar).
    with bpy.context.temp_override(active_object=domain, object=domain, scene=bpy.context.scene,
                                   view_layer=view_layer):
        result = bpy.ops.fluid.bake_all()
    elapsed = time.perf_counter() - started
    if result != {'FINISHED'}:
        raise RuntimeError(f"fluid.bake_all returned {result}")
    missing = [path for path in expected_cache_files(cache_directory) if not os.path.isfile(path)]
    if missing:
        raise RuntimeError(f"the bake left {len(missing)} cache files missing, e.g. {missing[0]}")
    log(f"baked in {elapsed:.1f} s")
    return elapsed


def expected_cache_files(cache_directory):
    """The files prepare.sh checks for: per frame, the liquid data, the secondary particles and the mesh."""
    files = []
    for frame in range(FRAME_START, FRAME_END + 1):
        files.append(os.path.join(cache_directory, "data", f"fluid_data_{frame:04d}.vdb"))
        files.append(os.path.join(cache_directory, "particles", f"fluid_particles_{frame:04d}.vdb"))
        files.append(os.path.join(cache_directory, "mesh", f"fluid_mesh_{frame:04d}.bobj.gz"))
    return files


def report_baked_frame(domain, frame):
    """Prints what Blender reads back from the cache at `frame`: particle counts and the liquid mesh's extent.

    Blender's particle systems give the counts only: in Blender 3.4.1 their positions are displaced for a
    domain that is not a cube (by about -0.73 along y here). The liquid mesh is placed correctly, and its
    extent relative to the domain's minimum corner is what the cache's particle positions should match
    (examples/README.md compares them).
    """
    bpy.context.scene.frame_set(frame)
    evaluated = domain.evaluated_get(bpy.context.evaluated_depsgraph_get())
    counts = {system.name: len(system.particles) for system in evaluated.particle_systems}
    log(f"particles at frame {frame}: " + ", ".join(f"{name} {count}" for name, count in counts.items()))

    corner = domain_minimum_corner(domain)
    mesh = evaluated.to_mesh()
    points = [domain.matrix_world @ vertex.co - corner for vertex in mesh.vertices]
    evaluated.to_mesh_clear()
    if points:
        low = [min(p[axis] for p in points) for axis in range(3)]
        high = [max(p[axis] for p in points) for axis in range(3)]
        log(f"liquid mesh at frame {frame}, relative to the domain's minimum corner: "
            f"({low[0]:.4f} {low[1]:.4f} {low[2]:.4f}) - ({high[0]:.4f} {high[1]:.4f} {high[2]:.4f})")
    return counts


def configure_background_render(scene, render_directory):
    scene.render.engine = 'CYCLES'
    scene.cycles.device = 'CPU'
    scene.cycles.samples = RENDER_SAMPLES
    scene.cycles.use_adaptive_sampling = True
    scene.cycles.use_denoising = False  # Debian's Blender has no OpenImageDenoise; rendering would fail
    scene.cycles.max_bounces = 4
    scene.render.resolution_x = RENDER_WIDTH
    scene.render.resolution_y = RENDER_HEIGHT
    scene.render.resolution_percentage = 100
    scene.render.film_transparent = False
    # Standard, not Filmic: the PNG preview is then plain sRGB of the EXR's linear values, which is how
    # Spindrift displays the background too.
    scene.view_settings.view_transform = 'Standard'
    scene.view_settings.look = 'None'
    scene.view_layers[0].use_pass_z = True  # planar eye depth, 1e10 where a ray meets only the sky

    settings = scene.render.image_settings
    settings.file_format = 'OPEN_EXR_MULTILAYER'
    settings.color_depth = '32'  # half floats would turn the sky's depth of 1e10 into infinity
    settings.exr_codec = 'ZIP'
    scene.render.filepath = os.path.join(render_directory, "background.exr")
    scene.render.use_file_extension = False


def render_background(scene, render_directory):
    os.makedirs(render_directory, exist_ok=True)
    configure_background_render(scene, render_directory)
    log(f"rendering the background ({RENDER_WIDTH}x{RENDER_HEIGHT}, {RENDER_SAMPLES} samples, CPU)")
    started = time.perf_counter()
    bpy.ops.render.render(write_still=True)
    elapsed = time.perf_counter() - started
    log(f"rendered {scene.render.filepath} in {elapsed:.1f} s")

    # The same render result, as the PNG preview the README shows.
    preview_path = os.path.join(render_directory, "background.png")
    settings = scene.render.image_settings
    settings.file_format = 'PNG'
    settings.color_mode = 'RGB'
    settings.color_depth = '8'
    bpy.data.images["Render Result"].save_render(preview_path, scene=scene)
    log(f"wrote {preview_path}")
    return elapsed


def render_with_liquid(scene, domain, domain_settings, cache_directory, render_directory):
    """Renders the showcase frame with Mantaflow's liquid mesh as water: the full render foam is composited over.

    The domain reads a copy of the cache in replay mode, so Blender never frees (deletes) the real cache and
    never simulates: every file of the frame is already there. The domain's evaluated mesh is then the liquid
    mesh of `cache/mesh/fluid_mesh_####.bobj.gz`; it renders as glass of water's index of refraction.
    """
    os.makedirs(render_directory, exist_ok=True)
    configure_background_render(scene, render_directory)
    scene.cycles.samples = LIQUID_RENDER_SAMPLES
    scene.cycles.max_bounces = LIQUID_RENDER_BOUNCES
    scene.cycles.transmission_bounces = LIQUID_RENDER_BOUNCES
    scene.cycles.transparent_max_bounces = LIQUID_RENDER_BOUNCES
    # Caustics through glass are what makes fireflies at few samples; the floor seen through the water and the
    # reflections do not need them.
    scene.cycles.caustics_reflective = False
    scene.cycles.caustics_refractive = False
    scene.cycles.blur_glossy = 1.0
    scene.cycles.sample_clamp_indirect = 4.0
    scene.render.filepath = os.path.join(render_directory, "with_liquid.exr")

    # Changing the domain's cache settings makes Blender free (delete) the bake in the directory the domain
    # points at. The real cache is moved aside first, so nothing is there to delete, and put back at the end.
    stash = cache_directory.rstrip(os.sep) + ".stash"
    os.rename(cache_directory, stash)
    try:
        copy = tempfile.TemporaryDirectory(prefix="dam_break_replay_")
        replay_cache = os.path.join(copy.name, "cache")
        shutil.copytree(stash, replay_cache)
        domain_settings.cache_type = 'REPLAY'
        domain_settings.cache_directory = replay_cache

        water = bpy.data.materials.new("Water")
        water.use_nodes = True
        nodes = water.node_tree.nodes
        nodes.remove(nodes["Principled BSDF"])
        glass = nodes.new("ShaderNodeBsdfGlass")
        glass.inputs["IOR"].default_value = WATER_IOR
        glass.inputs["Roughness"].default_value = 0.0
        # Without caustics the glass would cast a black shadow; shadow rays pass through it instead, so the floor
        # under the water is lit as under clear water.
        light_path = nodes.new("ShaderNodeLightPath")
        transparent = nodes.new("ShaderNodeBsdfTransparent")
        mix = nodes.new("ShaderNodeMixShader")
        links = water.node_tree.links
        links.new(light_path.outputs["Is Shadow Ray"], mix.inputs["Fac"])
        links.new(glass.outputs["BSDF"], mix.inputs[1])
        links.new(transparent.outputs["BSDF"], mix.inputs[2])
        links.new(mix.outputs["Shader"], nodes["Material Output"].inputs["Surface"])
        domain.data.materials.clear()
        domain.data.materials.append(water)
        domain.hide_render = False
        # The secondary particles are Spindrift's foam: they must not show in this render.
        for system in domain.particle_systems:
            system.settings.render_type = 'NONE'

        scene.frame_set(SHOWCASE_FRAME)
        evaluated = domain.evaluated_get(bpy.context.evaluated_depsgraph_get())
        vertices = len(evaluated.data.vertices)
        if vertices == 0:
            raise RuntimeError(f"the liquid mesh of frame {SHOWCASE_FRAME} did not load from {replay_cache}")
        log(f"rendering the frame with the liquid mesh ({vertices} vertices, glass IOR {WATER_IOR}, "
            f"{LIQUID_RENDER_SAMPLES} samples, CPU)")
        started = time.perf_counter()
        bpy.ops.render.render(write_still=True)
        elapsed = time.perf_counter() - started
        log(f"rendered {scene.render.filepath} in {elapsed:.1f} s")
        copy.cleanup()
    finally:
        if os.path.isdir(cache_directory):
            shutil.rmtree(cache_directory)  # Only what Blender may have recreated, empty, while freeing.
        os.rename(stash, cache_directory)
    return elapsed


def row_major(matrix):
    """A 4x4 matrix as 16 numbers, row by row, rounded so the file is stable and readable."""
    return [clean_number(matrix[row][column]) for row in range(4) for column in range(4)]


def clean_number(value, digits=6):
    # Adding 0.0 turns -0.0 into 0.0, so a value that rounds to zero is always written the same way.
    return round(value, digits) + 0.0


def domain_minimum_corner(domain):
    # The box's own vertices: once baked, the object's bound_box is that of the evaluated liquid mesh.
    corners = [domain.matrix_world @ vertex.co for vertex in domain.data.vertices]
    return Vector((min(c.x for c in corners), min(c.y for c in corners), min(c.z for c in corners)))


def camera_description(camera):
    return {
        "width": RENDER_WIDTH,
        "height": RENDER_HEIGHT,
        "fov_y_deg": clean_number(math.degrees(camera.data.angle_y)),
        "near": clean_number(camera.data.clip_start),
        "far": clean_number(camera.data.clip_end),
        "world_from_camera": row_major(camera.matrix_world),
    }


# The domain settings that shape Mantaflow's liquid mesh, as the scene file's `domain` object names them:
# Spindrift derives the liquid's radius and surface offset from them and reads the cell size and the domain's
# transform from the cache's config files (docs/mantaflow-caches.md).
MESH_SETTINGS = ("particle_radius", "mesh_particle_radius", "mesh_scale", "mesh_smoothen_pos", "mesh_smoothen_neg",
                 "mesh_concave_upper", "mesh_concave_lower", "particle_number", "mesh_generator")


def domain_description(domain):
    settings = domain.modifiers["Fluid"].domain_settings
    return {name: clean_number(value) if isinstance(value, float) else value
            for name, value in ((name, getattr(settings, name)) for name in MESH_SETTINGS)}


def particle_sources(domain):
    """The liquid and the foam source, in this order."""
    # Mantaflow writes positions in the domain's local frame with its minimum corner at the origin, in world
    # units; the domain has no rotation or scale, so file -> world is a translation to that corner. The liquid
    # source reads it from the cache's config instead; the foam source states it.
    world_from_file = row_major(Matrix.Translation(domain_minimum_corner(domain)))
    return [
        {
            "path": "cache/data/fluid_data_####.vdb",
            "grid": "particles",
            "role": "liquid",
            "domain": domain_description(domain),
        },
        {
            "path": "cache/particles/fluid_particles_####.vdb",
            "grid": "particles_secondary",
            "role": "foam",
            "radius": clean_number(FOAM_RADIUS),
            "world_from_file": world_from_file,
        },
    ]


def scene_description(camera, domain):
    """The Spindrift scene file (version 1) for this example, with paths relative to the file: liquid and foam
    over the background render, which has no liquid in it."""
    return {
        "version": 1,
        "frame": SHOWCASE_FRAME,
        "camera": camera_description(camera),
        "particles": particle_sources(domain),
        "background": {
            "image": "renders/background.exr",
            "color": [clean_number(c) for c in WORLD_COLOR],
        },
        "foam": {"lifetime_frames": SECONDARY_LIFE_MAX},
    }


def foam_only_scene_description(camera, domain):
    """Foam only, over the full render that already holds the liquid mesh: with no liquid source Spindrift
    renders no liquid; the solids' depth comes from the background render, the liquid's surface from the
    depth of the render with the liquid, and foam behind that surface fades with its depth below it."""
    return {
        "version": 1,
        "frame": SHOWCASE_FRAME,
        "camera": camera_description(camera),
        "particles": particle_sources(domain)[1:],
        "background": {
            "image": "renders/with_liquid.exr",
            "depth": "renders/background.exr",
            "liquid_depth": "renders/with_liquid.exr",
            "color": [clean_number(c) for c in WORLD_COLOR],
        },
        "foam": {"lifetime_frames": SECONDARY_LIFE_MAX},
    }


def format_scene_json(description):
    """Indented JSON with every list of numbers on one line, so a matrix reads as a matrix."""
    text = json.dumps(description, indent=2)
    number_list = re.compile(r"\[\s*([-0-9.e+]+(?:,\s*[-0-9.e+]+)*)\s*\]")
    return number_list.sub(lambda match: "[" + re.sub(r"\s+", " ", match.group(1)) + "]", text) + "\n"


def check_domain_transform(domain):
    """Fails loudly if the domain's transform is more than a translation, which scene.json assumes."""
    linear = domain.matrix_world.to_3x3()
    if any(abs(linear[r][c] - (1.0 if r == c else 0.0)) > 1e-9 for r in range(3) for c in range(3)):
        raise RuntimeError("the liquid domain must have no rotation and unit scale")


def write_scene_file(path, description, domain):
    check_domain_transform(domain)
    text = format_scene_json(description)
    with open(path, "w", encoding="utf-8") as handle:
        handle.write(text)
    log(f"wrote {path}")


def main():
    arguments = parse_arguments()
    output = os.path.abspath(arguments.output)
    cache_directory = os.path.join(output, "cache")
    render_directory = os.path.join(output, "renders")
    os.makedirs(output, exist_ok=True)

    log("building the scene")
    # Without a bake in this session Blender does not know the cache on disk is a finished bake, and may free
    # it; the domain then gets a scratch directory (the render with the liquid reads a copy of the cache).
    scratch = tempfile.TemporaryDirectory(prefix="dam_break_cache_") if arguments.skip_bake else None
    domain, domain_settings, camera = build_scene(scratch.name if scratch else cache_directory)
    scene = bpy.context.scene

    if arguments.skip_bake:
        log("skipping the bake: reusing the cache")
    else:
        bake(domain, cache_directory)
        report_baked_frame(domain, SHOWCASE_FRAME)

    if arguments.skip_render:
        log("skipping the render: reusing renders/background.exr")
    else:
        scene.frame_set(SHOWCASE_FRAME)
        render_background(scene, render_directory)

    if arguments.skip_liquid_render:
        log("skipping the render with the liquid: reusing renders/with_liquid.exr")
    else:
        render_with_liquid(scene, domain, domain_settings, cache_directory, render_directory)

    write_scene_file(os.path.join(output, "scene.json"), scene_description(camera, domain), domain)
    write_scene_file(os.path.join(output, "scene_foam_only.json"), foam_only_scene_description(camera, domain),
                     domain)
    if scratch:
        scratch.cleanup()
    log("done")


if __name__ == "__main__":
    main()
