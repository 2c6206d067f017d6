"""Blender properties generated from Spindrift's one parameter table (`_spindrift.parameter_table()`).

Pure Python: `property_definitions` takes the table and a module with Blender's property constructors
(`bpy.props` in Blender, a fake in the plain-Python tests), so the mapping is testable without Blender.
"""

# Where the add-on keeps each group of the table: liquid and foam on the object whose parameters a frame uses
# (export.primary_object), light on the scene, because lamps and the world light the whole scene whichever
# object holds the liquid. Properties, panels and the scene file all go by this one mapping.
GROUP_OWNERS = {"liquid": "object", "foam": "object", "light": "scene"}

# Rows the add-on takes from Blender's own settings rather than from a property of its own: no property or
# panel entry is made for them, and frame.parameter_values fills them from the scene. A second knob beside
# Blender's would only disagree with it.
FROM_BLENDER = {("liquid", "pixel_filter_width"): "Render properties > Film > Pixel Filter"}

# The width of the Blackman-Harris filter (Cycles' default pixel filter) with the spread of Cycles' other
# filters of width 1: a box's standard deviation is 1 / sqrt(12) of its width and a Blackman-Harris one's
# 0.277 (Cycles spans it over twice its width); Cycles spans a Gaussian over three times its width with
# sigma a quarter of it (intern/cycles/scene/film.cpp).
_BLACKMAN_HARRIS_WIDTH_PER_WIDTH = {"BLACKMAN_HARRIS": 1.0, "BOX": 1.0 / 0.96, "GAUSSIAN": 0.866 / 0.96}


def pixel_filter_width(filter_type, width):
    """liquid.pixel_filter_width (a Blackman-Harris width in pixels) for a render whose pixel filter is
    `filter_type` (Cycles' BOX, GAUSSIAN or BLACKMAN_HARRIS) of `width` pixels: the filter of the same spread."""
    if filter_type not in _BLACKMAN_HARRIS_WIDTH_PER_WIDTH:
        raise ValueError(f"unknown pixel filter {filter_type!r}")
    return float(width) * _BLACKMAN_HARRIS_WIDTH_PER_WIDTH[filter_type]


# Blender's FloatProperty keeps soft limits for the slider; the table's range is the hard limit the native
# validator enforces too, so a value Blender accepts is always one the renderer accepts.
_SOFT_SPAN = 1e4


def _description(row):
    # Blender shows the description as the tooltip; it must be a single string without a trailing period issue.
    return row["doc"]


def _label(name):
    return name.replace("_", " ").capitalize()


def property_definition(row, props, update=None):
    """One table row as a Blender property (the object `props.XxxProperty(...)` returns); `update` is the
    callback Blender calls when the value changes (none by default)."""
    kind = row["type"]
    common = {"name": _label(row["name"]), "description": _description(row)}
    if update is not None:
        common["update"] = update
    if kind == "float":
        low, high = float(row["min"]), float(row["max"])
        return props.FloatProperty(default=float(row["default"]), min=low, max=high,
                                   soft_min=max(low, -_SOFT_SPAN), soft_max=min(high, _SOFT_SPAN),
                                   precision=4, **common)
    if kind == "int":
        low, high = int(row["min"]), int(row["max"])
        return props.IntProperty(default=int(row["default"]), min=low, max=high, **common)
    if kind == "bool":
        return props.BoolProperty(default=bool(row["default"]), **common)
    if kind == "color":
        low, high = float(row["min"]), float(row["max"])
        return props.FloatVectorProperty(default=tuple(float(v) for v in row["default"]), size=3,
                                         subtype="COLOR", min=low, max=high,
                                         soft_min=max(low, 0.0), soft_max=min(high, 1.0), **common)
    if kind == "vec3":
        return props.FloatVectorProperty(default=tuple(float(v) for v in row["default"]), size=3,
                                         subtype="XYZ", **common)
    if kind == "choice":
        items = [(choice, _label(choice), "") for choice in row["choices"]]
        if row["default"] not in row["choices"]:
            raise ValueError(f"parameter {row['group']}.{row['name']}: default {row['default']!r} "
                             f"is not one of {row['choices']}")
        return props.EnumProperty(items=items, default=row["default"], **common)
    raise ValueError(f"parameter {row['group']}.{row['name']}: unknown type {kind!r}")


def property_definitions(table, group, props, update=None):
    """{name: property} for every row of `group` (one of GROUP_OWNERS) but those FROM_BLENDER, in table
    order."""
    definitions = {}
    for row in table:
        if row["group"] == group and (group, row["name"]) not in FROM_BLENDER:
            definitions[row["name"]] = property_definition(row, props, update)
    if not definitions:
        raise ValueError(f"the parameter table has no rows in group {group!r}")
    return definitions


def json_value(row, value):
    """A property's value as the scene file wants it (plain floats, ints, bools, lists, strings)."""
    kind = row["type"]
    if kind == "float":
        return float(value)
    if kind == "int":
        return int(value)
    if kind == "bool":
        return bool(value)
    if kind in ("color", "vec3"):
        return [float(v) for v in value]
    return str(value)


def group_values(table, group, settings):
    """{name: value} of `settings` (a PropertyGroup or any object with the attributes) for the scene file.

    Only values that differ from the table's default are written, so a scene file stays short and a change of
    a default in parameters.def reaches every .blend that never touched the parameter.
    """
    values = {}
    for row in table:
        if row["group"] != group or (group, row["name"]) in FROM_BLENDER:
            continue
        value = json_value(row, getattr(settings, row["name"]))
        default = json_value(row, row["default"])
        if not _same(value, default):
            values[row["name"]] = value
    return values


def group_defaults(table, group):
    """{name: default} of `group` as the scene file writes values: what a document's group object means for
    every parameter it leaves out (group_values writes only the changed ones)."""
    return {row["name"]: json_value(row, row["default"]) for row in table if row["group"] == group}


def _same(a, b):
    if isinstance(a, list):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b))
    if isinstance(a, float):
        # Blender stores floats in single precision; the table's defaults are single-precision values too.
        return abs(a - b) <= 1e-6 * max(1.0, abs(b))
    return a == b
