#!/usr/bin/python3
"""How far Mantaflow's liquid mesh stands off its own FLIP particles, measured on a bake.

    tests/bench/surface_offset.py examples/dam_break [--frame 16] [--json out.json]

Reads the example's liquid particles with Spindrift's loader (`spindrift_export_particles`, world space) and
Mantaflow's mesh of the same frame (`cache/mesh/fluid_mesh_NNNN.bobj.gz`, with its per-vertex normals), placed
in the world as references.py places it. For every mesh vertex it finds the nearest particle; for every
particle the nearest vertex, whose outward normal gives the particle's signed distance to the surface
(negative: inside). Vertices are split by where they are: against a wall of the domain (within 1.5 cells of
the domain's box), on the free surface of the body, or around a lone particle (at most 3 particles within 2
cells). Distances are printed in cells and in Mantaflow's own particle radius r_m (docs/mantaflow-caches.md).
"""

import argparse
import gzip
import json
import math
import os
import struct
import subprocess
import sys

import numpy as np
from scipy.spatial import cKDTree

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import runs  # noqa: E402



def read_config(cache_directory):
    """Resolution, normalised cell size, local bounds and matrix_world from Mantaflow's config header."""
    name = sorted(n for n in os.listdir(os.path.join(cache_directory, "config")) if n.endswith(".uni"))[0]
    data = gzip.open(os.path.join(cache_directory, "config", name)).read()
    values = struct.unpack_from("<i3iff3f3f3f3i3f16f", data)
    matrix = np.array(values[21:37]).reshape(4, 4).T  # Blender stores obmat column by column
    return {"resolution": values[1:4], "dx": values[4], "p0": np.array(values[6:9]), "p1": np.array(values[9:12]),
            "matrix_world": matrix}


def read_bobj(path):
    """Mantaflow's gzipped mesh: vertex count and xyz floats, normals likewise, then triangles."""
    data = gzip.open(path).read()
    count = struct.unpack_from("<i", data, 0)[0]
    vertices = np.frombuffer(data, "<f4", count * 3, 4).reshape(-1, 3).astype(np.float64)
    normals = np.frombuffer(data, "<f4", count * 3, 8 + count * 12).reshape(-1, 3).astype(np.float64)
    return vertices, normals


def read_ply(path):
    data = open(path, "rb").read()
    header_end = data.index(b"end_header\n") + len(b"end_header\n")
    return np.frombuffer(data[header_end:], dtype="<f4").reshape(-1, 4)


def mantaflow_radius_cells(mesh_particle_radius, mesh_scale):
    """The particle radius of Mantaflow's mesh level set, in simulation cells (docs/mantaflow-caches.md)."""
    return 0.5 * math.sqrt(3.0) * (mesh_particle_radius + 0.01) / mesh_scale


def summarise(values):
    if len(values) == 0:
        return None
    return {"count": int(len(values)), "median": float(np.median(values)),
            "p10": float(np.percentile(values, 10)), "p90": float(np.percentile(values, 90))}


def measure(example_directory, frame, settings, work):
    # A scene with the example's liquid source alone: its background renders need not exist.
    description = json.load(open(os.path.join(example_directory, "scene.json")))
    liquid = dict(next(p for p in description["particles"] if p.get("role", "liquid") == "liquid"))
    liquid["path"] = os.path.join(example_directory, liquid["path"])
    scene = os.path.join(work, f"{os.path.basename(example_directory)}_liquid.json")
    with open(scene, "w") as handle:
        json.dump({"version": 1, "camera": description["camera"], "particles": [liquid]}, handle)
    ply = os.path.join(work, f"{os.path.basename(example_directory)}_{frame}.ply")
    subprocess.run([runs.EXPORT_PARTICLES, scene, str(frame), ply], check=True, capture_output=True)
    particles = read_ply(ply)[:, :3].astype(np.float64)

    cache = os.path.join(example_directory, "cache")
    config = read_config(cache)
    matrix = config["matrix_world"]
    scale = np.linalg.norm(matrix[:3, :3], axis=0)
    size = (config["p1"] - config["p0"]) * scale
    cell = config["dx"] * size.max()
    # The mesh is in the domain's normalised frame: centred on its box, in units of its longest scaled side.
    vertices, normals = read_bobj(os.path.join(cache, "mesh", f"fluid_mesh_{frame:04d}.bobj.gz"))
    local = (config["p0"] + config["p1"]) / 2 + vertices * size.max() / scale
    vertices = local @ matrix[:3, :3].T + matrix[:3, 3]
    normals = normals @ matrix[:3, :3].T
    normals /= np.linalg.norm(normals, axis=1, keepdims=True)
    corners = np.array([[x, y, z] for x in (config["p0"][0], config["p1"][0]) for y in (config["p0"][1], config["p1"][1])
                        for z in (config["p0"][2], config["p1"][2])]) @ matrix[:3, :3].T + matrix[:3, 3]
    domain_min, domain_max = corners.min(axis=0), corners.max(axis=0)

    particle_tree = cKDTree(particles)
    vertex_distance, _ = particle_tree.query(vertices)
    vertex_tree = cKDTree(vertices)
    _, nearest_vertex = vertex_tree.query(particles)
    signed = np.einsum("ij,ij->i", particles - vertices[nearest_vertex], normals[nearest_vertex])

    to_wall = np.minimum(vertices - domain_min, domain_max - vertices)
    # The top of the domain is open air in both examples: only the floor and the four sides are walls.
    to_wall[:, 2] = vertices[:, 2] - domain_min[2]
    against_wall = to_wall.min(axis=1) < 1.5 * cell
    crowd = np.array([len(n) for n in particle_tree.query_ball_point(vertices, 2.0 * cell)])
    lone = (crowd <= 3) & ~against_wall
    free = ~against_wall & ~lone

    outermost = signed > -1.5 * cell  # particles near the surface: the interior says nothing about it
    r_m = mantaflow_radius_cells(settings["mesh_particle_radius"], settings["mesh_scale"])
    result = {"example": os.path.basename(example_directory), "frame": frame, "cell": cell,
              "particles": int(len(particles)), "vertices": int(len(vertices)),
              "mantaflow_radius_cells": r_m,
              "vertex_to_particle_cells": {
                  "free surface": summarise(vertex_distance[free] / cell),
                  "against a wall": summarise(vertex_distance[against_wall] / cell),
                  "around a lone particle": summarise(vertex_distance[lone] / cell)},
              "particle_signed_distance_cells": summarise(signed[outermost] / cell)}
    return result


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("examples", nargs="+")
    parser.add_argument("--frame", type=int, default=None, help="default: the example's showcase frame")
    parser.add_argument("--json", default=None)
    parser.add_argument("--work", default=os.path.join(runs.REPOSITORY, "build", "bench", "surface_offset"))
    arguments = parser.parse_args()
    os.makedirs(arguments.work, exist_ok=True)
    results = []
    for example in arguments.examples:
        directory = os.path.abspath(example)
        frame = arguments.frame or json.load(open(os.path.join(directory, "scene.json")))["frame"]
        description = json.load(open(os.path.join(directory, "scene.json")))
        domain = next((p.get("domain") for p in description["particles"] if "domain" in p), None)
        settings = {"mesh_particle_radius": 2.0, "mesh_scale": 2, **(domain or {"mesh_scale": 1})}
        result = measure(directory, frame, settings, arguments.work)
        results.append(result)
        print(json.dumps(result, indent=1))
    if arguments.json:
        with open(arguments.json, "w") as handle:
            json.dump(results, handle, indent=1)


if __name__ == "__main__":
    main()
