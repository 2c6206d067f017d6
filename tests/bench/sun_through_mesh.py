"""The sun's light on the floor under Mantaflow's liquid mesh by exact ray tracing: the independent reference
for Spindrift's liquid_shadow and caustics passes (tests/bench/sun_report.py runs it).

Run inside Blender:

    blender -b --factory-startup --python-exit-code 1 --python tests/bench/sun_through_mesh.py -- \
        --example examples/dam_break --scene build/bench/references/.../topdown/scene_sun.json \
        --output sun_factor.npz [--rays 4000000]

Floor points on a fine grid over the example's domain each receive one ray of the scene's sun (its first
light), traced back to above everything and then forward through the liquid mesh of the scene's frame, as
geometric optics has it: the exact Fresnel reflectance of a dielectric at every surface met (the transmitted
part goes on), total internal reflection followed (up to 24 surface meetings), Beer-Lambert absorption along
every segment in the liquid, smooth-shaded normals as Cycles interpolates them. Where the ray meets the floor
(z = 0) its energy lands, in the camera pixel that shows that point; the same ray without the liquid lands at
its own floor point. The ratio of the two sums, per pixel, is the share of the sun's light the floor keeps
under the water: exactly what Spindrift's liquid_shadow + caustics stand for. Light that the walls would stop
and light that leaves the domain are not followed; the sums are made over the floor inside the domain.

Writes OUTPUT (numpy .npz): `wet` (H x W x 3, energy landing per pixel) and `dry` (H x W, rays per pixel
without the liquid).
"""

import argparse
import json
import math
import os
import sys
import time

import bpy
import numpy as np
from mathutils import Vector
from mathutils.bvhtree import BVHTree
from mathutils.geometry import barycentric_transform

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import references  # noqa: E402 (Blender runs this file by path)

MAX_SURFACE_MEETINGS = 24


def parse_arguments():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    parser = argparse.ArgumentParser(prog="sun_through_mesh.py", description=__doc__.split("\n")[0])
    parser.add_argument("--example", required=True)
    parser.add_argument("--scene", required=True, help="a scene file with the camera, the frame and a sun")
    parser.add_argument("--output", required=True)
    parser.add_argument("--rays", type=int, default=4_000_000)
    parser.add_argument("--absorption-rgb", default="0.9,0.3,0.15")
    parser.add_argument("--ior", type=float, default=1.33)
    return parser.parse_args(argv)


def dielectric_fresnel(cosine, n1, n2):
    """Unpolarised Fresnel reflectance and the refracted cosine; reflectance 1 at total internal reflection."""
    sine = n1 / n2 * math.sqrt(max(0.0, 1.0 - cosine * cosine))
    if sine >= 1.0:
        return 1.0, 0.0
    refracted = math.sqrt(1.0 - sine * sine)
    rs = ((n1 * cosine - n2 * refracted) / (n1 * cosine + n2 * refracted)) ** 2
    rp = ((n1 * refracted - n2 * cosine) / (n1 * refracted + n2 * cosine)) ** 2
    return 0.5 * (rs + rp), refracted


class SmoothMesh:
    """Ray casts against a mesh object, with its smooth-shaded (vertex-interpolated) normals."""

    def __init__(self, obj):
        self.bvh = BVHTree.FromObject(obj, bpy.context.evaluated_depsgraph_get())
        mesh = obj.data
        self.vertices = [v.co.copy() for v in mesh.vertices]
        self.normals = [v.normal.copy() for v in mesh.vertices]
        self.triangles = [tuple(p.vertices)[:3] for p in mesh.polygons]

    def cast(self, origin, direction):
        location, face_normal, index, distance = self.bvh.ray_cast(origin, direction)
        if location is None:
            return None
        a, b, c = self.triangles[index]
        weights = barycentric_transform(location, self.vertices[a], self.vertices[b], self.vertices[c],
                                        Vector((1, 0, 0)), Vector((0, 1, 0)), Vector((0, 0, 1)))
        normal = self.normals[a] * weights.x + self.normals[b] * weights.y + self.normals[c] * weights.z
        normal = normal.normalized() if normal.length > 1e-9 else face_normal.normalized()
        return location, normal, distance


def trace_to_floor(mesh, start, direction, sigma, ior):
    """Follows the transmitted light from `start` along `direction`; returns (energy RGB, floor point) where
    it meets z = 0, or None where it leaves upwards."""
    energy = np.ones(3)
    position, inside = start, False
    for _ in range(MAX_SURFACE_MEETINGS):
        hit = mesh.cast(position + direction * 1e-5, direction)
        to_floor = -position.z / direction.z if direction.z < 0.0 else math.inf
        if hit is None or to_floor < hit[2]:
            if inside:
                energy = energy * np.exp(-sigma * to_floor)
            return (energy, position + direction * to_floor) if math.isfinite(to_floor) else None
        location, normal, distance = hit
        if inside:
            energy = energy * np.exp(-sigma * distance)
        if normal.dot(direction) > 0.0:
            normal = -normal  # facing the ray
        cosine = -normal.dot(direction)
        n1, n2 = (ior, 1.0) if inside else (1.0, ior)
        reflectance, refracted_cosine = dielectric_fresnel(cosine, n1, n2)
        if reflectance >= 1.0:
            direction = (direction + 2.0 * cosine * normal).normalized()
        else:
            energy = energy * (1.0 - reflectance)
            ratio = n1 / n2
            direction = (ratio * direction + (ratio * cosine - refracted_cosine) * normal).normalized()
            inside = not inside
        position = location
    return None  # still bouncing: its energy is left out, as a path tracer's bounce limit would


def main():
    arguments = parse_arguments()
    with open(arguments.scene, encoding="utf-8") as handle:
        scene = json.load(handle)
    suns = [light for light in scene.get("lights", []) if light["type"] == "sun"]
    if not suns:
        sys.exit(f"{arguments.scene}: no sun in `lights`")
    example = references.load_example(os.path.abspath(arguments.example))
    liquid = references.add_liquid_mesh(example, os.path.join(os.path.abspath(arguments.example), "cache"),
                                        scene["frame"], [float(c) for c in arguments.absorption_rgb.split(",")])
    mesh = SmoothMesh(liquid)
    sigma = np.array([float(c) for c in arguments.absorption_rgb.split(",")])
    sun = Vector(suns[0]["direction"]).normalized()

    camera = scene["camera"]
    width, height = camera["width"], camera["height"]
    camera_from_world = np.linalg.inv(np.array(camera["world_from_camera"]).reshape(4, 4))
    tan_half_y = math.tan(math.radians(camera["fov_y_deg"]) / 2)

    def pixel_of(point):
        x, y, z, _ = camera_from_world @ np.array([point.x, point.y, point.z, 1.0])
        if z >= 0.0:
            return None
        column = int((x / -z / (tan_half_y * width / height) + 1) / 2 * width)
        row = int((1 - y / -z / tan_half_y) / 2 * height)
        return (row, column) if 0 <= row < height and 0 <= column < width else None

    low, size = example.LAYOUT.domain_min, example.LAYOUT.domain_size
    wet, dry = np.zeros((height, width, 3)), np.zeros((height, width))
    side = int(math.sqrt(arguments.rays))
    started = time.perf_counter()
    for i in range(side):
        for j in range(side):
            floor = Vector((low.x + (i + 0.5) / side * size.x, low.y + (j + 0.5) / side * size.y, 0.0))
            pixel = pixel_of(floor)
            if pixel:
                dry[pixel] += 1.0
            # From above everything, towards this floor point.
            landed = trace_to_floor(mesh, floor - sun * (3.0 * size.z / -sun.z), sun, sigma, arguments.ior)
            if landed:
                landing_pixel = pixel_of(landed[1])
                if landing_pixel:
                    wet[landing_pixel] += landed[0]
    np.savez(arguments.output, wet=wet, dry=dry)
    print(f"[sun_through_mesh] {side * side} rays in {time.perf_counter() - started:.0f} s: {arguments.output}",
          flush=True)


if __name__ == "__main__":
    main()
