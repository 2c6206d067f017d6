"""Builds and bakes Spindrift's second example: a ball of water dropped into a shallow pool.

Run headless from the repository root:

    blender -b --factory-startup --python-exit-code 1 --python examples/drop/bake.py -- --output examples/drop

Where the dam break is one wave sweeping sideways, this is vertical motion: the ball falls, punches a crater
into the pool, and a crown of sheets and droplets rises around it. The scene is built with the dam-break
example's functions (floor, boxes, materials, domain, bake, scene file); only the layout below is its own.
Options as for dam_break/bake.py (`--skip-bake`, `--skip-render`).
"""

import importlib.util
import os

from mathutils import Vector

HERE = os.path.dirname(os.path.abspath(__file__))


def load_dam_break():
    path = os.path.join(HERE, "..", "dam_break", "bake.py")
    spec = importlib.util.spec_from_file_location("dam_break_bake", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


dam_break = load_dam_break()

DOMAIN_MIN = Vector((-0.6, -0.6, 0.0))
DOMAIN_SIZE = Vector((1.2, 1.2, 0.9))
RESOLUTION = 56
CELL_SIZE = max(DOMAIN_SIZE) / RESOLUTION

FRAME_START = 1
FRAME_END = 30
# The crown stands around the crater and the first droplets leave its rim.
SHOWCASE_FRAME = 16

POOL_DEPTH = 0.12
BALL_CENTRE = Vector((0.0, 0.0, 0.55))
BALL_RADIUS = 0.16
BALL_VELOCITY = Vector((0.0, 0.0, -1.5))  # m/s: an initial push so the impact comes within the short bake

RENDER_WIDTH = 960
RENDER_HEIGHT = 540
WORLD_COLOR = dam_break.WORLD_COLOR
FOAM_RADIUS = 0.2 * CELL_SIZE

CAMERA_LOCATION = Vector((1.25, -1.55, 0.85))
CAMERA_TARGET = Vector((0.0, 0.0, 0.12))
CAMERA_LENS_MM = 35.0
CAMERA_SENSOR_MM = 24.0

# The dam-break functions read their layout from their module's constants; this example's values replace
# them there, once, so every shared function (domain, bake, cache check, camera, scene file) uses them.
for name in ("DOMAIN_MIN", "DOMAIN_SIZE", "RESOLUTION", "CELL_SIZE", "FRAME_START", "FRAME_END",
             "SHOWCASE_FRAME", "RENDER_WIDTH", "RENDER_HEIGHT", "FOAM_RADIUS",
             "CAMERA_LOCATION", "CAMERA_TARGET", "CAMERA_LENS_MM", "CAMERA_SENSOR_MM"):
    setattr(dam_break, name, globals()[name])
dam_break.log = lambda message: print(f"[drop] {message}", flush=True)


def build_static_geometry():
    """A tiled floor and a low rim around the pool, so refraction and the crown's silhouette show."""
    floor = dam_break.add_plane("Floor", 12.0, (0.0, 0.0, 0.0))
    floor.data.materials.append(dam_break.make_checker_material("FloorTiles", (0.62, 0.6, 0.56),
                                                                (0.30, 0.33, 0.36), scale=16.0))
    rim = dam_break.make_material("Stone", (0.55, 0.5, 0.45), roughness=0.8)
    low, high, t = DOMAIN_MIN, DOMAIN_MIN + DOMAIN_SIZE, 0.05
    for name, box_min, box_max in [
            ("RimBack", Vector((low.x - t, high.y, 0)), Vector((high.x + t, high.y + t, 0.2))),
            ("RimFront", Vector((low.x - t, low.y - t, 0)), Vector((high.x + t, low.y, 0.2))),
            ("RimLeft", Vector((low.x - t, low.y, 0)), Vector((low.x, high.y, 0.2))),
            ("RimRight", Vector((high.x, low.y, 0)), Vector((high.x + t, high.y, 0.2)))]:
        dam_break.add_box(name, box_min, box_max).data.materials.append(rim)


def add_liquid_source(obj, velocity=None):
    flow = obj.modifiers.new("Fluid", 'FLUID')
    flow.fluid_type = 'FLOW'
    flow.flow_settings.flow_type = 'LIQUID'
    flow.flow_settings.flow_behavior = 'GEOMETRY'
    if velocity is not None:
        flow.flow_settings.use_initial_velocity = True
        flow.flow_settings.velocity_coord = velocity
    obj.hide_render = True
    obj.display_type = 'WIRE'


def build_scene(cache_directory):
    import bmesh
    import bpy
    scene = bpy.context.scene
    scene.frame_start, scene.frame_end = FRAME_START, FRAME_END
    dam_break.clear_scene()
    build_static_geometry()
    domain = dam_break.add_box("LiquidDomain", DOMAIN_MIN, DOMAIN_MIN + DOMAIN_SIZE)
    settings = dam_break.configure_domain(domain, cache_directory)
    domain.hide_render = True
    domain.display_type = 'WIRE'

    pool = dam_break.add_box("Pool", DOMAIN_MIN, Vector((DOMAIN_MIN.x + DOMAIN_SIZE.x,
                                                          DOMAIN_MIN.y + DOMAIN_SIZE.y, POOL_DEPTH)))
    add_liquid_source(pool)
    mesh = bpy.data.meshes.new("Ball")
    sphere = bmesh.new()
    bmesh.ops.create_icosphere(sphere, subdivisions=3, radius=BALL_RADIUS)
    sphere.to_mesh(mesh)
    sphere.free()
    ball = bpy.data.objects.new("Ball", mesh)
    ball.location = BALL_CENTRE
    scene.collection.objects.link(ball)
    add_liquid_source(ball, BALL_VELOCITY)

    camera = dam_break.build_camera()
    dam_break.build_lighting()
    bpy.context.view_layer.update()
    return domain, settings, camera


# The reference renderer (tests/bench/references.py) builds either example through this one entry point.
dam_break.build_scene = build_scene
scene_description = dam_break.scene_description


def main():
    dam_break.main()


if __name__ == "__main__":
    main()
