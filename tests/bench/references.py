"""Renders the benchmark's references with Cycles, from an example's own Mantaflow bake.

Run inside Blender (tests/bench/benchmark.py does this when a reference is missing):

    blender -b --factory-startup --python-exit-code 1 --python tests/bench/references.py -- \
        --example examples/drop --output build/bench/references/drop [--width 480 --height 270 ...]

The scene is built by the example's own bake.py (its `LAYOUT` and `build_scene`, over examples/bakelib), never
copied here. For every camera of
EXAMPLE/cameras.json it writes into OUTPUT/CAMERA/:

- background.exr: everything but the liquid, colour and planar depth (Spindrift's background);
- liquid_passes.exr: Mantaflow's liquid mesh alone, Depth and Normal passes at one sample through the pixel
  centre (the geometric truth for depth, silhouette and normals);
- reference.exr: the whole scene with the liquid mesh as water (glass, IOR 1.33, Beer-Lambert absorption
  matching liquid.absorption_rgb) at --reference-spp samples;
- scene.json: the Spindrift scene file for this camera, pointing at the example's cache and background.exr;
- for --sweep-camera, cycles_spp_NNNN.exr for every --sweep-spp, and cycles_timings.json (wall seconds).
  With --retime-sweep every sweep render is made again (same seed: the same image), so that the times are
  this run's, on this host's load, as Spindrift's are; the previous times stay in the file as
  "earlier" for comparison.

In reference.exr the water casts no shadow (Cycles ray visibility): Spindrift refracts the background render,
whose floor is lit, so a shadowed floor under the water would measure the light model rather than the
screen-space surface. With --full-references, what a user's render shows besides (docs/benchmarks.md,
"Against the user's render"):

- reference_full.exr: the same with the water casting its shadow and caustics;
- background_light_passes.exr: background.exr with Cycles' light passes (DiffDir, DiffInd, DiffCol, GlossDir,
  GlossInd, GlossCol), which Spindrift's shadow and caustics apply to;
- scene_sun.json: scene.json with the scene's sun (as the Blender add-on exports it) over that background;
- for --sweep-camera, cycles_full_spp_NNNN.exr and cycles_full_timings.json, the sweep with the shadow.

With --whitewater PLY (the frame's spray, foam and bubbles, `spindrift_export_particles ... whitewater`), what
the user's render shows when it renders Mantaflow's whitewater as well (tests/bench/foam_light.py):

- reference_full_whitewater.exr: reference_full.exr with every whitewater particle a white diffuse sphere
  (albedo WHITEWATER_ALBEDO) of the particle's radius, as Blender renders a point cloud; the spheres cast
  shadows and the ones under the water are seen through it.

With --sun-factor, the sun's light on the floor under the water as Cycles finds it (tests/bench/sun_report.py
compares it with Spindrift's and with an exact trace), both with the world's light off:

- sun_only_dry.exr: the scene without the water, lit by its lamps alone;
- sun_only_under_water.exr: the same with the water casting its shadow and caustics but hidden from the
  camera, so that the camera sees the floor under it directly.
"""

import argparse
import gzip
import importlib.util
import json
import os
import struct
import sys
import tempfile
import time

import bpy
from mathutils import Vector

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "examples"))
from bakelib import render as example_render, scene_file  # noqa: E402 (Blender runs this file by path)
# The add-on's own lamp export, so that scene_sun.json holds what a user's scene file would; the add-on loads
# its native module only when it renders, so importing it here needs no build.
sys.path.insert(0, os.path.join(ROOT, "addon"))
from spindrift import export as addon_export  # noqa: E402


def log(message):
    print(f"[references] {message}", flush=True)


def parse_arguments():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    parser = argparse.ArgumentParser(prog="references.py", description=__doc__.split("\n")[0])
    parser.add_argument("--example", required=True, help="example directory with bake.py, cameras.json, cache/")
    parser.add_argument("--output", required=True)
    parser.add_argument("--cameras", default="", help="comma-separated camera names (default: all)")
    parser.add_argument("--width", type=int, default=480)
    parser.add_argument("--height", type=int, default=270)
    parser.add_argument("--background-spp", type=int, default=64)
    parser.add_argument("--reference-spp", type=int, default=256)
    parser.add_argument("--sweep-camera", default="oblique")
    parser.add_argument("--sweep-spp", default="", help="comma-separated sample counts to time, e.g. 1,4,16")
    parser.add_argument("--retime-sweep", action="store_true",
                        help="render the sweep again even where it exists, for this run's times")
    parser.add_argument("--full-references", action="store_true",
                        help="also the references with the water's shadow and what Spindrift needs for them")
    parser.add_argument("--whitewater", default="",
                        help="with --full-references, also reference_full_whitewater.exr with this PLY's "
                             "whitewater (spindrift_export_particles ... whitewater) as white spheres")
    parser.add_argument("--sun-factor", action="store_true",
                        help="also the floor lit by the lamps alone, without and under the water")
    parser.add_argument("--absorption-rgb", default="0.9,0.3,0.15",
                        help="a * c_a of Spindrift's equation 9, per world unit")
    return parser.parse_args(argv)


def load_example(directory):
    spec = importlib.util.spec_from_file_location("example_bake", os.path.join(directory, "bake.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def read_bobj(path):
    """Mantaflow's gzipped binary mesh: vertex count and xyz floats, normals likewise, triangles as int triples."""
    data = gzip.open(path).read()
    offset = 0

    def read_block(item_format, item_size):
        nonlocal offset
        count = struct.unpack_from("<i", data, offset)[0]
        offset += 4
        items = [struct.unpack_from(item_format, data, offset + i * item_size) for i in range(count)]
        offset += count * item_size
        return items

    vertices = read_block("<3f", 12)
    read_block("<3f", 12)  # per-vertex normals: Cycles interpolates its own from the smooth-shaded mesh
    triangles = read_block("<3i", 12)
    return vertices, triangles


def add_mantaflow_mesh(cache_directory, frame, domain_centre, domain_longest_side, absorption_rgb):
    """Mantaflow's liquid mesh of `frame`, placed as Blender's fluid modifier places it, as water (smooth-shaded,
    casting shadows).

    The bobj's vertices are in the domain's normalised frame: centred on the domain and divided by its
    longest side (checked: dam_break frame 16 spans 0.0213 to 2.8698 m from the minimum corner, as bake.py
    prints for Blender's own evaluated mesh).
    """
    vertices, triangles = read_bobj(os.path.join(cache_directory, "mesh", f"fluid_mesh_{frame:04d}.bobj.gz"))
    world = [tuple(domain_centre + Vector(v) * domain_longest_side) for v in vertices]
    mesh = bpy.data.meshes.new("LiquidMesh")
    mesh.from_pydata(world, [], [tuple(t) for t in triangles])
    mesh.polygons.foreach_set("use_smooth", [True] * len(mesh.polygons))
    mesh.update()
    liquid = bpy.data.objects.new("LiquidMesh", mesh)
    bpy.context.scene.collection.objects.link(liquid)
    liquid.data.materials.append(make_water_material(absorption_rgb))
    log(f"liquid mesh of frame {frame}: {len(world)} vertices, {len(triangles)} triangles")
    return liquid


def add_liquid_mesh(example, cache_directory, frame, absorption_rgb):
    """An example's liquid mesh of `frame` as water casting no shadow (the no-shadow reference)."""
    layout = example.LAYOUT
    liquid = add_mantaflow_mesh(cache_directory, frame, layout.domain_min + layout.domain_size / 2,
                                max(layout.domain_size), absorption_rgb)
    liquid.visible_shadow = False
    return liquid


# A white diffuse material, as whitewater is usually rendered (foam scatters most of the light it gets).
WHITEWATER_ALBEDO = 0.8


def read_ply_rows(path):
    """The float rows of a binary little-endian PLY of float properties (spindrift_export_particles)."""
    with open(path, "rb") as handle:
        data = handle.read()
    header, body = data.split(b"end_header\n", 1)
    lines = header.decode("ascii").split("\n")
    count = int(next(line for line in lines if line.startswith("element vertex")).split()[2])
    columns = sum(line.startswith("property float") for line in lines)
    values = struct.unpack(f"<{count * columns}f", body[:count * columns * 4])
    return [values[i * columns:(i + 1) * columns] for i in range(count)]


def add_whitewater(path):
    """The whitewater of `path` (x, y, z, radius, type rows) as spheres of their radius: a mesh of points that
    geometry nodes turn into a point cloud, which Cycles renders as spheres. Hidden until a render shows it."""
    rows = read_ply_rows(path)
    mesh = bpy.data.meshes.new("Whitewater")
    mesh.vertices.add(len(rows))
    mesh.vertices.foreach_set("co", [c for row in rows for c in row[:3]])
    radius = mesh.attributes.new("radius", 'FLOAT', 'POINT')
    radius.data.foreach_set("value", [row[3] for row in rows])
    mesh.update()
    whitewater = bpy.data.objects.new("Whitewater", mesh)
    bpy.context.scene.collection.objects.link(whitewater)
    material = bpy.data.materials.new("Whitewater")
    material.use_nodes = True
    surface = material.node_tree.nodes["Principled BSDF"]
    surface.inputs["Base Color"].default_value = (WHITEWATER_ALBEDO, WHITEWATER_ALBEDO, WHITEWATER_ALBEDO, 1)
    surface.inputs["Roughness"].default_value = 1.0
    surface.inputs["Specular"].default_value = 0.0
    group = bpy.data.node_groups.new("WhitewaterPoints", 'GeometryNodeTree')
    group.inputs.new('NodeSocketGeometry', "Geometry")
    group.outputs.new('NodeSocketGeometry', "Geometry")
    nodes, links = group.nodes, group.links
    to_points = nodes.new('GeometryNodeMeshToPoints')
    named = nodes.new('GeometryNodeInputNamedAttribute')
    named.data_type = 'FLOAT'
    named.inputs["Name"].default_value = "radius"
    set_material = nodes.new('GeometryNodeSetMaterial')
    set_material.inputs["Material"].default_value = material
    links.new(nodes.new('NodeGroupInput').outputs["Geometry"], to_points.inputs["Mesh"])
    # The node has an output per data type, all named "Attribute"; the float one is enabled.
    radius_output = next(output for output in named.outputs if output.enabled and output.type == 'VALUE')
    links.new(radius_output, to_points.inputs["Radius"])
    links.new(to_points.outputs["Points"], set_material.inputs["Geometry"])
    links.new(set_material.outputs["Geometry"], nodes.new('NodeGroupOutput').inputs["Geometry"])
    whitewater.modifiers.new("Points", 'NODES').node_group = group
    whitewater.hide_render = True
    log(f"whitewater: {len(rows)} particles")
    return whitewater


def make_water_material(absorption_rgb):
    """Glass with IOR 1.33 and a volume that absorbs exp(-l c) per channel, as Spindrift's equation 9.

    Cycles' Volume Absorption removes density * (1 - colour) per unit length, so density is the largest
    coefficient and each channel's colour is 1 - c / density.
    """
    material = bpy.data.materials.new("Water")
    material.use_nodes = True
    nodes, links = material.node_tree.nodes, material.node_tree.links
    nodes.remove(nodes["Principled BSDF"])
    output = nodes["Material Output"]
    glass = nodes.new("ShaderNodeBsdfGlass")
    glass.distribution = 'SHARP'
    glass.inputs["IOR"].default_value = 1.33
    glass.inputs["Color"].default_value = (1, 1, 1, 1)
    links.new(glass.outputs["BSDF"], output.inputs["Surface"])
    density = max(absorption_rgb)
    absorption = nodes.new("ShaderNodeVolumeAbsorption")
    absorption.inputs["Density"].default_value = density
    absorption.inputs["Color"].default_value = (*[1 - c / density for c in absorption_rgb], 1)
    links.new(absorption.outputs["Volume"], output.inputs["Volume"])
    return material


def place_camera(camera, definition, width, height):
    camera.location = Vector(definition["location"])
    direction = Vector(definition["target"]) - camera.location
    camera.rotation_euler = direction.to_track_quat('-Z', 'Y').to_euler()
    camera.data.lens = definition["lens_mm"]
    scene = bpy.context.scene
    scene.render.resolution_x, scene.render.resolution_y = width, height
    bpy.context.view_layer.update()


def write_scene_file(example, camera, domain, example_directory, path, width, height):
    description = scene_file.scene_description(example.LAYOUT, camera, domain)
    description["camera"]["width"], description["camera"]["height"] = width, height
    for source in description["particles"]:
        source["path"] = os.path.join(example_directory, source["path"])
    description["background"]["image"] = "background.exr"
    with open(path, "w", encoding="utf-8") as handle:
        handle.write(scene_file.format_scene_json(description))


LIGHT_PASSES = ("use_pass_diffuse_direct", "use_pass_diffuse_indirect", "use_pass_diffuse_color",
                "use_pass_glossy_direct", "use_pass_glossy_indirect", "use_pass_glossy_color")


def scene_lights():
    """The scene's lamps as the Blender add-on exports them (addon/spindrift/export.py; the examples light
    their scene with one sun and the world, examples/bakelib/blender_scene.py), rounded as the rest of the
    scene file."""
    def rounded(value):
        if isinstance(value, list):
            return [rounded(v) for v in value]
        return scene_file.clean_number(value) if isinstance(value, float) else value

    lights = addon_export.scene_lights(bpy.context.evaluated_depsgraph_get())
    return [{key: rounded(value) for key, value in light.items()} for light in lights]


def write_sun_scene_file(directory):
    """scene_sun.json: the camera's scene file with the scene's lamps, over the background with light passes."""
    with open(os.path.join(directory, "scene.json"), encoding="utf-8") as handle:
        description = json.load(handle)
    description["background"]["image"] = "background_light_passes.exr"
    description["lights"] = scene_lights()
    with open(os.path.join(directory, "scene_sun.json"), "w", encoding="utf-8") as handle:
        handle.write(scene_file.format_scene_json(description))


def render(path, samples, seed=0):
    """Renders the current scene to a 32-bit multilayer EXR; returns the wall time in seconds."""
    scene = bpy.context.scene
    scene.cycles.samples = samples
    scene.cycles.seed = seed
    scene.render.filepath = path
    started = time.perf_counter()
    bpy.ops.render.render(write_still=True)
    return time.perf_counter() - started


def set_visible(objects, visible):
    for obj in objects:
        obj.hide_render = not visible


def configure_cycles(example, output):
    scene = bpy.context.scene
    layout = example.LAYOUT
    example_render.configure_background_render(scene, output, layout.render_width, layout.render_height,
                                               layout.render_samples)
    # Adaptive sampling would make "N samples" mean fewer on easy pixels; the sweep wants exactly N.
    scene.cycles.use_adaptive_sampling = False
    set_water_bounces(scene)
    scene.view_layers[0].use_pass_normal = True


# Bounces of every kind a path through water takes. A reflection is a glossy bounce in Cycles, total internal
# reflection included, and Cycles' default of 4 glossy bounces ends a path at its fifth: light guided along a
# sheet of water by total internal reflection came out black. Measured on the dam break's frame 16 (256 spp,
# 2026-12-04): from glossy 4 to 16 the water's mean colour over the grazing camera's water went from (0.130,
# 0.169, 0.205) to (0.142, 0.211, 0.267), the reference moving by an MAE of 0.039; from 16 to 64 by 0.005 more.
# The 256-sample render took the same time. Compact bodies (tests/bench/thick_bodies.py) moved by 0.0004 at most.
WATER_BOUNCES = 64


def set_water_bounces(scene):
    """Enough bounces that no path through the water is cut short; diffuse bounces keep Cycles' default (the
    background's own light, which Spindrift composites over, is rendered the same way)."""
    for kind in ("max_bounces", "transmission_bounces", "transparent_max_bounces", "glossy_bounces"):
        setattr(scene.cycles, kind, WATER_BOUNCES)
    scene.cycles.volume_bounces = 0


def empty_cycles_scene(samples, clamp_indirect, size):
    """An empty scene (Blender's factory settings) that Cycles renders on the CPU at `size` x `size` pixels
    with exactly `samples` samples a pixel, no denoising, the water's bounces and Cycles' indirect clamp at
    `clamp_indirect` (0: off): the small experiments that measure Cycles against closed-form optics."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.engine = 'CYCLES'
    scene.cycles.device = 'CPU'
    scene.cycles.samples = samples
    scene.cycles.use_denoising = False
    scene.cycles.use_adaptive_sampling = False
    set_water_bounces(scene)
    scene.cycles.sample_clamp_indirect = clamp_indirect
    scene.render.resolution_x = scene.render.resolution_y = size
    return scene


def render_camera(arguments, example, camera, domain, liquid, definition, example_directory, whitewater=None):
    scene = bpy.context.scene
    directory = os.path.join(arguments.output, definition["name"])
    os.makedirs(directory, exist_ok=True)
    place_camera(camera, definition, arguments.width, arguments.height)
    write_scene_file(example, camera, domain, example_directory, os.path.join(directory, "scene.json"),
                     arguments.width, arguments.height)
    solids = [obj for obj in scene.objects
              if obj.type == 'MESH' and obj != liquid and not obj.hide_render]

    def missing(name):
        return not os.path.isfile(os.path.join(directory, name))

    if missing("background.exr"):
        set_visible([liquid], False)
        seconds = render(os.path.join(directory, "background.exr"), arguments.background_spp)
        log(f"{definition['name']}: background in {seconds:.1f} s")
        set_visible([liquid], True)
    if missing("liquid_passes.exr"):
        # One sample through each pixel's centre: depth and normal of exactly the surface the ray meets.
        set_visible(solids, False)
        scene.render.film_transparent = True
        filter_width = scene.cycles.filter_width
        scene.cycles.filter_width = 0.01
        render(os.path.join(directory, "liquid_passes.exr"), 1)
        scene.cycles.filter_width = filter_width
        scene.render.film_transparent = False
        set_visible(solids, True)
    if missing("reference.exr"):
        seconds = render(os.path.join(directory, "reference.exr"), arguments.reference_spp)
        log(f"{definition['name']}: reference ({arguments.reference_spp} spp) in {seconds:.1f} s")
    if definition["name"] == arguments.sweep_camera and arguments.sweep_spp:
        sweep(directory, definition["name"], arguments.sweep_spp, "cycles_spp", "cycles_timings.json",
              arguments.retime_sweep)
    if arguments.sun_factor:
        render_sun_factor(directory, liquid, arguments.reference_spp)
    if not arguments.full_references:
        return
    write_sun_scene_file(directory)
    layer = scene.view_layers[0]
    if missing("background_light_passes.exr"):
        set_visible([liquid], False)
        for name in LIGHT_PASSES:
            setattr(layer, name, True)
        seconds = render(os.path.join(directory, "background_light_passes.exr"), arguments.background_spp)
        for name in LIGHT_PASSES:
            setattr(layer, name, False)
        set_visible([liquid], True)
        log(f"{definition['name']}: background with light passes in {seconds:.1f} s")
    liquid.visible_shadow = True
    if missing("reference_full.exr"):
        seconds = render(os.path.join(directory, "reference_full.exr"), arguments.reference_spp)
        log(f"{definition['name']}: reference with the water's shadow ({arguments.reference_spp} spp) in "
            f"{seconds:.1f} s")
    if definition["name"] == arguments.sweep_camera and arguments.sweep_spp:
        sweep(directory, definition["name"], arguments.sweep_spp, "cycles_full_spp", "cycles_full_timings.json",
              arguments.retime_sweep)
    if whitewater and missing("reference_full_whitewater.exr"):
        set_visible([whitewater], True)
        seconds = render(os.path.join(directory, "reference_full_whitewater.exr"), arguments.reference_spp)
        set_visible([whitewater], False)
        log(f"{definition['name']}: reference with the water's shadow and the whitewater "
            f"({arguments.reference_spp} spp) in {seconds:.1f} s")
    liquid.visible_shadow = False


def render_sun_factor(directory, liquid, samples):
    """The floor lit by the lamps alone, dry and under the water, which the camera does not see: their ratio
    is the part of the lamps' light that reaches each point of the floor through the water, as Cycles'
    path tracing (caustics through the refracting surface included, Cycles' default clamp) finds it."""
    strength = bpy.context.scene.world.node_tree.nodes["Background"].inputs["Strength"]
    world_strength = strength.default_value
    strength.default_value = 0.0
    try:
        if not os.path.isfile(os.path.join(directory, "sun_only_dry.exr")):
            set_visible([liquid], False)
            render(os.path.join(directory, "sun_only_dry.exr"), samples)
            set_visible([liquid], True)
        if not os.path.isfile(os.path.join(directory, "sun_only_under_water.exr")):
            liquid.visible_shadow = True
            liquid.visible_camera = False
            seconds = render(os.path.join(directory, "sun_only_under_water.exr"), samples)
            liquid.visible_camera = True
            liquid.visible_shadow = False
            log(f"{os.path.basename(directory)}: the lamps' light under the water ({samples} spp) in {seconds:.1f} s")
    finally:
        strength.default_value = world_strength


def sweep(directory, camera_name, sample_counts, prefix, timings_name, retime=False):
    """Renders the scene as it is set up at each sample count (missing ones only, or all with `retime`) and
    records the wall times: {"1": seconds, ...}, and with `retime` the replaced times under "earlier"."""
    timings_path = os.path.join(directory, timings_name)
    timings = json.load(open(timings_path)) if os.path.isfile(timings_path) else {}
    earlier = timings.pop("earlier", {})
    for samples in [int(s) for s in sample_counts.split(",")]:
        name = f"{prefix}_{samples:04d}.exr"
        if str(samples) in timings and os.path.isfile(os.path.join(directory, name)) and not retime:
            continue
        if str(samples) in timings:
            earlier[str(samples)] = timings[str(samples)]
        # Another seed than the reference's, so the sweep's noise is independent of the reference's.
        timings[str(samples)] = render(os.path.join(directory, name), samples, seed=1)
        log(f"{camera_name}: {prefix} {samples} spp in {timings[str(samples)]:.2f} s")
    if earlier:
        timings["earlier"] = earlier
    with open(timings_path, "w", encoding="utf-8") as handle:
        json.dump(timings, handle, indent=1)


def main():
    arguments = parse_arguments()
    arguments.output = os.path.abspath(arguments.output)
    example_directory = os.path.abspath(arguments.example)
    example = load_example(example_directory)
    cameras = json.load(open(os.path.join(example_directory, "cameras.json")))
    if arguments.cameras:
        wanted = arguments.cameras.split(",")
        cameras = [c for c in cameras if c["name"] in wanted]

    # The example's domain gets a scratch cache directory: nothing here bakes, and Blender may free a cache
    # it did not bake in this session (see examples/bakelib/example.py).
    with tempfile.TemporaryDirectory(prefix="references_cache_") as scratch:
        domain, _, camera = example.build_scene(scratch)
        bpy.context.scene.frame_set(example.LAYOUT.showcase_frame)
        absorption = [float(c) for c in arguments.absorption_rgb.split(",")]
        liquid = add_liquid_mesh(example, os.path.join(example_directory, "cache"), example.LAYOUT.showcase_frame,
                                 absorption)
        whitewater = add_whitewater(arguments.whitewater) if arguments.whitewater else None
        configure_cycles(example, arguments.output)
        for definition in cameras:
            render_camera(arguments, example, camera, domain, liquid, definition, example_directory, whitewater)
    log("done")


if __name__ == "__main__":
    main()
