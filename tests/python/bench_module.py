#!/usr/bin/env python3
"""What the Python module adds to a frame (not a test; docs/python-module.md records its output): the wall
time of Renderer.render against the library's own total (stats["total_ms"]), so the difference is the argument
hand-off (validation and copies) and the conversion of the layers to bytes; and the occluder prepass's cost for
a mesh of many triangles. Prints one line per case."""

import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from spindrift_testing import import_module, scene_json, sphere_of_particles  # noqa: E402


def grid_mesh(cells, y=-2.0, half=1.0):
    """A (cells x cells) grid of quads in the plane y, as two triangles each."""
    u = np.linspace(-half, half, cells + 1, dtype=np.float32)
    xs, zs = np.meshgrid(u, u)
    vertices = np.stack([xs.ravel(), np.full(xs.size, y, np.float32), zs.ravel()], axis=1)
    index = np.arange((cells + 1) ** 2, dtype=np.uint32).reshape(cells + 1, cells + 1)
    a, b, c, d = index[:-1, :-1].ravel(), index[:-1, 1:].ravel(), index[1:, 1:].ravel(), index[1:, :-1].ravel()
    triangles = np.concatenate([np.stack([a, b, c], 1), np.stack([a, c, d], 1)])
    return {"vertices": np.ascontiguousarray(vertices), "triangles": np.ascontiguousarray(triangles)}


def main():
    spindrift = import_module()
    renderer = spindrift.Renderer()
    print(f"GL: {renderer.gl_renderer}; load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")
    for count, width, height in ((20000, 640, 360), (200000, 640, 360), (200000, 1280, 720)):
        arrays = sphere_of_particles(count=count, particle_radius=0.02)
        scene = scene_json(width=width, height=height)
        renderer.render(scene, 1, particles=arrays, layers=["composite"])  # warm up: targets, buffers
        for layers in (["composite"], None):
            start = time.perf_counter()
            result = renderer.render(scene, 1, particles=arrays, layers=layers)
            wall = (time.perf_counter() - start) * 1000.0
            total = result["stats"]["total_ms"]
            print(f"{count} particles {width}x{height}, layers={'all' if layers is None else layers}: render() "
                  f"{wall:.1f} ms, library {total:.1f} ms, module {wall - total:.1f} ms "
                  f"({100.0 * (wall - total) / total:.1f} %)")
    arrays = sphere_of_particles(count=20000, particle_radius=0.02)
    scene = scene_json(width=1280, height=720)
    for cells in (10, 100, 300):
        mesh = grid_mesh(cells)
        renderer.render(scene, 1, particles=arrays, occluders=mesh, layers=["composite"])
        result = renderer.render(scene, 1, particles=arrays, occluders=mesh, layers=["composite"])
        prepass = next(p for p in result["stats"]["passes"] if p["name"] == "occluder_depth")
        print(f"occluder prepass, {2 * cells * cells} triangles at 1280x720: GPU {prepass['gpu_ms']:.2f} ms, "
              f"CPU {prepass['cpu_ms']:.2f} ms; frame total {result['stats']['total_ms']:.1f} ms")
    renderer.close()


if __name__ == "__main__":
    main()
