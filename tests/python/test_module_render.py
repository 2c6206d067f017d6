"""Frames rendered through the module against references it did not produce: the same particles loaded from a
PLY file by the command line, a CPU rasterisation of an occluder, the refraction split recombined with a CPU
bilinear lookup, and a Python thread that keeps running while a frame renders."""

import json
import subprocess
import threading
import time

import numpy as np
import OpenImageIO as oiio

from spindrift_testing import CLI, HEIGHT, WIDTH, layer, project, scene_json, sphere_of_particles


def write_ply(path, arrays):
    vertices = np.zeros(len(arrays["radii"]), dtype=[("x", "<f4"), ("y", "<f4"), ("z", "<f4"), ("radius", "<f4")])
    for axis, name in enumerate("xyz"):
        vertices[name] = arrays["positions"][:, axis]
    vertices["radius"] = arrays["radii"]
    header = ("ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty float x\nproperty float y\n"
              "property float z\nproperty float radius\nend_header\n" % len(vertices))
    path.write_bytes(header.encode() + vertices.tobytes())


def read_exr_layers(path):
    image = oiio.ImageInput.open(str(path))
    spec = image.spec()
    pixels = image.read_image(oiio.FLOAT).reshape(spec.height, spec.width, spec.nchannels)
    image.close()
    layers = {}
    for index, name in enumerate(spec.channelnames):
        layer_name, channel = name.rsplit(".", 1)
        layers.setdefault(layer_name, []).append((channel, pixels[:, :, index]))
    return {name: np.stack([plane for _, plane in planes], axis=2) for name, planes in layers.items()}


def assert_all_finite(result):
    for name in result["layers"]:
        values = layer(result, name)
        assert np.isfinite(values).all(), f"non-finite values in layer {name}"


def test_in_memory_particles_match_the_command_line_reading_a_ply_file(renderer, tmp_path):
    arrays = sphere_of_particles()
    write_ply(tmp_path / "sphere.ply", arrays)
    scene = scene_json(particles=[{"path": "sphere.ply", "radius": 1.0}])
    (tmp_path / "scene.json").write_text(scene)
    command = [str(CLI), "render", str(tmp_path / "scene.json"), "-o", str(tmp_path / "cli.exr")]
    completed = subprocess.run(command, capture_output=True, text=True, timeout=300)
    assert completed.returncode == 0, completed.stderr
    from_file = read_exr_layers(tmp_path / "cli.exr")

    exr_path = tmp_path / "module.exr"
    in_memory = renderer.render(scene_json(), 1, particles=arrays, exr_path=str(exr_path))
    assert_all_finite(in_memory)
    assert in_memory["stats"]["particles"]["liquid"] == len(arrays["radii"])
    assert in_memory["stats"]["liquid"]["liquid_pixels"] > 500
    assert set(from_file) == set(in_memory["layers"])
    for name in from_file:
        np.testing.assert_array_equal(layer(in_memory, name), from_file[name], err_msg=name)
    # The module's own EXR is the same frame, written by the library's writer.
    written = read_exr_layers(exr_path)
    for name in written:
        np.testing.assert_array_equal(layer(in_memory, name), written[name], err_msg=name)


def quad_coverage(corners, width=WIDTH, height=HEIGHT, margin=0.01):
    """Pixels whose centre lies inside the projected quad (two triangles 0-1-2, 0-2-3), and those whose centre
    lies within `margin` pixels of an edge, where GL's snapping to sub-pixel precision may decide either way."""
    pixels, _ = project(corners, width, height)
    ys, xs = np.mgrid[0:height, 0:width] + 0.5
    inside = np.zeros((height, width), bool)
    ambiguous = np.zeros((height, width), bool)
    for triangle in ((0, 1, 2), (0, 2, 3)):
        a, b, c = (pixels[i] for i in triangle)
        edges = []
        for p, q in ((a, b), (b, c), (c, a)):
            edge = (q[0] - p[0]) * (ys - p[1]) - (q[1] - p[1]) * (xs - p[0])
            edges.append(edge / np.hypot(*(q - p)))  # signed distance in pixels
        edges = np.stack(edges)
        inside |= (edges > 0).all(axis=0) | (edges < 0).all(axis=0)
        ambiguous |= (np.abs(edges) < margin).any(axis=0)
    return inside, ambiguous


def test_occluder_quad_hides_the_liquid_where_a_cpu_rasterisation_says(renderer):
    arrays = sphere_of_particles()
    # A quad between the camera (y = -5) and the liquid, over the left part of the ball, its edges slanted.
    corners = np.array([[-1.3, -2.0, -1.1], [0.17, -2.0, -0.9], [0.31, -2.0, 1.2], [-1.2, -2.0, 1.05]], np.float32)
    occluder = {"vertices": corners, "triangles": np.array([[0, 1, 2], [0, 2, 3]], np.uint32)}
    # Without smoothing every pixel's first surface is its own ray cast, so pixels beside the quad must keep
    # their depth exactly (smoothing would carry the quad's edge a few pixels into them).
    scene = scene_json(liquid={"smoothing": "none"})
    open_view = renderer.render(scene, 1, particles=arrays)
    hidden = renderer.render(scene, 1, particles=arrays, occluders=occluder)
    assert_all_finite(hidden)
    assert any(p["name"] == "occluder_depth" for p in hidden["stats"]["passes"])
    inside, ambiguous = quad_coverage(corners.astype(np.float64))
    liquid_before = layer(open_view, "liquid")[..., 3] > 0
    liquid_after = layer(hidden, "liquid")[..., 3] > 0
    behind_quad = inside & liquid_before & ~ambiguous
    assert behind_quad.sum() > 300, "the quad must cover a good part of the liquid"
    assert not liquid_after[behind_quad].any(), "liquid drawn where the occluder covers it"
    assert not liquid_after[~inside & ~ambiguous & ~liquid_before].any()
    # Beyond the quad the liquid stays, at the same depth.
    visible = ~inside & ~ambiguous & liquid_before
    assert visible.sum() > 100
    assert liquid_after[visible].all(), "liquid lost outside the occluder"
    depth_before, depth_after = layer(open_view, "depth")[..., 0], layer(hidden, "depth")[..., 0]
    np.testing.assert_array_equal(depth_after[visible], depth_before[visible])


def bilinear(image, u, v):
    """CPU bilinear lookup of a top-row-first image at UV (0..1, origin bottom left), clamped at the edges."""
    height, width = image.shape[:2]
    x = np.clip(u * width - 0.5, 0, width - 1)
    y = np.clip((1.0 - v) * height - 0.5, 0, height - 1)
    x0, y0 = np.floor(x).astype(int), np.floor(y).astype(int)
    x1, y1 = np.minimum(x0 + 1, width - 1), np.minimum(y0 + 1, height - 1)
    fx, fy = (x - x0)[..., None], (y - y0)[..., None]
    top = image[y0, x0] * (1 - fx) + image[y0, x1] * fx
    bottom = image[y1, x0] * (1 - fx) + image[y1, x1] * fx
    return top * (1 - fy) + bottom * fy


def bilinear_on_surface(image, depth, u, v, surface_depth):
    """`bilinear`, over those of the four texels whose depth lies within a tenth of `surface_depth` (the surface
    the ray met), or the nearest texel where none does (lib/frame.glsl's bilinearOnSurface)."""
    height, width = image.shape[:2]
    x = np.clip(u * width - 0.5, 0, width - 1.001)
    y = np.clip(v * height - 0.5, 0, height - 1.001)  # from the bottom, as the shader counts
    x0, y0 = np.floor(x).astype(int), np.floor(y).astype(int)
    fx, fy = x - x0, y - y0
    total, weights = 0.0, 0.0
    for dx, dy in ((0, 0), (1, 0), (0, 1), (1, 1)):
        row, column = height - 1 - np.minimum(y0 + dy, height - 1), np.minimum(x0 + dx, width - 1)
        weight = (fx if dx else 1 - fx) * (fy if dy else 1 - fy)
        weight = weight * (np.abs(depth[row, column] - surface_depth) <= 0.1 * surface_depth)
        total = total + weight[..., None] * image[row, column]
        weights = weights + weight
    nearest = image[height - 1 - np.minimum((v * height).astype(int), height - 1),
                    np.minimum((u * width).astype(int), width - 1)]
    return np.where(weights[..., None] > 0, total / np.maximum(weights, 1e-30)[..., None], nearest)


def depth_at(depth, u, v):
    """The depth of the texel a lookup at UV falls in."""
    height, width = depth.shape
    return depth[height - 1 - np.minimum((v * height).astype(int), height - 1), np.minimum((u * width).astype(int), width - 1)]


# Cycles' Blackman-Harris pixel filter as a box (liquid.pixel_filter_width's default 1.5 times 0.96,
# RefractionFootprintPass.cpp's kBlackmanHarrisAsBox).
FOOTPRINT_BOX = 1.5 * 0.96


def footprint_average(image, depth, uv, looks_up, box=FOOTPRINT_BOX):
    """A CPU reference of the background over each pixel's footprint (docs/liquid.md, "The background's
    footprint"): along each axis, where both neighbours look up and step the same way as each other, the
    shorter of the two steps, ignored past 16 texels or within one; a box of `box` times sqrt(length^2 - 1)
    along it, sampled every texel at most (8 taps an axis) by bilinear lookups on the centre's surface. None
    where no axis adds anything."""
    height, width = image.shape[:2]
    # Lookups in texels, in the shader's window coordinates (origin bottom left); rows of the arrays count from
    # the top, so the shader's "y - 1" neighbour is the row below in the array (row + 1).
    texel = np.where(looks_up[..., None], uv[..., :2] * (width, height), -1.0)
    padded = np.pad(texel, ((1, 1), (1, 1), (0, 0)), mode="edge")
    averaged = {}
    for row, column in zip(*np.nonzero(looks_up)):
        centre = texel[row, column]
        axes = []
        for before, after in ((padded[row + 1, column], padded[row + 1, column + 2]),
                              (padded[row + 2, column + 1], padded[row, column + 1])):
            step = np.zeros(2)
            if before[0] >= 0 and after[0] >= 0 and (centre - before) @ (after - centre) > 0:
                step = min(centre - before, after - centre, key=lambda s: s @ s)
            extent = np.linalg.norm(step)
            axes.append(np.zeros(2) if extent <= 1 or extent > 16 else step * box * np.sqrt(extent**2 - 1) / extent)
        if not any(axis.any() for axis in axes):
            continue
        taps = [int(np.clip(np.ceil(np.linalg.norm(axis)), 1, 8)) for axis in axes]
        offsets = [(np.arange(n) + 0.5) / n - 0.5 for n in taps]
        points = np.array([np.clip(centre + ox * axes[0] + oy * axes[1], 0, (width - 1, height - 1))
                           for oy in offsets[1] for ox in offsets[0]])
        u, v = points[:, 0] / width, points[:, 1] / height
        surface = depth_at(depth, centre[0] / width, centre[1] / height)
        averaged[row, column] = bilinear_on_surface(image, depth, u, v, surface).mean(axis=0)
    return averaged


def test_liquid_is_the_background_through_the_refraction_uv_times_transmittance_plus_reflection(renderer):
    random = np.random.default_rng(11)
    # An opaque background with detail at every scale, and a wall behind the liquid that rays meet.
    colour = np.ones((HEIGHT, WIDTH, 4), np.float32)
    colour[..., :3] = random.uniform(0.0, 1.0, (HEIGHT, WIDTH, 3))
    depth = np.full((HEIGHT, WIDTH), 7.0, np.float32)
    depth[: HEIGHT // 4] = 1e10  # sky above (Blender's depth where nothing is): rays there may fall back to the environment colour
    result = renderer.render(scene_json(liquid={"absorption": 0.8}), 1, particles=sphere_of_particles(),
                             background={"color": colour, "depth": depth})
    assert_all_finite(result)
    liquid = layer(result, "liquid")
    uv, transmittance, reflection = (layer(result, name) for name in ("refraction_uv", "transmittance", "reflection"))
    covered = liquid[..., 3] > 0
    looks_up = uv[..., 2] == 1.0
    # Most final rays read the background (78 % since the ball's faces reach its particles' radius,
    # liquid.reach_radius: more of its rim's rays leave upwards, into the sky quarter), so the identity below is
    # checked on most pixels.
    assert covered.sum() > 500 and looks_up[covered].mean() > 0.7
    assert not looks_up[~covered].any(), "refraction UV flagged outside the liquid"
    assert set(np.unique(uv[..., 2])) <= {0.0, 1.0}
    assert ((transmittance >= 0) & (transmittance <= 1)).all()
    assert (transmittance[looks_up] > 0).any(axis=-1).all()
    # Where the final ray looks up the background, the shader reads it between texels at the UV (bilinear), or
    # averaged over the pixel's footprint where the refraction shrinks it; the CPU repeats both. The scene
    # names no lamp, so the world's light alone lights the background first (light.sky_without_lamps): what
    # is refracted is the background times liquid_sky, as the add-on's group multiplies the render before its
    # Map UV node.
    sky = layer(result, "liquid_sky")
    assert (sky[~covered & (depth < 1e9)] < 0.999).any(), "the liquid takes sky light from the wall"
    lit = colour[..., :3] * sky[..., :3]
    seen = np.zeros_like(reflection)
    u, v = uv[looks_up][:, 0], uv[looks_up][:, 1]
    seen[looks_up] = bilinear_on_surface(lit, depth, u, v, depth_at(depth, u, v))
    averaged = footprint_average(lit, depth, uv, looks_up)
    # The ball's rim shrinks what it refracts: a good part of its pixels are averaged.
    assert len(averaged) > 0.1 * looks_up.sum()
    for (row, column), value in averaged.items():
        seen[row, column] = value
    recombined = reflection + seen * transmittance
    # The tolerance covers float32 rounding of the UV (which moves a bilinear lookup in noise by up to its
    # gradient times the rounding) and of the sums; a footprint chosen otherwise, or not averaged, is off by
    # tenths.
    close = np.abs(recombined[covered] - liquid[covered][:, :3]).max(axis=-1) < 2e-3
    assert close.mean() > 0.995, f"{(~close).sum()} of {close.size} pixels differ from the CPU's"
    assert (uv[~looks_up] == 0).all() and (transmittance[~looks_up] == 0).all()


def test_other_python_threads_run_while_a_frame_renders(renderer):
    scene = scene_json(width=320, height=240)
    stamps, stop = [], threading.Event()

    def stamp():
        while not stop.is_set():
            stamps.append(time.monotonic())
            time.sleep(0.001)

    worker = threading.Thread(target=stamp)
    worker.start()
    try:
        # Until a render lasts long enough for the margins below: each try more particles, and new ones (the
        # renderer keeps the shapes of particles it rendered the frame before, liquid.reuse_shapes).
        for attempt in range(5):
            arrays = sphere_of_particles(count=3000 * 2**attempt, particle_radius=0.05, seed=attempt)
            start = time.monotonic()
            renderer.render(scene, 1, particles=arrays, layers=["composite"])
            end = time.monotonic()
            if end - start > 0.2:
                break
    finally:
        stop.set()
        worker.join()
    # A thread holding the GIL through the call would let the worker stamp only before the call began (at most
    # one switch interval, 5 ms, after `start`) or after it ended: a stamp well inside proves the GIL was free.
    margin = 0.02
    assert end - start > 2 * margin + 0.05, "the frame rendered too fast to tell"
    inside = [t for t in stamps if start + margin < t < end - margin]
    assert len(inside) >= 3, f"{len(inside)} stamps while rendering for {end - start:.3f} s"


def test_layers_argument_reads_back_only_those_layers(renderer):
    result = renderer.render(scene_json(), 1, particles=sphere_of_particles(count=50), layers=["liquid", "depth"])
    assert set(result["layers"]) == {"liquid", "depth"}
    channels, pixels = result["layers"]["liquid"]
    assert channels == ("R", "G", "B", "A") and len(pixels) == WIDTH * HEIGHT * 4 * 4
    assert result["width"] == WIDTH and result["height"] == HEIGHT
    assert json.loads(json.dumps(result["stats"]))["resolution"] == [WIDTH, HEIGHT]
    # An empty list reads nothing back (a frame written only to its EXR); None reads every layer.
    assert renderer.render(scene_json(), 1, layers=[])["layers"] == {}
    assert "refraction_uv" in renderer.render(scene_json(), 1, layers=None)["layers"]


def test_gl_strings(renderer):
    assert renderer.gl_renderer and renderer.gl_version.startswith("4.")


def test_a_liquid_mesh_acts_as_the_liquid_depth_it_would_render(renderer, tmp_path):
    # Surface foam around a liquid surface: the plane y = 0, square to the view, so its planar eye depth is 5
    # at every pixel. Handed as triangles it must give the foam what a liquid_depth file of 5 gives.
    random = np.random.default_rng(5)
    count = 3000
    foam = {"positions": random.uniform([-1.5, -0.4, -1.0], [1.5, 0.4, 1.0], (count, 3)).astype(np.float32),
            "radii": np.full(count, 0.04, np.float32), "kinds": np.full(count, 8, np.uint8)}
    plane = {"vertices": np.array([[-50, 0, -50], [50, 0, -50], [50, 0, 50], [-50, 0, 50]], np.float32),
             "triangles": np.array([[0, 1, 2], [0, 2, 3]], np.int32)}
    depth_file = tmp_path / "liquid_depth.exr"
    output = oiio.ImageOutput.create(str(depth_file))
    spec = oiio.ImageSpec(WIDTH, HEIGHT, 1, oiio.FLOAT)
    spec.channelnames = ("Z",)
    output.open(str(depth_file), spec)
    output.write_image(np.full((HEIGHT, WIDTH, 1), 5.0, np.float32))
    output.close()
    foam_layers = ["foam", "foam_surface"]
    from_mesh = renderer.render(scene_json(), 1, particles=foam, liquid_mesh=plane, layers=foam_layers)
    background = {"color": [0.2, 0.3, 0.4], "liquid_depth": "liquid_depth.exr"}  # scene_json's colour, and the file
    from_file = renderer.render(scene_json(background=background), 1,
                                base_dir=str(tmp_path), particles=foam, layers=foam_layers)
    without = renderer.render(scene_json(), 1, particles=foam, layers=foam_layers)
    assert any(p["name"] == "liquid_mesh_depth" for p in from_mesh["stats"]["passes"])
    assert_all_finite(from_mesh)
    for name in foam_layers:
        np.testing.assert_allclose(layer(from_mesh, name), layer(from_file, name), rtol=0, atol=1e-4, err_msg=name)
    # And the liquid's depth matters: foam behind the surface fades.
    assert np.abs(layer(without, "foam") - layer(from_mesh, "foam")).max() > 0.05


def test_two_threads_sharing_a_renderer_get_their_own_frames(renderer):
    # Calls are serialised by the renderer's lock (taken without the GIL): each thread gets the frame it asked
    # for, identical to the same frame rendered alone.
    small, large = sphere_of_particles(count=100, seed=1), sphere_of_particles(count=400, seed=2)
    alone = {name: layer(renderer.render(scene_json(), 1, particles=arrays, layers=["liquid"]), "liquid")
             for name, arrays in (("small", small), ("large", large))}
    results, errors = {}, []

    def render(name, arrays):
        try:
            for _ in range(3):
                results.setdefault(name, []).append(
                    layer(renderer.render(scene_json(), 1, particles=arrays, layers=["liquid"]), "liquid"))
        except Exception as error:  # noqa: BLE001 (reported below)
            errors.append(error)

    threads = [threading.Thread(target=render, args=item) for item in (("small", small), ("large", large))]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert not errors
    for name in ("small", "large"):
        for frame in results[name]:
            np.testing.assert_array_equal(frame, alone[name])


def test_a_png_background_is_read_as_the_same_linear_colour_as_an_exr(renderer, tmp_path):
    # The module links OpenImageIO's reader in (the command line opens it as a plugin): a PNG background
    # holding the sRGB encoding of an EXR background's linear values composites as the EXR does, to within
    # 8-bit quantisation.
    random = np.random.default_rng(3)
    linear = random.uniform(0.0, 1.0, (HEIGHT, WIDTH, 3)).astype(np.float32)
    encoded = np.where(linear <= 0.0031308, 12.92 * linear, 1.055 * linear ** (1 / 2.4) - 0.055)
    for name, pixels, pixel_type in (("b.exr", linear, oiio.FLOAT), ("b.png", encoded, oiio.UINT8)):
        output = oiio.ImageOutput.create(str(tmp_path / name))
        output.open(str(tmp_path / name), oiio.ImageSpec(WIDTH, HEIGHT, 3, pixel_type))
        output.write_image(pixels.astype(np.float32))
        output.close()
    composites = [layer(renderer.render(scene_json(background={"image": name}), 1, base_dir=str(tmp_path),
                                        layers=["composite"]), "composite")
                  for name in ("b.exr", "b.png")]
    np.testing.assert_allclose(composites[0][..., :3], linear, rtol=0, atol=1e-6)
    # Half a step of 8-bit sRGB is at most 0.0045 in linear (at 1).
    np.testing.assert_allclose(composites[1], composites[0], rtol=0, atol=0.0045)
