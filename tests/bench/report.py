"""Writes docs/benchmarks.md and docs/images/bench_*.png from the benchmark's results."""

import math
import os

import plots

HERE = os.path.dirname(os.path.abspath(__file__))
# The README's "Benchmarks" section heads the page (one text, kept in the README); the notes on method are the
# benchmark's own.
README_FILE = os.path.join(HERE, "..", "..", "README.md")
NOTES_FILE = os.path.join(HERE, "method_notes.md")


def readme_benchmarks_section():
    """The README's "## Benchmarks" section, as the page's title and introduction."""
    text = open(README_FILE).read()
    start = text.index("## Benchmarks")
    end = text.find("\n## ", start + 1)
    section = text[start:end if end >= 0 else len(text)].strip()
    return "# Benchmarks" + section[len("## Benchmarks"):]


# The settings a user gets without --set: the parameter table's defaults (plane_fit, 3 iterations, 9x9,
# four refractions, split layers, foam on).
DEFAULT_LABEL = "plane_fit i3 w9"


def defaults_on_front(data):
    """Whether the default setting is on the Pareto front of Spindrift's settings (with foam) for frame time
    against each error, and which settings beat it where it is not."""
    rows = []
    settings = [entry for entry in data["spindrift"] if entry.get("foam", True) and entry.get("errors")]
    default = next((entry for entry in settings if entry["label"] == DEFAULT_LABEL), None)
    if default is None:
        return "The default setting was not measured."
    for key, name in (("mae", "image MAE"), ("normal_median_deg", "median normal error"),
                      ("depth_median_r", "median depth error")):
        time, error = default["timing"]["total_ms"], default["errors"][key]
        better = [entry["label"] for entry in settings
                  if entry["timing"]["total_ms"] <= time and entry["errors"][key] <= error
                  and (entry["timing"]["total_ms"] < time or entry["errors"][key] < error)]
        rows.append([name, "yes" if not better else "no", ", ".join(better) or "–"])
    return table(["error", f"default ({DEFAULT_LABEL}) on the Pareto front?", "settings faster and no worse"], rows)


def number(value, digits=3):
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "–"
    return f"{value:.{digits}g}" if abs(value) < 1000 else f"{value:.0f}"


def table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(str(cell) for cell in row) + " |" for row in rows]
    return "\n".join(lines)


def cycles_time_at_error(cycles, error):
    """Cycles' time for `error` (MAE), interpolated on log time against log error between sweep points;
    None where the error lies outside the sweep's range."""
    points = sorted((p["mae"], p["time_s"]) for p in cycles if p["mae"] == p["mae"])
    for (low_error, low_time), (high_error, high_time) in zip(points, points[1:]):
        if low_error <= error <= high_error:
            t = (math.log(error) - math.log(low_error)) / (math.log(high_error) - math.log(low_error))
            return math.exp(math.log(low_time) + t * (math.log(high_time) - math.log(low_time)))
    return None


def method_points(data):
    points = [(row["timing"]["total_ms"], row["errors"]["mae"], "spindrift", row["label"])
              for row in data["spindrift"] if "timing" in row]
    points += [(row["timing"]["warm_total_ms"], row["errors"]["mae"], "spindrift, warm frame", row["label"])
               for row in data["spindrift"] if "timing" in row and row["timing"].get("warm_total_ms")]
    points += [(row["frame_ms"], row["errors"]["mae"], "vtk", row["label"]) for row in data["vtk"]]
    points += [(p["time_s"] * 1e3, p["mae"], "cycles", f"{p['spp']} spp") for p in data["cycles"]]
    return points


def spindrift_table(data):
    rows = []
    for row in data["spindrift"]:
        if "skipped" in row:
            rows.append([row["label"], "skipped: " + row["skipped"]] + [""] * 13)
            continue
        t, e = row["timing"], row["errors"]
        gpu = sum(p["gpu_ms"] for p in t["passes"].values())
        smoothing = t["passes"].get("smoothing", {}).get("gpu_ms")
        cycles_time = cycles_time_at_error(data["cycles"], e["mae"])
        warm = t.get("warm_total_ms")  # absent from results.json files written before session 45
        ratio = number(cycles_time * 1e3 / t["total_ms"]) + "×" if cycles_time else "–"
        warm_ratio = number(cycles_time * 1e3 / warm) + "×" if cycles_time and warm else "–"
        rows.append([row["label"], number(t["wall_s"] * 1e3, 4), number(t["total_ms"], 4),
                     number(warm, 4) if warm else "–", number(gpu, 4), number(smoothing), number(e["iou"]),
                     number(e["depth_median_r"]), number(e["depth_p95_r"]), number(e["silhouette_bias_r"]),
                     number(e["normal_median_deg"]), number(e["normal_p95_deg"]),
                     f"{number(e['mae'])} / {number(e['ssim'])}", ratio, warm_ratio])
    return table(["setting", "wall ms", "frame ms", "warm frame ms", "GPU ms", "smoothing GPU ms", "IoU",
                  "depth med (r)", "depth p95 (r)", "edge bias (r)", "normal med °", "normal p95 °", "MAE / SSIM",
                  "Cycles time at equal MAE", "the same, warm frame"], rows)


def pass_table(data):
    names = []
    for row in data["spindrift"]:
        for name in row.get("timing", {}).get("passes", {}):
            if name not in names:
                names.append(name)
    rows = [[row["label"]] + [number(row["timing"]["passes"].get(name, {}).get("gpu_ms")) for name in names]
            for row in data["spindrift"] if "timing" in row]
    return table(["setting"] + [f"{name} GPU ms" for name in names], rows)


def raymarch_table(data):
    """The ray-marched surface's own counters (on the timing camera): steps per ray, rays, tiles."""
    rows = []
    for row in data["spindrift"]:
        stats = row.get("timing", {}).get("raymarch")
        if not stats:
            continue
        tiles = stats["tiles"]
        marching = sum(row["timing"]["passes"].get(name, {}).get("gpu_ms") or 0.0
                       for name in row["timing"]["passes"] if name.startswith("raymarch"))
        # Results older than the kernel-bound steps have no refinement or particle counters.
        optional = [number(stats[key]) if key in stats else "–"
                    for key in ("refinement_evaluations_per_ray", "particles_visited_per_ray")]
        rows.append([row["label"], stats["stepping"], number(stats["average_steps_per_ray"]),
                     number(stats["density_evaluations_per_ray"]), *optional, f"{stats['rays_cast']:,}",
                     f"{stats['hits']:,}", f"{tiles['full']} / {tiles['half']} / {tiles['quarter']} / {tiles['empty']}",
                     number(marching, 4)])
    if not rows:
        return ""
    return table(["setting", "stepping", "steps per ray", "density evaluations per ray",
                  "of them refinement", "particles read per ray", "rays cast", "hits",
                  "tiles full / half / quarter / empty", "raymarch passes GPU ms"], rows)


def peers_table(data):
    rows = [[row["label"], number(row["frame_ms"], 4), number(row["first_frame_ms"], 4), number(row["errors"]["mae"]),
             number(row["errors"]["ssim"])] for row in data["vtk"]]
    rows += [[f"Cycles {p['spp']} spp", number(p["time_s"] * 1e3, 4), "", number(p["mae"]), number(p["ssim"])]
             for p in data["cycles"]]
    table_text = table(["method", "frame ms", "first frame ms", "MAE", "SSIM"], rows)
    earlier = [p for p in data["cycles"] if p.get("earlier_time_s")]
    if earlier:
        table_text += ("\n\nCycles' renders were timed again in this run (the same images); the times they "
                       "replaced, from the last run that timed them (or the references' own renders): " +
                       ", ".join(f"{p['spp']} spp {number(p['earlier_time_s'] * 1e3, 4)} ms" for p in earlier) + ".")
    return table_text


def users_render_table(users, cameras):
    """Each renderer against both references (users_render.py), and Cycles' sweep with the water's shadow."""
    cycles = users["cycles_full"]
    rows = []
    for row in users["rows"]:
        at_equal = cycles_time_at_error(cycles, row["mae"]["full"]) if row["label"].startswith("Spindrift") else None
        ratio = f"{at_equal * 1e3 / row['frame_ms']:.3g}×" if at_equal else "–"
        per_camera = ", ".join(number(row["per_camera"][camera]["full"]) for camera in cameras)
        whitewater = number(row["mae"]["whitewater"]) if "whitewater" in row["mae"] else "–"
        rows.append([row["label"], number(row["frame_ms"], 4), number(row["mae"]["no_shadow"]),
                     number(row["mae"]["full"]), whitewater, per_camera, ratio])
    rows += [[f"Cycles {p['spp']} spp, the water casting its shadow", number(p["time_s"] * 1e3, 4), "",
              number(p["mae"]), "", "", ""] for p in cycles]
    return table(["renderer", "frame ms", "MAE, no-shadow reference", "MAE, the user's render",
                  "MAE, the user's render with its whitewater",
                  f"the user's render, per camera ({', '.join(cameras)})",
                  "Cycles' time at equal MAE (the user's render)"], rows)


def scaling_tables(scaling):
    particle_rows = [[row["source"], f"{row['count']:,}", number(row["total_ms"], 4), number(row["wall_s"] * 1e3, 4),
                      number(row["peak_rss_mib"], 4), number(row["peak_gpu_mib"]), row["repeats"]]
                     for row in scaling["particles"]]
    resolution_rows = [[f"{row['width']}×{row['height']}", number(row["total_ms"], 4),
                        number(row["wall_s"] * 1e3, 4), number(row["peak_rss_mib"], 4), number(row["peak_gpu_mib"]),
                        row["repeats"]] for row in scaling["resolutions"]]
    slopes = scaling["slopes"]
    slope_rows = [[key.replace("_", " "), number(value)] for key, value in slopes.items()]
    return "\n\n".join([
        table(["particles", "count", "frame ms", "wall ms", "peak host MiB", "peak GPU MiB", "runs"], particle_rows),
        table(["resolution", "frame ms", "wall ms", "peak host MiB", "peak GPU MiB", "runs"], resolution_rows),
        table(["fitted log-log slope", "exponent"], slope_rows)])


def bigger_bake_table(bake):
    """Spindrift beside VTK on the resampled bake (issue 11: Spindrift's frame at most half VTK's, at no worse
    an image error)."""
    vtk = [row for row in bake["rows"] if row["label"].startswith("VTK")]
    fastest_vtk = min(row["steady_frame_ms"] for row in vtk) if vtk else float("nan")
    def new_particles(row):
        return row.get("steady_new_particles_ms")

    rows = [[row["label"], number(row["steady_frame_ms"], 4),
             number(new_particles(row), 4) if new_particles(row) else "–", number(row["frame_ms"], 4),
             number(row["steady_frame_ms"] / fastest_vtk),
             number(new_particles(row) / fastest_vtk) if new_particles(row) else "–",
             number(row["mae"])] for row in bake["rows"]]
    return table(["renderer", "frame ms (steady)", "steady, shaped anew", "first frame ms", "× the fastest VTK",
                  "shaped anew, × the fastest VTK", "MAE"], rows)


def stability_table(suite):
    if not suite:
        return "The test binary `build/bin/spindrift_tests` was not built; no stability results."
    rows = []
    for group in suite.get("testsuites", []):
        for test in group.get("testsuite", []):
            failed = bool(test.get("failures"))
            known = {"name", "file", "line", "status", "result", "timestamp", "time", "classname", "failures"}
            errors = ", ".join(f"{k} {v}" for k, v in test.items() if k not in known) or "–"
            outcome = "fail" if failed else ("skipped" if test.get("result") == "SKIPPED" else "pass")
            rows.append([f"{group['name']}.{test['name']}", outcome,
                         test.get("time", ""), errors])
    return table(["case", "result", "time", "error against its reference"], rows)


def write_plots(results, images):
    written = []
    for example, data in results["examples"].items():
        path = os.path.join(images, f"bench_time_vs_error_{example}.png")
        plots.time_vs_error(method_points(data), "composite MAE over liquid (linear RGB)", path,
                            f"{example}: time per frame against image error (mean over cameras; Cycles on one)")
        written.append(path)
        geometric = [(row["timing"]["total_ms"], row["errors"]["depth_median_r"], "spindrift", row["label"])
                     for row in data["spindrift"] if "timing" in row]
        path = os.path.join(images, f"bench_time_vs_depth_{example}.png")
        plots.time_vs_error(geometric, "median |depth error| (particle radii)", path,
                            f"{example}: time per frame against depth error")
        written.append(path)
    if not results.get("scaling"):
        return written
    particles = results["scaling"]["particles"]
    series = {}
    for source in ("synthetic", "resampled"):
        rows = [row for row in particles if row["source"] == source]
        series[source] = ([r["count"] for r in rows], [r["total_ms"] for r in rows], [r["peak_rss_mib"] for r in rows])
    path = os.path.join(images, "bench_scaling_particles.png")
    plots.scaling(series, "particles", path, "Frame time and memory against particle count")
    written.append(path)
    rows = results["scaling"]["resolutions"]
    path = os.path.join(images, "bench_scaling_resolution.png")
    plots.scaling({"dam_break": ([r["pixels"] for r in rows], [r["total_ms"] for r in rows],
                                 [r["peak_rss_mib"] for r in rows])}, "pixels", path,
                  "Frame time and memory against resolution")
    written.append(path)
    return written


def write(results, output, quick):
    images = os.path.join(output, "images")
    os.makedirs(images, exist_ok=True)
    write_plots(results, images)
    plan, machine = results["plan"], results["machine"]
    parts = [readme_benchmarks_section(), "", open(NOTES_FILE).read().strip()]
    parts += ["", "## The machine", "",
              table(["", ""], [["OpenGL renderer", machine["gl_renderer"]], ["CPU", machine["cpu"]],
                               ["memory", machine["memory"]], ["OS", machine["os"]], ["Blender", machine["blender"]],
                               ["load average at start", ", ".join(f"{v:.1f}" for v in machine["load_average"])],
                               ["run", ("--quick" if quick else "full") + f", {results['runtime_s'] / 60:.1f} min"],
                               ["filters", ", ".join(f"{k} {v}" for k, v in plan.get("filters", {}).items())
                                or "none"]])]
    for example, data in results["examples"].items():
        parts += ["", f"## {example}", "",
                  f"{plan['width']}×{plan['height']}, cameras {', '.join(plan['cameras'])}; times on "
                  f"`{plan['cameras'][0]}` (median of {plan['repeats']} runs), errors the mean over the cameras.",
                  "", f"![time against error, {example}](images/bench_time_vs_error_{example}.png)",
                  f"![time against depth error, {example}](images/bench_time_vs_depth_{example}.png)", "",
                  "### Spindrift settings", "", spindrift_table(data), "", "### Where the defaults stand", "",
                  defaults_on_front(data), "", "### GPU time per pass", "",
                  pass_table(data), "", "### Peers: VTK's fluid mapper and Cycles", "", peers_table(data)]
        if data.get("users_render"):
            parts += ["", "### Against the user's render (the water casting its shadow)", "",
                      "The same frames against a Cycles render in which the water casts its shadow and caustics, "
                      "as a user's render of the example does, beside the reference above, where it casts none "
                      "(`tests/bench/users_render.py`). *The sun with light passes*: the example's sun in the "
                      "scene file, as the Blender add-on exports it, over a background render with Cycles' light "
                      "passes, so that Spindrift's shadow, caustics and sky occlusion apply. *With its "
                      "whitewater*: the same render with the example's spray, foam and bubbles as white diffuse "
                      "spheres of their radius, the only reference with foam (docs/foam.md, \"Lit by the scene's "
                      "lights\"). Errors are the mean over the cameras; Cycles' sweep and the times are the first "
                      "camera's.", "",
                      users_render_table(data["users_render"], plan["cameras"])]
        marching = raymarch_table(data)
        if marching:
            parts += ["", "### The ray-marched surface (liquid.surface = raymarch)", "",
                      f"Counters of the `{plan['cameras'][0]}` camera (docs/raymarch.md).", "", marching]
    if not results.get("scaling"):
        if results.get("stability"):
            parts += ["", "## Stability suite", "", stability_table(results["stability"]), ""]
        parts += ["", f"A subset run (`--sweep-only`, configurations: "
                  f"{', '.join(plan.get('only_configurations') or ['all'])}): no scaling or stability suite. "
                  f"Load average at the end: "
                  f"{', '.join(f'{v:.1f}' for v in machine.get('load_average_at_end', []))}.", ""]
        with open(os.path.join(output, "benchmarks.md"), "w") as handle:
            handle.write("\n".join(parts))
        return
    parts += ["", "## Scaling", "", "Default settings, the dam-break `oblique` camera (480×270 for the particle sweep, "
              "its background resampled for the resolution sweep).", "",
              "![scaling with particles](images/bench_scaling_particles.png)",
              "![scaling with resolution](images/bench_scaling_resolution.png)", "",
              scaling_tables(results["scaling"]), ""]
    bake = results.get("bigger_bake")
    if bake:
        parts += ["### A bigger bake beside VTK's fluid mapper", "",
                  f"The dam-break frame resampled to {bake['count']:,} particles (as the `resampled` rows above), "
                  f"liquid only, rendered by Spindrift's defaults and by VTK's fluid mapper from the same PLY, "
                  f"camera (`{bake['camera']}`) and background, both scored against the same Cycles reference "
                  f"(`tests/bench/bigger_bake.py`). *Steady*: Spindrift's later frames of one process rendering "
                  f"the frame again (each pass finished, read back, written nowhere), which keep the particles' "
                  f"shapes of the frame before "
                  f"(`liquid.reuse_shapes`: the same particles), VTK's renders after a warm-up render; *shaped "
                  f"anew*: the same with `liquid.reuse_shapes` false, what each frame of a sequence of new "
                  f"particles costs; *first frame*: a fresh process's only frame, VTK's first render.", "",
                  bigger_bake_table(bake), ""]
    parts += ["## Stability suite", "",
              "`build/bin/spindrift_tests --gtest_filter='GLLiquidStability.*:GLLiquidAccuracy.*' "
              "--gtest_output=json:…`, run by the benchmark; errors are the properties the tests record.", "",
              stability_table(results["stability"]), ""]
    with open(os.path.join(output, "benchmarks.md"), "w") as handle:
        handle.write("\n".join(parts))

