"""The Mantaflow side: a liquid domain's settings, liquid flow objects, the bake and a check of its files."""

import os
import shutil
import time

import bpy
from mathutils import Vector


def configure_liquid_domain(domain, cache_directory, resolution, frame_start, frame_end, use_mesh=True,
                            mesh_scale=None, secondary_particles=True, secondary_life_max=None):
    """Makes `domain` a FLIP liquid domain caching OpenVDB data (and, with `use_mesh`, the liquid mesh).

    `mesh_scale` None keeps Blender's default (2). With `secondary_life_max` the secondary particles are sampled
    as the examples sample them (`tune_secondary_particles`); without, at Blender's defaults. Returns the domain
    settings.
    """
    modifier = domain.modifiers.new("Fluid", 'FLUID')
    modifier.fluid_type = 'DOMAIN'
    settings = modifier.domain_settings
    settings.domain_type = 'LIQUID'
    settings.simulation_method = 'FLIP'
    settings.resolution_max = resolution
    settings.use_adaptive_domain = False  # an adaptive domain would move the cache's origin every frame

    settings.cache_type = 'ALL'
    settings.cache_frame_start = frame_start
    settings.cache_frame_end = frame_end
    settings.cache_data_format = 'OPENVDB'
    settings.cache_mesh_format = 'BOBJECT'

    settings.use_mesh = use_mesh
    if mesh_scale is not None:
        settings.mesh_scale = mesh_scale

    settings.use_spray_particles = secondary_particles
    settings.use_foam_particles = secondary_particles
    settings.use_bubble_particles = secondary_particles
    if secondary_life_max is not None:
        tune_secondary_particles(settings, secondary_life_max)

    # Last: changing almost any domain setting makes Blender free the cache in the domain's cache directory,
    # files on disk included.
    settings.cache_directory = cache_directory
    return settings


def tune_secondary_particles(settings, life_max):
    """The examples' secondary particles: Mantaflow's default potentials with sampling well below its defaults.

    Mantaflow samples 300 wave crest and 40 trapped air by default; in trials here trapped-air sampling of 10
    already piled up over 100k bubbles by the last frame, and the secondary files grew to ~10 MB a frame. With
    these values the dam break's splash has a few thousand particles of each kind and its last frames about
    200k in all, mostly bubbles and foam.
    """
    settings.sndparticle_combined_export = 'OFF'
    settings.sndparticle_potential_min_wavecrest = 2.0
    settings.sndparticle_potential_max_wavecrest = 8.0
    settings.sndparticle_potential_min_trappedair = 5.0
    settings.sndparticle_potential_max_trappedair = 20.0
    settings.sndparticle_potential_min_energy = 1.0
    settings.sndparticle_potential_max_energy = 5.0
    settings.sndparticle_sampling_wavecrest = 150
    settings.sndparticle_sampling_trappedair = 6
    settings.sndparticle_life_min = 6.0
    settings.sndparticle_life_max = life_max


def add_liquid_flow(obj, velocity=None):
    """Makes `obj` a liquid source that fills its volume once at the first frame (a body, not a tap), hidden
    from renders: the liquid is Spindrift's job."""
    flow = obj.modifiers.new("Fluid", 'FLUID')
    flow.fluid_type = 'FLOW'
    flow.flow_settings.flow_type = 'LIQUID'
    flow.flow_settings.flow_behavior = 'GEOMETRY'
    if velocity is not None:
        flow.flow_settings.use_initial_velocity = True
        flow.flow_settings.velocity_coord = velocity
    obj.hide_render = True
    obj.display_type = 'WIRE'
    return flow


def add_collision(obj):
    collision = obj.modifiers.new("Fluid", 'FLUID')
    collision.fluid_type = 'EFFECTOR'
    collision.effector_settings.effector_type = 'COLLISION'
    return collision


def bake(domain):
    """Bakes `domain` synchronously (in background mode the operator runs no job); returns the seconds taken."""
    view_layer = bpy.context.view_layer
    view_layer.objects.active = domain
    domain.select_set(True)
    started = time.perf_counter()
    with bpy.context.temp_override(active_object=domain, object=domain, selected_objects=[domain],
                                   scene=bpy.context.scene, view_layer=view_layer):
        result = bpy.ops.fluid.bake_all()
    if result != {'FINISHED'}:
        raise RuntimeError(f"fluid.bake_all of {domain.name} returned {result}")
    return time.perf_counter() - started


def bake_clean(domain, cache_directory, frame_start, frame_end, with_mesh=True, log=print):
    """Bakes into an emptied `cache_directory` and checks that every frame's files are there."""
    # A partial cache from an interrupted bake would be mixed with the new frames; start clean.
    if os.path.isdir(cache_directory):
        shutil.rmtree(cache_directory)
    os.makedirs(cache_directory)
    elapsed = bake(domain)
    files = expected_cache_files(cache_directory, frame_start, frame_end, with_mesh)
    missing = [path for path in files if not os.path.isfile(path)]
    if missing:
        raise RuntimeError(f"the bake left {len(missing)} cache files missing, e.g. {missing[0]}")
    log(f"baked in {elapsed:.1f} s")
    return elapsed


def expected_cache_files(cache_directory, frame_start, frame_end, with_mesh=True):
    """Per frame: the liquid data, the secondary particles and (with the mesh) the liquid mesh."""
    files = []
    for frame in range(frame_start, frame_end + 1):
        files.append(os.path.join(cache_directory, "data", f"fluid_data_{frame:04d}.vdb"))
        files.append(os.path.join(cache_directory, "particles", f"fluid_particles_{frame:04d}.vdb"))
        if with_mesh:
            files.append(os.path.join(cache_directory, "mesh", f"fluid_mesh_{frame:04d}.bobj.gz"))
    return files


def domain_minimum_corner(domain):
    # The box's own vertices: once baked, the object's bound_box is that of the evaluated liquid mesh.
    corners = [domain.matrix_world @ vertex.co for vertex in domain.data.vertices]
    return Vector((min(c.x for c in corners), min(c.y for c in corners), min(c.z for c in corners)))


def report_baked_frame(domain, frame, log=print):
    """Prints what Blender reads back from the cache at `frame`: particle counts and the liquid mesh's extent.

    Blender's particle systems give the counts only: in Blender 3.4.1 their positions are displaced for a
    domain that is not a cube. The liquid mesh is placed correctly, and its extent relative to the domain's
    minimum corner is what the cache's particle positions should match (examples/README.md compares them).
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
