"""One Spindrift frame's inputs from a Blender scene: the scene file's text plus the in-memory arrays.

Used by the final render (render_layer.py), the viewport (viewport.py), the compositing set-up and the
scene-file export, so all of them render the same thing for the same frame.
"""

import numpy as np

from . import export, native, parameters, scene_json
from .scene_json import BadInput

# Viewport quality presets: parameter overrides on top of the primary object's own values (FULL adds none).
QUALITY_OVERRIDES = {
    "DRAFT": {"liquid": {"max_refractions": 1, "internal_reflections": 0, "smoothing_iterations": 1,
                         "trace_max_steps": 32},
              "foam": {"ao_passes": 1, "ao_max_samples": 32, "occlusion_block": 4}},
    "BALANCED": {"liquid": {"max_refractions": 2, "internal_reflections": 2, "smoothing_iterations": 2,
                            "trace_max_steps": 64},
                 "foam": {"ao_passes": 2, "ao_max_samples": 128}},
    "FULL": {"liquid": {}, "foam": {}},
}

MODES = ("OVER", "FOAM_ONLY")


class Frame:
    """What `Renderer.render` needs for one frame, and the problems met while collecting it."""

    def __init__(self, document, kwargs, issues):
        self.document = document
        self.kwargs = kwargs
        self.issues = issues

    @property
    def scene_text(self):
        return scene_json.dumps(self.document)

    def particle_count(self):
        particles = self.kwargs.get("particles")
        return 0 if particles is None else len(particles["radii"])


def parameter_values(scene, obj, quality=None):
    """{group: the values the scene file's group object takes} for every group of the table: liquid and foam
    from `obj` (the frame's primary object; none without one), light from the scene
    (parameters.GROUP_OWNERS). `quality` adds a viewport preset's overrides."""
    table = native.parameter_table()
    owners = {"object": obj.spindrift if obj else None, "scene": scene.spindrift}
    values = {}
    for group, owner in parameters.GROUP_OWNERS.items():
        settings = owners[owner]
        values[group] = parameters.group_values(table, group, getattr(settings, group)) if settings else {}
        if quality:
            values[group].update(QUALITY_OVERRIDES[quality].get(group, {}))
    # What Blender's settings say (parameters.FROM_BLENDER): the film's pixel filter, written where it is not
    # the table's default, as group_values writes the rest.
    width = parameters.pixel_filter_width(*export.film_pixel_filter(scene))
    if abs(width - parameters.group_defaults(table, "liquid")["pixel_filter_width"]) > 1e-6:
        values["liquid"]["pixel_filter_width"] = width
    return values


def collect(scene, depsgraph, frame, camera, *, mode="OVER", occluders=True, quality=None, for_render=True):
    """The frame's inputs for `camera` (a scene-file camera dict). `mode` FOAM_ONLY renders the foam alone,
    with the domains' own meshes as the liquid surface; OVER renders liquid and foam."""
    if mode not in MODES:
        raise ValueError(f"mode must be one of {MODES}, not {mode!r}")
    objects = export.enabled_objects(scene)
    if not objects:
        raise BadInput("no object has Spindrift enabled (Physics properties > Spindrift)")
    issues, sources, particle_sets, liquid_meshes = [], [], [], []
    for obj in objects:
        if export.liquid_domain_settings(obj) is not None:
            domain_sources = export.domain_sources(obj, frame, issues)
            if mode == "FOAM_ONLY":
                domain_sources = [s for s in domain_sources if s["role"] != "liquid"]
                mesh = export.domain_mesh_triangles(obj.evaluated_get(depsgraph))
                if mesh is None:
                    issues.append(f"domain {obj.name}: no liquid mesh at frame {frame} (enable Mesh in the "
                                  f"domain's settings and bake it); foam is not faded below the surface")
                else:
                    liquid_meshes.append(mesh)
            sources.extend(domain_sources)
        else:
            sets = export.object_particles(obj, depsgraph, frame, issues)
            if mode == "FOAM_ONLY":
                sets = [export.ParticleSet(s.positions[s.kinds != 0], s.radii[s.kinds != 0], s.kinds[s.kinds != 0],
                                           None if s.life is None else s.life[s.kinds != 0]) for s in sets]
            particle_sets.extend(sets)

    values = parameter_values(scene, export.primary_object(scene), quality)
    # Lamps light the foam (foam.lit_by_lights) and, under OVER, the background under the liquid
    # (liquid_shadow, caustics); with the liquid in the render (FOAM_ONLY) Cycles has lit that already, and
    # no liquid particle is handed, so the light passes are skipped (no light sees the liquid).
    lights = export.scene_lights(depsgraph, for_render=for_render)
    document = scene_json.scene_document(camera, frame, sources, {"color": export.world_color(scene)},
                                         values["liquid"], values["foam"], lights, values["light"])
    kwargs = {}
    particles = export.merge_particles(particle_sets)
    if particles is not None:
        kwargs["particles"] = particles
    if occluders:
        triangles = scene_occluders(scene, depsgraph, for_render=for_render)
        if triangles is not None:
            kwargs["occluders"] = triangles
    if liquid_meshes:
        kwargs["liquid_mesh"] = merge_triangles(liquid_meshes)
    if not sources and particles is None:
        issues.append("no particles to render")
    return Frame(document, kwargs, issues)


def scene_occluders(scene, depsgraph, for_render=True):
    """The scene's solids as one triangle soup for the occluder depth prepass, or None. Point and domain
    objects are Spindrift's to draw; an emitter that renders its own mesh is a solid."""
    excluded = {obj.name for obj in export.enabled_objects(scene)
                if not (obj.particle_systems and obj.show_instancer_for_render)
                or export.liquid_domain_settings(obj) is not None}
    return export.occluder_triangles(depsgraph, excluded, for_render=for_render)


def merge_triangles(meshes):
    vertices, triangles, offset = [], [], 0
    for mesh_vertices, mesh_triangles in meshes:
        vertices.append(mesh_vertices)
        triangles.append(mesh_triangles + offset)
        offset += len(mesh_vertices)
    return {"vertices": np.ascontiguousarray(np.concatenate(vertices), dtype=np.float32),
            "triangles": np.ascontiguousarray(np.concatenate(triangles), dtype=np.int32)}
