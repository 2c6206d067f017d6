"""Shared pieces of the Python module's tests: where the built module is, a scene, particle clouds and a CPU
camera projection (Blender's convention, as native/src/Camera.cpp) that the tests compare against."""

import json
import math
import os
import pathlib
import sys

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[2]
BUILD = pathlib.Path(os.environ.get("SPINDRIFT_BUILD_DIR", ROOT / "build"))
MODULE_DIR = BUILD / "lib"
CLI = BUILD / "bin" / "spindrift"


def import_module():
    if str(MODULE_DIR) not in sys.path:
        sys.path.insert(0, str(MODULE_DIR))
    import _spindrift

    return _spindrift


WIDTH, HEIGHT, FOV_Y = 96, 72, 40.0
CAMERA_POSITION = (0.0, -5.0, 0.0)


def scene_json(width=WIDTH, height=HEIGHT, particles=(), **extra):
    scene = {
        "version": 1,
        "camera": {"width": width, "height": height, "fov_y_deg": FOV_Y, "near": 0.1, "far": 100.0,
                   "position": list(CAMERA_POSITION), "target": [0.0, 0.0, 0.0], "up": [0.0, 0.0, 1.0]},
        "particles": list(particles),
        "background": {"color": [0.2, 0.3, 0.4]},
    }
    scene.update(extra)
    return json.dumps(scene)


def sphere_of_particles(count=400, radius=0.8, particle_radius=0.12, seed=3):
    """Liquid particles filling a ball at the origin (a body: aggregates, not splashes)."""
    random = np.random.default_rng(seed)
    points = random.uniform(-1.0, 1.0, size=(count * 3, 3))
    points = points[np.linalg.norm(points, axis=1) <= 1.0][:count] * radius
    return {
        "positions": np.ascontiguousarray(points, dtype=np.float32),
        "radii": np.full(len(points), particle_radius, dtype=np.float32),
        "kinds": np.zeros(len(points), dtype=np.uint8),
    }


def camera_from_world():
    """The look-at camera of scene_json: rows are the camera's x, y, z axes (looking down -z, +y up)."""
    position = np.array(CAMERA_POSITION)
    forward = -position / np.linalg.norm(position)
    right = np.cross(forward, [0.0, 0.0, 1.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    rotation = np.stack([right, up, -forward])
    return rotation, -rotation @ position


def project(points, width=WIDTH, height=HEIGHT):
    """Pixel coordinates (x right, y down, centres at +0.5) and planar eye depth of world points."""
    rotation, translation = camera_from_world()
    eye = np.asarray(points, dtype=np.float64) @ rotation.T + translation
    depth = -eye[:, 2]
    tan_y = math.tan(math.radians(FOV_Y) / 2.0)
    ndc_x = eye[:, 0] / (depth * tan_y * width / height)
    ndc_y = eye[:, 1] / (depth * tan_y)
    return np.stack([(ndc_x * 0.5 + 0.5) * width, (0.5 - ndc_y * 0.5) * height], axis=1), depth


def layer(result, name):
    """A layer of a render result as a float32 array (H, W, channels), top row first."""
    channels, pixels = result["layers"][name]
    return np.frombuffer(pixels, dtype=np.float32).reshape(result["height"], result["width"], len(channels))
