"""Scaling: frame time and memory against particle count and against resolution, with fitted log-log slopes.

Particle counts come two ways, both written as PLY files (x, y, z, radius) into the work directory:
- synthetic: a uniformly random slab of liquid filling the dam-break domain's floor to a third of its height;
- resampled Mantaflow: the dam-break frame's own particles, subsampled below its count and, above it, copied
  with jitter of half the new spacing (the spacing shrinks as N^(-1/3), so the liquid keeps its shape).
In both, the radius is 1.1 times the spacing, as the examples use (0.55 cells for particles half a cell apart).
"""

import copy
import json
import os

import numpy as np

import runs
import sweep

SLAB_MIN = np.array([-1.5, -0.9375, 0.0])
SLAB_MAX = np.array([1.5, 0.9375, 0.375])
RADIUS_PER_SPACING = 1.1


def write_ply(path, positions, radius):
    rows = np.empty((len(positions), 4), dtype="<f4")
    rows[:, :3] = positions
    rows[:, 3] = radius
    with open(path, "wb") as handle:
        handle.write(f"ply\nformat binary_little_endian 1.0\nelement vertex {len(rows)}\nproperty float x\n"
                     "property float y\nproperty float z\nproperty float radius\nend_header\n".encode())
        handle.write(rows.tobytes())


def read_ply(path):
    with open(path, "rb") as handle:
        header = b""
        while not header.endswith(b"end_header\n"):
            header += handle.readline()
        count = int(header.split(b"element vertex ")[1].split()[0])
        return np.frombuffer(handle.read(count * 16), dtype="<f4").reshape(count, 4)


def synthetic_particles(count, seed=1):
    generator = np.random.default_rng(seed)
    positions = SLAB_MIN + generator.random((count, 3)) * (SLAB_MAX - SLAB_MIN)
    spacing = (np.prod(SLAB_MAX - SLAB_MIN) / count) ** (1 / 3)
    return positions, RADIUS_PER_SPACING * spacing


def resampled_particles(source_rows, count, seed=1):
    generator = np.random.default_rng(seed)
    source_count = len(source_rows)
    source_radius = float(np.median(source_rows[:, 3]))
    spacing = source_radius / RADIUS_PER_SPACING * (source_count / count) ** (1 / 3)
    chosen = generator.choice(source_count, size=count, replace=count > source_count)
    positions = source_rows[chosen, :3].astype(np.float64)
    if count > source_count:
        positions += (generator.random((count, 3)) - 0.5) * spacing
    return positions, RADIUS_PER_SPACING * spacing


def scene_with(base_scene_path, ply_path=None, width=None, height=None, output_path=None):
    """A copy of a camera's scene file with its particles replaced by one PLY, or another image size."""
    description = json.load(open(base_scene_path))
    description = copy.deepcopy(description)
    base_directory = os.path.dirname(os.path.abspath(base_scene_path))
    description["background"]["image"] = os.path.join(base_directory, description["background"]["image"])
    if ply_path:
        description["particles"] = [{"path": ply_path, "role": "liquid", "radius": 1.0}]
    if width:
        description["camera"]["width"], description["camera"]["height"] = width, height
    with open(output_path, "w") as handle:
        json.dump(description, handle, indent=1)
    return output_path


def fitted_slope(xs, ys, minimum_x=0):
    """Slope of log(y) against log(x) over the points with x >= minimum_x (NaN with fewer than two)."""
    points = [(x, y) for x, y in zip(xs, ys) if x >= minimum_x and y > 0]
    if len(points) < 2:
        return float("nan")
    logs = np.log(np.array(points, dtype=float))
    return float(np.polyfit(logs[:, 0], logs[:, 1], 1)[0])


def particle_scaling(base_scene, mantaflow_ply, counts, repeats_for, work_directory):
    source_rows = read_ply(mantaflow_ply)
    rows = []
    for source in ("synthetic", "resampled"):
        for count in counts:
            positions, radius = synthetic_particles(count) if source == "synthetic" else \
                resampled_particles(source_rows, count)
            ply = os.path.join(work_directory, f"{source}_{count}.ply")
            write_ply(ply, positions, radius)
            scene = scene_with(base_scene, ply_path=ply, output_path=os.path.join(work_directory, "scaling.json"))
            timing = runs.timed_spindrift(scene, os.path.join(work_directory, "scaling.exr"), sweep.AS_THE_REFERENCE,
                                          repeats_for(count), work_directory)
            os.remove(ply)
            rows.append({"source": source, "count": count, **timing})
            print(f"  scaling {source} {count}: {timing['total_ms']:.0f} ms, {timing['peak_rss_mib']:.0f} MiB",
                  flush=True)
    return rows


def resolution_scaling(base_scene, sizes, repeats_for, work_directory):
    rows = []
    for width, height in sizes:
        scene = scene_with(base_scene, width=width, height=height,
                           output_path=os.path.join(work_directory, "resolution.json"))
        timing = runs.timed_spindrift(scene, os.path.join(work_directory, "resolution.exr"), sweep.AS_THE_REFERENCE,
                                      repeats_for(width * height), work_directory)
        rows.append({"width": width, "height": height, "pixels": width * height, **timing})
        print(f"  scaling {width}x{height}: {timing['total_ms']:.0f} ms", flush=True)
    return rows


def slopes(particle_rows, resolution_rows):
    """Fitted exponents: frame time and peak host memory against particle count (from 100k up, where the
    fixed cost of a frame stops dominating) and frame time against pixel count."""
    result = {}
    for source in ("synthetic", "resampled"):
        rows = [row for row in particle_rows if row["source"] == source]
        counts = [row["count"] for row in rows]
        result[f"time_vs_particles_{source}"] = fitted_slope(counts, [row["total_ms"] for row in rows], 100_000)
        result[f"memory_vs_particles_{source}"] = fitted_slope(counts, [row["peak_rss_mib"] for row in rows],
                                                               100_000)
    result["time_vs_pixels"] = fitted_slope([row["pixels"] for row in resolution_rows],
                                            [row["total_ms"] for row in resolution_rows])
    return result
