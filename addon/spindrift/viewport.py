"""The live preview in the 3D viewport.

Main thread (the draw callback, POST_PIXEL): when the view, the frame or the scene changed and no frame for
that region is waiting or rendering, collect the frame's inputs and queue them; then draw the latest finished
image (premultiplied, with the gpu module). The scene's solids hide the liquid through the native occluder
depth prepass, which draws their triangles on the renderer's own thread: the viewport's depth buffer is never
read, because reading it waits for llvmpipe to finish drawing the viewport (150-300 ms per handed frame,
measured in docs/blender.md). The triangles are extracted once per depsgraph change and frame, not per view.

Rendering: `Renderer.submit` renders the frame on a native thread and composes the display image (foam over
liquid, premultiplied display sRGB) there too; a timer on the main thread collects it with `Renderer.poll` and
redraws the viewports. No Python runs off the main thread: an earlier Python worker thread crashed Blender
about one run in ten (its main thread made Python strings without holding the GIL while the worker held it;
docs/blender.md).

What the preview refracts: the world colour, not the scene's colour: reading the scene's colour needs
`GPUOffScreen.draw_view3d`, which costs ~0.7 s of main-thread time per redraw on llvmpipe (docs/blender.md).
"""

import time

import bpy
import gpu
import numpy as np
from gpu_extras.presets import draw_texture_2d

from . import export, frame as frame_inputs, native, reports, scene_json
from .scene_json import BadInput

TIMER_INTERVAL = 0.05


class Job:
    def __init__(self, key, inputs, size, offset, scale):
        self.key, self.inputs, self.size, self.offset, self.scale = key, inputs, size, offset, scale


class Image:
    """A finished preview: premultiplied display-space RGBA rows bottom first, and where to draw it."""

    def __init__(self, job, pixels, width, height, seconds, stats):
        self.key, self.offset, self.scale = job.key, job.offset, job.scale
        self.pixels, self.width, self.height = pixels, width, height
        self.seconds, self.stats = seconds, stats
        self.texture = None


class Previews:
    """The regions' preview frames, rendered one at a time by the shared Renderer on its native thread.

    One queued job per viewport region (a newer one replaces one not yet started). Everything here runs on the
    main thread: the draw callback queues, the timer collects (`collect`), and each collection starts the
    next queued frame. A region's latest result is an Image, or the error's text."""

    def __init__(self):
        self._queued = {}
        self._rendering = None  # (region_key, job, start time) of the frame on the native thread.
        self._finished = {}
        self._buffers = {}  # (region_key, width, height) -> two display arrays, used in turn (_display_buffer).

    def submit(self, region_key, job):
        self._queued[region_key] = job
        self._start_next()

    def idle(self, region_key):
        return region_key not in self._queued and (self._rendering is None or self._rendering[0] != region_key)

    def latest(self, region_key):
        return self._finished.get(region_key)

    def fail(self, region_key, message):
        self._finished[region_key] = message

    def collect(self):
        """Takes the frame that finished, if one did, and starts the next; True when a region has news."""
        if self._rendering is None:
            return self._start_next()
        region_key, job, started = self._rendering
        try:
            renderer = native.renderer()
            if renderer.busy:
                return False
            result = renderer.poll()
            if result is None:  # Nothing in flight: the renderer was closed and made again. Render it anew.
                self._queued.setdefault(region_key, job)
                self._rendering = None
                return self._start_next()
            pixels = result["display"]
            self._finished[region_key] = Image(job, pixels, result["width"], result["height"],
                                               time.perf_counter() - started, result.get("stats", {}))
        except Exception as error:  # noqa: BLE001 - shown in the panel; the viewport keeps working
            self._finished[region_key] = str(error) or type(error).__name__
        self._rendering = None
        self._start_next()
        return True

    def _display_buffer(self, region_key, size):
        """The array the region's next frame is written into, by the rendering thread: a fresh 4 MB array per
        frame cost the main thread 15-30 ms of page faults when the module made it (docs/blender.md). Two per
        region alternate, so the region's image still waiting to be uploaded is never written over."""
        key = (region_key, *size)
        pair = self._buffers.get(key)
        if pair is None:
            pair = self._buffers[key] = [np.zeros(size[0] * size[1] * 4, np.float32) for _ in range(2)]
        pair.reverse()
        return pair[0]

    def stop(self):
        """Waits for the frame on the native thread (the shared Renderer takes one at a time) and drops it."""
        self._queued.clear()
        if self._rendering is None:
            return
        self._rendering = None
        try:
            renderer = native.renderer()
            while renderer.busy:
                time.sleep(0.005)
            renderer.poll()
        except Exception:  # noqa: BLE001 - the frame is dropped either way
            pass

    def _start_next(self):
        """Submits a queued frame when none is rendering; True when that failed at once (the region has news)."""
        if self._rendering is not None or not self._queued:
            return False
        region_key, job = self._queued.popitem()
        try:
            inputs = job.inputs
            native.renderer().submit(inputs.scene_text, inputs.document["frame"], layers=[], display=True,
                                     display_into=self._display_buffer(region_key, job.size), **inputs.kwargs)
        except Exception as error:  # noqa: BLE001 - shown in the panel; the viewport keeps working
            self._finished[region_key] = str(error) or type(error).__name__
            return True
        self._rendering = (region_key, job, time.perf_counter())
        return False


# --- State shared by the callbacks -----------------------------------------------------------------------------

_state = {"previews": None, "draw_handler": None, "timer": False, "version": 0, "submitted": {}, "status": {},
          "redraw_ms": [], "occluders": {}, "status_redraws": 0}


def settings_changed():
    _state["version"] += 1
    scene = bpy.context.scene
    if _state["previews"] is not None and scene is not None and scene.spindrift.preview:
        hide_own_drawing(scene)
    _tag_redraw()


def status(region_key=None):
    """(message, frame ms) for the panel: the last region's status when no key is given."""
    statuses = _state["status"]
    if region_key is None:
        return next(reversed(statuses.values()), ("", None)) if statuses else ("", None)
    return statuses.get(region_key, ("", None))


def _set_status(region_key, value):
    """Sets a region's status; a new one redraws the panels that show it. They are drawn apart from the viewport
    (the Render properties, the viewport's sidebar, drawn before its main region), so a status set while the
    viewport draws showed only at their next redraw: the trial by hand of 2026-12-02 saw no frame time until
    the mouse went over the panel."""
    statuses = _state["status"]
    if statuses.get(region_key) == value:
        return
    statuses[region_key] = value
    if not bpy.app.timers.is_registered(_redraw_status_panels):
        bpy.app.timers.register(_redraw_status_panels, first_interval=0.0)


def _redraw_status_panels():
    _state["status_redraws"] += 1
    window_manager = bpy.context.window_manager if bpy.context else None
    for window in window_manager.windows if window_manager else ():
        for area in window.screen.areas:
            if area.type in ("PROPERTIES", "VIEW_3D"):
                area.tag_redraw()
    return None


def redraw_times_ms():
    """The draw callback's recent main-thread times: dicts of total_ms, and occluders_ms, job_ms (a new
    frame queued), collect_ms (a finished frame taken and the next one started), texture (a new image
    uploaded), upload_ms, draw_ms where they happened."""
    return list(_state["redraw_ms"])


def _tag_redraw():
    window_manager = bpy.context.window_manager if bpy.context else None
    if window_manager is None:
        return
    for window in window_manager.windows:
        for area in window.screen.areas:
            if area.type == "VIEW_3D":
                area.tag_redraw()


def _poll():
    previews = _state["previews"]
    if previews is None:
        _state["timer"] = False
        return None
    if previews.collect():
        _tag_redraw()
    return TIMER_INTERVAL


# --- Building a job on the main thread -------------------------------------------------------------------------

def preview_size(region_width, region_height, scale):
    width, height = int(region_width * scale), int(region_height * scale)
    if width < 1 or height < 1:
        raise BadInput(f"the viewport is {region_width}x{region_height} pixels: too small to preview at scale "
                       f"{scale:g}")
    return width, height


def cached_occluders(scene, depsgraph):
    """The scene's solid triangles, extracted again only when the depsgraph changed or the frame moved: a view
    change (orbit, zoom) reuses them, so handing a frame costs the main thread no extraction."""
    key = (_state["version"], scene.name, scene.frame_current)
    cache = _state["occluders"]
    if cache.get("key") != key:
        cache.update(key=key, triangles=frame_inputs.scene_occluders(scene, depsgraph, for_render=False))
    return cache["triangles"]


def shading_hides_liquid(shading):
    """Whether the view draws the scene's solids opaque: in wireframe shading, and with X-ray in solid shading,
    the viewport shows what lies behind them, so the preview hands no occluders."""
    if shading is None:
        return True
    if shading.type == "WIREFRAME":
        return False
    return not (shading.type == "SOLID" and shading.show_xray)


def build_job(context, region, region_data, key, phases):
    scene = context.scene
    settings = scene.spindrift
    width, height = preview_size(region.width, region.height, settings.preview_scale)
    projection = [list(row) for row in region_data.window_matrix]
    camera, (left, bottom) = scene_json.camera_description(
        width, height, region_data.view_matrix.inverted(), projection)
    started = time.perf_counter()
    depsgraph = context.evaluated_depsgraph_get()
    inputs = frame_inputs.collect(scene, depsgraph, scene.frame_current, camera, occluders=False,
                                  quality=settings.preview_quality, for_render=False, mode="OVER")
    occluders_started = time.perf_counter()
    if settings.occluders and shading_hides_liquid(getattr(context.space_data, "shading", None)):
        triangles = cached_occluders(scene, depsgraph)
        if triangles is not None:
            inputs.kwargs["occluders"] = triangles
    phases["occluders_ms"] = (time.perf_counter() - occluders_started) * 1000
    job = Job(key, inputs, (width, height),
              (-round(left) * region.width / width, -round(bottom) * region.height / height), region.width / width)
    phases["job_ms"] = (time.perf_counter() - started) * 1000
    return job


def _view_key(context, region, region_data):
    return (tuple(tuple(round(v, 6) for v in row) for row in region_data.view_matrix),
            tuple(tuple(round(v, 6) for v in row) for row in region_data.window_matrix),
            region.width, region.height, context.scene.frame_current, _state["version"],
            shading_hides_liquid(getattr(context.space_data, "shading", None)))


def draw():
    started = time.perf_counter()
    context = bpy.context
    region, region_data = context.region, context.region_data
    previews = _state["previews"]
    if previews is None or region is None or region_data is None or not context.scene.spindrift.preview:
        return
    region_key = region.as_pointer()
    phases = {}
    collected = time.perf_counter()
    if previews.collect():  # A frame that finished since the timer last looked is drawn now, not 50 ms later.
        phases["collect_ms"] = (time.perf_counter() - collected) * 1000
    try:
        key = _view_key(context, region, region_data)
        if _state["submitted"].get(region_key) != key and previews.idle(region_key):
            _state["submitted"][region_key] = key
            job = build_job(context, region, region_data, key, phases)
            for issue in job.inputs.issues:
                reports.warn(f"viewport: {issue}")
            previews.submit(region_key, job)
    except BadInput as error:
        _set_status(region_key, (str(error), None))
    except Exception as error:  # noqa: BLE001 - a draw callback must never raise into Blender's drawing
        _set_status(region_key, (f"{type(error).__name__}: {error}", None))

    image = previews.latest(region_key)
    if isinstance(image, str):
        _set_status(region_key, (image, None))
    elif image is not None:
        drawn = time.perf_counter()
        try:
            _draw_image(image, phases)
        except Exception as error:  # noqa: BLE001 - never raise into Blender's drawing
            previews.fail(region_key, f"{type(error).__name__}: {error}")
            return
        phases["draw_ms"] = (time.perf_counter() - drawn) * 1000
        _set_status(region_key, (f"{image.width}x{image.height}", image.seconds * 1000))
    phases["total_ms"] = (time.perf_counter() - started) * 1000
    _state["redraw_ms"] = (_state["redraw_ms"] + [phases])[-200:]


def _draw_image(image, phases):
    if image.texture is None:
        phases["texture"] = True
        # gpu.types.GPUTexture takes FLOAT buffers only (Blender 3.4); the overlay it is drawn into is 8-bit.
        # RGBA8 uploads faster than RGBA32F here: 13-49 ms against 105-133 ms for a 640x400 frame on llvmpipe.
        started = time.perf_counter()
        buffer = gpu.types.Buffer("FLOAT", image.pixels.size, image.pixels.ravel())
        image.texture = gpu.types.GPUTexture((image.width, image.height), format="RGBA8", data=buffer)
        phases["upload_ms"] = (time.perf_counter() - started) * 1000
    gpu.state.blend_set("ALPHA_PREMULT")
    gpu.state.depth_test_set("NONE")
    draw_texture_2d(image.texture, image.offset, image.width * image.scale, image.height * image.scale)
    gpu.state.blend_set("NONE")


# --- Switching on and off --------------------------------------------------------------------------------------

# Blender's own stand-ins for the liquid (a domain's mesh drawn solid, its particles as points) would show
# beside Spindrift's liquid and hide the scene behind it. While the preview is on, enabled objects draw as
# wire and their particles not at all; the originals come back after.
SAVED_DISPLAY = export.SAVED_DISPLAY


def hide_own_drawing(scene):
    for obj in export.enabled_objects(scene):
        if SAVED_DISPLAY in obj:
            continue
        saved = {"display_type": obj.display_type,
                 "particles": {system.settings.name: system.settings.display_method
                               for system in obj.particle_systems}}
        obj[SAVED_DISPLAY] = repr(saved)
        if obj.display_type in ("SOLID", "TEXTURED"):
            obj.display_type = "WIRE"
        for system in obj.particle_systems:
            system.settings.display_method = "NONE"


def restore_own_drawing():
    import ast

    for obj in bpy.data.objects:
        if SAVED_DISPLAY not in obj:
            continue
        saved = ast.literal_eval(obj[SAVED_DISPLAY])
        del obj[SAVED_DISPLAY]
        obj.display_type = saved["display_type"]
        for system in obj.particle_systems:
            method = saved["particles"].get(system.settings.name)
            if method is not None:
                system.settings.display_method = method


def enable(on):
    if on:
        for scene in bpy.data.scenes:
            if scene.spindrift.preview:
                hide_own_drawing(scene)
        if _state["previews"] is None:
            _state["previews"] = Previews()
        if _state["draw_handler"] is None:
            _state["draw_handler"] = bpy.types.SpaceView3D.draw_handler_add(draw, (), "WINDOW", "POST_PIXEL")
        if not _state["timer"]:
            bpy.app.timers.register(_poll, first_interval=TIMER_INTERVAL, persistent=True)
            _state["timer"] = True
    elif not any(scene.spindrift.preview for scene in bpy.data.scenes):
        shutdown()
    _tag_redraw()


def shutdown():
    restore_own_drawing()
    if _state["draw_handler"] is not None:
        bpy.types.SpaceView3D.draw_handler_remove(_state["draw_handler"], "WINDOW")
        _state["draw_handler"] = None
    if _state["previews"] is not None:
        _state["previews"].stop()
        _state["previews"] = None
    if _state["timer"] and bpy.app.timers.is_registered(_poll):
        bpy.app.timers.unregister(_poll)
    if bpy.app.timers.is_registered(_redraw_status_panels):
        bpy.app.timers.unregister(_redraw_status_panels)
    _state["timer"] = False
    _state["submitted"].clear()
    _state["occluders"].clear()


def on_depsgraph_update(_scene, _depsgraph=None):
    _state["version"] += 1


def register():
    bpy.app.handlers.depsgraph_update_post.append(on_depsgraph_update)


def unregister():
    if on_depsgraph_update in bpy.app.handlers.depsgraph_update_post:
        bpy.app.handlers.depsgraph_update_post.remove(on_depsgraph_update)
    shutdown()
