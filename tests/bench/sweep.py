"""What the benchmark runs: the plan (full or quick), Spindrift's configurations, Cycles' sample counts and
VTK's fluid mapper, each measured on the same frames against the same Cycles references."""

import json
import os

import runs

CAMERAS = ["oblique", "closeup", "topdown", "grazing"]


def plan(quick):
    """Sizes of the run. The full run is sized to take about 35 minutes on 2 cores with llvmpipe."""
    if quick:
        return {"examples": ["dam_break"], "cameras": ["oblique"], "width": 480, "height": 270,
                "background_spp": 16, "reference_spp": 32, "sweep_spp": [1, 4], "repeats": 1,
                "configurations": configurations(quick=True), "vtk_filters": ["narrow_range"],
                "particle_counts": [10_000, 100_000], "particle_repeats": lambda count: 1,
                "resolutions": [(854, 480), (1280, 720)], "resolution_repeats": lambda pixels: 1,
                "bigger_bake_count": 30_000, "users_render": False}
    return {"examples": ["dam_break", "drop"], "cameras": CAMERAS, "width": 480, "height": 270,
            "background_spp": 64, "reference_spp": 256, "sweep_spp": [1, 4, 16, 64], "repeats": 5,
            "configurations": configurations(quick=False), "vtk_filters": ["narrow_range", "bilateral"],
            "particle_counts": [10_000, 30_000, 100_000, 300_000, 1_000_000, 4_000_000],
            "particle_repeats": lambda count: 3 if count <= 300_000 else 1,
            "resolutions": [(854, 480), (1280, 720), (1920, 1080), (3840, 2160)],
            "resolution_repeats": lambda pixels: 3 if pixels <= 1280 * 720 else 1,
            "bigger_bake_count": 150_000,
            # The examples against Cycles with the water's shadow (users_render.py): about 5 minutes of Cycles
            # the first time, 2 of Spindrift and VTK.
            "users_render": True}


# What the sweep's reference leaves out, left out of every run scored against it or timed beside the sweep
# (scaling, the bigger bake): the world's light alone, which the examples' scene files, naming no lamp, would
# otherwise take (see configurations).
AS_THE_REFERENCE = runs.WORLD_LIGHT_OFF


def configurations(quick):
    """(label, settings, foam) for every point of the sweep. The defaults (plane_fit, 3 iterations, window 9,
    4 refractions, layers split, foam on) are the centre; every other axis varies one thing from them."""
    # The sweep's reference is Cycles with the water casting no shadow, of the sun or the sky: the sweep leaves
    # the world's light alone untaken too (light.sky_without_lamps), as the scene files' missing sun would
    # otherwise be taken for it. The default, which takes it, is scored against the user's render
    # (users_render.py; docs/liquid.md, "The world's light alone").
    default = {"liquid.smoothing": "plane_fit", "liquid.smoothing_iterations": 3, "liquid.plane_fit_window": 9,
               "liquid.max_refractions": 4, "liquid.layers": "split", **AS_THE_REFERENCE}

    def variant(label, foam=True, **changes):
        settings = dict(default)
        settings.update({f"liquid.{key}": value for key, value in changes.items()})
        return label, settings, foam

    # The ray-marched surface (docs/raymarch.md) beside the screen-space one: its defaults, and the two
    # baselines its adaptive parts are measured against (uniform steps; every pixel cast).
    raymarch = [variant("raymarch", surface="raymarch"),
                variant("raymarch uniform steps", surface="raymarch", raymarch_stepping="uniform"),
                variant("raymarch full resolution", surface="raymarch", raymarch_resolution="full")]
    if quick:
        return [variant("plane_fit i3 w9"), variant("none", smoothing="none"),
                variant("max_refractions 1", max_refractions=1), variant("plane_fit, foam off", foam=False),
                raymarch[0]]
    points = [variant(f"plane_fit i{i} w{w}", smoothing_iterations=i, plane_fit_window=w)
              for i in (1, 3, 5) for w in (5, 9, 15)]
    points += [variant(f"{method} i{i}", smoothing=method, smoothing_iterations=i)
               for method in ("bilateral", "narrow_range") for i in (1, 3)]
    points += [variant(f"curvature_flow s{steps}", smoothing="curvature_flow", curvature_flow_steps=steps)
               for steps in (20, 60)]
    points += [variant("none", smoothing="none")]
    points += [variant(f"max_refractions {n}", max_refractions=n) for n in (1, 2)]
    points += [variant("layers merged", layers="merged"), variant("plane_fit, foam off", foam=False)]
    # The foam's shadow and irradiance estimated at every foam pixel, as the paper does (the default makes one
    # estimate per 2 x 2 block, docs/foam.md).
    label, settings, foam = variant("plane_fit, foam per pixel")
    points.append((label, {**settings, "foam.occlusion_block": 1}, foam))
    # Each smoothing method without the surface the Mantaflow domain derives (offset and splash sizes): the
    # particles drawn at their radius alone, as every method was before issue 9 (docs/mantaflow-caches.md).
    points += [variant(f"{label}, no offset", surface_offset=0.0, mesh_kernel_radius=0.0, **changes)
               for label, changes in
               (("plane_fit i3 w9", {}), ("bilateral i1", {"smoothing": "bilateral", "smoothing_iterations": 1}),
                ("narrow_range i1", {"smoothing": "narrow_range", "smoothing_iterations": 1}),
                ("curvature_flow s20", {"smoothing": "curvature_flow", "curvature_flow_steps": 20}),
                ("none", {"smoothing": "none"}))]
    return points + raymarch


def scene_for(camera_directory, foam):
    """The camera's scene file, or a copy without the foam sources (foam off) beside it."""
    scene = os.path.join(camera_directory, "scene.json")
    if foam:
        return scene
    description = json.load(open(scene))
    description["particles"] = [p for p in description["particles"] if p.get("role", "liquid") != "foam"]
    without_foam = os.path.join(camera_directory, "scene_without_foam.json")
    with open(without_foam, "w") as handle:
        json.dump(description, handle, indent=1)
    return without_foam


def liquid_radius(scene, stats_path):
    """The liquid's radius r, the unit of the depth errors: the scene's, or the one Spindrift derived from the
    Mantaflow domain (its --stats say which)."""
    description = json.load(open(scene))
    source = next(p for p in description["particles"] if p.get("role", "liquid") == "liquid")
    if "radius" in source:
        return source["radius"]
    return json.load(open(stats_path))["liquid_sources"][0]["radius"]


def run_configurations(example, references, plan, table, work):
    rows = []
    wanted = plan.get("only_configurations")
    work_directory = os.path.join(work, "runs", example)
    os.makedirs(work_directory, exist_ok=True)
    for label, settings, foam in plan["configurations"]:
        if wanted and label not in wanted:
            continue
        why_not = runs.unsupported_settings(settings, table)
        if why_not and "liquid.layers" in settings and settings["liquid.layers"] == "split":
            # Builds without the layers parameter always split: drop the default rather than skip the point.
            settings = {k: v for k, v in settings.items() if k != "liquid.layers"}
            why_not = runs.unsupported_settings(settings, table)
        if why_not:
            rows.append({"label": label, "settings": settings, "foam": foam, "skipped": why_not})
            print(f"  {label}: skipped ({why_not})", flush=True)
            continue
        per_camera, timing = [], None
        for index, camera in enumerate(plan["cameras"]):
            camera_directory = os.path.join(references, camera)
            scene = scene_for(camera_directory, foam)
            exr = os.path.join(work_directory, f"{camera}.exr")
            # Timing on the first camera; one run on each other camera for its errors.
            repeats = plan["repeats"] if index == 0 else 1
            measured = runs.timed_spindrift(scene, exr, settings, repeats, work_directory)
            timing = timing or measured
            radius = liquid_radius(scene, os.path.join(work_directory, "stats_0.json"))
            per_camera.append(runs.frame_errors(exr, camera_directory, radius, runs.SPINDRIFT_CHANNELS))
        errors = runs.mean_errors(per_camera)
        rows.append({"label": label, "settings": settings, "foam": foam, "timing": timing, "errors": errors,
                     "per_camera": dict(zip(plan["cameras"], per_camera))})
        print(f"  {label}: {timing['total_ms']:.0f} ms/frame, MAE {errors['mae']:.4f}, "
              f"depth {errors['depth_median_r']:.2f} r", flush=True)
    return rows


def cycles_points(references, plan):
    camera_directory = os.path.join(references, plan["cameras"][0])
    timings = json.load(open(os.path.join(camera_directory, "cycles_timings.json")))
    points = []
    for samples in plan["sweep_spp"]:
        exr = os.path.join(camera_directory, f"cycles_spp_{samples:04d}.exr")
        errors = runs.frame_errors(exr, camera_directory, 1.0,
                                   {"composite": ["Combined.R", "Combined.G", "Combined.B"]})
        # "earlier": the times this run replaced (references.py --retime-sweep), for the page to show the drift.
        points.append({"spp": samples, "time_s": timings[str(samples)],
                       "earlier_time_s": timings.get("earlier", {}).get(str(samples)), **errors})
    return points


def vtk_npz(work, example, camera, filter_name):
    """Where vtk_points keeps a camera's VTK render (its composite, as run_vtk writes it)."""
    return os.path.join(work, "vtk", example, f"{camera}_{filter_name}.npz")


def vtk_points(example, references, plan, absorption, work):
    work_directory = os.path.join(work, "vtk", example)
    os.makedirs(work_directory, exist_ok=True)
    first_scene = os.path.join(references, plan["cameras"][0], "scene.json")
    particles = runs.export_particles(first_scene, json.load(open(first_scene))["frame"],
                                      os.path.join(work_directory, "particles.ply"))
    rows = []
    for filter_name in plan["vtk_filters"]:
        per_camera, timing = [], None
        for index, camera in enumerate(plan["cameras"]):
            camera_directory = os.path.join(references, camera)
            composite, frame_ms, first_ms, renderer = runs.run_vtk(
                os.path.join(camera_directory, "scene.json"), particles,
                vtk_npz(work, example, camera, filter_name), plan["repeats"] if index == 0 else 1,
                filter_name, absorption)
            timing = timing or {"frame_ms": frame_ms, "first_frame_ms": first_ms, "gl_renderer": renderer}
            per_camera.append(runs.frame_errors(None, camera_directory, 1.0, {"composite_array": composite}))
        rows.append({"label": f"VTK {filter_name}", "filter": filter_name, **timing,
                     "errors": runs.mean_errors(per_camera)})
        print(f"  VTK {filter_name}: {timing['frame_ms']:.0f} ms/frame, MAE {rows[-1]['errors']['mae']:.4f}",
              flush=True)
    return rows


def error_of(row):
    """The error axis shared by all three renderers: mean absolute error of the composite over liquid."""
    return row["errors"]["mae"] if "errors" in row else row["mae"]

