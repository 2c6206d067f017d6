"""The examples against the user's own render (issue 10's scope 6): Cycles with the water casting its shadow
and caustics, as a user's render of the example has them, beside the benchmark's reference without them.

For every camera, each renderer is scored against both references (references.py --full-references):

- Spindrift without lights and without the world's light (light.sky_without_lamps off): the benchmark's scene
  file, over the background render, as the main sweep runs it;
- Spindrift's defaults on that scene file, which names no lamp: the world's light alone is taken, the whole
  background counted as sky light (docs/liquid.md, "The world's light alone");
- Spindrift's defaults with the example's sun (scene_sun.json, as the Blender add-on exports the scene's lamps)
  over the background with Cycles' light passes: the liquid's shadow, caustics and sky occlusion applied;
- VTK's fluid mapper (the plan's first filter; the renders sweep.vtk_points made), which has no light model;
- on the first camera, Cycles' sample sweep rendered with the water's shadow, timed as the main sweep is.

A third reference, where the example has whitewater, is the user's render with it: every spray, foam and bubble
particle a white diffuse sphere of its radius (references.py --whitewater; tests/bench/foam_light.py). The
others have no foam, so Spindrift's foam counts as error against them.

Times are Spindrift's frame (`total_ms`, median of the plan's repeats on the first camera).
"""

import json
import os

import numpy as np

import runs
import sweep

COMPOSITE = {"composite": ["composite.R", "composite.G", "composite.B"]}
CYCLES = {"composite": ["Combined.R", "Combined.G", "Combined.B"]}
WHITEWATER_REFERENCE = "reference_full_whitewater.exr"
# The user's render with the example's whitewater as white diffuse spheres (references.py --whitewater) is
# scored where the example has it: the only reference in which foam is anything but error.
REFERENCES = {"no_shadow": "reference.exr", "full": "reference_full.exr", "whitewater": WHITEWATER_REFERENCE}
SPINDRIFT_VARIANTS = [("Spindrift, no lights", "scene.json", runs.WORLD_LIGHT_OFF),
                      ("Spindrift, no lamps: the world's light alone (defaults)", "scene.json", {}),
                      ("Spindrift, the sun with light passes", "scene_sun.json", {})]


def scores(camera_directory, test_exr=None, composite=None):
    """Image MAE against each reference."""
    names = COMPOSITE if composite is None else {"composite_array": composite}
    return {key: runs.frame_errors(test_exr, camera_directory, 1.0, names, reference=name)["mae"]
            for key, name in REFERENCES.items() if os.path.isfile(os.path.join(camera_directory, name))}


def mean_scores(per_camera):
    return {key: float(np.mean([camera[key] for camera in per_camera])) for key in REFERENCES
            if all(key in camera for camera in per_camera)}


def compare(example, references, plan, vtk_rows, work):
    """Rows for each renderer (mean MAE over the cameras against each reference, per-camera MAEs, time) and
    Cycles' sweep with the shadow against the full reference."""
    work_directory = os.path.join(work, "users_render", example)
    os.makedirs(work_directory, exist_ok=True)
    rows = []
    for variant, (label, scene_name, settings) in enumerate(SPINDRIFT_VARIANTS):
        per_camera, timing = [], None
        for index, camera in enumerate(plan["cameras"]):
            camera_directory = os.path.join(references, camera)
            exr = os.path.join(work_directory, f"{camera}_{scene_name.replace('.json', '')}_{variant}.exr")
            measured = runs.timed_spindrift(os.path.join(camera_directory, scene_name), exr, settings,
                                            plan["repeats"] if index == 0 else 1, work_directory)
            timing = timing or measured
            per_camera.append(scores(camera_directory, test_exr=exr))
        rows.append({"label": label, "frame_ms": timing["total_ms"], "mae": mean_scores(per_camera),
                     "per_camera": dict(zip(plan["cameras"], per_camera))})
    vtk = vtk_rows[0]
    per_camera = [scores(os.path.join(references, camera),
                         composite=np.load(sweep.vtk_npz(work, example, camera, vtk["filter"]))["composite"])
                  for camera in plan["cameras"]]
    rows.append({"label": vtk["label"], "frame_ms": vtk["frame_ms"], "mae": mean_scores(per_camera),
                 "per_camera": dict(zip(plan["cameras"], per_camera))})
    for row in rows:
        print(f"  {row['label']}: MAE {row['mae']['no_shadow']:.4f} against the reference without the water's "
              f"shadow, {row['mae']['full']:.4f} against the user's render", flush=True)
    return {"rows": rows, "cycles_full": cycles_full_points(references, plan)}


def cycles_full_points(references, plan):
    """Cycles' sweep with the water's shadow on the first camera, against the full reference."""
    camera_directory = os.path.join(references, plan["cameras"][0])
    with open(os.path.join(camera_directory, "cycles_full_timings.json")) as handle:
        timings = json.load(handle)
    points = []
    for samples in plan["sweep_spp"]:
        exr = os.path.join(camera_directory, f"cycles_full_spp_{samples:04d}.exr")
        mae = runs.frame_errors(exr, camera_directory, 1.0, CYCLES, reference=REFERENCES["full"])["mae"]
        points.append({"spp": samples, "time_s": timings[str(samples)], "mae": mae})
    return points
