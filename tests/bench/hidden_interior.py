#!/usr/bin/python3
"""A/B of liquid.drop_hidden_interior (the interior test and each view's occlusion): prints a Markdown table of interleaved runs (docs/frame-cost.md).

    tests/bench/hidden_interior.py [--rounds 3] [--work build/bench/hidden_interior]

Two scenes: the dam-break example's frame (a sheet of water a few radii thick) and a thick tank made here,
108,000 particles on a jittered lattice 60 x 60 x 30 (spacing 0.02, radius 0.0225, grown by the 1.91 r a
default Mantaflow domain derives), seen obliquely at 480 x 270. Each round renders every variant once, in
turn, so a changing load falls on all alike; medians are reported, and the EXRs of both variants are compared
with idiff (they must be identical).
"""

import argparse
import json
import math
import os
import random
import statistics
import struct
import subprocess

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SPINDRIFT = os.path.join(ROOT, "build", "bin", "spindrift")


def look_at(eye, target):
    forward = [t - e for t, e in zip(target, eye)]
    length = math.sqrt(sum(f * f for f in forward))
    forward = [f / length for f in forward]
    right = [forward[1], -forward[0], 0.0]  # forward x (0, 0, 1)
    length = math.sqrt(sum(r * r for r in right))
    right = [r / length for r in right]
    up = [right[1] * forward[2] - right[2] * forward[1], right[2] * forward[0] - right[0] * forward[2],
          right[0] * forward[1] - right[1] * forward[0]]
    back = [-f for f in forward]
    rows = [[right[i], up[i], back[i], eye[i]] for i in range(3)] + [[0.0, 0.0, 0.0, 1.0]]
    return [value for row in rows for value in row]


def make_tank(directory):
    os.makedirs(directory, exist_ok=True)
    random.seed(3)
    spacing = 0.02
    points = [(i * spacing + random.uniform(-0.3, 0.3) * spacing, j * spacing + random.uniform(-0.3, 0.3) * spacing,
               k * spacing + random.uniform(-0.3, 0.3) * spacing)
              for k in range(30) for j in range(60) for i in range(60)]
    with open(os.path.join(directory, "tank.ply"), "wb") as ply:
        ply.write(f"ply\nformat binary_little_endian 1.0\nelement vertex {len(points)}\n"
                  "property float x\nproperty float y\nproperty float z\nend_header\n".encode())
        for point in points:
            ply.write(struct.pack("<3f", *point))
    scene = {"version": 1, "frame": 1,
             "camera": {"width": 480, "height": 270, "fov_y_deg": 40, "near": 0.05, "far": 100,
                        "world_from_camera": look_at([2.6, -1.2, 1.4], [0.6, 0.6, 0.25])},
             "particles": [{"path": "tank.ply", "role": "liquid", "radius": 0.0225}],
             "background": {"color": [0.5, 0.6, 0.7]},
             "liquid": {"surface_offset": 1.91}}
    path = os.path.join(directory, "scene.json")
    with open(path, "w") as file:
        json.dump(scene, file, indent=1)
    return path


def render(scene, drop, work, name):
    exr = os.path.join(work, f"{name}_{drop}.exr")
    stats_path = os.path.join(work, f"{name}_{drop}.json")
    subprocess.run([SPINDRIFT, "render", scene, "-o", exr, "-q", "--stats", stats_path, "--set",
                    f"liquid.drop_hidden_interior={'true' if drop else 'false'}"], check=True)
    with open(stats_path) as file:
        stats = json.load(file)
    passes = {entry["name"]: entry["gpu_ms"] for entry in stats["passes"]}
    return exr, {"aggregates": stats["liquid"]["aggregate_particles"],
                 "dropped": stats["liquid"]["hidden_interior_dropped"],
                 "front_only": stats["liquid"]["hidden_interior_front_layer_only"],
                 "back_only": stats["liquid"]["hidden_interior_back_layer_only"],
                 "why_not": stats["liquid"]["hidden_interior_not_applied"],
                 "drop_ms": stats["liquid"]["hidden_interior_ms"],
                 "occluded_front": stats["liquid"]["occluded_from_front"],
                 "occluded_back": stats["liquid"]["occluded_from_back"],
                 "occluded_dropped": stats["liquid"]["occluded_dropped"],
                 "occlusion_ms": stats["liquid"]["occlusion_ms"],
                 "aggregate_ms": passes.get("aggregate_depth_layers", 0.0),
                 "prepare_ms": stats["prepare_ms"], "total_ms": stats["total_ms"]}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--work", default=os.path.join(ROOT, "build", "bench", "hidden_interior"))
    arguments = parser.parse_args()
    scenes = {"dam_break": os.path.join(ROOT, "examples", "dam_break", "scene.json"),
              "thick tank": make_tank(arguments.work)}
    print(f"load average at start: {os.getloadavg()}")
    results = {(name, drop): [] for name in scenes for drop in (False, True)}
    identical = {}
    for _ in range(arguments.rounds):
        for name, scene in scenes.items():
            files = {}
            for drop in (False, True):
                files[drop], stats = render(scene, drop, arguments.work, name.replace(" ", "_"))
                results[(name, drop)].append(stats)
            same = subprocess.run(["idiff", "-a", "-fail", "0", "-warn", "0", files[False], files[True]],
                                  capture_output=True).returncode == 0
            identical[name] = identical.get(name, True) and same
    print(f"load average at end: {os.getloadavg()}\n")
    print("| scene | drop_hidden_interior | aggregates | interior: dropped | interior: front layer only / back layer "
          "only | interior ms | occluded: from front / from back / dropped | occlusion ms | aggregate depth layers ms "
          "| prepare ms | frame ms | EXR identical |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for (name, drop), runs in results.items():
        median = {key: statistics.median(run[key] for run in runs)
                  for key in ("drop_ms", "occlusion_ms", "aggregate_ms", "prepare_ms", "total_ms")}
        note = f" ({runs[0]['why_not']})" if runs[0]["why_not"] else ""
        print(f"| {name} | {'true' if drop else 'false'} | {runs[0]['aggregates']:,} | {runs[0]['dropped']:,}{note} "
              f"| {runs[0]['front_only']:,} / {runs[0]['back_only']:,} | {median['drop_ms']:.0f} "
              f"| {runs[0]['occluded_front']:,} / {runs[0]['occluded_back']:,} / {runs[0]['occluded_dropped']:,} "
              f"| {median['occlusion_ms']:.0f} | {median['aggregate_ms']:.0f} | {median['prepare_ms']:.0f} "
              f"| {median['total_ms']:.0f} | {'yes' if identical[name] else 'NO'} |")


if __name__ == "__main__":
    main()
