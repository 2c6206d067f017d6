#!/usr/bin/python3
"""Rim normals (liquid.rim_normals, docs/liquid.md "Rim normals"): the first surface's normals near a
silhouette with and without them, against the exact ones, and what that does to the image.

    tests/bench/rim_normals.py

Needs the light benchmark's frames (build/bench/thick/, tests/bench/thick_report.py renders them) and the
benchmark's example references (build/bench/references/, tests/bench/benchmark.py). For the thick bodies it
scores the water against Cycles' full reference (with the sun and Cycles' light passes, as the light
benchmark's "sun, light passes" row) over the water, its outer 4 px and the rest, and the first surface's
normal against the exact sphere's or box's, by distance from the silhouette. For the examples' eight cameras
it compares the normal with Cycles' Normal pass of Mantaflow's mesh. Prints Markdown tables and writes
docs/images/rim_ball.png (the ball: Cycles, without, with; the normal's error, 0 to 30 degrees, without and
with).
"""

import json
import os

import numpy as np
from scipy import ndimage

import metrics
import runs
import thick_report

EXAMPLES = os.path.join(runs.REPOSITORY, "build", "bench", "references")
CAMERAS = ("oblique", "closeup", "topdown", "grazing")
BANDS = ((0, 2), (2, 4), (4, 8), (8, 1e9))
SETTINGS = (("without", {"liquid.rim_normals": False}), ("with", {}))


def exact_normals(scene, shape):
    """The exact shape's outward normal where each pixel's ray first meets it (NaN where it misses)."""
    origin, directions = thick_report.camera_rays(scene)
    normals = np.full(directions.shape, np.nan)
    if shape[0] == "sphere":
        centre, radius = np.array(shape[1]), shape[2]
        b = directions @ (centre - origin)
        discriminant = b * b - (np.sum((centre - origin) ** 2) - radius * radius)
        hit = discriminant > 0
        t = b - np.sqrt(np.maximum(discriminant, 0.0))
        normals[hit] = ((origin + directions * t[..., None] - centre) / radius)[hit]
    else:
        low, high = np.array(shape[1]), np.array(shape[2])
        with np.errstate(divide="ignore", invalid="ignore"):
            t0, t1 = (low - origin) / directions, (high - origin) / directions
        near, far = np.minimum(t0, t1), np.maximum(t0, t1)
        entry, axis = near.max(-1), near.argmax(-1)
        hit = (entry < far.min(-1)) & (entry > 0)
        signs = -np.sign(np.take_along_axis(directions, axis[..., None], -1))[..., 0]
        for a in range(3):
            normals[..., a] = np.where(hit & (axis == a), signs, np.where(hit, 0.0, np.nan))
    return normals


def band_medians(errors, covered):
    distance = ndimage.distance_transform_edt(covered)
    medians = []
    for low, high in BANDS:
        band = errors[covered & (distance > low) & (distance <= high)]
        medians.append(float(np.nanmedian(band)) if np.isfinite(band).any() else float("nan"))
    return medians


def degrees_text(value):
    return "—" if np.isnan(value) else f"{value:.1f}°"


def thick_bodies():
    rows, images = [], {}
    for frame in ("ball", "block"):
        directory = os.path.join(thick_report.OUTPUT, frame)
        water, shadowed = thick_report.regions(directory)
        inner = ndimage.binary_erosion(water, iterations=4)
        full = thick_report.rgb(os.path.join(directory, "reference_full.exr"))
        scene_path = thick_report.scene_variant(directory, True, True)
        shape = json.load(open(os.path.join(directory, "shape.json")))["shape"]
        exact = exact_normals(json.load(open(scene_path)), shape)
        for name, settings in SETTINGS:
            exr = os.path.join(directory, f"spindrift_rim_{name}.exr")
            runs.run_spindrift(scene_path, exr, settings, exr + ".stats.json")
            test = metrics.read_channels(exr, ["composite.R", "composite.G", "composite.B"])
            normal = metrics.read_channels(exr, ["normal.X", "normal.Y", "normal.Z"])
            covered = np.linalg.norm(normal, axis=-1) > 0.5
            errors = np.where(covered & ~np.isnan(exact[..., 0]), metrics.normal_angles(normal, exact), np.nan)
            rows.append((frame, name, thick_report.mae(test, full, water), thick_report.mae(test, full, water & ~inner),
                         thick_report.mae(test, full, inner), band_medians(errors, covered)))
            if frame == "ball":
                images[name] = (test, np.nan_to_num(errors, nan=0.0))
                images["reference"] = full
    return rows, images


def examples():
    rows = []
    for example in ("dam_break", "drop"):
        for camera in CAMERAS:
            directory = os.path.join(EXAMPLES, f"{example}_480x270_256spp", camera)
            reference = metrics.read_channels(os.path.join(directory, "reference.exr"),
                                              [f"ViewLayer.Normal.{c}" for c in "XYZ"])
            for name, settings in SETTINGS:
                exr = os.path.join(directory, f"spindrift_rim_{name}.exr")
                runs.run_spindrift(os.path.join(directory, "scene.json"), exr, settings, exr + ".stats.json")
                normal = metrics.read_channels(exr, ["normal.X", "normal.Y", "normal.Z"])
                covered = (np.linalg.norm(normal, axis=-1) > 0.5) & (np.linalg.norm(reference, axis=-1) > 0.5)
                errors = metrics.normal_angles(normal, reference)
                rows.append((example, camera, name, float(errors[covered].mean()), band_medians(
                    np.where(covered, errors, np.nan), np.linalg.norm(normal, axis=-1) > 0.5)))
    return rows


def write_picture(images):
    """The ball's water cropped: Cycles, without and with, then the normal's error without and with."""
    covered = images["with"][1] > 0
    rows, columns = np.nonzero(covered)
    crop = (slice(max(rows.min() - 6, 0), rows.max() + 7), slice(max(columns.min() - 6, 0), columns.max() + 7))
    error = [np.repeat((images[name][1] / 30.0).clip(0, 1)[..., None], 3, axis=2) for name in ("without", "with")]
    thick_report.strip([image[crop] for image in (images["reference"], images["without"][0], images["with"][0],
                                                  *error)],
                       os.path.join(thick_report.IMAGES, "rim_ball.png"))


def main():
    thick, images = thick_bodies()
    print("| Frame | Rim normals | Water | Outer 4 px | Inside | Normal error, median: 0–2 px | 2–4 px | 4–8 px "
          "| beyond |")
    print("|---|---|---|---|---|---|---|---|---|")
    for frame, name, water, rim, inside, bands in thick:
        print(f"| {frame} | {name} | {water:.4f} | {rim:.4f} | {inside:.4f} | " +
              " | ".join(degrees_text(b) for b in bands) + " |")
    write_picture(images)
    print()
    print("| Example | Camera | Rim normals | Normal error vs Cycles, mean | median 0–2 px | 2–4 px | 4–8 px "
          "| beyond |")
    print("|---|---|---|---|---|---|---|---|")
    for example, camera, name, mean, bands in examples():
        print(f"| {example} | {camera} | {name} | {mean:.2f}° | " + " | ".join(degrees_text(b) for b in bands) + " |")


if __name__ == "__main__":
    main()
