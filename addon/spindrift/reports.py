"""Where the add-on's messages go: the console (always under -b), the status shown in the panels, and
Blender's report area for operators. Nothing here raises: reporting must never stop a render."""

import sys
import time

import bpy

PREFIX = "Spindrift"

# The panels show these; they live in Python (not in scene properties) so that writing them from a render
# handler or a timer never triggers a depsgraph update.
last_render = {"frame": None, "message": "", "issues": [], "ms": None, "time": 0.0}


def console(message):
    print(f"{PREFIX}: {message}", file=sys.stdout, flush=True)


def warn(message):
    print(f"{PREFIX}: warning: {message}", file=sys.stderr, flush=True)


def error(message):
    print(f"{PREFIX}: error: {message}", file=sys.stderr, flush=True)


def record_render(frame, message, issues, ms=None):
    last_render.update(frame=frame, message=message, issues=list(issues), ms=ms, time=time.time())


def log_frames_enabled():
    try:
        return bpy.context.preferences.addons[__package__].preferences.log_frames
    except (KeyError, AttributeError):
        return True
