#!/usr/bin/python3
"""Plots a spindrift_soak CSV (frame, seconds, rss_kib, gl_objects, open_fds) as three stacked panels.
usage: plot_soak.py SOAK.csv OUT.png"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

rows = list(csv.DictReader(open(sys.argv[1])))
frames = [int(r["frame"]) for r in rows]
panels = [("rss_kib", "resident memory (MiB)", 1 / 1024), ("gl_objects", "live GL objects", 1),
          ("open_fds", "open file descriptors", 1)]
figure, axes = plt.subplots(3, 1, figsize=(7, 5.5), sharex=True)
for axis, (key, label, scale) in zip(axes, panels):
    axis.plot(frames, [float(r[key]) * scale for r in rows], lw=1.2)
    axis.set_ylabel(label)
    axis.axvline(70, color="0.6", lw=0.8, ls="--")  # the end of the warm-up (spindrift_soak's kWarmUpFrames)
    low, high = axis.get_ylim()
    if high - low < 4:
        middle = (high + low) / 2
        axis.set_ylim(middle - 2, middle + 2)
axes[-1].set_xlabel("frame (dashed: end of warm-up)")
figure.suptitle(f"spindrift_soak: {frames[-1]} frames in one process, {float(rows[-1]['seconds']):.0f} s")
figure.tight_layout()
figure.savefig(sys.argv[2], dpi=110)
