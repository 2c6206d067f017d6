"""Blender properties generated from Spindrift's one parameter table (`_spindrift.parameter_table()`).

Pure Python: `property_definitions` takes the table and a module with Blender's property constructors
(`bpy.props` in Blender, a fake in the plain-Python tests), so the mapping is testable without Blender.
"""

# Where the add-on keeps each group of the table: liquid and foam on the object whose parameters a frame uses
# (export.primary_object), light on the scene, because lamps and the world light the whole scene whichever
# object holds the liquid. Properties, panels and the scene file all go by this one mapping.
GROUP_OWNERS = {"liquid": "object", "foam": "object", "light": "scene"}

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
    """{name: property} for every row of `group` (one of GROUP_OWNERS), in table order."""
    definitions = {}
    for row in table:
        if row["group"] == group:
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
        if row["group"] != group:
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
