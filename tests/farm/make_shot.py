#!/usr/bin/python3
"""Writes a small shot for the farm tests: FRAMES PLY files of a liquid blob that falls and spreads, and a
scene file that renders them at WIDTHxHEIGHT.  usage: make_shot.py DIRECTORY FRAMES WIDTH HEIGHT [SLOW]

SLOW: a range of frames (e.g. 5-6) whose blob holds forty times the particles, so that each takes a
renderer about a second instead of under a tenth: the farm test kills a renderer after it reports a frame
done, and the frames after it must still be rendering when the kill lands (with 60-90 ms frames the renderer
sometimes finished them first, and the task was never requeued)."""
import json
import math
import pathlib
import random
import sys

directory, frames, width, height = pathlib.Path(sys.argv[1]), int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4])
first_slow, last_slow = (int(frame) for frame in sys.argv[5].split("-")) if len(sys.argv) > 5 else (0, -1)
directory.mkdir(parents=True, exist_ok=True)
rng = random.Random(7)
ball = [(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)) for _ in range(240000)]
ball = [p for p in ball if p[0] ** 2 + p[1] ** 2 + p[2] ** 2 <= 1]
for frame in range(1, frames + 1):
    t = frame / frames
    spread = 1.0 + 1.5 * t
    base = ball if first_slow <= frame <= last_slow else ball[:3000]
    rows = [f"{x * 0.5 * spread:.5f} {y * 0.5 * spread:.5f} {max(z * 0.5 / spread + 1.2 - 1.2 * t, -0.4):.5f}"
            for x, y, z in base]
    header = ["ply", "format ascii 1.0", f"element vertex {len(rows)}", "property float x", "property float y",
              "property float z", "end_header"]
    (directory / f"p_{frame:04d}.ply").write_text("\n".join(header + rows) + "\n")
scene = {
    "version": 1,
    "camera": {"width": width, "height": height, "fov_y_deg": 40, "position": [0, -5, 1.5], "target": [0, 0, 0.3],
               "up": [0, 0, 1]},
    "particles": [{"path": "p_####.ply", "radius": 0.06}],
    "background": {"color": [0.2, 0.25, 0.3]},
}
(directory / "scene.json").write_text(json.dumps(scene, indent=2) + "\n")
