"""Scene files (docs/scene-format.md) from Blender's numbers: cameras, Mantaflow cache sources, backgrounds.

Pure Python and numpy (no bpy), so every formula here is tested outside Blender against hand-computed cases.
Matrices are 4x4 nested sequences (Blender's `Matrix` works, as do numpy arrays), row-major as Blender prints.
"""

import json
import math

import numpy as np

# What the scene file writes where nothing was hit: Blender's Depth pass uses 1e10 for the sky as well.
FAR_DEPTH = 1e10


class BadInput(Exception):
    """Something in the Blender scene the add-on cannot render; the message is shown to the user as is."""


def row_major(matrix):
    return [float(matrix[row][column]) for row in range(4) for column in range(4)]


# --- Mantaflow -------------------------------------------------------------------------------------------------

def mantaflow_grid(bound_lo, bound_hi, scale, matrix_world, resolution_max):
    """The world_from_file matrix of a Mantaflow domain's caches, its cell size and grid resolution.

    docs/mantaflow-caches.md derives and verifies the formula: the grid is centred on the mesh's bound box,
    cells are cubes of dx = max(size) / R in scaled units, and a cache position p maps to
    world = M · (gridLo + p ⊘ |s|).
    """
    lo = np.asarray(bound_lo, dtype=np.float64)
    hi = np.asarray(bound_hi, dtype=np.float64)
    abs_scale = np.abs(np.asarray(scale, dtype=np.float64))
    if resolution_max < 1:
        raise BadInput(f"resolution_max {resolution_max} must be at least 1")
    if np.any(abs_scale == 0):
        raise BadInput("the domain has a zero scale")
    size = (hi - lo) * abs_scale
    longest = float(size.max())
    if not longest > 0:
        raise BadInput("the domain's mesh has no extent")
    dx = longest / resolution_max
    resolution = np.maximum((size * resolution_max / longest + 0.5).astype(np.int64), 4)
    grid_lo = (lo + hi) / 2 - resolution * dx / (2 * abs_scale)
    file_to_local = np.diag([*(1.0 / abs_scale), 1.0])
    file_to_local[:3, 3] = grid_lo
    world_from_file = np.asarray(matrix_world, dtype=np.float64) @ file_to_local
    return world_from_file, dx, [int(r) for r in resolution]


def mantaflow_cache_paths(cache_directory):
    """The liquid and secondary-particle files of an OpenVDB cache, with #### for the frame."""
    return {
        "liquid": cache_directory.rstrip("/\\") + "/data/fluid_data_####.vdb",
        "secondary": cache_directory.rstrip("/\\") + "/particles/fluid_particles_####.vdb",
    }


def frame_path(pattern, frame):
    """A #### pattern with the frame filled in, as the native loader does (a run of # is zero-padded)."""
    start = pattern.find("#")
    if start < 0:
        return pattern
    end = start
    while end < len(pattern) and pattern[end] == "#":
        end += 1
    return pattern[:start] + str(frame).zfill(end - start) + pattern[end:]


# The Mantaflow domain settings that place its liquid mesh (docs/mantaflow-caches.md); the scene file's
# "domain" object takes them under Blender's own names.
MESH_SETTINGS = ("particle_radius", "mesh_particle_radius", "mesh_scale", "mesh_smoothen_pos", "mesh_smoothen_neg",
                 "mesh_concave_upper", "mesh_concave_lower", "particle_number", "mesh_generator")


def domain_description(settings):
    """The scene file's "domain" object from a FluidDomainSettings (or anything with those attributes)."""
    description = {}
    for name in MESH_SETTINGS:
        value = getattr(settings, name)
        description[name] = value if isinstance(value, str) else (
            int(value) if isinstance(value, int) and not isinstance(value, bool) else float(value))
    return description


def mantaflow_sources(cache_directory, world_from_file, liquid_radius, foam_radius, domain=None):
    """The liquid and foam sources of a Mantaflow cache. With `domain` (domain_description) the liquid source
    names the domain's mesh settings, so the renderer derives its surface offset, and its radius too when
    `liquid_radius` is None; a given radius wins."""
    paths = mantaflow_cache_paths(cache_directory)
    matrix = row_major(world_from_file)
    liquid = {"path": paths["liquid"], "grid": "particles", "role": "liquid", "world_from_file": matrix}
    if liquid_radius is not None:
        liquid["radius"] = float(liquid_radius)
    if domain is not None:
        liquid["domain"] = dict(domain)
    return [
        liquid,
        {"path": paths["secondary"], "grid": "particles_secondary", "role": "foam", "radius": float(foam_radius),
         "world_from_file": matrix},
    ]


# --- Cameras ---------------------------------------------------------------------------------------------------

def perspective_parts(projection):
    """(tan half-width, tan half-height, centre offsets in NDC, near, far) of an OpenGL perspective matrix.

    An off-centre matrix (a panned camera view, a camera with shift) has P[0][2] and P[1][2] non-zero.
    """
    p = np.asarray(projection, dtype=np.float64)
    if abs(p[3][3]) > 1e-9 or abs(p[3][2] + 1.0) > 1e-6:
        raise BadInput("orthographic views are not supported: Spindrift renders perspective cameras only")
    near = p[2][3] / (p[2][2] - 1.0)
    far = p[2][3] / (p[2][2] + 1.0)
    return 1.0 / p[0][0], 1.0 / p[1][1], (p[0][2], p[1][2]), float(near), float(far)


def camera_description(width, height, world_from_camera, projection):
    """The scene file's camera for an image of width x height whose projection is `projection`.

    Spindrift's camera is a symmetric frustum. An off-centre projection (a panned camera view) is covered by a
    larger symmetric one with the same pixel size: returns (camera, (left, bottom)), the wanted image being the
    camera's image from pixel (left, bottom) (counted from its bottom-left corner) on, width x height pixels.
    For a centred projection the camera is exactly width x height and (left, bottom) is (0, 0).
    """
    if width < 1 or height < 1:
        raise BadInput(f"the image is {width}x{height} pixels: nothing to render")
    tan_x, tan_y, (shift_x, shift_y), near, far = perspective_parts(projection)
    # The wanted image spans (shift ± 1) tan: a symmetric frustum must reach (1 + |shift|) tan.
    grow_x, grow_y = 1.0 + abs(shift_x), 1.0 + abs(shift_y)
    full_width = int(math.ceil(width * grow_x - 1e-6))
    full_height = int(math.ceil(height * grow_y - 1e-6))
    # Keep pixels square and the window aligned: the full frustum's half-extent follows the pixel counts.
    half_x = tan_x * full_width / width
    half_y = tan_y * full_height / height
    camera = {
        "width": full_width,
        "height": full_height,
        "fov_y_deg": math.degrees(2.0 * math.atan(half_y)),
        "near": near,
        "far": far,
        "world_from_camera": row_major(world_from_camera),
    }
    # x_ndc = P00 (x / -z) - P02: the wanted image's centre (x_ndc = 0) looks along x / -z = shift * tan.
    centre_x = shift_x * tan_x
    centre_y = shift_y * tan_y
    left = (centre_x - tan_x + half_x) / (2 * half_x) * full_width
    bottom = (centre_y - tan_y + half_y) / (2 * half_y) * full_height
    aspect_error = abs(half_x / half_y - full_width / full_height) / (full_width / full_height)
    if aspect_error > 0.02:
        raise BadInput(f"non-square pixels (aspect off by {aspect_error:.1%}) are not supported")
    return camera, (left, bottom)


# --- The document ----------------------------------------------------------------------------------------------

def scene_document(camera, frame, sources=(), background=None, liquid=None, foam=None, lights=(), light=None):
    """The scene file's document. `liquid`, `foam` and `light` hold the parameters that differ from the table's
    defaults (parameters.group_values); "light" is written only when it holds one, as the lamps are."""
    document = {"version": 1, "frame": int(frame), "camera": camera, "particles": list(sources)}
    if background:
        document["background"] = background
    if lights:
        document["lights"] = list(lights)
    document["liquid"] = dict(liquid or {})
    document["foam"] = dict(foam or {})
    if light:
        document["light"] = dict(light)
    return document


def lights_through_liquid(document, mode, occluders_handed, light_defaults):
    """Whether the renderer lights the background under the liquid for `document`, so that the frame's EXR
    carries the light layers the OVER group multiplies the render by (FOAM_ONLY has none: Cycles lit the
    liquid in its render). With lamps; and without them where the world's light alone is taken
    (light.sky_without_lamps, `light_defaults` standing for what the document's "light" leaves out: the
    table's defaults): the scene's solids are handed (`occluders_handed`), so the renderer has a background to
    light, and the world is not black. Where the renderer then lights nothing (no lamp sees the liquid) the
    layers leave the render as it is; without lamps liquid_shadow holds the world's multiplier, liquid_sky's,
    so the group's formula gives it whatever its lamps' share. With light.sky_without_lamps off a scene without
    lamps is lit by nothing, and its EXR has no light layers."""
    if mode != "OVER":
        return False
    if document.get("lights"):
        return True
    light = {**light_defaults, **document.get("light", {})}
    world = document.get("background", {}).get("color", [0.0, 0.0, 0.0])
    return bool(light["sky_without_lamps"]) and occluders_handed and max(world) > 0.0


def dumps(document):
    return json.dumps(document, indent=1, sort_keys=False)
