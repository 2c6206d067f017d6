"""Cycles settings and the examples' two renders: the background without liquid, and the frame with
Mantaflow's liquid mesh as water."""

import os
import shutil
import tempfile
import time

import bpy


def configure_background_render(scene, render_directory, width, height, samples):
    """Cycles on the CPU into a 32-bit multilayer EXR with a Depth pass, `render_directory`/background.exr."""
    scene.render.engine = 'CYCLES'
    scene.cycles.device = 'CPU'
    scene.cycles.samples = samples
    scene.cycles.use_adaptive_sampling = True
    scene.cycles.use_denoising = False  # Debian's Blender has no OpenImageDenoise; rendering would fail
    scene.cycles.max_bounces = 4
    scene.render.resolution_x = width
    scene.render.resolution_y = height
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


def render_background(scene, render_directory, layout, log=print):
    os.makedirs(render_directory, exist_ok=True)
    configure_background_render(scene, render_directory, layout.render_width, layout.render_height,
                                layout.render_samples)
    log(f"rendering the background ({layout.render_width}x{layout.render_height}, {layout.render_samples} "
        f"samples, CPU)")
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


def make_clear_water_material(ior):
    """Glass of water's index of refraction whose shadow rays pass straight through.

    Without caustics the glass would cast a black shadow; shadow rays pass through it instead, so the floor
    under the water is lit as under clear water.
    """
    water = bpy.data.materials.new("Water")
    water.use_nodes = True
    nodes = water.node_tree.nodes
    nodes.remove(nodes["Principled BSDF"])
    glass = nodes.new("ShaderNodeBsdfGlass")
    glass.inputs["IOR"].default_value = ior
    glass.inputs["Roughness"].default_value = 0.0
    light_path = nodes.new("ShaderNodeLightPath")
    transparent = nodes.new("ShaderNodeBsdfTransparent")
    mix = nodes.new("ShaderNodeMixShader")
    links = water.node_tree.links
    links.new(light_path.outputs["Is Shadow Ray"], mix.inputs["Fac"])
    links.new(glass.outputs["BSDF"], mix.inputs[1])
    links.new(transparent.outputs["BSDF"], mix.inputs[2])
    links.new(mix.outputs["Shader"], nodes["Material Output"].inputs["Surface"])
    return water


def render_with_liquid(scene, domain, domain_settings, cache_directory, render_directory, layout, log=print):
    """Renders the showcase frame with Mantaflow's liquid mesh as water: the full render foam is composited over.

    The domain reads a copy of the cache in replay mode, so Blender never frees (deletes) the real cache and
    never simulates: every file of the frame is already there. The domain's evaluated mesh is then the liquid
    mesh of `cache/mesh/fluid_mesh_####.bobj.gz`; it renders as glass of water's index of refraction.
    """
    os.makedirs(render_directory, exist_ok=True)
    configure_background_render(scene, render_directory, layout.render_width, layout.render_height,
                                layout.liquid_render_samples)
    # Glass needs a few more bounces than the opaque background (in and out of the water, and the floor seen
    # through it).
    scene.cycles.max_bounces = layout.liquid_render_bounces
    scene.cycles.transmission_bounces = layout.liquid_render_bounces
    scene.cycles.transparent_max_bounces = layout.liquid_render_bounces
    # Total internal reflections are glossy bounces in Cycles: at its default of 4 light guided along a sheet
    # of water comes out black.
    scene.cycles.glossy_bounces = layout.liquid_render_bounces
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
        copy = tempfile.TemporaryDirectory(prefix=f"{layout.name}_replay_")
        replay_cache = os.path.join(copy.name, "cache")
        shutil.copytree(stash, replay_cache)
        domain_settings.cache_type = 'REPLAY'
        domain_settings.cache_directory = replay_cache

        domain.data.materials.clear()
        domain.data.materials.append(make_clear_water_material(layout.water_ior))
        domain.hide_render = False
        # The secondary particles are Spindrift's foam: they must not show in this render.
        for system in domain.particle_systems:
            system.settings.render_type = 'NONE'

        scene.frame_set(layout.showcase_frame)
        evaluated = domain.evaluated_get(bpy.context.evaluated_depsgraph_get())
        vertices = len(evaluated.data.vertices)
        if vertices == 0:
            raise RuntimeError(f"the liquid mesh of frame {layout.showcase_frame} did not load from {replay_cache}")
        log(f"rendering the frame with the liquid mesh ({vertices} vertices, glass IOR {layout.water_ior}, "
            f"{layout.liquid_render_samples} samples, CPU)")
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
