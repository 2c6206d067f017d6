"""An example's layout and the command line every example's bake.py runs."""

import argparse
import dataclasses
import os
import sys
import tempfile

import bpy
from mathutils import Vector

from . import mantaflow, render, scene_file
from .blender_scene import add_box, clear_scene


@dataclasses.dataclass(frozen=True)
class Layout:
    """What an example decides; its bake.py builds the objects (`build_scene`) from it."""

    name: str
    # The liquid domain, in world units. Its size is an exact multiple of the cell size (size / resolution
    # along the longest side), so Mantaflow's grid covers the box exactly and the cache's positions, which
    # start at the domain's minimum corner, need no correction for a rounded grid.
    domain_min: Vector
    domain_size: Vector
    resolution: int
    frame_start: int
    frame_end: int
    # The frame scene.json names as the default and the renders show.
    showcase_frame: int
    camera_location: Vector
    camera_target: Vector
    camera_lens_mm: float
    # Secondary particles are flecks of foam: the foam pipeline draws particle i at foam radius /
    # ((i mod 5) + 1) (bubbles at half that), so the flecks read as a few pixels wide at the camera's distance.
    foam_radius_cells: float
    camera_sensor_mm: float = 24.0
    render_width: int = 960
    render_height: int = 540
    render_samples: int = 48
    # The render with the liquid mesh: fewer samples keep it near half a minute on two cores.
    liquid_render_samples: int = 32
    liquid_render_bounces: int = 8
    water_ior: float = 1.33
    # A plain world colour and strength: it lights the scene softly, and its radiance (world_radiance) is the
    # colour Spindrift falls back on where a ray leaves everything the frame shows.
    world_color: tuple = (0.52, 0.62, 0.78)
    world_strength: float = 0.55
    # The longest life of a secondary particle, in frames; scene files pass it on as foam.lifetime_frames, which
    # normalises the remaining life the cache stores into the age that fades foam out.
    secondary_life_max: float = 16.0

    @property
    def world_radiance(self):
        """What the world's Background node emits (its colour times its strength): the colour a scene file gives
        Spindrift for the world, as the add-on's export.world_color computes it."""
        return tuple(c * self.world_strength for c in self.world_color)

    @property
    def cell_size(self):
        return max(self.domain_size) / self.resolution

    @property
    def foam_radius(self):
        return self.foam_radius_cells * self.cell_size

    @property
    def domain_max(self):
        return self.domain_min + self.domain_size

    def log(self, message):
        print(f"[{self.name}] {message}", flush=True)


def add_domain(layout, cache_directory):
    """The example's liquid domain box, hidden from renders, with the examples' Mantaflow settings: the liquid
    mesh is cached at the simulation's resolution (`mesh_scale` 1) for comparison and for renderers that want a
    surface."""
    domain = add_box("LiquidDomain", layout.domain_min, layout.domain_max)
    settings = mantaflow.configure_liquid_domain(domain, cache_directory, layout.resolution, layout.frame_start,
                                                 layout.frame_end, use_mesh=True, mesh_scale=1,
                                                 secondary_life_max=layout.secondary_life_max)
    domain.hide_render = True
    domain.display_type = 'WIRE'
    return domain, settings


def prepare_scene(layout):
    """An empty scene over the example's frame range."""
    scene = bpy.context.scene
    scene.frame_start = layout.frame_start
    scene.frame_end = layout.frame_end
    clear_scene()
    return scene


def parse_arguments(name):
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    parser = argparse.ArgumentParser(prog=f"{name}/bake.py",
                                     description=f"Builds, bakes and renders Spindrift's {name} example.")
    parser.add_argument("--output", required=True, help="directory for cache/, renders/ and scene.json")
    parser.add_argument("--skip-bake", action="store_true", help="reuse the cache already in OUTPUT/cache")
    parser.add_argument("--skip-render", action="store_true", help="reuse OUTPUT/renders/background.exr")
    parser.add_argument("--skip-liquid-render", action="store_true", help="reuse OUTPUT/renders/with_liquid.exr")
    return parser.parse_args(argv)


def main(layout, build_scene):
    """Builds the scene with `build_scene(cache_directory)` -> (domain, domain settings, camera), bakes it into
    OUTPUT/cache, renders OUTPUT/renders/background.exr (and .png) and with_liquid.exr, and writes
    OUTPUT/scene.json and OUTPUT/scene_foam_only.json. The scene files depend only on the layout, so they come
    out byte-identical on every run."""
    arguments = parse_arguments(layout.name)
    log = layout.log
    output = os.path.abspath(arguments.output)
    cache_directory = os.path.join(output, "cache")
    render_directory = os.path.join(output, "renders")
    os.makedirs(output, exist_ok=True)

    log("building the scene")
    # Without a bake in this session Blender does not know the cache on disk is a finished bake, and may free
    # it; the domain then gets a scratch directory (the render with the liquid reads a copy of the cache).
    scratch = tempfile.TemporaryDirectory(prefix=f"{layout.name}_cache_") if arguments.skip_bake else None
    domain, domain_settings, camera = build_scene(scratch.name if scratch else cache_directory)
    scene = bpy.context.scene

    if arguments.skip_bake:
        log("skipping the bake: reusing the cache")
    else:
        log(f"baking frames {layout.frame_start}-{layout.frame_end} at resolution {layout.resolution} "
            f"(cell {layout.cell_size:.4f}) into {cache_directory}")
        mantaflow.bake_clean(domain, cache_directory, layout.frame_start, layout.frame_end, log=log)
        mantaflow.report_baked_frame(domain, layout.showcase_frame, log=log)

    if arguments.skip_render:
        log("skipping the render: reusing renders/background.exr")
    else:
        scene.frame_set(layout.showcase_frame)
        render.render_background(scene, render_directory, layout, log=log)

    if arguments.skip_liquid_render:
        log("skipping the render with the liquid: reusing renders/with_liquid.exr")
    else:
        render.render_with_liquid(scene, domain, domain_settings, cache_directory, render_directory, layout, log=log)

    for name, describe in (("scene.json", scene_file.scene_description),
                           ("scene_foam_only.json", scene_file.foam_only_scene_description)):
        scene_file.write_scene_file(os.path.join(output, name), describe(layout, camera, domain), domain, log=log)
    if scratch:
        scratch.cleanup()
    log("done")
