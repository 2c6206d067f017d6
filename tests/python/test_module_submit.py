"""Renderer.submit / poll: a frame rendered on a native thread (what Blender's viewport uses, so that no Python
runs off Blender's main thread), checked against render() of the same frame, and its display image against a
CPU composition written here from the formula."""

import json
import time

import numpy as np
import pytest

from spindrift_testing import HEIGHT, WIDTH, layer, scene_json, sphere_of_particles

POLL_TIMEOUT_S = 300


def wait_for(renderer):
    """poll() until the submitted frame arrives; the calling thread runs Python all the while."""
    deadline = time.monotonic() + POLL_TIMEOUT_S
    while time.monotonic() < deadline:
        result = renderer.poll()
        if result is not None:
            return result
        time.sleep(0.005)
    raise AssertionError("the submitted frame did not arrive")


def liquid_and_foam():
    """A ball of liquid with a shell of foam particles around it, so both layers have coverage."""
    liquid = sphere_of_particles(count=300)
    random = np.random.default_rng(7)
    directions = random.normal(size=(200, 3))
    foam = directions / np.linalg.norm(directions, axis=1, keepdims=True) * 0.95
    return {
        "positions": np.ascontiguousarray(np.concatenate([liquid["positions"], foam]), dtype=np.float32),
        "radii": np.concatenate([liquid["radii"], np.full(200, 0.04, np.float32)]),
        "kinds": np.concatenate([liquid["kinds"], np.full(200, 8, np.uint8)]),
    }


def display_reference(liquid, foam):
    """Foam over liquid (premultiplied), straight colour encoded to sRGB, premultiplied again, rows bottom first."""
    over = foam + (1.0 - foam[..., 3:4]) * liquid
    alpha = np.clip(over[..., 3:4], 0.0, 1.0)
    safe = np.where(alpha > 1e-6, alpha, 1.0)
    straight = np.where(alpha > 1e-6, np.clip(over[..., :3] / safe, 0.0, 1.0), 0.0)
    srgb = np.where(straight <= 0.0031308, straight * 12.92, 1.055 * np.power(straight, 1 / 2.4) - 0.055)
    return np.concatenate([srgb * alpha, alpha], axis=2)[::-1]


def test_poll_with_nothing_submitted_is_none(spindrift):
    with spindrift.Renderer() as renderer:
        assert renderer.poll() is None and renderer.busy is False


def test_a_submitted_frame_is_the_frame_render_returns(renderer):
    arrays = liquid_and_foam()
    rendered = renderer.render(scene_json(), 1, particles=arrays, layers=["liquid", "foam", "depth"])
    renderer.submit(scene_json(), 1, particles=arrays, layers=["liquid", "foam", "depth"])
    submitted = wait_for(renderer)
    assert renderer.poll() is None, "a result is returned once"
    assert set(submitted["layers"]) == {"liquid", "foam", "depth"} and "display" not in submitted
    for name in ("liquid", "foam", "depth"):
        np.testing.assert_array_equal(layer(submitted, name), layer(rendered, name), err_msg=name)
    assert json.loads(json.dumps(submitted["stats"]))["resolution"] == [WIDTH, HEIGHT]


def test_display_is_foam_over_liquid_in_premultiplied_srgb_bottom_row_first(renderer):
    arrays = liquid_and_foam()
    both = renderer.render(scene_json(), 1, particles=arrays, layers=["liquid", "foam"])
    liquid, foam = layer(both, "liquid"), layer(both, "foam")
    assert (liquid[..., 3] > 0.5).mean() > 0.02 and (foam[..., 3] > 0.1).mean() > 0.002, "both layers are seen"
    renderer.submit(scene_json(), 1, particles=arrays, layers=[], display=True)
    result = wait_for(renderer)
    assert result["layers"] == {}
    display = np.frombuffer(result["display"], np.float32).reshape(HEIGHT, WIDTH, 4)
    assert np.isfinite(display).all() and display.min() >= 0.0 and display.max() <= 1.0
    np.testing.assert_allclose(display, display_reference(liquid, foam), rtol=0, atol=2e-6)
    # Bottom row first: the image's top row is the display's last.
    assert not np.array_equal(display[0], display[-1]) or not liquid[0].any()


def test_display_of_an_empty_frame_is_transparent(renderer):
    empty = {"positions": np.zeros((0, 3), np.float32), "radii": np.zeros(0, np.float32),
             "kinds": np.zeros(0, np.uint8)}
    renderer.submit(scene_json(), 1, particles=empty, layers=[], display=True)
    display = np.frombuffer(wait_for(renderer)["display"], np.float32)
    assert display.size == WIDTH * HEIGHT * 4 and not display.any()


def test_a_second_submit_before_poll_is_refused_and_the_first_frame_still_arrives(renderer):
    arrays = sphere_of_particles(count=100)
    renderer.submit(scene_json(), 1, particles=arrays, layers=["liquid"])
    with pytest.raises(RuntimeError, match="already in flight"):
        renderer.submit(scene_json(), 1, particles=arrays, layers=["liquid"])
    assert "liquid" in wait_for(renderer)["layers"]


def test_bad_arguments_raise_at_submit_and_a_failing_frame_at_poll(renderer, tmp_path):
    arrays = sphere_of_particles(count=10)
    bad = dict(arrays, kinds=np.full(10, 3, np.uint8))
    with pytest.raises(ValueError, match="kinds"):
        renderer.submit(scene_json(), 1, particles=bad)
    assert renderer.poll() is None, "nothing was started"
    missing = tmp_path / "missing_####.ply"
    scene = scene_json(particles=[{"path": str(missing), "role": "liquid", "radius": 0.1}])
    renderer.submit(scene, 1, layers=["liquid"])
    with pytest.raises(RuntimeError, match="missing_0001"):
        wait_for(renderer)
    assert renderer.poll() is None and not renderer.busy
    renderer.submit(scene_json(), 1, particles=arrays, layers=["liquid"])  # The renderer goes on working.
    assert "liquid" in wait_for(renderer)["layers"]


def test_submit_returns_while_the_frame_renders(renderer):
    arrays = sphere_of_particles(count=3000, particle_radius=0.05)
    for _ in range(5):  # Until a frame lasts long enough to be seen in flight.
        started = time.monotonic()
        renderer.submit(scene_json(width=320, height=240), 1, particles=arrays, layers=["composite"])
        returned = time.monotonic() - started
        in_flight = renderer.busy
        wait_for(renderer)
        if in_flight and time.monotonic() - started > 0.2:
            break
    assert in_flight, "submit() waited for the frame"
    assert returned < 0.1, f"submit() took {returned:.3f} s"


def test_closing_or_dropping_a_renderer_with_a_frame_in_flight_waits_for_it(spindrift):
    arrays = sphere_of_particles(count=500)
    renderer = spindrift.Renderer()
    renderer.submit(scene_json(), 1, particles=arrays, layers=["liquid"])
    renderer.close()
    assert renderer.poll() is None, "the frame was dropped with the renderer"
    with pytest.raises(RuntimeError, match="closed"):
        renderer.submit(scene_json(), 1, particles=arrays)
    dropped = spindrift.Renderer()
    dropped.submit(scene_json(), 1, particles=arrays, layers=["liquid"])
    del dropped  # Deallocation joins the native thread before the renderer goes.


def test_display_into_is_written_by_the_rendering_thread(renderer):
    arrays = liquid_and_foam()
    renderer.submit(scene_json(), 1, particles=arrays, layers=[], display=True)
    fresh = np.frombuffer(wait_for(renderer)["display"], np.float32)
    target = np.full(WIDTH * HEIGHT * 4, -1.0, np.float32)
    renderer.submit(scene_json(), 1, particles=arrays, layers=[], display=True, display_into=target)
    result = wait_for(renderer)
    assert result["display"] is target
    np.testing.assert_array_equal(target, fresh)
    # Checked at submit, before anything renders: the size, writability, and that there is a display.
    with pytest.raises(ValueError, match="display_into"):
        renderer.submit(scene_json(), 1, particles=arrays, display=True, display_into=np.zeros(7, np.float32))
    read_only = np.zeros(WIDTH * HEIGHT * 4, np.float32)
    read_only.flags.writeable = False
    with pytest.raises(ValueError, match="written"):
        renderer.submit(scene_json(), 1, particles=arrays, display=True, display_into=read_only)
    with pytest.raises(ValueError, match="display=True"):
        renderer.submit(scene_json(), 1, particles=arrays, display_into=target)
    assert renderer.poll() is None and not renderer.busy, "nothing was started"
    # render() takes it too, and a crop sizes it.
    cropped = np.zeros(10 * 8 * 4, np.float32)
    result = renderer.render(scene_json(), 1, particles=arrays, layers=[], display=True, display_into=cropped,
                             crop=(WIDTH // 2 - 5, HEIGHT // 2 - 4, 10, 8))
    assert result["display"] is cropped and cropped.any()
