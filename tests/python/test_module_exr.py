"""The module's EXR for the Blender compositor: only the layers asked for are rendered and written, colour as
half float, depth and refraction UV as float32, with the compression asked for; the values are those of a full
frame (rounded to half where written as half)."""

import numpy as np
import OpenImageIO as oiio

from spindrift_testing import layer, scene_json, sphere_of_particles

# The layers the add-on's "Spindrift Over" group reads (addon/spindrift/compositing.py).
GROUP_LAYERS = ["liquid", "depth", "refraction_uv", "transmittance", "reflection", "foam"]
FLOAT_LAYERS = {"depth", "refraction_uv"}


def liquid_and_foam():
    liquid = sphere_of_particles()
    foam = sphere_of_particles(count=60, radius=1.0, particle_radius=0.05, seed=5)
    return {"positions": np.concatenate([liquid["positions"], foam["positions"]]),
            "radii": np.concatenate([liquid["radii"], foam["radii"]]),
            "kinds": np.concatenate([np.zeros(len(liquid["radii"]), np.uint8), np.full(60, 8, np.uint8)])}


def read_exr(path):
    """{layer: (H, W, C) float32}, {channel name: its type in the file}, and the file's compression."""
    image = oiio.ImageInput.open(str(path))
    spec = image.spec()
    pixels = image.read_image(oiio.FLOAT).reshape(spec.height, spec.width, spec.nchannels)
    formats = spec.channelformats or [spec.format] * spec.nchannels
    image.close()
    planes, types = {}, {}
    for index, name in enumerate(spec.channelnames):
        layer_name, _channel = name.rsplit(".", 1)
        planes.setdefault(layer_name, []).append(pixels[:, :, index])
        types[name] = str(formats[index])
    layers = {name: np.stack(channel_planes, axis=2) for name, channel_planes in planes.items()}
    return layers, types, spec.get_string_attribute("compression")


def test_only_the_group_layers_are_rendered_and_written_colour_as_half(renderer, tmp_path):
    arrays = liquid_and_foam()
    full = renderer.render(scene_json(), 1, particles=arrays)
    path = tmp_path / "group.exr"
    subset = renderer.render(scene_json(), 1, particles=arrays, layers=[], exr_path=str(path),
                             exr_layers=GROUP_LAYERS, exr_half_color=True, exr_compression="zips")
    assert subset["layers"] == {}
    assert full["stats"]["liquid"]["liquid_pixels"] > 500 and full["stats"]["particles"]["foam"] == 60
    # Unused passes are not run at all: the composite is the one the group never reads.
    skipped = {entry["name"] for entry in subset["stats"]["skipped"]}
    assert "composite" in skipped and "composite" not in {e["name"] for e in full["stats"]["skipped"]}

    written, types, compression = read_exr(path)
    assert set(written) == set(GROUP_LAYERS)
    assert compression == "zips"
    for channel, kind in types.items():
        assert kind == ("float" if channel.split(".")[0] in FLOAT_LAYERS else "half"), channel
    for name in GROUP_LAYERS:
        expected = layer(full, name)
        if name not in FLOAT_LAYERS:
            expected = expected.astype(np.float16).astype(np.float32)
        np.testing.assert_array_equal(written[name], expected, err_msg=name)
    assert np.any(written["foam"][..., 3] > 0) and np.any(written["refraction_uv"][..., 2] > 0)


def test_returned_and_written_layers_are_chosen_apart(renderer, tmp_path):
    arrays = sphere_of_particles()
    path = tmp_path / "depth.exr"
    result = renderer.render(scene_json(), 1, particles=arrays, layers=["composite"], exr_path=str(path),
                             exr_layers=["depth"])
    assert set(result["layers"]) == {"composite"}
    written, types, compression = read_exr(path)
    assert set(written) == {"depth"} and types == {"depth.Z": "float"}
    assert compression == "zip"  # the default, as the command line writes
    np.testing.assert_array_equal(written["depth"], layer(renderer.render(scene_json(), 1, particles=arrays,
                                                                          layers=["depth"]), "depth"))


def test_every_lossless_compression_reads_back_the_same_values(renderer, tmp_path):
    arrays = sphere_of_particles()
    reference = None
    for compression in ("none", "zips", "zip", "piz", "rle"):
        path = tmp_path / f"{compression}.exr"
        renderer.render(scene_json(), 1, particles=arrays, layers=[], exr_path=str(path),
                        exr_layers=GROUP_LAYERS, exr_half_color=True, exr_compression=compression)
        written, _types, stored = read_exr(path)
        assert stored == compression
        if reference is None:
            reference = written
        for name in GROUP_LAYERS:
            np.testing.assert_array_equal(written[name], reference[name], err_msg=f"{compression} {name}")


def test_crop_cuts_every_layer_and_re_expresses_refraction_uv_over_the_window(renderer):
    """The add-on renders a camera with lens shift as a larger symmetric one and cuts it (docs/blender.md)."""
    arrays = sphere_of_particles()
    full = renderer.render(scene_json(), 1, particles=arrays, layers=GROUP_LAYERS)
    x, y, width, height = 20, 10, 50, 40
    cut = renderer.render(scene_json(), 1, particles=arrays, layers=GROUP_LAYERS, crop=(x, y, width, height))
    assert (cut["width"], cut["height"]) == (width, height)
    for name in GROUP_LAYERS:
        if name != "refraction_uv":
            np.testing.assert_array_equal(layer(cut, name), layer(full, name)[y:y + height, x:x + width], name)
    uv_full = layer(full, "refraction_uv")[y:y + height, x:x + width]
    uv_cut = layer(cut, "refraction_uv")
    np.testing.assert_array_equal(uv_cut[..., 2], uv_full[..., 2])
    reads = uv_cut[..., 2] > 0
    assert reads.sum() > 100
    full_height, full_width = layer(full, "liquid").shape[:2]
    expected_u = (uv_full[..., 0] * full_width - x) / width
    expected_v = (uv_full[..., 1] * full_height - (full_height - y - height)) / height
    inside = reads & (expected_u > 0.5 / width) & (expected_u < 1 - 0.5 / width) & (expected_v > 0.5 / height) & (
        expected_v < 1 - 0.5 / height)
    assert inside.sum() > 50
    np.testing.assert_allclose(uv_cut[..., 0][inside], expected_u[inside], atol=1e-5)
    np.testing.assert_allclose(uv_cut[..., 1][inside], expected_v[inside], atol=1e-5)
    # A ray refracted outside the window reads the window's nearest edge pixel.
    assert (uv_cut[..., 0][reads] >= 0.5 / width - 1e-6).all() and (uv_cut[..., 0][reads] <= 1 - 0.5 / width + 1e-6).all()
