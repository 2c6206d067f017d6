#!/usr/bin/python3
"""Spindrift's speed-against-error benchmark: one command that regenerates docs/benchmarks.md and its plots.

    tests/bench/benchmark.py [--quick] [--output DIR] [--work build/bench]

Bakes the examples and renders the Cycles references where they are missing (git-ignored, under --work),
runs every configuration of the sweep through `build/bin/spindrift render --set ... --stats`, VTK's fluid
mapper and Cycles at increasing sample counts on the same frames, measures the scaling with particle count and
resolution, runs the stability suite, and writes OUTPUT/benchmarks.md and OUTPUT/images/bench_*.png.
`--quick` is a smoke run of a tiny subset (one example, one camera, few settings, one repeat); it writes its page
to WORK/quick/ (and its results to WORK/results_quick.json), never over the committed docs/benchmarks.md.
"""

import argparse
import json
import os
import platform
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bigger_bake  # noqa: E402
import report  # noqa: E402
import runs  # noqa: E402
import scaling  # noqa: E402
import sweep  # noqa: E402
import users_render  # noqa: E402

EXAMPLES = ("dam_break", "drop")


def parse_arguments():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--quick", action="store_true", help="a smoke run of a tiny subset")
    parser.add_argument("--output", help="where the page and its images go (default: docs, or WORK/quick with "
                                           "--quick)")
    parser.add_argument("--work", default=os.path.join(runs.REPOSITORY, "build", "bench"))
    parser.add_argument("--blender", default="blender")
    parser.add_argument("--sweep-only", action="store_true",
                        help="the Spindrift sweep and Cycles' sample points only: no VTK, scaling or stability suite")
    parser.add_argument("--report-only", action="store_true",
                        help="rewrite the page and plots from WORK/results.json without running anything")
    # Filters for a partial run on a busy machine; the page records what was left out.
    parser.add_argument("--examples", default="", help="comma-separated examples (default: the plan's)")
    parser.add_argument("--cameras", default="", help="comma-separated cameras (default: the plan's)")
    parser.add_argument("--configurations", default="",
                        help="semicolon-separated labels of Spindrift settings to run (labels hold commas; default: all)")
    parser.add_argument("--reference-spp", type=int, default=0, help="Cycles reference samples (default: the plan's)")
    parser.add_argument("--background-spp", type=int, default=0, help="background samples (default: the plan's)")
    parser.add_argument("--sweep-spp", default="", help="comma-separated Cycles sweep sample counts")
    parser.add_argument("--repeats", type=int, default=0, help="timed runs per setting (default: the plan's)")
    parser.add_argument("--no-vtk", action="store_true", help="leave VTK's fluid mapper out")
    parser.add_argument("--no-scaling", action="store_true", help="leave the scaling measurements out")
    arguments = parser.parse_args()
    if arguments.output is None:
        arguments.output = (os.path.join(arguments.work, "quick") if arguments.quick
                            else os.path.join(runs.REPOSITORY, "docs"))
    os.makedirs(os.path.join(arguments.output, "images"), exist_ok=True)
    return arguments


def results_path(arguments):
    """A quick run keeps its results apart, so it never replaces a full run's for --report-only."""
    return os.path.join(arguments.work, "results_quick.json" if arguments.quick else "results.json")


def apply_filters(plan, arguments):
    """Narrows the plan to what the filters name and records them, so the page says what was run."""
    filters = {}
    for key in ("examples", "cameras"):
        value = getattr(arguments, key)
        if value:
            plan[key] = value.split(",")
            filters[key] = value
    if arguments.configurations:
        wanted = arguments.configurations.split(";")
        plan["configurations"] = [c for c in plan["configurations"] if c[0] in wanted]
        filters["configurations"] = arguments.configurations
    for key in ("reference_spp", "background_spp", "repeats"):
        value = getattr(arguments, key)
        if value:
            plan[key] = value
            filters[key] = value
    if arguments.sweep_spp:
        plan["sweep_spp"] = [int(v) for v in arguments.sweep_spp.split(",")]
        filters["sweep_spp"] = arguments.sweep_spp
    if arguments.no_vtk:
        plan["vtk_filters"] = []
        filters["vtk"] = "off"
    if arguments.no_scaling:
        filters["scaling"] = "off"
    plan["filters"] = filters
    return plan


def log(message):
    print(f"[benchmark] {message}", flush=True)


def blender(arguments, script, *script_arguments):
    command = [arguments.blender, "-b", "--factory-startup", "--python-exit-code", "1", "--python", script,
               "--", *script_arguments]
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        raise RuntimeError(f"{' '.join(command)} failed:\n{result.stdout[-3000:]}\n{result.stderr[-2000:]}")


def references_directory(work, example, plan):
    """One directory per example, size and sample count, so a quick run's noisy references never stand in
    for a full run's (a reference is rendered only where its file is missing)."""
    return os.path.join(work, "references",
                        f"{example}_{plan['width']}x{plan['height']}_{plan['reference_spp']}spp")


def prepare_example(arguments, example, plan, absorption_rgb):
    """Bakes the example if its cache is missing and renders whatever references are missing."""
    directory = os.path.join(runs.REPOSITORY, "examples", example)
    if not os.path.isdir(os.path.join(directory, "cache", "mesh")):
        log(f"{example}: baking the Mantaflow cache")
        # The whole script, renders included, as a user runs it: run with --skip-render from here, the bake left
        # an empty cache directory behind (seen once with Blender 3.4.1; the cause was not pinned down).
        blender(arguments, os.path.join(directory, "bake.py"), "--output", directory)
    references = references_directory(arguments.work, example, plan)
    started = time.perf_counter()
    blender(arguments, os.path.join(runs.REPOSITORY, "tests", "bench", "references.py"),
            "--example", directory, "--output", references, "--cameras", ",".join(plan["cameras"]),
            "--width", str(plan["width"]), "--height", str(plan["height"]),
            "--background-spp", str(plan["background_spp"]), "--reference-spp", str(plan["reference_spp"]),
            "--sweep-camera", plan["cameras"][0], "--sweep-spp", ",".join(map(str, plan["sweep_spp"])),
            "--absorption-rgb", ",".join(map(str, absorption_rgb)),
            # Cycles' sweep is timed again in every run, so its times and Spindrift's share the host's state.
            "--retime-sweep",
            *(["--full-references"] if plan.get("users_render") else []))
    if plan.get("users_render"):
        render_whitewater_references(arguments, example, plan, absorption_rgb, references)
    log(f"{example}: references ready ({time.perf_counter() - started:.0f} s)")
    return references


def render_whitewater_references(arguments, example, plan, absorption_rgb, references):
    """The user's render with the example's whitewater as white spheres (references.py --whitewater), where
    missing: read with Spindrift's loader from the scene file the first references.py run wrote."""
    if all(os.path.isfile(os.path.join(references, camera, users_render.WHITEWATER_REFERENCE))
           for camera in plan["cameras"]):
        return
    scene = os.path.join(references, plan["cameras"][0], "scene.json")
    frame = json.load(open(scene))["frame"]
    ply = os.path.join(references, f"whitewater_{frame:04d}.ply")
    exported = subprocess.run([runs.EXPORT_PARTICLES, scene, str(frame), ply, "whitewater"], check=True,
                              capture_output=True, text=True)
    if exported.stdout.startswith("0 "):
        log(f"{example}: no whitewater, no reference with it")
        return
    blender(arguments, os.path.join(runs.REPOSITORY, "tests", "bench", "references.py"),
            "--example", os.path.join(runs.REPOSITORY, "examples", example), "--output", references,
            "--cameras", ",".join(plan["cameras"]), "--width", str(plan["width"]), "--height", str(plan["height"]),
            "--background-spp", str(plan["background_spp"]), "--reference-spp", str(plan["reference_spp"]),
            "--absorption-rgb", ",".join(map(str, absorption_rgb)), "--full-references", "--whitewater", ply)


def machine_description():
    cpu = "?"
    if os.path.isfile("/proc/cpuinfo"):
        names = [line.split(":", 1)[1].strip() for line in open("/proc/cpuinfo") if line.startswith("model name")]
        cpu = f"{names[0]} ({len(names)} logical cores)" if names else cpu
    memory = "?"
    if os.path.isfile("/proc/meminfo"):
        kib = int(open("/proc/meminfo").readline().split()[1])
        memory = f"{kib / 1024 ** 2:.0f} GiB"
    blender_version = subprocess.run(["blender", "--version"], capture_output=True, text=True).stdout
    return {"cpu": cpu, "memory": memory, "os": platform.platform(), "gl_renderer": runs.gl_renderer(),
            "blender": blender_version.splitlines()[0] if blender_version else "?",
            "load_average": os.getloadavg()}


def run_stability_suite(work):
    """The hard cases (and the closed-form accuracy tests, whose errors they record) as gtest JSON."""
    binary = os.path.join(runs.REPOSITORY, "build", "bin", "spindrift_tests")
    output = os.path.join(work, "stability.json")
    if not os.path.isfile(binary):
        return None
    subprocess.run([binary, "--gtest_filter=GLLiquidStability.*:GLLiquidAccuracy.*",
                    f"--gtest_output=json:{output}"], capture_output=True)
    return json.load(open(output)) if os.path.isfile(output) else None


def main():
    arguments = parse_arguments()
    os.makedirs(arguments.work, exist_ok=True)
    if arguments.report_only:
        results = json.load(open(results_path(arguments)))
        report.write(results, arguments.output, results["plan"].get("quick", False))
        return
    started = time.perf_counter()
    plan = apply_filters(sweep.plan(arguments.quick), arguments)
    plan["quick"] = arguments.quick
    if arguments.examples:
        plan["examples"] = arguments.examples.split(",")
    if arguments.configurations:
        plan["only_configurations"] = arguments.configurations.split(";")
    plan["sweep_only"] = arguments.sweep_only
    subset = bool(arguments.examples or arguments.configurations or arguments.sweep_only)
    plan["subset"] = subset
    if subset and os.path.abspath(arguments.output) == os.path.abspath(os.path.join(runs.REPOSITORY, "docs")):
        sys.exit("a subset run must not overwrite docs/benchmarks.md: give --output")
    table = runs.parameter_table()
    absorption = runs.absorption_from(table)
    machine = machine_description()
    log(f"renderer: {machine['gl_renderer']}; {machine['cpu']}")

    results = {"machine": machine, "plan": plan, "examples": {}}
    for example in plan["examples"]:
        references = prepare_example(arguments, example, plan, absorption)
        log(f"{example}: Spindrift configurations")
        spindrift_rows = sweep.run_configurations(example, references, plan, table, arguments.work)
        log(f"{example}: Cycles sample sweep and VTK")
        results["examples"][example] = {
            "spindrift": spindrift_rows,
            "cycles": sweep.cycles_points(references, plan),
            "vtk": [] if arguments.sweep_only else sweep.vtk_points(example, references, plan, absorption,
                                                                      arguments.work),
        }
        if plan.get("users_render") and not arguments.sweep_only:
            log(f"{example}: against the user's render (the water casting its shadow)")
            results["examples"][example]["users_render"] = users_render.compare(
                example, references, plan, results["examples"][example]["vtk"], arguments.work)
    if arguments.sweep_only:
        results["scaling"] = results["stability"] = None
        finish(results, arguments, started)
        return

    if arguments.no_scaling:
        results["scaling"] = None
    else:
        log("scaling")
        base_scene = os.path.join(references_directory(arguments.work, plan["examples"][0], plan),
                                  plan["cameras"][0], "scene.json")
        scaling_work = os.path.join(arguments.work, "scaling")
        os.makedirs(scaling_work, exist_ok=True)
        mantaflow_ply = runs.export_particles(base_scene, json.load(open(base_scene))["frame"],
                                              os.path.join(scaling_work, "mantaflow.ply"))
        particle_rows = scaling.particle_scaling(base_scene, mantaflow_ply, plan["particle_counts"],
                                                 plan["particle_repeats"], scaling_work)
        resolution_rows = scaling.resolution_scaling(base_scene, plan["resolutions"], plan["resolution_repeats"],
                                                     scaling_work)
        results["scaling"] = {"particles": particle_rows, "resolutions": resolution_rows,
                              "slopes": scaling.slopes(particle_rows, resolution_rows)}
        log("a bigger bake against VTK")
        results["bigger_bake"] = bigger_bake.compare(
            base_scene, os.path.dirname(base_scene), mantaflow_ply, plan["bigger_bake_count"], plan["repeats"],
            absorption, plan["vtk_filters"], arguments.work)

    log("stability suite")
    results["stability"] = run_stability_suite(arguments.work)
    finish(results, arguments, started)


def finish(results, arguments, started):
    results["runtime_s"] = time.perf_counter() - started
    results["machine"]["load_average_at_end"] = os.getloadavg()
    # A subset's results stay beside its page, so they never replace a full run's under WORK.
    path = (os.path.join(arguments.output, "results.json") if results["plan"].get("subset")
            else results_path(arguments))
    with open(path, "w") as handle:
        json.dump(results, handle, indent=1, default=str)
    report.write(results, arguments.output, results["plan"]["quick"])
    log(f"done in {results['runtime_s'] / 60:.1f} min: {os.path.join(arguments.output, 'benchmarks.md')}")


if __name__ == "__main__":
    main()
