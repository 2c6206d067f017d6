"""Running the renderers the benchmark compares, and measuring one run: Spindrift's CLI, VTK's fluid mapper.

Every Spindrift run is `build/bin/spindrift render SCENE -o EXR --stats JSON --set key=value ...`, exactly
what a user runs, so the benchmark measures whatever the renderer does at the commit it is run on.
"""

import json
import os
import shutil
import statistics
import subprocess
import threading
import time

import numpy as np

import metrics

REPOSITORY = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
SPINDRIFT = os.path.join(REPOSITORY, "build", "bin", "spindrift")
EXPORT_PARTICLES = os.path.join(REPOSITORY, "build", "bin", "spindrift_export_particles")
VTK_SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "vtk_fluid.py")


def parameter_table():
    """`spindrift params` as {key: entry}: which parameters and choices this build has."""
    output = subprocess.run([SPINDRIFT, "params"], check=True, capture_output=True, text=True).stdout
    return {entry["key"]: entry for entry in json.loads(output)}


def absorption_from(table):
    """a * c_a, the per-unit-length absorption the Cycles water must match (parameter defaults)."""
    a = table["liquid.absorption"]["default"]
    return [a * c for c in table["liquid.absorption_rgb"]["default"]]


def unsupported_settings(settings, table):
    """Why a configuration cannot run on this build (a parameter or choice it lacks), or None."""
    for key, value in settings.items():
        if key not in table:
            return f"no parameter {key} in this build"
        choices = table[key].get("choices") or []
        if choices and value not in choices:
            return f"{key} has no choice {value} in this build"
    return None


def gl_renderer():
    output = subprocess.run([SPINDRIFT, "info"], check=True, capture_output=True, text=True).stdout
    return next((line.split(":", 1)[1].strip() for line in output.splitlines() if "renderer" in line), "?")


class GpuMemorySampler:
    """Peak GPU memory of the machine while a run lasts, from nvidia-smi; None where there is none (llvmpipe
    draws in host memory, which the child's peak RSS already counts)."""

    def __init__(self):
        self.available = shutil.which("nvidia-smi") is not None
        self.peak_mib = None
        self._stop = threading.Event()

    def _sample(self):
        while not self._stop.is_set():
            output = subprocess.run(["nvidia-smi", "--query-gpu=memory.used", "--format=csv,noheader,nounits"],
                                    capture_output=True, text=True).stdout.split()
            if output:
                self.peak_mib = max(self.peak_mib or 0.0, float(output[0]))
            self._stop.wait(0.1)

    def __enter__(self):
        if self.available:
            self._thread = threading.Thread(target=self._sample, daemon=True)
            self._thread.start()
        return self

    def __exit__(self, *_):
        if self.available:
            self._stop.set()
            self._thread.join()


# The world's light alone left untaken (light.sky_without_lamps off): the background of a scene without lamps
# as it is, as before the parameter. The benchmark's examples name no lamp but have a sun in their backgrounds,
# which the default would take for the world's light (docs/liquid.md, "The world's light alone").
WORLD_LIGHT_OFF = {"light.sky_without_lamps": False}


def set_arguments(settings):
    """`spindrift render`'s --set arguments for a {parameter: value} dict (values as JSON)."""
    return [argument for key, value in settings.items() for argument in ("--set", f"{key}={json.dumps(value)}")]


def run_spindrift(scene, exr, settings, stats_path):
    """One end-to-end run; returns (wall seconds, stats dict, peak host RSS MiB, peak GPU MiB or None)."""
    command = [SPINDRIFT, "render", scene, "-o", exr, "--stats", stats_path, "-q", *set_arguments(settings)]
    with GpuMemorySampler() as gpu:
        started = time.perf_counter()
        process = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        _, status, usage = os.wait4(process.pid, 0)
        wall = time.perf_counter() - started
    process.returncode = os.waitstatus_to_exitcode(status)
    if process.returncode != 0:
        raise RuntimeError(f"{' '.join(command)} failed: {process.stderr.read().strip()}")
    with open(stats_path) as handle:
        stats = json.load(handle)
    return wall, stats, usage.ru_maxrss / 1024.0, gpu.peak_mib


def warm_frame_ms(scene, settings, work_directory):
    """The scene's frame rendered three times in one process, its particles shaped anew each time
    (liquid.reuse_shapes false, as a sequence's new particles are): the mean total_ms of the second and third,
    what a frame costs a renderer already running. VTK's frame ms (after a warm-up frame) and Cycles' render
    times (inside a running Blender) are measured so; the one-frame process's frame ms also pays for the
    process's first frame (shader variants, first touch of every page: docs/frame-cost.md, session 45)."""
    frame = json.load(open(scene)).get("frame", 1)
    stats_path = os.path.join(work_directory, "warm_stats.json")
    command = [SPINDRIFT, "render", scene, "--frames", f"{frame},{frame},{frame}", "--stats", stats_path, "-q",
               "--set", "liquid.reuse_shapes=false", *set_arguments(settings)]
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    with open(stats_path) as handle:
        frames = json.load(handle)["frames"]
    return statistics.mean(entry["total_ms"] for entry in frames[1:])


def timed_spindrift(scene, exr, settings, repeats, work_directory):
    """`repeats` runs (at least one); medians of wall time, total_ms and every pass's gpu_ms and cpu_ms; and
    warm_frame_ms."""
    walls, totals, passes, rss, gpu = [], [], {}, [], []
    for repeat in range(max(1, repeats)):
        stats_path = os.path.join(work_directory, f"stats_{repeat}.json")
        wall, stats, peak_rss, peak_gpu = run_spindrift(scene, exr, settings, stats_path)
        walls.append(wall)
        totals.append(stats["total_ms"])
        rss.append(peak_rss)
        gpu.append(peak_gpu)
        for entry in stats["passes"]:
            passes.setdefault(entry["name"], {"gpu_ms": [], "cpu_ms": []})
            passes[entry["name"]]["gpu_ms"].append(entry["gpu_ms"])
            passes[entry["name"]]["cpu_ms"].append(entry["cpu_ms"])
    return {
        "wall_s": statistics.median(walls),
        "total_ms": statistics.median(totals),
        "passes": {name: {k: statistics.median(v) for k, v in times.items()} for name, times in passes.items()},
        "peak_rss_mib": max(rss),
        "peak_gpu_mib": None if gpu[0] is None else max(gpu),
        "repeats": len(walls),
        "particles": stats.get("particles", {}),
        "gl_renderer": stats.get("gl_renderer", "?"),
        "raymarch": stats.get("raymarch"),  # steps per ray, rays cast, tiles (liquid.surface = raymarch)
        "warm_total_ms": warm_frame_ms(scene, settings, work_directory),
    }


def frame_errors(test_exr, camera_directory, radius, names, reference="reference.exr"):
    """Geometric and image metrics of one render against a camera's Cycles references.

    `names` maps the test file's channels: {"depth": ..., "normal": [x, y, z], "composite": [r, g, b]}; a
    render without depth and normals (VTK's) passes only "composite". `reference` names the image the colour
    is scored against (reference_full.exr: the water casting its shadow).
    """
    passes = metrics.read_channels(os.path.join(camera_directory, "liquid_passes.exr"),
                                   ["Depth.Z", "Normal.X", "Normal.Y", "Normal.Z"])
    reference_rgb = metrics.read_channels(os.path.join(camera_directory, reference),
                                          ["Combined.R", "Combined.G", "Combined.B"])
    solids = metrics.read_channels(os.path.join(camera_directory, "background.exr"), ["Depth.Z"])[..., 0]
    reference_depth = metrics.visible_depth(passes[..., 0], solids)
    reference_mask = metrics.liquid_mask(reference_depth)
    result = {}
    if "depth" in names:
        test = metrics.read_channels(test_exr, [names["depth"], *names["normal"]])
        result.update(metrics.geometry_metrics(metrics.visible_depth(test[..., 0], solids), test[..., 1:4],
                                               reference_depth, passes[..., 1:4], radius))
    test_rgb = names["composite_array"] if "composite_array" in names else \
        metrics.read_channels(test_exr, names["composite"])
    result["mae"], result["ssim"] = metrics.image_errors(test_rgb, reference_rgb, reference_mask)
    return result


SPINDRIFT_CHANNELS = {"depth": "depth.Z", "normal": ["normal.X", "normal.Y", "normal.Z"],
                      "composite": ["composite.R", "composite.G", "composite.B"]}


def mean_errors(per_camera):
    """The mean of each metric over cameras, ignoring NaN (a camera where a metric has no pixels)."""
    keys = per_camera[0].keys()
    return {key: float(np.nanmean([errors[key] for errors in per_camera])) for key in keys}


def run_vtk(scene, particles_ply, output_npz, repeats, filter_name, absorption_rgb):
    """VTK's fluid mapper on one frame under Xvfb; returns (composite, median frame ms, first frame ms, GL)."""
    command = ["xvfb-run", "-a", "-s", "-screen 0 1920x1080x24", "/usr/bin/python3", VTK_SCRIPT, scene,
               particles_ply, output_npz, "--repeats", str(repeats), "--filter", filter_name,
               "--absorption-rgb", ",".join(str(c) for c in absorption_rgb)]
    subprocess.run(command, check=True, capture_output=True, cwd=os.path.dirname(VTK_SCRIPT))
    result = np.load(output_npz)
    return (result["composite"], float(np.median(result["frame_ms"])), float(result["first_frame_ms"]),
            str(result["gl_renderer"]))


def export_particles(scene, frame, ply):
    if not os.path.isfile(ply):
        subprocess.run([EXPORT_PARTICLES, scene, str(frame), ply], check=True, capture_output=True)
    return ply

