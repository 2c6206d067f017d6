"""Plain-Python tests of the add-on's pure parts (no Blender, no native module): properties generated from the
parameter table (liquid and foam on the object, light on the scene) and the scene file's groups, when the EXR
carries the light layers, Mantaflow's cache-to-world formula, cameras from projection matrices, viewport depth.

Run: /usr/bin/python3 -m pytest -q tests/blender/test_addon_python.py
"""

import ast
import importlib.util
import json
import math
import pathlib
import re
import sys
import types

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
ADDON = ROOT / "addon" / "spindrift"


def load(name):
    spec = importlib.util.spec_from_file_location(f"spindrift_{name}", ADDON / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


parameters = load("parameters")
scene_json = load("scene_json")


def load_in_package(name, **stubs):
    """An add-on module that imports its siblings (`from . import ...`), in a package of the pure modules
    above and `stubs` standing for those that need Blender or the native module."""
    package = types.ModuleType("spindrift_stub")
    package.__path__ = []
    siblings = {"parameters": parameters, "scene_json": scene_json, **stubs}
    for sibling, module in siblings.items():
        setattr(package, sibling, module)
        sys.modules[f"spindrift_stub.{sibling}"] = module
    sys.modules["spindrift_stub"] = package
    spec = importlib.util.spec_from_file_location(f"spindrift_stub.{name}", ADDON / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


# --- The parameter table, read from parameters.def independently of the native module ------------------------

def table_from_def():
    """Rows of parameters.def as `_spindrift.parameter_table()` promises them (docs/python-module.md)."""
    text = (ROOT / "native/include/spindrift/parameters.def").read_text()
    rows = []
    pattern = re.compile(r'X\((liquid|foam|light),\s*(\w+),\s*(\w+),\s*\(([^)]*)\),'
                         r'\s*([-\d.e+]+),\s*([-\d.e+]+),\s*"([^"]*)"')
    for group, name, kind, default, low, high, choices in pattern.findall(text):
        kind = kind.lower()
        values = [v.strip().rstrip("f").strip('"') for v in default.split(",")]
        if kind in ("color", "vec3"):
            value = tuple(float(v) for v in values)
        elif kind == "float":
            value = float(values[0])
        elif kind == "int":
            value = int(values[0])
        elif kind == "bool":
            value = values[0] == "true"
        else:
            value = values[0]
        rows.append({"group": group, "name": name, "type": kind, "default": value, "min": float(low),
                     "max": float(high), "choices": choices.split("|") if choices else [], "doc": "doc " + name})
    return rows


class FakeProps:
    """Stands in for bpy.props: each constructor returns (constructor name, keywords)."""

    def __getattr__(self, name):
        return lambda **keywords: (name, keywords)


def test_every_parameter_becomes_a_property_of_its_type():
    table = table_from_def()
    assert len(table) > 40
    expected = {"float": "FloatProperty", "int": "IntProperty", "bool": "BoolProperty",
                "color": "FloatVectorProperty", "vec3": "FloatVectorProperty", "choice": "EnumProperty"}
    assert list(parameters.GROUP_OWNERS) == ["liquid", "foam", "light"]
    for group in parameters.GROUP_OWNERS:
        definitions = parameters.property_definitions(table, group, FakeProps())
        rows = [row for row in table if row["group"] == group and (group, row["name"]) not in parameters.FROM_BLENDER]
        assert list(definitions) == [row["name"] for row in rows]
        for row in rows:
            constructor, keywords = definitions[row["name"]]
            assert constructor == expected[row["type"]], row["name"]
            assert keywords["description"] == row["doc"]
            if row["type"] in ("float", "int"):
                assert keywords["min"] == row["min"] and keywords["max"] == row["max"], row["name"]
                assert keywords["min"] <= keywords["default"] <= keywords["max"], row["name"]
            if row["type"] == "choice":
                assert [item[0] for item in keywords["items"]] == row["choices"]
                assert keywords["default"] == row["default"]
            if row["type"] == "color":
                assert keywords["subtype"] == "COLOR" and keywords["size"] == 3


def cycles_filter_deviation(filter_type, width):
    """The standard deviation in pixels of Cycles' pixel filter, integrated here from the filter functions and
    spans of intern/cycles/scene/film.cpp: a box over the width; a Gaussian exp(-2 (6 x / 3w)^2) over three
    widths; Blackman-Harris over two."""
    span = {"BOX": 1.0, "GAUSSIAN": 3.0, "BLACKMAN_HARRIS": 2.0}[filter_type] * width
    x = np.linspace(-span / 2, span / 2, 200001)
    if filter_type == "BOX":
        weight = np.ones_like(x)
    elif filter_type == "GAUSSIAN":
        weight = np.exp(-2.0 * (x * 6.0 / span) ** 2)
    else:
        t = 2 * np.pi * (x / span + 0.5)
        weight = 0.35875 - 0.48829 * np.cos(t) + 0.14128 * np.cos(2 * t) - 0.01168 * np.cos(3 * t)
    return math.sqrt((weight * x * x).sum() / weight.sum())


def test_the_pixel_filter_comes_from_the_film():
    """liquid.pixel_filter_width is Blender's Film > Pixel Filter, as the Blackman-Harris width of the same
    spread, not a property of the add-on's own."""
    table = table_from_def()
    assert ("liquid", "pixel_filter_width") in parameters.FROM_BLENDER
    assert "pixel_filter_width" not in parameters.property_definitions(table, "liquid", FakeProps())
    settings = types.SimpleNamespace(**{row["name"]: row["default"] for row in table if row["group"] == "liquid"})
    settings.pixel_filter_width = 3.0  # would be written if it were a property; it is not
    assert "pixel_filter_width" not in parameters.group_values(table, "liquid", settings)
    assert parameters.pixel_filter_width("BLACKMAN_HARRIS", 1.5) == 1.5
    for filter_type in ("BOX", "GAUSSIAN", "BLACKMAN_HARRIS"):
        for width in (0.5, 1.5, 3.0):
            equivalent = parameters.pixel_filter_width(filter_type, width)
            assert cycles_filter_deviation("BLACKMAN_HARRIS", equivalent) == pytest.approx(
                cycles_filter_deviation(filter_type, width), rel=0.01), (filter_type, width)
    with pytest.raises(ValueError, match="unknown pixel filter"):
        parameters.pixel_filter_width("MITCHELL", 1.5)


def test_every_group_of_the_table_has_a_home():
    """A group missing from GROUP_OWNERS would have no properties, no panel and no place in the scene file."""
    text = (ROOT / "native/include/spindrift/parameters.def").read_text()
    block = text[text.index("#define SPINDRIFT_PARAMETER_GROUPS"):]
    groups = re.findall(r"X\((\w+), \w+, SPINDRIFT_\w+_PARAMETERS\)", block)
    assert groups == ["liquid", "foam", "light"]
    assert set(parameters.GROUP_OWNERS) == set(groups)
    # Lamps and the world are scene-wide: the light group is the scene's, the others the primary object's.
    assert parameters.GROUP_OWNERS == {"liquid": "object", "foam": "object", "light": "scene"}


def test_light_rows_become_scene_properties_with_their_docs_and_update():
    table = table_from_def()
    rows = [row for row in table if row["group"] == "light"]
    assert [row["name"] for row in rows] == [
        "shadow_map_size", "texels_per_radius", "column_particles", "caustics", "caustic_grid_step",
        "max_concentration", "skip_unlit_tiles", "direct_fraction", "sky_occlusion_directions", "sky_without_lamps"]

    def changed(_self, _context):
        pass

    definitions = parameters.property_definitions(table, "light", FakeProps(), update=changed)
    assert definitions["caustics"] == ("BoolProperty", {"default": True, "name": "Caustics",
                                                        "description": "doc caustics", "update": changed})
    assert definitions["sky_without_lamps"][0] == "BoolProperty"
    assert definitions["sky_without_lamps"][1]["default"] is True
    constructor, keywords = definitions["direct_fraction"]
    assert constructor == "FloatProperty" and keywords["default"] == pytest.approx(0.6)
    assert (keywords["min"], keywords["max"]) == (0.0, 1.0)
    assert definitions["shadow_map_size"][0] == "IntProperty"
    assert definitions["shadow_map_size"][1]["default"] == 512
    assert all(keywords["update"] is changed for _, keywords in definitions.values())
    # Without an update callback none is passed (Blender refuses update=None).
    assert all("update" not in keywords for _, keywords in parameters.property_definitions(
        table, "liquid", FakeProps()).values())


class Settings:
    """A PropertyGroup's stand-in: one attribute per row of `group`, at its default."""

    def __init__(self, table, group):
        for row in table:
            if row["group"] == group:
                setattr(self, row["name"], row["default"])


def test_changed_light_values_reach_the_documents_light_group():
    table = table_from_def()
    scene_settings = types.SimpleNamespace(light=Settings(table, "light"))
    obj = types.SimpleNamespace(spindrift=types.SimpleNamespace(liquid=Settings(table, "liquid"),
                                                                foam=Settings(table, "foam")))
    scene = types.SimpleNamespace(spindrift=scene_settings)
    native = types.SimpleNamespace(parameter_table=lambda: table)
    export = types.ModuleType("export")
    export.film_pixel_filter = lambda scene: scene.film
    frame = load_in_package("frame", native=native, export=export)

    scene.film = ("BLACKMAN_HARRIS", 1.5)  # Cycles' default, the table's
    values = frame.parameter_values(scene, obj)
    assert values == {"liquid": {}, "foam": {}, "light": {}}
    scene.film = ("BOX", 1.2)  # the film's filter reaches the liquid group (parameters.FROM_BLENDER)
    assert frame.parameter_values(scene, obj)["liquid"] == {"pixel_filter_width": pytest.approx(1.25)}
    scene.film = ("BLACKMAN_HARRIS", 1.5)
    document = scene_json.scene_document({}, 1, (), None, values["liquid"], values["foam"], (), values["light"])
    assert "light" not in document, "a light group at its defaults is left out"

    scene_settings.light.caustics = False
    scene_settings.light.direct_fraction = float(np.float32(0.3))
    scene_settings.light.sky_without_lamps = False
    scene_settings.light.shadow_map_size = 512  # the default, still left out
    # No object (nothing enabled yet): the scene's light values are written all the same.
    values = frame.parameter_values(scene, None, quality="DRAFT")
    assert values["light"] == {"caustics": False, "direct_fraction": pytest.approx(0.3), "sky_without_lamps": False}
    assert values["liquid"] == frame.QUALITY_OVERRIDES["DRAFT"]["liquid"]
    document = scene_json.scene_document({}, 1, (), None, values["liquid"], values["foam"], (), values["light"])
    written = json.loads(scene_json.dumps(document))["light"]
    assert written == {"caustics": False, "direct_fraction": pytest.approx(0.3), "sky_without_lamps": False}
    assert type(written["direct_fraction"]) is float


def test_the_exr_carries_light_layers_only_where_something_lights():
    defaults = parameters.group_defaults(table_from_def(), "light")
    assert defaults["sky_without_lamps"] is True and defaults["caustics"] is True
    sun = [{"type": "sun", "direction": [0, 0, -1], "strength": 3.0, "color": [1, 1, 1]}]
    grey = {"color": [0.05, 0.05, 0.05]}
    black = {"color": [0.0, 0.0, 0.0]}

    def lit(lights=(), background=grey, light=None, mode="OVER", occluders=True):
        document = scene_json.scene_document({}, 1, (), background, {}, {}, lights, light)
        return scene_json.lights_through_liquid(document, mode, occluders, defaults)

    assert lit(sun) and lit(sun, black, {"sky_without_lamps": False}) and lit(sun, occluders=False)
    assert not lit(sun, mode="FOAM_ONLY"), "Cycles lit the liquid of a Foam Only render"
    # Without lamps: the world's light alone, over the scene's solids and a world that is not black...
    assert lit() and lit(light={"caustics": False})
    assert not lit(background=black) and not lit(occluders=False)
    # ...unless light.sky_without_lamps is off: then nothing lights a scene without lamps.
    assert not lit(light={"sky_without_lamps": False})


def test_viewport_quality_presets_name_parameters_within_their_ranges():
    """frame.QUALITY_OVERRIDES is applied on top of an object's values: a misspelt or out-of-range key would
    fail only when an artist picks that preset."""
    tree = ast.parse((ADDON / "frame.py").read_text())
    presets = next(ast.literal_eval(node.value) for node in tree.body if isinstance(node, ast.Assign)
                   and any(getattr(target, "id", None) == "QUALITY_OVERRIDES" for target in node.targets))
    rows = {(row["group"], row["name"]): row for row in table_from_def()}
    assert set(presets) == {"DRAFT", "BALANCED", "FULL"}
    for preset, groups in presets.items():
        for group, values in groups.items():
            for name, value in values.items():
                row = rows.get((group, name))
                assert row is not None, f"{preset}: {group}.{name} is not a parameter"
                assert row["min"] <= value <= row["max"], f"{preset}: {group}.{name} = {value}"


def test_known_rows_keep_their_defaults():
    table = table_from_def()
    definitions = parameters.property_definitions(table, "liquid", FakeProps())
    assert definitions["ior"][1]["default"] == pytest.approx(1.33)
    assert definitions["max_refractions"][1]["default"] == 4
    assert definitions["absorption_rgb"][1]["default"] == pytest.approx((0.9, 0.3, 0.15))
    assert definitions["smoothing"][1]["default"] == "plane_fit"


def test_bad_rows_are_rejected_by_name():
    row = {"group": "liquid", "name": "odd", "type": "matrix", "default": 0, "min": 0, "max": 1, "choices": [],
           "doc": ""}
    with pytest.raises(ValueError, match="liquid.odd: unknown type 'matrix'"):
        parameters.property_definition(row, FakeProps())
    row.update(type="choice", default="c", choices=["a", "b"])
    with pytest.raises(ValueError, match="default 'c' is not one of"):
        parameters.property_definition(row, FakeProps())
    with pytest.raises(ValueError, match="no rows in group 'water'"):
        parameters.property_definitions(table_from_def(), "water", FakeProps())


def test_scene_file_values_are_only_the_changed_ones():
    table = table_from_def()
    settings = Settings(table, "liquid")
    # Blender stores floats in single precision: a default read back as float32 is still the default.
    settings.ior = float(np.float32(1.33))
    assert parameters.group_values(table, "liquid", settings) == {}
    settings.ior = 1.5
    settings.absorption_rgb = (0.1, 0.2, 0.3)
    settings.smoothing = "bilateral"
    values = parameters.group_values(table, "liquid", settings)
    assert values == {"ior": 1.5, "absorption_rgb": [0.1, 0.2, 0.3], "smoothing": "bilateral"}
    assert all(type(v) in (float, list, str) for v in values.values())


# --- Mantaflow's grid ------------------------------------------------------------------------------------------

def test_unscaled_cube_maps_cache_origin_to_its_minimum_corner():
    # docs/mantaflow-caches.md: a cube of size 2 centred at (0, 0, 1) stores positions 0.05..1.95.
    matrix = np.identity(4)
    matrix[:3, 3] = (0, 0, 1)
    world_from_file, dx, resolution = scene_json.mantaflow_grid((-1, -1, -1), (1, 1, 1), (1, 1, 1), matrix, 32)
    assert dx == pytest.approx(2 / 32)
    assert resolution == [32, 32, 32]
    assert world_from_file @ np.array([0.05, 0.05, 0.05, 1]) == pytest.approx([-0.95, -0.95, 0.05, 1])


def test_scaled_domains_give_blenders_resolution():
    # The two domains of tests/fixtures/bake_blender_reference.py; Blender reported these resolutions.
    for scale, expected in (((1.5, 1.1, 0.7), [24, 18, 11]), ((1.2, 1.45, 0.85), [20, 24, 14])):
        _, dx, resolution = scene_json.mantaflow_grid((-1, -1, -1), (1, 1, 1), scale, np.identity(4), 24)
        assert resolution == expected
        assert dx == pytest.approx(2 * max(scale) / 24)


def test_rotated_scaled_domain_keeps_the_grid_centred_on_the_bound_box():
    rotation = np.array([[0, -1, 0], [1, 0, 0], [0, 0, 1]], dtype=float)  # 90 degrees about z
    scale = np.array([1.5, 1.1, 0.7])
    matrix = np.identity(4)
    matrix[:3, :3] = rotation * scale
    matrix[:3, 3] = (3, -2, 1.5)
    world_from_file, dx, resolution = scene_json.mantaflow_grid((-1, -1, -1), (1, 1, 1), scale, matrix, 24)
    centre_in_file = np.array(resolution) * dx / 2  # the grid's centre, in scaled units
    centre = world_from_file @ np.array([*centre_in_file, 1])
    assert centre[:3] == pytest.approx([3, -2, 1.5], abs=1e-9)
    # One cell along file x is dx world units along the rotated x axis (the scale is undone, then redone).
    step = world_from_file @ np.array([*(centre_in_file + [dx, 0, 0]), 1]) - centre
    assert np.linalg.norm(step[:3]) == pytest.approx(dx)
    assert step[:3] / dx == pytest.approx(rotation[:, 0], abs=1e-9)


def test_degenerate_domains_are_reported():
    with pytest.raises(scene_json.BadInput, match="zero scale"):
        scene_json.mantaflow_grid((-1, -1, -1), (1, 1, 1), (1, 0, 1), np.identity(4), 32)
    with pytest.raises(scene_json.BadInput, match="no extent"):
        scene_json.mantaflow_grid((0, 0, 0), (0, 0, 0), (1, 1, 1), np.identity(4), 32)


def test_cache_paths_and_frame_numbers():
    paths = scene_json.mantaflow_cache_paths("/tmp/cache/")
    assert paths["liquid"] == "/tmp/cache/data/fluid_data_####.vdb"
    assert scene_json.frame_path(paths["secondary"], 7) == "/tmp/cache/particles/fluid_particles_0007.vdb"
    assert scene_json.frame_path("a_##.exr", 123) == "a_123.exr"


class DomainSettings:
    """The FluidDomainSettings attributes the scene file takes, at Blender 3.4's defaults but one."""
    particle_radius, mesh_particle_radius, mesh_scale = 1.0, 2.0, 1
    mesh_smoothen_pos, mesh_smoothen_neg, mesh_concave_upper, mesh_concave_lower = 1, 1, 3.5, 0.4
    particle_number, mesh_generator = 2, "IMPROVED"


def test_domain_settings_go_with_the_liquid_source_and_a_radius_only_when_given():
    domain = scene_json.domain_description(DomainSettings())
    assert domain == {"particle_radius": 1.0, "mesh_particle_radius": 2.0, "mesh_scale": 1, "mesh_smoothen_pos": 1,
                      "mesh_smoothen_neg": 1, "mesh_concave_upper": 3.5, "mesh_concave_lower": 0.4,
                      "particle_number": 2, "mesh_generator": "IMPROVED"}
    identity = [[1.0 if i == j else 0.0 for j in range(4)] for i in range(4)]
    derived, foam = scene_json.mantaflow_sources("/c", identity, None, 0.3, domain=domain)
    assert "radius" not in derived and derived["domain"] == domain and foam["radius"] == 0.3
    assert "domain" not in foam
    given, _ = scene_json.mantaflow_sources("/c", identity, 0.05, 0.3, domain=domain)
    assert given["radius"] == 0.05 and given["domain"] == domain


# --- Cameras and depth -----------------------------------------------------------------------------------------

def perspective(fov_y, aspect, near, far, shift=(0.0, 0.0)):
    """OpenGL's perspective matrix, as Blender's window_matrix (with a lens shift in NDC)."""
    f = 1 / math.tan(fov_y / 2)
    return np.array([[f / aspect, 0, shift[0], 0], [0, f, shift[1], 0],
                     [0, 0, (far + near) / (near - far), 2 * far * near / (near - far)], [0, 0, -1, 0]])


def test_centred_projection_gives_the_same_camera():
    projection = perspective(math.radians(40), 1280 / 800, 0.1, 100)
    camera, window = scene_json.camera_description(1280, 800, np.identity(4), projection)
    assert (camera["width"], camera["height"]) == (1280, 800)
    assert camera["fov_y_deg"] == pytest.approx(40)
    assert camera["near"] == pytest.approx(0.1) and camera["far"] == pytest.approx(100)
    assert window == pytest.approx((0, 0))


def test_offcentre_projection_is_covered_by_a_larger_symmetric_one():
    width, height, fov = 400, 200, math.radians(30)
    projection = perspective(fov, width / height, 0.1, 100, shift=(0.5, -0.25))
    camera, (left, bottom) = scene_json.camera_description(width, height, np.identity(4), projection)
    assert (camera["width"], camera["height"]) == (600, 250)
    # Project a point with the wanted (off-centre) matrix and with the larger camera: same pixel.
    point = np.array([0.3, -0.1, -2.0, 1.0])
    clip = projection @ point
    wanted = ((clip[0] / clip[3] + 1) / 2 * width, (clip[1] / clip[3] + 1) / 2 * height)
    tan_y = math.tan(math.radians(camera["fov_y_deg"]) / 2)
    tan_x = tan_y * camera["width"] / camera["height"]
    full = ((point[0] / -point[2] / tan_x + 1) / 2 * camera["width"],
            (point[1] / -point[2] / tan_y + 1) / 2 * camera["height"])
    assert (full[0] - left, full[1] - bottom) == pytest.approx(wanted, abs=1e-6)


def test_orthographic_and_empty_views_are_bad_input():
    ortho = np.identity(4)
    with pytest.raises(scene_json.BadInput, match="orthographic"):
        scene_json.camera_description(100, 100, np.identity(4), ortho)
    with pytest.raises(scene_json.BadInput, match="0x100 pixels"):
        scene_json.camera_description(0, 100, np.identity(4), perspective(1, 1, 0.1, 10))
