"""Spindrift for Blender: screen-space liquid and foam in the viewport, and as compositor layers of every
rendered frame. See docs/blender.md."""

bl_info = {
    "name": "Spindrift",
    "author": "Spindrift contributors",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "Properties > Physics > Spindrift; Properties > Render > Spindrift; 3D Viewport > Sidebar",
    "description": "Screen-space liquid and foam: live viewport preview and compositor layers per frame",
    "category": "Render",
}

if "bpy" in locals():
    import importlib

    for _name in ("native", "parameters", "scene_json", "export", "frame", "reports", "compositing",
                  "render_layer", "viewport", "properties", "operators", "ui"):
        if _name in locals():
            importlib.reload(locals()[_name])

import bpy  # noqa: E402
from bpy.app.handlers import persistent  # noqa: E402

from . import (compositing, export, frame, native, operators, parameters, properties,  # noqa: E402,F401
               render_layer, reports, scene_json, ui, viewport)

_MODULES = (properties, operators, ui, render_layer, viewport)


@persistent
def _on_load(_scene, _depsgraph=None):
    viewport.enable(any(scene.spindrift.preview for scene in bpy.data.scenes))


def register():
    for module in _MODULES:
        module.register()
    bpy.app.handlers.load_post.append(_on_load)


def unregister():
    if _on_load in bpy.app.handlers.load_post:
        bpy.app.handlers.load_post.remove(_on_load)
    for module in reversed(_MODULES):
        module.unregister()
    native.close()
