"""The Spindrift scene files (version 1) written beside an example's bake, byte-identical on every run."""

import json
import math
import re

from mathutils import Matrix

from .mantaflow import domain_minimum_corner

# The domain settings that shape Mantaflow's liquid mesh, as the scene file's `domain` object names them:
# Spindrift derives the liquid's radius and surface offset from them and reads the cell size and the domain's
# transform from the cache's config files (docs/mantaflow-caches.md).
MESH_SETTINGS = ("particle_radius", "mesh_particle_radius", "mesh_scale", "mesh_smoothen_pos", "mesh_smoothen_neg",
                 "mesh_concave_upper", "mesh_concave_lower", "particle_number", "mesh_generator")


def clean_number(value, digits=6):
    # Adding 0.0 turns -0.0 into 0.0, so a value that rounds to zero is always written the same way.
    return round(value, digits) + 0.0


def row_major(matrix):
    """A 4x4 matrix as 16 numbers, row by row, rounded so the file is stable and readable."""
    return [clean_number(matrix[row][column]) for row in range(4) for column in range(4)]


def camera_description(camera, width, height):
    return {
        "width": width,
        "height": height,
        "fov_y_deg": clean_number(math.degrees(camera.data.angle_y)),
        "near": clean_number(camera.data.clip_start),
        "far": clean_number(camera.data.clip_end),
        "world_from_camera": row_major(camera.matrix_world),
    }


def domain_description(domain):
    settings = domain.modifiers["Fluid"].domain_settings
    return {name: clean_number(value) if isinstance(value, float) else value
            for name, value in ((name, getattr(settings, name)) for name in MESH_SETTINGS)}


def particle_sources(domain, foam_radius):
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
            "radius": clean_number(foam_radius),
            "world_from_file": world_from_file,
        },
    ]


def scene_description(layout, camera, domain):
    """The scene file for an example, with paths relative to the file: liquid and foam over the background
    render, which has no liquid in it."""
    return {
        "version": 1,
        "frame": layout.showcase_frame,
        "camera": camera_description(camera, layout.render_width, layout.render_height),
        "particles": particle_sources(domain, layout.foam_radius),
        "background": {
            "image": "renders/background.exr",
            "color": [clean_number(c) for c in layout.world_radiance],
        },
        "foam": {"lifetime_frames": layout.secondary_life_max},
    }


def foam_only_scene_description(layout, camera, domain):
    """Foam only, over the full render that already holds the liquid mesh: with no liquid source Spindrift
    renders no liquid; the solids' depth comes from the background render, the liquid's surface from the
    depth of the render with the liquid, and foam behind that surface fades with its depth below it."""
    return {
        "version": 1,
        "frame": layout.showcase_frame,
        "camera": camera_description(camera, layout.render_width, layout.render_height),
        "particles": particle_sources(domain, layout.foam_radius)[1:],
        "background": {
            "image": "renders/with_liquid.exr",
            "depth": "renders/background.exr",
            "liquid_depth": "renders/with_liquid.exr",
            "color": [clean_number(c) for c in layout.world_radiance],
        },
        "foam": {"lifetime_frames": layout.secondary_life_max},
    }


def format_scene_json(description):
    """Indented JSON with every list of numbers on one line, so a matrix reads as a matrix."""
    text = json.dumps(description, indent=2)
    number_list = re.compile(r"\[\s*([-0-9.e+]+(?:,\s*[-0-9.e+]+)*)\s*\]")
    return number_list.sub(lambda match: "[" + re.sub(r"\s+", " ", match.group(1)) + "]", text) + "\n"


def check_domain_transform(domain):
    """Fails loudly if the domain's transform is more than a translation, which the foam source assumes."""
    linear = domain.matrix_world.to_3x3()
    if any(abs(linear[r][c] - (1.0 if r == c else 0.0)) > 1e-9 for r in range(3) for c in range(3)):
        raise RuntimeError("the liquid domain must have no rotation and unit scale")


def write_scene_file(path, description, domain, log=print):
    check_domain_transform(domain)
    text = format_scene_json(description)
    with open(path, "w", encoding="utf-8") as handle:
        handle.write(text)
    log(f"wrote {path}")
