"""The add-on's properties: `obj.spindrift` (enabled, source settings, the generated `liquid` and `foam`
parameter groups), `scene.spindrift` (preview and render-layer settings, the generated `light` parameter group)
and the add-on's preferences."""

import bpy
from bpy.props import BoolProperty, EnumProperty, FloatProperty, PointerProperty
from bpy.types import AddonPreferences, PropertyGroup

from . import native, parameters

ROLE_ITEMS = [
    ("LIQUID", "Liquid", "The particles are liquid"),
    ("FOAM", "Foam", "The particles are surface foam"),
    ("SPRAY", "Spray", "The particles are spray"),
    ("BUBBLE", "Bubbles", "The particles are bubbles"),
]

QUALITY_ITEMS = [
    ("DRAFT", "Draft", "One refraction, one smoothing iteration, one occlusion pass per 4x4 block: fastest"),
    ("BALANCED", "Balanced", "Two refractions, two smoothing iterations and occlusion passes"),
    ("FULL", "Full", "The object's own parameters, as the final render uses them"),
]

ON_ERROR_ITEMS = [
    ("SKIP", "Render without the layer", "Report the problem and let the frame finish without Spindrift's "
     "layer (its compositor nodes are bypassed)"),
    ("STOP", "Stop (background only)", "Under blender -b, stop with exit code 1; in the interface, report "
     "the problem and go on without the layer"),
]


def _redraw_viewports(_self=None, _context=None):
    from . import viewport
    viewport.settings_changed()


def _toggle_preview(self, context):
    from . import viewport
    viewport.enable(self.preview)


class SpindriftObjectSettings(PropertyGroup):
    enabled: BoolProperty(name="Spindrift", default=False, update=_redraw_viewports,
                          description="Render this liquid domain, particle system or point object with Spindrift")
    role: EnumProperty(name="Particles are", items=ROLE_ITEMS, default="LIQUID", update=_redraw_viewports,
                       description="What the particles of a particle system, mesh or point cloud are")
    radius: FloatProperty(name="Radius", default=0.05, min=1e-6, soft_max=10.0, unit="LENGTH", precision=4,
                          update=_redraw_viewports,
                          description="Radius of each vertex or point (a 'radius' attribute overrides it)")
    size_scale: FloatProperty(name="Size Scale", default=1.0, min=1e-6, soft_max=10.0, update=_redraw_viewports,
                              description="A particle system's particle radius is its size times this factor")
    liquid_radius_from_domain: BoolProperty(
        name="Radius from Domain", default=True, update=_redraw_viewports,
        description="Derive the liquid particles' radius from the domain's settings (1.1 particle spacings), as "
                    "Spindrift always derives the surface offset that puts the liquid where Blender's liquid "
                    "mesh stands")
    liquid_radius_cells: FloatProperty(
        name="Liquid Radius", default=0.55, min=0.05, max=4.0, update=_redraw_viewports,
        description="With Radius from Domain off: the radius of a Mantaflow liquid particle in grid cells "
                    "(Mantaflow seeds two particles per cell and axis, half a cell apart; 0.55 closes the "
                    "surface)")
    foam_radius_cells: FloatProperty(
        name="Foam Radius", default=0.6, min=0.01, max=4.0, update=_redraw_viewports,
        description="Radius of spray, foam and bubble particles in grid cells")


class SpindriftSceneSettings(PropertyGroup):
    preview: BoolProperty(name="Viewport Preview", default=False, update=_toggle_preview,
                          description="Draw Spindrift's liquid and foam in the 3D viewports")
    preview_scale: FloatProperty(name="Preview Scale", default=0.5, min=0.1, max=1.0, update=_redraw_viewports,
                                 description="Resolution of the viewport preview relative to the viewport")
    preview_quality: EnumProperty(name="Quality", items=QUALITY_ITEMS, default="BALANCED",
                                  update=_redraw_viewports, description="Speed against quality in the viewport")
    render_layer: BoolProperty(name="Render Layer", default=True,
                               description="Write Spindrift's multilayer EXR beside the render output for every "
                                           "rendered frame, for the compositor")
    occluders: BoolProperty(name="Scene Hides Liquid", default=True,
                            description="Draw the scene's visible geometry into a depth prepass, so solids in "
                                        "front of the liquid and foam hide them in the rendered layers and the "
                                        "viewport preview")
    composite_mode: EnumProperty(
        name="Composite", default="OVER",
        items=[("OVER", "Liquid and Foam Over", "Liquid and foam over a render without the liquid"),
               ("FOAM_ONLY", "Foam Only", "Foam over a render that contains the domain's liquid mesh")],
        description="What the layers hold; set by Set Up Compositing")
    all_layers: BoolProperty(name="Every Layer", default=False,
                             description="Render and write every Spindrift layer (normal, thickness, foam parts, "
                                         "...) for nodes of your own, not only those the Spindrift group reads; "
                                         "costs render and write time per frame")
    on_error: EnumProperty(name="On Error", items=ON_ERROR_ITEMS, default="SKIP",
                           description="What a frame does when Spindrift cannot render its layer")


class SpindriftPreferences(AddonPreferences):
    bl_idname = __package__

    default_preview_scale: FloatProperty(name="Default Preview Scale", default=0.5, min=0.1, max=1.0)
    log_frames: BoolProperty(name="Log Every Frame", default=True,
                             description="Print one line per rendered frame on the console")

    def draw(self, context):
        layout = self.layout
        layout.prop(self, "log_frames")
        status = native.status()
        layout.label(text=f"Native module: {status}")


def _light_changed(self, _context):
    # The compositor's group multiplies the render with light.direct_fraction as a constant: keep it the
    # scene's, as the renderer's lit background under the liquid takes it from the frame's scene file.
    from . import compositing
    compositing.set_direct_fraction(self.direct_fraction)
    _redraw_viewports()


# The classes that hold each owner's groups (parameters.GROUP_OWNERS), and what a change of a group's value
# must do beyond the depsgraph update every property change brings.
_OWNER_CLASSES = {"object": SpindriftObjectSettings, "scene": SpindriftSceneSettings}
_GROUP_UPDATES = {"light": _light_changed}


def parameter_group_classes():
    """{group: PropertyGroup class} for every group of the native table (liquid, foam, light), generated from
    its rows."""
    table = native.parameter_table()
    classes = {}
    for group in parameters.GROUP_OWNERS:
        annotations = parameters.property_definitions(table, group, bpy.props, _GROUP_UPDATES.get(group))
        classes[group] = type(f"SpindriftParameters_{group}", (PropertyGroup,), {"__annotations__": annotations})
    return classes


_registered = []


def register():
    groups = parameter_group_classes()
    for group, cls in groups.items():
        _OWNER_CLASSES[parameters.GROUP_OWNERS[group]].__annotations__[group] = PointerProperty(type=cls)
    for cls in (*groups.values(), SpindriftObjectSettings, SpindriftSceneSettings, SpindriftPreferences):
        bpy.utils.register_class(cls)
        _registered.append(cls)
    bpy.types.Object.spindrift = PointerProperty(type=SpindriftObjectSettings)
    bpy.types.Scene.spindrift = PointerProperty(type=SpindriftSceneSettings)


def unregister():
    del bpy.types.Scene.spindrift
    del bpy.types.Object.spindrift
    while _registered:
        bpy.utils.unregister_class(_registered.pop())
