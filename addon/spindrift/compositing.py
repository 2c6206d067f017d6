"""The compositor side: the Image node that shows the frame's layers, and the node groups that put them over
Blender's own render.

OVER (liquid and foam over a render without the liquid), per pixel, as the CLI composites:
    render    = render * (f * (liquid_shadow + caustics) + (1 - f) * liquid_sky)   # with lamps only
    refracted = MapUV(render, refraction_uv)             # the render seen through the liquid
    liquid    = refracted * transmittance + reflection   # with the layer's alpha (premultiplied)
    out       = AlphaOver(render, liquid, fac = depth < render Depth) then AlphaOver(., foam)
FOAM_ONLY (foam over a render that contains the domain's liquid mesh): out = AlphaOver(render, foam).
"""

import os

import bpy

IMAGE_NAME = "Spindrift Layers"
IMAGE_NODE = "Spindrift Layers"
GROUP_NODE = "Spindrift"
GROUP_NAMES = {"OVER": "Spindrift Over", "FOAM_ONLY": "Spindrift Foam Only"}
# The layers each group reads from the EXR (group input name = EXR layer name).
GROUP_LAYERS = {
    "OVER": ["liquid", "depth", "refraction_uv", "transmittance", "reflection", "foam"],
    "FOAM_ONLY": ["foam"],
}
# With lamps (OVER only), the light through the liquid onto the render (docs/scene-format.md, "Lights").
LIGHT_LAYERS = ["liquid_shadow", "caustics", "liquid_sky"]


def frame_layers(mode, lit):
    """The layers a frame's EXR holds for the mode's group: lit adds the light layers under OVER."""
    return GROUP_LAYERS[mode] + (LIGHT_LAYERS if lit and mode == "OVER" else [])


def direct_fraction(scene):
    """The scene's light.direct_fraction (Render properties > Spindrift > Light): the share of the render's
    brightness taken to come straight from the lamps, as the command line's composite uses it without Cycles'
    light passes and as the renderer's lit background under the liquid takes it from the same scene file."""
    return float(scene.spindrift.light.direct_fraction)


# The node of the OVER group whose factor is light.direct_fraction: kept the scene's when the value changes.
DIRECT_SHARE_NODE = "Direct fraction"


def set_direct_fraction(fraction):
    """Sets the OVER group's direct share to `fraction` (the group is built with the value at Set Up
    Compositing; this keeps it when the setting changes afterwards). Only a change is written: a write tags
    the node tree for the compositor."""
    group = bpy.data.node_groups.get(GROUP_NAMES["OVER"])
    node = group.nodes.get(DIRECT_SHARE_NODE) if group is not None else None
    if node is not None and abs(node.inputs["Fac"].default_value - fraction) > 1e-7:
        node.inputs["Fac"].default_value = fraction


def _tree(scene):
    return scene.node_tree if scene.use_nodes and scene.node_tree else None


def spindrift_nodes(scene):
    tree = _tree(scene)
    if tree is None:
        return []
    return [node for node in tree.nodes if node.name in (IMAGE_NODE, GROUP_NODE)]


def bypass(scene, bypassed):
    """Mutes the group node (the render passes through unchanged) when a frame has no valid layers."""
    tree = _tree(scene)
    if tree is None:
        return
    node = tree.nodes.get(GROUP_NODE)
    if node is not None and node.mute != bypassed:
        node.mute = bypassed


def layers_image(path):
    image = bpy.data.images.get(IMAGE_NAME)
    if image is None:
        image = bpy.data.images.load(path, check_existing=False)
        image.name = IMAGE_NAME
    return image


def show_layers(scene, path):
    """Makes the Image node show the frame's EXR. The image is a sequence (spindrift_####.exr), so the
    compositor picks each frame's file by itself: under -b nothing needs doing (touching the image would make
    Blender re-read the file at once, ~0.3 s). The interface keeps a stale copy of a file it has shown, so
    there the image is reloaded (checked in 3.4.1: docs/blender.md)."""
    tree = _tree(scene)
    node = tree.nodes.get(IMAGE_NODE) if tree else None
    if node is None or node.image is None:
        return
    image = node.image
    if os.path.dirname(bpy.path.abspath(image.filepath)) != os.path.dirname(path):
        image.filepath = path  # the render output moved since the set-up
    elif not bpy.app.background:
        image.reload()


# --- Building the nodes ----------------------------------------------------------------------------------------

def _socket(node, name):
    for socket in node.outputs:
        if socket.name == name and socket.enabled:
            return socket
    raise KeyError(f"the Spindrift layers have no layer {name!r} "
                   f"(has {[s.name for s in node.outputs if s.enabled]})")


def _new_group(mode, width, lit=False):
    """An empty group of the mode's inputs; returns (group, its input node, its output node)."""
    name = GROUP_NAMES[mode]
    old = bpy.data.node_groups.get(name)
    if old is not None:
        bpy.data.node_groups.remove(old)
    group = bpy.data.node_groups.new(name, "CompositorNodeTree")
    inputs = group.inputs
    inputs.new("NodeSocketColor", "Image")
    if mode == "OVER":
        inputs.new("NodeSocketFloat", "Depth")
    for layer in frame_layers(mode, lit):
        inputs.new("NodeSocketFloat" if layer == "depth" else "NodeSocketColor", layer)
    group.outputs.new("NodeSocketColor", "Image")
    source = group.nodes.new("NodeGroupInput")
    source.location = (-width / 2, 0)
    sink = group.nodes.new("NodeGroupOutput")
    sink.location = (width / 2, 0)
    return group, source, sink


def _lit_render(group, source, fraction):
    """render * (f * (liquid_shadow + caustics) + (1 - f) * liquid_sky), f = `fraction`: the render without
    the liquid, with the liquid's shadow and caustics, before anything refracts or shows it (as the command
    line does)."""
    nodes, links = group.nodes, group.links
    direct = nodes.new("CompositorNodeMixRGB")
    direct.blend_type = "ADD"
    direct.location = (-1000, 450)
    links.new(source.outputs["liquid_shadow"], direct.inputs[1])
    links.new(source.outputs["caustics"], direct.inputs[2])
    share = nodes.new("CompositorNodeMixRGB")  # MIX: (1 - fac) * sky + fac * direct
    share.blend_type = "MIX"
    share.name = share.label = DIRECT_SHARE_NODE
    share.inputs["Fac"].default_value = fraction
    share.location = (-800, 450)
    links.new(source.outputs["liquid_sky"], share.inputs[1])
    links.new(direct.outputs["Image"], share.inputs[2])
    lit = nodes.new("CompositorNodeMixRGB")
    lit.blend_type = "MULTIPLY"
    lit.label = "Lamps through the liquid"
    lit.location = (-600, 450)
    links.new(source.outputs["Image"], lit.inputs[1])
    links.new(share.outputs["Image"], lit.inputs[2])
    return lit.outputs["Image"]


def build_over_group(lit, fraction):
    """The OVER group; `lit` applies the light layers with `fraction` as light.direct_fraction."""
    group, source, sink = _new_group("OVER", 1600, lit)
    nodes, links = group.nodes, group.links
    render = _lit_render(group, source, fraction) if lit else source.outputs["Image"]

    map_uv = nodes.new("CompositorNodeMapUV")
    map_uv.location = (-600, 200)
    links.new(render, map_uv.inputs["Image"])
    links.new(source.outputs["refraction_uv"], map_uv.inputs["UV"])

    transmitted = nodes.new("CompositorNodeMixRGB")
    transmitted.blend_type = "MULTIPLY"
    transmitted.location = (-400, 200)
    links.new(map_uv.outputs["Image"], transmitted.inputs[1])
    links.new(source.outputs["transmittance"], transmitted.inputs[2])

    lit = nodes.new("CompositorNodeMixRGB")
    lit.blend_type = "ADD"
    lit.location = (-200, 200)
    links.new(transmitted.outputs["Image"], lit.inputs[1])
    links.new(source.outputs["reflection"], lit.inputs[2])

    # The liquid's coverage from its own layer; its colour rebuilt from the real render.
    coverage = nodes.new("CompositorNodeSepRGBA")
    coverage.location = (-400, -50)
    links.new(source.outputs["liquid"], coverage.inputs["Image"])
    liquid = nodes.new("CompositorNodeSetAlpha")
    liquid.mode = "REPLACE_ALPHA"
    liquid.location = (0, 200)
    links.new(lit.outputs["Image"], liquid.inputs["Image"])
    links.new(coverage.outputs["A"], liquid.inputs["Alpha"])

    in_front = nodes.new("CompositorNodeMath")
    in_front.operation = "LESS_THAN"
    in_front.location = (0, -150)
    links.new(source.outputs["depth"], in_front.inputs[0])
    links.new(source.outputs["Depth"], in_front.inputs[1])

    over_liquid = nodes.new("CompositorNodeAlphaOver")
    over_liquid.location = (250, 0)
    links.new(in_front.outputs["Value"], over_liquid.inputs["Fac"])
    links.new(render, over_liquid.inputs[1])
    links.new(liquid.outputs["Image"], over_liquid.inputs[2])

    over_foam = nodes.new("CompositorNodeAlphaOver")
    over_foam.location = (480, 0)
    links.new(over_liquid.outputs["Image"], over_foam.inputs[1])
    links.new(source.outputs["foam"], over_foam.inputs[2])
    links.new(over_foam.outputs["Image"], sink.inputs["Image"])
    return group


def build_foam_only_group():
    group, source, sink = _new_group("FOAM_ONLY", 700)
    links = group.links
    over_foam = group.nodes.new("CompositorNodeAlphaOver")
    links.new(source.outputs["Image"], over_foam.inputs[1])
    links.new(source.outputs["foam"], over_foam.inputs[2])
    links.new(over_foam.outputs["Image"], sink.inputs["Image"])
    return group


def build_tree(scene, mode, layers_path):
    """Replaces the scene's Spindrift nodes with a fresh set wired between Render Layers and the Composite
    output. `layers_path` is an EXR of the current frame: its layers become the Image node's sockets."""
    scene.use_nodes = True
    tree = scene.node_tree
    for node in spindrift_nodes(scene):
        tree.nodes.remove(node)
    render_layers = next((n for n in tree.nodes if n.type == "R_LAYERS"), None) or tree.nodes.new(
        "CompositorNodeRLayers")
    composite = next((n for n in tree.nodes if n.type == "COMPOSITE"), None) or tree.nodes.new(
        "CompositorNodeComposite")
    render_layers.location = (-300, 300)

    image = layers_image(layers_path)
    image.filepath = layers_path
    image.source = "SEQUENCE"
    image.reload()
    image_node = tree.nodes.new("CompositorNodeImage")
    image_node.name = image_node.label = IMAGE_NODE
    image_node.image = image
    # File number = scene frame: spindrift_0012.exr is frame 12's.
    image_node.frame_start = 1
    image_node.frame_offset = 0
    image_node.frame_duration = 1048574
    image_node.use_auto_refresh = True
    image_node.location = (-300, -100)

    # Lamps were handed when the EXR has their layers; the group then applies them.
    lit = mode == "OVER" and all(any(o.name == name and o.enabled for o in image_node.outputs)
                                 for name in LIGHT_LAYERS)
    group = build_over_group(lit, direct_fraction(scene)) if mode == "OVER" else build_foam_only_group()
    group_node = tree.nodes.new("CompositorNodeGroup")
    group_node.node_tree = group
    group_node.name = group_node.label = GROUP_NODE
    group_node.location = (100, 200)

    links = tree.links
    links.new(render_layers.outputs["Image"], group_node.inputs["Image"])
    if mode == "OVER":
        links.new(render_layers.outputs["Depth"], group_node.inputs["Depth"])
    for layer in frame_layers(mode, lit):
        links.new(_socket(image_node, layer), group_node.inputs[layer])
    links.new(group_node.outputs["Image"], composite.inputs["Image"])
    composite.location = (400, 200)
    viewer = next((n for n in tree.nodes if n.type == "VIEWER"), None) or tree.nodes.new("CompositorNodeViewer")
    viewer.location = (400, 0)
    links.new(group_node.outputs["Image"], viewer.inputs["Image"])
    return group_node
