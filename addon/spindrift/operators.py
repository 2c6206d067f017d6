"""Operators: set up compositing, render the current frame's layers, export a scene file for the CLI."""

import os

import bpy
import numpy as np
from bpy.props import EnumProperty, IntProperty, StringProperty

from . import compositing, export, frame as frame_inputs, render_layer, reports, scene_json
from .scene_json import BadInput


def _report_issues(operator, issues):
    for issue in issues:
        operator.report({"WARNING"}, issue)
        reports.warn(issue)


class SPINDRIFT_OT_setup_compositing(bpy.types.Operator):
    """Render this frame's Spindrift layers and build the compositor nodes that put them over the render"""

    bl_idname = "spindrift.setup_compositing"
    bl_label = "Set Up Compositing"
    bl_options = {"REGISTER", "UNDO"}

    mode: EnumProperty(
        name="Mode", default="OVER",
        items=[("OVER", "Liquid and Foam Over",
                "Liquid and foam over a render without the liquid (the domain's mesh is hidden from the render)"),
               ("FOAM_ONLY", "Foam Only",
                "Foam over a render that contains the domain's liquid mesh (its depth fades the foam below)")])

    def execute(self, context):
        scene = context.scene
        domains = [obj for obj in export.enabled_objects(scene) if export.liquid_domain_settings(obj)]
        if self.mode == "FOAM_ONLY":
            missing_mesh = [obj.name for obj in domains if not export.liquid_domain_settings(obj).use_mesh]
            if missing_mesh:
                self.report({"WARNING"}, f"domains without a liquid mesh (enable Mesh and bake): {missing_mesh}")
        for obj in domains:
            obj.hide_render = self.mode == "OVER"
        scene.spindrift.composite_mode = self.mode
        for view_layer in scene.view_layers:
            view_layer.use_pass_z = True

        window_manager = context.window_manager
        window_manager.progress_begin(0, 3)
        try:
            window_manager.progress_update(1)
            path = render_layer.layer_path(scene, scene.frame_current)
            depsgraph = context.evaluated_depsgraph_get()
            _result, inputs, _times = render_layer.render_frame(scene, depsgraph, scene.frame_current, path)
            window_manager.progress_update(2)
            compositing.build_tree(scene, self.mode, path)
        except BadInput as error:
            self.report({"ERROR"}, str(error))
            reports.error(str(error))
            return {"CANCELLED"}
        except Exception as error:  # noqa: BLE001 - the module's Error: reported, Blender keeps running
            self.report({"ERROR"}, f"{type(error).__name__}: {error}")
            reports.error(f"{type(error).__name__}: {error}")
            return {"CANCELLED"}
        finally:
            window_manager.progress_end()
        _report_issues(self, inputs.issues)
        self.report({"INFO"}, f"Spindrift compositing set up ({self.mode}) with {path}")
        return {"FINISHED"}


class SPINDRIFT_OT_render_layers(bpy.types.Operator):
    """Render Spindrift's layers of the current frame beside the render output and show them in the
    compositor"""

    bl_idname = "spindrift.render_layers"
    bl_label = "Render Layers"

    def execute(self, context):
        scene = context.scene
        ok = render_layer.render_layers_now(scene, context.evaluated_depsgraph_get(), scene.frame_current)
        message = reports.last_render["message"]
        self.report({"INFO"} if ok else {"ERROR"}, message)
        _report_issues(self, reports.last_render["issues"])
        return {"FINISHED"} if ok else {"CANCELLED"}


def write_ply(path, particles, role):
    """Particles as a binary PLY that the scene file's `ply` sources read (x y z radius type life)."""
    count = len(particles["radii"])
    kinds = particles["kinds"].astype(np.int32)
    life = particles.get("life", np.zeros(count, np.float32))
    record = np.dtype([("x", "<f4"), ("y", "<f4"), ("z", "<f4"), ("radius", "<f4"), ("type", "<i4"),
                       ("life", "<f4")])
    rows = np.empty(count, dtype=record)
    rows["x"], rows["y"], rows["z"] = particles["positions"].T
    rows["radius"], rows["type"], rows["life"] = particles["radii"], kinds, life
    header = ("ply\nformat binary_little_endian 1.0\n"
              f"comment Spindrift {role} particles exported from Blender\nelement vertex {count}\n"
              "property float x\nproperty float y\nproperty float z\nproperty float radius\n"
              "property int type\nproperty float life\nend_header\n")
    with open(path, "wb") as file:
        file.write(header.encode("ascii"))
        file.write(rows.tobytes())


def export_scene(scene, depsgraph, path, frame, background=""):
    """Writes a scene file for `spindrift render` with the frame's camera, caches and parameters; particles
    that exist only in Blender go to PLY files beside it. Returns the Frame."""
    camera = export.scene_camera(scene, depsgraph)
    inputs = frame_inputs.collect(scene, depsgraph, frame, camera, occluders=False)
    document = inputs.document
    particles = inputs.kwargs.get("particles")
    base = os.path.splitext(path)[0]
    if particles is not None:
        for role, mask in (("liquid", particles["kinds"] == 0), ("foam", particles["kinds"] != 0)):
            if mask.any():
                subset = {name: values[mask] for name, values in particles.items()}
                ply_path = f"{base}_{role}_{frame:04d}.ply"
                write_ply(ply_path, subset, role)
                document["particles"].append({"path": os.path.basename(ply_path), "role": role,
                                              "radius": float(subset["radii"].max())})
    if background:
        document["background"]["image"] = os.path.relpath(bpy.path.abspath(background), os.path.dirname(path))
    with open(path, "w", encoding="utf-8") as file:
        file.write(scene_json.dumps(document))
    return inputs


class SPINDRIFT_OT_export_scene(bpy.types.Operator):
    """Write a Spindrift scene file of the current frame for the command line (`spindrift render`)"""

    bl_idname = "spindrift.export_scene"
    bl_label = "Export Scene File"

    filepath: StringProperty(subtype="FILE_PATH", default="//spindrift_scene.json")
    frame: IntProperty(name="Frame", default=-1, description="The frame to export; -1 for the current frame")
    background: StringProperty(name="Background", subtype="FILE_PATH", default="",
                               description="An image (e.g. Blender's render as EXR with Depth) the CLI renders over")

    def execute(self, context):
        scene = context.scene
        frame = scene.frame_current if self.frame < 0 else self.frame
        if frame != scene.frame_current:
            scene.frame_set(frame)  # particle systems are read as evaluated at the frame
        path = bpy.path.abspath(self.filepath)
        try:
            inputs = export_scene(scene, context.evaluated_depsgraph_get(), path, frame, self.background)
        except BadInput as error:
            self.report({"ERROR"}, str(error))
            reports.error(str(error))
            return {"CANCELLED"}
        _report_issues(self, inputs.issues)
        self.report({"INFO"}, f"wrote {path}")
        return {"FINISHED"}

    def invoke(self, context, _event):
        context.window_manager.fileselect_add(self)
        return {"RUNNING_MODAL"}


CLASSES = (SPINDRIFT_OT_setup_compositing, SPINDRIFT_OT_render_layers, SPINDRIFT_OT_export_scene)


register, unregister = bpy.utils.register_classes_factory(CLASSES)
