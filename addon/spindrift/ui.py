"""Panels: Physics properties (per object: enable, source, liquid and foam parameters), Render properties
(render layer, compositing, viewport preview, the last frame, the scene's light parameters) and the 3D
viewport's sidebar (preview)."""

import bpy

from . import export, native, parameters, reports, viewport


def _draw_parameters(layout, settings, group):
    try:
        table = native.parameter_table()
    except ImportError as error:
        layout.label(text=str(error), icon="ERROR")
        return
    column = layout.column(align=True)
    for row in table:
        if row["group"] != group:
            continue
        from_blender = parameters.FROM_BLENDER.get((group, row["name"]))
        if from_blender:  # no property of ours: Blender's own setting is the one to change
            column.label(text=f"{row['name'].replace('_', ' ').capitalize()}: from {from_blender}")
        else:
            column.prop(settings, row["name"])


class SPINDRIFT_PT_object(bpy.types.Panel):
    bl_label = "Spindrift"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "physics"

    @classmethod
    def poll(cls, context):
        obj = context.object
        return obj is not None and obj.type in {"MESH", "POINTCLOUD"} | ({obj.type} if obj.particle_systems else set())

    def draw_header(self, context):
        self.layout.prop(context.object.spindrift, "enabled", text="")

    def draw(self, context):
        obj = context.object
        props = obj.spindrift
        layout = self.layout
        layout.use_property_split = True
        layout.active = props.enabled
        domain = export.liquid_domain_settings(obj)
        if domain is not None:
            layout.label(text="Source: Mantaflow liquid domain (OpenVDB cache)", icon="MOD_FLUIDSIM")
            if domain.cache_data_format != "OPENVDB":
                layout.label(text="Set the cache's volume format to OpenVDB and bake", icon="ERROR")
            layout.prop(props, "liquid_radius_from_domain")
            row = layout.row()
            row.active = not props.liquid_radius_from_domain
            row.prop(props, "liquid_radius_cells")
            layout.prop(props, "foam_radius_cells")
        elif obj.particle_systems:
            layout.label(text=f"Source: {len(obj.particle_systems)} particle system(s)", icon="PARTICLES")
            layout.prop(props, "role")
            layout.prop(props, "size_scale")
        else:
            layout.label(text="Source: the object's vertices or points", icon="POINTCLOUD_DATA")
            layout.prop(props, "role")
            layout.prop(props, "radius")
        primary = export.primary_object(context.scene)
        if props.enabled and primary is not None and primary != obj:
            layout.label(text=f"The frame uses {primary.name}'s parameters", icon="INFO")


def draw_preview_settings(layout, scene):
    settings = scene.spindrift
    layout.prop(settings, "preview")
    column = layout.column()
    column.active = settings.preview
    column.prop(settings, "preview_scale")
    column.prop(settings, "preview_quality")
    message, frame_ms = viewport.status()
    if frame_ms is not None:
        column.label(text=f"Preview frame: {frame_ms:.0f} ms ({message})", icon="TIME")
    elif message:
        column.label(text=message, icon="ERROR")


class SPINDRIFT_PT_render(bpy.types.Panel):
    bl_label = "Spindrift"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "render"

    def draw(self, context):
        scene = context.scene
        settings = scene.spindrift
        layout = self.layout
        layout.use_property_split = True
        enabled = export.enabled_objects(scene)
        if not enabled:
            layout.label(text="Enable Spindrift on a liquid domain or particle object (Physics)", icon="INFO")
        else:
            layout.label(text="Sources: " + ", ".join(obj.name for obj in enabled))
        layout.prop(settings, "render_layer")
        layout.prop(settings, "occluders")
        layout.prop(settings, "all_layers")
        layout.prop(settings, "on_error")
        row = layout.row(align=True)
        row.operator("spindrift.setup_compositing", text="Liquid and Foam Over").mode = "OVER"
        row.operator("spindrift.setup_compositing", text="Foam Only").mode = "FOAM_ONLY"
        layout.operator("spindrift.render_layers", icon="RENDER_STILL")
        layout.operator("spindrift.export_scene", icon="EXPORT")
        last = reports.last_render
        if last["message"]:
            layout.label(text=f"Last: {last['message']}", icon="ERROR" if last["ms"] is None else "CHECKMARK")
            for issue in last["issues"][:4]:
                layout.label(text=issue, icon="ERROR")
        layout.separator()
        draw_preview_settings(layout, scene)


def parameter_panel(group, label, parent):
    """A closed sub-panel of `parent` (a Spindrift panel) with every parameter of one group of the table, read
    from the object or the scene as parameters.GROUP_OWNERS says; each tooltip is the row's documentation."""
    owner = parameters.GROUP_OWNERS[group]

    def draw(self, context):
        self.layout.use_property_split = True
        holder = context.object if owner == "object" else context.scene
        _draw_parameters(self.layout, getattr(holder.spindrift, group), group)

    return type(f"{parent.__name__}_{group}", (bpy.types.Panel,), {
        "bl_label": label, "bl_parent_id": parent.__name__, "bl_space_type": "PROPERTIES",
        "bl_region_type": "WINDOW", "bl_context": parent.bl_context, "bl_options": {"DEFAULT_CLOSED"},
        "draw": draw})


SPINDRIFT_PT_object_liquid = parameter_panel("liquid", "Liquid", SPINDRIFT_PT_object)
SPINDRIFT_PT_object_foam = parameter_panel("foam", "Foam", SPINDRIFT_PT_object)
# Lamps and the world light the whole scene: its light parameters sit with the render's settings.
SPINDRIFT_PT_render_light = parameter_panel("light", "Light", SPINDRIFT_PT_render)


class SPINDRIFT_PT_view3d(bpy.types.Panel):
    bl_label = "Spindrift"
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "Spindrift"

    def draw(self, context):
        self.layout.use_property_split = True
        draw_preview_settings(self.layout, context.scene)


CLASSES = (SPINDRIFT_PT_object, SPINDRIFT_PT_object_liquid, SPINDRIFT_PT_object_foam, SPINDRIFT_PT_render,
           SPINDRIFT_PT_render_light, SPINDRIFT_PT_view3d)


register, unregister = bpy.utils.register_classes_factory(CLASSES)
