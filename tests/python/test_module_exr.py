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
