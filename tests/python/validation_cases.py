"""Bad arguments to the module, each with the exception it must raise. Run as a script, it tries every case
against one Renderer and prints one JSON line when a case starts and one when it ends, so that a crash (which
would kill a pytest process, and Blender) is pinned on the case that caused it (test_module_validation.py)."""

import json
import os
import sys

import numpy as np

from spindrift_testing import HEIGHT, WIDTH, import_module, scene_json, sphere_of_particles


def particles(**changes):
    arrays = sphere_of_particles(count=50)
    arrays.update(changes)
    return {key: value for key, value in arrays.items() if value is not None}


def quad(**changes):
    mesh = {"vertices": np.array([[-1, -1, -1], [1, -1, -1], [1, -1, 1], [-1, -1, 1]], dtype=np.float32),
            "triangles": np.array([[0, 1, 2], [0, 2, 3]], dtype=np.int32)}
    mesh.update(changes)
    return mesh


def scene_with(camera=None, source=None, raw=None):
    """The test scene with camera keys changed and/or one particle source; RAW replaces a quoted placeholder
    in the text (JSON has no literal for a non-finite number, but 1e999 parses to infinity)."""
    base = json.loads(scene_json())
    base["camera"].update(camera or {})
    base["camera"] = {key: value for key, value in base["camera"].items() if value is not None}  # None: remove
    if source is not None:
        base["particles"] = [{"path": "none_####.ply", **source}]
    text = json.dumps(base)
    return text.replace('"RAW"', raw) if raw else text


IDENTITY = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]
N = len(sphere_of_particles(count=50)["radii"])
positions = sphere_of_particles(count=50)["positions"]

# name: (keyword arguments of render, expected exception name or None for success, fragment of the message)
CASES = {
    "positions_float64": (dict(particles=particles(positions=positions.astype(np.float64))), "ValueError",
                          'particles["positions"]: expected float32, got float64'),
    "positions_big_endian": (dict(particles=particles(positions=positions.astype(">f4"))), "ValueError", "float32"),
    "positions_four_columns": (dict(particles=particles(positions=np.zeros((N, 4), np.float32))), "ValueError",
                               f"expected shape (N, 3), got ({N}, 4)"),
    "positions_flat": (dict(particles=particles(positions=positions.ravel())), "ValueError", "expected shape (N, 3)"),
    "positions_not_contiguous": (dict(particles=particles(positions=np.zeros((2 * N, 3), np.float32)[::2])),
                                 "ValueError", "not C-contiguous"),
    "positions_fortran_order": (dict(particles=particles(positions=np.asfortranarray(positions))), "ValueError",
                                "not C-contiguous"),
    "positions_list": (dict(particles=particles(positions=positions.tolist())), "TypeError", "got list"),
    "radii_one_short": (dict(particles=particles(radii=np.ones(N - 1, np.float32))), "ValueError",
                        f'particles["radii"]: expected {N} float32 values, got {N - 1}'),
    "radii_float64": (dict(particles=particles(radii=np.ones(N))), "ValueError", "got float64"),
    "kinds_int64": (dict(particles=particles(kinds=np.zeros(N, np.int64))), "ValueError", "expected uint8, got int64"),
    "kinds_unknown_value": (dict(particles=particles(kinds=np.full(N, 3, np.uint8))), "ValueError",
                            "value 3 at index 0"),
    "velocities_mismatched": (dict(particles=particles(velocities=np.zeros((N + 1, 3), np.float32))), "ValueError",
                              f"expected shape ({N}, 3), got ({N + 1}, 3)"),
    "life_wrong_length": (dict(particles=particles(life=np.zeros(N + 2, np.float32))), "ValueError",
                          f"expected {N} float32 values, got {N + 2}"),
    "missing_radii": (dict(particles=particles(radii=None)), "ValueError", "missing 'radii'"),
    "unknown_particle_key": (dict(particles=particles(radius=np.ones(N, np.float32))), "ValueError",
                             "unknown key 'radius'"),
    "particles_not_dict": (dict(particles=[1, 2, 3]), "TypeError", "particles: expected a dict"),
    "empty_positions_wrong_shape": (dict(particles=particles(positions=np.array([], np.float32))), "ValueError",
                                    "expected shape (N, 3), got (0,)"),
    "occluder_index_out_of_range": (dict(occluders=quad(triangles=np.array([[0, 1, 4]], np.int32))), "ValueError",
                                    'occluders["triangles"]: triangle 0 names vertex 4, outside the 4 vertices'),
    "occluder_negative_index": (dict(occluders=quad(triangles=np.array([[0, -1, 2]], np.int32))), "ValueError",
                                "names vertex -1"),
    "occluder_uint32_out_of_range": (dict(occluders=quad(triangles=np.array([[0, 1, 2**32 - 1]], np.uint32))),
                                     "ValueError", "names vertex 4294967295"),
    "occluder_int64_indices": (dict(occluders=quad(triangles=np.array([[0, 1, 2]], np.int64))), "ValueError",
                               "expected int32 or uint32, got int64"),
    "occluder_nan_vertex": (dict(occluders=quad(vertices=np.full((4, 3), np.nan, np.float32))), "ValueError",
                            "vertex 0 is not finite"),
    "liquid_mesh_float64": (dict(liquid_mesh=quad(vertices=np.zeros((4, 3)))), "ValueError",
                            'liquid_mesh["vertices"]: expected float32, got float64'),
    "background_wrong_size": (dict(background={"color": np.zeros((HEIGHT, WIDTH + 1, 4), np.float32)}), "ValueError",
                              f"expected shape ({HEIGHT}, {WIDTH}, 4), got ({HEIGHT}, {WIDTH + 1}, 4)"),
    "background_depth_float64": (dict(background={"depth": np.zeros((HEIGHT, WIDTH))}), "ValueError", "float64"),
    "unknown_layer": (dict(layers=["liquid", "no_such_layer"]), "ValueError", "no layer named 'no_such_layer'"),
    "layers_not_list": (dict(layers="liquid"), "TypeError", "layers: expected a list"),
    "unknown_exr_layer": (dict(exr_path="/tmp/unused.exr", exr_layers=["foam", "fome"]), "ValueError",
                          "exr_layers: no layer named 'fome'"),
    "crop_outside_the_image": (dict(crop=(1, 0, WIDTH, HEIGHT)), "ValueError", "does not lie inside the"),
    "crop_not_a_tuple": (dict(crop=[0, 0, 4, 4]), "TypeError", "crop: expected a tuple"),
    "unknown_exr_compression": (dict(exr_path=__file__ + ".exr", exr_compression="zipp"), "Error",
                                'unknown EXR compression "zipp"'),
    "exr_compression_level_out_of_range": (dict(exr_path=__file__ + ".exr", exr_compression="zip:0"), "Error",
                                           'unknown EXR compression "zip:0"'),
    "bad_scene_json": (dict(scene_json="{"), "Error", "not valid JSON"),
    "scene_unknown_key": (dict(scene_json='{"version": 1, "camera": {}, "particles": [], "bogus": 1}'), "Error",
                          "bogus"),
    # The limits of docs/reliability.md ("Limits"), through the module: the scene's camera and radii. The
    # scene parser refuses them first, naming the key; a non-finite number cannot be written in JSON (1e999
    # overflows, and is refused as such; `validateCamera` checks matrices built through the C++ API).
    "radius_zero": (dict(scene_json=scene_with(source={"radius": 0})), "Error",
                    "particles[0].radius: 0 is outside (0, 1e+30]"),
    "radius_negative": (dict(scene_json=scene_with(source={"radius": -0.1})), "Error",
                        "radius: -0.1 is outside (0, 1e+30]"),
    "fov_zero": (dict(scene_json=scene_with({"fov_y_deg": 0})), "Error", "camera.fov_y_deg: 0 is outside (0, 179]"),
    "fov_negative": (dict(scene_json=scene_with({"fov_y_deg": -30})), "Error", "fov_y_deg: -30 is outside (0, 179]"),
    "fov_180": (dict(scene_json=scene_with({"fov_y_deg": 180})), "Error", "fov_y_deg: 180 is outside (0, 179]"),
    "near_equals_far": (dict(scene_json=scene_with({"near": 5, "far": 5})), "Error",
                        "camera.far: must be greater than near"),
    "near_beyond_far": (dict(scene_json=scene_with({"near": 50, "far": 5})), "Error",
                        "camera.far: must be greater than near"),
    "camera_matrix_infinite": (dict(scene_json=scene_with({"world_from_camera": IDENTITY[:3] + ["RAW"] + IDENTITY[4:],
                                                           "position": None, "target": None, "up": None},
                                                          raw="1e999")),
                               "Error", "number overflow parsing '1e999'"),
    "camera_matrix_singular": (dict(scene_json=scene_with({"world_from_camera": [0] * 12 + [0, 0, 0, 1],
                                                           "position": None, "target": None, "up": None})),
                               "Error", "camera.world_from_camera: the matrix is singular"),
    "width_over_16384": (dict(scene_json=scene_with({"width": 16385})), "Error",
                         "camera.width: 16385 is outside [1, 16384]"),
    "height_zero": (dict(scene_json=scene_with({"height": 0})), "Error", "camera.height: 0 is outside [1, 16384]"),
    # 16384² is within the hard cap, and GL's on llvmpipe, but its ~256 GiB of targets are not: refused
    # before anything is allocated.
    "resolution_over_memory": (dict(scene_json=scene_with({"width": 16384, "height": 16384})), "Error",
                               "16384x16384"),
    # A million particles need ~244 MiB of preparation, over the 64 MiB limit run_case sets for this case.
    "particles_over_memory": (dict(particles=particles(positions=np.zeros((1_000_000, 3), np.float32),
                                                       radii=np.full(1_000_000, 0.1, np.float32),
                                                       kinds=np.zeros(1_000_000, np.uint8))), "Error",
                              "frame of 1000000 particles needs"),
    # A directory cannot be made inside a file: the library's writer fails, and says where.
    "exr_path_under_a_file": (dict(exr_path=__file__ + "/frame.exr"), "Error", "frame.exr"),
    # Valid inputs at the edges: these must render.
    "nan_positions_dropped": (dict(particles=particles(positions=np.where(np.arange(N)[:, None] < 5, np.nan,
                                                                          positions).astype(np.float32))), None, ""),
    "empty_arrays": (dict(particles={"positions": np.zeros((0, 3), np.float32), "radii": np.zeros(0, np.float32),
                                     "kinds": np.zeros(0, np.uint8)},
                          occluders={"vertices": np.zeros((0, 3), np.float32),
                                     "triangles": np.zeros((0, 3), np.int32)}), None, ""),
    "occluder_list": (dict(occluders=[quad(), quad()]), None, ""),
    # Per-particle radii ≤ 0 (or not finite) are dropped and counted, as file loading does (docs/python-module.md):
    # one bad particle of a simulation must not cost the frame.
    "radii_not_positive_dropped": (dict(particles=particles(radii=np.concatenate(
        [np.array([0.0, -1.0, np.inf], np.float32), np.full(N - 3, 0.1, np.float32)]))), None, ""),
}
MEMORY_LIMIT_MB = {"particles_over_memory": 64}


def run_case(spindrift, renderer, name):
    arguments, _, _ = CASES[name]
    arguments = dict(arguments)
    scene = arguments.pop("scene_json", scene_json())
    if name in MEMORY_LIMIT_MB:  # The library reads it at every check (os.environ sets the C environment).
        os.environ["SPINDRIFT_MEMORY_LIMIT_MB"] = str(MEMORY_LIMIT_MB[name])
    try:
        result = renderer.render(scene, 1, **arguments)
    except Exception as error:  # noqa: BLE001 (the test compares the exception's type)
        return {"exception": type(error).__name__, "message": str(error)}
    finally:
        os.environ.pop("SPINDRIFT_MEMORY_LIMIT_MB", None)
    return {"exception": None, "message": "", "dropped": result["stats"]["particles"]["dropped_invalid"],
            "liquid": result["stats"]["particles"]["liquid"]}


def main():
    spindrift = import_module()
    renderer = spindrift.Renderer()
    for name in CASES:
        print(json.dumps({"case": name, "started": True}), flush=True)
        outcome = run_case(spindrift, renderer, name)
        print(json.dumps({"case": name, **outcome}), flush=True)
    renderer.close()
    try:
        renderer.render(scene_json(), 1)
        closed = {"exception": None, "message": ""}
    except Exception as error:  # noqa: BLE001
        closed = {"exception": type(error).__name__, "message": str(error)}
    print(json.dumps({"case": "render_after_close", **closed}), flush=True)


if __name__ == "__main__":
    sys.exit(main())
