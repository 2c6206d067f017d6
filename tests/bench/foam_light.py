#!/usr/bin/python3
"""Foam under the scene's lights: Spindrift's foam lit by its environment alone and by the scene's lights too
(foam.lit_by_lights), against Cycles rendering the same whitewater (docs/foam.md, "Lit by the scene's lights").

    tests/bench/foam_light.py [--examples drop,dam_break] [--cameras oblique,closeup,topdown,grazing]

Reads the benchmark's references (build/bench/references/EXAMPLE_480x270_256spp, made by
tests/bench/benchmark.py), among them the user's render (the water casting its shadow and caustics) with the
frame's whitewater, read by Spindrift's loader, as white diffuse spheres of the particles' radius
(references.py --whitewater). Renders each camera's scene_sun.json (the example's sun over Cycles' light
passes, as the Blender add-on exports the scene) with foam.lit_by_lights false and true, and compares them
with that render:

- over Spindrift's dense foam (foam alpha > 0.5, where the foam rather than the liquid under it makes the
  pixel): the mean colour of Cycles' render, of Spindrift's foam (its foam layer over its alpha) and of its
  composite, and the composite's mean absolute error;
- over the benchmark's liquid mask (docs/benchmarks.md): the image MAE against the render with the whitewater
  and against the one without (reference_full.exr).

The spheres' size and material are choices a Blender user makes, not data: the whitewater render says how
bright lit foam is, not how much of the screen it covers. Prints a Markdown table; writes
docs/images/foam_lit_by_lights.png (the first example's first camera, around its foam: Cycles with the
whitewater, Spindrift lit by its environment alone, and by the sun too).
"""

import argparse
import os
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import metrics  # noqa: E402
import runs  # noqa: E402
import thick_report  # noqa: E402
import users_render  # noqa: E402

REFERENCES = os.path.join(runs.REPOSITORY, "build", "bench", "references")
IMAGE = os.path.join(runs.REPOSITORY, "docs", "images", "foam_lit_by_lights.png")
DENSE_FOAM = 0.5
RGB = ["R", "G", "B"]
VARIANTS = (("environment alone", "false"), ("lights too", "true"))


def parse_arguments():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--examples", default="drop,dam_break")
    parser.add_argument("--cameras", default="oblique,closeup,topdown,grazing")
    return parser.parse_args()


def require_references(example, cameras):
    output = os.path.join(REFERENCES, f"{example}_480x270_256spp")
    missing = [camera for camera in cameras
               if not os.path.isfile(os.path.join(output, camera, users_render.WHITEWATER_REFERENCE))]
    if missing:
        raise SystemExit(f"{example}: no {users_render.WHITEWATER_REFERENCE} for {', '.join(missing)} under "
                         f"{output}: tests/bench/benchmark.py renders it with the other references")


def render(directory, lit_by_lights):
    exr = os.path.join(directory, f"spindrift_foam_lit_{lit_by_lights}.exr")
    subprocess.run([runs.SPINDRIFT, "render", os.path.join(directory, "scene_sun.json"), "-o", exr, "-q", "--set",
                    f"foam.lit_by_lights={lit_by_lights}"], check=True, stdout=subprocess.DEVNULL)
    return exr


def compare(example, camera):
    directory = os.path.join(REFERENCES, f"{example}_480x270_256spp", camera)
    cycles = metrics.read_channels(os.path.join(directory, users_render.WHITEWATER_REFERENCE), [f"Combined.{c}" for c in RGB])
    row = {"variants": {}}
    panels = [cycles]
    for label, value in VARIANTS:
        exr = render(directory, value)
        composite = metrics.read_channels(exr, [f"composite.{c}" for c in RGB])
        foam = metrics.read_channels(exr, [f"foam.{c}" for c in RGB + ["A"]])
        dense = foam[..., 3] > DENSE_FOAM
        row["pixels"] = int(dense.sum())
        errors = {name: runs.frame_errors(exr, directory, 1.0, runs.SPINDRIFT_CHANNELS, reference=name)["mae"]
                  for name in (users_render.WHITEWATER_REFERENCE, "reference_full.exr")}
        row["cycles"] = cycles[dense].mean(axis=0)
        row["variants"][label] = {
            "foam": (foam[..., :3][dense] / foam[..., 3][dense][:, None]).mean(axis=0),
            "composite": composite[dense].mean(axis=0),
            "dense_mae": float(np.abs(composite[dense] - cycles[dense]).mean()),
            "mae_whitewater": errors[users_render.WHITEWATER_REFERENCE],
            "mae_without": errors["reference_full.exr"],
        }
        panels.append(composite)
        row["alpha"] = foam[..., 3]
    return row, panels


def write_image(panels, alpha):
    rows, columns = np.nonzero(alpha > 0.0)
    top, bottom = max(rows.min() - 10, 0), min(rows.max() + 11, alpha.shape[0])
    left, right = max(columns.min() - 10, 0), min(columns.max() + 11, alpha.shape[1])
    # Twice the size, pixel for pixel: the foam's speckle is what the picture shows.
    crops = [np.repeat(np.repeat(panel[top:bottom, left:right], 2, axis=0), 2, axis=1) for panel in panels]
    thick_report.strip(crops, IMAGE)


def main():
    arguments = parse_arguments()
    cameras = arguments.cameras.split(",")
    triple = lambda values: "(" + ", ".join(f"{v:.3f}" for v in values) + ")"
    print("| example, camera | dense foam px | Cycles with whitewater | foam lit by | Spindrift's foam | "
          "composite | its MAE there | MAE over the liquid: with whitewater | without |")
    print("|---|---|---|---|---|---|---|---|---|")
    first = None
    for example in arguments.examples.split(","):
        require_references(example, cameras)
        for camera in cameras:
            row, panels = compare(example, camera)
            first = first or (panels, row["alpha"])
            for label, values in row["variants"].items():
                print(f"| {example}, {camera} | {row['pixels']} | {triple(row['cycles'])} | {label} | "
                      f"{triple(values['foam'])} | {triple(values['composite'])} | {values['dense_mae']:.3f} | "
                      f"{values['mae_whitewater']:.4f} | {values['mae_without']:.4f} |", flush=True)
    write_image(*first)


if __name__ == "__main__":
    main()
