"""A bigger bake against VTK's fluid mapper, side by side (issue 11's second target): the dam-break frame
resampled to more particles (scaling.resampled_particles), liquid only, rendered by Spindrift's defaults and by
VTK's mapper from the same PLY, camera and background, and scored against the same Cycles reference.

Spindrift is timed two ways: a fresh process's only frame (as the benchmark's tables time it) and the later
frames of a sequence of the same frame in one process (each pass finished), which is what VTK's timing is:
its renders after one warm-up render.

    tests/bench/bigger_bake.py [--count 150000] [--repeats 3]    # writes build/bench/bigger_bake.json
"""

import argparse
import json
import os
import statistics
import subprocess

import runs
import sweep
import scaling

DEFAULT_COUNT = 150_000


def steady_frame_ms(scene, work_directory, frames=5, reuse_shapes=True):
    """Median total_ms of frames 2..frames of one process rendering the same frame again (passes finished),
    read back and written nowhere, as VTK's renders are timed. With reuse_shapes, each keeps the shapes of the
    frame before (what a re-render of unchanged particles costs, as VTK's re-renders do); without, each frame
    shapes them anew (what a sequence's new particles cost)."""
    stats = os.path.join(work_directory, "steady_####.json")
    command = [runs.SPINDRIFT, "render", scene, "--stats", stats, "--frames", f"1-{frames}", "-q",
               "--set", f"liquid.reuse_shapes={'true' if reuse_shapes else 'false'}",
               *runs.set_arguments(sweep.AS_THE_REFERENCE)]
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL,
                   env=dict(os.environ, SPINDRIFT_FINISH_PASSES="1"))
    totals = []
    for frame in range(2, frames + 1):
        with open(stats.replace("####", f"{frame:04d}")) as handle:
            totals.append(json.load(handle)["total_ms"])
    return statistics.median(totals)


def compare(base_scene, camera_directory, mantaflow_ply, count, repeats, absorption, vtk_filters, work):
    """Rows for Spindrift and each VTK filter on `count` resampled particles; errors against the camera's
    Cycles reference."""
    work_directory = os.path.join(work, "bigger_bake")
    os.makedirs(work_directory, exist_ok=True)
    positions, radius = scaling.resampled_particles(scaling.read_ply(mantaflow_ply), count)
    ply = os.path.join(work_directory, f"resampled_{count}.ply")
    scaling.write_ply(ply, positions, radius)
    scene = scaling.scene_with(base_scene, ply_path=ply, output_path=os.path.join(work_directory, "scene.json"))
    exr = os.path.join(work_directory, "spindrift.exr")
    timing = runs.timed_spindrift(scene, exr, sweep.AS_THE_REFERENCE, repeats, work_directory)
    errors = runs.frame_errors(exr, camera_directory, radius, runs.SPINDRIFT_CHANNELS)
    rows = [{"label": "Spindrift (defaults; light.sky_without_lamps off, as the reference)", "frame_ms": timing["total_ms"],
             "steady_frame_ms": steady_frame_ms(scene, work_directory),
             "steady_new_particles_ms": steady_frame_ms(scene, work_directory, reuse_shapes=False),
             "mae": errors["mae"],
             "iou": errors["iou"], "gl_renderer": timing["gl_renderer"]}]
    for filter_name in vtk_filters:
        composite, frame_ms, first_ms, renderer = runs.run_vtk(
            scene, ply, os.path.join(work_directory, f"vtk_{filter_name}.npz"), repeats, filter_name, absorption)
        vtk_errors = runs.frame_errors(None, camera_directory, radius, {"composite_array": composite})
        rows.append({"label": f"VTK {filter_name}", "frame_ms": first_ms, "steady_frame_ms": frame_ms,
                     "mae": vtk_errors["mae"], "iou": float("nan"), "gl_renderer": renderer})
    for row in rows:
        print(f"  bigger bake {row['label']}: {row['steady_frame_ms']:.0f} ms/frame steady, "
              f"{row['frame_ms']:.0f} ms first, MAE {row['mae']:.4f}", flush=True)
    return {"count": count, "radius": radius, "camera": os.path.basename(camera_directory), "rows": rows}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--count", type=int, default=DEFAULT_COUNT)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--work", default=os.path.join(runs.REPOSITORY, "build", "bench"))
    parser.add_argument("--references", default="dam_break_480x270_256spp",
                        help="the directory under WORK/references whose first camera is used")
    arguments = parser.parse_args()
    camera_directory = os.path.join(arguments.work, "references", arguments.references, "oblique")
    base_scene = os.path.join(camera_directory, "scene.json")
    scaling_work = os.path.join(arguments.work, "scaling")
    os.makedirs(scaling_work, exist_ok=True)
    mantaflow_ply = runs.export_particles(base_scene, json.load(open(base_scene))["frame"],
                                          os.path.join(scaling_work, "mantaflow.ply"))
    absorption = runs.absorption_from(runs.parameter_table())
    result = compare(base_scene, camera_directory, mantaflow_ply, arguments.count, arguments.repeats, absorption,
                     ["narrow_range", "bilateral"], arguments.work)
    with open(os.path.join(arguments.work, "bigger_bake.json"), "w") as handle:
        json.dump(result, handle, indent=1)


if __name__ == "__main__":
    main()
