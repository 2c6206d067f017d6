"""Spindrift's layers for every rendered frame (F12, Ctrl+F12, -f, -a; interface and background).

Blender calls render_pre before a frame's scene is evaluated and frame_change_post right after, with the
render's own depsgraph, before the engine runs and before compositing (checked in 3.4.1). The layers are
rendered there: the render depsgraph has every object (particle systems, the domain's liquid mesh) at the
frame, and the multilayer EXR is on disk, and the compositor's Image node reloaded, before the compositor
reads it. See docs/blender.md.
"""

import os
import time

import bpy
from bpy.app.handlers import persistent

from . import compositing, export, frame as frame_inputs, native, parameters, reports, scene_json
from .scene_json import BadInput

# The frame's EXR is temporary (the compositor reads it once), so it is written for speed: only the layers the
# compositing group reads are rendered at all, colour layers as half float (depth and refraction_uv stay
# float32: half moves a UV by up to ~1 px at 1920 px), compressed by zlib at its fastest level (docs/blender.md).
EXR_OPTIONS = {"exr_half_color": True, "exr_compression": "zips:1"}

_state = {"pending": None, "frames_done": 0, "frames_total": 0, "progress": False, "started": 0.0}


def layer_path(scene, frame):
    """The frame's EXR, beside the render output: <output directory>/spindrift_<frame>.exr."""
    output = bpy.path.abspath(scene.render.frame_path(frame=frame))
    directory = os.path.dirname(output) or "."
    return os.path.join(directory, f"spindrift_{frame:04d}.exr")


def render_frame(scene, depsgraph, frame, exr_path):
    """Renders the scene's Spindrift layers for `frame` into `exr_path`; returns (result, Frame, timing).
    Raises BadInput (the scene) or the module's Error (rendering)."""
    camera, crop = export.render_camera(scene, depsgraph)
    settings = scene.spindrift
    mode = settings.composite_mode if settings.composite_mode in frame_inputs.MODES else "OVER"
    renderer = native.renderer()  # made once (EGL context, shaders): not part of any frame's time
    started = time.perf_counter()
    inputs = frame_inputs.collect(scene, depsgraph, frame, camera, mode=mode, occluders=settings.occluders)
    collected = time.perf_counter() - started
    os.makedirs(os.path.dirname(exr_path), exist_ok=True)
    lit = lights_through_liquid(inputs, mode)
    exr_layers = None if settings.all_layers else compositing.frame_layers(mode, lit)
    result = renderer.render(inputs.scene_text, frame, exr_path=exr_path, layers=[], exr_layers=exr_layers,
                             crop=crop, **EXR_OPTIONS, **inputs.kwargs)
    total = time.perf_counter() - started
    return result, inputs, timing(result.get("stats", {}), collected, total)


def lights_through_liquid(inputs, mode):
    """Whether the frame's EXR carries the light layers the OVER group multiplies the render by: with lamps,
    and without them where the world's light alone is taken (light.sky_without_lamps, from the scene's
    Light settings) over the scene's solids and a world that is not black (scene_json.lights_through_liquid)."""
    light_defaults = parameters.group_defaults(native.parameter_table(), "light")
    return scene_json.lights_through_liquid(inputs.document, mode, "occluders" in inputs.kwargs, light_defaults)


def timing(stats, collect_s, total_s):
    """Where a final frame's time went. Spindrift's own frame is the native total without the occluder
    prepass; the add-on's overhead is everything else: reading Blender's data into arrays, handing them over,
    the prepass of the scene's triangles, writing the EXR (exr_write_ms, part of the call's time beyond the
    native total)."""
    native_ms = float(stats.get("total_ms", 0.0))
    prepass_ms = sum(max(float(p.get("gpu_ms", 0.0)), float(p.get("cpu_ms", 0.0)))
                     for p in stats.get("passes", []) if p.get("name") in ("occluder_depth", "liquid_mesh_depth"))
    call_ms = (total_s - collect_s) * 1000
    return {"collect_ms": collect_s * 1000, "call_ms": call_ms, "native_total_ms": native_ms,
            "exr_write_ms": float(stats.get("exr_write_ms", 0.0)),
            "prepass_ms": prepass_ms, "spindrift_ms": native_ms - prepass_ms,
            "overhead_ms": collect_s * 1000 + prepass_ms + max(call_ms - native_ms, 0.0), "total_s": total_s}


def _fail(scene, frame, message):
    reports.error(f"frame {frame}: {message}")
    reports.record_render(frame, f"frame {frame}: {message}", [])
    compositing.bypass(scene, True)
    if scene.spindrift.on_error == "STOP" and bpy.app.background:
        reports.error("stopping (On Error is Stop)")
        os._exit(1)


def render_layers_now(scene, depsgraph, frame):
    """Renders and publishes the frame's layers; on failure reports and bypasses the compositor nodes."""
    path = layer_path(scene, frame)
    try:
        result, inputs, times = render_frame(scene, depsgraph, frame, path)
    except BadInput as error:
        _fail(scene, frame, str(error))
        return False
    except ImportError as error:
        _fail(scene, frame, str(error))
        return False
    except Exception as error:  # noqa: BLE001 - the module's Error or a ValueError: report, never crash
        _fail(scene, frame, f"{type(error).__name__}: {error}")
        return False
    for issue in inputs.issues:
        reports.warn(f"frame {frame}: {issue}")
    reload_started = time.perf_counter()
    compositing.show_layers(scene, path)
    compositing.bypass(scene, False)
    times["reload_ms"] = (time.perf_counter() - reload_started) * 1000
    times["overhead_ms"] += times["reload_ms"]
    message = f"frame {frame}: {times['total_s'] * 1000:.0f} ms, {os.path.basename(path)}"
    _state["frames_done"] += 1
    if reports.log_frames_enabled():
        reports.console(f"frame {frame}: layers written to {path} in "
                        f"{times['total_s'] * 1000:.0f} ms (Spindrift {times['spindrift_ms']:.0f} ms, add-on "
                        f"overhead {times['overhead_ms']:.0f} ms; {_state['frames_done']} this render)")
    reports.record_render(frame, message, inputs.issues, times["total_s"] * 1000)
    reports.last_render["timing"] = times
    reports.last_render["stats"] = result.get("stats", {})
    _progress_update()
    return True


def _wants_layers(scene):
    return scene.spindrift.render_layer and any(obj.spindrift.enabled for obj in scene.objects)


@persistent
def on_render_init(scene, _depsgraph=None):
    if not _wants_layers(scene):
        return
    _state.update(frames_done=0, started=time.perf_counter(),
                  frames_total=scene.frame_end - scene.frame_start + 1)
    if not bpy.app.background:
        try:
            bpy.context.window_manager.progress_begin(0, max(_state["frames_total"], 1))
            _state["progress"] = True
        except (AttributeError, RuntimeError):
            _state["progress"] = False


def _progress_update():
    if _state["progress"]:
        try:
            bpy.context.window_manager.progress_update(_state["frames_done"])
        except (AttributeError, RuntimeError):
            pass


@persistent
def on_render_pre(scene, _depsgraph=None):
    # The scene is evaluated for the frame only after this; the work happens in frame_change_post.
    _state["pending"] = scene.name if _wants_layers(scene) else None


@persistent
def on_frame_change_post(scene, depsgraph=None):
    if _state["pending"] != scene.name:
        return
    _state["pending"] = None
    if depsgraph is None:
        depsgraph = bpy.context.evaluated_depsgraph_get()
    render_layers_now(scene, depsgraph, scene.frame_current)


@persistent
def on_render_done(scene, _depsgraph=None):
    _state["pending"] = None
    if _state["progress"]:
        try:
            bpy.context.window_manager.progress_end()
        except (AttributeError, RuntimeError):
            pass
        _state["progress"] = False


HANDLERS = [
    ("render_init", on_render_init),
    ("render_pre", on_render_pre),
    ("frame_change_post", on_frame_change_post),
    ("render_complete", on_render_done),
    ("render_cancel", on_render_done),
]


def register():
    for name, handler in HANDLERS:
        getattr(bpy.app.handlers, name).append(handler)


def unregister():
    for name, handler in HANDLERS:
        handlers = getattr(bpy.app.handlers, name)
        while handler in handlers:
            handlers.remove(handler)
    # Frames rendered after the add-on is gone go on without the layer instead of showing a stale one.
    for scene in bpy.data.scenes:
        compositing.bypass(scene, True)
