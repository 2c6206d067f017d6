#!/usr/bin/python3
"""Frame overheads, measured by interleaved A/B runs: writes docs/frame-overheads.md (or OUTPUT/...).

    tests/bench/frame_overheads.py [--scene examples/dam_break/scene.json] [--size 480x270] [--rounds 3]
                                   [--output docs]

Each round runs every variant once, in turn, so a load that changes during the run (the machine is shared)
falls on all variants alike; the page reports medians and the load average at start and end. Variants:
the program binary cache off (SPINDRIFT_PROGRAM_CACHE=off) and on (warm: a previous process filled it);
every layer read back, or only the composite (`--layers composite`); and a three-frame sequence, whose frames
after the first carry no setup and overlap their EXR writing with the next frame's render. The image layers a
variant writes are compared with the first variant's, so a speed-up that changed a pixel would show.
What the levers cost and saved, measured by hand session by session, is docs/frame-cost.md (not generated).
"""

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import runs  # noqa: E402


def parse_arguments():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--scene", default=os.path.join(runs.REPOSITORY, "examples", "dam_break", "scene.json"))
    parser.add_argument("--size", default="480x270")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--output", default=os.path.join(runs.REPOSITORY, "docs"))
    return parser.parse_args()


def sized_scene(path, size, work):
    """The scene at another camera size (the background is resampled by the renderer), absolute paths."""
    scene = json.load(open(path))
    width, height = (int(v) for v in size.split("x"))
    scene["camera"]["width"], scene["camera"]["height"] = width, height
    base = os.path.dirname(os.path.abspath(path))
    for source in scene["particles"]:
        source["path"] = os.path.join(base, source["path"])
    for key in ("image", "depth", "environment", "liquid_depth"):
        if key in scene.get("background", {}):
            scene["background"][key] = os.path.join(base, scene["background"][key])
    out = os.path.join(work, "scene.json")
    json.dump(scene, open(out, "w"), indent=1)
    return out, scene["frame"]


def run(scene, work, name, extra=(), environment=None, frames=None):
    exr = os.path.join(work, f"{name}_####.exr" if frames else f"{name}.exr")
    stats = os.path.join(work, f"{name}.json")
    command = [runs.SPINDRIFT, "render", scene, "-q", "-o", exr, "--stats", stats, *extra]
    if frames:
        command += ["--frames", frames]
    env = dict(os.environ, **(environment or {}))
    started = time.perf_counter()
    subprocess.run(command, check=True, env=env)
    wall = (time.perf_counter() - started) * 1000.0
    data = json.load(open(stats))
    return {"wall_ms": wall, "frames": data["frames"] if "frames" in data else [data], "exr": exr}


def read_layers(path):
    import OpenImageIO as oiio
    image = oiio.ImageInput.open(path)
    spec = image.spec()
    pixels = image.read_image(format="float").reshape(spec.height, spec.width, spec.nchannels)
    image.close()
    return {name: pixels[:, :, c] for c, name in enumerate(spec.channelnames)}


def main():
    arguments = parse_arguments()
    work = tempfile.mkdtemp(prefix="spindrift-overheads-")
    scene, frame = sized_scene(arguments.scene, arguments.size, work)
    cache = os.path.join(work, "program-cache")
    variants = {
        "cache off, all layers": dict(environment={"SPINDRIFT_PROGRAM_CACHE": "off"}),
        "cache warm, all layers": dict(environment={"SPINDRIFT_PROGRAM_CACHE": cache}),
        "cache warm, --layers composite": dict(environment={"SPINDRIFT_PROGRAM_CACHE": cache},
                                               extra=["--layers", "composite"]),
        "cache warm, 3-frame sequence": dict(environment={"SPINDRIFT_PROGRAM_CACHE": cache},
                                             frames=f"{frame - 2}-{frame}"),
    }
    run(scene, work, "fill_cache", environment={"SPINDRIFT_PROGRAM_CACHE": cache})
    load_start = os.getloadavg()
    samples = {name: [] for name in variants}
    for round_index in range(arguments.rounds):
        for name, variant in variants.items():
            samples[name].append(run(scene, work, name.replace(" ", "_").replace(",", "").replace("-", ""),
                                     **variant))
            print(f"[overheads] round {round_index + 1}: {name}: {samples[name][-1]['wall_ms']:.0f} ms", flush=True)
    load_end = os.getloadavg()

    reference = read_layers(samples["cache off, all layers"][-1]["exr"])
    rows = []
    for name, results in samples.items():
        first = [r["frames"][0] for r in results]
        later = [f for r in results for f in r["frames"][1:]]
        exr = results[-1]["exr"].replace("####", f"{frame:04d}")
        layers = read_layers(exr)
        difference = max(float(np.max(np.abs(layers[c] - reference[c]))) for c in layers if c in reference)
        rows.append({
            "variant": name,
            "process_ms": statistics.median(r["wall_ms"] for r in results),
            "setup_ms": statistics.median(f["setup"]["ms"] for f in first),
            "compiled": first[0]["setup"]["programs_compiled"],
            "from_cache": first[0]["setup"]["programs_from_cache"],
            "frame_ms": statistics.median(f["total_ms"] for f in first),
            "readback_ms": statistics.median(f["readback_ms"] for f in first),
            "later_frame_ms": statistics.median(f["total_ms"] for f in later) if later else None,
            "max_difference": difference,
            "channels": len(layers),
        })
    write_page(arguments, rows, load_start, load_end, runs.gl_renderer())


def write_page(arguments, rows, load_start, load_end, renderer):
    lines = ["# Frame overheads", "",
             "Generated by `tests/bench/frame_overheads.py` (interleaved A/B rounds; medians). Times are wall "
             "clock on a shared machine: compare rows with each other, not with other pages.", "",
             f"- scene: `{os.path.relpath(arguments.scene, runs.REPOSITORY)}` at {arguments.size}, "
             f"{arguments.rounds} rounds", f"- OpenGL renderer: {renderer}",
             f"- load average at start {', '.join(f'{v:.1f}' for v in load_start)}; at end "
             f"{', '.join(f'{v:.1f}' for v in load_end)}", "",
             "| variant | process ms | setup ms | programs compiled / from cache | first frame ms | readback ms | "
             "later frames ms | channels | max abs difference to row 1 |",
             "|---|---|---|---|---|---|---|---|---|"]
    for row in rows:
        later = f"{row['later_frame_ms']:.0f}" if row["later_frame_ms"] is not None else ""
        lines.append(f"| {row['variant']} | {row['process_ms']:.0f} | {row['setup_ms']:.0f} | {row['compiled']} / "
                     f"{row['from_cache']} | {row['frame_ms']:.0f} | {row['readback_ms']:.1f} | {later} | "
                     f"{row['channels']} | {row['max_difference']:.3g} |")
    lines += ["", "*Process*: the whole command's wall time; *setup*: the EGL context and the programs (from the "
              "program binary cache, or compiled; the programs are built beside the first frame's loading and "
              "preparation, so setup and first frame overlap); *first frame*: `total_ms` of the process's first frame "
              "(loading, preparation, every pass, readback; not the EXR's write); *later frames*: the "
              "sequence's frames after the first, whose EXR writes overlap the next frame's render "
              "(`docs/farm.md`). What each lever costs and saves: `docs/frame-cost.md`."]
    os.makedirs(arguments.output, exist_ok=True)
    with open(os.path.join(arguments.output, "frame-overheads.md"), "w") as handle:
        handle.write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
