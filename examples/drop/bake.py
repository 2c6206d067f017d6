"""Builds and bakes Spindrift's second example: a ball of water dropped into a shallow pool.

Run headless from the repository root:

    blender -b --factory-startup --python-exit-code 1 --python examples/drop/bake.py -- --output examples/drop

Where the dam break is one wave sweeping sideways, this is vertical motion: the ball falls, punches a crater
into the pool, and a crown of sheets and droplets rises around it. What every example shares (domain, bake,
renders, scene files) is in examples/bakelib; only the layout and the objects are this file's own. Options as
for dam_break/bake.py.
"""

import os
import sys

import bpy
from mathutils import Vector

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from bakelib import blender_scene, mantaflow  # noqa: E402 (Blender runs this file by path)
from bakelib.example import Layout, add_domain, main, prepare_scene  # noqa: E402

LAYOUT = Layout(
    name="drop",
    domain_min=Vector((-0.6, -0.6, 0.0)),
    domain_size=Vector((1.2, 1.2, 0.9)),
    resolution=56,
    frame_start=1,
    frame_end=30,
    # The crown stands around the crater and the first droplets leave its rim.
    showcase_frame=16,
    camera_location=Vector((1.25, -1.55, 0.85)),
    camera_target=Vector((0.0, 0.0, 0.12)),
    camera_lens_mm=35.0,
    foam_radius_cells=0.2,
)

POOL_DEPTH = 0.12
BALL_CENTRE = Vector((0.0, 0.0, 0.55))
BALL_RADIUS = 0.16
BALL_VELOCITY = Vector((0.0, 0.0, -1.5))  # m/s: an initial push so the impact comes within the short bake
RIM_THICKNESS = 0.05
RIM_HEIGHT = 0.2


def build_static_geometry():
    """A tiled floor and a low rim around the pool, so refraction and the crown's silhouette show."""
    floor = blender_scene.add_plane("Floor", 12.0, (0.0, 0.0, 0.0))
    floor.data.materials.append(blender_scene.make_checker_material("FloorTiles", (0.62, 0.6, 0.56),
                                                                    (0.30, 0.33, 0.36), scale=16.0))
    rim = blender_scene.make_material("Stone", (0.55, 0.5, 0.45), roughness=0.8)
    low, high, t, h = LAYOUT.domain_min, LAYOUT.domain_max, RIM_THICKNESS, RIM_HEIGHT
    for name, box_min, box_max in [
            ("RimBack", Vector((low.x - t, high.y, 0)), Vector((high.x + t, high.y + t, h))),
            ("RimFront", Vector((low.x - t, low.y - t, 0)), Vector((high.x + t, low.y, h))),
            ("RimLeft", Vector((low.x - t, low.y, 0)), Vector((low.x, high.y, h))),
            ("RimRight", Vector((high.x, low.y, 0)), Vector((high.x + t, high.y, h)))]:
        blender_scene.add_box(name, box_min, box_max).data.materials.append(rim)


def build_scene(cache_directory):
    """The whole scene, its domain caching into `cache_directory`; returns (domain, domain settings, camera).
    tests/bench/references.py builds the example through this too."""
    prepare_scene(LAYOUT)
    build_static_geometry()
    domain, settings = add_domain(LAYOUT, cache_directory)
    pool_max = Vector((LAYOUT.domain_max.x, LAYOUT.domain_max.y, POOL_DEPTH))
    mantaflow.add_liquid_flow(blender_scene.add_box("Pool", LAYOUT.domain_min, pool_max))
    mantaflow.add_liquid_flow(blender_scene.add_icosphere("Ball", BALL_CENTRE, BALL_RADIUS), BALL_VELOCITY)
    camera = blender_scene.build_camera(LAYOUT.camera_location, LAYOUT.camera_target, LAYOUT.camera_lens_mm,
                                        LAYOUT.camera_sensor_mm)
    blender_scene.build_lighting(LAYOUT.world_color, LAYOUT.world_strength)
    bpy.context.view_layer.update()
    return domain, settings, camera


if __name__ == "__main__":
    main(LAYOUT, build_scene)
