"""Blender data to what the native renderer takes: cache sources, particle arrays, triangles, the camera.

Every function reads Blender's data on the main thread (or the render job's thread inside a render handler),
never on another thread. Problems with the user's data are appended to `issues` as one-line
messages naming the object, not raised, so one bad object never stops the others from rendering.
"""

import os

import bpy
import numpy as np

from . import scene_json
from .scene_json import BadInput

KIND_CODES = {"LIQUID": 0, "SPRAY": 2, "BUBBLE": 4, "FOAM": 8}
TRIANGLE_TYPES = {"MESH", "CURVE", "SURFACE", "META", "FONT"}
# Objects the viewport draws as lines or a box: the scene behind them shows through, so in the viewport they hide
# no liquid (a Mantaflow flow or effector object is usually shown so).
SEE_THROUGH_DISPLAY = {"WIRE", "BOUNDS"}
# While the viewport preview is on, enabled objects are drawn as wire; their own settings are kept here
# (viewport.hide_own_drawing).
SAVED_DISPLAY = "spindrift_saved_display"


def fluid_modifier(obj):
    for modifier in obj.modifiers:
        if modifier.type == "FLUID":
            return modifier
    return None


def liquid_domain_settings(obj):
    """The domain settings of a Mantaflow liquid domain, or None for any other object."""
    modifier = fluid_modifier(obj) if obj.type == "MESH" else None
    if modifier is None or modifier.fluid_type != "DOMAIN":
        return None
    settings = modifier.domain_settings
    return settings if settings.domain_type == "LIQUID" else None


def enabled_objects(scene):
    return sorted((obj for obj in scene.objects if obj.spindrift.enabled), key=lambda obj: obj.name)


def primary_object(scene):
    """The object whose parameters the frame uses: the first enabled liquid domain, else the first enabled
    object (by name). One frame has one parameter set, as a scene file has."""
    objects = enabled_objects(scene)
    domains = [obj for obj in objects if liquid_domain_settings(obj) is not None]
    return (domains or objects or [None])[0]


# --- Mantaflow domains -----------------------------------------------------------------------------------------

def domain_grid(obj):
    """(world_from_file, dx, resolution) of a liquid domain (docs/mantaflow-caches.md)."""
    settings = liquid_domain_settings(obj)
    # The original mesh: once baked, the evaluated mesh (and obj.bound_box) is the liquid surface.
    vertices = np.empty(len(obj.data.vertices) * 3, dtype=np.float64)
    obj.data.vertices.foreach_get("co", vertices)
    if vertices.size == 0:
        raise BadInput(f"domain {obj.name}: its mesh has no vertices")
    vertices = vertices.reshape(-1, 3)
    return scene_json.mantaflow_grid(vertices.min(axis=0), vertices.max(axis=0), tuple(obj.scale),
                                     [list(row) for row in obj.matrix_world], settings.resolution_max)


def domain_sources(obj, frame, issues):
    """The scene file's particle sources for a liquid domain's OpenVDB caches at `frame` (maybe fewer)."""
    settings = liquid_domain_settings(obj)
    if settings.cache_data_format != "OPENVDB":
        issues.append(f"domain {obj.name}: its cache format is {settings.cache_data_format}; Spindrift reads "
                      f"OpenVDB caches (set Cache > Format Volumes to OpenVDB and bake again)")
        return []
    directory = bpy.path.abspath(settings.cache_directory)
    try:
        world_from_file, dx, _ = domain_grid(obj)
    except BadInput as error:
        issues.append(str(error))
        return []
    props = obj.spindrift
    # The domain's mesh settings go along, so the liquid stands where Blender's liquid mesh stands; the radius
    # is derived from them too unless the user set one (docs/blender.md).
    sources = scene_json.mantaflow_sources(
        directory, world_from_file,
        liquid_radius=None if props.liquid_radius_from_domain else props.liquid_radius_cells * dx,
        foam_radius=props.foam_radius_cells * dx, domain=scene_json.domain_description(settings))
    kept = []
    for source in sources:
        path = scene_json.frame_path(source["path"], frame)
        if os.path.isfile(path):
            kept.append(source)
        elif source["role"] == "liquid":
            issues.append(f"domain {obj.name}: no baked cache for frame {frame} ({path} is missing); bake the "
                          f"domain (Cache type All or Replay) over this frame")
        elif settings.use_spray_particles or settings.use_foam_particles or settings.use_bubble_particles:
            issues.append(f"domain {obj.name}: no secondary particle cache for frame {frame} ({path})")
    return kept


def domain_mesh_triangles(obj_eval):
    """The liquid surface Blender loaded for the frame (a baked domain's evaluated mesh), as triangles."""
    return object_triangles(obj_eval, np.asarray(obj_eval.matrix_world, dtype=np.float64))


# --- Particles from any object ---------------------------------------------------------------------------------

class ParticleSet:
    """Arrays of one object's particles in world space, float32, ready for the buffer protocol."""

    def __init__(self, positions, radii, kinds, life=None):
        self.positions = np.ascontiguousarray(positions, dtype=np.float32).reshape(-1, 3)
        self.radii = np.ascontiguousarray(radii, dtype=np.float32).reshape(-1)
        self.kinds = np.ascontiguousarray(kinds, dtype=np.uint8).reshape(-1)
        self.life = None if life is None else np.ascontiguousarray(life, dtype=np.float32).reshape(-1)

    def __len__(self):
        return len(self.radii)


def drop_non_finite(particles, name, issues):
    """Removes particles whose position or radius is NaN or infinite, and says how many."""
    finite = np.isfinite(particles.positions).all(axis=1) & np.isfinite(particles.radii) & (particles.radii > 0)
    dropped = int(len(finite) - finite.sum())
    if dropped:
        issues.append(f"{name}: {dropped} of {len(finite)} particles have a non-finite location or a radius "
                      f"that is not positive; they are skipped")
        life = None if particles.life is None else particles.life[finite]
        return ParticleSet(particles.positions[finite], particles.radii[finite], particles.kinds[finite], life)
    return particles


def particle_system_arrays(obj_eval, kind, radius_scale, frame, issues):
    """Every visible particle of the object's particle systems (world space, as Blender stores them)."""
    sets = []
    for system in obj_eval.particle_systems:
        particles = system.particles
        count = len(particles)
        name = f"{obj_eval.name}, particle system {system.name}"
        if count == 0:
            issues.append(f"{name}: no particles at this frame")
            continue
        positions = np.empty(count * 3, dtype=np.float32)
        particles.foreach_get("location", positions)
        sizes = np.empty(count, dtype=np.float32)
        particles.foreach_get("size", sizes)
        alive = np.empty(count, dtype=np.int32)
        particles.foreach_get("alive_state", alive)
        die_time = np.empty(count, dtype=np.float32)
        particles.foreach_get("die_time", die_time)
        # alive_state: 0 dead, 1 unborn, 2 alive, 3 dying; what Blender itself shows depends on the settings.
        shown = alive == 2
        if system.settings.show_unborn:
            shown |= alive == 1
        if system.settings.use_dead:
            shown |= alive == 0
        if not shown.any():
            issues.append(f"{name}: no particle is alive at this frame")
            continue
        positions = positions.reshape(-1, 3)[shown]
        sets.append(ParticleSet(positions, sizes[shown] * radius_scale, np.full(len(positions), kind, np.uint8),
                                np.maximum(die_time - frame, 0.0)[shown]))
    return sets


def vertex_arrays(obj_eval, kind, radius, issues):
    """The vertices of a mesh or the points of a point cloud (geometry-nodes output), in world space."""
    data = obj_eval.data
    if obj_eval.type == "POINTCLOUD":
        elements = data.points
    else:
        elements = data.vertices
    count = len(elements)
    if count == 0:
        issues.append(f"{obj_eval.name}: no points at this frame")
        return []
    local = np.empty(count * 3, dtype=np.float32)
    elements.foreach_get("co", local)
    radii = np.full(count, radius, dtype=np.float32)
    attribute = data.attributes.get("radius") if hasattr(data, "attributes") else None
    if attribute is not None and attribute.data_type == "FLOAT" and attribute.domain == "POINT":
        attribute.data.foreach_get("value", radii)
    matrix = np.asarray(obj_eval.matrix_world, dtype=np.float64)
    positions = local.reshape(-1, 3).astype(np.float64) @ matrix[:3, :3].T + matrix[:3, 3]
    return [ParticleSet(positions, radii, np.full(count, kind, np.uint8))]


def object_particles(obj, depsgraph, frame, issues):
    """The particles an enabled non-domain object contributes, after dropping non-finite ones."""
    obj_eval = obj.evaluated_get(depsgraph)
    props = obj.spindrift
    kind = KIND_CODES[props.role]
    if obj_eval.particle_systems:
        sets = particle_system_arrays(obj_eval, kind, props.size_scale, frame, issues)
    elif obj.type in ("MESH", "POINTCLOUD"):
        sets = vertex_arrays(obj_eval, kind, props.radius, issues)
    else:
        issues.append(f"{obj.name}: a {obj.type.lower()} object has no particles or points for Spindrift")
        sets = []
    return [drop_non_finite(s, obj.name, issues) for s in sets if len(s)]


def merge_particles(sets):
    """One `particles` dict for the native renderer, or None when there is nothing."""
    sets = [s for s in sets if len(s)]
    if not sets:
        return None
    merged = {
        "positions": np.ascontiguousarray(np.concatenate([s.positions for s in sets])),
        "radii": np.ascontiguousarray(np.concatenate([s.radii for s in sets])),
        "kinds": np.ascontiguousarray(np.concatenate([s.kinds for s in sets])),
    }
    if any(s.life is not None for s in sets):
        merged["life"] = np.ascontiguousarray(np.concatenate(
            [s.life if s.life is not None else np.zeros(len(s), np.float32) for s in sets]))
    return merged


# --- Triangles -------------------------------------------------------------------------------------------------

def object_triangles(obj_eval, matrix):
    """(vertices (V,3) float32 world, triangles (T,3) int32) of an evaluated object, or None."""
    try:
        mesh = obj_eval.to_mesh()
    except RuntimeError:
        return None
    try:
        if mesh is None or len(mesh.polygons) == 0:
            return None
        mesh.calc_loop_triangles()
        vertex_count, triangle_count = len(mesh.vertices), len(mesh.loop_triangles)
        local = np.empty(vertex_count * 3, dtype=np.float32)
        mesh.vertices.foreach_get("co", local)
        triangles = np.empty(triangle_count * 3, dtype=np.int32)
        mesh.loop_triangles.foreach_get("vertices", triangles)
    finally:
        obj_eval.to_mesh_clear()
    world = local.reshape(-1, 3).astype(np.float64) @ matrix[:3, :3].T + matrix[:3, 3]
    return world.astype(np.float32), triangles.reshape(-1, 3)


def viewport_display_type(obj):
    """How the viewport draws `obj` as its user set it (the preview's own wire drawing of enabled objects set
    aside)."""
    saved = obj.get(SAVED_DISPLAY)
    if saved:
        import ast

        try:
            return ast.literal_eval(saved)["display_type"]
        except (ValueError, SyntaxError, KeyError, TypeError):
            pass
    return obj.display_type


def occluder_triangles(depsgraph, excluded_names, for_render=True):
    """Every solid the depsgraph shows (instances included) except `excluded_names`, as one triangle soup. For
    the viewport (`for_render` False) an object displayed as wire or bounds is not a solid: it hides nothing
    there, whereas the render draws it as it renders."""
    cache = {}
    vertex_blocks, triangle_blocks, offset = [], [], 0
    for instance in depsgraph.object_instances:
        obj = instance.object
        if obj.type not in TRIANGLE_TYPES:
            continue
        original = obj.original
        owner = instance.parent.original if instance.is_instance and instance.parent else original
        if original.name in excluded_names or owner.name in excluded_names:
            continue
        if for_render and owner.hide_render:
            continue
        if not for_render and viewport_display_type(original) in SEE_THROUGH_DISPLAY:
            continue
        if liquid_domain_settings(original) is not None:
            continue
        key = obj.name
        if key not in cache:
            cache[key] = object_triangles(obj, np.identity(4))
        local = cache[key]
        if local is None:
            continue
        matrix = np.asarray(instance.matrix_world, dtype=np.float64)
        vertices = local[0].astype(np.float64) @ matrix[:3, :3].T + matrix[:3, 3]
        vertex_blocks.append(vertices.astype(np.float32))
        triangle_blocks.append(local[1] + offset)
        offset += len(vertices)
    if not triangle_blocks:
        return None
    return {"vertices": np.ascontiguousarray(np.concatenate(vertex_blocks)),
            "triangles": np.ascontiguousarray(np.concatenate(triangle_blocks))}


# --- Camera and world ------------------------------------------------------------------------------------------

def render_size(scene):
    render = scene.render
    return (max(int(render.resolution_x * render.resolution_percentage / 100), 1),
            max(int(render.resolution_y * render.resolution_percentage / 100), 1))


def render_camera(scene, depsgraph):
    """The scene file's camera for the scene's render camera at the render resolution, and the crop window
    (x, y from the top, width, height) of its image that is the render, or None.

    A lens shift (shift_x, shift_y) makes the projection off-axis; Spindrift's camera is symmetric, so the
    frame is rendered by the larger symmetric camera that contains the shifted view and cut to it by the module
    (`crop`). The window is placed at the nearest whole pixel: within half a pixel of Blender's projection."""
    camera = scene.camera
    if camera is None:
        raise BadInput(f"scene {scene.name} has no camera")
    if camera.type != "CAMERA":
        raise BadInput(f"scene {scene.name}: the active camera {camera.name} is not a camera object")
    if camera.data.type != "PERSP":
        kind = {"ORTHO": "orthographic", "PANO": "panoramic"}.get(camera.data.type, camera.data.type.lower())
        raise BadInput(f"camera {camera.name}: {kind} cameras are not supported "
                       f"(Spindrift renders perspective cameras)")
    width, height = render_size(scene)
    camera_eval = camera.evaluated_get(depsgraph)
    projection = camera_eval.calc_matrix_camera(depsgraph, x=width, y=height,
                                                scale_x=scene.render.pixel_aspect_x,
                                                scale_y=scene.render.pixel_aspect_y)
    description, (left, bottom) = scene_json.camera_description(width, height, camera_eval.matrix_world,
                                                                projection)
    if description["width"] == width and description["height"] == height:
        return description, None
    x = min(max(int(round(left)), 0), description["width"] - width)
    y_from_bottom = min(max(int(round(bottom)), 0), description["height"] - height)
    return description, (x, description["height"] - y_from_bottom - height, width, height)


def scene_camera(scene, depsgraph):
    """The scene file's camera for the render camera, for a scene file (the command line has no crop)."""
    description, crop = render_camera(scene, depsgraph)
    if crop is not None:
        raise BadInput(f"camera {scene.camera.name}: a lens shift is not supported in scene files for the "
                       f"command line (shift {scene.camera.data.shift_x:g}, {scene.camera.data.shift_y:g}); "
                       f"the render layers support it")
    return description


def scene_lights(depsgraph, for_render=True):
    """The depsgraph's lamps in the scene format's terms (docs/scene-format.md, "Lights"), instances included.

    The format has sun, spot and point lights. Blender's units match it (sun strength in W/m², spot and point
    power in W). An area lamp becomes a point light at its centre with 4x its power: on its axis Blender's
    area lamp gives P/(pi d^2), a point light P/(4 pi d^2), and the power only weights the lamps' shares in the
    liquid_shadow and caustics layers. A lamp's radius, a sun's angle and a spot's blend are not handed."""
    lights = []
    for instance in depsgraph.object_instances:
        obj = instance.object
        if obj.type != "LIGHT":
            continue
        owner = instance.parent.original if instance.is_instance and instance.parent else obj.original
        if for_render and owner.hide_render:
            continue
        lamp = obj.data
        matrix = np.asarray(instance.matrix_world, dtype=np.float64)
        position = [float(v) for v in matrix[:3, 3]]
        direction = [float(-v) for v in matrix[:3, 2]]  # a lamp shines down its local -Z
        light = {"color": [float(c) for c in lamp.color], "strength": float(lamp.energy)}
        if lamp.type == "SUN":
            light.update(type="sun", direction=direction)
        elif lamp.type == "SPOT":
            light.update(type="spot", position=position, direction=direction,
                         spot_angle_deg=float(np.degrees(lamp.spot_size)))
        elif lamp.type == "AREA":
            light.update(type="point", position=position, strength=4.0 * float(lamp.energy))
        else:
            light.update(type="point", position=position)
        lights.append(light)
    return lights


def film_pixel_filter(scene):
    """The render's pixel filter as (Cycles' filter type, width in pixels): Cycles' Film settings, or for
    another engine the render's filter size, a Blackman-Harris width as Eevee's is."""
    if scene.render.engine == "CYCLES" and hasattr(scene, "cycles"):
        return scene.cycles.pixel_filter_type, scene.cycles.filter_width
    return "BLACKMAN_HARRIS", scene.render.filter_size


def world_color(scene):
    """The world's background colour (times its strength), what Spindrift shows and refracts where the
    background image has nothing."""
    world = scene.world
    if world is None:
        return [0.05, 0.05, 0.06]
    if world.use_nodes and world.node_tree:
        for node in world.node_tree.nodes:
            if node.type == "BACKGROUND" and not node.inputs["Color"].is_linked:
                color = node.inputs["Color"].default_value
                strength = node.inputs["Strength"].default_value
                return [max(float(c) * strength, 0.0) for c in color[:3]]
    return [float(c) for c in world.color]
