"""What hides the liquid in the viewport preview: the solids the viewport draws opaque, not objects it draws as
wire or bounds. Found by the trial by hand of docs/blender.md (2026-12-02): the fixture's Mantaflow flow object
(a sphere displayed as wire, hidden from the render) hid the upper half of the liquid in the viewport, while
the final render showed all of it.

Run: run_blender.py --zip ZIP test_viewport_occluders.py -- FIXTURE_DIR
"""

import os
import sys
from types import SimpleNamespace

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import bpy  # noqa: E402
import numpy as np  # noqa: E402

from blender_test_common import arguments, check, install_addon, open_fixture_scene, run, spindrift_module  # noqa: E402


def triangle_count(depsgraph, name):
    module = spindrift_module()
    triangles = module.export.object_triangles(bpy.data.objects[name].evaluated_get(depsgraph), np.identity(4))
    return 0 if triangles is None else len(triangles[1])


def occluder_count(scene, for_render):
    module = spindrift_module()
    depsgraph = bpy.context.evaluated_depsgraph_get()
    soup = module.frame.scene_occluders(scene, depsgraph, for_render=for_render)
    return 0 if soup is None else len(soup["triangles"])


def main():
    install_addon()
    scene = open_fixture_scene(arguments()[0])
    scene.frame_set(4)
    module = spindrift_module()
    bpy.data.objects["Domain"].spindrift.enabled = True
    depsgraph = bpy.context.evaluated_depsgraph_get()
    floor, cube, flow = (triangle_count(depsgraph, name) for name in ("Floor", "Occluder", "Flow"))
    check(floor > 0 and cube > 0 and flow > 0, f"triangles: floor {floor}, cube {cube}, flow sphere {flow}")
    check(bpy.data.objects["Flow"].display_type == "WIRE", "the fixture's flow object is displayed as wire")

    viewport = occluder_count(scene, for_render=False)
    check(viewport == floor + cube, f"viewport: the floor and the cube hide liquid, the wire flow sphere does not "
                                    f"({viewport} triangles, expected {floor + cube})")
    render = occluder_count(scene, for_render=True)
    check(render == floor + cube, f"render: the flow sphere is hidden from the render ({render} triangles)")

    bpy.data.objects["Occluder"].display_type = "BOUNDS"
    viewport = occluder_count(scene, for_render=False)
    check(viewport == floor, f"viewport: a cube displayed as bounds hides nothing ({viewport} triangles)")
    render = occluder_count(scene, for_render=True)
    check(render == floor + cube, f"render: the cube displayed as bounds still renders, so it still hides liquid "
                                  f"({render} triangles)")
    bpy.data.objects["Occluder"].display_type = "TEXTURED"

    # An enabled emitter that renders its own mesh is a solid; the preview draws it as wire (its own drawing
    # hidden), which must not make it stop hiding liquid.
    bpy.ops.mesh.primitive_cube_add(size=0.3, location=(0.6, -1.2, 0.5))
    emitter = bpy.context.object
    emitter.name = "Emitter"
    emitter.modifiers.new("Particles", "PARTICLE_SYSTEM")
    emitter.particle_systems[0].settings.count = 10
    emitter.spindrift.enabled = True
    check(emitter.show_instancer_for_render, "the emitter renders its own mesh")
    module.viewport.hide_own_drawing(scene)
    check(emitter.display_type == "WIRE", "the preview draws the enabled emitter as wire")
    viewport = occluder_count(scene, for_render=False)
    check(viewport == floor + cube + 12, f"viewport: the emitter drawn as wire by the preview still hides liquid "
                                         f"({viewport} triangles, expected {floor + cube + 12})")
    module.viewport.restore_own_drawing()
    check(emitter.display_type == "TEXTURED", "its display comes back when the preview is off")

    shading = module.viewport.shading_hides_liquid
    check(shading(SimpleNamespace(type="SOLID", show_xray=False)), "solid shading: solids hide liquid")
    check(not shading(SimpleNamespace(type="SOLID", show_xray=True)), "solid shading with X-ray: they do not")
    check(not shading(SimpleNamespace(type="WIREFRAME", show_xray=False)), "wireframe shading: they do not")
    check(shading(SimpleNamespace(type="MATERIAL", show_xray=False)), "material preview: they do")
    check(shading(SimpleNamespace(type="RENDERED", show_xray=True)), "rendered shading (no X-ray there): they do")
    print("test_viewport_occluders: passed", flush=True)


run(main)
