"""Builds, bakes and renders Spindrift's dam-break example scene in Blender.

Run headless from the repository root:

    blender -b --factory-startup --python-exit-code 1 --python examples/dam_break/bake.py -- --output examples/dam_break

It builds the scene from an empty file, bakes a Mantaflow FLIP liquid with spray, foam and bubbles into
OUTPUT/cache, renders the background (everything but the liquid, with a Depth pass) into
OUTPUT/renders/background.exr plus a PNG preview, renders the same frame again with Mantaflow's liquid mesh
as water into OUTPUT/renders/with_liquid.exr (for foam composited over a full render), and writes
OUTPUT/scene.json and OUTPUT/scene_foam_only.json, the Spindrift scene files that point at them.
`--skip-bake`, `--skip-render` and `--skip-liquid-render` reuse what is already there
(examples/dam_break/prepare.sh uses them). What every example shares is in examples/bakelib; this file holds
only the layout and the objects.
"""

import os
import sys

import bpy
from mathutils import Vector

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from bakelib import blender_scene, mantaflow  # noqa: E402 (Blender runs this file by path)
from bakelib.example import Layout, add_domain, main, prepare_scene  # noqa: E402

LAYOUT = Layout(
    name="dam_break",
    domain_min=Vector((-1.5, -0.9375, 0.0)),
    domain_size=Vector((3.0, 1.875, 1.125)),
    resolution=80,
    frame_start=1,
    frame_end=48,
    # The collapsing column has just hit the block and throws a splash over it, before the wave reaches the far
    # wall and sheets of liquid climb the domain's walls.
    showcase_frame=16,
    camera_location=Vector((2.05, -3.35, 1.6)),
    camera_target=Vector((-0.1, 0.15, 0.3)),
    camera_lens_mm=32.0,
    # Foam radii spread between 0.12 and 0.6 cells.
    foam_radius_cells=0.6,
)

# The water column, in the back left corner of the domain.
COLUMN_MIN = Vector((-1.5, 0.0, 0.0))
COLUMN_MAX = Vector((-0.95, 0.9375, 0.85))

# A block in the path of the wave, as a Mantaflow collision object and visible geometry.
OBSTACLE_MIN = Vector((0.15, 0.2, 0.0))
OBSTACLE_MAX = Vector((0.45, 0.5, 0.3))

WALL_THICKNESS = 0.08
WALL_HEIGHT = 0.6


def build_static_geometry():
    """Floor, three walls around the domain and the obstacle: everything the background render shows."""
    floor = blender_scene.add_plane("Floor", 24.0, (0.0, 0.0, 0.0))
    floor.data.materials.append(blender_scene.make_checker_material("FloorTiles", (0.62, 0.6, 0.56),
                                                                    (0.36, 0.35, 0.33), scale=12.0))

    # The walls stand just outside the domain, whose own borders are what the liquid collides with.
    wall_material = blender_scene.make_material("Concrete", (0.72, 0.7, 0.66), roughness=0.8)
    low, high, t = LAYOUT.domain_min, LAYOUT.domain_max, WALL_THICKNESS
    walls = [
        ("WallBack", Vector((low.x - t, high.y, 0.0)), Vector((high.x + t, high.y + t, WALL_HEIGHT))),
        ("WallLeft", Vector((low.x - t, low.y, 0.0)), Vector((low.x, high.y, WALL_HEIGHT))),
        ("WallRight", Vector((high.x, low.y, 0.0)), Vector((high.x + t, high.y, WALL_HEIGHT))),
    ]
    for name, box_min, box_max in walls:
        blender_scene.add_box(name, box_min, box_max).data.materials.append(wall_material)

    obstacle = blender_scene.add_box("Obstacle", OBSTACLE_MIN, OBSTACLE_MAX)
    obstacle.data.materials.append(blender_scene.make_material("Painted", (0.75, 0.22, 0.08), roughness=0.45))
    return obstacle


def build_scene(cache_directory):
    """The whole scene, its domain caching into `cache_directory`; returns (domain, domain settings, camera).
    tests/bench/references.py builds the example through this too."""
    prepare_scene(LAYOUT)
    obstacle = build_static_geometry()
    domain, settings = add_domain(LAYOUT, cache_directory)
    # A column, not a tap: the flow fills its volume once at the first frame.
    mantaflow.add_liquid_flow(blender_scene.add_box("WaterColumn", COLUMN_MIN, COLUMN_MAX))
    mantaflow.add_collision(obstacle)
    camera = blender_scene.build_camera(LAYOUT.camera_location, LAYOUT.camera_target, LAYOUT.camera_lens_mm,
                                        LAYOUT.camera_sensor_mm)
    blender_scene.build_lighting(LAYOUT.world_color, LAYOUT.world_strength)
    bpy.context.view_layer.update()
    return domain, settings, camera


if __name__ == "__main__":
    main(LAYOUT, build_scene)
